// Browser tests of `slender view` in headless Chromium (same set-up as check-report.mjs).
//
//  1. drag: open the page on scenes/drag_cable.toml, drag the end clamp's handle by a set
//     vector (through the gizmo's objectChange path); the page's cable must reach the
//     equilibrium of `slender solve` on the same scene with the equivalent [[motion]] stage:
//     every vertex, the tip included, to 1e-9 of the cable length; no console errors; the
//     canvas is not blank (pixels); colour by axial force (legend, range); the supports
//     table's reactions along the cable. Undo takes the whole drag back bit for bit, redo
//     (Ctrl+Shift+Z) brings it back. A pose typed in the panel (position, rotation in
//     degrees) moves the clamp there = `slender solve` along the same path; one Undo. The
//     arrow and Page keys nudge it by 1 mm (1 cm with Shift), each press one step of undo.
//  2. clip + save: click on the cable in "add a clip" mode (a real mouse click, raycast to an
//     arc length), then "Save scene": the downloaded TOML has the clip and its `slender solve`
//     gives the page's equilibrium. The panel's length field pays cable out; the saved scene
//     (new length) re-solves to the page's equilibrium.
//  3. Euler column: push a straight clamped column past its Euler load (scenes/euler_column.toml,
//     unstable = "keep"): the page marks it unstable; "Snap to the stable branch" buckles it
//     and the mark goes.
//  3b. point forces (scenes/point_forces.toml): one arrow per dead force of the cable and of
//     the flat cable, tip at its vertex; the panel's editor refuses an empty box, sets the
//     cable's tip force and the strip's force, and the page reaches the equilibrium of
//     `slender solve` with those forces in the file (1e-9 of the length); the saved scene
//     round-trips; a click in "add a point force" mode adds one (on the cable and on the flat
//     cable), set in its row (= slender
//     solve with it in the file), removed by its ×, put back by Ctrl+Z; a force that does not
//     exist is refused, the equilibrium kept.
//  3c. moments and line loads (scenes/moment_line_load.toml): the point moment is a
//     double-headed arrow from its vertex along its axis, the line load one arrow per loaded
//     vertex with its tip on the cable, each along its load, labelled in N·m and N/m. The
//     moment set in its panel row (a new axis): the page reaches `slender solve`'s
//     equilibrium with the new moment in the file (1e-9 of the length), the arrow turns; a
//     click in "add a point moment" mode adds one, set in its row (= slender solve with it in
//     the file), removed by its ×, put back by Ctrl+Z.
//  3d. follower force (examples/follower_cantilever.toml): drawn at the tip along the force as
//     it acts now, normal to the tip; set in the panel (as given at rest), the page reaches
//     `slender solve`'s equilibrium with the new force in the file and the arrow turns with it.
//  4. obstacles (scenes/obstacles.toml: a plane, a box, a ball, a round bar, a ramp read
//     from an OBJ file and a ring): each is a mesh of the three.js scene, tagged with its
//     obstacle, at its pose (the ball's and the ring's bounds, the box's corners, the ramp's
//     vertices as in the file); the
//     toggle hides them; one marker per active contact of the server's reply; the clamp
//     dragged 8 cm down, into the floor: every reply's min gap > 0, no vertex under the floor,
//     the page shows the min gap ≥ 0 and the refused move, no console errors.
//  5. contacts (examples/cable_over_bracket.toml): one marker per active contact of the
//     server's reply, coloured by sticking / sliding / frictionless; the normal-force arrows
//     along the reply's normal forces with lengths |f_n| × the page's scale; the bracket's
//     value under the pointer (hover) and its resultant in the panel; a drag updates them;
//     the bracket lifted 1 cm and then turned 10° about z through the obstacle rows: drawn
//     there (the reply's axis to round-off), converged, the cable still on it; grabbed by a
//     click in "move an obstacle" mode, dragged 5 mm down and turned back 10° with the gizmo
//     (live: each gizmo change is a move from the server's pose; the turn about the drawn
//     piece's centre, the gizmo's pivot); one Undo takes a whole gizmo drag back.
//  5c. a flat cable over the bracket (examples/flat_cable_on_bracket.toml): the bracket lifted
//     5 mm through the obstacle row carries the strip up; its equilibrium = slender solve's of
//     the file with the lift as its motion stage (1e-9 of the length).
//  5b. cable on cable (scenes/crossing_cables.toml, self_contact): where the core's results
//     list the touching segment pairs, one marker per pair, the force on each cable as an
//     arrow, the pair's values on hover (skipped, and said so, where they are not listed).
//  6. speed (a measurement, never a pass/fail criterion): drag a 100-element cable with 3 clips
//     and a 100-element flat cable; update rates, median and 95th percentile of frame times.
//
// Usage: node check-view.mjs SLENDER_BINARY [OUT_DIR]
//   OUT_DIR (default ../../target/view-test) receives screenshots and speed.json.
// Chromium: $CHROMIUM or /usr/bin/chromium.

import { launchChromium } from "./chromium.mjs";
import { spawn, execFileSync } from "node:child_process";
import { mkdirSync, readFileSync, writeFileSync, existsSync, readdirSync } from "node:fs";
import { join, resolve, dirname } from "node:path";
import { fileURLToPath } from "node:url";

const here = dirname(fileURLToPath(import.meta.url));
const bin = resolve(process.argv[2] ?? join(here, "../../target/release/slender"));
const out = resolve(process.argv[3] ?? join(here, "../../target/view-test"));
if (!existsSync(bin)) {
  console.error(`usage: node check-view.mjs SLENDER_BINARY [OUT_DIR]; no ${bin}`);
  process.exit(2);
}
mkdirSync(out, { recursive: true });
const scenes = join(here, "scenes");
const problems = [];
const fail = (what) => { problems.push(what); console.error(`view test: FAIL ${what}`); };
const pass = (what) => console.log(`view test: ok   ${what}`);
const check = (cond, what) => (cond ? pass(what) : fail(what));

