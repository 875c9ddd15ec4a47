// The page of `rover drive` (live, over the WebSocket at /ws) and of
// `rover view` (a finished run's run.csv). One scene for both: the terrain
// mesh, the rover's body, its suspension members (from the rover's sketch
// in /meta.json, at the state's coordinates y1…ym), the wheels, the
// contact forces as arrows and the path so far; with `rover drive
// --estimate`, the estimated rover as a translucent ghost (the state's
// est_ values). Z is up, as in the
// simulation; the attitude is R = Rz(psi)·Rx(phi)·Ry(theta) (MODEL.md).
import * as THREE from '/three.min.js';

const canvas = document.getElementById('view');
const hud = document.getElementById('hud');
const help = document.getElementById('help');
const legend = document.getElementById('legend');

// What a test (or a curious user at the console) can read.
const page = { hello: null, meta: null, states: 0, first: null, last: null, shown: null, errors: [], send: null, arrowScale: null };
window.roverPage = page;

const meta = await (await fetch('/meta.json')).json();
const terrainGrid = await (await fetch('/terrain.json')).json();
page.meta = meta;
const wheels = meta.wheels;

const renderer = new THREE.WebGLRenderer({ canvas, antialias: true });
renderer.setPixelRatio(window.devicePixelRatio);
const scene = new THREE.Scene();
scene.background = new THREE.Color(0x10141a);
const camera = new THREE.PerspectiveCamera(50, 1, 0.02, 500);
camera.up.set(0, 0, 1);
scene.add(new THREE.HemisphereLight(0xdde8ff, 0x3a2a1a, 1.2));
const sun = new THREE.DirectionalLight(0xffffff, 1.6);
sun.position.set(-3, -2, 6);
scene.add(sun);

function resize() {
  const w = window.innerWidth, h = window.innerHeight;
  renderer.setSize(w, h, false);
  camera.aspect = w / h;
  camera.updateProjectionMatrix();
}
window.addEventListener('resize', resize);
resize();

// ---- terrain ----
function terrainMesh(g, zFallback) {
  const geo = new THREE.BufferGeometry();
  const pos = new Float32Array(g.nx * g.ny * 3);
  const col = new Float32Array(g.nx * g.ny * 3);
  let lo = Infinity, hi = -Infinity;
  for (const z of g.z) if (z !== null) { lo = Math.min(lo, z); hi = Math.max(hi, z); }
  if (!isFinite(lo)) { lo = hi = zFallback; }
  const c = new THREE.Color();
  for (let j = 0; j < g.ny; j++) for (let i = 0; i < g.nx; i++) {
    const k = j * g.nx + i;
    const z = g.z[k] === null ? lo : g.z[k];
    pos.set([g.x0 + i * g.dx, g.y0 + j * g.dy, z], 3 * k);
    const s = hi > lo ? (z - lo) / (hi - lo) : 0.5;
    c.setHSL(0.07, 0.35, 0.28 + 0.35 * s);
    col.set([c.r, c.g, c.b], 3 * k);
  }
  const idx = [];
  for (let j = 0; j + 1 < g.ny; j++) for (let i = 0; i + 1 < g.nx; i++) {
    const a = j * g.nx + i, b = a + 1, d = a + g.nx, e = d + 1;
    idx.push(a, b, e, a, e, d);
  }
  geo.setAttribute('position', new THREE.BufferAttribute(pos, 3));
  geo.setAttribute('color', new THREE.BufferAttribute(col, 3));
  geo.setIndex(idx);
  geo.computeVertexNormals();
  return new THREE.Mesh(geo, new THREE.MeshLambertMaterial({ vertexColors: true }));
}

