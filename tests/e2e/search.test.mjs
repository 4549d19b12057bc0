// End-to-end tests of watching the search on the grid page and of the race
// page: the A* animation passes through open and closed states (page state
// and canvas pixels at several steps) and ends with the CLI's expanded
// count, dragging the S and G markers replans, D* Lite repairs a painted
// wall with fewer expansions than a fresh A*, and the race plays 2+
// planners to a results table. The 512 × 512 animation's frame work is
// printed (measured, not asserted: timings are benchmarks, not tests).

import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import {
  REPO,
  DATA,
  startSession,
  openPage,
  screenshot,
  setEndpoints,
  chooseTool,
  afterReplan,
  cellPoint,
  dragCells,
  metric,
  pathCells,
  pixelAt,
  errorText,
  readScen,
} from './harness.mjs';

const ARENA = path.join(DATA, 'movingai/dao/arena.map');
const ROW = readScen(`${ARENA}.scen`).find((r) => r.optimal > 55);
/** A Moving AI map with rooms, where A* expands thousands of cells. */
const ARENA2 = path.join(DATA, 'movingai/dao/arena2.map');
const ROW2 = readScen(`${ARENA2}.scen`).at(-1);
const RANDOM512 = path.join(DATA, 'movingai/random/random512-10-0.map');

let session;
before(async () => {
  session = await startSession();
});
after(async () => {
  await session?.close();
});

/** The planlab CLI: PLANLAB_BIN, or a release/debug build under the repo's
 *  target/ or $CARGO_TARGET_DIR. */
function cli() {
  const dirs = [path.join(REPO, 'target'), process.env.CARGO_TARGET_DIR].filter(Boolean);
  const candidates = [process.env.PLANLAB_BIN, ...dirs.flatMap((d) => ['release', 'debug'].map((p) => path.join(d, p, 'planlab')))];
  for (const bin of candidates.filter(Boolean)) {
    if (fs.existsSync(bin) && spawnSync(bin, ['plan', '--help']).status === 0) return bin;
  }
  throw new Error('build planlab (cargo build -p planlab-cli) or set PLANLAB_BIN for the CLI comparison');
}

/** Passable cells of a Moving AI map file: `free(col, row)`. */
function movingAiFree(file) {
  const lines = fs.readFileSync(file, 'utf8').split('\n');
  const at = lines.findIndex((l) => l.trim() === 'map') + 1;
  return (c, r) => r >= 0 && c >= 0 && '.GS'.includes(lines[at + r]?.[c] ?? '@');
}

/** The first index from `from` on of a path cell with every cell within
 *  3 free: a short wall across the path there leaves a way round it. */
function openStretch(free, cells, from) {
  for (let k = from; k < cells.length - 1; k++) {
    const [c, r] = cells[k];
    let open = true;
    for (let dr = -3; dr <= 3 && open; dr++) for (let dc = -3; dc <= 3 && open; dc++) open = free(c + dc, r + dr);
    if (open) return k;
  }
  throw new Error('no open stretch on the path');
}

/** A 3-cell wall across the path at `cells[k]` (perpendicular to the step
 *  to `cells[k + 1]`), as two cell ends for dragCells. */
function wallAcross(cells, k) {
  const [c, r] = cells[k];
  const [nc, nr] = cells[k + 1];
  const [pc, pr] = nr === r ? [0, 1] : nc === c ? [1, 0] : [nc - c, -(nr - r)];
  return [[c - pc, r - pr], [c + pc, r + pr]];
}

function near(actual, expected, tol, what) {
  assert.ok(Math.abs(actual - expected) <= tol, `${what}: ${actual} not within ${tol} of ${expected}`);
}

const grid = (page, fn, ...args) => page.evaluate(([f, a]) => window.planlabGrid[f](...a), [fn, args]);

/** Canvas colour channels of a cell vs the player's colours (blended over the free cell). */
function looksOpen([r, g, b]) {
  return g > r + 25 && g > b;
}
function looksClosed([r, g, b]) {
  return b > r + 40 && b > g;
}