/** Starts `slender view SCENE --port 0`; resolves to { url, proc }. */
function startView(scene) {
  const proc = spawn(bin, ["view", scene, "--port", "0"], { stdio: ["ignore", "pipe", "pipe"] });
  let stderr = "";
  proc.stderr.on("data", (d) => (stderr += d));
  return new Promise((res, rej) => {
    let buf = "";
    const timer = setTimeout(() => rej(new Error(`no URL printed within 60 s: ${buf} ${stderr}`)), 60000);
    proc.stdout.on("data", (d) => {
      buf += d;
      const m = buf.match(/http:\/\/127\.0\.0\.1:\d+\//);
      if (m) { clearTimeout(timer); res({ url: m[0], proc }); }
    });
    proc.on("exit", (c) => rej(new Error(`slender view exited (${c}): ${stderr}`)));
  });
}

/** `slender solve` of TOML text; the result of the last step (result.json). */
function solveSceneResult(name, text) {
  const file = join(out, `${name}.toml`);
  writeFileSync(file, text);
  const dir = join(out, `${name}-solve`);
  execFileSync(bin, ["solve", file, "--out", dir, "--no-preview"], { stdio: ["ignore", "ignore", "inherit"] });
  const steps = readdirSync(dir).filter((d) => d.startsWith("step_")).sort();
  const last = JSON.parse(readFileSync(join(dir, steps.at(-1), "result.json"), "utf8"));
  if (!last.converged) fail(`${name}: slender solve did not converge`);
  return last;
}

/** `slender solve` of TOML text; the positions of every rod at the last step. */
function solveScene(name, text) {
  return solveSceneResult(name, text).rods.map((r) => r.positions);
}

/** Moves obstacle `index` through the panel's obstacle rows — translation `t` (m), turn `deg`
 *  (a rotation vector in degrees) — and resolves to the server's reply once the page has
 *  drawn it (null if none came within two minutes). */
async function moveObstacleByRows(s, index, t, deg = [0, 0, 0]) {
  const n = s.replies.length;
  await s.page.selectOption("#obstacle-pick", String(index));
  for (const [i, c] of ["x", "y", "z"].entries()) {
    await s.page.fill(`#o${c}`, String(t[i]));
    await s.page.fill(`#or${c}`, String(deg[i]));
  }
  await s.page.click("#obstacle-apply");
  for (let k = 0; k < 1200; k++) {
    const reply = (await Promise.all(s.replies.slice(n))).find((r) => r.op === "obstacle" || r.ok === false);
    if (reply) {
      await s.page.evaluate(() => new Promise((r) => requestAnimationFrame(() => r())));
      return reply;
    }
    await s.page.waitForTimeout(100);
  }
  return null;
}

/** Largest distance between corresponding vertices over the rods, over `length`. */
function maxRelativeDistance(a, b, length) {
  let worst = 0;
  a.forEach((rod, r) => rod.forEach((p, i) => {
    const q = b[r][i];
    worst = Math.max(worst, Math.hypot(p[0] - q[0], p[1] - q[1], p[2] - q[2]) / length);
  }));
  return worst;
}

const quantile = (xs, q) => {
  const s = [...xs].sort((a, b) => a - b);
  return s.length ? s[Math.min(s.length - 1, Math.floor(q * (s.length - 1) + 0.5))] : NaN;
};

const browser = await launchChromium();

/** Opens the page of `scene`; collects console errors, page errors and failed requests, and
 *  the server's replies to the page's requests (`replies`: promises of the JSON, in order). */
async function open(scene) {
  const { url, proc } = await startView(scene);
  const page = await browser.newPage({ viewport: { width: 1280, height: 800 }, acceptDownloads: true });
  const errors = [];
  const replies = [];
  page.on("response", (r) => { if (r.url().endsWith("/api")) replies.push(r.json()); });
  // The page's requests go over its WebSocket (GET /ws) when it opens: its replies too.
  page.on("websocket", (ws) => {
    ws.on("framereceived", (f) => replies.push(Promise.resolve(JSON.parse(f.payload.toString()))));
    ws.on("socketerror", (e) => errors.push(`WebSocket error: ${e}`));
  });
  page.on("console", (m) => { if (m.type() === "error") errors.push(`console error: ${m.text()}`); });
  page.on("pageerror", (e) => errors.push(`page error: ${e.message}`));
  page.on("requestfailed", (r) => errors.push(`request failed: ${r.url()} (${r.failure()?.errorText})`));
  page.on("response", (r) => { if (r.status() >= 400) errors.push(`HTTP ${r.status()}: ${r.url()}`); });
  await page.goto(url);
  await page.waitForSelector("body[data-ready=true]", { timeout: 30000 });
  return { page, proc, errors, url, replies };
}

/** Fraction of canvas pixels that differ from the background colour. */
async function paintedFraction(page) {
  const png = await page.locator("#canvas").screenshot();
  return page.evaluate(async (b64) => {
    const img = new Image();
    img.src = `data:image/png;base64,${b64}`;
    await img.decode();
    const c = new OffscreenCanvas(img.width, img.height);
    const g = c.getContext("2d");
    g.drawImage(img, 0, 0);
    const d = g.getImageData(0, 0, img.width, img.height).data;
    const [r0, g0, b0] = [d[0], d[1], d[2]];
    let differ = 0;
    for (let i = 0; i < d.length; i += 4) {
      if (Math.abs(d[i] - r0) + Math.abs(d[i + 1] - g0) + Math.abs(d[i + 2] - b0) > 30) differ++;
    }
    return differ / (d.length / 4);
  }, png.toString("base64"));
}

const sessions = [];
try {
  // ---- 1. drag vs slender solve ----
  const dragScene = join(scenes, "drag_cable.toml");
  const drag = [-0.25, 0.2, 0.15];
  const s1 = await open(dragScene);
  sessions.push(s1);
  const before = await paintedFraction(s1.page);
  const restPositions = await s1.page.evaluate(() => JSON.stringify(window.slender.state().rods[0].positions));
  const v = await s1.page.evaluate((d) => window.slender.dragSupport(0, 2, d, 20), drag);
  check(v.converged, "drag: every update converged");
  // The drag went over the page's socket, and POST /api (the fallback) answers the same.
  const transports = await s1.page.evaluate(() => [...new Set(window.slender.timing.updates.map((u) => u.transport))]);
  const posted = await s1.page.evaluate(async () => {
    const r = await fetch("/api", { method: "POST", headers: { "Content-Type": "application/json" }, body: '{"op":"state"}' });
    return JSON.stringify((await r.json()).view.rods[0].positions);
  });
  check(transports.length === 1 && transports[0] === "websocket" && posted === JSON.stringify(v.rods[0].positions),
    `requests over the page's WebSocket (${transports.join(", ")}); POST /api gives the same state`);
  const base = readFileSync(dragScene, "utf8");
  const solved = solveScene("drag_cable_solved",
    `${base}\n[[motion]]\nrod = 0\nsupport = 2\ntranslate = [${drag.join(", ")}]\nsteps = 4\n`);
  const pagePositions = v.rods.map((r) => r.positions);
  const dist = maxRelativeDistance(pagePositions, solved, 1.0);
  const tipPage = pagePositions[0].at(-1), tipSolve = solved[0].at(-1);
  const tipRel = Math.hypot(...tipPage.map((x, k) => x - tipSolve[k])) / Math.hypot(...tipSolve);
  const mid = pagePositions[0][8], midSolve = solved[0][8];
  const midRel = Math.hypot(...mid.map((x, k) => x - midSolve[k])) / Math.hypot(...midSolve);
  console.log(`view test: drag by [${drag}]: tip relative difference ${tipRel.toExponential(2)}, vertex 8 ${midRel.toExponential(2)}, every vertex ≤ ${dist.toExponential(2)} of the length`);
  check(tipRel <= 1e-9, `drag: tip position = slender solve's to 1e-9 relative (${tipRel.toExponential(2)})`);
  check(dist <= 1e-9, `drag: every vertex = slender solve's to 1e-9 of the length (${dist.toExponential(2)})`);
  const painted = await paintedFraction(s1.page);
  check(before > 0.01 && painted > 0.01, `canvas not blank (${(100 * painted).toFixed(1)} % of pixels drawn)`);
  const status = await s1.page.locator("#st-converged").textContent();
  check(status === "converged", `status panel says "${status}"`);
  // Colour by axial force: the legend's title and unit, its range the largest vertex value
  // (each vertex the mean of its edges' EA·ε).
  const colourBefore = await s1.page.inputValue("#colour");
  await s1.page.selectOption("#colour", "axial");
  const axialLegend = await s1.page.evaluate(() => ({ title: document.getElementById("legend-title").textContent,
    max: Number(document.getElementById("legend-max").textContent), axial: window.slender.state().rods[0].axial_force }));
  const ax = axialLegend.axial;
  const axMax = Math.max(...ax.map((_, i) => Math.abs(i === 0 ? ax[0] : 0.5 * (ax[i - 1] + ax[i]))), Math.abs(ax.at(-1)));
  check(axialLegend.title === "axial force, tension + (N)" && Math.abs(axialLegend.max - axMax) <= 1e-2 * axMax && axMax > 0,
    `colour by axial force: legend "${axialLegend.title}", range ±${axialLegend.max} N (largest vertex value ${axMax.toPrecision(4)} N)`);
  await s1.page.selectOption("#colour", colourBefore);
  // The supports table's "along": each reaction's component along the cable's tangent there.
  const alongCheck = await s1.page.evaluate(() => ({ shown: [...document.querySelectorAll("#rods .rod td.along")].map((td) => td.textContent),
    rod: window.slender.state().rods[0] }));
  const alongExpected = alongCheck.rod.supports.map((sp) => {
    const p = alongCheck.rod.positions, v = sp.vertex;
    const a = p[Math.max(0, v - 1)], b = p[Math.min(p.length - 1, v + 1)];
    const t = b.map((x, k) => x - a[k]), n = Math.hypot(...t);
    return sp.force.reduce((acc, f, k) => acc + f * t[k] / n, 0);
  });
  check(alongCheck.shown.length === alongExpected.length
    && alongCheck.shown.every((txt, i) => Math.abs(parseFloat(txt) - alongExpected[i]) <= 5e-3 * Math.abs(alongExpected[i]) + 1e-9),
    `supports table: the reactions along the cable [${alongCheck.shown.join(", ")}] (= force · tangent)`);
  await s1.page.screenshot({ path: join(out, "view-drag.png") });
  // The whole drag is one step of undo: Undo gives the equilibrium before it bit for bit,
  // Redo the dragged one.
  const dragged = JSON.stringify(v.rods[0].positions);
  await s1.page.click("#undo");
  await s1.page.waitForFunction((p) => JSON.stringify(window.slender.state().rods[0].positions) === p, restPositions, { timeout: 20000 });
  const handleBack = await s1.page.evaluate(() => window.slender.state().rods[0].supports[2].position);
  await s1.page.keyboard.press("Control+Shift+Z");
  await s1.page.waitForFunction((p) => JSON.stringify(window.slender.state().rods[0].positions) === p, dragged, { timeout: 20000 });
  const historyText = await s1.page.locator("#history").textContent();
  check(Math.abs(handleBack[1]) < 1e-12, `undo takes the 20-move drag back in one step, bit for bit; redo (Ctrl+Shift+Z) brings it back bit for bit (${historyText})`);

  // A pose typed in the panel: the end clamp to a position and a rotation (degrees) from
  // where the drag left it, one step of undo; = slender solve with the equivalent motion stage
  // from rest (a translation and a rotation vector about the clamp's vertex).
  await s1.page.evaluate(() => window.slender.select(0, 2));
  const typedAt = [0.8, 0.12, 0.62], typedDeg = [0, 10, 30];
  const typedRad = typedDeg.map((x) => x * Math.PI / 180);
  const poseShown = await s1.page.evaluate(() => !document.getElementById("pose-box").hidden
    && ["x", "y", "z"].map((c) => Number(document.getElementById(`pose-p${c}`).value)));
  for (const [i, c] of ["x", "y", "z"].entries()) {
    await s1.page.fill(`#pose-p${c}`, String(typedAt[i]));
    await s1.page.fill(`#pose-r${c}`, String(typedDeg[i]));
  }
  await s1.page.click("#pose-apply");
  // (The clamp's vertex is carried there by the load steps: at the typed point to rounding.)
  await s1.page.waitForFunction((p) => window.slender.state().rods[0].supports[2].position.every((x, i) => Math.abs(x - p[i]) <= 1e-12), typedAt, { timeout: 20000 });
  const placed = await s1.page.evaluate(() => window.slender.state());
  const rot = placed.rods[0].supports[2].rotation;
  // The same path in two stages (the drag, then the typed move): a cable turned this far is
  // bistable, and a single stage from rest ends on the other branch (0.23 m away).
  const dragEnd = [1.0 + drag[0], drag[1], 0.5 + drag[2]];
  const placedSolve = solveScene("drag_cable_placed",
    `${base}\n[[motion]]\nrod = 0\nsupport = 2\ntranslate = [${drag.join(", ")}]\nsteps = 4\n`
    + `\n[[motion]]\nrod = 0\nsupport = 2\ntranslate = [${typedAt.map((x, k) => x - dragEnd[k]).join(", ")}]\nrotate = [${typedRad.join(", ")}]\nsteps = 4\n`);
  const placedGap = maxRelativeDistance(placed.rods.map((r) => r.positions), placedSolve, 1.0);
  check(poseShown && Math.hypot(...poseShown.map((x, k) => x - JSON.parse(dragged).at(-1)[k])) <= 1e-12
    && Math.hypot(...rot.map((x, k) => x - typedRad[k])) <= 1e-12 && placedGap <= 1e-9,
    `typed pose: the panel showed the clamp where the drag left it; moved to [${typedAt}] m turned [${typedDeg}]° = slender solve along the same path (the drag, then the typed move), every vertex within ${placedGap.toExponential(2)} of the length`);
  await s1.page.click("#undo");
  await s1.page.waitForFunction((p) => JSON.stringify(window.slender.state().rods[0].positions) === p, dragged, { timeout: 20000 });
  const poseRefused = await s1.page.evaluate(async () => {
    window.slender.select(0, 2);
    document.getElementById("pose-px").value = "";
    document.getElementById("pose-apply").click();
    return window.slender.errors.splice(0);
  });
  check(poseRefused.some((e) => e.field === "rods[0].supports[2].position"), `typed pose: one Undo goes back to the dragged equilibrium bit for bit; an empty box is refused naming ${poseRefused.map((e) => e.field).join(", ")}`);

  // Keyboard nudges: → moves the selected clamp 1 mm along x, Shift+Page Up 1 cm along z;
  // each is one step of undo.
  await s1.page.evaluate(() => { document.activeElement?.blur(); window.slender.select(0, 2); });
  const nudgeFrom = await s1.page.evaluate(() => window.slender.state().rods[0].supports[2].position);
  await s1.page.keyboard.press("ArrowRight");
  await s1.page.waitForFunction((x) => window.slender.state().rods[0].supports[2].position[0] > x + 5e-4, nudgeFrom[0], { timeout: 20000 });
  await s1.page.keyboard.press("Shift+PageUp");
  await s1.page.waitForFunction((z) => window.slender.state().rods[0].supports[2].position[2] > z + 5e-3, nudgeFrom[2], { timeout: 20000 });
  const nudged = await s1.page.evaluate(() => window.slender.state().rods[0].supports[2].position);
  const nudgeErr = Math.hypot(nudged[0] - nudgeFrom[0] - 1e-3, nudged[1] - nudgeFrom[1], nudged[2] - nudgeFrom[2] - 1e-2);
  await s1.page.keyboard.press("Control+Z");
  await s1.page.keyboard.press("Control+Z");
  await s1.page.waitForFunction((p) => JSON.stringify(window.slender.state().rods[0].positions) === p, dragged, { timeout: 20000 });
  check(nudgeErr <= 1e-12, `keyboard: → and Shift+Page Up moved the clamp by [1 mm, 0, 1 cm] (to ${nudgeErr.toExponential(1)} m); two Ctrl+Z back bit for bit`);

  // ---- 2. add a clip by clicking the cable, save, solve the saved scene ----
  await s1.page.evaluate(() => window.slender.setTool("add-clip"));
  const p = await s1.page.evaluate(() => window.slender.screenPoint(0, 0.3));
  await s1.page.mouse.click(p.x, p.y);
  await s1.page.waitForFunction(() => window.slender.state().rods[0].supports.length === 4, null, { timeout: 20000 });
  const clip = await s1.page.evaluate(() => window.slender.state().rods[0].supports.find((s) => s.kind === "clip" && Math.abs(s.at - 0.5) > 1e-9));
  check(clip && Math.abs(clip.at - 0.3) < 0.02, `click added a clip at arc length ${clip?.at?.toFixed(4)} m (aimed at 0.3 m)`);
  const [download] = await Promise.all([s1.page.waitForEvent("download"), s1.page.click("#save")]);
  const savedPath = join(out, "drag_cable_edited.toml");
  await download.saveAs(savedPath);
  const savedText = readFileSync(savedPath, "utf8");
  const afterClip = await s1.page.evaluate(() => window.slender.state());
  const resolved = solveScene("drag_cable_edited_solved", savedText);
  const roundTrip = maxRelativeDistance(afterClip.rods.map((r) => r.positions), resolved, 1.0);
  // The session's new clip holds its edge as it is (stretched by the cable's tension); the
  // saved file can only move the clip rigidly from rest, so its edge has the rest length. The
  // difference this alone makes: the edge's strain times its length (measured here).
  const rod0 = afterClip.rods[0];
  const cv = clip.vertex, ce = cv < rod0.arclengths.length - 1 ? cv : cv - 1;
  const stretch = Math.abs(rod0.edge_strain[ce]) * (rod0.arclengths[ce + 1] - rod0.arclengths[ce]);
  console.log(`view test: saved scene (${download.suggestedFilename()}) re-solved: every vertex within ${roundTrip.toExponential(3)} of the length; the new clip's edge stretch is ${stretch.toExponential(3)} m`);
  check((savedText.match(/kind = "clip"/g) ?? []).length === 2, "saved scene has both clips");
  if (roundTrip <= 1e-9) pass(`clip + save round trip: same equilibrium to 1e-9 of the length (${roundTrip.toExponential(2)})`);
  else {
    console.log(`view test: note: the 1e-9 round trip is not met: ${roundTrip.toExponential(3)} (the clip edge's stretch, see above)`);
    check(roundTrip <= stretch * 1.001 + 1e-9,
      `clip + save round trip: the equilibria differ by no more than the new clip's edge stretch + 1e-9 (${roundTrip.toExponential(3)} ≤ ${stretch.toExponential(3)} + 1e-9)`);
  }
  await s1.page.screenshot({ path: join(out, "view-clip.png") });
  const [gltfDownload] = await Promise.all([s1.page.waitForEvent("download"), s1.page.click("#gltf")]);
  const gltf = JSON.parse(readFileSync(await gltfDownload.path(), "utf8"));
  check(gltf.asset?.version === "2.0" && gltf.meshes.length >= 2, `glTF export (${gltf.meshes.length} meshes)`);

  // Pay out cable through the panel's length field: the saved scene (new length, supports
  // moved from its rest centerline) re-solves to the page's equilibrium.
  const length0 = await s1.page.evaluate(() => { const a = window.slender.state().rods[0].arclengths; return a[a.length - 1]; });
  await s1.page.selectOption("#length-rod", "0");
  await s1.page.fill("#length-value", String(1.05 * length0));
  await s1.page.click("#length-apply");
  await s1.page.waitForFunction((l) => { const a = window.slender.state().rods[0].arclengths; return Math.abs(a[a.length - 1] - l) < 1e-12 || window.slender.errors.length > 0; }, 1.05 * length0, { timeout: 30000 });
  const paidOut = await s1.page.evaluate(() => window.slender.state());
  const paidOutConverged = await s1.page.evaluate(() => document.body.dataset.converged === "true");
  const [lengthDownload] = await Promise.all([s1.page.waitForEvent("download"), s1.page.click("#save")]);
  const lengthSaved = readFileSync(await lengthDownload.path(), "utf8");
  const lengthResolved = solveScene("drag_cable_paid_out_solved", lengthSaved);
  const lengthTrip = maxRelativeDistance(paidOut.rods.map((r) => r.positions), lengthResolved, 1.0);
  check(paidOutConverged && lengthTrip <= 1e-9,
    `length field: cable paid out from ${length0} m to ${(1.05 * length0).toFixed(4)} m; the saved scene re-solves to the page's equilibrium (${lengthTrip.toExponential(2)} of the length)`);

  // Delete the original clip (support 1) through the panel button.
  await s1.page.evaluate(() => window.slender.select(0, 1));
  await s1.page.click("#delete-support");
  await s1.page.waitForFunction(() => window.slender.state().rods[0].supports.length === 3 || window.slender.errors.length > 0, null, { timeout: 20000 });
  const deleteErrors = await s1.page.evaluate(() => window.slender.errors.splice(0));
  const left = await s1.page.evaluate(() => window.slender.state().rods[0].supports.map((s) => s.kind));
  check(deleteErrors.length === 0 && left.join() === "clamp,clamp,clip", `delete a support with the panel's button (left: ${left}; errors: ${JSON.stringify(deleteErrors)})`);
  // A hostile message through the page's own channel: an error named, the equilibrium kept.
  const kept = await s1.page.evaluate(async () => {
    const before = JSON.stringify(window.slender.state().rods[0].positions);
    const r = await window.slender.request({ op: "move_by", rod: 0, support: 1, translation: [1e6, 0, 0] });
    const s = await window.slender.request({ op: "state" });
    return { error: r.error, same: before === JSON.stringify(s.view.rods[0].positions) };
  });
  check(kept.error?.field === "rods[0].supports[1]" && kept.same, `a 10⁶ m drag is refused (${kept.error?.message}) and the equilibrium kept`);
  for (const e of s1.errors) fail(e);
  check(s1.errors.length === 0, "no console errors, page errors or failed requests (drag page)");

  // ---- 3. Euler column ----
  const s3 = await open(join(scenes, "euler_column.toml"));
  sessions.push(s3);
  const c = await s3.page.evaluate(() => window.slender.dragSupport(0, 1, [0, 0, -0.0004], 10));
  const markedUnstable = await s3.page.evaluate(() => document.body.dataset.stable === "false" && !document.getElementById("unstable-box").hidden);
  const modes = c.structures.map((s) => s.unstable_modes);
  check(!c.stable && markedUnstable, `Euler column pushed to 1.6× its buckling shortening: marked unstable (negative eigenvalues: ${modes})`);
  await s3.page.screenshot({ path: join(out, "view-euler-unstable.png") });
  await s3.page.click("#snap");
  await s3.page.waitForFunction(() => document.body.dataset.stable === "true", null, { timeout: 30000 });
  const buckled = await s3.page.evaluate(() => window.slender.state());
  const lateral = Math.max(...buckled.rods[0].positions.map((q) => Math.hypot(q[0], q[1])));
  check(buckled.stable && lateral > 1e-3, `snap to the stable branch: stable, buckled (largest lateral deflection ${(lateral * 1000).toFixed(2)} mm)`);
  await s3.page.screenshot({ path: join(out, "view-euler-snapped.png") });
  for (const e of s3.errors) fail(e);
  check(s3.errors.length === 0, "no console errors (Euler page)");

  // ---- 3b. point forces: arrows, the panel's editor, save ----
  const forceScene = join(scenes, "point_forces.toml");
  const s3b = await open(forceScene);
  sessions.push(s3b);
  /** The load arrows in the three.js scene: the force they stand for, tail, tip, direction. */
  const loadArrows = (page) => page.evaluate(() => {
    const found = [];
    window.slender.scene.traverse((o) => {
      if (!o.userData?.load || !o.visible) return;
      o.updateMatrixWorld(true);
      const dir = [0, 1, 0].map((_, k) => o.matrixWorld.elements[4 + k]);
      const n = Math.hypot(...dir);
      const tail = [o.matrixWorld.elements[12], o.matrixWorld.elements[13], o.matrixWorld.elements[14]];
      // ArrowHelper: +y of its frame along the force, the cone's tip at y = its length.
      const len = o.cone.position.y;
      found.push({ load: o.userData.load, tail, tip: tail.map((x, k) => x + (dir[k] / n) * len), dir: dir.map((x) => x / n) });
    });
    return found;
  });
  const arrowsMatch = (arrows, state) => state.rods[0].forces.every((f, k) => {
    const a = arrows.find((x) => x.load[0] === "rod" && x.load[1] === 0 && x.load[2] === k);
    const n = Math.hypot(...f.force);
    return a && Math.hypot(...a.tip.map((x, i) => x - f.position[i])) <= 1e-6
      && a.dir.every((x, i) => Math.abs(x - f.now[i] / n) <= 1e-6);
  });
  const rows = await s3b.page.locator("#loads .force-apply").count();
  const boxShown = await s3b.page.evaluate(() => !document.getElementById("loads-box").hidden);
  check(boxShown && rows === 3, `point forces: the panel lists the cable's two forces and the strip's one with an editor (${rows} rows)`);
  const state0 = await s3b.page.evaluate(() => window.slender.state());
  const arrows0 = await loadArrows(s3b.page);
  check(arrows0.length === 3 && arrowsMatch(arrows0, state0),
    `point forces: one arrow per force, its tip at the loaded vertex, along the force (${arrows0.length} arrows)`);
  // An empty box is refused in the page (it would read as 0), with the field named.
  await s3b.page.fill("#f-0-0-x", "");
  await s3b.page.click('#loads .force-apply[data-load="f-0-0"]');
  const emptyRefused = await s3b.page.evaluate(() => window.slender.errors.splice(0));
  check(emptyRefused.length === 1 && emptyRefused[0].field === "rods[0].forces[0].force",
    `point forces: an empty box is refused naming ${emptyRefused[0]?.field}`);
  // The tip force edited through the panel: type, Apply, the re-solve from the last equilibrium.
  const newForce = [0.01, -0.005, -0.05];
  for (const [i, c] of ["x", "y", "z"].entries()) await s3b.page.fill(`#f-0-0-${c}`, String(newForce[i]));
  await s3b.page.click('#loads .force-apply[data-load="f-0-0"]');
  await s3b.page.waitForFunction((f) => window.slender.state().rods[0].forces[0].force.every((x, i) => x === f[i]), newForce, { timeout: 20000 });
  const edited = await s3b.page.evaluate(() => window.slender.state());
  check(edited.converged && edited.rods[0].forces[0].force.join() === newForce.join(), `point forces: the panel set the tip force to [${newForce}] (converged: ${edited.converged})`);
  const forceText = readFileSync(forceScene, "utf8").replace("force = [0.0, 0.0, -0.02]", `force = [${newForce.map((x) => x.toFixed(3)).join(", ")}]`);
  const cold = solveScene("point_forces_edited_cold", forceText);
  const editGap = maxRelativeDistance(edited.rods.map((r) => r.positions), cold, 1.0);
  const tipMoved = Math.hypot(...edited.rods[0].positions.at(-1).map((x, k) => x - state0.rods[0].positions.at(-1)[k]));
  console.log(`view test: tip force edited in the panel: the tip moved ${(tipMoved * 1000).toFixed(2)} mm; every vertex within ${editGap.toExponential(2)} of the length of slender solve with the new force in the file`);
  check(tipMoved > 1e-3 && editGap <= 1e-9, `point forces: the edited equilibrium = slender solve's with the force in the file, to 1e-9 of the length (${editGap.toExponential(2)})`);
  const arrows1 = await loadArrows(s3b.page);
  check(arrowsMatch(arrows1, edited), "point forces: the arrows follow the edit (tip at the moved vertex, along the new force)");
  // The flat cable's force, edited the same way: the strip's equilibrium = slender solve's.
  const stripForce = [0.0, -0.02, 0.004];
  for (const [i, c] of ["x", "y", "z"].entries()) await s3b.page.fill(`#fs-0-0-${c}`, String(stripForce[i]));
  await s3b.page.click('#loads .force-apply[data-load="fs-0-0"]');
  await s3b.page.waitForFunction((f) => window.slender.state().shells[0].forces[0].force.every((x, i) => x === f[i]), stripForce, { timeout: 20000 });
  const stripEdited = await s3b.page.evaluate(() => window.slender.state());
  const stripText = forceText.replace("force = [0.0, -0.005, 0.0]", `force = [${stripForce.map((x) => x.toFixed(3)).join(", ")}]`);
  const stripCold = solveSceneResult("point_forces_strip_cold", stripText).shells[0].positions;
  const stripGap = maxRelativeDistance([stripEdited.shells[0].positions], [stripCold], 0.2);
  const stripMoved = Math.hypot(...stripEdited.shells[0].positions.at(-1).map((x, k) => x - state0.shells[0].positions.at(-1)[k]));
  console.log(`view test: flat-cable force edited in the panel: its corner moved ${(stripMoved * 1000).toFixed(2)} mm; every vertex within ${stripGap.toExponential(2)} of its length of slender solve with the new force in the file`);
  check(stripMoved > 1e-3 && stripGap <= 1e-9, `point forces: the strip's edited equilibrium = slender solve's, to 1e-9 of its length (${stripGap.toExponential(2)})`);
  const stripArrow = (await loadArrows(s3b.page)).find((x) => x.load[0] === "shell");
  const sf = stripEdited.shells[0].forces[0];
  check(stripArrow && Math.hypot(...stripArrow.tip.map((x, i) => x - sf.position[i])) <= 1e-6
    && stripArrow.dir.every((x, i) => Math.abs(x - sf.force[i] / Math.hypot(...sf.force)) <= 1e-6),
    "point forces: the strip's arrow at its loaded vertex, along the new force");
  const [forceDownload] = await Promise.all([s3b.page.waitForEvent("download"), s3b.page.click("#save")]);
  const forceSaved = readFileSync(await forceDownload.path(), "utf8");
  const reSolvedAll = solveSceneResult("point_forces_saved", forceSaved);
  const reSolved = reSolvedAll.rods.map((r) => r.positions);
  const saveGap = Math.max(maxRelativeDistance(stripEdited.rods.map((r) => r.positions), reSolved, 1.0),
    maxRelativeDistance([stripEdited.shells[0].positions], [reSolvedAll.shells[0].positions], 0.2));
  check(saveGap <= 1e-9, `point forces: the saved scene re-solves to the page's equilibrium (${saveGap.toExponential(2)} of the length)`);
  // Add a force by clicking the cable in "add a point force" mode (at 0.7 m: its vertex 28),
  // set it in its new row, then remove it with the row's ×.
  await s3b.page.evaluate(() => window.slender.setTool("add-force"));
  const clickAt = await s3b.page.evaluate(() => window.slender.screenPoint(0, 0.7));
  await s3b.page.mouse.click(clickAt.x, clickAt.y);
  await s3b.page.waitForFunction(() => window.slender.state().rods[0].forces.length === 3, null, { timeout: 20000 });
  const addedForce = await s3b.page.evaluate(() => window.slender.state().rods[0].forces[2]);
  check(Math.abs(addedForce.at - 0.7) <= 0.025 && addedForce.force.every((x) => x === 0),
    `point forces: a click added a force at vertex ${addedForce.vertex} (${addedForce.at.toFixed(3)} m; aimed at 0.7 m), starting at zero`);
  const added = [0.0, 0.0, -0.03];
  for (const [i, c] of ["x", "y", "z"].entries()) await s3b.page.fill(`#f-0-2-${c}`, String(added[i]));
  await s3b.page.click('#loads .force-apply[data-load="f-0-2"]');
  await s3b.page.waitForFunction((f) => window.slender.state().rods[0].forces[2].force.every((x, i) => x === f[i]), added, { timeout: 20000 });
  const withAdded = await s3b.page.evaluate(() => window.slender.state());
  const addedText = stripText.replace("{ vertex = 20, force = [0.0, 0.01, 0.0] },",
    `{ vertex = 20, force = [0.0, 0.01, 0.0] },\n    { vertex = ${addedForce.vertex}, force = [${added.map((x) => x.toFixed(3)).join(", ")}] },`);
  const addedCold = solveScene("point_forces_added_cold", addedText);
  const addedGap = maxRelativeDistance(withAdded.rods.map((r) => r.positions), addedCold, 1.0);
  check(addedGap <= 1e-9, `point forces: with the added force set, the page = slender solve with it in the file (${addedGap.toExponential(2)} of the length)`);
  await s3b.page.click('#loads .force-remove[data-load="f-0-2"]');
  await s3b.page.waitForFunction(() => window.slender.state().rods[0].forces.length === 2, null, { timeout: 20000 });
  const removed = await s3b.page.evaluate(() => window.slender.state());
  const removedGap = maxRelativeDistance(removed.rods.map((r) => r.positions), stripEdited.rods.map((r) => r.positions), 1.0);
  check(removedGap <= 1e-9, `point forces: × removed it, back to the equilibrium before (${removedGap.toExponential(2)} of the length)`);
  await s3b.page.evaluate(() => document.activeElement?.blur());
  await s3b.page.keyboard.press("Control+Z");
  await s3b.page.waitForFunction(() => window.slender.state().rods[0].forces.length === 3, null, { timeout: 20000 });
  const undone = await s3b.page.evaluate(() => window.slender.state());
  check(JSON.stringify(undone.rods[0].positions) === JSON.stringify(withAdded.rods[0].positions) && undone.rods[0].forces[2].force.join() === added.join(),
    "point forces: Ctrl+Z puts the removed force back with its equilibrium, bit for bit");
  // The same on the flat cable: a click near its grid vertex (station 4, column 1) adds a
  // force there at zero, its row sets it (= slender solve with it in the file), × removes it.
  const stripBefore = (await s3b.page.evaluate(() => window.slender.state())).shells[0];
  const cols = stripBefore.width_elements + 1;
  const vertexAt = (v) => stripBefore.positions[v];
  const aim = [0, 1, 2].map((k) => 0.9 * vertexAt(4 * cols + 1)[k] + 0.05 * vertexAt(4 * cols + 2)[k] + 0.05 * vertexAt(5 * cols + 1)[k]);
  const stripClick = await s3b.page.evaluate((x) => window.slender.screenPointOf(x), aim);
  await s3b.page.mouse.click(stripClick.x, stripClick.y);
  await s3b.page.waitForFunction(() => window.slender.state().shells[0].forces.length === 2, null, { timeout: 20000 });
  const stripAdded = await s3b.page.evaluate(() => window.slender.state().shells[0].forces[1]);
  check(stripAdded.station === 4 && stripAdded.column === 1 && stripAdded.force.every((x) => x === 0),
    `point forces: a click on the flat cable added a force at station ${stripAdded.station}, column ${stripAdded.column} (aimed at 4, 1), starting at zero`);
  const stripExtra = [0.0, 0.01, 0.0];
  for (const [i, c] of ["x", "y", "z"].entries()) await s3b.page.fill(`#fs-0-1-${c}`, String(stripExtra[i]));
  await s3b.page.click('#loads .force-apply[data-load="fs-0-1"]');
  await s3b.page.waitForFunction((f) => window.slender.state().shells[0].forces[1].force.every((x, i) => x === f[i]), stripExtra, { timeout: 20000 });
  const stripWith = await s3b.page.evaluate(() => window.slender.state().shells[0]);
  const stripAddedText = stripText.replace(/forces = \[\{ station = 8, column = 1, force = (\[[^\]]*\]) \}\]/,
    `forces = [{ station = 8, column = 1, force = $1 }, { station = 4, column = 1, force = [${stripExtra.map((x) => x.toFixed(3)).join(", ")}] }]`);
  const stripAddedCold = solveSceneResult("point_forces_strip_added_cold", stripAddedText).shells[0].positions;
  const stripAddedGap = maxRelativeDistance([stripWith.positions], [stripAddedCold], 0.2);
  const stripAddedMoved = Math.max(...stripWith.positions.map((p, v) => Math.hypot(...p.map((x, k) => x - stripBefore.positions[v][k]))));
  check(stripAddedMoved > 1e-4 && stripAddedGap <= 1e-9,
    `point forces: with the strip's added force set (moved ${(stripAddedMoved * 1000).toFixed(2)} mm), the page = slender solve with it in the file (${stripAddedGap.toExponential(2)} of its length)`);
  await s3b.page.click('#loads .force-remove[data-load="fs-0-1"]');
  await s3b.page.waitForFunction(() => window.slender.state().shells[0].forces.length === 1, null, { timeout: 20000 });
  const stripRemoved = await s3b.page.evaluate(() => window.slender.state().shells[0]);
  const stripRemovedGap = maxRelativeDistance([stripRemoved.positions], [stripBefore.positions], 0.2);
  check(stripRemovedGap <= 1e-9, `point forces: × removed the strip's force, back to its equilibrium before (${stripRemovedGap.toExponential(2)} of its length)`);
  await s3b.page.evaluate(() => window.slender.setTool("drag"));
  // Through the page's channel: a force that does not exist is refused, the equilibrium kept.
  const keptForce = await s3b.page.evaluate(async () => {
    const before = JSON.stringify(window.slender.state().rods[0].positions);
    const r = await window.slender.request({ op: "force", rod: 0, force: 7, value: [0, 0, 1] });
    const s = await window.slender.request({ op: "state" });
    return { error: r.error, same: before === JSON.stringify(s.view.rods[0].positions) };
  });
  check(keptForce.error?.field?.startsWith("rods[0].forces") && keptForce.same, `point forces: force 7 is refused (${keptForce.error?.field}: ${keptForce.error?.message}) and the equilibrium kept`);
  await s3b.page.screenshot({ path: join(out, "view-point-forces.png") });
  for (const e of s3b.errors) fail(e);
  check(s3b.errors.length === 0, "no console errors (point-force page)");

  // ---- 3c. point moments and line loads drawn ----
  const s3c = await open(join(scenes, "moment_line_load.toml"));
  sessions.push(s3c);
  const loadsDrawn = await s3c.page.evaluate(() => {
    const found = { moments: [], lineLoads: [] };
    window.slender.scene.traverse((o) => {
      if (!o.visible || !(o.userData?.moment !== undefined || o.userData?.lineLoad !== undefined)) return;
      o.updateMatrixWorld(true);
      const e = o.matrixWorld.elements;
      const dir = [e[4], e[5], e[6]];
      const n = Math.hypot(...dir);
      const tail = [e[12], e[13], e[14]];
      const len = o.cone.position.y;
      const a = { tail, tip: tail.map((x, k) => x + (dir[k] / n) * len), dir: dir.map((x) => x / n), len };
      (o.userData.moment !== undefined ? found.moments : found.lineLoads).push(a);
    });
    found.labels = [...document.querySelectorAll("#labels div")].filter((d) => d.style.display !== "none").map((d) => d.textContent);
    found.state = window.slender.state();
    return found;
  });
  const rod3c = loadsDrawn.state.rods[0];
  const m3c = rod3c.moments[0];
  const mDir = m3c.moment.map((x) => x / Math.hypot(...m3c.moment));
  const near = (a, b, tol) => Math.hypot(...a.map((x, k) => x - b[k])) <= tol;
  const momentOk = loadsDrawn.moments.length === 2 && loadsDrawn.moments.every((a) => a.dir.every((x, k) => Math.abs(x - mDir[k]) <= 1e-6))
    && loadsDrawn.moments.some((a) => near(a.tail, m3c.position, 1e-6));
  check(momentOk && m3c.vertex === 20, `moment: a double-headed arrow (${loadsDrawn.moments.length} heads) from vertex ${m3c.vertex} along [${m3c.moment}]`);
  const loadedVertices = rod3c.line_load.map((q, v) => (Math.hypot(...q) > 0 ? v : -1)).filter((v) => v >= 0);
  const lineOk = loadsDrawn.lineLoads.length === loadedVertices.length && loadedVertices.length === 21
    && loadsDrawn.lineLoads.every((a) => a.dir[1] > 1 - 1e-9 && loadedVertices.some((v) => near(a.tip, rod3c.positions[v], 1e-6)));
  check(lineOk, `line load: one arrow per loaded vertex (${loadsDrawn.lineLoads.length} for vertices ${loadedVertices[0]}…${loadedVertices.at(-1)}), tips on the cable, along +y`);
  check(loadsDrawn.labels.some((t) => t === "0.00200 N·m") && loadsDrawn.labels.some((t) => t === "0.0500 N/m"),
    `moment and line load labelled (${loadsDrawn.labels.filter((t) => /N·m|N\/m/.test(t)).join(", ")})`);
  // The moment set in its panel row: the page reaches slender solve's equilibrium with the
  // new moment in the file, and its arrow turns to the new axis.
  const newMoment = [0.001, -0.003, 0.002];
  for (const [i, c] of ["x", "y", "z"].entries()) await s3c.page.fill(`#m-0-0-${c}`, String(newMoment[i]));
  await s3c.page.click('#moments .moment-apply[data-moment="m-0-0"]');
  await s3c.page.waitForFunction((m) => window.slender.state().rods[0].moments[0].moment.every((x, i) => x === m[i]), newMoment, { timeout: 20000 });
  const momentEdited = await s3c.page.evaluate(() => window.slender.state());
  const momentText = readFileSync(join(scenes, "moment_line_load.toml"), "utf8").replace("moment = [0.0, 0.002, 0.0]", `moment = [${newMoment.join(", ")}]`);
  const momentCold = solveScene("moment_edited_cold", momentText);
  const momentGap = maxRelativeDistance(momentEdited.rods.map((r) => r.positions), momentCold, 1.0);
  const momentMoved = Math.max(...momentEdited.rods[0].positions.map((p, v) => Math.hypot(...p.map((x, k) => x - rod3c.positions[v][k]))));
  console.log(`view test: moment set to [${newMoment}] N·m in the panel (the cable moved ${(momentMoved * 1000).toFixed(1)} mm): every vertex within ${momentGap.toExponential(2)} of the length of slender solve with the new moment in the file`);
  check(momentText.includes(`[${newMoment.join(", ")}]`) && momentEdited.converged && momentMoved > 1e-3 && momentGap <= 1e-9,
    `moment: the edited equilibrium = slender solve's with the moment in the file, to 1e-9 of the length (${momentGap.toExponential(2)})`);
  const newDir = newMoment.map((x) => x / Math.hypot(...newMoment));
  const turned = await s3c.page.evaluate(() => {
    const dirs = [];
    window.slender.scene.traverse((o) => {
      if (!o.visible || o.userData?.moment === undefined) return;
      o.updateMatrixWorld(true);
      const e = o.matrixWorld.elements;
      const n = Math.hypot(e[4], e[5], e[6]);
      dirs.push([e[4] / n, e[5] / n, e[6] / n]);
    });
    return dirs;
  });
  check(turned.length === 2 && turned.every((d) => d.every((x, k) => Math.abs(x - newDir[k]) <= 1e-6)),
    `moment: its arrow turned to the new axis [${newDir.map((x) => x.toFixed(3))}]`);
  // A moment added by a click in "add a point moment" mode (at 0.8 m: vertex 32), set in its
  // new row (= slender solve with it in the file), removed by its ×, put back by Ctrl+Z.
  await s3c.page.evaluate(() => window.slender.setTool("add-moment"));
  const momentClick = await s3c.page.evaluate(() => window.slender.screenPoint(0, 0.8));
  await s3c.page.mouse.click(momentClick.x, momentClick.y);
  await s3c.page.waitForFunction(() => window.slender.state().rods[0].moments.length === 2, null, { timeout: 20000 });
  const addedMoment = await s3c.page.evaluate(() => window.slender.state().rods[0].moments[1]);
  check(Math.abs(addedMoment.at - 0.8) <= 0.025 && addedMoment.moment.every((x) => x === 0),
    `moment: a click added one at vertex ${addedMoment.vertex} (${addedMoment.at.toFixed(3)} m; aimed at 0.8 m), starting at zero`);
  const addedValue = [0.0, 0.0, 0.002];
  for (const [i, c] of ["x", "y", "z"].entries()) await s3c.page.fill(`#m-0-1-${c}`, String(addedValue[i]));
  await s3c.page.click('#moments .moment-apply[data-moment="m-0-1"]');
  await s3c.page.waitForFunction((m) => window.slender.state().rods[0].moments[1].moment.every((x, i) => x === m[i]), addedValue, { timeout: 20000 });
  const withMoment = await s3c.page.evaluate(() => window.slender.state());
  const withMomentText = momentText.replace(`moment = [${newMoment.join(", ")}] }]`,
    `moment = [${newMoment.join(", ")}] }, { vertex = ${addedMoment.vertex}, moment = [${addedValue.map((x) => x.toFixed(3)).join(", ")}] }]`);
  const withMomentCold = solveScene("moment_added_cold", withMomentText);
  const addedMomentGap = maxRelativeDistance(withMoment.rods.map((r) => r.positions), withMomentCold, 1.0);
  check(withMomentText !== momentText && addedMomentGap <= 1e-9,
    `moment: with the added moment set, the page = slender solve with it in the file (${addedMomentGap.toExponential(2)} of the length)`);
  await s3c.page.click('#moments .moment-remove[data-moment="m-0-1"]');
  await s3c.page.waitForFunction(() => window.slender.state().rods[0].moments.length === 1, null, { timeout: 20000 });
  const momentRemoved = await s3c.page.evaluate(() => window.slender.state());
  const momentRemovedGap = maxRelativeDistance(momentRemoved.rods.map((r) => r.positions), momentEdited.rods.map((r) => r.positions), 1.0);
  check(momentRemovedGap <= 1e-9, `moment: × removed it, back to the equilibrium before (${momentRemovedGap.toExponential(2)} of the length)`);
  await s3c.page.evaluate(() => document.activeElement?.blur());
  await s3c.page.keyboard.press("Control+Z");
  await s3c.page.waitForFunction(() => window.slender.state().rods[0].moments.length === 2, null, { timeout: 20000 });
  const momentUndone = await s3c.page.evaluate(() => window.slender.state());
  check(JSON.stringify(momentUndone.rods[0].positions) === JSON.stringify(withMoment.rods[0].positions),
    "moment: Ctrl+Z puts the removed moment back with its equilibrium, bit for bit");
  await s3c.page.evaluate(() => window.slender.setTool("drag"));
  await s3c.page.screenshot({ path: join(out, "view-moment-line-load.png") });
  for (const e of s3c.errors) fail(e);
  check(s3c.errors.length === 0, "no console errors (moment and line load page)");
  await s3c.page.close();
  s3c.proc.kill();
  sessions.splice(sessions.indexOf(s3c), 1);

  // ---- 3d. a follower force: drawn as it acts now, edited as given at rest ----
  const followerScene = join(here, "../../examples/follower_cantilever.toml");
  const s3d = await open(followerScene);
  sessions.push(s3d);
  /** The follower's arrow against the state: tip at the vertex, along `now`, normal to the
   *  last edge (the follower turns with it). */
  const followerDrawn = async () => {
    const st = await s3d.page.evaluate(() => window.slender.state());
    const f = st.rods[0].forces[0];
    const a = (await loadArrows(s3d.page)).find((x) => x.load[0] === "rod" && x.load[2] === 0);
    const p = st.rods[0].positions;
    const tip = p.at(-1).map((x, k) => x - p.at(-2)[k]);
    const n = Math.hypot(...f.now);
    const normal = Math.abs(f.now.reduce((m, x, k) => m + x * tip[k], 0)) / (n * Math.hypot(...tip));
    const ok = !!a && Math.hypot(...a.tip.map((x, i) => x - f.position[i])) <= 1e-6
      && a.dir.every((x, i) => Math.abs(x - f.now[i] / n) <= 1e-6) && normal <= 1e-9 && f.follower;
    return { st, f, ok, normal };
  };
  const d0 = await followerDrawn();
  check(d0.ok, `follower force: drawn at the tip along the force as it acts now [${d0.f.now.map((x) => x.toFixed(3))}] N, normal to the tip (cos ${d0.normal.toExponential(1)})`);
  const followerForce = [0, 3, 0];
  for (const [i, c] of ["x", "y", "z"].entries()) await s3d.page.fill(`#f-0-0-${c}`, String(followerForce[i]));
  await s3d.page.click('#loads .force-apply[data-load="f-0-0"]');
  await s3d.page.waitForFunction((f) => window.slender.state().rods[0].forces[0].force.every((x, i) => x === f[i]), followerForce, { timeout: 20000 });
  const d1 = await followerDrawn();
  const followerText = readFileSync(followerScene, "utf8").replace("force = [0.0, 2.0, 0.0], follower = true", "force = [0.0, 3.0, 0.0], follower = true");
  const followerCold = solveScene("follower_edited_cold", followerText);
  const followerGap = maxRelativeDistance(d1.st.rods.map((r) => r.positions), followerCold, 1.0);
  // The follower is +y at rest: its angle from +y toward −x is the tip's turn.
  const turnOf = (f) => Math.atan2(-f.now[0], f.now[1]);
  const followerTurn = turnOf(d1.f);
  console.log(`view test: follower force set to [${followerForce}] N (as at rest) in the panel: it acts along [${d1.f.now.map((x) => x.toFixed(4))}] N now (turned ${followerTurn.toFixed(3)} rad with the tip); every vertex within ${followerGap.toExponential(2)} of the length of slender solve with the new force in the file`);
  check(followerText.includes("[0.0, 3.0, 0.0]") && d1.st.converged && followerGap <= 1e-9,
    `follower force: the edited equilibrium = slender solve's with the force in the file, to 1e-9 of the length (${followerGap.toExponential(2)})`);
  check(d1.ok && followerTurn > turnOf(d0.f) + 0.1, `follower force: the arrow follows the edit, normal to the tip, turned further (${turnOf(d0.f).toFixed(3)} → ${followerTurn.toFixed(3)} rad)`);
  await s3d.page.screenshot({ path: join(out, "view-follower.png") });
  for (const e of s3d.errors) fail(e);
  check(s3d.errors.length === 0, "no console errors (follower page)");
  await s3d.page.close();
  s3d.proc.kill();
  sessions.splice(sessions.indexOf(s3d), 1);

  // ---- 4. obstacles drawn; a clamp dragged into the floor ----
  const s4 = await open(join(scenes, "obstacles.toml"));
  sessions.push(s4);
  const first = await s4.replies[0];
  const shapes = first.geometry?.obstacles ?? [];
  /** What the page's three.js scene holds: obstacle meshes, visible contact markers, contact
   *  arrows (world-space origin, tip, the force they stand for), all read from the scene graph. */
  const drawn = (page) => page.evaluate(() => {
    const out = { obstacles: [], markers: [], arrows: [] };
    window.slender.scene.updateMatrixWorld(true);
    const visible = (o) => { for (let x = o; x; x = x.parent) if (!x.visible) return false; return true; };
    window.slender.scene.traverse((o) => {
      if (o.isMesh && o.name.startsWith("obstacle:")) {
        const pos = o.geometry.attributes.position;
        const world = [];
        for (let i = 0; i < pos.count; i++) world.push(o.localToWorld(o.position.clone().fromBufferAttribute(pos, i)).toArray());
        o.geometry.computeBoundingBox();
        const box = o.geometry.boundingBox.clone().applyMatrix4(o.matrixWorld);
        out.obstacles.push({ ...o.userData, name: o.name, visible: visible(o), triangles: (o.geometry.index ? o.geometry.index.count : pos.count) / 3,
          world, box: [box.min.toArray(), box.max.toArray()] });
      }
      if (o.userData.contactMarker && visible(o)) {
        out.markers.push({ ...o.userData.contact, colour: o.material.color.getHex(), at: o.getWorldPosition(o.position.clone()).toArray() });
      }
      if (o.userData.contactArrow && visible(o)) {
        const origin = o.getWorldPosition(o.position.clone());
        const tip = o.cone.getWorldPosition(o.position.clone());
        out.arrows.push({ kind: o.userData.contactArrow, force: o.userData.force, ...o.userData.contact, origin: origin.toArray(), tip: tip.toArray() });
      }
    });
    out.scale = window.slender.contactScale();
    return out;
  });
  const countContacts = (reply) => reply.view.obstacles.reduce((n, o) => n + o.contacts.length, 0);
  let d4 = await drawn(s4.page);
  const kinds = d4.obstacles.map((o) => `${o.name.slice(9)}=${o.kind}`).join(", ");
  check(shapes.length === 6 && d4.obstacles.length === 6 && d4.obstacles.every((o, i) => o.obstacle === i && o.kind === shapes[i].shape.kind && o.visible),
    `obstacles: every obstacle is a mesh of the scene, tagged (${kinds})`);
  const ball = d4.obstacles.find((o) => o.kind === "sphere");
  const ballErr = Math.max(...[0, 1, 2].flatMap((k) => [Math.abs(ball.box[0][k] - ([0.4, 0, 0][k] - 0.045)), Math.abs(ball.box[1][k] - ([0.4, 0, 0][k] + 0.045))]));
  check(ballErr < 1e-6, `obstacles: the ball's bounds are its centre ± its radius (${ballErr.toExponential(1)} m)`);
  // The box's corners: centre + R(rotate)·(±size/2), R by Rodrigues' formula.
  const rodrigues = (w, v) => {
    const t = Math.hypot(...w);
    if (t === 0) return v;
    const k = w.map((x) => x / t);
    const kv = k[0] * v[0] + k[1] * v[1] + k[2] * v[2];
    const kxv = [k[1] * v[2] - k[2] * v[1], k[2] * v[0] - k[0] * v[2], k[0] * v[1] - k[1] * v[0]];
    return v.map((x, i) => x * Math.cos(t) + kxv[i] * Math.sin(t) + k[i] * kv * (1 - Math.cos(t)));
  };
  const block = d4.obstacles.find((o) => o.kind === "box");
  const corners = [];
  for (const sx of [-1, 1]) for (const sy of [-1, 1]) for (const sz of [-1, 1])
    corners.push(rodrigues([0, 0, 0.4], [sx * 0.03, sy * 0.04, sz * 0.015]).map((x, i) => x + [0.2, 0, 0.015][i]));
  const nearest = (p, pts) => Math.min(...pts.map((q) => Math.hypot(p[0] - q[0], p[1] - q[1], p[2] - q[2])));
  const boxErr = Math.max(...corners.map((c) => nearest(c, block.world)));
  check(boxErr < 1e-6, `obstacles: the box's corners at its centre, size and rotation (${boxErr.toExponential(1)} m)`);
  // The ramp: the OBJ file's triangles, at the file's vertices.
  const obj = readFileSync(join(scenes, "ramp.obj"), "utf8").split("\n");
  const objVertices = obj.filter((l) => l.startsWith("v ")).map((l) => l.split(/\s+/).slice(1, 4).map(Number));
  const objFaces = obj.filter((l) => l.startsWith("f ")).length;
  const ramp = d4.obstacles.find((o) => o.kind === "mesh");
  const rampErr = Math.max(...ramp.world.map((p) => nearest(p, objVertices)), ...objVertices.map((p) => nearest(p, ramp.world)));
  check(ramp.triangles === objFaces && rampErr < 1e-6, `obstacles: the ramp has the OBJ file's ${objFaces} triangles at its vertices (${ramp.triangles} drawn, ${rampErr.toExponential(1)} m)`);
  // The ring (axis z): its circle's radius plus its tube's across the axis, the tube's along it.
  const ring = d4.obstacles.find((o) => o.kind === "torus");
  const ringReach = [0.038, 0.038, 0.008];
  const ringErr = Math.max(...[0, 1, 2].flatMap((k) => [Math.abs(ring.box[0][k] - ([0.7, 0.08, 0.03][k] - ringReach[k])), Math.abs(ring.box[1][k] - ([0.7, 0.08, 0.03][k] + ringReach[k]))]));
  check(ringErr < 1e-6, `obstacles: the ring's bounds are its centre ± (radius + tube radius) across its axis, ± its tube radius along it (${ringErr.toExponential(1)} m)`);
  const floor = d4.obstacles.find((o) => o.kind === "plane");
  const floorShape = shapes.find((o) => o.shape.kind === "plane").shape;
  check(Math.max(Math.abs(floor.box[0][2]), Math.abs(floor.box[1][2])) < 1e-9 && Math.abs(floor.box[1][0] - floor.box[0][0] - floorShape.size) < 1e-6,
    `obstacles: the floor is a square of ${floorShape.size.toFixed(3)} m in its plane`);
  check(d4.markers.length === countContacts(first) && d4.markers.length > 0,
    `obstacles: ${d4.markers.length} contact markers for the reply's ${countContacts(first)} active contacts`);
  const shown = await paintedFraction(s4.page);
  await s4.page.click("#show-obstacles");
  const hidden = await drawn(s4.page);
  const without = await paintedFraction(s4.page);
  await s4.page.click("#show-obstacles");
  check(hidden.obstacles.every((o) => !o.visible) && without < shown && (await drawn(s4.page)).obstacles.every((o) => o.visible),
    `obstacles: the toggle hides and shows them (${(100 * shown).toFixed(1)} % → ${(100 * without).toFixed(1)} % of pixels drawn)`);
  // Drag the clamp 8 cm down (to 2 cm under the floor) in 1 cm gizmo moves.
  const n4 = s4.replies.length;
  await s4.page.evaluate(async () => {
    for (let k = 0; k < 8; k++) await window.slender.dragSupport(0, 0, [0, 0, -0.01], 1);
  });
  // The drags' move replies (each drag also sends its undo checkpoint).
  const dragReplies = (await Promise.all(s4.replies.slice(n4))).filter((r) => r.op !== "checkpoint");
  const gaps = dragReplies.filter((r) => r.ok).map((r) => r.view.min_gap);
  const lowest = Math.min(...dragReplies.filter((r) => r.ok).flatMap((r) => r.view.rods[0].positions.map((p) => p[2])));
  const refused = dragReplies.filter((r) => !r.ok || !r.edit?.converged).length;
  check(gaps.length === dragReplies.length && gaps.every((g) => g > 0) && lowest > 0,
    `drag into the floor: ${dragReplies.length} replies, every min gap > 0 (smallest ${Math.min(...gaps).toExponential(2)} m), lowest vertex at ${(lowest * 1000).toFixed(2)} mm`);
  check(refused > 0, `drag into the floor: the moves that would take the cable through it do not converge (${refused} of ${dragReplies.length}) and keep the last equilibrium`);
  const last4 = dragReplies.at(-1);
  const pageGap = await s4.page.evaluate(() => ({ data: Number(document.body.dataset.minGap), text: document.getElementById("min-gap").textContent, status: document.getElementById("st-converged").textContent }));
  check(pageGap.data === last4.view.min_gap && pageGap.data >= 0 && pageGap.text !== "–",
    `drag into the floor: the page shows min gap ${pageGap.text} (≥ 0), status "${pageGap.status}"`);
  d4 = await drawn(s4.page);
  check(d4.markers.length === countContacts(last4), `drag into the floor: ${d4.markers.length} markers for the last reply's ${countContacts(last4)} contacts`);
  await s4.page.screenshot({ path: join(out, "view-obstacles.png") });
  for (const e of s4.errors) fail(e);
  check(s4.errors.length === 0, "no console errors (obstacles page)");

  // ---- 5. contacts of the cable over the bracket ----
  const s5 = await open(join(here, "../../examples/cable_over_bracket.toml"));
  sessions.push(s5);
  const r5 = await s5.replies[0];
  const d5 = await drawn(s5.page);
  check(d5.obstacles.map((o) => `${o.name}=${o.kind}`).join() === "obstacle:bracket=cylinder,obstacle:floor=plane", `bracket: the bar and the floor are drawn (${d5.obstacles.map((o) => o.name).join(", ")})`);
  check(d5.markers.length === countContacts(r5) && d5.markers.length >= 2,
    `bracket: ${d5.markers.length} contact markers for the reply's ${countContacts(r5)} active contacts`);
  const colours = { sticking: 0x2e7d32, sliding: 0xe65100, frictionless: 0x8e24aa };
  const stateOf = (o, c) => (o.friction === 0 ? "frictionless" : c.sticking ? "sticking" : "sliding");
  const byState = {};
  const colourOk = d5.markers.every((m) => {
    const o = r5.view.obstacles[m.obstacle];
    const st = stateOf(o, o.contacts[m.index]);
    byState[st] = (byState[st] ?? 0) + 1;
    return m.colour === colours[st];
  });
  check(colourOk, `bracket: markers coloured by state (${Object.entries(byState).map(([k, n]) => `${n} ${k}`).join(", ")})`);
  // Normal-force arrows: along the reply's force, |f_n| × the page's scale long.
  let worstLen = 0, worstDir = 0, arrowsSeen = 0;
  for (const a of d5.arrows.filter((x) => x.kind === "normal")) {
    const f = r5.view.obstacles[a.obstacle].contacts[a.index].normal_force;
    const fn = Math.hypot(...f);
    const v = a.tip.map((x, k) => x - a.origin[k]);
    const len = Math.hypot(...v);
    worstLen = Math.max(worstLen, Math.abs(len - fn * d5.scale) / (fn * d5.scale));
    worstDir = Math.max(worstDir, 1 - v.reduce((s, x, k) => s + x * f[k], 0) / (len * fn));
    arrowsSeen++;
  }
  const bracketFn = Math.hypot(...r5.view.obstacles[0].contacts[0].normal_force);
  const bracketArrow = d5.arrows.find((a) => a.kind === "normal" && a.obstacle === 0 && a.index === 0);
  check(arrowsSeen >= 2 && bracketArrow && worstLen < 1e-6 && worstDir < 1e-9 && Math.abs(bracketArrow.force - bracketFn) <= 1e-12 * bracketFn,
    `bracket: ${arrowsSeen} normal-force arrows along the reply's forces, lengths |f_n| × ${d5.scale.toPrecision(3)} m/N to ${worstLen.toExponential(1)} (bracket: ${bracketFn.toPrecision(4)} N)`);
  // The bracket's contact under the pointer: its values.
  const bm = d5.markers.find((m) => m.obstacle === 0);
  const at = await s5.page.evaluate((x) => window.slender.screenPointOf(x), bm.at);
  await s5.page.mouse.move(at.x, at.y);
  await s5.page.waitForSelector("#tooltip:not([hidden])", { timeout: 5000 }).catch(() => {});
  const tip = await s5.page.evaluate(() => (document.getElementById("tooltip").hidden ? "" : document.getElementById("tooltip").textContent));
  const fmt = (n) => (n === 0 ? "0 N" : Math.abs(n) >= 1e3 || Math.abs(n) < 1e-3 ? `${n.toExponential(2)} N` : `${n.toPrecision(3)} N`);
  check(tip.startsWith("bracket · cable vertex ") && tip.includes(`normal force ${fmt(bracketFn)}, frictionless`),
    `bracket: hovering its contact shows "${tip}"`);
  const panel = await s5.page.evaluate(() => [...document.querySelectorAll("#obstacle-table .resultant")].map((e) => e.textContent));
  const resultants = r5.view.obstacles.map((o) => fmt(Math.hypot(...o.force)));
  check(panel.join() === resultants.join(), `bracket: the panel gives each obstacle's resultant (${panel.join(", ")}) and min gap ${await s5.page.locator("#min-gap").textContent()}`);
  const painted5 = await paintedFraction(s5.page);
  check(painted5 > 0.01, `bracket: canvas not blank (${(100 * painted5).toFixed(1)} % of pixels drawn)`);
  await s5.page.screenshot({ path: join(out, "view-contact.png") });
  // A drag (the clamp pulled back 2 cm, as in the example's motion): the markers follow.
  const n5 = s5.replies.length;
  await s5.page.mouse.move(5, 5);
  const v5 = await s5.page.evaluate(() => window.slender.dragSupport(0, 0, [-0.02, 0, 0], 4));
  const last5 = (await Promise.all(s5.replies.slice(n5))).filter((r) => r.ok).at(-1);
  const d5b = await drawn(s5.page);
  check(d5b.markers.length === countContacts(last5) && last5.view.min_gap > 0,
    `bracket: after a drag (${v5.converged ? "converged" : "not converged: last equilibrium kept"}) ${d5b.markers.length} markers for the reply's ${countContacts(last5)} contacts, min gap ${last5.view.min_gap.toExponential(2)} m`);
  // The bracket lifted 1 cm through the obstacle row: the reply carries the moved bar, the
  // page draws it there, the cable rests on it (every gap positive), the markers follow.
  const bar0 = d5b.obstacles.find((o) => o.name === "obstacle:bracket").box;
  const moved5 = await moveObstacleByRows(s5, 0, [0, 0, 0.01]);
  const d5c = await drawn(s5.page);
  const bar1 = d5c.obstacles.find((o) => o.name === "obstacle:bracket").box;
  const lift = bar1[0][2] - bar0[0][2];
  check(moved5?.ok && moved5.edit.converged && Math.abs(lift - 0.01) < 1e-6 && moved5.view.min_gap > 0 && d5c.markers.length === countContacts(moved5),
    `bracket lifted 1 cm through the obstacle row: ${moved5?.ok ? (moved5.edit.converged ? "converged" : "not converged") : "refused"}, drawn ${lift.toFixed(6)} m higher, min gap ${moved5.view?.min_gap?.toExponential(2)} m, ${d5c.markers.length} markers for ${countContacts(moved5)} contacts`);
  // Then turned 10° about the vertical through its reference point (the row's rotation
  // fields, degrees): the reply's bar axis is the y axis turned by 10° about z, the page draws
  // the bar along it, and the cable still rests on it.
  const turned5 = await moveObstacleByRows(s5, 0, [0, 0, 0], [0, 0, 10]);
  const axis = turned5?.geometry?.obstacles?.find((o) => o.name === "bracket")?.shape?.axis ?? [NaN, NaN, NaN];
  const t = 10 / 180 * Math.PI;
  const axisErr = Math.hypot(axis[0] + Math.sin(t), axis[1] - Math.cos(t), axis[2]);
  const d5d = await drawn(s5.page);
  const bar2 = d5d.obstacles.find((o) => o.name === "obstacle:bracket").box;
  // Drawn x extent: the bar's length L seen at 10°, L sin 10° + 2 r cos 10°, wider than 2 r.
  const widened = (bar2[1][0] - bar2[0][0]) - (bar1[1][0] - bar1[0][0]);
  check(turned5?.ok && turned5.edit.converged && axisErr < 1e-12 && widened > 0.01 && turned5.view.min_gap > 0,
    `bracket turned 10° about z through the obstacle row: ${turned5?.ok ? (turned5.edit.converged ? "converged" : "not converged") : "refused"}, axis off by ${axisErr.toExponential(1)}, drawn ${widened.toFixed(4)} m wider in x, min gap ${turned5?.view?.min_gap?.toExponential(2)} m`);
  // The gizmo: in "move an obstacle" mode a click on the bracket grabs it; dragged 5 mm down
  // in five gizmo changes, the cable follows live (one move per change) and it ends there
  // (the gizmo holds the new mesh); turned back by
  // −10° about z, it turns about the centre of its drawn piece (the gizmo's pivot): the axis
  // is the y axis again and still passes through that centre.
  await s5.page.evaluate(() => window.slender.setTool("move-obstacle"));
  const barCentre = d5d.obstacles.find((o) => o.name === "obstacle:bracket");
  const centre5 = turned5.geometry.obstacles.find((o) => o.name === "bracket").shape.center;
  const at5 = await s5.page.evaluate((c) => window.slender.screenPointOf(c), centre5);
  await s5.page.mouse.click(at5.x, at5.y);
  const grabbed5 = await s5.page.evaluate(() => window.slender.grabbedObstacle());
  const nDrag5 = s5.replies.length;
  const down5 = await s5.page.evaluate(() => window.slender.dragObstacle(0, [0, 0, -0.005]));
  const pieces5 = (await Promise.all(s5.replies.slice(nDrag5))).filter((r) => r.op === "obstacle");
  const d5e = await drawn(s5.page);
  const bar3 = d5e.obstacles.find((o) => o.name === "obstacle:bracket").box;
  const drop = bar3[0][2] - bar2[0][2];
  const still5 = await s5.page.evaluate(() => window.slender.grabbedObstacle());
  check(barCentre && grabbed5 === 0 && down5?.ok && down5.edit.converged && Math.abs(drop + 0.005) < 1e-6 && still5 === 0 && down5.view.min_gap > 0
    && pieces5.length >= 2 && pieces5.every((r) => r.ok && r.edit.converged),
    `bracket grabbed by a click (obstacle ${grabbed5}) and dragged 5 mm down with the gizmo, live (${pieces5.length} moves answered during the drag): ${down5?.ok ? (down5.edit.converged ? "converged" : "not converged") : "refused"}, drawn ${(-drop * 1000).toFixed(3)} mm lower, the gizmo still on it (${still5}), min gap ${down5?.view?.min_gap?.toExponential(2)} m`);
  const pivot5 = down5.geometry.obstacles.find((o) => o.name === "bracket").shape.center;
  const back5 = await s5.page.evaluate(() => window.slender.dragObstacle(0, [0, 0, 0], [0, 0, -10 / 180 * Math.PI]));
  const bent = back5?.geometry?.obstacles?.find((o) => o.name === "bracket")?.shape;
  const axisBack = bent ? Math.hypot(bent.axis[0], bent.axis[1] - 1, bent.axis[2]) : NaN;
  // Distance from the pivot to the new axis line (through bent.center along bent.axis).
  const rel = bent ? pivot5.map((x, k) => x - bent.center[k]) : [NaN, NaN, NaN];
  const along = bent ? rel[0] * bent.axis[0] + rel[1] * bent.axis[1] + rel[2] * bent.axis[2] : NaN;
  const offAxis = Math.hypot(...rel.map((x, k) => x - along * (bent?.axis[k] ?? NaN)));
  check(back5?.ok && back5.edit.converged && axisBack < 1e-12 && offAxis < 1e-9,
    `bracket turned back 10° with the gizmo: ${back5?.ok ? (back5.edit.converged ? "converged" : "not converged") : "refused"}, axis off y by ${axisBack.toExponential(1)}, the turn's pivot ${offAxis.toExponential(1)} m from the new axis`);
  // The turning drag was many moves and is one step of undo: Undo draws the bracket where the
  // 5 mm drag left it, with that drag's cable.
  await s5.page.click("#undo");
  await s5.page.waitForFunction(() => window.slender.lastReply?.op === "undo", null, { timeout: 20000 });
  const bar4 = (await drawn(s5.page)).obstacles.find((o) => o.name === "obstacle:bracket").box;
  const undoErr = Math.max(...[0, 1].flatMap((c) => [0, 1, 2].map((k) => Math.abs(bar4[c][k] - bar3[c][k]))));
  const cableBack = await s5.page.evaluate(() => JSON.stringify(window.slender.state().rods[0].positions));
  check(undoErr < 1e-12 && cableBack === JSON.stringify(down5.view.rods[0].positions),
    `one Undo takes the turning gizmo drag back: the bracket drawn where the 5 mm drag left it (${undoErr.toExponential(1)} m), the cable that drag's bit for bit`);
  for (const e of s5.errors) fail(e);
  check(s5.errors.length === 0, "no console errors (bracket page)");

  // ---- 5c. a flat cable over the bracket: the bracket lifted through the obstacle row ----
  const flatScene = join(here, "../../examples/flat_cable_on_bracket.toml");
  const flatText = readFileSync(flatScene, "utf8");
  const s5f = await open(flatScene);
  sessions.push(s5f);
  const r5f = await s5f.replies[0];
  const flat0 = r5f.view.shells[0].positions;
  const lifted5f = await moveObstacleByRows(s5f, 0, [0, 0.005, 0]);
  const flat1 = lifted5f?.view?.shells?.[0]?.positions ?? flat0;
  // Over the bracket (x = 0.2 ± 3 cm): the strip's highest point there, lifted with it.
  const overBracket = (ps) => Math.max(...ps.filter((p) => Math.abs(p[0] - 0.2) < 0.03).map((p) => p[1]));
  const rise = overBracket(flat1) - overBracket(flat0);
  // slender solve of the file with the lift as its motion stage (instead of the clamp's).
  const liftText = flatText.slice(0, flatText.indexOf("[[motion]]")) + "[[motion]]\nobstacle = 0\ntranslate = [0.0, 0.005, 0.0]\n";
  const liftCold = solveSceneResult("flat_cable_bracket_lifted", liftText).shells[0].positions;
  const liftGap = maxRelativeDistance([flat1], [liftCold], 0.6);
  check(lifted5f?.ok && lifted5f.edit.converged && rise > 0.004 && liftGap <= 1e-9 && lifted5f.view.min_gap > 0,
    `flat cable: the bracket lifted 5 mm through the obstacle row: ${lifted5f?.ok ? (lifted5f.edit.converged ? "converged" : "not converged") : "refused"}, the strip over it ${(rise * 1000).toFixed(2)} mm higher, every vertex within ${liftGap.toExponential(2)} of its length of slender solve with the lift as a motion stage, min gap ${lifted5f?.view?.min_gap?.toExponential(2)} m`);
  for (const e of s5f.errors) fail(e);
  check(s5f.errors.length === 0, "no console errors (flat cable on the bracket)");

  // ---- 5b. cable on cable (self-contact), where the core's results list the pairs ----
  const s5c = await open(join(scenes, "crossing_cables.toml"));
  sessions.push(s5c);
  const r5c = await s5c.replies[0];
  if (r5c.view.segment_contacts === undefined) {
    console.log("view test: skipped cable on cable: the core's results do not list segment contacts (segment_contacts)");
  } else {
    const pairs = r5c.view.segment_contacts;
    const d5c = await s5c.page.evaluate(() => {
      const out = { markers: [], arrows: [] };
      window.slender.scene.updateMatrixWorld(true);
      const visible = (o) => { for (let x = o; x; x = x.parent) if (!x.visible) return false; return true; };
      window.slender.scene.traverse((o) => {
        if (o.userData.pairMarker && visible(o)) out.markers.push({ pair: o.userData.pair, at: o.getWorldPosition(o.position.clone()).toArray() });
        if (o.userData.contactArrow === "pair" && visible(o)) {
          out.arrows.push({ pair: o.userData.pair, origin: o.getWorldPosition(o.position.clone()).toArray(), tip: o.cone.getWorldPosition(o.position.clone()).toArray() });
        }
      });
      out.scale = window.slender.contactScale();
      return out;
    });
    check(pairs.length >= 1 && d5c.markers.length === pairs.length,
      `cable on cable: ${d5c.markers.length} pair markers for the reply's ${pairs.length} touching segment pairs (min segment gap ${r5c.view.min_segment_gap})`);
    // Two arrows per pair, one along each side's force, |f| × the scale long.
    let worst = 0;
    for (const a of d5c.arrows) {
      const p = pairs[a.pair];
      const v = a.tip.map((x, k) => x - a.origin[k]);
      const err = Math.min(...[p.force_a, p.force_b].map((f) => Math.hypot(...v.map((x, k) => x - f[k] * d5c.scale))));
      worst = Math.max(worst, err / (Math.hypot(...p.force_a) * d5c.scale));
    }
    check(d5c.arrows.length === 2 * pairs.length && worst < 1e-6, `cable on cable: the force on each cable drawn (${d5c.arrows.length} arrows, to ${worst.toExponential(1)})`);
    const at = await s5c.page.evaluate((x) => window.slender.screenPointOf(x), d5c.markers[0].at);
    await s5c.page.mouse.move(at.x, at.y);
    await s5c.page.waitForSelector("#tooltip:not([hidden])", { timeout: 5000 }).catch(() => {});
    const tip = await s5c.page.evaluate(() => (document.getElementById("tooltip").hidden ? "" : document.getElementById("tooltip").textContent));
    check(/^(lower|upper) (edge|vertex) \d+ – (lower|upper) edge \d+ /.test(tip), `cable on cable: hovering the pair shows "${tip}"`);
    await s5c.page.screenshot({ path: join(out, "view-cable-on-cable.png") });
  }
  for (const e of s5c.errors) fail(e);
  check(s5c.errors.length === 0, "no console errors (crossing cables page)");

  // ---- 6. speed (measured, not asserted) ----
  // One page at a time, as a user has it: the pages and servers of the checks above are
  // closed first (their renderers would share the two cores with the measured page).
  for (const s of sessions.splice(0)) { await s.page.close(); s.proc.kill(); }
  const speed = {};
  for (const [name, scene, support, d, n] of [
    ["cable_100_elements_3_clips", "bench_cable_3clips.toml", 4, [-0.4, 0.3, 0.3], 300],
    ["flat_cable_100_elements", "bench_flat_cable.toml", 1, [-0.1, 0.1, 0.1], 100],
  ]) {
    const s = await open(join(scenes, scene));
    sessions.push(s);
    const b = await s.page.evaluate(({ support, d, n }) => window.slender.benchmarkDrag(0, support, d, n), { support, d, n });
    const r = {
      updates: b.updates,
      all_converged: b.allConverged,
      updates_per_second: (1000 * b.updates) / b.elapsedMs,
      frame_interval_ms: { median: quantile(b.intervalMs, 0.5), p95: quantile(b.intervalMs, 0.95) },
      pose_to_frame_ms: { median: quantile(b.latencyMs, 0.5), p95: quantile(b.latencyMs, 0.95) },
      server_solve_ms: { median: quantile(b.serverMs, 0.5), p95: quantile(b.serverMs, 0.95) },
      round_trip_ms: { median: quantile(b.roundTripMs, 0.5), p95: quantile(b.roundTripMs, 0.95) },
      page_update_ms: { median: quantile(b.updateMs, 0.5), p95: quantile(b.updateMs, 0.95) },
      page_render_ms: { median: quantile(b.renderMs, 0.5), p95: quantile(b.renderMs, 0.95) },
      transports: b.transports,
    };
    speed[name] = r;
    console.log(`view speed: ${name}: ${r.updates} updates, ${r.updates_per_second.toFixed(1)} updates/s; frame interval median ${r.frame_interval_ms.median.toFixed(2)} ms, p95 ${r.frame_interval_ms.p95.toFixed(2)} ms; server solve median ${r.server_solve_ms.median.toFixed(2)} ms, p95 ${r.server_solve_ms.p95.toFixed(2)} ms; request round trip (${r.transports.join(", ")}) median ${r.round_trip_ms.median.toFixed(2)} ms; page update ${r.page_update_ms.median.toFixed(2)} ms + render ${r.page_render_ms.median.toFixed(2)} ms (medians); all converged: ${r.all_converged}`);
    await s.page.screenshot({ path: join(out, `view-speed-${name}.png`) });
    for (const e of s.errors) fail(e);
    await s.page.close();
  }
  writeFileSync(join(out, "speed.json"), JSON.stringify(speed, null, 2) + "\n");
} finally {
  await browser.close();
  for (const s of sessions) s.proc.kill();
}
const total = problems.length;
if (total) {
  console.error(`view test: FAILED (${total} problems)`);
  process.exit(1);
}
console.log(`view test: passed (screenshots and speed.json in ${out})`);
