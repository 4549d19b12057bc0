// End-to-end tests of the compare page in headless Chromium: a preset and
// two planners picked with real clicks run together; the table has a column
// per planner whose values are the native CLI's (`planlab run SCEN
// --planner P --json`, run from the test), the winner marks follow the
// rules, both views draw, the CSV copy has the same numbers; the robot
// page's link and URL parameters open a comparison; bad input (a fifth
// planner, one planner, unknown names, a broken file) is refused with a
// hint or the error banner, never an exception.

import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { REPO, startSession, screenshot, errorText } from './harness.mjs';

const TRAP = 'T-fig3-2.json';

/** The native CLI: the release build when there is one (scripts/build.sh), else the debug one. */
const CLI = ['release', 'debug'].map((p) => path.join(REPO, 'target', p, 'planlab')).find((p) => fs.existsSync(p));

let session;
before(async () => {
  session = await startSession();
});
after(async () => {
  await session?.close();
});

/** `planlab run SCEN --planner P [--set path=value]… --json`. */
function cli(file, planner, set = []) {
  assert.ok(CLI, 'build the CLI first (cargo build -p planlab-cli)');
  const edits = set.flatMap((e) => ['--set', e]);
  const run = spawnSync(CLI, ['run', path.join(REPO, 'assets/scenarios', file), '--planner', planner, ...edits, '--json'], {
    encoding: 'utf8',
    timeout: 120_000,
  });
  assert.equal(run.status, 0, run.stderr);
  return JSON.parse(run.stdout);
}

async function openCompare(query = '') {
  const page = await session.context.newPage();
  const problems = [];
  page.on('console', (m) => {
    if (m.type() === 'error') problems.push(`console.error: ${m.text()}`);
  });
  page.on('pageerror', (e) => problems.push(`pageerror: ${e.message}`));
  await page.goto(`${session.base}compare.html${query}`);
  await waitBuilt(page);
  return { page, problems };
}

async function waitBuilt(page) {
  await page.waitForFunction(() => Number(document.body.dataset.buildSeq) > 0 || document.body.dataset.state === 'error', null, {
    timeout: 30_000,
  });
}

/** Runs `action` and waits until the page rebuilt its planners after it. */
async function afterRebuild(page, action) {
  const before = await page.evaluate(() => Number(document.body.dataset.buildSeq ?? 0));
  await action();
  await page.waitForFunction((s) => Number(document.body.dataset.buildSeq) > s, before, { timeout: 30_000 });
}

const hooks = (page, fn) => page.evaluate((f) => window.planlabCompare[f](), fn);
const bodyData = (page, key) => page.evaluate((k) => document.body.dataset[k], key);

async function waitDone(page, timeout = 180_000) {
  await page.waitForFunction(() => document.body.dataset.done === 'true', null, { timeout });
}

/** Picks exactly `names` in the planner list by clicking the checkboxes. */
async function pickPlanners(page, names) {
  for (const n of await hooks(page, 'chosen')) {
    if (!names.includes(n)) await afterRebuild(page, () => page.click(`#pick-${n}`));
  }
  for (const n of names) {
    if (!(await page.isChecked(`#pick-${n}`))) await afterRebuild(page, () => page.click(`#pick-${n}`));
  }
  assert.deepEqual((await hooks(page, 'chosen')).sort(), [...names].sort());
}

/** The table: planner columns, and per metric row the cells' values and winner flags. */
async function readTable(page) {
  return page.evaluate(() => {
    const t = document.getElementById('metrics-table');
    const cols = Array.from(t.querySelectorAll('thead th[data-planner]')).map((th) => th.dataset.planner);
    const rows = {};
    for (const tr of t.querySelectorAll('tbody tr')) {
      rows[tr.dataset.metric] = Array.from(tr.querySelectorAll('td')).map((td) => ({
        planner: td.dataset.planner,
        value: td.dataset.value,
        text: td.textContent,
        win: td.dataset.win === 'true',
      }));
    }
    return { cols, rows, final: t.dataset.final === 'true' };
  });
}

