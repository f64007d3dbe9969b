// The page of `slender view`: draws the equilibria the slender process computes and sends it
// the user's edits: one JSON request, one reply (see src/view/protocol.rs), over the page's
// WebSocket (GET /ws) when it opens, else by POST /api. A fetch costs the page several
// milliseconds per request on a busy machine, a socket message under one (src/view/socket.rs).
//
// Drags are throttled to one request in flight: while a reply is awaited, only the latest
// pose is kept, and it is sent when the reply arrives. All requests go through one queue, so
// the server sees them in order.

import * as THREE from "three";
import { OrbitControls } from "three/addons/OrbitControls.js";
import { TransformControls } from "three/addons/TransformControls.js";

const TUBE_SIDES = 12;
const $ = (id) => document.getElementById(id);

// ---------- talking to the server ----------

/** The open WebSocket, or null (then requests are POSTed). */
let socket = null;
/** Takes the reply text (null: the socket closed) of the request in flight on the socket. */
let socketWaiter = null;
/** Settles once the socket is open or has failed (after at most two seconds). */
const socketReady = new Promise((resolve) => {
  let ws;
  try {
    ws = new WebSocket(`ws://${location.host}/ws`);
  } catch {
    resolve();
    return;
  }
  setTimeout(resolve, 2000);
  ws.onopen = () => { socket = ws; resolve(); };
  ws.onmessage = (e) => { const w = socketWaiter; socketWaiter = null; if (w) w(e.data); };
  ws.onclose = () => {
    if (socket === ws) socket = null;
    resolve();
    const w = socketWaiter; socketWaiter = null; if (w) w(null);
  };
});

let queue = Promise.resolve();
/** Sends one request after the previous ones; resolves to the reply (or a transport error). */
function request(req) {
  const p = queue.then(async () => {
    await socketReady;
    const t0 = performance.now();
    const body = JSON.stringify(req);
    let reply;
    if (socket) {
      const ws = socket;
      const text = await new Promise((r) => { socketWaiter = r; ws.send(body); });
      try {
        // A socket that closed mid-request is not retried by POST: the server may have
        // applied the edit already.
        reply = text === null
          ? { ok: false, error: { field: "connection", message: "the WebSocket closed before the reply" } }
          : JSON.parse(text);
      } catch (e) {
        reply = { ok: false, error: { field: "connection", message: `${e}` } };
      }
      reply.transport = "websocket";
    } else {
      try {
        const r = await fetch("/api", {
          method: "POST",
          headers: { "Content-Type": "application/json" },
          body,
        });
        reply = await r.json();
      } catch (e) {
        reply = { ok: false, error: { field: "connection", message: `${e}` } };
      }
      reply.transport = "post";
    }
    reply.roundTripMs = performance.now() - t0;
    return reply;
  });
  queue = p.catch(() => {});
  return p;
}

// ---------- three.js scene ----------

const canvas = $("canvas");
const renderer = new THREE.WebGLRenderer({ canvas, antialias: true, preserveDrawingBuffer: true });
renderer.setPixelRatio(Math.min(window.devicePixelRatio, 2));
const scene3 = new THREE.Scene();
scene3.background = new THREE.Color(0xf4f6f8);
const camera = new THREE.PerspectiveCamera(40, 1, 1e-4, 1e4);
scene3.add(new THREE.HemisphereLight(0xffffff, 0x8090a0, 1.6));
const sun = new THREE.DirectionalLight(0xffffff, 1.6);
scene3.add(sun);
const orbit = new OrbitControls(camera, canvas);
const gizmo = new TransformControls(camera, canvas);
scene3.add(gizmo.getHelper());
// A drag is one step of undo: the server keeps the session as it was when the drag starts
// (its moves wait for that checkpoint).
let checkpointing = null;
gizmo.addEventListener("dragging-changed", (e) => {
  orbit.enabled = !e.value;
  if (e.value) checkpointing = request({ op: "checkpoint" });
  // An obstacle follows the gizmo live too: each change is sent as the move from where the
  // server has it (`drag_obstacle`), the whole drag one step of undo.
  if (grabbed) { if (e.value) startObstacleDrag(); else endObstacleDrag(); return; }
  if (!e.value) afterDrag();
});
gizmo.addEventListener("objectChange", () => (grabbed ? onObstacleChange() : onHandleChange()));
orbit.addEventListener("change", () => requestRender());
gizmo.addEventListener("change", () => requestRender());

const world = new THREE.Group(); // rods, shells, handles, arrows
scene3.add(world);

let view = null; // the last ViewState
let geometry = null; // the obstacles' shapes (the last `state` or `obstacle` reply's `geometry`)
let sceneSize = 1; // diagonal of the first equilibrium's bounding box (m)
const rods = []; // per rod: { mesh, outline, tight, colours }
const shells = [];
let handles = []; // per support: Object3D with userData { rod, support, kind } (a strip's clamp: { shell, support, kind: "shell_clamp" })
let arrows = [];
let labels = [];
let labelSpecs = []; // reaction values: { at, text, cls }
let selected = null; // the handle being edited
let grabbed = null; // an obstacle held by the gizmo: { index, mesh, sent: { position, quaternion } (the pose the server has), dragging }
let dragging = false;
let pendingMove = null; // the next move: { req, queued }, or { obstacle: true, queued } (built when sent)
let moveInFlight = false;
let lastObstacleReply = null; // the reply to the last piece of an obstacle's drag
const timing = { updates: [] }; // per applied move: { sent, received, rendered, serverMs }
let lastEdit = null;

// ---------- colour maps ----------

const VIRIDIS = [[0.267, 0.005, 0.329], [0.283, 0.141, 0.458], [0.254, 0.265, 0.530], [0.207, 0.372, 0.553],
  [0.164, 0.471, 0.558], [0.128, 0.567, 0.551], [0.135, 0.659, 0.518], [0.267, 0.749, 0.441],
  [0.478, 0.821, 0.318], [0.741, 0.873, 0.150], [0.993, 0.906, 0.144]];
const DIVERGING = [[0.230, 0.299, 0.754], [0.552, 0.690, 0.996], [0.865, 0.865, 0.865], [0.958, 0.604, 0.482], [0.706, 0.016, 0.150]];
function ramp(stops, t) {
  t = Math.min(1, Math.max(0, Number.isFinite(t) ? t : 0));
  const x = t * (stops.length - 1);
  const i = Math.min(stops.length - 2, Math.floor(x));
  const u = x - i;
  return stops[i].map((c, k) => c + (stops[i + 1][k] - c) * u);
}
function cssGradient(stops) {
  return `linear-gradient(to right, ${stops.map((c) => `rgb(${c.map((v) => Math.round(v * 255)).join(",")})`).join(",")})`;
}

/** The colour field of a rod: values per vertex, the map, range and unit. */
function field(rod, what) {
  if (what === "twist") return { values: rod.twist, signed: true, scale: 1, unit: "rad/m", title: "twist rate" };
  if (what === "axial") return { values: vertexAverage(rod.axial_force), signed: true, scale: 1, unit: "N", title: "axial force, tension +" };
  if (what === "stress" && rod.bending_stress)
    return { values: rod.bending_stress, signed: false, scale: 1e-6, unit: "MPa", title: "bending stress" };
  return { values: rod.curvature, signed: false, scale: 1, unit: "1/m", title: "curvature |κ|" };
}

/** What the supports table's "along" column is. */
const ALONG_TITLE = "the reaction's component along the cable at the support (N; positive toward the cable's end, increasing arc length): what a clip holds against the cable sliding through it, the pull on an end's connector";

/** Unit tangent of the centerline at vertex `v` (along increasing arc length). */
function tangentAt(rod, v) {
  const p = rod.positions;
  const a = v3(p[Math.max(0, v - 1)]), b = v3(p[Math.min(p.length - 1, v + 1)]);
  return b.sub(a).normalize();
}

/** Per-vertex values from per-edge ones: the mean of the edges beside each vertex. */
function vertexAverage(edges) {
  const n = edges.length;
  if (n === 0) return [0];
  return Array.from({ length: n + 1 }, (_, i) => (i === 0 ? edges[0] : i === n ? edges[n - 1] : 0.5 * (edges[i - 1] + edges[i])));
}

function colourRange(what) {
  let max = 0;
  let stressAvailable = true;
  for (const r of view.rods) {
    if (what === "stress" && !r.bending_stress) stressAvailable = false;
    const f = field(r, what);
    for (const v of f.values) max = Math.max(max, Math.abs(v * f.scale));
  }
  return { max: max > 0 ? max : 1, stressAvailable };
}

function updateLegend(what, range) {
  const sample = view.rods.length ? field(view.rods[0], what) : { signed: false, unit: "", title: "" };
  const stops = sample.signed ? DIVERGING : VIRIDIS;
  $("legend-bar").style.background = cssGradient(stops);
  let title = `${sample.title} (${sample.unit})`;
  if (what === "stress" && !range.stressAvailable)
    title = "bending stress: needs a material (section given by stiffnesses): curvature (1/m) shown";
  $("legend-title").textContent = title;
  const fmt = (v) => (Math.abs(v) >= 1e4 || (Math.abs(v) < 1e-2 && v !== 0) ? v.toExponential(2) : v.toPrecision(3));
  $("legend-min").textContent = fmt(sample.signed ? -range.max : 0);
  $("legend-mid").textContent = fmt(sample.signed ? 0 : range.max / 2);
  $("legend-max").textContent = fmt(range.max);
}

// ---------- geometry ----------

const v3 = (a) => new THREE.Vector3(a[0], a[1], a[2]);

/** Ring frame (n1, n2) at vertex i from the adjacent edges' directors and tangents. */
function ringFrame(rod, i) {
  const p = rod.positions;
  const n = p.length;
  const t = new THREE.Vector3();
  const m = new THREE.Vector3();
  for (const j of [i - 1, i]) {
    if (j < 0 || j >= n - 1) continue;
    t.add(v3(p[j + 1]).sub(v3(p[j])).normalize());
    m.add(v3(rod.directors[j]));
  }
  if (t.lengthSq() < 1e-18) t.copy(v3(p[Math.min(i + 1, n - 1)]).sub(v3(p[Math.max(i - 1, 0)])));
  t.normalize();
  const n1 = m.sub(t.clone().multiplyScalar(t.dot(m)));
  if (n1.lengthSq() < 1e-18) n1.set(1, 0, 0).cross(t);
  if (n1.lengthSq() < 1e-18) n1.set(0, 1, 0).cross(t);
  n1.normalize();
  return [n1, t.clone().cross(n1)];
}

