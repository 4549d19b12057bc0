// End-to-end tests of the arm page in headless Chromium (WebGL through
// SwiftShader): the T-tab5-3 preset loads, plays to the goal and shows the
// minimum link-to-hand distance the core measured; switching the predictor
// off and replaying shows a smaller one (the thesis's Table 5-3 relation,
// in the page); an unreachable target is refused in the message bar; no
// console errors. Also writes docs/arm-screenshot.png.

import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import path from 'node:path';
import { REPO, startSession, screenshot, errorText } from './harness.mjs';

let session;
before(async () => {
  session = await startSession();
});
after(async () => {
  await session?.close();
});

async function openArm() {
  const page = await session.context.newPage();
  const problems = [];
  page.on('console', (m) => {
    if (m.type() === 'error') problems.push(`console.error: ${m.text()}`);
  });
  page.on('pageerror', (e) => problems.push(`pageerror: ${e.message}`));
  await page.goto(`${session.base}arm.html?scenario=T-tab5-3.json`);
  await page.waitForFunction(() => ['ready', 'error'].includes(document.body.dataset.state), null, { timeout: 30_000 });
  assert.equal(await errorText(page), null, 'no error after loading');
  return { page, problems };
}

const metric = async (page, name) => Number(await page.getAttribute(`#metric-${name}`, 'data-value'));

async function playToEnd(page) {
  await page.selectOption('#speed', '4');
  await page.click('#play');
  await page.waitForFunction(() => document.body.dataset.outcome && document.body.dataset.outcome !== 'running', null, {
    timeout: 120_000,
  });
  return page.evaluate(() => document.body.dataset.outcome);
}

test('T-tab5-3 preset plays to the goal and shows the minimum distance', async () => {
  const { page, problems } = await openArm();
  assert.equal(await page.getAttribute('#nav-arm', 'aria-current'), 'page');
  assert.equal(await page.inputValue('#predictor'), 'constant-velocity');
  assert.equal(await page.$$eval('#joints tr', (r) => r.length), 7, 'seven joints in the readout');
  assert.ok(await page.$('#view canvas'), 'WebGL canvas present');
  assert.equal(await playToEnd(page), 'reached');
  const shown = await page.textContent('#metric-min');
  const withPred = await metric(page, 'min');
  const core = await page.evaluate(() => window.planlabArm.metrics());
  assert.equal(withPred, core.min_obstacle_distance_m);
  assert.match(shown, new RegExp(`^${core.min_obstacle_distance_m.toFixed(4)} m$`));
  assert.ok(withPred > 0, `min distance ${withPred}`);
  assert.ok(core.path_points > 5 && core.path_length_m > 0.3, JSON.stringify(core));
  // The canvas drew something: not a single flat colour.
  const distinct = await page.evaluate(() => {
    const c = document.querySelector('#view canvas');
    const g = document.createElement('canvas');
    g.width = 64;
    g.height = 64;
    const x = g.getContext('2d');
    x.drawImage(c, 0, 0, 64, 64);
    const d = x.getImageData(0, 0, 64, 64).data;
    const set = new Set();
    for (let i = 0; i < d.length; i += 4) set.add((d[i] >> 4) * 256 + (d[i + 1] >> 4) * 16 + (d[i + 2] >> 4));
    return set.size;
  });
  assert.ok(distinct > 8, `the 3D view shows a scene (${distinct} colours)`);
  await screenshot(page, 'arm-01-reached.png');

  // Without prediction the arm passes closer to the hand (Table 5-3).
  await page.selectOption('#predictor', 'none');
  await page.click('#reset');
  assert.equal(await page.evaluate(() => document.body.dataset.outcome), 'running');
  assert.equal(await playToEnd(page), 'reached');
  const without = await metric(page, 'min');
  assert.ok(without < withPred, `without prediction ${without} < with ${withPred}`);
  // Mid-run with prediction: the hand's predicted positions are drawn.
  await page.selectOption('#predictor', 'constant-velocity');
  await page.click('#reset');
  for (let i = 0; i < 26; i++) await page.click('#step');
  assert.equal(await page.evaluate(() => document.body.dataset.time), '2.60');
  assert.ok(Number(await page.evaluate(() => document.body.dataset.predictions)) > 0, 'predictions drawn');
  await page.screenshot({ path: path.join(REPO, 'docs/arm-screenshot.png') });
  assert.deepEqual(problems, []);
  await page.close();
});

