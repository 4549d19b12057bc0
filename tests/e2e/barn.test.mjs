// End-to-end test of the BARN page in headless Chromium: a world and dwb
// run to the end at top speed with the outcome, T, OT and a score equal to
// the core's barnScore of them, and the costmap layer holding laser marks;
// a race of two planners ends with a results row each; a world the file
// does not hold is a one-line error. No page error, no failed request.
// Writes docs/barn-screenshot.png (mid-run) and docs/barn-race-screenshot.png.

import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import path from 'node:path';
import { REPO, startSession, watchedPage, errorText } from './harness.mjs';

let session;
before(async () => {
  session = await startSession();
});
after(async () => {
  await session?.close();
});

/** The BARN page, loaded, with console errors, page errors and failed
 *  requests collected in `problems`. */
async function openBarn(query, size = { width: 1366, height: 768 }) {
  const { page, problems } = await watchedPage(session);
  page.on('requestfailed', (r) => problems.push(`request failed: ${r.url()} ${r.failure()?.errorText ?? ''}`));
  page.on('response', (r) => {
    if (r.status() >= 400) problems.push(`HTTP ${r.status()}: ${r.url()}`);
  });
  await page.setViewportSize(size);
  await page.goto(`${session.base}barn.html${query}`);
  await page.waitForFunction(() => ['ready', 'error', 'empty'].includes(document.body.dataset.state), null, { timeout: 30_000 });
  return { page, problems };
}

const bodyData = (page, key) => page.evaluate((k) => document.body.dataset[k], key);

/** The results table's rows: planner and each cell's text and exact value. */
function results(page) {
  return page.$$eval('#results tbody tr', (rows) =>
    rows.map((tr) => {
      const out = { planner: tr.dataset.planner };
      for (const td of tr.querySelectorAll('td')) out[td.dataset.key] = { text: td.textContent, value: td.dataset.value };
      return out;
    }),
  );
}

/** Waits until every lane has ended. */
const untilDone = (page) => page.waitForFunction(() => document.body.dataset.done === 'true', null, { timeout: 120_000 });

test('world 1 with dwb runs to the end: outcome, T, OT, the core score, and laser marks in the costmap', async () => {
  const { page, problems } = await openBarn('?world=3&planner=dwb&seed=1');
  assert.equal(await errorText(page), null, 'no error after loading');
  assert.equal(await page.getAttribute('#nav-barn', 'aria-current'), 'page');
  assert.equal(await page.evaluate(() => window.planlabBarn.worldCount()), 250);
  // Choose world 1 and dwb through the controls.
  const seq = Number(await bodyData(page, 'buildSeq'));
  await page.fill('#world', '1');
  await page.dispatchEvent('#world', 'change');
  await page.waitForFunction((s) => Number(document.body.dataset.buildSeq) > s, seq);
  await page.selectOption('#planner', 'dwb');
  assert.match(await page.textContent('#planner-summary'), /\w{10,}/, 'the planner is described');
  assert.equal(await page.textContent('#world-difficulty'), (await page.textContent('#world-difficulty')).trim());
  // Before the first step nothing is known: no laser mark yet, most unseen.
  const start = await page.evaluate(() => window.planlabBarn.costmapCounts(0));
  assert.ok(start.unknown > start.free, `unseen at the start: ${JSON.stringify(start)}`);
  // Mid-run: a few seconds at 4×, then the screenshot.
  await page.check('#show-truth');
  await page.click('#play');
  await page.waitForFunction(() => Number(document.body.dataset.time) >= 3.5, null, { timeout: 60_000 });
  await page.click('#play');
  const canvas = await page.$('#lane-canvas-0');
  assert.equal(await canvas.getAttribute('data-costmap'), 'on');
  assert.equal(await canvas.getAttribute('data-truth'), 'on');
  assert.ok((await canvas.getAttribute('data-lidar-layers')) !== null);
  await page.screenshot({ path: path.join(REPO, 'docs/barn-screenshot.png') });
  // Then to the end at top speed.
  await page.click('#instant');
  await untilDone(page);
  const [row] = await results(page);
  assert.equal(row.planner, 'dwb');
  // `planlab run barn:1 --planner dwb --seed 1`: reached at 10.30 s, trace hash c2bd27030861f5a2.
  assert.equal(row.outcome.text, 'reached');
  assert.equal(row.time.text, '10.30');
  assert.equal(row.hash.text, 'c2bd27030861f5a2');
  const [t, ot, score] = [Number(row.time.value), Number(row.ot.value), Number(row.score.value)];
  assert.ok(ot > 0 && score > 0 && score <= 0.5, JSON.stringify(row));
  assert.equal(score, await page.evaluate(([a, b]) => window.planlabBarn.score(true, a, b), [t, ot]));
  // The displayed numbers give the displayed score (to its 3 decimals).
  const shown = await page.evaluate(([a, b]) => window.planlabBarn.score(true, a, b), [Number(row.time.text), Number(row.ot.text)]);
  assert.ok(Math.abs(shown - Number(row.score.text)) <= 0.0015, `${shown} vs ${row.score.text}`);
  assert.match(await page.textContent('#score-formula'), new RegExp(`= ${row.ot.text} / clip\\(${row.time.text},.*= ${row.score.text}$`));
  assert.match(await page.textContent('#status'), new RegExp(`reached · T = ${row.time.text} s · OT = ${row.ot.text} s · score ${row.score.text}`));
  const end = await page.evaluate(() => window.planlabBarn.costmapCounts(0));
  assert.ok(end.lethal > 0, `laser marks in the costmap: ${JSON.stringify(end)}`);
  assert.ok(end.inscribed > 0 && end.decay > 0, `inflated around them: ${JSON.stringify(end)}`);
  assert.ok(end.unknown < start.unknown, 'the scans have uncovered space');
  assert.deepEqual(problems, []);
  await page.close();
});

