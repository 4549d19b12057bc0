// End-to-end tests of the robot simulation page in headless Chromium: the
// demo preset runs to the goal with metrics shown, the goal moves mid-run,
// movers are placed by dragging and removed, errors land in the message
// bar without killing the page, the page's trace hash equals the native
// CLI's for the same scenario, and the frame time on a crowded scene
// (20 movers, DWA with 20 × 40 samples) is measured and printed.

import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { REPO, startSession, screenshot, errorText, openRobotPage } from './harness.mjs';

const DEMO = 'dwa-demo.json';
const CROWD = 'dwa-crowd.json';
const CLI = path.join(REPO, 'target/release/planlab');

let session;
before(async () => {
  session = await startSession();
});
after(async () => {
  await session?.close();
});

/** Opens the robot page on a preset and waits until its episode is built. */
async function openRobot(scenario = DEMO) {
  return openRobotPage(session, `robot.html?scenario=${scenario}`);
}

const hooks = (page, fn, ...args) => page.evaluate(([f, a]) => window.planlabRobot[f](...a), [fn, args]);
const bodyData = (page, key) => page.evaluate((k) => document.body.dataset[k], key);

async function setSpeed(page, x) {
  await page.selectOption('#speed', String(x));
}

async function waitOutcome(page, timeout = 120_000) {
  await page.waitForFunction(() => document.body.dataset.outcome && document.body.dataset.outcome !== 'running', null, {
    timeout,
  });
  return bodyData(page, 'outcome');
}

async function waitTime(page, t) {
  await page.waitForFunction((tt) => Number(document.body.dataset.time) >= tt, t, { timeout: 60_000 });
}

async function metric(page, name) {
  const v = await page.getAttribute(`#metric-${name}`, 'data-value');
  return v === null ? null : Number(v);
}

/** Client coordinates of a world point (m). */
const screenOf = (page, x, y) => hooks(page, 'toScreen', x, y);

test('demo preset: play runs DWA to the goal, draws the fan and shows the metrics', async () => {
  const { page, problems } = await openRobot();
  assert.equal(await page.inputValue('#preset'), DEMO);
  // Pages link to each other.
  assert.equal(await page.getAttribute('#nav-grid', 'href'), './index.html');
  const scenario = JSON.parse(fs.readFileSync(path.join(REPO, 'assets/scenarios', DEMO), 'utf8'));
  assert.equal(await page.inputValue('#planner'), scenario.local_planner.name);
  // The parameter panel is generated from the registry's fields.
  const fields = await page.$$eval('#params .param', (els) => els.map((e) => e.dataset.field));
  assert.ok(fields.length > 0, 'parameter controls generated');
  await setSpeed(page, 8);
  await page.click('#play');
  await waitTime(page, 1.0);
  // Mid-run: the fan of rollouts is there, with a chosen one.
  assert.ok((await hooks(page, 'rollouts')) > 10, 'rollouts drawn');
  await screenshot(page, 'robot-01-demo-running.png');
  assert.equal(await waitOutcome(page), 'reached');
  assert.equal(await page.getAttribute('#metric-outcome', 'data-outcome'), 'reached');
  const time = await metric(page, 'time');
  const length = await metric(page, 'length');
  const clearance = await metric(page, 'clearance');
  const straight = Math.hypot(11.05 - 1.05, 8.05 - 1.05);
  assert.ok(time > 0, `time ${time}`);
  assert.ok(length >= straight - 0.25, `path length ${length} vs straight line ${straight}`);
  assert.ok(clearance > 0, `min clearance ${clearance}`);
  assert.ok((await metric(page, 'turn')) >= 0);
  assert.ok((await metric(page, 'drops')) >= 0);
  // The robot ended within the goal tolerance, per the page's own state.
  const [x, y] = await hooks(page, 'state');
  assert.ok(Math.hypot(x - 11.05, y - 8.05) <= 0.2 + 1e-9, `final position ${x}, ${y}`);
  // The plots have the whole episode.
  const plotted = await page.$$eval('#plots canvas', (cs) => cs.length);
  assert.ok(plotted >= 3, 'three uPlot charts');
  await screenshot(page, 'robot-02-demo-reached.png');
  assert.deepEqual(problems, []);
  await page.close();
});