test('the A* search plays through open and closed states and ends with the CLI’s expanded count', async () => {
  const { page, problems } = await openPage(session);
  await afterReplan(page, () => page.setInputFiles('#file-input', ARENA2));
  await setEndpoints(page, ROW2.start, ROW2.goal);
  assert.equal(await errorText(page), null);
  const expanded = await metric(page, 'expanded');
  const events = Number(await page.getAttribute('body', 'data-search-events'));
  assert.ok(events > expanded, `events ${events} > expanded ${expanded}`);
  // Played out after a replan: the counter equals the plan's.
  assert.equal(Number(await page.getAttribute('#count-expanded', 'data-value')), expanded);

  // The CLI plans the same query natively: same expanded count and cost.
  const r = spawnSync(cli(), ['plan', ARENA2, '--start', ROW2.start.join(','), '--goal', ROW2.goal.join(','), '--algo', 'astar', '--json'], { encoding: 'utf8' });
  assert.equal(r.status, 0, r.stderr);
  const native = JSON.parse(r.stdout);
  assert.equal(native.expanded, expanded, 'page and CLI expand the same number of cells');
  assert.ok(Math.abs(native.cost - (await metric(page, 'cost'))) < 1e-9);

  // Step through: at a quarter, half and three quarters the counters grow,
  // cells expanded by then are closed, cells first opened after are unseen.
  let lastExpanded = 0;
  for (const q of [0.25, 0.5, 0.75]) {
    const k = Math.floor(events * q);
    await grid(page, 'seek', k);
    const c = await grid(page, 'counters');
    assert.equal(c.step, k);
    assert.ok(c.expanded > lastExpanded && c.expanded < expanded, `expanded ${c.expanded} at step ${k}`);
    assert.ok(c.open > 0, `open set non-empty at step ${k}`);
    lastExpanded = c.expanded;
    assert.equal(Number(await page.getAttribute('body', 'data-search-step')), k);
  }
  // A cell's state follows the steps: the 60th expanded cell is unseen
  // before it was opened, open (green) while waiting, closed (blue) after.
  const cell = await page.evaluate(() => {
    const g = window.planlabGrid;
    const n = g.counters().events;
    for (let k = 1; k <= n; k++) {
      g.seek(k);
      if (g.counters().expanded === 60) return { k };
    }
    return null;
  });
  assert.ok(cell, 'the search expands at least 60 cells');
  const [cc, cr] = await grid(page, 'current');
  const info = await grid(page, 'info', cc, cr);
  assert.equal(info.state, 'closed');
  assert.equal(info.closedAt, cell.k);
  assert.ok(info.openedAt < info.closedAt, 'opened before it was expanded');
  assert.ok(Number.isFinite(info.g) && Number.isFinite(info.h), `g ${info.g}, h ${info.h}`);
  assert.ok(Math.abs(info.f - info.g - info.h) < 1e-9);
  await grid(page, 'seek', info.openedAt - 1);
  assert.equal(await grid(page, 'cellState', cc, cr), 'unseen');
  await grid(page, 'seek', info.openedAt);
  assert.equal(await grid(page, 'cellState', cc, cr), 'open');
  // On the canvas, mid-search: an open cell is green, a closed one blue
  // (cells away from the orange marker of the cell being expanded); at the
  // end the frontier left open is still green.
  for (const step of [Math.floor(events / 2), events]) {
    await grid(page, 'seek', step);
    for (const state of ['open', 'closed']) {
      const at = await page.evaluate(
        ([want]) => {
          const g = window.planlabGrid;
          const cur = g.current();
          const cv = document.getElementById('map-canvas');
          const path = (cv.dataset.path ?? '').split(',').map(Number);
          const onPath = (c, r) => path.some((v, i) => i % 2 === 0 && Math.abs(v - c) <= 2 && Math.abs(path[i + 1] - r) <= 2);
          for (let r = 0; r < Number(document.body.dataset.mapHeight); r++) {
            for (let c = 0; c < Number(document.body.dataset.mapWidth); c++) {
              if (g.cellState(c, r) !== want) continue;
              if (cur && Math.max(Math.abs(cur[0] - c), Math.abs(cur[1] - r)) <= 3) continue;
              if (onPath(c, r)) continue;
              return [c, r];
            }
          }
          return null;
        },
        [state],
      );
      if (state === 'closed' || step < events) assert.ok(at, `an ${state} cell at step ${step}`);
      if (!at) continue;
      await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
      const px = await pixelAt(page, at[0], at[1]);
      assert.ok(state === 'open' ? looksOpen(px) : looksClosed(px), `${state} cell (${at}) at step ${step}: pixel ${px}`);
    }
  }

  // Hover shows g, h, f, parent and the steps.
  const { x, y } = await cellPoint(page, cc, cr);
  await page.mouse.move(x, y);
  const hover = await page.textContent('#hover');
  assert.match(hover, /expanded · g [\d.]+ h [\d.]+ f [\d.]+ · parent \(\d+, \d+\) · opened at step \d+ · expanded at step \d+/);

  // Play from the start: mid-animation the path is not drawn yet, the end
  // draws it and stops with the plan's expanded count.
  await page.selectOption('#speed', '1024');
  await page.click('#play');
  await page.waitForFunction((n) => Number(document.body.dataset.searchStep) > n / 3, events);
  await page.click('#play'); // pause mid-animation
  const mid = await grid(page, 'counters');
  assert.ok(mid.step < events, 'paused before the end');
  assert.equal(await page.getAttribute('#map-canvas', 'data-path-drawn'), 'false', 'no path mid-search');
  await page.screenshot({ path: path.join(REPO, 'docs/grid-search.png') });
  await page.click('#play'); // resume
  await page.waitForFunction(() => document.body.dataset.playing === 'false', null, { timeout: 30_000 });
  assert.equal(Number(await page.getAttribute('#count-expanded', 'data-value')), expanded);
  assert.deepEqual(problems, []);
  await page.close();
});