/** Pixel statistics of a canvas: distinct colours and pixels near each given RGB. */
async function canvasStats(page, selector, rgbs = []) {
  return page.evaluate(
    ([sel, cols]) => {
      const cv = document.querySelector(sel);
      const d = cv.getContext('2d').getImageData(0, 0, cv.width, cv.height).data;
      const distinct = new Set();
      const near = cols.map(() => 0);
      for (let i = 0; i < d.length; i += 4) {
        if (distinct.size < 5000) distinct.add((d[i] << 16) | (d[i + 1] << 8) | d[i + 2]);
        cols.forEach((c, k) => {
          if (Math.abs(d[i] - c[0]) + Math.abs(d[i + 1] - c[1]) + Math.abs(d[i + 2] - c[2]) < 24) near[k] += 1;
        });
      }
      return { width: cv.width, height: cv.height, distinct: distinct.size, near };
    },
    [selector, rgbs],
  );
}

const METRIC_KEYS = [
  'time_s',
  'path_length_m',
  'min_clearance_m',
  'mean_clearance_m',
  'total_turn_rad',
  'max_turn_rad',
  'speed_drops',
  'temp_goal_switches',
  'mean_tracking_error_m',
  'max_tracking_error_m',
  'tracking_error_var_m2',
  'load_ok_share',
];

/**
 * Winners of a row by the rules the page states, from the CLI's numbers:
 * values compared as shown (rounded to the table's digits); fewer than two
 * values → no winner; time and length only among planners that reached,
 * the other rows too when any planner reached.
 */
function expectedWinners(key, natives) {
  const digits = { time_s: 2, speed_drops: 0, temp_goal_switches: 0, tracking_error_var_m2: 4, load_ok_share: 1 }[key] ?? 3;
  const scale = key === 'load_ok_share' ? 100 : 1;
  const higher = ['min_clearance_m', 'mean_clearance_m', 'load_ok_share'].includes(key);
  const reachedOnly = ['time_s', 'path_length_m'].includes(key);
  const names = Object.keys(natives);
  if (key === 'outcome') return names.filter((n) => natives[n].outcome === 'reached');
  const shown = Object.fromEntries(names.map((n) => [n, natives[n][key] === null ? null : Number((natives[n][key] * scale).toFixed(digits))]));
  if (names.filter((n) => shown[n] !== null).length < 2) return [];
  const anyReached = names.some((n) => natives[n].outcome === 'reached');
  const competes = (n) => natives[n].outcome === 'reached' || (!reachedOnly && !anyReached);
  const eligible = names.filter((n) => shown[n] !== null && competes(n));
  if (!eligible.length) return [];
  const best = (higher ? Math.max : Math.min)(...eligible.map((n) => shown[n]));
  return eligible.filter((n) => shown[n] === best);
}

function checkTable(table, natives, file) {
  const names = Object.keys(natives);
  assert.deepEqual([...table.cols].sort(), [...names].sort(), 'one column per planner');
  assert.ok(table.final, 'winners marked once every planner finished');
  for (const key of ['outcome', ...METRIC_KEYS]) {
    const cells = table.rows[key];
    assert.ok(cells, `row ${key}`);
    for (const c of cells) {
      const native = natives[c.planner][key];
      if (key === 'outcome') assert.equal(c.value, native, `${file} ${c.planner} outcome`);
      else if (native === null) assert.equal(c.text, 'n/a', `${file} ${c.planner} ${key}`);
      else assert.equal(Number(c.value), native, `${file} ${c.planner} ${key}: page ${c.value}, CLI ${native}`);
    }
    const got = cells.filter((c) => c.win).map((c) => c.planner).sort();
    assert.deepEqual(got, expectedWinners(key, natives).sort(), `${file}: winners of ${key}`);
  }
  for (const c of table.rows.trace_hash) assert.equal(c.value, natives[c.planner].trace_hash, `${file} ${c.planner} trace hash`);
  for (const c of table.rows.steps) assert.equal(Number(c.value), natives[c.planner].steps, `${file} ${c.planner} steps`);
}