test('the goal moves while the robot runs and the robot goes there instead', async () => {
  const { page, problems } = await openRobot();
  await setSpeed(page, 4);
  await page.click('#play');
  await waitTime(page, 2.0);
  await page.click('#tool-goal');
  const newGoal = [10.6, 1.2];
  const p = await screenOf(page, ...newGoal);
  await page.mouse.click(p.x, p.y);
  const [gx, gy] = (await bodyData(page, 'goal')).split(',').map(Number);
  assert.ok(Math.hypot(gx - newGoal[0], gy - newGoal[1]) < 0.05, `goal set to ${gx}, ${gy}`);
  assert.equal(await errorText(page), null);
  assert.equal(await bodyData(page, 'playing'), 'true', 'still running after the goal moved');
  assert.equal(await waitOutcome(page), 'reached');
  const [x, y] = await hooks(page, 'state');
  assert.ok(Math.hypot(x - gx, y - gy) <= 0.2 + 1e-9, `ended at ${x}, ${y}, goal ${gx}, ${gy}`);
  // A goal inside a wall is refused with the core's message; the old one stays.
  await page.click('#reset');
  const wall = await screenOf(page, 4.0, 3.0);
  await page.mouse.click(wall.x, wall.y);
  assert.match((await errorText(page)) ?? '', /wall|blocked/i);
  await screenshot(page, 'robot-03-goal-moved.png');
  assert.deepEqual(problems, []);
  await page.close();
});

test('a mover is placed by dragging (press = position, drag = velocity) and removed', async () => {
  const { page, problems } = await openRobot();
  const before = (await hooks(page, 'movers')).length / 6;
  await page.click('#tool-mover');
  await page.selectOption('#motion-model', 'back-and-forth');
  await page.fill('#mover-radius', '0.35');
  const from = [2.5, 4.5];
  const vel = [0.6, -0.3];
  const a = await screenOf(page, ...from);
  const b = await screenOf(page, from[0] + vel[0], from[1] + vel[1]);
  await page.mouse.move(a.x, a.y);
  await page.mouse.down();
  await page.mouse.move(b.x, b.y, { steps: 12 });
  await screenshot(page, 'robot-04-mover-drag.png');
  await page.mouse.up();
  const movers = await hooks(page, 'movers');
  assert.equal(movers.length / 6, before + 1, 'one more mover');
  const m = movers.slice(-6);
  const [, radius, mx, my, vx, vy] = m;
  const k = Number(await page.getAttribute('#sim-canvas', 'data-scale'));
  const tol = 2 / k; // two pixels, in metres
  assert.equal(radius, 0.35);
  assert.ok(Math.hypot(mx - from[0], my - from[1]) < tol, `placed at ${mx}, ${my}`);
  assert.ok(Math.hypot(vx - vel[0], vy - vel[1]) < 2 * tol, `velocity ${vx}, ${vy}`);
  assert.equal(await page.$$eval('#mover-list li', (l) => l.length), before + 1);
  // It moves along its drag once the episode runs.
  await page.click('#step');
  await page.click('#step');
  const moved = (await hooks(page, 'movers')).slice(-6);
  assert.ok(moved[2] > mx && moved[3] < my, `mover moved along its velocity: ${moved[2]}, ${moved[3]}`);
  // Reset puts it back where it was dropped, at t = 0.
  await page.click('#reset');
  const again = (await hooks(page, 'movers')).slice(-6);
  assert.ok(Math.hypot(again[2] - from[0], again[3] - from[1]) < tol, 'placed mover survives reset');
  // Remove it with the remove tool.
  await page.click('#tool-remove');
  const c = await screenOf(page, again[2], again[3]);
  await page.mouse.click(c.x, c.y);
  assert.equal((await hooks(page, 'movers')).length / 6, before, 'mover removed');
  assert.equal(await errorText(page), null);
  assert.deepEqual(problems, []);
  await page.close();
});

