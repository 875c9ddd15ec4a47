// The page of `rover view` in headless Chromium, on a short run over rough
// ground: the load arrows' scale is the run's median wheel load read from
// its run.csv (and near the rover's weight share per wheel), it stays put
// when the run is scrubbed, and each arrow is its load at that scale; the
// ground is the run's terrain (from the output folder's terrain.json,
// without `--scenario`); the follow camera frames the rover; the legend,
// help and player bar do not overlap at common window sizes.
//
// node view.mjs <rover binary> <chromium binary>
import { spawnSync } from 'node:child_process';
import { mkdtempSync, readFileSync, writeFileSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { launchBrowser, startRover } from './serve.mjs';

const [rover, browserPath] = process.argv.slice(2);
const fail = (msg) => { console.error(`FAIL: ${msg}`); process.exitCode = 1; };

const dir = mkdtempSync(join(tmpdir(), 'rover-view-'));
const scenario = join(dir, 'rough.toml');
writeFileSync(scenario, `rover = "swing4"
duration = 4.0
output_rate = 50.0
[terrain]
kind = "random"
z_r = 0.2
seed = 3
node_amplitude = 0.25
patch_radius = 0.6
patch_blend = 0.5
[control.speed]
speed = 0.1
[integrator.rk4]
step = 1e-3
`);
const out = join(dir, 'out');
const sim = spawnSync(rover, ['simulate', '--scenario', scenario, '--out', out, '--quiet', '--no-plots'], { encoding: 'utf8' });
if (sim.status !== 0) throw new Error(`rover simulate failed (${sim.status}): ${sim.stderr}`);

// The CSV's loads, read here: the median over rows of the mean wheel load.
const lines = readFileSync(join(out, 'run.csv'), 'utf8').trim().split('\n');
const cols = lines[0].split(',');
const fnCols = cols.map((c, k) => [c, k]).filter(([c]) => /^Fn\d+$/.test(c)).map(([, k]) => k);
const means = lines.slice(1).map((l) => {
  const v = l.split(',').map(Number);
  return fnCols.reduce((a, k) => a + Math.max(0, v[k]), 0) / fnCols.length;
}).filter((m) => m > 0).sort((a, b) => a - b);
const h = means.length >> 1;
const csvLoad = means.length % 2 ? means[h] : 0.5 * (means[h - 1] + means[h]);

// No `--scenario`: the ground comes from the output folder.
const { server, port } = await startRover(rover, ['view', out, '--port', '0']);

const browser = await launchBrowser(browserPath);
try {
  const page = await browser.newPage({ viewport: { width: 1280, height: 720 } });
  const errors = [];
  page.on('pageerror', (e) => errors.push(String(e)));
  await page.goto(`http://127.0.0.1:${port}/`);
  await page.waitForFunction(() => window.roverPage && window.roverPage.arrowScale && window.roverPage.shown, null, { timeout: 60000 });

  // (a) The arrows' scale is the CSV's, and honest: near m·g/n.
  const scale = await page.evaluate(() => window.roverPage.arrowScale);
  const meta = await page.evaluate(() => window.roverPage.meta);
  const weightShare = meta.mass * meta.gravity / meta.wheels;
  if (!(Math.abs(scale.load - csvLoad) <= 0.01 * csvLoad)) fail(`arrow scale ${scale.load} N, the CSV's median wheel load is ${csvLoad} N`);
  if (!(Math.abs(scale.load - weightShare) <= 0.2 * weightShare)) fail(`arrow scale ${scale.load} N, far from the weight share per wheel m·g/n = ${weightShare} N`);
  const legend = await page.locator('#legend').innerText();
  if (!legend.includes(`${scale.load.toPrecision(3)} N`)) fail(`the legend does not give the scale: ${legend}`);
  if (Number(await page.evaluate(() => document.body.dataset.arrowLoad)) !== scale.load) fail('the data attribute is not the scale');
  // Scrubbing back and forth leaves the scale as it was, and each arrow is
  // its wheel's load at that scale.
  for (const at of [900, 50, 500]) {
    await page.evaluate((v) => { const s = document.getElementById('scrub'); s.value = v; s.dispatchEvent(new Event('input')); }, at);
    await page.waitForTimeout(200);
    const now = await page.evaluate(() => ({ scale: window.roverPage.arrowScale, s: window.roverPage.shown, len: window.roverPage.arrowLengths() }));
    if (now.scale.load !== scale.load) fail(`the scale moved from ${scale.load} to ${now.scale.load} N after scrubbing to ${at}`);
    now.len.forEach((len, j) => {
      const want = now.s[`Fn${j + 1}`] * scale.metresPerNewton;
      if (now.s[`Fn${j + 1}`] > 0 && !(Math.abs(len - want) <= 1e-6 + 1e-3 * want)) fail(`arrow ${j + 1} is ${len} m, its load ${now.s[`Fn${j + 1}`]} N makes ${want} m`);
    });
  }

  // (b) The ground is the run's rough terrain, not a plane.
  const grid = await page.evaluate(async () => (await fetch('/terrain.json')).json());
  if (!grid) fail('no terrain served without --scenario');
  else {
    const z = grid.z.filter((v) => v !== null);
    const relief = Math.max(...z) - Math.min(...z);
    if (!(relief > 0.05)) fail(`the served terrain is flat: relief ${relief} m`);
  }

  // The follow camera frames the rover with margin: every wheel within
  // the middle 80 % of the view.
  const onScreen = await page.evaluate(() => window.roverPage.wheelsOnScreen());
  const far = Math.max(...onScreen.flat().map(Math.abs));
  if (!(far < 0.8)) fail(`a wheel is at ${far} of the half view from its centre: ${JSON.stringify(onScreen)}`);

  // (c) Legend, help and player bar do not overlap one another (or the
  // HUD) at common window sizes.
  for (const [width, height] of [[1280, 720], [1920, 1080], [1024, 600]]) {
    await page.setViewportSize({ width, height });
    await page.waitForTimeout(100);
    const boxes = {};
    for (const id of ['hud', 'legend', 'help', 'player']) boxes[id] = await page.locator(`#${id}`).boundingBox();
    for (const [id, b] of Object.entries(boxes)) if (!b) fail(`#${id} is not shown at ${width}×${height}`);
    const ids = Object.keys(boxes);
    for (let i = 0; i < ids.length; i++) for (let j = i + 1; j < ids.length; j++) {
      const a = boxes[ids[i]], b = boxes[ids[j]];
      if (!a || !b) continue;
      const overlap = a.x < b.x + b.width && b.x < a.x + a.width && a.y < b.y + b.height && b.y < a.y + a.height;
      if (overlap) fail(`#${ids[i]} and #${ids[j]} overlap at ${width}×${height}: ${JSON.stringify(a)} ${JSON.stringify(b)}`);
    }
  }
  if (errors.length) fail(`page errors: ${errors.join('; ')}`);
  if (!process.exitCode) {
    console.log(`ok: arrow scale ${scale.load.toFixed(2)} N (CSV median ${csvLoad.toFixed(2)} N, m·g/n ${weightShare.toFixed(2)} N), "${legend}"; terrain ${grid.nx}×${grid.ny} from the output folder; wheels within ${far.toFixed(2)} of the half view; no overlap at 1280×720, 1920×1080, 1024×600`);
  }
} catch (e) {
  fail(e.message);
} finally {
  await browser.close();
  server.kill();
  rmSync(dir, { recursive: true, force: true });
}