/** Tube positions, normals (and, with `colours`, vertex colours) of a rod into `geometry`. */
function fillTube(geometry, rod, radius, colourOf) {
  const nv = rod.positions.length;
  const pos = geometry.attributes.position.array;
  const nrm = geometry.attributes.normal.array;
  const col = geometry.attributes.color ? geometry.attributes.color.array : null;
  for (let i = 0; i < nv; i++) {
    const [n1, n2] = ringFrame(rod, i);
    const c = rod.positions[i];
    const rgb = col ? colourOf(i) : null;
    for (let k = 0; k < TUBE_SIDES; k++) {
      const a = (2 * Math.PI * k) / TUBE_SIDES;
      const ca = Math.cos(a), sa = Math.sin(a);
      const nx = n1.x * ca + n2.x * sa, ny = n1.y * ca + n2.y * sa, nz = n1.z * ca + n2.z * sa;
      const o = 3 * (i * TUBE_SIDES + k);
      pos[o] = c[0] + radius * nx; pos[o + 1] = c[1] + radius * ny; pos[o + 2] = c[2] + radius * nz;
      nrm[o] = nx; nrm[o + 1] = ny; nrm[o + 2] = nz;
      if (col) { col[o] = rgb[0]; col[o + 1] = rgb[1]; col[o + 2] = rgb[2]; }
    }
  }
  geometry.attributes.position.needsUpdate = true;
  geometry.attributes.normal.needsUpdate = true;
  if (col) geometry.attributes.color.needsUpdate = true;
  geometry.computeBoundingSphere();
}

function tubeGeometry(nv, colours, segments) {
  const g = new THREE.BufferGeometry();
  g.setAttribute("position", new THREE.BufferAttribute(new Float32Array(nv * TUBE_SIDES * 3), 3));
  g.setAttribute("normal", new THREE.BufferAttribute(new Float32Array(nv * TUBE_SIDES * 3), 3));
  if (colours) g.setAttribute("color", new THREE.BufferAttribute(new Float32Array(nv * TUBE_SIDES * 3), 3));
  const idx = [];
  for (const i of segments ?? [...Array(nv - 1).keys()]) {
    for (let k = 0; k < TUBE_SIDES; k++) {
      const a = i * TUBE_SIDES + k;
      const b = i * TUBE_SIDES + ((k + 1) % TUBE_SIDES);
      idx.push(a, b, b + TUBE_SIDES, a, b + TUBE_SIDES, a + TUBE_SIDES);
    }
  }
  g.setIndex(idx);
  return g;
}

function disposeObject(o) {
  o.traverse((c) => {
    if (c.geometry) c.geometry.dispose();
    if (c.material) (Array.isArray(c.material) ? c.material : [c.material]).forEach((m) => m.dispose());
  });
  o.removeFromParent();
}

function buildRods() {
  for (const r of rods) ["mesh", "outline", "tight"].forEach((k) => r[k] && disposeObject(r[k]));
  rods.length = 0;
  view.rods.forEach((rod, index) => {
    const nv = rod.positions.length;
    const mesh = new THREE.Mesh(tubeGeometry(nv, true),
      new THREE.MeshStandardMaterial({ vertexColors: true, roughness: 0.55, metalness: 0.0 }));
    mesh.userData = { rod: index };
    world.add(mesh);
    const outline = new THREE.Mesh(tubeGeometry(nv, false),
      new THREE.MeshBasicMaterial({ color: 0xd32f2f, side: THREE.BackSide }));
    outline.visible = false;
    world.add(outline);
    rods.push({ mesh, outline, tight: null, nv });
  });
}

function updateRods() {
  const what = $("colour").value;
  const range = colourRange(what);
  updateLegend(what, range);
  view.rods.forEach((rod, index) => {
    let r = rods[index];
    if (!r || r.nv !== rod.positions.length) { buildRods(); r = rods[index]; }
    const f = field(rod, what);
    const stops = f.signed ? DIVERGING : VIRIDIS;
    fillTube(r.mesh.geometry, rod, rod.display_radius, (i) => {
      const v = f.values[i] * f.scale;
      return ramp(stops, f.signed ? 0.5 + 0.5 * v / range.max : v / range.max);
    });
    // An unstable rod: a red outline (a slightly larger tube seen from inside).
    r.outline.visible = !rod.stable;
    if (!rod.stable) fillTube(r.outline.geometry, rod, rod.display_radius * 1.9, null);
    // Segments bent tighter than the allowed radius: a red translucent sleeve.
    if (r.tight) { disposeObject(r.tight); r.tight = null; }
    if (rod.tight_vertices.length) {
      const segs = new Set();
      for (const v of rod.tight_vertices) { if (v > 0) segs.add(v - 1); if (v < rod.positions.length - 1) segs.add(v); }
      const g = tubeGeometry(rod.positions.length, false, [...segs].sort((a, b) => a - b));
      r.tight = new THREE.Mesh(g, new THREE.MeshBasicMaterial({ color: 0xff1744, transparent: true, opacity: 0.45, depthWrite: false }));
      fillTube(g, rod, rod.display_radius * 1.6, null);
      r.tight.userData.tight = true;
      world.add(r.tight);
    }
  });
}

function updateShells() {
  for (const s of shells) disposeObject(s);
  shells.length = 0;
  for (const sh of view.shells) {
    const g = new THREE.BufferGeometry();
    g.setAttribute("position", new THREE.BufferAttribute(new Float32Array(sh.positions.flat()), 3));
    g.setIndex(sh.faces.flat());
    g.computeVertexNormals();
    const m = new THREE.Mesh(g, new THREE.MeshStandardMaterial({ color: 0x8aa4c0, side: THREE.DoubleSide, roughness: 0.7 }));
    m.add(new THREE.LineSegments(new THREE.WireframeGeometry(g), new THREE.LineBasicMaterial({ color: 0x4a6078 })));
    m.userData.shell = shells.length;
    world.add(m);
    shells.push(m);
  }
  $("shells").textContent = view.shells.length
    ? `${view.shells.length} shell strip(s): drag their clamps (the flat boxes at their clamped edges).`
    : "";
}

// ---------- supports: handles, arrows, labels ----------

function handleSize() {
  let r = 0;
  for (const rod of view.rods) r = Math.max(r, rod.display_radius);
  return Math.max(4 * r, 0.02 * sceneSize);
}

function handleMesh(kind, size, sup) {
  const colours = { clamp: 0x37474f, clip: 0x00897b, pin: 0x5e35b1, slider: 0xef6c00, twist_hold: 0x6d4c41, shell_clamp: 0x37474f };
  const mat = new THREE.MeshStandardMaterial({ color: colours[kind] ?? 0x333333, roughness: 0.4, transparent: true, opacity: 0.85 });
  let g;
  if (kind === "clamp") g = new THREE.BoxGeometry(size, size, size);
  // A strip's clamp: a flat box along its edge (z at rest), the handle turning with the clamp.
  else if (kind === "shell_clamp") g = new THREE.BoxGeometry(size * 0.6, size * 0.6, Math.max(size, sup.edge_length * 1.1));
  else if (kind === "clip") g = new THREE.TorusGeometry(size * 0.55, size * 0.18, 8, 20);
  else if (kind === "pin") g = new THREE.SphereGeometry(size * 0.55, 16, 12);
  else if (kind === "slider") g = new THREE.CylinderGeometry(size * 0.3, size * 0.3, size * 2, 12);
  else g = new THREE.TorusGeometry(size * 0.6, size * 0.1, 6, 20);
  const m = new THREE.Mesh(g, mat);
  if (kind === "slider" && sup.axis) {
    const holder = new THREE.Group();
    m.quaternion.setFromUnitVectors(new THREE.Vector3(0, 1, 0), v3(sup.axis).normalize());
    holder.add(m);
    return holder;
  }
  return m;
}

function rotationToQuaternion(r) {
  const angle = Math.hypot(r[0], r[1], r[2]);
  const q = new THREE.Quaternion();
  if (angle > 0) q.setFromAxisAngle(new THREE.Vector3(r[0] / angle, r[1] / angle, r[2] / angle), angle);
  return q;
}

/** Rotation vector (rad) of a unit quaternion. */
function quaternionToRotation(q) {
  let { x, y, z, w } = q;
  if (w < 0) { x = -x; y = -y; z = -z; w = -w; }
  const s = Math.hypot(x, y, z);
  if (s < 1e-15) return [0, 0, 0];
  const angle = 2 * Math.atan2(s, w);
  return [(x / s) * angle, (y / s) * angle, (z / s) * angle];
}

function supportKey() {
  return view.rods.map((r) => r.supports.map((s) => `${s.kind}@${s.vertex}`).join(",")).join(";")
    + "|" + view.shells.map((sh) => sh.clamps.map((c) => c.edge).join(",")).join(";");
}

/** The server's pose of the support (or strip clamp) a handle stands for. */
function handleTarget(u) {
  return u.shell !== undefined ? view.shells[u.shell].clamps[u.support] : view.rods[u.rod].supports[u.support];
}
let handlesKey = "";

function buildHandles() {
  const sel = selected ? { ...selected.userData } : null;
  gizmo.detach();
  selected = null;
  for (const h of handles) disposeObject(h);
  handles = [];
  const size = handleSize();
  view.rods.forEach((rod, ri) => rod.supports.forEach((sup, si) => {
    const h = new THREE.Group();
    h.add(handleMesh(sup.kind, size, sup));
    h.userData = { rod: ri, support: si, kind: sup.kind, handle: true };
    world.add(h);
    handles.push(h);
  }));
  view.shells.forEach((sh, shi) => sh.clamps.forEach((c) => {
    const h = new THREE.Group();
    h.add(handleMesh("shell_clamp", size, c));
    h.userData = { shell: shi, support: c.index, kind: "shell_clamp", handle: true };
    world.add(h);
    handles.push(h);
  }));
  handlesKey = supportKey();
  syncHandles();
  if (sel) {
    const h = handles.find((x) => x.userData.rod === sel.rod && x.userData.shell === sel.shell && x.userData.support === sel.support && x.userData.kind === sel.kind);
    if (h) select(h);
  }
  updateSelectionPanel();
}

/** Puts every handle where the server says its support is (except the one being dragged). */
function syncHandles() {
  for (const h of handles) {
    if (dragging && h === selected) continue;
    const sup = handleTarget(h.userData);
    h.position.copy(v3(sup.position));
    h.quaternion.copy(rotationToQuaternion(sup.rotation));
  }
}

/** Reaction arrows (one ArrowHelper per support, kept and updated in place). */
function updateArrows() {
  const count = view.rods.reduce((n, r) => n + r.supports.length, 0);
  if (arrows.length !== count) {
    for (const a of arrows) { a.removeFromParent(); a.line.material.dispose(); a.cone.material.dispose(); }
    arrows = [];
    for (let i = 0; i < count; i++) {
      const a = new THREE.ArrowHelper(new THREE.Vector3(1, 0, 0), new THREE.Vector3(), 1, 0xc62828);
      world.add(a);
      arrows.push(a);
    }
  }
  labelSpecs = [];
  // Arrow lengths relative to the largest reaction now (the labels give the values).
  let fmax = 0;
  for (const rod of view.rods) for (const s of rod.supports) fmax = Math.max(fmax, Math.hypot(...s.force));
  const forceScale = fmax > 0 ? (0.2 * sceneSize) / fmax : 0;
  const show = $("arrows").checked;
  let i = 0;
  for (const rod of view.rods) {
    for (const s of rod.supports) {
      const a = arrows[i++];
      const f = v3(s.force);
      const n = f.length();
      a.visible = show && n > 0;
      if (!a.visible) continue;
      const len = Math.max(0.04 * sceneSize, n * forceScale);
      const dir = f.multiplyScalar(1 / n);
      a.position.copy(v3(s.position));
      a.setDirection(dir);
      a.setLength(len, 0.25 * len, 0.12 * len);
      labelSpecs.push({ at: v3(s.position).addScaledVector(dir, len), text: fmtForce(n), cls: "label" });
    }
  }
}