// ---- ruts: a dark overlay on the terrain where the wheels left a rut,
// darker the deeper (opaque from 3 cm), one small mesh per tile of the
// `ruts` messages (docs/DRIVE.md), replaced when the tile changes ----
let groundGrid = null;
page.ruts = { messages: 0, tiles: 0, deepest: 0 };
// Lambert, as the terrain (the bundle has no other mesh material).
const rutMat = new THREE.MeshLambertMaterial({
  vertexColors: true, transparent: true, depthWrite: false,
  polygonOffset: true, polygonOffsetFactor: -2, polygonOffsetUnits: -2,
});
const rutMeshes = new Map();
// The terrain mesh's height at (x, y): its own triangles (a, b, e) and
// (a, e, d) of the cell, so that the overlay lies on what is drawn.
function groundAt(x, y) {
  const g = groundGrid;
  if (!g) return 0;
  const fx = Math.min(Math.max((x - g.x0) / g.dx, 0), g.nx - 1.000001);
  const fy = Math.min(Math.max((y - g.y0) / g.dy, 0), g.ny - 1.000001);
  const i = Math.floor(fx), j = Math.floor(fy), u = fx - i, v = fy - j;
  const z = k => (g.z[k] === null ? g.lo : g.z[k]);
  const a = j * g.nx + i;
  const za = z(a), zb = z(a + 1), zd = z(a + g.nx), ze = z(a + g.nx + 1);
  return u >= v ? za + u * (zb - za) + v * (ze - zb) : za + v * (zd - za) + u * (ze - zd);
}
function showRuts(m) {
  page.ruts.messages++;
  for (const t of m.tiles) {
    const key = `${t.origin[0]},${t.origin[1]}`;
    const old = rutMeshes.get(key);
    if (old) { scene.remove(old); old.geometry.dispose(); }
    const [nx, ny] = t.nodes;
    const pos = new Float32Array(nx * ny * 3), col = new Float32Array(nx * ny * 4);
    const depth = t.depth.map(k => k * m.scale);
    for (let j = 0; j < ny; j++) for (let i = 0; i < nx; i++) {
      const k = j * nx + i, d = depth[k];
      const x = t.origin[0] + i * m.cell, y = t.origin[1] + j * m.cell;
      pos.set([x, y, groundAt(x, y) + 0.002], 3 * k);
      col.set([0.10, 0.06, 0.03, d > 0 ? Math.min(0.9, 0.35 + 0.55 * d / 0.03) : 0], 4 * k);
      page.ruts.deepest = Math.max(page.ruts.deepest, d);
    }
    const idx = [];
    for (let j = 0; j + 1 < ny; j++) for (let i = 0; i + 1 < nx; i++) {
      const a = j * nx + i, b = a + 1, d = a + nx, e = d + 1;
      if (depth[a] > 0 || depth[b] > 0 || depth[d] > 0 || depth[e] > 0) idx.push(a, b, e, a, e, d);
    }
    if (!idx.length) { rutMeshes.delete(key); continue; }
    const geo = new THREE.BufferGeometry();
    geo.setAttribute('position', new THREE.BufferAttribute(pos, 3));
    geo.setAttribute('color', new THREE.BufferAttribute(col, 4));
    geo.setIndex(idx);
    geo.computeVertexNormals();
    const mesh = new THREE.Mesh(geo, rutMat);
    scene.add(mesh);
    rutMeshes.set(key, mesh);
  }
  page.ruts.tiles = rutMeshes.size;
}

// ---- rover ----
const radius = meta.radius || new Array(wheels).fill(0.1);
const rMax = Math.max(...radius);
const body = new THREE.Group();
const bodyDims = meta.body || { length: 8 * rMax, width: 5 * rMax, height: rMax };
const bodyBox = new THREE.Mesh(
  new THREE.BoxGeometry(bodyDims.length, bodyDims.width, bodyDims.height),
  new THREE.MeshLambertMaterial({ color: 0xd8d2c4 }));
body.add(bodyBox);
const nose = new THREE.Mesh(new THREE.ConeGeometry(bodyDims.height * 0.4, bodyDims.height, 12),
  new THREE.MeshLambertMaterial({ color: 0xc0392b }));
nose.rotation.z = -Math.PI / 2;
nose.position.set(bodyDims.length / 2 + bodyDims.height * 0.5, 0, 0);
body.add(nose);
scene.add(body);

