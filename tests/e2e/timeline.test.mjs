// End-to-end tests of the robot page's timeline and plots, and the arm
// page's distance plot, in headless Chromium with real mouse and keys:
// a run is scrubbed with the slider, the arrow keys and the step buttons,
// and what is drawn (pose, trail, goal, fan of that step) matches the trace
// row of that frame (the page's `traceCsv()`, the format of `planlab run
// --trace`); Replay re-runs the recorded run, edits included, and gets the
// identical trace hash; Play from a past frame branches; the plots'
// cursors follow the timeline and a press in a plot moves it; wheel loads
// are plotted for a vehicle preset and not for the DWA demo; the arm page
// plots the distance to the hand.

import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { startSession, screenshot, errorText, openRobotPage } from './harness.mjs';

let session;
before(async () => {
  session = await startSession();
});
after(async () => {
  await session?.close();
});

async function openRobot(scenario) {
  return openRobotPage(session, `robot.html?scenario=${scenario}`);
}

const robot = (page, fn, ...args) => page.evaluate(([f, a]) => window.planlabRobot[f](...a), [fn, args]);
const tl = (page, fn, ...args) => page.evaluate(([f, a]) => window.planlabTimeline[f](...a), [fn, args]);
const tlData = (page) => page.evaluate(() => ({ ...document.getElementById('timeline').dataset }));

async function runToEnd(page, speed = 8) {
  await page.selectOption('#speed', String(speed));
  await page.click('#play');
  await page.waitForFunction(() => document.body.dataset.outcome && document.body.dataset.outcome !== 'running', null, {
    timeout: 150_000,
  });
  return page.evaluate(() => document.body.dataset.outcome);
}

/** Trace CSV rows as objects of numbers (the columns the timeline shows). */
async function traceRows(page) {
  const csv = await robot(page, 'traceCsv');
  const [head, ...lines] = csv.trim().split('\n');
  const cols = head.split(',');
  return lines.map((l) => {
    const f = l.split(',');
    const o = {};
    for (const c of ['t', 'x', 'y', 'theta', 'v', 'w', 'goal_x', 'goal_y']) o[c] = Number(f[cols.indexOf(c)]);
    o.goal_kind = f[cols.indexOf('goal_kind')];
    o.movers = f[cols.indexOf('movers')];
    return o;
  });
}

/** The drawn frame agrees with trace row `k` (pose, trail, goal, movers). */
async function assertFrameMatches(page, rows, k) {
  const d = await tlData(page);
  assert.equal(Number(d.frame), k, `timeline at frame ${k}`);
  const r = rows[k];
  assert.equal(Number(d.t), r.t);
  assert.equal(Number(d.x), r.x);
  assert.equal(Number(d.y), r.y);
  assert.equal(Number(d.theta), r.theta);
  const pose = await tl(page, 'drawnPose');
  assert.deepEqual(pose.slice(0, 3), [r.x, r.y, r.theta], `drawn pose at frame ${k}`);
  assert.equal(await tl(page, 'trailLen'), k + 1, 'trail drawn up to the frame');
  const [gx, gy, kind] = await tl(page, 'drawnGoal');
  assert.deepEqual([gx, gy, kind], [r.goal_x, r.goal_y, r.goal_kind], 'the goal steered to then');
  const movers = await tl(page, 'drawnMovers');
  const want = r.movers ? r.movers.split(';').map((m) => m.split(':').map(Number)) : [];
  assert.equal(movers.length / 6, want.length);
  want.forEach(([id, x, y], i) => assert.deepEqual(movers.slice(6 * i, 6 * i + 1).concat(movers.slice(6 * i + 2, 6 * i + 4)), [id, x, y]));
  // The readout says so too.
  const text = await page.textContent('#tl-readout');
  assert.ok(text.includes(`frame ${k}/`) && text.includes(`t = ${r.t.toFixed(1)} s`), text);
  assert.ok(text.includes(`(${r.x.toFixed(2)}, ${r.y.toFixed(2)})`), text);
}