// ---------- point loads: arrows and the panel ----------

const LOAD_ARROW = 0xef6c00;
const FOLLOWER_ARROW = 0x00897b; // a follower force: it turns with the cable
let loadArrows = []; // one ArrowHelper per point force, userData { load: [owner, index, k], force (N), follower }
let loadsKey = null;

/** Every point force of the scene: rods' (`owner` "rod") and shell strips' ("shell"), with the
 *  edit that sets it and the id prefix of its panel inputs. */
function pointLoads() {
  const out = [];
  view.rods.forEach((rod, r) => rod.forces.forEach((f, k) => out.push({
    owner: "rod", index: r, k, f, id: `f-${r}-${k}`, field: `rods[${r}].forces[${k}].force`,
    where: `${rod.name}, force ${k} at v ${f.vertex} (${fmtLength(f.at)})`,
  })));
  view.shells.forEach((sh, i) => sh.forces.forEach((f, k) => out.push({
    owner: "shell", index: i, k, f, id: `fs-${i}-${k}`, field: `shells[${i}].forces[${k}].force`,
    where: `${sh.name}, force ${k} at station ${f.station}, column ${f.column}`,
  })));
  return out;
}

/** Arrows of the point forces as they act now, their tips at the loaded vertices; lengths
 *  relative to the largest force now (labels give the values). A follower force (a rod's,
 *  turning with the cable) is drawn where it points in the current equilibrium, in its own
 *  colour. */
function updateLoadArrows() {
  const loads = pointLoads();
  while (loadArrows.length < loads.length) {
    const a = new THREE.ArrowHelper(new THREE.Vector3(1, 0, 0), new THREE.Vector3(), 1, LOAD_ARROW);
    world.add(a);
    loadArrows.push(a);
  }
  const now = (d) => d.f.now ?? d.f.force;
  let fmax = 0;
  for (const d of loads) fmax = Math.max(fmax, Math.hypot(...now(d)));
  const scale = fmax > 0 ? (0.2 * sceneSize) / fmax : 0;
  const show = $("load-arrows").checked;
  loadArrows.forEach((a, i) => {
    const d = loads[i];
    a.visible = false;
    if (!d) return;
    const f = v3(now(d));
    const n = f.length();
    const follower = !!d.f.follower;
    a.userData = { load: [d.owner, d.index, d.k], force: n, follower };
    if (!show || n === 0) return;
    a.visible = true;
    a.setColor(follower ? FOLLOWER_ARROW : LOAD_ARROW);
    const len = Math.max(0.04 * sceneSize, n * scale);
    const dir = f.multiplyScalar(1 / n);
    // The tip at the vertex: the force pushes on the cable there.
    const tail = v3(d.f.position).addScaledVector(dir, -len);
    a.position.copy(tail);
    a.setDirection(dir);
    a.setLength(len, 0.25 * len, 0.12 * len);
    labelSpecs.push({ at: tail, text: follower ? `${fmtForce(n)} follower` : fmtForce(n), cls: "label load" });
  });
}

// ---------- point moments and line loads: drawn (moments are edited in the panel) ----------

const MOMENT_ARROW = 0x6a1b9a;
const LINE_LOAD_ARROW = 0xffa726;
let momentArrows = []; // per dead point moment: [arrow, its second head], userData { moment (N m) }
let lineLoadArrows = []; // pooled ArrowHelpers, userData { lineLoad (N/m) }

function fmtMoment(n) {
  if (n === 0) return "0 N·m";
  return Math.abs(n) >= 1e3 || Math.abs(n) < 1e-3 ? `${n.toExponential(2)} N·m` : `${n.toPrecision(3)} N·m`;
}

/** The point moments of the rods as double-headed arrows along their axes as they act now
 *  (the right-hand rule), tails at the loaded vertices; lengths relative to the largest moment
 *  now. A follower moment, turned with the cable, is drawn in the follower colour. */
function updateMomentArrows() {
  const dead = view.rods.flatMap((rod) => rod.moments);
  while (momentArrows.length < dead.length) {
    const pair = [0, 1].map(() => new THREE.ArrowHelper(new THREE.Vector3(1, 0, 0), new THREE.Vector3(), 1, MOMENT_ARROW));
    for (const a of pair) world.add(a);
    momentArrows.push(pair);
  }
  let mmax = 0;
  for (const m of dead) mmax = Math.max(mmax, Math.hypot(...m.now));
  const scale = mmax > 0 ? (0.2 * sceneSize) / mmax : 0;
  const show = $("load-arrows").checked;
  momentArrows.forEach(([arrow, head], i) => {
    const m = dead[i];
    arrow.visible = head.visible = false;
    if (!m) return;
    const v = v3(m.now);
    const n = v.length();
    arrow.userData = { moment: n, follower: m.follower };
    head.userData = { moment: n, follower: m.follower };
    const colour = m.follower ? FOLLOWER_ARROW : MOMENT_ARROW;
    arrow.setColor(colour);
    head.setColor(colour);
    if (!show || n === 0) return;
    const len = Math.max(0.04 * sceneSize, n * scale);
    const dir = v.multiplyScalar(1 / n);
    const at = v3(m.position);
    arrow.position.copy(at);
    arrow.setDirection(dir);
    arrow.setLength(len, 0.2 * len, 0.1 * len);
    // A second head just behind the first: a moment's double arrow.
    head.position.copy(at).addScaledVector(dir, 0.6 * len);
    head.setDirection(dir);
    head.setLength(0.2 * len, 0.2 * len, 0.1 * len);
    arrow.visible = head.visible = true;
    labelSpecs.push({ at: at.clone().addScaledVector(dir, len), text: m.follower ? `${fmtMoment(n)} follower` : fmtMoment(n), cls: "label load" });
  });
}

/** The rods' line loads as arrows at the loaded vertices (at most 40 per rod, evenly picked),
 *  their tips on the cable; lengths relative to the largest load per length now, the value
 *  (N/m) labelled at the middle one of each rod. */
function updateLineLoadArrows() {
  const items = [];
  let qmax = 0;
  for (const rod of view.rods) {
    const loaded = [];
    rod.line_load.forEach((q, v) => {
      const n = Math.hypot(...q);
      if (n > 0) loaded.push(v);
      qmax = Math.max(qmax, n);
    });
    const stride = Math.max(1, Math.ceil(loaded.length / 40));
    const picked = loaded.filter((_, k) => k % stride === 0);
    picked.forEach((v, k) => items.push({ position: rod.positions[v], q: rod.line_load[v], label: k === Math.floor(picked.length / 2) }));
  }
  while (lineLoadArrows.length < items.length) {
    const a = new THREE.ArrowHelper(new THREE.Vector3(1, 0, 0), new THREE.Vector3(), 1, LINE_LOAD_ARROW);
    world.add(a);
    lineLoadArrows.push(a);
  }
  const scale = qmax > 0 ? (0.08 * sceneSize) / qmax : 0;
  const show = $("load-arrows").checked;
  lineLoadArrows.forEach((a, i) => {
    const it = items[i];
    a.visible = false;
    if (!it || !show) return;
    const f = v3(it.q);
    const n = f.length();
    a.userData = { lineLoad: n };
    const len = Math.max(0.02 * sceneSize, n * scale);
    const dir = f.multiplyScalar(1 / n);
    const tail = v3(it.position).addScaledVector(dir, -len);
    a.position.copy(tail);
    a.setDirection(dir);
    a.setLength(len, 0.3 * len, 0.15 * len);
    a.visible = true;
    if (it.label) labelSpecs.push({ at: tail, text: `${fmtForce(n)}/m`, cls: "label load" });
  });
}

/** The panel's force editors: rebuilt when the list of forces changes, values refreshed on
 *  every update except in the row being typed in. */
function updateLoadsPanel() {
  const loads = pointLoads();
  const key = loads.map((l) => `${l.id}${l.f.follower}`).join(",");
  $("loads-box").hidden = loads.length === 0;
  if (key !== loadsKey) {
    loadsKey = key;
    $("loads").innerHTML = loads.map((l) => {
      // A follower force is given, and edited, as it acts on the cable at rest: it turns
      // with the cable from there.
      const where = l.f.follower ? `${l.where}, follower (as at rest)` : l.where;
      const inputs = ["x", "y", "z"].map((c) =>
        `<input id="${l.id}-${c}" type="number" step="any" aria-label="${l.where} ${c} (N)">`).join("");
      const remove = `<button class="force-remove" data-load="${l.id}" title="remove this force" aria-label="remove ${l.where}">×</button>`;
      return `<div class="load"><span>${where}</span><div class="vec">${inputs}<button class="force-apply" data-load="${l.id}">Apply</button>${remove}</div></div>`;
    }).join("");
    for (const b of document.querySelectorAll("#loads .force-apply")) {
      b.addEventListener("click", () => {
        const l = pointLoads().find((x) => x.id === b.dataset.load);
        if (!l) return;
        const value = readVector(["x", "y", "z"].map((c) => `${l.id}-${c}`), l.field);
        if (value) edit({ op: "force", [l.owner]: l.index, force: l.k, value });
      });
    }
    for (const b of document.querySelectorAll("#loads .force-remove")) {
      b.addEventListener("click", () => {
        const l = pointLoads().find((x) => x.id === b.dataset.load);
        if (l) edit({ op: "remove_force", [l.owner]: l.index, force: l.k });
      });
    }
  }
  const typing = document.activeElement?.tagName === "INPUT" ? document.activeElement.id.replace(/-[xyz]$/, "") : null;
  for (const l of loads) {
    if (typing === l.id) continue;
    ["x", "y", "z"].forEach((c, i) => ($(`${l.id}-${c}`).value = l.f.force[i]));
  }
}

/** The rods' point moments, as the panel edits them (a follower moment as given at rest). */
function pointMoments() {
  const out = [];
  view.rods.forEach((rod, r) => rod.moments.forEach((m, k) => out.push({
    index: r, k, m, id: `m-${r}-${k}`, field: `rods[${r}].moments[${k}].moment`,
    where: `${rod.name}, moment ${k} at v ${m.vertex} (${fmtLength(m.at)})${m.follower ? ", follower (as at rest)" : ""}`,
  })));
  return out;
}

let momentsKey = null;

/** The panel's moment editors, as the force editors: rebuilt when the list changes, values
 *  refreshed on every update except in the row being typed in. */
