// End-to-end tests of the robot page's Critics list in headless Chromium:
// it lists the critics of the planner in force with the weights of the last
// step (the config's, read from the registry, not written here), follows a
// weight edit, and colouring the fan by a critic repaints the fan with that
// critic's normalised values: each sums to one over the admissible
// rollouts (DWA normalises by the sum) and their weighted sum is the total
// score the fan shows by default; the compare page colours each lane's
// fan by the critic picked. Leaves docs/robot-critics.png.

import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { REPO, startSession, openRobotPage, watchedPage } from './harness.mjs';

const DEMO = 'dwa-demo.json';

let session;
before(async () => {
  session = await startSession();
});
after(async () => {
  await session?.close();
});

const hooks = (page, fn, ...args) => page.evaluate(([f, a]) => window.planlabRobot[f](...a), [fn, args]);

/** The Critics list as shown: name, weight text and data-weight per row
 *  (the first row is the total). */
const criticRows = (page) =>
  page.$$eval('#critics .critic', (els) =>
    els.map((e) => ({ name: e.dataset.critic, text: e.querySelector('.weight').textContent, weight: e.dataset.weight })),
  );

/** Steps `n` control steps with the Step button. */
async function step(page, n) {
  const s0 = Number(await page.evaluate(() => document.body.dataset.steps));
  for (let i = 0; i < n; i++) await page.click('#step');
  await page.waitForFunction((s) => Number(document.body.dataset.steps) >= s, s0 + n);
}

/** A canvas's pixels (RGBA). */
const pixels = (page, id = 'sim-canvas') =>
  page.evaluate((i) => {
    const c = document.getElementById(i);
    return Array.from(c.getContext('2d').getImageData(0, 0, c.width, c.height).data);
  }, id);

/** How many pixels differ in colour between two pictures of one canvas. */
function changedPixels(a, b) {
  assert.equal(a.length, b.length);
  let changed = 0;
  for (let i = 0; i < a.length; i += 4) if (a[i] !== b[i] || a[i + 1] !== b[i + 1] || a[i + 2] !== b[i + 2]) changed++;
  return changed;
}

/** Waits until the views have painted what the last change asked for. */
const painted = (page) => page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));

/** The dwa weights in force: the scenario's config over the registry's defaults. */
async function dwaWeights(page) {
  const scenario = JSON.parse(fs.readFileSync(path.join(REPO, 'assets/scenarios', DEMO), 'utf8'));
  assert.equal(scenario.local_planner.name, 'dwa');
  const defaults = await hooks(page, 'plannerDefaults', 'dwa');
  const config = scenario.local_planner.config ?? {};
  return ['alpha', 'beta', 'gamma'].map((k) => {
    assert.equal(typeof defaults[k], 'number', `registry default of dwa.${k}`);
    return config[k] ?? defaults[k];
  });
}

test('the Critics list shows the weights of the last step and follows a weight edit', async () => {
  const { page, problems } = await openRobotPage(session, `robot.html?scenario=${DEMO}`);
  const weights = await dwaWeights(page);
  // Before the first step: the critics with the weights they were built
  // with (the engine's configured weights).
  let rows = await criticRows(page);
  assert.equal(rows[0].name, 'total');
  const names = rows.slice(1).map((r) => r.name);
  assert.equal(names.length, 3, `dwa's three critics: ${names}`);
  assert.equal(new Set(names).size, 3);
  assert.deepEqual(
    rows.slice(1).map((r) => Number(r.weight)),
    weights,
  );
  await step(page, 1);
  rows = await criticRows(page);
  assert.deepEqual(
    rows.slice(1).map((r) => Number(r.weight)),
    weights,
  );
  assert.deepEqual(
    rows.slice(1).map((r) => Number(r.text)),
    weights,
  );
  // β in the parameter panel: the clearance critic's weight after the next step.
  await page.fill('#param-beta', '0.35');
  await page.waitForFunction(() => window.planlabRobot.plannerChoice()?.config?.beta === 0.35);
  await step(page, 1);
  rows = await criticRows(page);
  assert.deepEqual(
    rows.slice(1).map((r) => Number(r.weight)),
    [weights[0], 0.35, weights[2]],
  );
  assert.deepEqual(problems, []);
  await page.close();
});