test('sliders re-tune the running planner; the planner select swaps it', async () => {
  const { page, problems } = await openRobot();
  await setSpeed(page, 2);
  await page.click('#play');
  await waitTime(page, 1.0);
  // Drag a slider with the keyboard (real input events), and type a value.
  const slider = page.locator('#params .param[data-field="gamma"] input[type="range"]');
  await slider.focus();
  for (let i = 0; i < 10; i++) await page.keyboard.press('ArrowRight');
  await page.fill('#params .param[data-field="alpha"] input[type="number"]', '0.08');
  await page.waitForFunction(() => window.planlabRobot.plannerChoice().config.alpha === 0.08);
  const choice = await hooks(page, 'plannerChoice');
  assert.equal(choice.name, 'dwa');
  assert.ok(choice.config.gamma > 0.1, `gamma re-tuned: ${choice.config.gamma}`);
  assert.equal(await page.getAttribute('#params .param[data-field="alpha"]', 'data-changed'), 'true');
  assert.equal(await bodyData(page, 'playing'), 'true', 'still running');
  assert.equal(await errorText(page), null);
  // Paper defaults puts every field back, still live.
  await page.click('#params-default');
  await page.waitForFunction(() => window.planlabRobot.plannerChoice().config.alpha === 0.05);
  // Another planner: its own fields, same running episode.
  const names = await page.$$eval('#planner option', (os) => os.map((o) => o.value));
  const other = names.find((n) => n !== 'dwa');
  assert.ok(other, `another planner to pick among ${names}`);
  const t = Number(await bodyData(page, 'time'));
  await page.selectOption('#planner', other);
  assert.equal((await hooks(page, 'plannerChoice')).name, other);
  assert.equal(await errorText(page), null);
  assert.ok(Number(await bodyData(page, 'time')) >= t, 'the episode went on');
  const fields = await page.$$eval('#params .param', (els) => els.map((e) => e.dataset.field));
  assert.deepEqual(fields, await hooks(page, 'plannerFields', other), `the panel shows ${other}'s fields`);
  await screenshot(page, 'robot-07-retuned.png');
  assert.deepEqual(problems, []);
  await page.close();
});

test('bad input lands in the message bar and the page keeps working', async () => {
  const { page, problems } = await openRobot();
  // A parameter the core refuses (negative) shows its message; the old
  // planner keeps driving.
  const box = page.locator('#params .param input[type="number"]').first();
  const field = await page.locator('#params .param').first().getAttribute('data-field');
  await box.fill('-5');
  await page.waitForFunction(() => !document.getElementById('error').hidden, null, { timeout: 5000 });
  const msg = await errorText(page);
  assert.ok(msg && msg.length > 0, 'error shown');
  console.log(`negative ${field}: ${msg}`);
  // A scenario that is not JSON, and one with NaN-like limits.
  await page.setInputFiles('#file-input', { name: 'broken.json', mimeType: 'application/json', buffer: Buffer.from('{"version": 1, "map": ') });
  await page.waitForFunction(() => /broken\.json/.test(document.getElementById('error').textContent));
  const scenario = JSON.parse(fs.readFileSync(path.join(REPO, 'assets/scenarios', DEMO), 'utf8'));
  scenario.robot.limits.v_max = -1;
  await page.setInputFiles('#file-input', { name: 'negative.json', mimeType: 'application/json', buffer: Buffer.from(JSON.stringify(scenario)) });
  await page.waitForFunction(() => /negative\.json.*v_max/.test(document.getElementById('error').textContent));
  // A scenario whose map is a file: refused alone (naming the file), loaded
  // when the map is opened with it.
  const rows = ['..........', '..........', '..........', '..........'];
  const mapText = `type octile\nheight 4\nwidth 10\nmap\n${rows.join('\n')}\n`;
  const byRef = JSON.stringify({
    version: 1,
    name: 'by reference',
    map: { file: '../maps/strip.map' },
    start: { col: 1, row: 2 },
    goal: { col: 8, row: 2 },
    local_planner: { name: 'dwa' },
  });
  const refFile = { name: 'strip.json', mimeType: 'application/json', buffer: Buffer.from(byRef) };
  await page.setInputFiles('#file-input', refFile);
  await page.waitForFunction(() => /strip\.json.*strip\.map/.test(document.getElementById('error').textContent));
  const loads = Number(await bodyData(page, 'loadSeq'));
  await page.setInputFiles('#file-input', [refFile, { name: 'strip.map', mimeType: 'text/plain', buffer: Buffer.from(mapText) }]);
  await page.waitForFunction((n) => Number(document.body.dataset.loadSeq) > n, loads);
  assert.equal(await errorText(page), null);
  assert.match(await page.textContent('#map-size'), /^10 × 4/);
  // Still alive: stepping works and time advances.
  const t0 = Number(await bodyData(page, 'time'));
  await page.click('#step');
  assert.ok(Number(await bodyData(page, 'time')) > t0, 'stepping still works');
  await screenshot(page, 'robot-05-error.png');
  assert.deepEqual(problems, []);
  await page.close();
});

