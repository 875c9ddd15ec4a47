// The page of `rover drive` in headless Chromium: it loads, its canvas has
// a WebGL context, the keyboard drives the rover forward, the states the
// page received over its WebSocket show the rover moved, and the
// suspension members are drawn on the rover, and the load arrows are at
// the rover's weight share per wheel. Then a drive on soft soil: the page
// receives `ruts` messages with a nonzero depth and draws their tiles.
// Then `--estimate`: the page draws the ghost, translucent, at the state's
// est_ pose, its wheels at the est_ wheel centres, and the HUD gives the
// estimate's 1σ.
//
// node drive.mjs <rover binary> <chromium binary>
import { mkdtempSync, writeFileSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { launchBrowser, startRover } from './serve.mjs';

const [rover, browserPath] = process.argv.slice(2);
const fail = (msg) => { console.error(`FAIL: ${msg}`); process.exitCode = 1; };

const { server, port } = await startRover(rover, ['drive', 'swing4', '--port', '0', '--rate', '500']);

const browser = await launchBrowser(browserPath);
try {
  const page = await browser.newPage();
  const errors = [];
  page.on('pageerror', (e) => errors.push(String(e)));
  await page.goto(`http://127.0.0.1:${port}/`);
  const webgl = await page.evaluate(() => {
    const c = document.querySelector('canvas');
    return !!c && !!(c.getContext('webgl2') || c.getContext('webgl'));
  });
  if (!webgl) fail('the canvas has no WebGL context');
  await page.waitForFunction(() => window.roverPage && window.roverPage.states > 5, null, { timeout: 60000 });
  const before = await page.evaluate(() => window.roverPage.last);
  // Drive from the keyboard: five presses of W raise the set-point to the
  // rover's speed hint.
  await page.locator('canvas').click();
  for (let i = 0; i < 5; i++) await page.keyboard.press('w');
  await page.waitForFunction(
    (x0) => window.roverPage.last && window.roverPage.last.X - x0 > 0.05,
    before.X, { timeout: 90000 });
  const after = await page.evaluate(() => window.roverPage.last);
  if (!(after.V_set > 0)) fail(`no speed set-point in the state: V_set = ${after.V_set}`);
  // The suspension members: every joint of the rover's sketch placed in
  // world axes near the rover, the wheel joints on the wheels.
  const members = await page.evaluate(() => ({
    sketch: window.roverPage.meta.sketch, joints: window.roverPage.sketchJoints(), s: window.roverPage.shown,
    meta: window.roverPage.meta,
  }));
  if (!(members.sketch && members.sketch.links.length >= 4)) fail(`no suspension links in the sketch: ${JSON.stringify(members.sketch)}`);
  members.joints.forEach((p, i) => {
    const d = Math.hypot(p[0] - members.s.X, p[1] - members.s.Y, p[2] - members.s.Z);
    if (!(d < 1)) fail(`joint ${i} drawn ${d} m from the rover's centre of mass`);
    const w = members.sketch.joints[i].wheel;
    if (w !== null) {
      const k = w + 1, e = Math.hypot(p[0] - members.s[`W${k}X`], p[1] - members.s[`W${k}Y`], p[2] - members.s[`W${k}Z`]);
      if (!(e < 1e-9)) fail(`joint ${i} is ${e} m off wheel ${k}`);
    }
  });
  // The load arrows' scale: the rover's weight share per wheel, m·g/n.
  const scale = await page.evaluate(() => window.roverPage.arrowScale);
  const share = members.meta.mass * members.meta.gravity / members.meta.wheels;
  if (!(scale && Math.abs(scale.load - share) <= 1e-9 * share)) fail(`arrow scale ${JSON.stringify(scale)}, m·g/n = ${share} N`);
  const hud = await page.locator('#hud').innerText();
  if (!/real-time factor/.test(hud)) fail(`HUD without the real-time factor: ${hud}`);
  if (errors.length) fail(`page errors: ${errors.join('; ')}`);
  console.log(`ok: WebGL canvas; ${members.sketch.links.length} suspension links; the rover moved ${(after.X - before.X).toFixed(3)} m at set-point ${after.V_set} m/s (t ${before.t.toFixed(2)} → ${after.t.toFixed(2)} s)`);
} catch (e) {
  fail(e.message);
} finally {
  await browser.close();
  server.kill();
}

// Soft soil: the wheels leave ruts, and the page is sent and draws them.
const dir = mkdtempSync(join(tmpdir(), 'rover-drive-ruts-'));
const soil = join(dir, 'soil.toml');
writeFileSync(soil, 'duration = 1.0\n[terrain]\nkind = "flat"\nsoil = "dry_sand"\n');
const soft = await startRover(rover, ['drive', 'mer', '--scenario', soil, '--port', '0', '--rate', '500']);
const browser2 = await launchBrowser(browserPath);
try {
  const page = await browser2.newPage();
  const errors = [];
  page.on('pageerror', (e) => errors.push(String(e)));
  await page.goto(`http://127.0.0.1:${soft.port}/`);
  await page.waitForFunction(() => window.roverPage && window.roverPage.states > 5, null, { timeout: 60000 });
  await page.locator('canvas').click();
  for (let i = 0; i < 5; i++) await page.keyboard.press('w');
  await page.waitForFunction(() => window.roverPage.ruts.deepest > 0, null, { timeout: 120000 });
  const ruts = await page.evaluate(() => window.roverPage.ruts);
  if (!(ruts.messages >= 1 && ruts.tiles >= 1)) fail(`ruts received but not drawn: ${JSON.stringify(ruts)}`);
  if (!(ruts.deepest < 0.13)) fail(`a rut deeper than the wheel's radius: ${ruts.deepest} m`);
  if (errors.length) fail(`page errors: ${errors.join('; ')}`);
  console.log(`ok: ${ruts.messages} rut messages, ${ruts.tiles} tiles drawn, deepest ${(1e3 * ruts.deepest).toFixed(2)} mm`);
} catch (e) {
  fail(e.message);
} finally {
  await browser2.close();
  soft.server.kill();
  rmSync(dir, { recursive: true, force: true });
}

// --estimate: the ghost at the estimated pose.
const est = await startRover(rover, ['drive', 'swing4', '--estimate', '--port', '0', '--rate', '500']);
const browser3 = await launchBrowser(browserPath);
try {
  const page = await browser3.newPage();
  const errors = [];
  page.on('pageerror', (e) => errors.push(String(e)));
  await page.goto(`http://127.0.0.1:${est.port}/`);
  await page.waitForFunction(() => window.roverPage && window.roverPage.states > 5, null, { timeout: 60000 });
  await page.locator('canvas').click();
  for (let i = 0; i < 5; i++) await page.keyboard.press('w');
  await page.waitForFunction(
    () => window.roverPage.shown && window.roverPage.shown.t > 2 && window.roverPage.shown.vx > 0.05,
    null, { timeout: 90000 });
  // The ghost as drawn for the state last shown (read in one go).
  const { g, s } = await page.evaluate(() => ({ g: window.roverPage.ghost(), s: window.roverPage.shown }));
  if (!g) fail('no ghost with --estimate');
  else {
    if (!g.visible) fail('the ghost is hidden');
    if (!(g.opacity > 0 && g.opacity < 1)) fail(`the ghost is not translucent: opacity ${g.opacity}`);
    const d = Math.hypot(g.position[0] - s.est_X, g.position[1] - s.est_Y, g.position[2] - s.est_Z);
    if (!(d < 1e-9)) fail(`the ghost is ${d} m from the state's est_ position`);
    // Its attitude: R = Rz(ψ)·Rx(φ)·Ry(θ) of the est_ angles, as a quaternion (x, y, z, w).
    const h = (a) => [Math.cos(a / 2), Math.sin(a / 2)];
    const [cz, sz] = h(s.est_psi), [cx, sx] = h(s.est_phi), [cy, sy] = h(s.est_theta);
    const mul = (a, b) => [
      a[3] * b[0] + a[0] * b[3] + a[1] * b[2] - a[2] * b[1],
      a[3] * b[1] - a[0] * b[2] + a[1] * b[3] + a[2] * b[0],
      a[3] * b[2] + a[0] * b[1] - a[1] * b[0] + a[2] * b[3],
      a[3] * b[3] - a[0] * b[0] - a[1] * b[1] - a[2] * b[2],
    ];
    const want = mul(mul([0, 0, sz, cz], [sx, 0, 0, cx]), [0, sy, 0, cy]);
    const dot = Math.abs(want.reduce((acc, v, i) => acc + v * g.quaternion[i], 0));
    if (!(dot > 1 - 1e-9)) fail(`the ghost's attitude is not the est_ one: ${g.quaternion} against ${want}`);
    g.wheels.forEach((p, j) => {
      const k = j + 1, e = Math.hypot(p[0] - s[`est_W${k}X`], p[1] - s[`est_W${k}Y`], p[2] - s[`est_W${k}Z`]);
      if (!(e < 1e-9)) fail(`ghost wheel ${k} is ${e} m off est_W${k}`);
    });
    // Beside the true rover: the estimate follows it within centimetres.
    const off = Math.hypot(s.est_X - s.X, s.est_Y - s.Y);
    if (!(off < 0.02)) fail(`the ghost is ${off} m from the rover`);
    const hud = await page.locator('#hud').innerText();
    if (!/estimate 1σ/.test(hud)) fail(`HUD without the estimate's 1σ: ${hud}`);
    console.log(`ok: the ghost at the estimate, ${(100 * off).toFixed(2)} cm from the rover at t = ${s.t.toFixed(2)} s`);
  }
  if (errors.length) fail(`page errors: ${errors.join('; ')}`);
} catch (e) {
  fail(e.message);
} finally {
  await browser3.close();
  est.server.kill();
}
