// End-to-end test of LiDAR navigation on the robot page in headless
// Chromium: the L-sim1 preset (temporary-goal navigator over DWA on an
// unknown map) runs to the goal; the rays, edges, obstacle patterns before
// and after expansion, candidates and the temporary goal are drawn from the
// core's data; the fog-of-war toggle shades what the robot has not seen
// (seen cells computed in the core); no console errors. Writes
// docs/lidar-screenshot.png.

import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { REPO, startSession, screenshot, errorText } from './harness.mjs';

const PRESET = 'L-sim1.json';

let session;
before(async () => {
  session = await startSession();
});
after(async () => {
  await session?.close();
});

const bodyData = (page, key) => page.evaluate((k) => document.body.dataset[k], key);
const canvasData = (page, key) => page.evaluate((k) => document.querySelector('#sim-canvas').dataset[k], key);

test('L-sim1: the LiDAR navigator reaches the goal with its layers drawn and the fog of war', async () => {
  const page = await session.context.newPage();
  await page.setViewportSize({ width: 1400, height: 900 });
  const problems = [];
  page.on('console', (m) => {
    if (m.type() === 'error') problems.push(`console.error: ${m.text()}`);
  });
  page.on('pageerror', (e) => problems.push(`pageerror: ${e.message}`));
  await page.goto(`${session.base}robot.html?scenario=${PRESET}`);
  await page.waitForFunction(() => ['ready', 'error'].includes(document.body.dataset.state), null, { timeout: 30_000 });
  assert.equal(await errorText(page), null, 'no error after loading');
  assert.equal(await page.inputValue('#planner'), 'lidar-dwa');
  await page.selectOption('#speed', '8');
  await page.click('#play');
  // Early on the symmetric scene starts a hold: its timer is drawn.
  await page.waitForFunction(
    () => (document.querySelector('#sim-canvas').dataset.lidarLayers || '').split(',').includes('hold'),
    null,
    { timeout: 60_000 },
  );
  assert.equal(await bodyData(page, 'lidar'), '1');
  assert.equal(await page.isVisible('#lidar-legend'), true, 'edge legend shown');
  // After the hold: every layer, candidates included.
  await page.waitForFunction(
    () => {
      const l = (document.querySelector('#sim-canvas').dataset.lidarLayers || '').split(',');
      return l.includes('candidates') && l.includes('temp-goal');
    },
    null,
    { timeout: 60_000 },
  );
  const layers = (await canvasData(page, 'lidarLayers')).split(',');
  for (const l of ['rays', 'edges', 'ops-raw', 'ops', 'candidates', 'temp-goal']) {
    assert.ok(layers.includes(l), `layer ${l} drawn (${layers})`);
  }
  assert.equal(await bodyData(page, 'outcome'), 'running');
  fs.mkdirSync(path.join(REPO, 'docs'), { recursive: true });
  await page.screenshot({ path: path.join(REPO, 'docs/lidar-screenshot.png') });
  // Fog of war: off by default; on, it shades the unseen part and the
  // seen count (from the core) grows as the robot drives.
  assert.equal(await canvasData(page, 'fog'), 'off');
  await page.check('#show-fog');
  await page.waitForFunction(() => document.querySelector('#sim-canvas').dataset.fog === 'on', null, { timeout: 10_000 });
  const seen1 = Number(await bodyData(page, 'seen'));
  assert.ok(seen1 > 100, `seen cells ${seen1}`);
  await page.waitForFunction((s) => Number(document.body.dataset.seen) > s, seen1, { timeout: 60_000 });
  await screenshot(page, 'lidar-01-running-fog.png');
  // Runs to the goal.
  await page.waitForFunction(() => document.body.dataset.outcome && document.body.dataset.outcome !== 'running', null, {
    timeout: 120_000,
  });
  assert.equal(await bodyData(page, 'outcome'), 'reached');
  await page.uncheck('#show-fog');
  await page.waitForFunction(() => document.querySelector('#sim-canvas').dataset.fog === 'off', null, { timeout: 10_000 });
  await page.check('#show-fog');
  await page.waitForFunction(() => document.querySelector('#sim-canvas').dataset.fog === 'on', null, { timeout: 10_000 });
  await screenshot(page, 'lidar-02-reached-fog.png');
  assert.deepEqual(problems, []);
  await page.close();
});