test('the path in the core’s draw list is at the plan’s cell centres, in metres, and painted there', async () => {
  const { page, problems } = await openPage(session);
  await afterReplan(page, () => page.setInputFiles('#file-input', ARENA));
  await setEndpoints(page, ROW.start, ROW.goal);
  assert.equal(await errorText(page), null);
  await page.waitForFunction(() => document.getElementById('map-canvas').dataset.pathDrawn === 'true');
  const cells = (await page.getAttribute('#map-canvas', 'data-path')).split(',').map(Number);
  const drawn = await grid(page, 'drawnPath');
  const [, h, res, ox, oy] = await grid(page, 'mapFrame');
  assert.equal(drawn.length, cells.length, 'a point per path cell');
  for (let i = 0; i < cells.length; i += 2) {
    const [c, r] = [cells[i], cells[i + 1]];
    near(drawn[i], ox + (c + 0.5) * res, 1e-9, `x of path cell ${i / 2}`);
    near(drawn[i + 1], oy + (h - r - 0.5) * res, 1e-9, `y of path cell ${i / 2}`);
  }
  // The middle of the path, away from the S and G markers, is path red.
  const k = 2 * Math.floor(cells.length / 4);
  await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
  const px = await pixelAt(page, cells[k], cells[k + 1]);
  assert.ok(px[0] > 180 && px[1] < 90 && px[2] < 120, `path cell (${cells[k]}, ${cells[k + 1]}): pixel ${px}`);
  assert.deepEqual(problems, []);
  await page.close();
});

test('dragging the start and goal markers replans', async () => {
  const { page, problems } = await openPage(session);
  await setEndpoints(page, ROW.start, ROW.goal);
  await chooseTool(page, 'wall'); // dragging a marker works with any tool
  const before = { path: await pathCells(page), expanded: await metric(page, 'expanded'), cost: await metric(page, 'cost') };
  const seq0 = Number(await page.getAttribute('body', 'data-plan-seq'));
  const dest = [ROW.start[0] + 6, ROW.start[1] - 8];
  await dragCells(page, ROW.start, dest, 12);
  assert.equal(await page.getAttribute('#map-canvas', 'data-start'), dest.join(','));
  const seq1 = Number(await page.getAttribute('body', 'data-plan-seq'));
  assert.ok(seq1 - seq0 >= 3, `replanned while dragging (${seq1 - seq0} plans)`);
  const mid = { path: await pathCells(page), expanded: await metric(page, 'expanded'), cost: await metric(page, 'cost') };
  assert.deepEqual(mid.path[0], dest);
  assert.notEqual(mid.expanded, before.expanded);
  assert.notEqual(mid.cost, before.cost);
  // No wall was painted by the drag.
  assert.ok((await pixelAt(page, ROW.start[0] + 3, ROW.start[1] - 4))[0] > 150);

  const goalDest = [ROW.goal[0] - 5, ROW.goal[1] - 6];
  await dragCells(page, ROW.goal, goalDest, 12);
  assert.equal(await page.getAttribute('#map-canvas', 'data-goal'), goalDest.join(','));
  const end = { path: await pathCells(page), expanded: await metric(page, 'expanded') };
  assert.deepEqual(end.path.at(-1), goalDest);
  assert.notEqual(end.expanded, mid.expanded);
  // The session kept its grid: no rebuild for drags.
  assert.equal(await grid(page, 'rebuilds'), 1);
  assert.deepEqual(problems, []);
  await page.close();
});