async function waitDetail(page) {
  await page.waitForFunction(() => document.getElementById('timeline').dataset.detail === 'replayed', null, { timeout: 20_000 });
}

async function plotCursorsAt(page, k) {
  // The cursors move in the frame after the timeline.
  await page.waitForFunction(
    (kk) => Object.values(window.planlabTimeline.plotCursors()).every((i) => i === kk),
    k,
    { timeout: 5_000 },
  ).catch(() => {});
  const c = await tl(page, 'plotCursors');
  for (const [key, idx] of Object.entries(c)) assert.equal(idx, k, `${key} plot cursor at the frame`);
}

test('timeline: scrub with slider and keys, step, plots follow, click in a plot, replay identical, branch', async () => {
  const { page, problems } = await openRobot('dwa-demo.json');
  assert.equal(await runToEnd(page), 'reached');
  const rows = await traceRows(page);
  const n = rows.length - 1;
  let d = await tlData(page);
  assert.equal(Number(d.frames), n);
  assert.equal(d.live, 'true');
  assert.equal(Number(d.frame), n);
  // The DWA demo has no vehicle model and no global path: no empty charts.
  assert.deepEqual(await tl(page, 'plotsShown'), ['v', 'w', 'clearance']);
  assert.equal(await page.getAttribute('#plot-loads', 'hidden'), '');
  assert.equal(await page.getAttribute('#plot-tracking', 'hidden'), '');

  // Drag the slider's thumb from the end to about 40 %.
  const box = await page.locator('#tl-slider').boundingBox();
  const thumbX = (f) => box.x + 8 + (box.width - 16) * f;
  await page.mouse.move(thumbX(1), box.y + box.height / 2);
  await page.mouse.down();
  await page.mouse.move(thumbX(0.7), box.y + box.height / 2, { steps: 8 });
  await page.mouse.move(thumbX(0.4), box.y + box.height / 2, { steps: 8 });
  await page.mouse.up();
  d = await tlData(page);
  let k = Number(d.frame);
  assert.ok(Math.abs(k - 0.4 * n) <= 0.03 * n + 2, `dragged to frame ${k} of ${n}`);
  assert.equal(d.live, 'false');
  await assertFrameMatches(page, rows, k);
  // Once the slider rests, that step is re-simulated: its fan is drawn.
  await waitDetail(page);
  assert.ok((await robot(page, 'rollouts')) > 10, 'the fan of that step');
  await assertFrameMatches(page, rows, k);
  // How long re-simulating to that frame from the start took (a backward
  // move costs this; a forward one only the steps in between).
  console.log(`re-simulating ${k} steps of the DWA demo for the fan: ${(await tl(page, 'scratchMs')).toFixed(1)} ms`);
  await plotCursorsAt(page, k);
  await screenshot(page, 'timeline-01-scrubbed.png');

  // Keys: ← one back, Shift+← ten back, → one on (the slider has focus).
  await page.keyboard.press('ArrowLeft');
  await assertFrameMatches(page, rows, k - 1);
  await page.keyboard.press('Shift+ArrowLeft');
  await assertFrameMatches(page, rows, k - 11);
  await page.keyboard.press('ArrowRight');
  await assertFrameMatches(page, rows, k - 10);
  await waitDetail(page);
  await plotCursorsAt(page, k - 10);
  // Step buttons, frame by frame.
  await page.click('#tl-fwd');
  await page.click('#tl-fwd');
  await assertFrameMatches(page, rows, k - 8);
  await page.click('#tl-back');
  await assertFrameMatches(page, rows, k - 9);
  k -= 9;
  // Home / End jump to the start and the live end.
  await page.keyboard.press('Home');
  await assertFrameMatches(page, rows, 0);
  await page.keyboard.press('End');
  d = await tlData(page);
  assert.equal(d.live, 'true');
  assert.equal(Number(d.frame), n);
  assert.equal(await tl(page, 'trailLen'), n + 1, 'whole trail again at the live end');

  // A press in the speed plot moves the timeline to that time; all
  // plots' cursors go there.
  const over = await page.locator('#plot-v .u-over').boundingBox();
  await page.mouse.click(over.x + over.width * 0.25, over.y + over.height * 0.5);
  d = await tlData(page);
  const kp = Number(d.frame);
  const tEnd = rows[n].t;
  const range = Math.max(5, tEnd);
  assert.ok(Math.abs(Number(d.t) - 0.25 * range) <= 0.02 * range + 0.1, `plot click at t ${d.t} of ${range}`);
  await assertFrameMatches(page, rows, kp);
  await page.mouse.move(over.x + over.width * 0.5, over.y - 60);
  await plotCursorsAt(page, kp);
  // Dragging in the plot scrubs on.
  await page.mouse.move(over.x + over.width * 0.25, over.y + over.height * 0.5);
  await page.mouse.down();
  await page.mouse.move(over.x + over.width * 0.6, over.y + over.height * 0.5, { steps: 6 });
  await page.mouse.up();
  const kd = Number((await tlData(page)).frame);
  assert.ok(kd > kp + 0.25 * n, `dragged in the plot to frame ${kd}`);
  await assertFrameMatches(page, rows, kd);
  // Hovering a plot reads its values in the legend.
  const legend = await page.textContent('#plot-clearance .u-legend');
  assert.match(legend, /clearance\s*[0-9.]+/);

  // Replay: the recorded run again from its setup and seed, played back,
  // with the identical trace.
  const hash = await robot(page, 'traceHash');
  await page.click('#tl-replay');
  await page.waitForFunction(() => document.getElementById('timeline').dataset.playback === 'true', null, { timeout: 5_000 });
  await page.waitForTimeout(400);
  const mid = await tlData(page);
  assert.ok(Number(mid.frame) > 0 && Number(mid.frame) < n, `replay plays back (frame ${mid.frame})`);
  await screenshot(page, 'timeline-02-replaying.png');
  await page.waitForFunction(() => document.getElementById('timeline').dataset.replayMatch !== undefined, null, { timeout: 120_000 });
  d = await tlData(page);
  assert.equal(d.replayMatch, 'true');
  assert.equal(d.replayHash, hash);
  assert.match(await page.textContent('#tl-note'), /identical/);

  // Play from a past frame branches there: the rows up to it are kept.
  await page.keyboard.press('Home');
  for (let i = 0; i < 3; i++) await page.keyboard.press('Shift+ArrowRight');
  await assertFrameMatches(page, rows, 30);
  await page.click('#play');
  await page.waitForFunction(() => Number(document.body.dataset.steps) > 40, null, { timeout: 30_000 });
  await page.click('#play');
  assert.match(await page.textContent('#tl-note'), /branched at frame 30/);
  const branched = await traceRows(page);
  assert.deepEqual(branched.slice(0, 31), rows.slice(0, 31), 'the branch starts with the run up to frame 30');
  assert.equal((await tlData(page)).live, 'true');
  assert.equal(await errorText(page), null);
  assert.deepEqual(problems, []);
  await page.close();
});