const wheelMeshes = [], links = [], arrows = [], arrowLengths = [];
page.arrowLengths = () => arrowLengths.slice();
const linkMat = new THREE.LineBasicMaterial({ color: 0x9ad0ff });
// The suspension members: one rod per link of the sketch, a small block at
// each joint that is not a wheel centre (pivots, ball joints).
const sketch = meta.sketch || { joints: [], links: [] };
const drawn = new Set();
for (const l of sketch.links) for (const i of l.joints) if (sketch.joints[i].wheel !== null) drawn.add(sketch.joints[i].wheel);
const rodR = 0.08 * rMax;
const rodMat = new THREE.MeshLambertMaterial({ color: 0x9ad0ff });
const rodGeo = new THREE.CylinderGeometry(rodR, rodR, 1, 10);
const rods = sketch.links.map(() => { const m = new THREE.Mesh(rodGeo, rodMat); scene.add(m); return m; });
const jointGeo = new THREE.BoxGeometry(2.4 * rodR, 2.4 * rodR, 2.4 * rodR);
const jointMat = new THREE.MeshLambertMaterial({ color: 0xf0f0f0 });
const jointMeshes = sketch.joints.map(j => {
  if (j.wheel !== null) return null;
  const m = new THREE.Mesh(jointGeo, jointMat); scene.add(m); return m;
});
const jointAt = sketch.joints.map(() => new THREE.Vector3());
page.sketchJoints = () => jointAt.map(p => [p.x, p.y, p.z]);
// A joint's position from G in body axes at the state's coordinates:
// c + Σ_terms Σ_p coeffs[p]·ξ^p, ξ = y_(coord+1) − center.
function jointBody(j, s, out) {
  out.set(j.c[0], j.c[1], j.c[2]);
  for (const t of j.terms) {
    const xi = s[`y${t.coord + 1}`] - t.center;
    let p = 1;
    for (const c of t.coeffs) { out.x += c[0] * p; out.y += c[1] * p; out.z += c[2] * p; p *= xi; }
  }
  return out;
}
for (let j = 0; j < wheels; j++) {
  const r = radius[j];
  const tyre = new THREE.Mesh(new THREE.CylinderGeometry(r, r, 0.5 * r, 24),
    new THREE.MeshLambertMaterial({ color: 0x333333 }));
  const hub = new THREE.Mesh(new THREE.BoxGeometry(1.6 * r, 0.52 * r, 0.25 * r),
    new THREE.MeshLambertMaterial({ color: 0x888888 }));
  const w = new THREE.Group();
  w.add(tyre); w.add(hub);
  scene.add(w);
  wheelMeshes.push(w);
  // A wheel on no member of the sketch (a suspension given as raw
  // polynomials has no linkage to draw): a straight line from the body.
  if (drawn.has(j)) { links.push(null); } else {
    const lg = new THREE.BufferGeometry();
    lg.setAttribute('position', new THREE.BufferAttribute(new Float32Array(6), 3));
    const line = new THREE.Line(lg, linkMat);
    line.frustumCulled = false;
    scene.add(line);
    links.push(line);
  }
  const arrow = new THREE.ArrowHelper(new THREE.Vector3(0, 0, 1), new THREE.Vector3(), 0.1, 0xffd23f);
  scene.add(arrow);
  arrows.push(arrow);
}

// ---- the ghost: the rover as its own estimator sees it (`rover drive
// --estimate`), body and wheels at the state's est_ pose, translucent ----
const GHOST_OPACITY = 0.35;
const ghostMat = new THREE.MeshLambertMaterial({
  color: 0x4fc3ff, transparent: true, opacity: GHOST_OPACITY, depthWrite: false,
});
let ghost = null;
if (meta.estimate) {
  const g = new THREE.Group();
  g.add(new THREE.Mesh(new THREE.BoxGeometry(bodyDims.length, bodyDims.width, bodyDims.height), ghostMat));
  const gNose = new THREE.Mesh(new THREE.ConeGeometry(bodyDims.height * 0.4, bodyDims.height, 12), ghostMat);
  gNose.rotation.z = -Math.PI / 2;
  gNose.position.set(bodyDims.length / 2 + bodyDims.height * 0.5, 0, 0);
  g.add(gNose);
  g.visible = false;
  scene.add(g);
  const gWheels = radius.map(r => {
    const w = new THREE.Mesh(new THREE.CylinderGeometry(r, r, 0.5 * r, 24), ghostMat);
    w.visible = false;
    scene.add(w);
    return w;
  });
  ghost = { body: g, wheels: gWheels };
}
// Where the ghost is drawn (null without --estimate).
page.ghost = () => ghost && {
  visible: ghost.body.visible,
  opacity: ghostMat.opacity,
  position: ghost.body.position.toArray(),
  quaternion: ghost.body.quaternion.toArray(),
  wheels: ghost.wheels.map(w => w.position.toArray()),
};

