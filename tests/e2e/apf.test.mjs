// End-to-end test of the potential-field page in headless Chromium: the
// T-fig4-6 preset runs to the goal with the sampling APF (path drawn,
// metrics from the core), the basic APF ends stuck on the same scene, a
// goal dropped inside the disc is refused in the message bar, and there
// are no console errors. Also writes docs/apf-screenshot.png.

import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import path from 'node:path';
import { REPO, startSession, errorText } from './harness.mjs';

let session;
before(async () => {
  session = await startSession();
});
after(async () => {
  await session?.close();
});

const metric = async (page, name) => page.getAttribute(`#metric-${name}`, 'data-value');

async function runToEnd(page) {
  await page.click('#play');
  await page.waitForFunction(() => document.body.dataset.outcome && document.body.dataset.outcome !== 'running', null, {
    timeout: 60_000,
  });
  return page.evaluate(() => document.body.dataset.outcome);
}

test('T-fig4-6: sampling APF reaches the goal, basic APF is stuck', async () => {
  const page = await session.context.newPage();
  const problems = [];
  page.on('console', (m) => {
    if (m.type() === 'error') problems.push(`console.error: ${m.text()}`);
  });
  page.on('pageerror', (e) => problems.push(`pageerror: ${e.message}`));
  await page.goto(`${session.base}apf.html?scenario=T-fig4-6.json&mode=sampling-prediction`);
  await page.waitForFunction(() => ['ready', 'error'].includes(document.body.dataset.state), null, { timeout: 30_000 });
  assert.equal(await errorText(page), null);
  assert.equal(await page.getAttribute('#nav-apf', 'aria-current'), 'page');
  assert.equal(await runToEnd(page), 'reached');
  assert.equal(await metric(page, 'outcome'), 'reached');
  const points = Number(await metric(page, 'points'));
  const length = Number(await metric(page, 'length'));
  assert.ok(points > 20, `path points ${points}`);
  assert.equal(Number(await page.evaluate(() => document.body.dataset.pathPoints)), points, 'drawn path = metric');
  assert.ok(length > 1.0 && length < 1.4, `path length ${length}`);
  assert.ok(Number(await metric(page, 'min')) > 0, 'kept off the disc');
  await page.screenshot({ path: path.join(REPO, 'docs/apf-screenshot.png') });
  // The canvas shows the draw list's start (sky) and goal (red) markers
  // where the list puts them.
  for (const [tag, want] of [
    [0, [56, 189, 248]],
    [1, [239, 68, 68]],
  ]) {
    const px = await page.evaluate((t) => {
      const a = window.planlabApf;
      const [x, y] = a.goal(t);
      const [cx, cy] = a.toCanvas(x, y);
      return Array.from(document.getElementById('view').getContext('2d').getImageData(Math.round(cx), Math.round(cy), 1, 1).data);
    }, tag);
    assert.ok(want.every((v, i) => Math.abs(px[i] - v) < 40), `marker ${tag}: pixel ${px}, want ${want}`);
  }

  await page.selectOption('#mode', 'basic');
  assert.equal(await runToEnd(page), 'stuck');

  // The goal inside the disc (centre of the map's obstacle) is refused.
  const box = await page.locator('#view').boundingBox();
  const [x0, y0, x1, y1] = await page.evaluate(() => [-0.2, -0.6, 1.4, 0.6]);
  const c = { w: 800, h: 600 };
  const s = Math.min(c.w / (x1 - x0), c.h / (y1 - y0));
  const px = (c.w - s * (x1 - x0)) / 2 + (0.5 - x0) * s;
  const py = c.h - (c.h - s * (y1 - y0)) / 2 - (0.0 - y0) * s;
  await page.mouse.click(box.x + (px / c.w) * box.width, box.y + (py / c.h) * box.height);
  const err = await errorText(page);
  assert.ok(err && err.includes('inside obstacle'), `error ${err}`);
  assert.deepEqual(problems, []);
  await page.close();
});