test('a mover hitting the robot at rest is named in the status line', async () => {
  const { page, problems } = await openRobot();
  // The demo with one fast mover 0.05 m from the robot, driving at it: it
  // hits in the first step, before the robot can reach 0.05 m/s.
  const scenario = JSON.parse(fs.readFileSync(path.join(REPO, 'assets/scenarios', DEMO), 'utf8'));
  scenario.movers = [{ id: 3, radius: 0.3, motion: { model: 'constant-velocity', start: [1.6, 1.05], velocity: [-3.0, 0.0] } }];
  await page.setInputFiles('#file-input', { name: 'hit.json', mimeType: 'application/json', buffer: Buffer.from(JSON.stringify(scenario)) });
  await page.waitForFunction(() => document.body.dataset.state === 'ready', null, { timeout: 30_000 });
  await page.click('#play');
  await page.waitForFunction(() => document.body.dataset.outcome === 'collision', null, { timeout: 30_000 });
  await page.waitForFunction(() => /hit by mover 3 while at rest/.test(document.getElementById('status').textContent), null, { timeout: 5000 });
  const status = await page.textContent('#status');
  assert.match(status, / · hit by mover 3 while at rest$/);
  assert.doesNotMatch(status, /· collision$/);
  assert.match(await page.textContent('#hint'), /Episode over: hit by mover 3 while at rest\./);
  await screenshot(page, 'robot-hit-at-rest.png');
  assert.deepEqual(problems, []);
  await page.close();
});

test('determinism: the page and the native CLI give the same trace hash', async () => {
  assert.ok(fs.existsSync(CLI), 'build target/release/planlab first (cargo build --release -p planlab-cli)');
  // The demo (baseline DWA), and when present an improved-DWA preset (global
  // path, classes, virtual goals go into the trace) and a cleaning-robot one
  // (omnidirectional, seeded road vibration and slip, wheel loads), and an
  // [S] one (safe-dual-dwa: safe A* feature nodes, held speed) run to reached.
  const cases = [DEMO, 'T-fig3-11.json', 'S-tab1.json', 'C-tab5-hollow-brick.json'].filter((f) => fs.existsSync(path.join(REPO, 'assets/scenarios', f)));
  for (const file of cases) {
    const run = spawnSync(CLI, ['run', path.join(REPO, 'assets/scenarios', file), '--json'], { encoding: 'utf8', timeout: 120_000 });
    assert.equal(run.status, 0, run.stderr);
    const native = JSON.parse(run.stdout);
    assert.ok(native.trace_hash, `planlab run --json has trace_hash: ${run.stdout}`);
    const { page, problems } = await openRobot(file);
    await setSpeed(page, 8);
    await page.click('#play');
    const outcome = await waitOutcome(page);
    assert.equal(outcome, native.outcome, file);
    // The CLI prints the u64 in hex, the page in decimal.
    const hash = await bodyData(page, 'traceHash');
    const nativeDec = BigInt(`0x${native.trace_hash}`).toString();
    console.log(`${file} (${native.planner}): trace hash native ${native.trace_hash} (= ${nativeDec}), wasm ${hash}; ${outcome} after ${native.steps} steps`);
    assert.equal(hash, nativeDec, file);
    // The page's metrics are the CLI's.
    const pageMetrics = await hooks(page, 'metrics');
    for (const k of ['time_s', 'path_length_m', 'min_clearance_m', 'mean_clearance_m', 'total_turn_rad', 'speed_drops', 'mean_tracking_error_m']) {
      assert.equal(pageMetrics[k], native[k], `${file}: ${k}`);
    }
    assert.deepEqual(problems, []);
    await page.close();
  }
});