test('colouring the fan by a critic repaints it with that critic’s normalised values', async () => {
  const { page, problems } = await openRobotPage(session, `robot.html?scenario=${DEMO}`);
  await step(page, 25);
  const weights = (await criticRows(page)).slice(1).map((r) => Number(r.weight));
  const names = (await criticRows(page)).slice(1).map((r) => r.name);
  assert.equal(await page.getAttribute('#critics', 'data-fan-colour'), 'total');
  const total = await hooks(page, 'fan');
  assert.ok(total.length > 10, 'a fan to colour');
  const ok = total.map((r) => r.admissible);
  assert.ok(ok.filter(Boolean).length > 5, 'admissible rollouts');
  const before = await pixels(page);

  const byCritic = [];
  for (const name of names) {
    await page.check(`#critics .critic[data-critic="${name}"] input`);
    assert.equal(await page.getAttribute('#critics', 'data-fan-colour'), name);
    assert.match(await page.textContent('#critics .fan-scale-what'), new RegExp(`by ${name}: its normalised value`));
    assert.equal(await page.textContent('#legend-fan'), `Rollouts (${name})`);
    await painted(page);
    const fan = await hooks(page, 'fan');
    assert.equal(fan.length, total.length);
    assert.deepEqual(
      fan.map((r) => r.admissible),
      ok,
    );
    // Normalised by the sum over the admissible rollouts.
    const sum = fan.filter((r) => r.admissible).reduce((s, r) => s + r.value, 0);
    assert.ok(Math.abs(sum - 1) < 1e-9 || sum === 0, `${name}: normalised values sum to ${sum}`);
    byCritic.push(fan.map((r) => r.value));
    if (name === names[0]) {
      // Other colours on the canvas: a fan of hundreds of rollouts changes many pixels.
      const changed = changedPixels(before, await pixels(page));
      assert.ok(changed > 200, `${changed} pixels changed`);
    }
  }
  // The total score is the weighted sum of the critics' normalised values.
  for (let i = 0; i < total.length; i++) {
    if (!ok[i]) continue;
    const s = byCritic.reduce((acc, v, k) => acc + weights[k] * v[i], 0);
    assert.ok(Math.abs(s - total[i].value) < 1e-9, `rollout ${i}: Σ w·n = ${s}, total ${total[i].value}`);
  }
  // The choice holds while the run steps, and "total" brings the score back.
  await step(page, 1);
  assert.equal(await page.getAttribute('#critics', 'data-fan-colour'), names[names.length - 1]);
  await page.check('#critics .critic[data-critic="total"] input');
  const again = await hooks(page, 'fan');
  assert.ok(!again.every((r, i) => r.value === byCritic[names.length - 1][i]), 'the total again');

  // The picture for docs: the fan coloured by the clearance critic.
  await page.check(`#critics .critic[data-critic="${names[1]}"] input`);
  await page.$eval('#critics', (e) => e.scrollIntoView({ block: 'center' }));
  // Zoomed in about the robot, so the fan's colours show.
  const [x, y, theta] = await hooks(page, 'state');
  const at = await hooks(page, 'toScreen', x + 1.2 * Math.cos(theta), y + 1.2 * Math.sin(theta));
  await page.mouse.move(at.x, at.y);
  for (let i = 0; i < 2; i++) await page.mouse.wheel(0, -300);
  await painted(page);
  await page.screenshot({ path: path.join(REPO, 'docs/robot-critics.png') });
  assert.deepEqual(problems, []);
  await page.close();
});

test('the compare page colours each lane’s fan by a critic its planner has', async () => {
  const { page, problems } = await watchedPage(session);
  await page.goto(`${session.base}compare.html?scenario=${DEMO}&planners=dwa,improved-dwa&view=side`);
  await page.waitForFunction(() => Number(document.body.dataset.buildSeq) > 0 && document.body.dataset.lanes === '2');
  for (let i = 0; i < 20; i++) await page.click('#step');
  // Total score, then every critic the lanes' planners report.
  const options = await page.$$eval('#fan-colour option', (os) => os.map((o) => o.value));
  assert.equal(options[0], '');
  assert.ok(options.length >= 4, `critics offered: ${options}`);
  await painted(page);
  const before = await pixels(page, 'lane-canvas-0');
  await page.selectOption('#fan-colour', options[1]);
  await painted(page);
  assert.equal(await page.evaluate(() => document.body.dataset.fanColour), options[1]);
  const heads = await page.$$eval('.lane .lane-state', (els) => els.map((e) => [e.dataset.fanColour, e.textContent]));
  for (const [fan, text] of heads) {
    assert.equal(fan, options[1], 'both planners have the critic');
    assert.match(text, new RegExp(`fan: ${options[1]}$`));
  }
  const changed = changedPixels(before, await pixels(page, 'lane-canvas-0'));
  await page.screenshot({ path: path.join(REPO, 'tests/e2e/screenshots/critics-compare.png') });
  assert.ok(changed > 200, `${changed} pixels of dwa's fan changed`);
  assert.deepEqual(problems, []);
  await page.close();
});