test('compare dwa and improved-dwa on the C-shaped trap: same numbers as the CLI, winners marked, both views drawn', async () => {
  const natives = { dwa: cli(TRAP, 'dwa'), 'improved-dwa': cli(TRAP, 'improved-dwa') };
  // The paper's point ([T] Fig 3-2): plain DWA is trapped, the fusion gets through.
  assert.notEqual(natives.dwa.outcome, 'reached');
  assert.equal(natives['improved-dwa'].outcome, 'reached');

  const { page, problems } = await openCompare();
  assert.equal(await page.getAttribute('#nav-compare', 'aria-current'), 'page');
  await afterRebuild(page, () => page.selectOption('#preset', TRAP));
  await pickPlanners(page, ['dwa', 'improved-dwa']);
  assert.equal(await bodyData(page, 'lanes'), '2');
  assert.equal(await page.isDisabled('#play'), false);
  assert.equal(new URL(page.url()).searchParams.get('planners'), 'dwa,improved-dwa', 'the URL names the comparison');

  // Step: one control step for each planner.
  await page.click('#step');
  assert.deepEqual(await page.$$eval('.lane .lane-state', (els) => els.map((e) => e.textContent)), ['t = 0.1 s', 't = 0.1 s']);
  // Side by side, played in real time at 16×: both robots move together.
  await page.click('#view-side');
  await page.selectOption('#speed', '16');
  await page.click('#play');
  await page.waitForFunction(() => Number(document.body.dataset.time) >= 3, null, { timeout: 60_000 });
  const times = await page.$$eval('.lane .lane-state', (els) => els.map((e) => e.textContent));
  assert.equal(times.length, 2);
  assert.equal(times[0], times[1], `time-synchronised: ${times}`);
  await screenshot(page, 'compare-01-side-running.png');
  await waitDone(page);
  const fs16 = await hooks(page, 'frameStats');
  console.log(`frame work at 16×, ${TRAP}, dwa + improved-dwa: ${fs16.frames} frames, median ${fs16.median.toFixed(2)} ms, p95 ${fs16.p95.toFixed(2)} ms, max ${fs16.max.toFixed(2)} ms`);
  assert.ok(fs16.frames > 10, 'played frame by frame');
  let table = await readTable(page);
  checkTable(table, natives, TRAP);
  // Spelled out: the trapped DWA turned less (it drove almost straight into
  // the C) but did not arrive, so the planner that reached the goal wins
  // every row it has a value in; the tracking error is improved-dwa's alone (no global path
  // for DWA), so nobody wins it.
  const winnersOf = (key) => table.rows[key].filter((c) => c.win).map((c) => c.planner);
  for (const key of ['outcome', 'time_s', 'path_length_m', 'min_clearance_m', 'total_turn_rad', 'temp_goal_switches']) {
    assert.deepEqual(winnersOf(key), ['improved-dwa'], key);
  }
  assert.ok(natives.dwa.total_turn_rad < natives['improved-dwa'].total_turn_rad, 'the loser has the smaller turning, and still does not win it');
  assert.deepEqual(winnersOf('mean_tracking_error_m'), []);
  assert.equal(table.rows.mean_tracking_error_m.find((c) => c.planner === 'dwa').text, 'n/a');
  // The page's own hashes are the CLI's: same trajectories, not only same summaries.
  const hashes = await hooks(page, 'hashes');
  for (const n of Object.keys(natives)) assert.equal(BigInt(hashes[n]).toString(16).padStart(16, '0'), natives[n].trace_hash, n);
  for (const i of [0, 1]) {
    const s = await canvasStats(page, `#lane-canvas-${i}`, [[14, 165, 233]]);
    assert.ok(s.width > 200 && s.height > 100, `lane ${i} canvas size ${s.width}×${s.height}`);
    assert.ok(s.distinct > 20, `lane ${i} canvas drawn (${s.distinct} colours)`);
    assert.ok(s.near[0] > 30, `lane ${i} trail drawn (${s.near[0]} px)`);
  }
  await screenshot(page, 'compare-02-side-done.png');

  // The wheel zooms both lanes together; a double click fits them again.
  const scales = () => page.$$eval('.lane-canvas', (cs) => cs.map((c) => Number(c.dataset.scale)));
  const fitted = await scales();
  const box = await page.locator('#lane-canvas-0').boundingBox();
  await page.mouse.move(box.x + box.width / 2, box.y + box.height / 2);
  await page.mouse.wheel(0, -300);
  // Input events reach the page asynchronously: wait for the zoom to land.
  await page.waitForFunction((f) => Number(document.getElementById('lane-canvas-0').dataset.scale) > f * 1.2, fitted[0]);
  const zoomed = await scales();
  assert.ok(zoomed[0] > fitted[0] * 1.2, `zoomed in: ${fitted} → ${zoomed}`);
  assert.equal(zoomed[1], zoomed[0], 'both lanes at the same zoom');
  await page.mouse.dblclick(box.x + box.width / 2, box.y + box.height / 2);
  await page.waitForFunction((f) => Number(document.getElementById('lane-canvas-0').dataset.scale) === f, fitted[0]);
  assert.deepEqual(await scales(), fitted);

  // The table as CSV on the clipboard: the CLI's numbers and the winners.
  await session.context.grantPermissions(['clipboard-read', 'clipboard-write'], { origin: new URL(session.base).origin });
  await page.click('#copy-csv');
  await page.waitForFunction(() => Number(document.body.dataset.copied) > 0);
  const csv = await page.evaluate(() => navigator.clipboard.readText());
  const lines = csv.trim().split('\n').map((l) => l.split(','));
  assert.deepEqual(lines[0], ['metric', 'unit', 'dwa', 'improved-dwa', 'winner']);
  const byKey = Object.fromEntries(lines.slice(1).map((l) => [l[0], l]));
  for (const key of ['time_s', 'path_length_m', 'min_clearance_m', 'total_turn_rad', 'speed_drops', 'mean_tracking_error_m']) {
    for (const [i, n] of ['dwa', 'improved-dwa'].entries()) {
      const native = natives[n][key];
      assert.equal(byKey[key][2 + i], native === null ? '' : String(native), `CSV ${key} ${n}`);
    }
  }
  assert.equal(byKey.outcome[4], 'improved-dwa');
  assert.equal(byKey.trace_hash[3], natives['improved-dwa'].trace_hash);
  assert.match(await page.textContent('#csv-status'), /Copied 15 rows/);

  // Overlaid: one canvas, each planner's trail in its colour, a legend.
  await page.click('#view-overlay');
  await page.waitForFunction(() => document.getElementById('overlay-canvas').getBoundingClientRect().width > 200);
  await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
  const colours = await page.$$eval('#overlay-legend li i', (is) => is.map((i) => getComputedStyle(i).backgroundColor));
  assert.equal(colours.length, 2, 'legend: one entry per planner');
  const rgb = colours.map((c) => c.match(/\d+/g).slice(0, 3).map(Number));
  const o = await canvasStats(page, '#overlay-canvas', rgb);
  assert.ok(o.distinct > 20, `overlay drawn (${o.distinct} colours)`);
  for (const i of [0, 1]) assert.ok(o.near[i] > 30, `overlay: planner ${i} trail in its colour (${o.near[i]} px)`);
  assert.equal(new URL(page.url()).searchParams.get('view'), 'overlay');
  await screenshot(page, 'compare-03-overlay-done.png');

  // Reset and run to the end at once: the same episodes again.
  await afterRebuild(page, () => page.click('#reset'));
  assert.equal(await page.$eval('#metrics-table', (t) => t.dataset.final), 'false');
  await page.click('#instant');
  await waitDone(page);
  table = await readTable(page);
  checkTable(table, natives, `${TRAP} (run to end)`);
  const steps = natives.dwa.steps + natives['improved-dwa'].steps;
  console.log(`run to end instantly, ${TRAP}, dwa + improved-dwa: ${steps} control steps in ${await bodyData(page, 'instantMs')} ms (wall time, paints included)`);
  assert.equal(await errorText(page), null);
  assert.deepEqual(problems, []);
  await page.close();
});