test('a race of two planners on one world ends with a results row each', async () => {
  const { page, problems } = await openBarn('?world=1&seed=1&planners=dwb,move-base-dwa', { width: 1440, height: 900 });
  assert.equal(await errorText(page), null);
  assert.equal(await page.getAttribute('#mode-race', 'aria-checked'), 'true');
  assert.equal(await page.$$eval('#lanes .lane', (l) => l.length), 2);
  await page.click('#instant');
  await untilDone(page);
  const rows = await results(page);
  assert.deepEqual(
    rows.map((r) => r.planner),
    ['dwb', 'move-base-dwa'],
  );
  for (const r of rows) {
    assert.ok(['reached', 'collision', 'timeout'].includes(r.outcome.text), JSON.stringify(r));
    const success = r.outcome.text === 'reached';
    const want = await page.evaluate(([s, a, b]) => window.planlabBarn.score(s, a, b), [success, Number(r.time.value), Number(r.ot.value)]);
    assert.equal(Number(r.score.value), want);
  }
  // The same world and seed as the single run: dwb's lane is that run.
  assert.equal(rows[0].hash.text, 'c2bd27030861f5a2');
  await page.screenshot({ path: path.join(REPO, 'docs/barn-race-screenshot.png') });
  assert.deepEqual(problems, []);
  await page.close();
});

test('a world the file does not hold, a fractional world and negative noise are one-line errors', async () => {
  const { page, problems } = await openBarn('?world=1&planner=dwb');
  await page.fill('#world', '6');
  await page.dispatchEvent('#world', 'change');
  await page.waitForFunction(() => document.body.dataset.error === 'true');
  const msg = await errorText(page);
  assert.match(msg, /BARN world 6 is not in the worlds file/);
  assert.ok(!msg.includes('\n'), msg);
  // The run on world 1 is still there.
  assert.match(await page.textContent('#status'), /World 1 /);
  await page.fill('#world', '2.5');
  await page.dispatchEvent('#world', 'change');
  assert.match(await errorText(page), /World “2.5” is not a whole number/);
  await page.fill('#world', '1');
  await page.fill('#noise', '-0.5');
  await page.dispatchEvent('#noise', 'change');
  assert.match(await errorText(page), /noise_std/);
  assert.ok(!(await errorText(page)).includes('\n'));
  assert.deepEqual(problems, []);
  await page.close();
});
