// The README's screenshots of `slender view`:
//  - assets/view.png: examples/clipped_cable.toml with its end pin dragged, coloured by
//    curvature, the pin selected;
//  - assets/view-contact.png (with a third argument): examples/cable_over_bracket.toml, the
//    cable draped over the bracket onto the rough floor, its contacts (sticking, sliding,
//    frictionless) with their force arrows, a floor contact's values under the pointer, the
//    panel at the obstacles with the floor's contacts listed.
// Usage: node screenshot-view.mjs SLENDER_BINARY OUT.png [CONTACT_OUT.png]
import { launchChromium } from "./chromium.mjs";
import { spawn } from "node:child_process";
import { resolve, dirname, join } from "node:path";
import { fileURLToPath } from "node:url";

const here = dirname(fileURLToPath(import.meta.url));
const [bin, shot, contactShot] = process.argv.slice(2).map((p) => resolve(p));

/** Opens `slender view SCENE` in a page of the shared Chromium; runs `body(page)`. */
async function withView(browser, scene, viewport, body) {
  const proc = spawn(bin, ["view", scene, "--port", "0"], { stdio: ["ignore", "pipe", "inherit"] });
  try {
    const url = await new Promise((res) => {
      let buf = "";
      proc.stdout.on("data", (d) => { buf += d; const m = buf.match(/http:\/\/\S+/); if (m) res(m[0]); });
    });
    const page = await browser.newPage({ viewport });
    await page.goto(url);
    await page.waitForSelector("body[data-ready=true]");
    await body(page);
  } finally {
    proc.kill();
  }
}

const browser = await launchChromium();
try {
  await withView(browser, join(here, "../../examples/clipped_cable.toml"), { width: 1280, height: 760 }, async (page) => {
    await page.selectOption("#colour", "curvature");
    await page.evaluate(() => window.slender.dragSupport(0, 3, [-0.06, 0.04, 0.06], 20));
    await page.screenshot({ path: shot });
  });
  if (contactShot) {
    await withView(browser, join(here, "../../examples/cable_over_bracket.toml"), { width: 1280, height: 820 }, async (page) => {
      await page.selectOption("#colour", "curvature");
      await page.evaluate(() => window.slender.setCamera([0.3, -1.85, 0.62], [0.76, 0, 0.1]));
      // The pointer on the floor's strongest contact: its values in the tooltip.
      const p = await page.evaluate(() => {
        const s = window.slender;
        const floor = s.state().obstacles.find((o) => o.name === "floor");
        const c = floor.contacts.reduce((a, b) => (Math.hypot(...b.normal_force) > Math.hypot(...a.normal_force) ? b : a));
        const r = s.state().rods[0].contact_radius + c.gap;
        return s.screenPointOf(c.position.map((x, k) => x - c.normal[k] * r));
      });
      await page.mouse.move(p.x, p.y);
      await page.waitForSelector("#tooltip:not([hidden])");
      // The panel at the obstacles, the floor's contacts listed.
      await page.evaluate(() => {
        document.querySelector('#obstacle-table details[data-obstacle="1"]').open = true;
        document.getElementById("contacts-box").scrollIntoView();
      });
      await page.screenshot({ path: contactShot });
    });
  }
} finally {
  await browser.close();
}
