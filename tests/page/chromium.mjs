// The one headless-Chromium set-up of the browser tests (report page, `slender view`, the
// README screenshot): Debian's Chromium ($CHROMIUM or /usr/bin/chromium), no network services.
//
// WebGL runs on SwiftShader (software) through Chromium's GPU process, and the compositor is
// the GPU one on the same SwiftShader device ("--ignore-gpu-blocklist"), as in a browser with
// a graphics card. With "--disable-gpu" instead, the software compositor reads every WebGL
// frame back to the page's main thread (GLES2::ReadPixels inside Commit: 8.4 ms per frame in a
// trace of the drag benchmark), which no user with a GPU pays and which halved the measured
// drag rate.
import { chromium } from "playwright-core";

export const CHROMIUM_ARGS = [
  "--no-sandbox",
  "--use-angle=swiftshader",
  "--enable-unsafe-swiftshader",
  "--ignore-gpu-blocklist",
  "--enable-gpu-rasterization",
  // The machine has no network: background services of Chromium must stay quiet.
  "--disable-background-networking",
  "--disable-component-update",
  "--no-first-run",
  "--disable-quic",
  "--disable-sync",
];

/** Launches the shared headless Chromium. */
export function launchChromium() {
  return chromium.launch({
    executablePath: process.env.CHROMIUM ?? "/usr/bin/chromium",
    headless: true,
    args: CHROMIUM_ARGS,
  });
}