const PATH_MAX = 50000;
const pathGeo = new THREE.BufferGeometry();
pathGeo.setAttribute('position', new THREE.BufferAttribute(new Float32Array(PATH_MAX * 3), 3));
pathGeo.setDrawRange(0, 0);
const path = new THREE.Line(pathGeo, new THREE.LineBasicMaterial({ color: 0x4cd964 }));
path.frustumCulled = false;
scene.add(path);
let pathCount = 0;
function pathPush(x, y, z) {
  if (pathCount > 0) {
    const a = pathGeo.attributes.position.array, k = 3 * (pathCount - 1);
    if (Math.hypot(a[k] - x, a[k + 1] - y) < 0.01) return;
  }
  if (pathCount >= PATH_MAX) return;
  pathGeo.attributes.position.array.set([x, y, z + 0.01], 3 * pathCount);
  pathCount++;
  pathGeo.setDrawRange(0, pathCount);
  pathGeo.attributes.position.needsUpdate = true;
}
function pathClear() { pathCount = 0; pathGeo.setDrawRange(0, 0); }

// Rest positions of the wheels in body axes; in `rover view` without a
// known rover, from the first row (the body's frame applied backwards).
let rest = meta.rest || null;
const euler = new THREE.Euler(), q = new THREE.Quaternion(), qs = new THREE.Quaternion();
const zAxis = new THREE.Vector3(0, 0, 1), v = new THREE.Vector3(), up = new THREE.Vector3();

function restFrom(s) {
  euler.set(s.phi, s.theta, s.psi, 'ZXY');
  q.setFromEuler(euler).invert();
  const out = [];
  for (let j = 1; j <= wheels; j++) {
    v.set(s[`W${j}X`] - s.X, s[`W${j}Y`] - s.Y, s[`W${j}Z`] - s.Z).applyQuaternion(q);
    out.push([v.x, v.y, v.z]);
  }
  return out;
}

// ---- the load arrows' scale: one for the whole run ----
// An arrow `length` long stands for the reference `load`: live, the
// rover's weight share per wheel (m·g/n, from /meta.json); in a replay,
// the median over the run's rows of the mean wheel load (from run.csv).
// Set once, it does not move with the loads or with scrubbing: a longer
// arrow is a heavier load.
let arrowScale = null;
// A round length near two wheel radii: 1, 2 or 5 times a power of ten.
function roundLength(x) {
  const p = Math.pow(10, Math.floor(Math.log10(x)));
  return [1, 2, 5, 10].map(k => k * p).reduce((a, b) => Math.abs(b - x) < Math.abs(a - x) ? b : a);
}
function setArrowScale(load, from) {
  const length = roundLength(2 * rMax);
  arrowScale = { load, length, metresPerNewton: length / load, from };
  page.arrowScale = arrowScale;
  document.body.dataset.arrowLoad = String(load);
  const len = length >= 1 ? `${+length.toFixed(2)} m` : `${+(100 * length).toFixed(1)} cm`;
  const n = load >= 100 ? load.toFixed(0) : load.toPrecision(3);
  legend.innerHTML = `<span style="color:#ffd23f">▲</span> load arrow: ${len} = ${n} N (${from})`;
}
// The median over rows of the mean wheel load Σ max(0, Fn_j) / n (rows
// with no wheel on the ground left out).
function medianLoad(rowsOfLoads) {
  const means = [];
  for (const fns of rowsOfLoads) {
    let sum = 0;
    for (const f of fns) sum += Math.max(0, f);
    if (sum > 0) means.push(sum / fns.length);
  }
  if (!means.length) return null;
  means.sort((a, b) => a - b);
  const m = means.length >> 1;
  return means.length % 2 ? means[m] : 0.5 * (means[m - 1] + means[m]);
}

// Place everything from one state (an object keyed by the CSV's names).
function show(s) {
  if (!rest) rest = restFrom(s);
  euler.set(s.phi, s.theta, s.psi, 'ZXY');
  q.setFromEuler(euler);
  body.position.set(s.X, s.Y, s.Z);
  body.quaternion.copy(q);
  for (let j = 0; j < wheels; j++) {
    const k = j + 1, c = [s[`W${k}X`], s[`W${k}Y`], s[`W${k}Z`]];
    wheelMeshes[j].position.set(...c);
    qs.setFromAxisAngle(zAxis, s[`delta${k}`] || 0);
    wheelMeshes[j].quaternion.copy(q).multiply(qs);
    if (links[j]) {
      v.set(rest[j][0], rest[j][1], 0).applyQuaternion(q).add(body.position);
      const a = links[j].geometry.attributes.position.array;
      a.set([v.x, v.y, v.z, ...c]);
      links[j].geometry.attributes.position.needsUpdate = true;
    }
    const fn = s[`Fn${k}`];
    if (fn > 0 && arrowScale) {
      arrows[j].visible = true;
      // Along the line from the contact point to the wheel centre (the
      // normal force's line of action on a round wheel), drawn from the top
      // of the wheel so that the tyre does not hide it.
      up.set(c[0] - s[`H${k}X`], c[1] - s[`H${k}Y`], c[2] - s[`H${k}Z`]);
      if (up.lengthSq() < 1e-12) up.set(0, 0, 1);
      up.normalize();
      arrows[j].position.set(c[0] + up.x * radius[j], c[1] + up.y * radius[j], c[2] + up.z * radius[j]);
      arrows[j].setDirection(up);
      const len = Math.max(1e-3, fn * arrowScale.metresPerNewton);
      arrows[j].setLength(len, 0.25 * Math.min(len, rMax), 0.15 * Math.min(len, rMax));
      arrowLengths[j] = len;
    } else {
      arrows[j].visible = false;
    }
  }
  showMembers(s);
  showGhost(s);
  pathPush(s.X, s.Y, groundBelow(s));
}