test('edits during a run are recorded: replay reproduces them exactly', async () => {
  const { page, problems } = await openRobot('dwa-demo.json');
  await page.selectOption('#speed', '4');
  await page.click('#play');
  await page.waitForFunction(() => Number(document.body.dataset.time) >= 2, null, { timeout: 60_000 });
  // Move the goal mid-run, then drop a standing mover.
  await page.click('#tool-goal');
  let p = await robot(page, 'toScreen', 10.6, 1.2);
  await page.mouse.click(p.x, p.y);
  await page.waitForFunction(() => Number(document.body.dataset.time) >= 4, null, { timeout: 60_000 });
  await page.click('#tool-mover');
  p = await robot(page, 'toScreen', 2.0, 6.5);
  await page.mouse.click(p.x, p.y);
  assert.equal(await errorText(page), null);
  await page.waitForFunction(() => document.body.dataset.outcome !== 'running', null, { timeout: 120_000 });
  const ticks = await page.$$eval('#timeline .tl-ticks i', (is) => is.length);
  assert.equal(ticks, 2, 'the two edits are marked on the timeline');
  const hash = await robot(page, 'traceHash');
  await page.click('#tl-replay');
  await page.waitForFunction(() => document.getElementById('timeline').dataset.replayMatch !== undefined, null, { timeout: 120_000 });
  const d = await tlData(page);
  assert.equal(d.replayMatch, 'true', 'the edited run replays to the identical trace');
  assert.equal(d.replayHash, hash);
  assert.deepEqual(problems, []);
  await page.close();
});