function updateMomentsPanel() {
  const moments = pointMoments();
  $("moments-box").hidden = moments.length === 0;
  const key = moments.map((m) => m.id).join(",");
  if (key !== momentsKey) {
    momentsKey = key;
    $("moments").innerHTML = moments.map((m) => {
      const inputs = ["x", "y", "z"].map((c) =>
        `<input id="${m.id}-${c}" type="number" step="any" aria-label="${m.where} ${c} (N m)">`).join("");
      const remove = `<button class="moment-remove" data-moment="${m.id}" title="remove this moment" aria-label="remove ${m.where}">×</button>`;
      return `<div class="load"><span>${m.where}</span><div class="vec">${inputs}<button class="moment-apply" data-moment="${m.id}">Apply</button>${remove}</div></div>`;
    }).join("");
    for (const b of document.querySelectorAll("#moments .moment-remove")) {
      b.addEventListener("click", () => {
        const m = pointMoments().find((x) => x.id === b.dataset.moment);
        if (m) edit({ op: "remove_moment", rod: m.index, moment: m.k });
      });
    }
    for (const b of document.querySelectorAll("#moments .moment-apply")) {
      b.addEventListener("click", () => {
        const m = pointMoments().find((x) => x.id === b.dataset.moment);
        if (!m) return;
        const value = readVector(["x", "y", "z"].map((c) => `${m.id}-${c}`), m.field);
        if (value) edit({ op: "moment", rod: m.index, moment: m.k, value });
      });
    }
  }
  const typing = document.activeElement?.tagName === "INPUT" ? document.activeElement.id.replace(/-[xyz]$/, "") : null;
  for (const m of moments) {
    if (typing === m.id) continue;
    ["x", "y", "z"].forEach((c, i) => ($(`${m.id}-${c}`).value = m.m.moment[i]));
  }
}

/** Three numbers from the inputs `ids`, or null after an error naming `field` (an empty box
 *  would read as 0: it is refused, not sent). */
function readVector(ids, field) {
  const raw = ids.map((id) => $(id).value.trim());
  const value = raw.map(Number);
  if (raw.some((x) => x === "") || value.some((x) => !Number.isFinite(x))) {
    showError({ field, message: `three finite numbers are needed, got [${raw.map((x) => x || "empty").join(", ")}]` });
    return null;
  }
  return value;
}

function fmtForce(n) {
  if (n === 0) return "0 N";
  return Math.abs(n) >= 1e3 || Math.abs(n) < 1e-3 ? `${n.toExponential(2)} N` : `${n.toPrecision(3)} N`;
}

function updateLabels() {
  const box = canvas.getBoundingClientRect();
  const wanted = labelSpecs;
  const holder = $("labels");
  while (labels.length < wanted.length) { const d = document.createElement("div"); holder.appendChild(d); labels.push(d); }
  labels.forEach((d, i) => {
    const w = wanted[i];
    if (!w) { d.style.display = "none"; return; }
    const p = w.at.clone().project(camera);
    d.style.display = p.z < 1 ? "block" : "none";
    d.className = w.cls;
    d.textContent = w.text;
    d.style.left = `${((p.x + 1) / 2) * box.width}px`;
    d.style.top = `${((1 - p.y) / 2) * box.height}px`;
  });
}

// ---------- obstacles and contacts ----------

const OBSTACLE_COLOUR = 0x90a4ae;
const OBSTACLE_EDGES = 0x546e7a;
const CONTACT_COLOURS = { sticking: 0x2e7d32, sliding: 0xe65100, frictionless: 0x8e24aa };
const NORMAL_ARROW = 0x1565c0;
const FRICTION_ARROW = 0x5d4037;
const PAIR_COLOUR = 0x00838f; // a cable touching itself or another cable
const obstacleGroup = new THREE.Group(); // one Mesh per obstacle, userData { obstacle, kind, name }
obstacleGroup.name = "obstacles";
scene3.add(obstacleGroup);
const contactGroup = new THREE.Group(); // markers and force arrows
contactGroup.name = "contacts";
scene3.add(contactGroup);
const markerGeometry = new THREE.SphereGeometry(1, 16, 10);
const markerMaterials = Object.fromEntries(Object.entries(CONTACT_COLOURS).map(([k, c]) =>
  [k, new THREE.MeshStandardMaterial({ color: c, roughness: 0.4 })]));
let markers = []; // pooled: Mesh with userData { contactMarker: true, contact }
let normalArrows = []; // pooled ArrowHelpers, userData { contactArrow: "normal", force (N) }
let frictionArrows = [];
let contactScale = 0; // arrow length per newton (m/N) of the last update
let contacts = []; // the last update's contacts, flat: { obstacle, index, name, state, c, surface }
const pairMaterial = new THREE.MeshStandardMaterial({ color: PAIR_COLOUR, roughness: 0.4 });
let pairMarkers = []; // pooled: Mesh with userData { pairMarker: true, pair }
let pairArrows = []; // pooled: [ArrowHelper on side a, on side b]

function quaternionFromTo(from, to) {
  return new THREE.Quaternion().setFromUnitVectors(from, v3(to).normalize());
}

/** The three.js geometry and pose of one obstacle's shape (see state.rs: ShapeGeometry). */
function obstacleMesh(shape) {
  let g;
  let position = new THREE.Vector3();
  let quaternion = new THREE.Quaternion();
  if (shape.kind === "plane") {
    g = new THREE.PlaneGeometry(shape.size, shape.size);
    position = v3(shape.center);
    quaternion = quaternionFromTo(new THREE.Vector3(0, 0, 1), shape.normal);
  } else if (shape.kind === "sphere") {
    g = new THREE.SphereGeometry(shape.radius, 48, 24);
    position = v3(shape.center);
  } else if (shape.kind === "cylinder") {
    // Unbounded: the piece over the scene, open-ended.
    g = new THREE.CylinderGeometry(shape.radius, shape.radius, shape.length, 48, 1, true);
    position = v3(shape.center);
    quaternion = quaternionFromTo(new THREE.Vector3(0, 1, 0), shape.axis);
  } else if (shape.kind === "torus") {
    // three.js's torus lies in its xy plane, around its z axis.
    g = new THREE.TorusGeometry(shape.radius, shape.tube_radius, 24, 96);
    position = v3(shape.center);
    quaternion = quaternionFromTo(new THREE.Vector3(0, 0, 1), shape.axis);
  } else if (shape.kind === "box") {
    g = new THREE.BoxGeometry(...shape.size);
    position = v3(shape.center);
    quaternion = rotationToQuaternion(shape.rotation);
  } else {
    const idx = new Uint32Array(shape.triangles.flat());
    g = new THREE.BufferGeometry();
    g.setAttribute("position", new THREE.BufferAttribute(new Float32Array(shape.vertices.flat()), 3));
    g.setIndex(new THREE.BufferAttribute(idx, 1));
    g = g.toNonIndexed(); // flat shading: one normal per triangle
    g.computeVertexNormals();
  }
  const mesh = new THREE.Mesh(g, new THREE.MeshStandardMaterial({
    color: OBSTACLE_COLOUR, roughness: 0.9, metalness: 0, transparent: true, opacity: 0.3,
    depthWrite: false, side: THREE.DoubleSide,
  }));
  mesh.add(new THREE.LineSegments(new THREE.EdgesGeometry(g, 30),
    new THREE.LineBasicMaterial({ color: OBSTACLE_EDGES, transparent: true, opacity: 0.55 })));
  mesh.position.copy(position);
  mesh.quaternion.copy(quaternion);
  return mesh;
}

/** Draws every obstacle (again after one was moved) and lists them for the move row. */
function buildObstacles() {
  for (const o of [...obstacleGroup.children]) disposeObject(o);
  const pick = $("obstacle-pick");
  const keep = pick.value;
  pick.innerHTML = geometry.obstacles.map((o, i) => `<option value="${i}">${o.name}</option>`).join("");
  if (keep && +keep < geometry.obstacles.length) pick.value = keep;
  $("obstacle-move").hidden = geometry.obstacles.length === 0;
  geometry.obstacles.forEach((ob, i) => {
    const mesh = obstacleMesh(ob.shape);
    mesh.name = `obstacle:${ob.name}`;
    mesh.userData = { obstacle: i, kind: ob.shape.kind, name: ob.name };
    obstacleGroup.add(mesh);
  });
  // A grabbed obstacle's mesh was replaced: the gizmo holds the new one, at its new pose.
  if (grabbed) grabObstacle(obstacleGroup.children.find((m) => m.userData.obstacle === grabbed.index) ?? null);
  const any = geometry.obstacles.length > 0 || geometry.self_contact;
  $("contacts-box").hidden = !any;
  $("pair-legend").hidden = !geometry.self_contact;
  const obstacles = geometry.obstacles.length > 0;
  $("min-gap-row").hidden = !obstacles;
  $("show-obstacles-row").hidden = !obstacles;
  const unbounded = geometry.obstacles.some((o) => o.shape.kind === "plane" || o.shape.kind === "cylinder");
  $("gap-note").textContent = geometry.activation
    ? `Contacts rest within the activation distance ĝ = ${fmtGap(geometry.activation)} of a surface; a negative gap would be a penetration.${unbounded ? " Planes and round bars are unbounded: drawn over the scene." : ""}`
    : "";
}

function fmtGap(g) {
  if (g === null || g === undefined) return "–";
  if (g >= 1e-3) return `${(g * 1e3).toPrecision(3)} mm`;
  if (g >= 1e-6) return `${(g * 1e6).toPrecision(3)} µm`;
  return `${g.toExponential(2)} m`;
}

/** Sticking, sliding, or frictionless (μ = 0: nothing to stick with). */
const contactState = (ob, c) => (ob.friction === 0 ? "frictionless" : c.sticking ? "sticking" : "sliding");

function newArrow(colour, kind) {
  const a = new THREE.ArrowHelper(new THREE.Vector3(1, 0, 0), new THREE.Vector3(), 1, colour);
  // Drawn over the cable and the obstacles: a force at a contact is always visible.
  for (const part of [a.line, a.cone]) { part.material.depthTest = false; part.renderOrder = 5; }
  a.userData = { contactArrow: kind, force: 0 };
  contactGroup.add(a);
  return a;
}

function placeArrow(a, origin, f, show) {
  const n = f.length();
  const len = n * contactScale;
  a.userData.force = n;
  a.visible = show && len > 1e-4 * sceneSize;
  if (!a.visible) return;
  const head = Math.min(0.3 * len, 0.02 * sceneSize);
  a.position.copy(origin);
  a.setDirection(f.clone().multiplyScalar(1 / n));
  a.setLength(len, head, 0.5 * head);
}

