// Opens a `slender validate` report (index.html) in headless Chromium and checks that
//   - the page loads,
//   - it shows every PNG figure found in the report's benchmark directories,
//   - every image has a non-zero natural size (decoded, not a broken link),
//   - no console error, page error or failed request occurs.
// Usage: node check-report.mjs REPORT_DIR [SCREENSHOT.png]
// Chromium: $CHROMIUM or /usr/bin/chromium (Debian's package; .ci/run installs it).

import { launchChromium } from "./chromium.mjs";
import { readdirSync, statSync, existsSync } from "node:fs";
import { join, resolve } from "node:path";
import { pathToFileURL } from "node:url";

const dir = resolve(process.argv[2] ?? "");
const screenshot = process.argv[3];
const index = join(dir, "index.html");
if (!process.argv[2] || !existsSync(index)) {
  console.error(`usage: node check-report.mjs REPORT_DIR [SCREENSHOT.png]; no ${index}`);
  process.exit(2);
}

// The figures the page must show: every PNG one level below the report directory.
const expected = [];
for (const sub of readdirSync(dir)) {
  const p = join(dir, sub);
  if (sub === "store" || !statSync(p).isDirectory()) continue;
  for (const f of readdirSync(p)) if (f.endsWith(".png")) expected.push(`${sub}/${f}`);
}

const browser = await launchChromium();
const problems = [];
try {
  const page = await browser.newPage({ viewport: { width: 1280, height: 900 } });
  page.on("console", (m) => {
    if (m.type() === "error") problems.push(`console error: ${m.text()}`);
  });
  page.on("pageerror", (e) => problems.push(`page error: ${e.message}`));
  page.on("requestfailed", (r) => problems.push(`request failed: ${r.url()} (${r.failure()?.errorText})`));
  const response = await page.goto(pathToFileURL(index).href, { waitUntil: "load" });
  if (response && !response.ok()) problems.push(`index.html: status ${response.status()}`);
  const images = await page.evaluate(async () => {
    const imgs = Array.from(document.images);
    await Promise.all(imgs.map((i) => (i.complete ? null : new Promise((r) => { i.onload = r; i.onerror = r; }))));
    return imgs.map((i) => ({ src: i.getAttribute("src"), w: i.naturalWidth, h: i.naturalHeight }));
  });
  const title = await page.title();
  if (!title.includes("slender")) problems.push(`unexpected title "${title}"`);
  const shown = new Set(images.map((i) => i.src));
  for (const f of expected) if (!shown.has(f)) problems.push(`figure ${f} is not on the page`);
  for (const i of images) if (!(i.w > 0 && i.h > 0)) problems.push(`image ${i.src}: natural size ${i.w}×${i.h}`);
  if (images.length === 0) problems.push("no images on the page");
  const rows = await page.locator("table").first().locator("tr").count();
  if (rows < 2) problems.push("the acceptance table is empty");
  if (screenshot) await page.screenshot({ path: screenshot, fullPage: false });
  console.log(`page test: ${images.length} images (${expected.length} figures expected), ${rows - 1} acceptance rows`);
} finally {
  await browser.close();
}
if (problems.length) {
  for (const p of problems) console.error(`page test: ${p}`);
  console.error(`page test: FAILED (${problems.length} problems)`);
  process.exit(1);
}
console.log("page test: passed");