test('a vehicle preset (C-tab5) plots wheel loads and tracking error; hover reads them', async () => {
  const { page, problems } = await openRobot('C-tab5-asphalt.json');
  assert.deepEqual(await tl(page, 'plotsShown'), ['v', 'w', 'clearance', 'tracking', 'loads']);
  assert.equal(await page.getAttribute('#plot-loads', 'hidden'), null);
  await page.selectOption('#speed', '8');
  await page.click('#play');
  await page.waitForFunction(() => Number(document.body.dataset.time) >= 6, null, { timeout: 60_000 });
  await page.click('#play');
  const s = await tl(page, 'plotSummary');
  const steps = Number(await page.evaluate(() => document.body.dataset.steps));
  assert.equal(s.loads.rows, steps + 1);
  // A quarter of the Table 1 vehicle's weight each, give or take.
  for (const f of s.loads.last) assert.ok(f > 20 && f < 120, `wheel load ${f} N`);
  // Every chart has a finite y range around its data (the start row has
  // no loads: that must not blank the loads chart).
  const ranges = await tl(page, 'plotRanges');
  for (const [key, [lo, hi]] of Object.entries(ranges)) assert.ok(Number.isFinite(lo) && Number.isFinite(hi) && lo < hi, `${key} range ${lo}..${hi}`);
  for (const f of s.loads.last) assert.ok(ranges.loads[0] < f && f < ranges.loads[1], `load ${f} within ${ranges.loads}`);
  const track = s.tracking.last[0];
  const m = await robot(page, 'metrics');
  assert.ok(track >= 0 && track <= m.max_tracking_error_m + 1e-12, `tracking ${track} ≤ max ${m.max_tracking_error_m}`);
  // Hover the loads plot: the legend reads the four loads at that time.
  const over = await page.locator('#plot-loads .u-over').boundingBox();
  await page.mouse.move(over.x + over.width * 0.3, over.y + over.height * 0.5);
  await page.waitForTimeout(100);
  const legend = await page.textContent('#plot-loads .u-legend');
  for (const w of ['FL', 'FR', 'RL', 'RR']) assert.match(legend, new RegExp(`${w}\\s*[0-9]+\\.[0-9]`), legend);
  // Synced cursors: the other plots' cursors are at the same row.
  const c = await tl(page, 'plotCursors');
  const rowsAt = new Set(Object.values(c));
  assert.equal(rowsAt.size, 1, `synced cursors ${JSON.stringify(c)}`);
  // Back to frame 30 with the keys: that step's fan and the plots' cursors.
  await page.mouse.move(10, 10);
  await page.focus('#tl-slider');
  await page.keyboard.press('Home');
  for (let i = 0; i < 3; i++) await page.keyboard.press('Shift+ArrowRight');
  await waitDetail(page);
  assert.equal(Number((await tlData(page)).frame), 30);
  assert.ok((await robot(page, 'rollouts')) > 10, 'the fan of frame 30');
  await plotCursorsAt(page, 30);
  await screenshot(page, 'timeline-03-wheel-loads.png');
  assert.equal(await errorText(page), null);
  assert.deepEqual(problems, []);
  await page.close();
});