/** Markers at the active contacts and their force arrows (pooled, updated in place). */
function updateContacts() {
  contacts = [];
  const radius = new Map(view.rods.map((r) => [r.name, r.contact_radius ?? r.display_radius]));
  // A strip's contacts (`shell`): its mid-surface keeps h/2 from the surface.
  const stripRadius = new Map((view.shells ?? []).map((s) => [s.name, s.contact_radius ?? 0]));
  view.obstacles.forEach((ob, i) => ob.contacts.forEach((c, k) => {
    // The contact point on the surface: the vertex minus the normal × (contact radius + gap).
    const r = c.shell ? stripRadius.get(c.rod) : radius.get(c.rod);
    const surface = v3(c.position).addScaledVector(v3(c.normal), -((r ?? 0) + c.gap));
    contacts.push({ obstacle: i, index: k, name: ob.name, friction: ob.friction, state: contactState(ob, c), c, surface });
  }));
  while (markers.length < contacts.length) {
    const m = new THREE.Mesh(markerGeometry, markerMaterials.sticking);
    m.userData = { contactMarker: true };
    contactGroup.add(m);
    markers.push(m);
    normalArrows.push(newArrow(NORMAL_ARROW, "normal"));
    frictionArrows.push(newArrow(FRICTION_ARROW, "friction"));
  }
  const pairs = view.segment_contacts ?? [];
  let fmax = 0;
  for (const { c } of contacts) fmax = Math.max(fmax, Math.hypot(...c.normal_force), Math.hypot(...c.friction_force));
  for (const p of pairs) fmax = Math.max(fmax, Math.hypot(...p.force_a));
  contactScale = fmax > 0 ? (0.12 * sceneSize) / fmax : 0;
  const show = $("show-contacts").checked;
  contactGroup.visible = show;
  let rmax = 0;
  for (const r of view.rods) rmax = Math.max(rmax, r.display_radius);
  const size = Math.max(0.8 * rmax, 0.004 * sceneSize);
  markers.forEach((m, j) => {
    const hit = contacts[j];
    m.visible = j < contacts.length;
    normalArrows[j].visible = false;
    frictionArrows[j].visible = false;
    if (!hit) { m.userData.contact = null; return; }
    m.userData.contact = { obstacle: hit.obstacle, index: hit.index };
    m.material = markerMaterials[hit.state];
    m.position.copy(hit.surface);
    m.scale.setScalar(size);
    placeArrow(normalArrows[j], hit.surface, v3(hit.c.normal_force), true);
    placeArrow(frictionArrows[j], hit.surface, v3(hit.c.friction_force), true);
    normalArrows[j].userData.contact = m.userData.contact;
    frictionArrows[j].userData.contact = m.userData.contact;
  });
  // Segment pairs (self-contact): a marker where the surfaces touch (between the closest
  // points of the centerlines), the force on each side from there.
  while (pairMarkers.length < pairs.length) {
    const m = new THREE.Mesh(markerGeometry, pairMaterial);
    m.userData = { pairMarker: true };
    contactGroup.add(m);
    pairMarkers.push(m);
    pairArrows.push([newArrow(NORMAL_ARROW, "pair"), newArrow(NORMAL_ARROW, "pair")]);
  }
  pairMarkers.forEach((m, j) => {
    const p = pairs[j];
    m.visible = j < pairs.length;
    pairArrows[j].forEach((a) => { a.visible = false; });
    if (!p) { m.userData.pair = null; return; }
    const at = v3(p.point_a).lerp(v3(p.point_b), 0.5);
    m.userData.pair = j;
    m.position.copy(at);
    m.scale.setScalar(size);
    placeArrow(pairArrows[j][0], at, v3(p.force_a), true);
    placeArrow(pairArrows[j][1], at, v3(p.force_b), true);
    pairArrows[j].forEach((a) => { a.userData.pair = j; });
  });
  // A label at each obstacle's strongest contact.
  if (!show) return;
  view.obstacles.forEach((ob, i) => {
    let best = null;
    for (const h of contacts) if (h.obstacle === i && (!best || Math.hypot(...h.c.normal_force) > Math.hypot(...best.c.normal_force))) best = h;
    if (!best) return;
    const fn = v3(best.c.normal_force);
    labelSpecs.push({ at: best.surface.clone().addScaledVector(fn, contactScale), text: `${ob.name}: ${fmtForce(fn.length())}`, cls: "label contact" });
  });
}

function contactText(h) {
  const c = h.c;
  const fn = Math.hypot(...c.normal_force), ft = Math.hypot(...c.friction_force);
  const friction = h.state === "frictionless" ? "frictionless"
    : `friction ${fmtForce(ft)} (${fn > 0 ? (ft / fn).toPrecision(2) : "–"} of the normal force, μ = ${h.friction}; ${h.state})`;
  return `${h.name} · ${c.rod} vertex ${c.vertex}: normal force ${fmtForce(fn)}, ${friction}, gap ${fmtGap(c.gap)}`;
}

function pairText(p) {
  const side = (rod, edge, vertex) => (vertex !== null && vertex !== undefined ? `${rod} vertex ${vertex}` : `${rod} edge ${edge}`);
  return `${side(p.rod_a, p.edge_a, p.vertex_a)} – ${side(p.rod_b, p.edge_b, null)} (${p.kind.replace("_", "–")}): force ${fmtForce(Math.hypot(...p.force_a))} on each side, gap ${fmtGap(p.gap)}`;
}

/** The obstacles' part of the panel: the min gap, per obstacle its resultant and contacts. */
function updateContactPanel() {
  const any = view.obstacles.length > 0 || geometry?.self_contact;
  document.body.dataset.minGap = view.min_gap ?? "";
  if (!any) return;
  const gap = view.min_gap;
  $("min-gap").textContent = fmtGap(gap);
  $("min-gap").className = gap === null || gap >= 0 ? "ok" : "bad";
  // Contact acts at the vertices: an obstacle thinner than an element can sit between two.
  const through = view.edges_through_obstacles ?? [];
  document.body.dataset.edgesThrough = String(through.length);
  $("through-note").hidden = through.length === 0;
  $("through-note").textContent = through.map((e) => (e.shell
    ? `${e.rod}, face ${e.edge} (vertices ${e.vertices.join(", ")}): its mid-surface runs`
    : `${e.rod}, edge ${e.edge}–${e.edge + 1}: its centerline runs`)
    + (e.depth > 0 ? ` ${fmtLength(e.depth)} deep through ${e.obstacle}` : ` across ${e.obstacle}`)
    + " between the vertices (contact acts at vertices): mesh finer than the obstacle").join("; ");
  const pairs = view.segment_contacts;
  $("pairs-row").hidden = !geometry?.self_contact;
  $("pairs").textContent = pairs === undefined
    ? "not reported"
    : `${pairs.length} touching segment pair${pairs.length === 1 ? "" : "s"}; min gap ${fmtGap(view.min_segment_gap ?? null)}`;
  $("contact-scale").textContent = contactScale > 0
    ? `an arrow of ${fmtLength(0.12 * sceneSize)} is ${fmtForce(0.12 * sceneSize / contactScale)}`
    : "no active contact";
  const open = new Set([...document.querySelectorAll("#obstacle-table details[open]")].map((d) => d.dataset.obstacle));
  $("obstacle-table").innerHTML = view.obstacles.map((ob, i) => {
    const mine = contacts.filter((h) => h.obstacle === i);
    const counts = ["sticking", "sliding", "frictionless"].map((k) => [k, mine.filter((h) => h.state === k).length]).filter(([, n]) => n > 0);
    const kind = geometry?.obstacles[i]?.shape.kind ?? "";
    const f = ob.force;
    const where = (c) => (view.rods.length + (view.shells?.length ?? 0) > 1 ? `${c.rod} v ${c.vertex}` : `v ${c.vertex}`);
    const rows = mine.slice(0, 200).map((h) => `<tr class="contact-row"><td>${where(h.c)}</td><td>${fmtGap(h.c.gap)}</td><td>${fmtForce(Math.hypot(...h.c.normal_force))}</td><td>${h.state === "frictionless" ? "–" : fmtForce(Math.hypot(...h.c.friction_force))}</td><td><span class="swatch" title="${h.state}" style="background:#${CONTACT_COLOURS[h.state].toString(16).padStart(6, "0")}"></span>${{ sticking: "stick", sliding: "slide", frictionless: "" }[h.state]}</td></tr>`).join("");
    return `<div class="obstacle" data-obstacle="${i}"><b>${ob.name}</b> <span class="muted">${kind}, μ = ${ob.friction}</span><br>
      ${mine.length} contact${mine.length === 1 ? "" : "s"}${counts.length ? ` (${counts.map(([k, n]) => `${n} ${k}`).join(", ")})` : ""};
      resultant <b class="resultant">${fmtForce(Math.hypot(...f))}</b> <span class="muted">[${f.map((x) => x.toExponential(2)).join(", ")}] N</span>
      ${mine.length ? `<details data-obstacle="${i}"${open.has(String(i)) ? " open" : ""}><summary>contacts</summary><table><tr><td>at</td><td>gap</td><td>|normal|</td><td>|friction|</td><td></td></tr>${rows}</table>${mine.length > 200 ? `<div class="note">the first 200 of ${mine.length}</div>` : ""}</details>` : ""}</div>`;
  }).join("");
}

// Values on hover: the contact under the pointer.
let hoverEvent = null;
canvas.addEventListener("pointermove", (ev) => {
  if (ev.buttons) { $("tooltip").hidden = true; return; }
  if (!hoverEvent) requestAnimationFrame(() => { hover(hoverEvent); hoverEvent = null; });
  hoverEvent = ev;
});
canvas.addEventListener("pointerleave", () => { $("tooltip").hidden = true; });
function hover(ev) {
  const tip = $("tooltip");
  if (!view || !contactGroup.visible) { tip.hidden = true; return; }
  const hit = pick(ev, [...markers, ...pairMarkers].filter((m) => m.visible))[0];
  const u = hit?.object.userData;
  const c = u?.contact && contacts.find((h) => h.obstacle === u.contact.obstacle && h.index === u.contact.index);
  const p = u?.pairMarker && view.segment_contacts?.[u.pair];
  if (!c && !p) { tip.hidden = true; return; }
  const box = canvas.getBoundingClientRect();
  tip.hidden = false;
  tip.textContent = c ? contactText(c) : pairText(p);
  tip.classList.toggle("left", ev.clientX - box.left > 0.5 * box.width);
  tip.style.left = `${ev.clientX - box.left}px`;
  tip.style.top = `${ev.clientY - box.top}px`;
}

// ---------- the panel ----------

function fmtLength(m) {
  if (m === null || m === undefined) return "∞ (straight)";
  return m < 1 ? `${(m * 1000).toPrecision(3)} mm` : `${m.toPrecision(4)} m`;
}