test('the robot page links to the comparison; URL parameters pick the scenario, planners, view and autorun', async () => {
  const page = await session.context.newPage();
  const problems = [];
  page.on('console', (m) => m.type() === 'error' && problems.push(m.text()));
  page.on('pageerror', (e) => problems.push(e.message));
  await page.goto(`${session.base}robot.html?scenario=${TRAP}`);
  await page.waitForFunction(() => document.body.dataset.state === 'ready', null, { timeout: 30_000 });
  await page.locator('#compare-link').scrollIntoViewIfNeeded();
  await screenshot(page, 'compare-00-robot-link.png');
  await Promise.all([page.waitForURL(/compare\.html/), page.click('#compare-link')]);
  await waitBuilt(page);
  const q = new URL(page.url()).searchParams;
  assert.equal(q.get('scenario'), TRAP);
  assert.equal(await page.inputValue('#preset'), TRAP);
  // T-fig3-2 runs improved-dwa: it is compared with the baseline.
  assert.deepEqual(await hooks(page, 'chosen'), ['improved-dwa', 'dwa']);
  assert.equal(await bodyData(page, 'lanes'), '2');

  // From a run link with edits (as the gallery opens them): the edits go along.
  await page.goto(`${session.base}robot.html?scenario=dwa-demo.json&planner=improved-dwa&set=${encodeURIComponent('movers=[]')}`);
  await page.waitForFunction(() => document.body.dataset.state === 'ready', null, { timeout: 30_000 });
  await Promise.all([page.waitForURL(/compare\.html/), page.click('#compare-link')]);
  await waitBuilt(page);
  assert.deepEqual(await hooks(page, 'chosen'), ['improved-dwa', 'dwa']);
  assert.equal(await page.textContent('#edits'), 'movers=[]');

  // A link such as the gallery's: four planners, overlaid, run to the end at once.
  const four = ['dwa', 'improved-dwa', 'fusion-53', 'pursuit'];
  await page.goto(`${session.base}compare.html?scenario=dwa-demo.json&planners=${four.join(',')}&view=overlay&autorun=instant`);
  await waitDone(page);
  assert.equal(await bodyData(page, 'view'), 'overlay');
  const table = await readTable(page);
  const natives = Object.fromEntries(four.map((n) => [n, cli('dwa-demo.json', n)]));
  checkTable(table, natives, 'dwa-demo.json');
  const steps = four.reduce((a, n) => a + natives[n].steps, 0);
  console.log(`run to end instantly, dwa-demo.json, ${four.join(' + ')}: ${steps} control steps in ${await bodyData(page, 'instantMs')} ms (wall time, paints included)`);
  // The fifth checkbox cannot be ticked while four are picked.
  assert.equal(await page.isDisabled('#pick-safe-dual-dwa'), true);
  await screenshot(page, 'compare-04-four-overlaid.png');
  // V switches to side by side: four canvases, each drawn.
  await page.keyboard.press('v');
  assert.equal(await bodyData(page, 'view'), 'side');
  await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
  for (const i of [0, 1, 2, 3]) assert.ok((await canvasStats(page, `#lane-canvas-${i}`)).distinct > 20, `lane ${i} drawn`);
  await screenshot(page, 'compare-06-four-side.png');
  // The help overlay (shared shell) describes the page.
  await page.keyboard.press('?');
  await page.waitForFunction(() => document.body.dataset.help === 'open');
  assert.match(await page.textContent('#help'), /run to the end instantly/);
  await page.keyboard.press('Escape');

  // Nobody reaches the goal: no winner for the outcome, time and length;
  // the other rows compare every planner.
  await page.goto(`${session.base}compare.html?scenario=${TRAP}&planners=dwa,apf&autorun=instant`);
  await waitDone(page);
  const stuck = { dwa: cli(TRAP, 'dwa'), apf: cli(TRAP, 'apf') };
  assert.ok(Object.values(stuck).every((n) => n.outcome !== 'reached'), 'neither reaches the goal');
  const none = await readTable(page);
  checkTable(none, stuck, `${TRAP} (dwa, apf)`);
  for (const key of ['outcome', 'time_s', 'path_length_m']) assert.ok(none.rows[key].every((c) => !c.win), `no winner of ${key}`);
  assert.ok(none.rows.min_clearance_m.some((c) => c.win), 'clearance still compared');

  // Edits in the URL (as `planlab run --set`): every planner runs the edited scenario.
  const set = ['movers=[]', 'sim.max_time=40'];
  const withSet = new URLSearchParams({ scenario: 'dwa-demo.json', planners: 'dwa,improved-dwa', autorun: 'instant' });
  for (const e of set) withSet.append('set', e);
  await page.goto(`${session.base}compare.html?${withSet}`);
  await waitDone(page);
  assert.equal(await page.textContent('#edits'), set.join(', '));
  const edited = { dwa: cli('dwa-demo.json', 'dwa', set), 'improved-dwa': cli('dwa-demo.json', 'improved-dwa', set) };
  assert.notEqual(edited.dwa.trace_hash, natives.dwa.trace_hash, 'the edits change the episode');
  checkTable(await readTable(page), edited, 'dwa-demo.json with edits');
  assert.deepEqual(new URL(page.url()).searchParams.getAll('set'), set, 'the URL keeps the edits');
  // Another preset drops them.
  await afterRebuild(page, () => page.selectOption('#preset', TRAP));
  assert.equal(await page.textContent('#edits'), '—');
  assert.deepEqual(new URL(page.url()).searchParams.getAll('set'), []);

  // autorun=1 plays in real time at the speed given; the result is the same.
  await page.goto(`${session.base}compare.html?scenario=${TRAP}&planners=dwa,improved-dwa&speed=16&autorun=1`);
  await page.waitForFunction(() => document.body.dataset.playing === 'true', null, { timeout: 30_000 });
  assert.equal(await page.inputValue('#speed'), '16');
  await waitDone(page);
  const trap = await readTable(page);
  checkTable(trap, { dwa: cli(TRAP, 'dwa'), 'improved-dwa': cli(TRAP, 'improved-dwa') }, `${TRAP} (autorun)`);
  assert.equal(await errorText(page), null);
  assert.deepEqual(problems, []);
  await page.close();
});