// The ghost at the estimate's pose; hidden while the state has no
// estimate (the estimator stopped: its values are null).
const qg = new THREE.Quaternion();
function showGhost(s) {
  if (!ghost) return;
  const on = Number.isFinite(s.est_X);
  ghost.body.visible = on;
  for (const w of ghost.wheels) w.visible = on;
  if (!on) return;
  euler.set(s.est_phi, s.est_theta, s.est_psi, 'ZXY');
  qg.setFromEuler(euler);
  ghost.body.position.set(s.est_X, s.est_Y, s.est_Z);
  ghost.body.quaternion.copy(qg);
  ghost.wheels.forEach((w, j) => {
    const k = j + 1;
    w.position.set(s[`est_W${k}X`], s[`est_W${k}Y`], s[`est_W${k}Z`]);
    qs.setFromAxisAngle(zAxis, s[`delta${k}`] || 0);
    w.quaternion.copy(qg).multiply(qs);
  });
}

const yAxis = new THREE.Vector3(0, 1, 0), dir = new THREE.Vector3();
// Joints in world axes (a wheel centre where the state has it), then one
// rod between the two joints of each link.
function showMembers(s) {
  page.shown = s;
  sketch.joints.forEach((j, i) => {
    const p = jointAt[i];
    if (j.wheel !== null) {
      const k = j.wheel + 1;
      p.set(s[`W${k}X`], s[`W${k}Y`], s[`W${k}Z`]);
    } else {
      jointBody(j, s, p).applyQuaternion(q).add(body.position);
      jointMeshes[i].position.copy(p);
      jointMeshes[i].quaternion.copy(q);
    }
  });
  sketch.links.forEach((l, i) => {
    const a = jointAt[l.joints[0]], b = jointAt[l.joints[1]];
    dir.subVectors(b, a);
    const len = dir.length();
    rods[i].visible = len > 1e-9;
    if (!rods[i].visible) return;
    rods[i].position.addVectors(a, b).multiplyScalar(0.5);
    rods[i].quaternion.setFromUnitVectors(yAxis, dir.multiplyScalar(1 / len));
    rods[i].scale.set(1, len, 1);
  });
}


// The ground's height under G, from the lowest wheel at rest.
function groundBelow(s) {
  return s.Z + (rest ? Math.min(...rest.map(p => p[2])) : 0) - rMax;
}

// ---- cameras: follow (behind the rover, along its heading, at a
// distance that frames it with margin, eased) and free (orbit about a
// target: drag to turn, wheel to zoom, right-drag to pan) ----
let follow = true;
const orbit = { target: new THREE.Vector3(), dist: 12 * rMax, az: -Math.PI / 2 - 0.6, el: 0.45 };
// The rover's size: the diagonal of its wheelbase and track, tyres
// included; the follow camera stands back so that it spans about half the
// view's height.
let framed = false;
function roverSize() {
  const xs = rest.map(p => p[0]), ys = rest.map(p => p[1]);
  const span = v => Math.max(...v) - Math.min(...v);
  return Math.hypot(span(xs) + 2 * rMax, span(ys) + 2 * rMax, bodyDims.height + 2 * rMax);
}
function followDistance() {
  return 2 * roverSize() / (2 * Math.tan(camera.fov * Math.PI / 360));
}
let dragging = null;
canvas.addEventListener('pointerdown', e => { dragging = { x: e.clientX, y: e.clientY, b: e.button }; });
window.addEventListener('pointerup', () => { dragging = null; });
window.addEventListener('pointermove', e => {
  if (!dragging) return;
  const dx = e.clientX - dragging.x, dy = e.clientY - dragging.y;
  dragging.x = e.clientX; dragging.y = e.clientY;
  if (follow) { follow = false; }
  if (dragging.b === 2) {
    const right = new THREE.Vector3(Math.sin(orbit.az), -Math.cos(orbit.az), 0);
    orbit.target.addScaledVector(right, -dx * orbit.dist * 0.002);
    orbit.target.z += dy * orbit.dist * 0.002;
  } else {
    orbit.az -= dx * 0.005;
    orbit.el = Math.min(1.5, Math.max(-0.2, orbit.el + dy * 0.005));
  }
});
canvas.addEventListener('contextmenu', e => e.preventDefault());
canvas.addEventListener('wheel', e => {
  orbit.dist = Math.min(200, Math.max(0.2, orbit.dist * Math.exp(e.deltaY * 0.001)));
  e.preventDefault();
}, { passive: false });