function updatePanel(reply) {
  const edit = reply?.edit ?? null;
  if (edit) lastEdit = { edit, solveMs: reply.solve_seconds * 1e3, roundTripMs: reply.roundTripMs };
  const converged = view.converged && (!lastEdit || lastEdit.edit.converged);
  $("st-converged").textContent = converged ? "converged" : "NOT converged";
  $("st-converged").className = converged ? "ok" : "bad";
  let res = 0, rel = 0, iters = 0;
  for (const s of view.structures) { res = Math.max(res, s.residual); rel = Math.max(rel, s.relative_residual); iters += s.iterations; }
  $("st-residual").textContent = `${res.toExponential(2)} N (relative ${rel.toExponential(2)})`;
  $("st-iterations").textContent = lastEdit ? `${lastEdit.edit.iterations} (${lastEdit.edit.load_steps} load step${lastEdit.edit.load_steps === 1 ? "" : "s"})` : `${iters}`;
  $("st-time").textContent = lastEdit
    ? `${lastEdit.solveMs.toFixed(2)} ms (round trip ${lastEdit.roundTripMs.toFixed(1)} ms)`
    : `${(reply?.solve_seconds * 1e3 || 0).toFixed(2)} ms`;
  const unstable = view.structures.filter((s) => !s.stable);
  const followed = view.structures.some((s) => s.followed_unstable_mode) || (lastEdit?.edit.followed_unstable_mode ?? false);
  $("st-stable").textContent = unstable.length
    ? `UNSTABLE (${unstable.map((s) => `${s.unstable_modes} negative eigenvalue${s.unstable_modes === 1 ? "" : "s"}`).join(", ")})`
    : followed ? "stable (an unstable equilibrium was followed to this one)" : "stable";
  $("st-stable").className = unstable.length ? "bad" : "ok";
  const reasons = [];
  if (lastEdit && !lastEdit.edit.converged) reasons.push(`the last edit did not converge (${lastEdit.edit.reason ?? "?"}); the last equilibrium is kept`);
  for (const s of view.structures) if (!s.converged && s.reason) reasons.push(s.reason);
  $("st-reason").textContent = reasons.join("; ");
  $("unstable-box").hidden = unstable.length === 0;
  $("unstable-what").textContent = unstable.map((s) => s.rods.join(", ")).join("; ");
  document.body.dataset.stable = unstable.length ? "false" : "true";
  document.body.dataset.converged = converged ? "true" : "false";
  // Gravity and policy (not while the user types).
  if (document.activeElement?.tagName !== "INPUT") ["gx", "gy", "gz"].forEach((id, k) => ($(id).value = view.gravity[k]));
  $("policy").value = view.unstable_policy;
  // Per rod: bend radius and reactions.
  const html = view.rods.map((rod, ri) => {
    const tight = rod.tight_vertices.length;
    const allowed = rod.allowed_bend_radius;
    const radius = `min bend radius <b class="${tight ? "bad" : ""}">${fmtLength(rod.min_bend_radius)}</b>` +
      (allowed ? ` (allowed ${fmtLength(allowed)}${tight ? `: <b class="bad">${tight} vertex${tight === 1 ? "" : "es"} too tight</b>, in red` : ""})` : "");
    const rows = rod.supports.map((s, si) => {
      const sel = selected && selected.userData.rod === ri && selected.userData.support === si ? "selected" : "";
      const along = v3(s.force).dot(tangentAt(rod, s.vertex));
      return `<tr class="${sel}"><td>${si}</td><td>${s.kind.replace("_", " ")}</td><td>v ${s.vertex}</td><td>${fmtForce(Math.hypot(...s.force))}</td><td class="along">${fmtForce(along)}</td><td>${Math.hypot(...s.moment).toExponential(2)} N m</td></tr>`;
    }).join("");
    return `<div class="rod"><b>${rod.name}</b> <span class="muted">${rod.model}</span>${rod.stable ? "" : ' <b class="bad">unstable</b>'}${rod.converged ? "" : ' <b class="bad">not converged</b>'}<br>${radius}
      <table><tr><td>#</td><td>support</td><td>at</td><td>|force|</td><td title="${ALONG_TITLE}">along</td><td>|moment|</td></tr>${rows}</table></div>`;
  }).join("");
  $("rods").innerHTML = html;
  // The length control: one entry per cable, its rest length (not while the user types).
  const pick = $("length-rod");
  const names = view.rods.map((r) => r.name).join("\n");
  if (pick.dataset.names !== names) {
    const keep = pick.value;
    pick.innerHTML = view.rods.map((r, i) => `<option value="${i}">${r.name}</option>`).join("");
    pick.dataset.names = names;
    if (keep && +keep < view.rods.length) pick.value = keep;
  }
  const rod = view.rods[+pick.value || 0];
  if (rod && document.activeElement !== $("length-value")) $("length-value").value = rod.arclengths[rod.arclengths.length - 1];
}

function showError(err) {
  const box = $("message");
  if (!err) { box.hidden = true; box.textContent = ""; return; }
  box.hidden = false;
  box.textContent = `${err.field}: ${err.message}`;
  slender.errors.push(err);
}

function updateSelectionPanel() {
  updatePoseEditor();
  if (!selected) {
    $("selection").textContent = "Click a support handle to select it; drag it with the gizmo.";
    $("delete-support").disabled = true;
    return;
  }
  const { rod, shell, support, kind } = selected.userData;
  if (shell !== undefined) {
    const c = view.shells[shell].clamps[support];
    $("selection").textContent = `selected: ${view.shells[shell].name}, clamp ${support} (${c.edge} edge); clamps are removed in the scene file`;
    $("delete-support").disabled = true;
    return;
  }
  $("selection").textContent = `selected: ${view.rods[rod].name}, support ${support} (${kind.replace("_", " ")})`;
  $("delete-support").disabled = false;
}

// ---------- typed pose of the selected support ----------

const POSE_IDS = ["pose-px", "pose-py", "pose-pz"];
const TURN_IDS = ["pose-rx", "pose-ry", "pose-rz"];
const DEG = 180 / Math.PI;

/** The selected support's pose in the editor: its position (m) and its rotation from rest as a
 *  rotation vector in degrees (what `place` takes, in radians). Pins and sliders have no
 *  orientation, a twist hold no position: those boxes are disabled. Refreshed on every update
 *  except while one of its boxes is being typed in. */
function updatePoseEditor() {
  const target = selected && view ? handleTarget(selected.userData) : null;
  $("pose-box").hidden = !target;
  if (!target) return;
  const kind = selected.userData.kind;
  POSE_IDS.forEach((id) => ($(id).disabled = kind === "twist_hold"));
  TURN_IDS.forEach((id) => ($(id).disabled = kind === "pin" || kind === "slider"));
  // Not during a drag (the boxes would only flicker; the drag's end fills them).
  const active = document.activeElement;
  if (dragging || (active?.tagName === "INPUT" && active.closest("#pose-box"))) return;
  POSE_IDS.forEach((id, i) => ($(id).value = target.position[i]));
  TURN_IDS.forEach((id, i) => ($(id).value = target.rotation[i] * DEG));
}

/** Moves the selected support to the typed pose (one step of undo); the continuation splits a
 *  long move, and one that does not converge leaves the support where it was. */
async function placeSelected() {
  if (!selected) return;
  const { rod, shell, support, kind } = selected.userData;
  const where = shell !== undefined ? `shells[${shell}].clamps[${support}]` : `rods[${rod}].supports[${support}]`;
  const position = kind === "twist_hold"
    ? handleTarget(selected.userData).position
    : readVector(POSE_IDS, `${where}.position`);
  if (!position) return;
  const req = shell !== undefined ? { op: "place", shell, support, position } : { op: "place", rod, support, position };
  if (kind !== "pin" && kind !== "slider") {
    const deg = readVector(TURN_IDS, `${where}.rotation`);
    if (!deg) return;
    req.rotation = deg.map((x) => x / DEG);
  }
  await edit(req);
}

// ---------- applying a reply ----------

function applyView(reply) {
  const first = view === null;
  view = reply.view;
  // The obstacles' shapes come with `state` and with every move of an obstacle; during a
  // gizmo drag the held mesh stays under the mouse and is redrawn from them on release.
  if (reply.geometry) { geometry = reply.geometry; if (!grabbed?.dragging) buildObstacles(); }
  if (first) frameCamera();
  updateRods();
  updateShells();
  if (supportKey() !== handlesKey) buildHandles(); else syncHandles();
  updateArrows();
  updateLoadArrows();
  updateMomentArrows();
  updateLineLoadArrows();
  updateContacts();
  updatePanel(reply);
  updatePoseEditor();
  updateLoadsPanel();
  updateMomentsPanel();
  updateContactPanel();
}

function applyReply(reply) {
  if (!reply.ok) {
    showError(reply.error);
    // The session kept its last equilibrium: put the handles back where it has them.
    if (view) { syncHandles(); render(); }
    return false;
  }
  showError(null);
  slender.lastReply = reply;
  const t0 = performance.now();
  applyView(reply);
  const t1 = performance.now();
  render();
  lastApply = { updateMs: t1 - t0, renderMs: performance.now() - t1 };
  return true;
}
let lastApply = { updateMs: 0, renderMs: 0 };

/** Sends an edit (not a drag) and applies its reply. */
async function edit(req) {
  await idle();
  const reply = await request(req);
  applyReply(reply);
  return reply;
}

// ---------- dragging ----------

function select(h) {
  if (h) grabbed = null;
  selected = h;
  if (!h) { gizmo.detach(); updateSelectionPanel(); requestRender(); return; }
  gizmo.attach(h);
  setGizmoMode(document.querySelector('input[name="gizmo"]:checked').value);
  updateSelectionPanel();
  if (view) updatePanel(null);
  requestRender();
}

/** Puts the gizmo on obstacle mesh `mesh` (null: lets go of any), remembering its pose (the
 *  server's): a drag sends the moves from it ([`onObstacleChange`]). */
function grabObstacle(mesh) {
  if (!mesh) {
    if (grabbed) { grabbed = null; gizmo.detach(); $("selection").textContent = "Click an obstacle to move it with the gizmo."; requestRender(); }
    return;
  }
  if (selected) select(null);
  grabbed = { index: mesh.userData.obstacle, mesh, sent: { position: mesh.position.clone(), quaternion: mesh.quaternion.clone() }, dragging: false };
  gizmo.attach(mesh);
  gizmo.setMode(document.querySelector('input[name="gizmo"]:checked').value);
  $("obstacle-pick").value = String(grabbed.index);
  $("selection").textContent = `selected: obstacle ${mesh.userData.name}: move or turn it with the gizmo; the cables follow as it moves`;
  requestRender();
}

/** A gizmo drag of the grabbed obstacle starts (after its checkpoint). */
function startObstacleDrag() {
  lastObstacleReply = null;
  grabbed.dragging = true;
  grabbed.sent = { position: grabbed.mesh.position.clone(), quaternion: grabbed.mesh.quaternion.clone() };
}

/** The gizmo moved the grabbed obstacle: queue its move (built when it is sent). */
function onObstacleChange() {
  if (!grabbed) return;
  dragging = true;
  pendingMove = { obstacle: true, queued: performance.now() };
  pump();
}

/** The grabbed obstacle's move from the pose the server has to the mesh's — a turn about the
 *  drawn shape's centre there (the gizmo's pivot), then a shift — and the pose it reaches;
 *  null if the mesh is where the server has it. */
function obstacleStep() {
  const g = grabbed;
  if (!g) return null;
  const position = g.mesh.position.clone();
  const quaternion = g.mesh.quaternion.clone();
  const translation = position.clone().sub(g.sent.position).toArray();
  const rotation = quaternionToRotation(quaternion.clone().multiply(g.sent.quaternion.clone().invert()));
  if (translation.every((x) => x === 0) && rotation.every((x) => x === 0)) return null;
  const req = { op: "drag_obstacle", obstacle: g.index, translation, rotation, pivot: g.sent.position.toArray() };
  return { req, target: { position, quaternion } };
}

/** The gizmo let go of the obstacle: once its last move is answered, the meshes are drawn
 *  from the server's shapes (a refused or unconverged piece leaves it where the server kept
 *  it) and the gizmo holds the new one. */
async function endObstacleDrag() {
  dragging = false;
  await idle();
  if (grabbed) grabbed.dragging = false;
  if (geometry) buildObstacles();
  render();
}

function setGizmoMode(mode) {
  if (grabbed) { gizmo.setMode(mode); return; }
  if (!selected) return;
  const kind = selected.userData.kind;
  // Pins and sliders have no orientation; a twist hold has no position.
  if (kind === "pin" || kind === "slider") mode = "translate";
  if (kind === "twist_hold") mode = "rotate";
  gizmo.setMode(mode);
}