test('D* Lite repairs a painted wall with fewer expansions than a fresh A*', async () => {
  // arena2's longest query: a fresh A* expands thousands of cells, a wall
  // near the start changes the goal distances of few.
  const { page, problems } = await openPage(session);
  await afterReplan(page, () => page.setInputFiles('#file-input', ARENA2));
  await afterReplan(page, () => page.selectOption('#algorithm', 'dstar-lite'));
  await setEndpoints(page, ROW2.start, ROW2.goal);
  assert.equal(await errorText(page), null);
  near(await metric(page, 'cost'), ROW2.optimal, 1e-3, 'D* Lite cost');
  const before = await pathCells(page);
  // A wall across the far end of the path (from the goal, which D* Lite
  // searches from), where the map is open round it: only the part of its
  // search behind the wall is repaired.
  const k = openStretch(movingAiFree(ARENA2), before, Math.floor(before.length * 0.1));
  const [mc, mr] = before[k];
  await chooseTool(page, 'wall');
  // One stroke, one replan: the wall is painted as one segment.
  await dragCells(page, ...wallAcross(before, k), 1);
  assert.equal(await errorText(page), null);
  const repair = (await page.getAttribute('body', 'data-repair')).split(',').map(Number);
  assert.equal(repair.length, 2, 'a repair was reported');
  const [repaired, freshAStar] = repair;
  assert.ok(repaired > 0 && repaired < freshAStar, `repair expanded ${repaired}, a fresh A* ${freshAStar}`);
  assert.match(await page.textContent('#status'), /D\* Lite repair: [\d,]+ cells expanded \(a fresh A\*: [\d,]+\)/);
  const after = await pathCells(page);
  assert.notDeepEqual(after, before, 'the path goes round the wall');
  // The repaired path is optimal on the edited map: A*'s cost.
  const dstarCost = await metric(page, 'cost');
  await afterReplan(page, () => page.selectOption('#algorithm', 'astar'));
  near(await metric(page, 'cost'), dstarCost, 1e-9, 'repaired cost vs A* on the edited map');
  assert.equal(Number(await metric(page, 'expanded')), freshAStar, 'the fresh A* of the comparison is the A* plan');
  assert.deepEqual(problems, []);
  await page.close();
});