test('a LiDAR preset: a past frame shows the scan taken there, from the re-simulated step', async () => {
  const { page, problems } = await openRobot('L-sim1.json');
  await page.selectOption('#speed', '8');
  await page.click('#play');
  await page.waitForFunction(() => Number(document.body.dataset.time) >= 5, null, { timeout: 60_000 });
  await page.click('#play');
  const live = await tl(page, 'drawnLidar');
  assert.ok(live && live.rays > 10, 'live scan drawn');
  const rows = await traceRows(page);
  await page.click('#tl-start');
  for (let i = 0; i < 2; i++) await page.click('#tl-fwd', { modifiers: ['Shift'] });
  await assertFrameMatches(page, rows, 20);
  await waitDetail(page);
  const past = await tl(page, 'drawnLidar');
  assert.ok(past && past.rays === live.rays, 'the scan of frame 20');
  // The scan was taken from where the robot stood before step 20 moved it.
  const d = Math.hypot(past.sensor[0] - rows[19].x, past.sensor[1] - rows[19].y);
  assert.ok(d < 1e-4, `sensor at ${past.sensor}, robot at frame 19 (${rows[19].x}, ${rows[19].y})`);
  assert.ok(past.seen > 0 && past.seen < live.seen, `fog of frame 20: ${past.seen} cells seen of ${live.seen}`);
  await screenshot(page, 'timeline-05-lidar-past.png');
  assert.equal(await errorText(page), null);
  assert.deepEqual(problems, []);
  await page.close();
});

test('arm page: the distance to the hand is plotted per sample with hover values', async () => {
  const page = await session.context.newPage();
  const problems = [];
  page.on('console', (m) => m.type() === 'error' && problems.push(m.text()));
  page.on('pageerror', (e) => problems.push(e.message));
  await page.goto(`${session.base}arm.html`);
  await page.waitForFunction(() => document.body.dataset.state === 'ready', null, { timeout: 30_000 });
  await page.selectOption('#speed', '4');
  await page.click('#play');
  await page.waitForFunction(() => Number(document.body.dataset.time) >= 3, null, { timeout: 60_000 });
  await page.click('#play');
  const p = await page.evaluate(() => window.planlabArm.distancePlot());
  assert.ok(p.rows >= 30, `${p.rows} samples plotted`);
  assert.equal(p.series.length, 3 * p.rows);
  const [t, arm, grip] = p.last;
  const shown = Number(await page.evaluate(() => document.body.dataset.time));
  assert.ok(Math.abs(t - shown) < 0.006, `last sample at ${t} s, page at ${shown} s`);
  const now = Number(await page.getAttribute('#metric-now', 'data-value'));
  assert.equal(arm, now, 'the last plotted arm distance is the distance now');
  assert.ok(grip >= arm, 'the gripper is never nearer than the nearest link');
  let min = Infinity;
  for (let i = 1; i < p.series.length; i += 3) min = Math.min(min, p.series[i]);
  assert.equal(min, Number(await page.getAttribute('#metric-min', 'data-value')), 'the plotted minimum is the metric');
  const over = await page.locator('#plot-hand .u-over').boundingBox();
  await page.mouse.move(over.x + over.width * 0.2, over.y + over.height * 0.5);
  await page.waitForTimeout(100);
  assert.match(await page.textContent('#plot-hand .u-legend'), /arm \(nearest link\)\s*[0-9.]+ m/);
  await screenshot(page, 'timeline-04-arm-distance.png');
  // Reset starts the plot over.
  await page.click('#reset');
  assert.equal((await page.evaluate(() => window.planlabArm.distancePlot())).rows, 1);
  assert.deepEqual(problems, []);
  await page.close();
});