// The follow camera eases towards the rover with a time constant of
// EASE_S: bumps and slip-steering wobble do not shake the view.
const EASE_S = 0.35;
let lastPlaced = null;
function placeCamera() {
  const now = performance.now();
  const dt = lastPlaced === null ? Infinity : (now - lastPlaced) / 1000;
  lastPlaced = now;
  if (!framed && rest) {
    orbit.dist = followDistance();
    framed = true;
    orbit.target.copy(body.position);
    orbit.az = (lastShown ? lastShown.psi : 0) + Math.PI;
  }
  if (follow) {
    const a = 1 - Math.exp(-dt / EASE_S);
    const az = (lastShown ? lastShown.psi : 0) + Math.PI;
    // The shorter way round.
    const turn = Math.atan2(Math.sin(az - orbit.az), Math.cos(az - orbit.az));
    orbit.az += a * turn;
    orbit.target.lerp(body.position, a);
  }
  const t = orbit.target;
  camera.position.set(
    t.x + orbit.dist * Math.cos(orbit.el) * Math.cos(orbit.az),
    t.y + orbit.dist * Math.cos(orbit.el) * Math.sin(orbit.az),
    t.z + orbit.dist * Math.sin(orbit.el));
  camera.lookAt(t);
}
// Where the wheel centres are on the screen (normalised device
// coordinates, −1…1 across the view).
page.wheelsOnScreen = () => wheelMeshes.map(w => {
  const p = w.position.clone().project(camera);
  return [p.x, p.y];
});

// ---- HUD ----
const deg = r => (r * 180 / Math.PI).toFixed(1);
function hudHtml(s, extra) {
  const loads = [];
  for (let j = 1; j <= wheels; j++) loads.push(s[`Fn${j}`].toFixed(0));
  let rows = `<tr><td>t</td><td>${s.t.toFixed(2)} s</td></tr>
    <tr><td>speed</td><td>${s.vx.toFixed(3)} m/s (set ${(s.V_set ?? 0).toFixed(3)})</td></tr>
    <tr><td>roll</td><td>${deg(s.phi)}°</td></tr><tr><td>pitch</td><td>${deg(s.theta)}°</td></tr>
    <tr><td>wheel loads</td><td>${loads.join(' ')} N</td></tr>`;
  return `<b>${meta.rover}</b> ${extra.title}<table>${rows}${extra.rows}</table>${extra.tail}`;
}
let lastShown = null;
// The estimate's own 1σ (its error against the truth is what the rover
// cannot know): σ_X, σ_Y in cm, σ_ψ in degrees.
function estimateRow(s) {
  if (!meta.estimate || !Number.isFinite(s.est_sigma_X)) return '';
  const cm = v => (100 * v).toFixed(1);
  return `<tr><td><span style="color:#4fc3ff">■</span> estimate 1σ</td><td>X ${cm(s.est_sigma_X)} cm, Y ${cm(s.est_sigma_Y)} cm, ψ ${(s.est_sigma_psi * 180 / Math.PI).toFixed(2)}°</td></tr>`;
}