/** The gizmo moved the selected handle: queue its pose (the one path of every drag). */
function onHandleChange() {
  if (!selected) return;
  dragging = true;
  const { rod, shell, support } = selected.userData;
  // The same `move` for a rod's support and a strip's clamp (addressed by `shell`).
  const req = shell !== undefined
    ? { op: "move", shell, support, position: selected.position.toArray() }
    : { op: "move", rod, support, position: selected.position.toArray() };
  if (gizmo.getMode() === "rotate") req.rotation = quaternionToRotation(selected.quaternion);
  pendingMove = { req, queued: performance.now() };
  pump();
}

async function pump() {
  if (moveInFlight || !pendingMove) return;
  const { queued } = pendingMove;
  let { req } = pendingMove;
  const obstacle = pendingMove.obstacle === true;
  pendingMove = null;
  moveInFlight = true;
  if (checkpointing) { const c = checkpointing; checkpointing = null; await c; }
  // An obstacle's move is taken from the pose the server has now (earlier pieces answered).
  const step = obstacle ? obstacleStep() : null;
  if (obstacle) req = step?.req;
  if (!req) {
    moveInFlight = false;
    if (pendingMove) pump();
    else if (!dragging) afterDrag();
    for (const w of idleWaiters.splice(0)) if (isIdle()) w(); else idleWaiters.push(w);
    return;
  }
  const sent = performance.now();
  const reply = await request(req);
  const received = performance.now();
  if (obstacle) {
    lastObstacleReply = reply;
    if (reply.ok && reply.edit?.converged && grabbed) grabbed.sent = step.target;
  }
  const ok = applyReply(reply);
  const rendered = performance.now();
  timing.updates.push({ queued, sent, received, rendered, serverMs: (reply.solve_seconds ?? 0) * 1e3,
    transport: reply.transport,
    ...lastApply, ok, converged: reply.edit?.converged ?? false });
  moveInFlight = false;
  if (pendingMove) pump();
  else if (!dragging) afterDrag();
  for (const w of idleWaiters.splice(0)) if (isIdle()) w(); else idleWaiters.push(w);
}

function afterDrag() {
  dragging = false;
  if (!moveInFlight && !pendingMove && view) { syncHandles(); updatePoseEditor(); render(); }
}

const idleWaiters = [];
const isIdle = () => !moveInFlight && !pendingMove;
/** Resolves when no drag request is queued or in flight. */
function idle() {
  return isIdle() ? Promise.resolve() : new Promise((r) => idleWaiters.push(r));
}

// ---------- picking ----------

const raycaster = new THREE.Raycaster();
function pick(ev, objects) {
  const box = canvas.getBoundingClientRect();
  const ndc = new THREE.Vector2(((ev.clientX - box.left) / box.width) * 2 - 1, -((ev.clientY - box.top) / box.height) * 2 + 1);
  raycaster.setFromCamera(ndc, camera);
  return raycaster.intersectObjects(objects, true);
}

/** Rest arc length of the centerline point nearest to `p` on rod `ri`. */
function arcLengthAt(ri, p) {
  const rod = view.rods[ri];
  let best = { d: Infinity, s: 0 };
  for (let j = 0; j + 1 < rod.positions.length; j++) {
    const a = v3(rod.positions[j]), b = v3(rod.positions[j + 1]);
    const ab = b.clone().sub(a);
    const u = Math.min(1, Math.max(0, p.clone().sub(a).dot(ab) / Math.max(ab.lengthSq(), 1e-300)));
    const d = a.clone().addScaledVector(ab, u).distanceTo(p);
    if (d < best.d) best = { d, s: rod.arclengths[j] + u * (rod.arclengths[j + 1] - rod.arclengths[j]) };
  }
  return best.s;
}

/** The grid vertex (station along the length, column across) of strip `si` nearest to `p`. */
function gridVertexAt(si, p) {
  const sh = view.shells[si];
  const columns = sh.width_elements + 1;
  let best = { d: Infinity, v: 0 };
  sh.positions.forEach((x, v) => {
    const d = v3(x).distanceTo(p);
    if (d < best.d) best = { d, v };
  });
  return { station: Math.floor(best.v / columns), column: best.v % columns };
}

let down = null;
canvas.addEventListener("pointerdown", (ev) => { down = { x: ev.clientX, y: ev.clientY }; });
canvas.addEventListener("pointerup", async (ev) => {
  if (!down || Math.hypot(ev.clientX - down.x, ev.clientY - down.y) > 4 || gizmo.dragging) { down = null; return; }
  down = null;
  const tool = document.querySelector('input[name="tool"]:checked').value;
  if (tool === "move-obstacle") {
    if (gizmo.axis) return;
    const hit = pick(ev, obstacleGroup.children).find((h) => h.object.isMesh && h.object.userData.obstacle !== undefined);
    grabObstacle(hit ? hit.object : null);
    return;
  }
  if (tool === "add-clip" || tool === "add-force" || tool === "add-moment") {
    const targets = rods.map((r) => r.mesh).concat(tool === "add-force" ? shells : []);
    // Meshes only: a strip's wireframe child is a line, which the ray "hits" within a metre.
    const hit = pick(ev, targets).find((h) => h.object.isMesh
      && (h.object.userData.shell !== undefined || h.object.userData.rod !== undefined));
    if (!hit) return;
    if (hit.object.userData.shell !== undefined) {
      // A strip's force goes on the grid vertex nearest the click; it starts at zero.
      const si = hit.object.userData.shell;
      const { station, column } = gridVertexAt(si, hit.point);
      const reply = await edit({ op: "add_force", shell: si, station, column });
      if (reply.ok) $(`fs-${si}-${view.shells[si].forces.length - 1}-z`)?.focus();
      return;
    }
    const ri = hit.object.userData.rod;
    const at = arcLengthAt(ri, hit.point);
    if (tool === "add-clip") { await edit({ op: "add_support", rod: ri, kind: "clip", at }); return; }
    if (tool === "add-moment") {
      // A new moment starts at zero too: its row takes the value.
      const reply = await edit({ op: "add_moment", rod: ri, at });
      if (reply.ok) $(`m-${ri}-${view.rods[ri].moments.length - 1}-z`)?.focus();
      return;
    }
    // A new force starts at zero: its row in the panel takes the value.
    const reply = await edit({ op: "add_force", rod: ri, at });
    if (reply.ok) $(`f-${ri}-${view.rods[ri].forces.length - 1}-z`)?.focus();
    return;
  }
  const h = pick(ev, handles)[0];
  if (h) {
    let o = h.object;
    while (o && !o.userData.handle) o = o.parent;
    select(o ?? null);
  } else if (!gizmo.axis) {
    select(null);
  }
});

// ---------- rendering ----------

let renderQueued = false;
function requestRender() {
  if (renderQueued) return;
  renderQueued = true;
  requestAnimationFrame(() => { renderQueued = false; render(); });
}

function resize() {
  const w = canvas.clientWidth, h = canvas.clientHeight;
  if (canvas.width !== Math.floor(w * renderer.getPixelRatio()) || canvas.height !== Math.floor(h * renderer.getPixelRatio())) {
    renderer.setSize(w, h, false);
    camera.aspect = w / Math.max(h, 1);
    camera.updateProjectionMatrix();
  }
}

function render() {
  resize();
  renderer.render(scene3, camera);
  updateLabels();
}
window.addEventListener("resize", () => requestRender());

function frameCamera() {
  const box = new THREE.Box3();
  for (const r of view.rods) for (const p of r.positions) box.expandByPoint(v3(p));
  for (const s of view.shells) for (const p of s.positions) box.expandByPoint(v3(p));
  // The cables at rest and the bounded obstacles.
  if (geometry) for (const p of geometry.extent) box.expandByPoint(v3(p));
  const size = box.getSize(new THREE.Vector3());
  sceneSize = Math.max(size.length(), 1e-3);
  const center = box.getCenter(new THREE.Vector3());
  const g = v3(view.gravity);
  const up = g.lengthSq() > 0 ? g.clone().normalize().negate() : new THREE.Vector3(0, 0, 1);
  camera.up.copy(up);
  // Look from the side, across the thinnest extent of the scene, a little from above.
  const side = new THREE.Vector3(0, 0, 0);
  const axes = [new THREE.Vector3(1, 0, 0), new THREE.Vector3(0, 1, 0), new THREE.Vector3(0, 0, 1)]
    .filter((a) => Math.abs(a.dot(up)) < 0.9);
  axes.sort((a, b) => Math.abs(size.dot(a)) - Math.abs(size.dot(b)));
  side.copy(axes[0] ?? new THREE.Vector3(1, 0, 0));
  const dir = side.multiplyScalar(-1).addScaledVector(up, 0.5).normalize();
  camera.near = sceneSize * 1e-3;
  camera.far = sceneSize * 100;
  camera.position.copy(center).addScaledVector(dir, sceneSize * 1.3);
  camera.updateProjectionMatrix();
  orbit.target.copy(center);
  orbit.update();
  sun.position.copy(center).addScaledVector(up, sceneSize).addScaledVector(dir, sceneSize);
  const grid = new THREE.GridHelper(sceneSize * 2, 20, 0xb0bac5, 0xd8dee5);
  grid.quaternion.setFromUnitVectors(new THREE.Vector3(0, 1, 0), up);
  const low = box.min.clone();
  grid.position.copy(center).addScaledVector(up, low.clone().sub(center).dot(up) - 0.05 * sceneSize);
  // A floor (a plane obstacle facing up, under the scene): the grid lies on it.
  for (const ob of geometry?.obstacles ?? []) {
    const s = ob.shape;
    if (s.kind !== "plane" || v3(s.normal).dot(up) < 0.999) continue;
    const height = v3(s.center).sub(center).dot(up);
    if (height <= low.clone().sub(center).dot(up) + 1e-9 * sceneSize)
      grid.position.copy(center).addScaledVector(up, height - 1e-4 * sceneSize);
  }
  scene3.add(grid);
  gizmo.size = 0.8;
}

// ---------- controls ----------