test('Drive: the robot follows the D* Lite path, a wall painted ahead of it is repaired with fewer expansions than a fresh A*, and it reaches the goal', async () => {
  const { page, problems } = await openPage(session);
  await afterReplan(page, () => page.setInputFiles('#file-input', ARENA2));
  await afterReplan(page, () => page.selectOption('#algorithm', 'dstar-lite'));
  await setEndpoints(page, ROW2.start, ROW2.goal);
  const first = await pathCells(page);
  await page.$eval('#drive', (b) => (b.dataset.period = '15'));
  await page.click('#drive');
  // It drives: the start moves along the path, cell by cell.
  await page.waitForFunction((s) => document.querySelector('#map-canvas').dataset.start !== s, first[0].join(','));
  await page.waitForFunction(() => Number(document.body.dataset.planSeq) > 20);
  await page.click('#drive');
  assert.equal(await page.getAttribute('body', 'data-driving'), 'false');
  const at = (await page.getAttribute('#map-canvas', 'data-start')).split(',').map(Number);
  assert.ok(first.some(([c, r]) => c === at[0] && r === at[1]), `the robot ${at} is on the first path`);
  // A wall across the path a few cells ahead of the robot, where the map
  // is open round it.
  const ahead = await pathCells(page);
  const k = openStretch(movingAiFree(ARENA2), ahead, 8);
  const [mc, mr] = ahead[k];
  await chooseTool(page, 'wall');
  await dragCells(page, ...wallAcross(ahead, k), 1);
  assert.equal(await errorText(page), null);
  const [repaired, freshAStar] = (await page.getAttribute('body', 'data-repair')).split(',').map(Number);
  assert.ok(repaired > 0 && repaired < freshAStar, `repair expanded ${repaired}, a fresh A* ${freshAStar}`);
  const around = await pathCells(page);
  assert.ok(!around.some(([c, r]) => c === mc && r === mr), 'the repaired path avoids the wall');
  await page.screenshot({ path: path.join(REPO, 'docs/grid-drive.png') });
  // Drives on round the wall to the goal; the repair's figures and its
  // search in the player stay until the next edit (each step's own repair,
  // a moved start, expands next to nothing).
  const seq = Number(await page.getAttribute('body', 'data-plan-seq'));
  const steps = await page.textContent('#count-step');
  await page.click('#drive');
  await page.waitForFunction((k) => Number(document.body.dataset.planSeq) >= k + 3, seq);
  assert.deepEqual((await page.getAttribute('body', 'data-repair')).split(',').map(Number), [repaired, freshAStar]);
  assert.match(await page.textContent('#status'), new RegExp(`D\\* Lite repair: ${repaired.toLocaleString('en-US')} cells expanded .* after the last edit`));
  assert.equal(await page.textContent('#count-step'), steps, 'the player still holds the repair');
  await page.waitForFunction(() => document.body.dataset.driving === 'false', null, { timeout: 60_000 });
  assert.equal(await page.getAttribute('#map-canvas', 'data-start'), ROW2.goal.join(','));
  assert.equal(await errorText(page), null);
  assert.deepEqual(problems, []);
  await page.close();
});

test('inflation below one cell is said on the grid page', async () => {
  // The arena preset has 1 m cells: 0.8 m of inflation grows no wall.
  const { page, problems } = await openPage(session);
  await afterReplan(page, () => page.fill('#inflate', '0.8'));
  assert.match(await page.textContent('#status'), /note: 0\.8 m inflation < 1 cell \(1 m\): no effect/);
  await afterReplan(page, () => page.fill('#inflate', '1'));
  assert.doesNotMatch(await page.textContent('#status'), /no effect/);
  assert.deepEqual(problems, []);
  await page.close();
});