test('frame time on the crowded scene (20 movers, DWA 20 × 40 samples)', async () => {
  const { page, problems } = await openRobot(CROWD);
  assert.equal((await hooks(page, 'movers')).length / 6, 20, '20 movers');
  await page.click('#play');
  await waitTime(page, 0.5);
  // 20 × 40 samples; the DWA adds v = 0 / ω = 0 to an axis when the even
  // spread misses it, so up to 21 × 41.
  const rollouts = await hooks(page, 'rollouts');
  assert.ok(rollouts >= 800 && rollouts <= 21 * 41, `${rollouts} rollouts drawn`);
  const results = {};
  for (const speed of [1, 8]) {
    await setSpeed(page, speed);
    await hooks(page, 'resetMeter');
    await page.waitForTimeout(4000);
    const s = await hooks(page, 'frameStats');
    results[`${speed}x`] = { ...s, loadavg: os.loadavg(), cpus: os.cpus().length };
    const f = (o) => `median ${o.median.toFixed(2)} ms, p95 ${o.p95.toFixed(2)} ms`;
    console.log(
      `frame stats at ${speed}× (${rollouts} rollouts): ${s.frames} frames; interval ${f(s.interval)}; work ${f(s.work)}; sim ${f(s.sim)}; paint ${f(s.paint)}; load average ${os.loadavg()[0].toFixed(2)} on ${os.cpus().length} CPUs`,
    );
    if ((await bodyData(page, 'outcome')) !== 'running') break;
  }
  await screenshot(page, 'robot-06-crowd.png');
  fs.mkdirSync(path.join(REPO, 'tests/e2e/screenshots'), { recursive: true });
  fs.writeFileSync(path.join(REPO, 'tests/e2e/screenshots/robot-frame-stats.json'), JSON.stringify(results, null, 2));
  assert.ok(Object.keys(results).length > 0);
  assert.deepEqual(problems, []);
  await page.close();
});

test('every parameter on the panel has a plain-language name; the symbol and config name stay in its tooltip and the help', async () => {
  const { page, problems } = await openRobot();
  const params = () => page.$$eval('#params .param', (els) => els.map((e) => ({ field: e.dataset.field, shown: (e.querySelector('.label b') ?? e.querySelector('label.check'))?.textContent.trim(), title: e.title })));
  const dwa = Object.fromEntries((await params()).map((p) => [p.field, p]));
  assert.equal(dwa.alpha.shown, 'heading weight α');
  assert.equal(dwa.beta.shown, 'clearance weight β');
  assert.equal(dwa.gamma.shown, 'speed weight γ');
  assert.equal(dwa.v_res.shown, 'speed resolution');
  assert.match(dwa.alpha.title, /^heading weight α — alpha: α, heading weight/);
  assert.match(dwa.v_res.title, /v_res/);
  // No planner shows a bare config name (alpha, v_res, acc_lim_x …) as a
  // field's name.
  const planners = await page.$$eval('#planner option', (os) => os.map((o) => o.value));
  const bare = [];
  for (const name of planners) {
    await page.selectOption('#planner', name);
    await page.waitForFunction((n) => window.planlabRobot.plannerChoice().name === n, name);
    for (const p of await params()) {
      const leaf = p.field.split('.').pop();
      if (!p.shown || p.shown === leaf || /^[a-z]+(_[a-z0-9]+)+$/.test(p.shown)) bare.push(`${name}: ${p.field} shown as ${p.shown}`);
    }
  }
  assert.deepEqual(bare, []);
  // The help's table: the plain name over the config name.
  await page.selectOption('#planner', 'dwa');
  await page.click('#help-button');
  const row = await page.$eval('.help-planner[open] tr[data-param="alpha"] .pname', (td) => ({ label: td.querySelector('.plabel')?.textContent, config: td.querySelector('.pconfig')?.textContent }));
  assert.deepEqual(row, { label: 'heading weight α', config: 'alpha' });
  assert.deepEqual(problems, []);
  await page.close();
});