// ---- live: the WebSocket ----
function live() {
  const keysHelp = meta.steering === 'ackermann' ? 'steer' : 'slip-steer (Δτ)';
  help.innerHTML = `W/S or ↑/↓ speed · A/D or ←/→ ${keysHelp} · space stop · P pause · R reset · C follow/free camera · gamepad: left stick`;
  if (meta.mass > 0 && meta.gravity > 0) setArrowScale(meta.mass * meta.gravity / wheels, 'weight per wheel, m·g/n');
  const ws = new WebSocket(`ws://${location.host}/ws`);
  const cmd = { speed: 0, turn: 0 };
  let status = 'connecting';
  let lastSent = '';
  function send(obj) {
    if (ws.readyState === WebSocket.OPEN) ws.send(JSON.stringify(obj));
  }
  page.send = send;
  function sendDrive() {
    const turn = meta.steering === 'ackermann'
      ? { steer: cmd.turn * meta.max_steer } : { delta_tau: cmd.turn * meta.max_delta_tau };
    const msg = JSON.stringify({ speed: cmd.speed, ...turn });
    if (msg !== lastSent) { lastSent = msg; if (ws.readyState === WebSocket.OPEN) ws.send(msg); }
  }
  ws.onopen = () => { status = 'connected'; send({ rate: 60 }); };
  ws.onclose = () => { status = 'disconnected'; };
  ws.onmessage = ev => {
    const m = JSON.parse(ev.data);
    if (m.type === 'hello') { page.hello = m; return; }
    if (m.type === 'error') { page.errors.push(m.message); return; }
    if (m.type === 'ruts') { showRuts(m); return; }
    if (m.type !== 'state') return;
    if (page.last && m.t < page.last.t) pathClear();
    page.states++;
    if (!page.first) page.first = m;
    // No mass known: the first loads on the ground, once.
    if (!arrowScale) {
      const l = medianLoad([Array.from({ length: wheels }, (_, j) => m[`Fn${j + 1}`])]);
      if (l) setArrowScale(l, 'first loads');
    }
    page.last = m;
  };
  const step = () => meta.speed_hint / 5;
  const held = new Set();
  window.addEventListener('keydown', e => {
    const k = e.key.toLowerCase();
    if (['arrowup', 'w'].includes(k)) cmd.speed = +(cmd.speed + step()).toFixed(6);
    else if (['arrowdown', 's'].includes(k)) cmd.speed = +(cmd.speed - step()).toFixed(6);
    else if (['arrowleft', 'a', 'arrowright', 'd'].includes(k)) held.add(k);
    else if (k === ' ') cmd.speed = 0;
    else if (k === 'p') send({ pause: !(page.last && page.last.paused) });
    else if (k === 'r') { cmd.speed = 0; cmd.turn = 0; lastSent = ''; send({ reset: true }); pathClear(); }
    else if (k === 'c') follow = !follow;
    else return;
    e.preventDefault();
  });
  window.addEventListener('keyup', e => held.delete(e.key.toLowerCase()));
  let padSpeed = false;
  function input() {
    let turn = 0;
    if (held.has('arrowleft') || held.has('a')) turn += 1;
    if (held.has('arrowright') || held.has('d')) turn -= 1;
    for (const pad of (navigator.getGamepads ? navigator.getGamepads() : [])) {
      if (!pad) continue;
      const dz = x => Math.abs(x) < 0.12 ? 0 : x;
      const fwd = -dz(pad.axes[1] || 0), side = -dz(pad.axes[0] || 0);
      if (fwd !== 0 || padSpeed) { cmd.speed = +(fwd * meta.speed_hint).toFixed(4); padSpeed = fwd !== 0; }
      if (side !== 0) turn = side;
      if (pad.buttons[9] && pad.buttons[9].pressed && !pad._p) send({ pause: !(page.last && page.last.paused) });
      if (pad.buttons[8] && pad.buttons[8].pressed && !pad._r) send({ reset: true });
      pad._p = pad.buttons[9] && pad.buttons[9].pressed;
      pad._r = pad.buttons[8] && pad.buttons[8].pressed;
    }
    cmd.turn = Math.round(turn * 100) / 100;
    sendDrive();
  }
  return () => {
    input();
    const s = page.last;
    if (!s) { hud.textContent = status; return; }
    show(s);
    lastShown = s;
    const warn = s.overruns > 0 ? 'warn' : '';
    hud.innerHTML = hudHtml(s, {
      title: `live · ${meta.method} at ${meta.rate_hz} Hz · ${status}${s.paused ? ' · <b>paused</b>' : ''}`,
      rows: `<tr><td>real-time factor</td><td>${s.rtf.toFixed(3)}</td></tr>
        <tr><td>overruns</td><td class="${warn}">${s.overruns} (${s.dropped_ticks} ticks dropped)</td></tr>
        <tr><td>step</td><td>${(s.step_us ?? 0).toFixed(0)} µs</td></tr>
        <tr><td>command</td><td>${cmd.speed.toFixed(3)} m/s, turn ${cmd.turn}</td></tr>${estimateRow(s)}`,
      tail: (s.error ? `<div class="err">${s.error} — press R to reset</div>` : '') +
        (s.est_error ? `<div class="err">${s.est_error} — press R to restart it</div>` : '') +
        (s.watchdog_tripped ? '<div class="warn">watchdog: command zeroed</div>' : ''),
    });
  };
}