test('the race plays 2+ planners to a table with winners', async () => {
  const page = await session.context.newPage();
  const problems = [];
  page.on('pageerror', (e) => problems.push(e.message));
  page.on('console', (m) => m.type() === 'error' && problems.push(m.text()));
  await page.goto(session.base + 'race.html');
  await page.waitForFunction(() => document.body.dataset.raceState === 'ready', null, { timeout: 30_000 });
  const lanes = await page.$$eval('.lane', (ls) => ls.map((l) => l.dataset.algorithm));
  assert.ok(lanes.length >= 2, `lanes ${lanes}`);
  // Before the race no lane's result is given away.
  const before = await page.$$eval('#race-table tbody tr', (trs) => trs.map((tr) => [tr.cells[4].textContent, tr.cells[5].textContent]));
  assert.ok(before.every(([c, n]) => c === '—' && n === '—'), `costs before the race: ${JSON.stringify(before)}`);
  await page.click('#race-go');
  await page.waitForFunction(() => document.body.dataset.raceState === 'racing');
  // Mid-race every lane has played the same number of events (or finished).
  await page.waitForTimeout(150);
  await screenshot(page, 'race-mid.png');
  await page.waitForFunction(() => document.body.dataset.raceState === 'finished', null, { timeout: 60_000 });
  await page.screenshot({ path: path.join(REPO, 'docs/grid-race.png') });
  await page.waitForFunction(() => document.body.dataset.raceState === 'finished', null, { timeout: 60_000 });
  const rows = await page.$$eval('#race-table tbody tr', (trs) => trs.map((tr) => Array.from(tr.cells, (td) => td.textContent)));
  assert.equal(rows.length, lanes.length);
  const byName = Object.fromEntries(rows.map((r) => [r[0], r]));
  // A* and Dijkstra: the same optimal cost, Dijkstra expands more.
  assert.equal(byName['A*'][4], byName['Dijkstra'][4]);
  assert.ok(Number(byName['Dijkstra'][1]) > Number(byName['A*'][1]));
  const winner = await page.getAttribute('#race-winner', 'data-expanded');
  assert.ok(winner && winner !== 'dijkstra', `fewest expanded: ${winner}`);
  assert.match(await page.textContent('#race-winner'), /Fewest expanded: .+ · Lowest cost: /);
  // JPS's few expansions come with its line scans, said beside them.
  if (winner.includes('jps')) assert.match(await page.textContent('#race-winner'), /line checks/);
  // A lane that needs fewer events finishes at an earlier frame.
  const frames = rows.filter((r) => r[6] !== '—').map((r) => [Number(r[3]), Number(r[6])]).sort((a, b) => a[0] - b[0]);
  assert.ok(frames.length >= 2, 'two lanes finished');
  assert.ok(frames[0][1] <= frames.at(-1)[1]);
  // Race again and Finish at once: the status says it is over.
  await page.click('#race-go');
  await page.click('#race-finish');
  assert.equal(await page.getAttribute('body', 'data-race-state'), 'finished');
  assert.doesNotMatch(await page.textContent('#status'), /Racing/);
  assert.deepEqual(problems, []);
  await page.close();
});

test('a 512 × 512 search animates (frame work printed)', async () => {
  const { page, problems } = await openPage(session);
  const row = readScen(`${RANDOM512}.scen`).at(-1);
  await afterReplan(page, () => page.setInputFiles('#file-input', RANDOM512));
  await setEndpoints(page, row.start, row.goal);
  assert.equal(await errorText(page), null);
  await page.selectOption('#speed', '256');
  await page.click('#play');
  await page.waitForFunction(() => document.body.dataset.playing === 'false', null, { timeout: 120_000 });
  const s = await grid(page, 'frameStats');
  assert.ok(s.frames > 20, `${s.frames} frames`);
  process.stderr.write(`random512 animation (256 events/frame): ${s.frames} frames, work median ${s.work.median.toFixed(2)} ms, p95 ${s.work.p95.toFixed(2)} ms, max ${s.work.max.toFixed(2)} ms; paint p95 ${s.paint.p95.toFixed(2)} ms\n`);
  assert.deepEqual(problems, []);
  await page.close();
});

test('a race with safe A* says its cost comes from other moves; Space races and F finishes', async () => {
  const page = await session.context.newPage();
  const problems = [];
  page.on('pageerror', (e) => problems.push(e.message));
  page.on('console', (m) => m.type() === 'error' && problems.push(m.text()));
  await page.goto(session.base + 'race.html');
  await page.waitForFunction(() => document.body.dataset.raceState === 'ready', null, { timeout: 30_000 });
  await page.locator('#lane-picks select').nth(3).selectOption('safe-astar');
  await page.waitForFunction(() => Array.from(document.querySelectorAll('.lane'), (l) => l.dataset.algorithm).includes('safe-astar'));
  await page.waitForFunction(() => document.body.dataset.raceState === 'ready', null, { timeout: 30_000 });
  await page.evaluate(() => document.activeElement instanceof HTMLElement && document.activeElement.blur());
  await page.keyboard.press(' ');
  await page.waitForFunction(() => document.body.dataset.raceState !== 'ready');
  await page.keyboard.press('f');
  assert.equal(await page.getAttribute('body', 'data-race-state'), 'finished');
  const text = await page.textContent('#race-winner');
  assert.match(text, /Lowest cost: /);
  assert.match(text, /Safe A\* \(Ge & Li\): 24-neighbourhood moves: not comparable with A\*/, text);
  assert.doesNotMatch(text, /A\*: .*not comparable.*A\*: /);
  assert.deepEqual(problems, []);
  await page.close();
});
