// The page of `rover drive` in headless Chromium: it loads, its canvas has
// a WebGL context, the keyboard drives the rover forward, the states the
// page received over its WebSocket show the rover moved, and the
// suspension members are drawn on the rover, and the load arrows are at
// the rover's weight share per wheel. Then a drive on soft soil: the page
// receives `ruts` messages with a nonzero depth and draws their tiles.
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