// ---- view: a finished run ----
async function view() {
  help.textContent = 'space play/pause · C follow/free camera · drag to turn, wheel to zoom';
  const text = await (await fetch('/run.csv')).text();
  const lines = text.trim().split('\n');
  const cols = lines[0].split(',');
  const rows = lines.slice(1).map(l => l.split(',').map(Number));
  const at = i => Object.fromEntries(cols.map((c, k) => [c, rows[i][k]]));
  const fnCols = Array.from({ length: wheels }, (_, j) => cols.indexOf(`Fn${j + 1}`));
  const load = medianLoad(rows.map(r => fnCols.map(k => r[k])));
  if (load) setArrowScale(load, 'median wheel load of the run');
  const ti = cols.indexOf('t');
  const t0 = rows[0][ti], t1 = rows[rows.length - 1][ti];
  const player = document.getElementById('player');
  player.style.display = 'flex';
  const playBtn = document.getElementById('play'), scrub = document.getElementById('scrub');
  const clock = document.getElementById('clock'), rateSel = document.getElementById('rate');
  let playing = true, t = t0, lastFrame = performance.now(), shownRow = -1;
  playBtn.onclick = () => { playing = !playing; playBtn.textContent = playing ? 'pause' : 'play'; };
  scrub.oninput = () => { t = t0 + (t1 - t0) * scrub.value / 1000; pathClear(); shownRow = -1; };
  window.addEventListener('keydown', e => {
    if (e.key === ' ') { playBtn.onclick(); e.preventDefault(); }
    if (e.key.toLowerCase() === 'c') follow = !follow;
  });
  page.states = rows.length;
  page.first = at(0);
  return () => {
    const now = performance.now();
    if (playing) t = Math.min(t1, t + (now - lastFrame) / 1000 * Number(rateSel.value));
    lastFrame = now;
    // The last row at or before t.
    let lo = 0, hi = rows.length - 1;
    while (lo < hi) { const mid = (lo + hi + 1) >> 1; if (rows[mid][ti] <= t) lo = mid; else hi = mid - 1; }
    if (lo < shownRow) pathClear();
    for (let i = Math.max(0, shownRow + 1); i < lo; i++) { const r = at(i); pathPush(r.X, r.Y, groundBelow(r)); }
    shownRow = lo;
    const s = at(lo);
    page.last = s;
    show(s);
    lastShown = s;
    scrub.value = Math.round(1000 * (t - t0) / Math.max(1e-9, t1 - t0));
    clock.textContent = `${t.toFixed(2)} / ${t1.toFixed(2)} s`;
    hud.innerHTML = hudHtml(s, { title: `replay ×${rateSel.value}`, rows: '', tail: '' });
  };
}

const frame = meta.mode === 'view' ? await view() : live();
if (terrainGrid) {
  scene.add(terrainMesh(terrainGrid, 0));
  groundGrid = terrainGrid;
} else {
  // No terrain known: a plane at the mean contact height of the first state.
  const s = page.first || {};
  let z = 0, n = 0;
  for (let j = 1; j <= wheels; j++) if (isFinite(s[`H${j}Z`])) { z += s[`H${j}Z`]; n++; }
  const g = { x0: (s.X || 0) - 20, y0: (s.Y || 0) - 20, dx: 40, dy: 40, nx: 2, ny: 2, z: new Array(4).fill(n ? z / n : 0) };
  scene.add(terrainMesh(g, 0));
  groundGrid = g;
}
{
  let lo = Infinity;
  for (const z of groundGrid.z) if (z !== null) lo = Math.min(lo, z);
  groundGrid.lo = isFinite(lo) ? lo : 0;
}
// A finished run's ruts, from its folder's ruts.csv.
if (meta.mode === 'view') {
  const r = await (await fetch('/ruts.json')).json();
  if (r) showRuts(r);
}
scene.add(new THREE.AxesHelper(rMax * 4));

function loop() {
  frame();
  placeCamera();
  renderer.render(scene, camera);
  requestAnimationFrame(loop);
}
loop();