test('bad input: a fifth planner, a single one, unknown names and a broken file are refused without exceptions', async () => {
  const five = ['dwa', 'improved-dwa', 'fusion-53', 'pursuit', 'safe-dual-dwa'];
  const { page, problems } = await openCompare(`?scenario=dwa-demo.json&planners=${five.join(',')}`);
  assert.match((await errorText(page)) ?? '', /at most 4 planners/);
  assert.deepEqual(await hooks(page, 'chosen'), five.slice(0, 4));
  assert.equal(await bodyData(page, 'lanes'), '4');
  // A real click on the disabled fifth box does nothing.
  await page.click('#pick-safe-dual-dwa', { force: true });
  assert.equal(await page.isChecked('#pick-safe-dual-dwa'), false);
  assert.equal((await hooks(page, 'chosen')).length, 4);
  // Down to one planner: a hint, nothing to run.
  for (const n of ['improved-dwa', 'fusion-53', 'pursuit']) await afterRebuild(page, () => page.click(`#pick-${n}`));
  assert.deepEqual(await hooks(page, 'chosen'), ['dwa']);
  assert.equal(await page.getAttribute('#planner-hint', 'data-warn'), 'true');
  assert.match(await page.textContent('#planner-hint'), /at least one more planner/);
  assert.equal(await page.isDisabled('#play'), true);
  assert.equal(await page.isDisabled('#instant'), true);
  await page.keyboard.press('Space');
  assert.equal(await bodyData(page, 'playing'), 'false');
  await screenshot(page, 'compare-05-one-planner.png');

  // A broken scenario file: the banner names it, the comparison stays.
  const broken = path.join(REPO, 'target', 'compare-broken.json');
  fs.writeFileSync(broken, '{"version": 1, "map": {"width": 3');
  await page.setInputFiles('#file-input', broken);
  await page.waitForFunction(() => document.body.dataset.error === 'true');
  assert.match((await errorText(page)) ?? '', /compare-broken\.json/);
  assert.equal(await page.inputValue('#preset'), 'dwa-demo.json');
  fs.rmSync(broken, { force: true });
  // A good file opens: the comparison moves to it.
  await afterRebuild(page, () => page.setInputFiles('#file-input', path.join(REPO, 'assets/scenarios', TRAP)));
  assert.equal(await errorText(page), null);
  assert.equal(await page.inputValue('#preset'), '');
  assert.match(await page.textContent('#scenario-description'), /C-shaped wall/);

  // An edit that breaks the scenario is reported and left out.
  await page.goto(`${session.base}compare.html?scenario=dwa-demo.json&planners=dwa,pursuit&set=${encodeURIComponent('sim.dt=-1')}`);
  await waitBuilt(page);
  assert.match((await errorText(page)) ?? '', /edits sim\.dt=-1 not applied/);
  assert.equal(await page.textContent('#edits'), '—');
  assert.equal(await bodyData(page, 'lanes'), '2');

  // Unknown planner names in the URL: reported, the known ones kept.
  await page.goto(`${session.base}compare.html?scenario=nope.json&planners=dwa,warp-drive,improved-dwa`);
  await waitBuilt(page);
  const err = (await errorText(page)) ?? '';
  assert.match(err, /unknown planner “warp-drive”/);
  assert.match(err, /no preset “nope.json”/);
  assert.deepEqual(await hooks(page, 'chosen'), ['dwa', 'improved-dwa']);
  assert.equal(await page.isDisabled('#play'), false);
  assert.deepEqual(problems, []);
  await page.close();
});
