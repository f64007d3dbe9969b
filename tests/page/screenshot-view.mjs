// The README's screenshot of `slender view` (assets/view.png): examples/clipped_cable.toml with
// its end pin dragged, coloured by curvature, the pin selected.
// Usage: node screenshot-view.mjs SLENDER_BINARY OUT.png
import { launchChromium } from "./chromium.mjs";
import { spawn } from "node:child_process";
import { resolve, dirname, join } from "node:path";
import { fileURLToPath } from "node:url";

const here = dirname(fileURLToPath(import.meta.url));
const [bin, shot] = process.argv.slice(2).map((p) => resolve(p));
const proc = spawn(bin, ["view", join(here, "../../examples/clipped_cable.toml"), "--port", "0"], { stdio: ["ignore", "pipe", "inherit"] });
const url = await new Promise((res) => {
  let buf = "";
  proc.stdout.on("data", (d) => { buf += d; const m = buf.match(/http:\/\/\S+/); if (m) res(m[0]); });
});
const browser = await launchChromium();
try {
  const page = await browser.newPage({ viewport: { width: 1280, height: 760 } });
  await page.goto(url);
  await page.waitForSelector("body[data-ready=true]");
  await page.selectOption("#colour", "curvature");
  await page.evaluate(() => window.slender.dragSupport(0, 3, [-0.06, 0.04, 0.06], 20));
  await page.screenshot({ path: shot });
} finally {
  await browser.close();
  proc.kill();
}