test('Global planner Hybrid A*: the car path of the CLI is drawn and followed to the goal, the same run as planlab run', async () => {
  assert.ok(fs.existsSync(CLI), 'build target/release/planlab first (cargo build --release -p planlab-cli)');
  const file = 'T-fig3-2.json';
  const { page, problems } = await openRobot(file);
  assert.equal(await page.inputValue('#global-planner'), '');
  assert.equal(await page.isVisible('#turning-radius'), false);
  await page.selectOption('#global-planner', 'hybrid-astar');
  await page.waitForFunction(() => document.body.dataset.globalLength && document.body.dataset.state === 'ready');
  // The preset's improved-dwa plans its own route: dwa follows the car path.
  assert.equal(await page.inputValue('#planner'), 'dwa');
  assert.match(await page.textContent('#global-summary'), /improved-dwa plans its own route/);
  assert.equal(await page.inputValue('#turning-radius'), '1');
  const run = spawnSync(
    CLI,
    ['run', path.join(REPO, 'assets/scenarios', file), '--planner', 'dwa', '--json',
      '--set', 'global_planner.algorithm=hybrid-astar', '--set', 'global_planner.turning_radius_m=1'],
    { encoding: 'utf8', timeout: 120_000 },
  );
  assert.equal(run.status, 0, run.stderr);
  const native = JSON.parse(run.stdout);
  const length = Number(await bodyData(page, 'globalLength'));
  assert.equal(length, native.global_path.length_m);
  // The drawn path: from the start to the goal, its polyline as long as the
  // car path (waypoints every cell: chords of arcs of radius ≥ 1 m lose
  // under 0.1 %), longer than the straight line.
  const pts = await hooks(page, 'globalPath');
  assert.ok(pts.length > 100, `${pts.length / 2} points`);
  let drawn = 0;
  for (let i = 2; i < pts.length; i += 2) drawn += Math.hypot(pts[i] - pts[i - 2], pts[i + 1] - pts[i - 1]);
  assert.ok(Math.abs(drawn - length) < 1e-3 * length, `drawn ${drawn} m, car path ${length} m`);
  assert.deepEqual(pts.slice(0, 2), [1.5, 4]);
  assert.deepEqual(pts.slice(-2), [10.5, 4]);
  assert.ok(length > 9);
  await setSpeed(page, 8);
  await page.click('#play');
  await waitTime(page, 8);
  // Paused, with the Global planner card in view, for the README.
  await page.click('#play');
  await page.locator('#global-summary').scrollIntoViewIfNeeded();
  await page.screenshot({ path: path.join(REPO, 'docs/robot-hybrid-astar-screenshot.png') });
  await page.click('#play');
  const outcome = await waitOutcome(page);
  assert.equal(outcome, 'reached', await page.textContent('#status'));
  assert.equal(native.outcome, 'reached');
  assert.equal(await bodyData(page, 'traceHash'), BigInt(`0x${native.trace_hash}`).toString());
  // A bad radius: the core's one-line error, the run in force stays.
  await page.fill('#turning-radius', '-1');
  await page.dispatchEvent('#turning-radius', 'change');
  assert.match(await errorText(page), /global_planner\.turning_radius_m = -1/);
  assert.equal(Number(await bodyData(page, 'globalLength')), length);
  // May reverse: a Reeds-Shepp car path, again the CLI's.
  await page.fill('#turning-radius', '1');
  await page.check('#car-reverse');
  await page.waitForFunction(() => /may reverse/.test(document.getElementById('global-summary').textContent));
  const back = spawnSync(
    CLI,
    ['run', path.join(REPO, 'assets/scenarios', file), '--planner', 'dwa', '--json', '--set', 'global_planner.algorithm=hybrid-astar',
      '--set', 'global_planner.turning_radius_m=1', '--set', 'global_planner.reverse=true'],
    { encoding: 'utf8', timeout: 120_000 },
  );
  assert.equal(back.status, 0, back.stderr);
  assert.equal(Number(await bodyData(page, 'globalLength')), JSON.parse(back.stdout).global_path.length_m);
  // Back to none: no car path.
  await page.selectOption('#global-planner', '');
  await page.waitForFunction(() => !document.body.dataset.globalLength && document.body.dataset.state === 'ready');
  assert.equal(await page.isVisible('#turning-radius'), false);
  assert.deepEqual(problems, []);
  await page.close();
});