document.querySelectorAll('input[name="gizmo"]').forEach((el) => el.addEventListener("change", () => setGizmoMode(el.value)));
document.querySelectorAll('input[name="tool"]').forEach((el) => el.addEventListener("change", () => {
  if (el.checked && el.value !== "move-obstacle") grabObstacle(null);
  $("hint").textContent = !el.checked ? "" : el.value === "add-clip" ? "Click a cable to add a clip there."
    : el.value === "move-obstacle" ? "Click an obstacle, then move or turn it with the gizmo: the move is applied on release."
    : el.value === "add-force" ? "Click a cable or a flat cable to add a point force at its nearest vertex; set its value in the panel."
    : el.value === "add-moment" ? "Click a cable to add a point moment at its nearest vertex; set its value in the panel." : "";
}));
$("colour").addEventListener("change", () => { if (view) { updateRods(); render(); } });
$("arrows").addEventListener("change", () => { if (view) { updateArrows(); updateLoadArrows(); updateMomentArrows(); updateLineLoadArrows(); updateContacts(); render(); } });
$("load-arrows").addEventListener("change", () => { if (view) { updateArrows(); updateLoadArrows(); updateMomentArrows(); updateLineLoadArrows(); updateContacts(); render(); } });
$("show-obstacles").addEventListener("change", () => { obstacleGroup.visible = $("show-obstacles").checked; render(); });
$("show-contacts").addEventListener("change", () => { if (view) { updateArrows(); updateContacts(); render(); } });
$("snap").addEventListener("click", () => edit({ op: "follow_stable" }));
$("policy").addEventListener("change", () => edit({ op: "unstable_policy", policy: $("policy").value }));
$("gravity-apply").addEventListener("click", () => {
  const gravity = readVector(["gx", "gy", "gz"], "gravity");
  if (gravity) edit({ op: "gravity", gravity });
});
$("length-rod").addEventListener("change", () => {
  const rod = view?.rods[+$("length-rod").value];
  if (rod) $("length-value").value = rod.arclengths[rod.arclengths.length - 1];
});
function setLength() {
  const raw = $("length-value").value.trim();
  const length = Number(raw);
  if (raw === "" || !Number.isFinite(length)) {
    showError({ field: "length", message: `a finite number of metres is needed, got ${raw || "nothing"}` });
    return;
  }
  edit({ op: "length", rod: +$("length-rod").value, length });
}
$("length-apply").addEventListener("click", setLength);
$("obstacle-apply").addEventListener("click", () => {
  const translation = readVector(["ox", "oy", "oz"], "translation");
  const deg = translation && readVector(["orx", "ory", "orz"], "rotation");
  if (deg) edit({ op: "obstacle", obstacle: +$("obstacle-pick").value, translation, rotation: deg.map((x) => x / DEG) });
});
$("length-value").addEventListener("keydown", (e) => { if (e.key === "Enter") setLength(); });
$("delete-support").addEventListener("click", () => deleteSelected());
$("pose-apply").addEventListener("click", () => placeSelected());
for (const id of POSE_IDS.concat(TURN_IDS)) {
  $(id).addEventListener("keydown", (e) => { if (e.key === "Enter") placeSelected(); });
}
/** Keyboard nudges of the selected support: world axis per key (m per press, ×10 with Shift). */
const NUDGE = { ArrowRight: [1, 0, 0], ArrowLeft: [-1, 0, 0], ArrowUp: [0, 1, 0], ArrowDown: [0, -1, 0], PageUp: [0, 0, 1], PageDown: [0, 0, -1] };
const NUDGE_STEP = 1e-3;
window.addEventListener("keydown", (ev) => {
  if (document.activeElement?.tagName === "INPUT") return;
  if (ev.key === "Delete" && selected) deleteSelected();
  if (NUDGE[ev.key] && selected && selected.userData.kind !== "twist_hold" && !ev.ctrlKey && !ev.metaKey) {
    // One `move_by` per press: one step of undo each, solved warm like any edit.
    ev.preventDefault();
    const translation = NUDGE[ev.key].map((x) => x * NUDGE_STEP * (ev.shiftKey ? 10 : 1));
    const { rod, shell, support } = selected.userData;
    const target = shell !== undefined ? { shell } : { rod };
    edit({ op: "move_by", ...target, support, translation, rotation: [0, 0, 0] });
  }
  const z = ev.key === "z" || ev.key === "Z";
  if ((ev.ctrlKey || ev.metaKey) && z) { ev.preventDefault(); undoRedo(ev.shiftKey ? "redo" : "undo"); }
  if ((ev.ctrlKey || ev.metaKey) && (ev.key === "y" || ev.key === "Y")) { ev.preventDefault(); undoRedo("redo"); }
});
$("undo").addEventListener("click", () => undoRedo("undo"));
$("redo").addEventListener("click", () => undoRedo("redo"));
/** One step back or forward: the server puts back the whole session (equilibrium, supports,
 *  loads) as it was; the handles follow. */
async function undoRedo(op) {
  select(null);
  const reply = await edit({ op });
  if (reply.ok) $("history").textContent = `${reply.history.undo} back, ${reply.history.redo} forward`;
}
async function deleteSelected() {
  if (!selected || selected.userData.shell !== undefined) return;
  const { rod, support } = selected.userData;
  select(null);
  await edit({ op: "remove_support", rod, support });
}

function download(name, text, type) {
  const url = URL.createObjectURL(new Blob([text], { type }));
  const a = document.createElement("a");
  a.href = url;
  a.download = name;
  document.body.appendChild(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(url), 1000);
}
const sceneStem = () => ($("scene-name").textContent.replace(/\.(toml|json)$/i, "") || "scene");
async function save() {
  const reply = await edit({ op: "save" });
  if (reply.ok) download(`${sceneStem()}-edited.toml`, reply.toml, "application/toml");
  return reply.toml;
}
async function exportGltf() {
  const reply = await edit({ op: "gltf" });
  if (reply.ok) download(`${sceneStem()}.gltf`, JSON.stringify(reply.gltf), "model/gltf+json");
  return reply.gltf;
}
$("save").addEventListener("click", save);
$("gltf").addEventListener("click", exportGltf);

// ---------- the test interface (drives the page through the same paths as the mouse) ----------

const nextFrame = () => new Promise((r) => requestAnimationFrame(() => r()));
const slender = {
  errors: [],
  timing,
  state: () => view,
  idle,
  /** Selects support `support` of rod `rod` as a click on its handle does. */
  select(rod, support) {
    const h = handles.find((x) => x.userData.rod === rod && x.userData.support === support);
    if (!h) throw new Error(`no handle for rod ${rod} support ${support}`);
    select(h);
    return h;
  },
  /** Drags a support by `d` (m) in `steps` gizmo moves (one per frame), as TransformControls
   *  does: the handle's position is set to start + d·k/steps and the gizmo's objectChange
   *  handler runs; resolves to the final view once every request has been answered. */
  async dragSupport(rod, support, d, steps = 20) {
    const h = this.select(rod, support);
    gizmo.setMode("translate");
    // What the gizmo's dragging-changed does when a drag starts: one step of undo.
    checkpointing = request({ op: "checkpoint" });
    const start = h.position.clone();
    for (let k = 1; k <= steps; k++) {
      const f = k / steps;
      h.position.set(start.x + d[0] * f, start.y + d[1] * f, start.z + d[2] * f);
      onHandleChange();
      await nextFrame();
    }
    afterDrag();
    await idle();
    return view;
  },
  /** Speed: `n` poses along `d`, each given as soon as the previous update was drawn (a
   *  mouse that always has a new position); per update the time from the pose to the drawn
   *  frame and the interval between drawn updates (ms). */
  async benchmarkDrag(rod, support, d, n) {
    const h = this.select(rod, support);
    gizmo.setMode("translate");
    const start = h.position.clone();
    const first = timing.updates.length;
    const t0 = performance.now();
    for (let k = 1; k <= n; k++) {
      const f = k / n;
      h.position.set(start.x + d[0] * f, start.y + d[1] * f, start.z + d[2] * f);
      onHandleChange();
      await idle();
    }
    const elapsed = performance.now() - t0;
    afterDrag();
    const ups = timing.updates.slice(first);
    const intervals = ups.slice(1).map((u, i) => u.rendered - ups[i].rendered);
    return {
      updates: ups.length, elapsedMs: elapsed,
      latencyMs: ups.map((u) => u.rendered - u.queued),
      intervalMs: intervals,
      serverMs: ups.map((u) => u.serverMs),
      roundTripMs: ups.map((u) => u.received - u.sent),
      updateMs: ups.map((u) => u.updateMs),
      renderMs: ups.map((u) => u.renderMs),
      allConverged: ups.every((u) => u.ok && u.converged),
      transports: [...new Set(ups.map((u) => u.transport))],
    };
  },
  /** Screen point (CSS px, page coordinates) of rest arc length `s` on rod `rod`. */
  screenPoint(rod, s) {
    const r = view.rods[rod];
    let j = 0;
    while (j + 2 < r.arclengths.length && r.arclengths[j + 1] < s) j++;
    const u = (s - r.arclengths[j]) / (r.arclengths[j + 1] - r.arclengths[j]);
    const p = v3(r.positions[j]).lerp(v3(r.positions[j + 1]), u).project(camera);
    const box = canvas.getBoundingClientRect();
    return { x: box.left + ((p.x + 1) / 2) * box.width, y: box.top + ((1 - p.y) / 2) * box.height };
  },
  /** The obstacle the gizmo holds (its index), or null. */
  grabbedObstacle() {
    return grabbed ? grabbed.index : null;
  },
  /** Drags obstacle `index` as the gizmo does: grabbed, its mesh shifted by `d` (m) and
   *  turned by the rotation vector `turn` (rad) about its drawn centre in `steps` gizmo
   *  changes (one per frame, each sent as it comes), then released; resolves to the reply to
   *  the drag's last piece. */
  async dragObstacle(index, d, turn = [0, 0, 0], steps = 5) {
    this.setTool("move-obstacle");
    grabObstacle(obstacleGroup.children.find((m) => m.userData.obstacle === index) ?? null);
    if (!grabbed) throw new Error(`no obstacle ${index}`);
    // What the gizmo's dragging-changed does when a drag starts: one step of undo.
    checkpointing = request({ op: "checkpoint" });
    startObstacleDrag();
    const { mesh } = grabbed;
    const p0 = mesh.position.clone();
    const q0 = mesh.quaternion.clone();
    const angle = Math.hypot(...turn);
    for (let k = 1; k <= steps; k++) {
      const f = k / steps;
      mesh.position.set(p0.x + d[0] * f, p0.y + d[1] * f, p0.z + d[2] * f);
      mesh.quaternion.copy(q0);
      if (angle > 0) mesh.quaternion.premultiply(new THREE.Quaternion().setFromAxisAngle(v3(turn).normalize(), angle * f));
      onObstacleChange();
      await nextFrame();
    }
    await endObstacleDrag();
    return lastObstacleReply;
  },
  setTool(name) {
    const el = document.querySelector(`input[name="tool"][value="${name}"]`);
    el.checked = true;
    el.dispatchEvent(new Event("change"));
  },
  /** Screen point (CSS px, page coordinates) of a point of the scene (m). */
  screenPointOf(x) {
    const p = v3(x).project(camera);
    const box = canvas.getBoundingClientRect();
    return { x: box.left + ((p.x + 1) / 2) * box.width, y: box.top + ((1 - p.y) / 2) * box.height };
  },
  /** Looks at `target` from `position` (m; the README screenshot's framing). */
  setCamera(position, target) {
    camera.position.copy(v3(position));
    orbit.target.copy(v3(target));
    orbit.update();
    render();
  },
  /** The three.js scene (the tests count what is drawn in it). */
  scene: scene3,
  /** Arrow length per newton (m/N) of the contact forces now. */
  contactScale: () => contactScale,
  save,
  exportGltf,
  edit,
  request,
  lastReply: null,
};
window.slender = slender;

// ---------- start ----------

(async () => {
  const reply = await request({ op: "state" });
  slender.lastReply = reply;
  if (!reply.ok) { showError(reply.error); return; }
  applyView(reply);
  render();
  document.body.dataset.ready = "true";
})();
