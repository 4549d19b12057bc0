// End-to-end test of the benchmark page (bench.html) in headless Chromium:
// pressing Run with the tiny size fills the planlab-vs-PathFinding.js
// table with every map (the bundled Moving AI arena, an open grid, the
// Moving AI maze); every row has both costs; planlab's cost equals the
// optimum read here from the Moving AI .scen files (or, on the open grid,
// the octile distance); PathFinding.js's cost equals planlab's on the rows
// the page marks like for like; both expanded counts and the ratios are
// finite (no block shorter than the timer's step); the DWA row's
// checksum equals the native CLI's. No timing assertions: times depend on
// the machine. The filled page fits 1366 px. No console errors. Screenshot: tests/e2e/screenshots/bench.png.

import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { DATA, REPO, SCREENSHOTS, startSession, watchedPage, readScen } from './harness.mjs';

let session;
before(async () => {
  session = await startSession();
});
after(async () => {
  await session?.close();
});

const SCEN = {
  arena: path.join(DATA, 'movingai/dao/arena.map.scen'),
  maze: path.join(DATA, 'movingai/maze/maze512-1-0.map.scen'),
};

/** The optimum of a query from the .scen itself (or the octile distance on
 *  the open grid), independent of what the page shows. */
function referenceOptimum(map, [sx, sy, gx, gy]) {
  if (map === 'open') {
    const a = Math.abs(gx - sx);
    const b = Math.abs(gy - sy);
    return Math.max(a, b) + (Math.SQRT2 - 1) * Math.min(a, b);
  }
  const row = readScen(SCEN[map]).find((r) => r.start[0] === sx && r.start[1] === sy && r.goal[0] === gx && r.goal[1] === gy);
  assert.ok(row, `${map}: (${sx}, ${sy}) → (${gx}, ${gy}) is a row of its .scen`);
  return row.optimal;
}

async function runTiny(page) {
  await page.goto(`${session.base}bench.html`);
  await page.waitForFunction(() => document.body.dataset.state !== 'loading', null, { timeout: 30_000 });
  assert.equal(await page.getAttribute('body', 'data-state'), 'ready', 'the wasm module loaded');
  await page.selectOption('#size', 'tiny');
  await page.selectOption('#reps', '1');
  await page.click('#run');
  await page.waitForFunction(() => ['done', 'error'].includes(document.body.dataset.run), null, { timeout: 120_000 });
  assert.equal(await page.isHidden('#error'), true, `no error: ${await page.textContent('#error')}`);
  assert.equal(await page.getAttribute('body', 'data-run'), 'done');
}

test('Run with the tiny size fills the table: optimal planlab costs, equal PathFinding.js costs, finite ratios, the DWA row', async () => {
  const { page, problems } = await watchedPage(session);
  await page.setViewportSize({ width: 1366, height: 768 });
  await runTiny(page);

  const rows = await page.$$eval('#astar-rows tr', (trs) => trs.map((tr) => ({ ...tr.dataset, cells: tr.cells.length })));
  // tiny: 3 arena rows, 2 open-grid queries, 2 maze rows.
  const count = (m) => rows.filter((r) => r.map === m).length;
  assert.deepEqual({ arena: count('arena'), open: count('open'), maze: count('maze') }, { arena: 3, open: 2, maze: 2 });
  for (const r of rows) {
    const q = r.query.split(',').map(Number);
    const label = `${r.map} ${r.query}`;
    assert.equal(r.cells, 12, `${label}: every column filled`);
    for (const k of ['planlabExpanded', 'pfExpanded']) {
      assert.ok(Number.isInteger(Number(r[k])) && Number(r[k]) > 0, `${label}: ${k} ${r[k]}`);
    }
    const planlab = Number(r.planlabCost);
    const pf = Number(r.pfCost);
    assert.ok(Number.isFinite(planlab) && planlab > 0, `${label}: planlab cost ${r.planlabCost}`);
    assert.ok(Number.isFinite(pf) && pf > 0, `${label}: PathFinding.js cost ${r.pfCost}`);
    // Every row here has an optimum; the page's must be the file's, and
    // planlab's cost must equal it (.scen optima are printed to 5+ decimals).
    const opt = referenceOptimum(r.map, q);
    assert.ok(r.optimal !== undefined, `${label}: marked with an optimum`);
    assert.ok(Math.abs(Number(r.optimal) - opt) < 1e-9, `${label}: page optimum ${r.optimal} != ${opt}`);
    assert.ok(Math.abs(planlab - opt) <= 1e-4, `${label}: planlab cost ${planlab} != optimum ${opt}`);
    // Both libraries use the no-corner-cutting rule, so the costs agree.
    assert.equal(r.likeForLike, 'true', `${label}: like for like`);
    assert.ok(Math.abs(pf - planlab) <= 1e-9 * planlab, `${label}: PathFinding.js ${pf} != planlab ${planlab}`);
    const ratio = Number(r.ratio);
    assert.ok(Number.isFinite(ratio) && ratio > 0, `${label}: ratio ${r.ratio}`);
  }

  // The page says which rule each library uses, and what the times are.
  const env = await page.textContent('#env');
  assert.match(env, /OnlyWhenNoObstacles/);
  assert.match(env, /no_corner_cutting/);
  assert.match(env, /medians of this run/);
  assert.match(env, /logical CPUs/);
  assert.match(await page.textContent('#astar-foot'), /equals the optimum on 7 of 7 rows/);

  // The DWA step: one row, a positive time, the native CLI's checksum.
  const dwa = await page.$$eval('#dwa-rows tr', (trs) => trs.map((tr) => ({ ...tr.dataset })));
  assert.equal(dwa.length, 1);
  assert.ok(Number(dwa[0].msPerStep) > 0 && Number.isFinite(Number(dwa[0].msPerStep)), `DWA ms/step ${dwa[0].msPerStep}`);
  const cli = path.join(REPO, 'target/release/planlab');
  assert.ok(fs.existsSync(cli), 'target/release/planlab is built (cargo build --release -p planlab-cli)');
  const out = spawnSync(cli, ['bench', 'step', '--steps', '40', '--blocks', '1'], { encoding: 'utf8' });
  assert.equal(out.status, 0, out.stderr);
  const native = JSON.parse(out.stdout.trim().split('\n').pop());
  assert.equal(Number(dwa[0].checksum), native.checksum, 'DWA checksum wasm = native');

  assert.match(await page.textContent('#progress'), /^Done in/);
  // The filled tables fit a laptop's window: no sideways scrolling.
  const overflow = await page.evaluate(() => document.documentElement.scrollWidth - window.innerWidth);
  assert.ok(overflow <= 1, `page ${overflow} px wider than the window at 1366`);
  fs.mkdirSync(SCREENSHOTS, { recursive: true });
  await page.screenshot({ path: path.join(SCREENSHOTS, 'bench.png'), fullPage: true });
  assert.deepEqual(problems, []);
});