test('target sliders move the goal; an unreachable target is refused', async () => {
  const { page, problems } = await openArm();
  // Move y by keyboard on the slider (a person's input events).
  await page.focus('#target-y');
  for (let i = 0; i < 10; i++) await page.keyboard.press('ArrowLeft');
  assert.equal(await errorText(page), null);
  const y = Number(await page.inputValue('#target-y'));
  assert.ok(Math.abs(y - (0.35 - 0.05)) < 1e-6, `target y ${y}`);
  // Far out of reach: refused with the core's reason, goal unchanged.
  for (const [axis, v] of [['x', '1.0'], ['y', '0.7'], ['z', '1.3']]) {
    await page.$eval(`#target-${axis}`, (e, val) => {
      e.value = val;
      e.dispatchEvent(new Event('input'));
    }, v);
  }
  assert.match((await errorText(page)) ?? '', /out of reach/);
  const goal = await page.evaluate(() => document.body.dataset.goal);
  assert.ok(goal.split(',').map(Number)[2] < 1.3, `goal kept in reach: ${goal}`);
  // The hand's motion can be changed and the episode restarts.
  await page.selectOption('#hand-preset', 'wave');
  assert.equal(await page.evaluate(() => document.body.dataset.time), '0.00');
  await page.click('#step');
  assert.equal(await page.evaluate(() => document.body.dataset.time), '0.10');
  assert.deepEqual(problems, []);
  await page.close();
});

test('the Planner menu runs RRT-Connect on T-tab5-3 as the CLI does, draws its plan, and goes back to the APF', async () => {
  const { page, problems } = await openArm();
  assert.deepEqual(
    await page.$$eval('#planner option', (o) => o.map((x) => x.value)),
    ['apf', 'rrt-connect'],
  );
  assert.equal(await page.inputValue('#planner'), 'apf');
  await page.selectOption('#planner', 'rrt-connect');
  await page.waitForFunction(() => document.body.dataset.planner === 'rrt-connect' && document.body.dataset.state === 'ready');
  // The predictor survives the restart.
  assert.equal(await page.inputValue('#predictor'), 'constant-velocity');
  // A few samples in, the plan ahead is drawn (Trail item tag 1).
  await page.click('#step');
  const plan = await page.evaluate(() => window.planlabArm.planner());
  assert.equal(plan.planner, 'rrt-connect');
  assert.ok(plan.plans >= 1 && plan.collision_checks > 0, JSON.stringify(plan));
  assert.equal(plan.min_table_m === null, false, 'RRT-Connect knows the table top');
  assert.equal(await playToEnd(page), 'reached');
  // The same run as `planlab run assets/scenarios/T-tab5-3.json --planner
  // rrt-connect --set arm.table_z_m=0.72`: 2.901 rad, 0.504 m, 0.008 m.
  const end = await page.evaluate(() => window.planlabArm.planner());
  const core = await page.evaluate(() => window.planlabArm.metrics());
  assert.ok(Math.abs(end.joint_path_rad - 2.901) < 0.0015, `joint path ${end.joint_path_rad}`);
  assert.ok(Math.abs(end.gripper_path_m - 0.504) < 0.0015, `gripper path ${end.gripper_path_m}`);
  assert.ok(core.min_obstacle_distance_m > 0 && Math.abs(core.min_obstacle_distance_m - 0.008) < 0.0015, JSON.stringify(core));
  assert.match(await page.textContent('#metric-plans'), /^\d+ \(\d+ replans\), \d+ checks$/);
  assert.match(await page.textContent('#status'), /RRT-Connect/);
  await page.screenshot({ path: path.join(REPO, 'docs/arm-rrt-screenshot.png') });
  // Back to the thesis's APF: a fresh run of the preset.
  await page.selectOption('#planner', 'apf');
  await page.waitForFunction(() => document.body.dataset.planner === 'apf' && document.body.dataset.state === 'ready');
  assert.equal(await page.evaluate(() => window.planlabArm.planner().plans), 0);
  assert.deepEqual(problems, []);
});
