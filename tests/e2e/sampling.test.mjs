// End-to-end tests of the sampling planners on the grid and race pages:
// choosing RRT* on the arena preset grows a tree that the player shows
// event by event with the search player's controls, the best-cost plot
// never goes up, the cost shown is the CLI's for the same map, cells,
// seed and iterations (the built binary is run), a budget in milliseconds
// stops and is reproduced by the CLI with the iterations it reached, bad
// input is one line, and the race plays RRT-Connect beside A*.
// Writes docs/sampling-tree-screenshot.png (the tree mid-growth).

import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { REPO, startSession, openPage, afterReplan, clickCell, chooseTool, errorText } from './harness.mjs';

let session;
before(async () => {
  session = await startSession();
});
after(async () => {
  await session?.close();
});

/** The arena preset's endpoints (shell/grid-maps.ts). */
const START = [1, 45];
const GOAL = [47, 9];
const ARENA = path.join(REPO, 'assets/maps/arena.map');

/** The planlab CLI: PLANLAB_BIN, or a release/debug build under target/. */
function cli() {
  const dirs = [path.join(REPO, 'target'), process.env.CARGO_TARGET_DIR].filter(Boolean);
  const candidates = [process.env.PLANLAB_BIN, ...dirs.flatMap((d) => ['release', 'debug'].map((p) => path.join(d, p, 'planlab')))];
  for (const bin of candidates.filter(Boolean)) {
    if (fs.existsSync(bin) && spawnSync(bin, ['plan', '--help']).status === 0) return bin;
  }
  throw new Error('build planlab (cargo build -p planlab-cli) or set PLANLAB_BIN for the CLI comparison');
}

/** `planlab plan` with `args` (--json added), parsed. */
function cliPlan(args) {
  const r = spawnSync(cli(), ['plan', ...args, '--json'], { cwd: REPO, encoding: 'utf8', timeout: 120_000 });
  assert.equal(r.status, 0, `planlab plan ${args.join(' ')}: ${r.stderr}`);
  return JSON.parse(r.stdout.trim().split('\n').at(-1));
}

const sampling = (page) => page.evaluate(() => window.planlabGrid.sampling());
const points = async (page) => JSON.parse((await page.getAttribute('#sampling-plot', 'data-points')) ?? '[]');
const value = async (page, id) => {
  const v = await page.getAttribute(`#${id}`, 'data-value');
  return v === null ? null : Number(v);
};

/** Chooses a sampling planner with seed and budget (replans once per
 *  changed control). */
async function chooseSampler(page, algo, { seed = 3, budget = 2000, kind = 'iterations' } = {}) {
  await afterReplan(page, () => page.selectOption('#algorithm', algo));
  if ((await page.inputValue('#sampling-budget-kind')) !== kind) await afterReplan(page, () => page.selectOption('#sampling-budget-kind', kind));
  if ((await page.inputValue('#sampling-seed')) !== String(seed)) await afterReplan(page, () => page.fill('#sampling-seed', String(seed)));
  if ((await page.inputValue('#sampling-budget')) !== String(budget)) await afterReplan(page, () => page.fill('#sampling-budget', String(budget)));
}

test('RRT* on the arena grows a tree in the player, the best cost only goes down, and the cost is the CLI’s', async () => {
  const { page, problems } = await openPage(session);
  await chooseSampler(page, 'rrt-star');
  assert.equal(await errorText(page), null);
  assert.equal(await page.getAttribute('#sampling-box', 'data-hidden'), 'false');
  assert.equal(await page.getAttribute('#sampling-metrics', 'hidden'), null);
  assert.notEqual(await page.getAttribute('#metrics', 'hidden'), null, 'the searches’ metrics make room');
  assert.equal(await page.getAttribute('#explain', 'hidden'), '', 'no search step to explain');
  assert.match(await page.textContent('#sampling-reference'), /Karaman/);

  // Played out: the whole tree and the path.
  const end = await sampling(page);
  assert.ok(end.done && end.events > 1000, JSON.stringify(end));
  assert.ok(end.nodes > 100 && end.drawnEdges >= end.nodes - 1, `nodes ${end.nodes}, edges drawn ${end.drawnEdges}`);
  assert.ok(end.rewires > 0, 'RRT* rewires');
  assert.equal(await value(page, 'sampling-iterations'), 2000);
  assert.equal(await value(page, 'sampling-nodes'), end.nodes);

  // The same player controls as the searches: back to the start, step,
  // scrub, play at a speed to the end.
  await page.evaluate(() => window.planlabGrid.seek(0));
  const zero = await sampling(page);
  assert.equal(zero.step, 0);
  assert.equal(zero.drawnEdges, 0);
  await page.click('#step-fwd');
  assert.equal((await sampling(page)).step, 1);
  assert.equal(await page.getAttribute('body', 'data-search-step'), '1');
  await page.$eval('#scrub', (s, k) => {
    s.value = String(k);
    s.dispatchEvent(new Event('input'));
  }, Math.floor(end.events / 2));
  const mid = await sampling(page);
  assert.equal(mid.step, Math.floor(end.events / 2));
  assert.ok(mid.drawnEdges > 0 && mid.drawnEdges < end.drawnEdges, `edges mid ${mid.drawnEdges}, end ${end.drawnEdges}`);
  assert.ok(mid.samples > 0 && mid.samples < end.samples);
  assert.equal(await page.getAttribute('#count-expanded', 'data-value'), String(mid.nodes));
  assert.equal(await page.$eval('#count-expanded', (d) => d.previousElementSibling.textContent), 'Nodes');
  await page.selectOption('#speed', '1024');
  await page.click('#play');
  await page.waitForFunction(() => document.body.dataset.playing === 'false', null, { timeout: 60_000 });
  const played = await sampling(page);
  assert.equal(played.step, end.events);
  assert.deepEqual(played.path, end.path);

  // The plot: every improvement, iterations rising and costs falling.
  const pts = await points(page);
  assert.ok(pts.length >= 2, JSON.stringify(pts));
  for (let i = 1; i < pts.length; i++) {
    assert.ok(pts[i][0] >= pts[i - 1][0], `iterations ${JSON.stringify(pts)}`);
    assert.ok(pts[i][1] < pts[i - 1][1], `costs ${JSON.stringify(pts)}`);
  }
  assert.equal(await value(page, 'sampling-first'), pts[0][0]);

  // The CLI on the same map file, cells, seed and iterations.
  const shown = await value(page, 'sampling-cost');
  const native = cliPlan([ARENA, '--start', START.join(','), '--goal', GOAL.join(','), '--algo', 'rrt-star', '--iterations', '2000', '--seed', '3']);
  assert.equal(shown, native.cost, 'the page’s cost is the CLI’s');
  assert.equal(await value(page, 'sampling-first'), native.first_solution_iteration);
  assert.equal(end.nodes, native.nodes);
  assert.equal(end.path.length / 2, native.path.length);
  assert.equal(pts.at(-1)[1], native.cost);
  // The command the status line gives reproduces it too.
  assert.match(await page.textContent('#status'), /planlab plan assets\/maps\/arena\.map --start 1,45 --goal 47,9 --algo rrt-star --iterations 2000 --seed 3/);

  // Shortened: the CLI's --shortcut gives the same cost.
  await afterReplan(page, () => page.check('#sampling-shortcut'));
  const short = cliPlan([ARENA, '--start', START.join(','), '--goal', GOAL.join(','), '--algo', 'rrt-star', '--iterations', '2000', '--seed', '3', '--shortcut']);
  assert.equal(await value(page, 'sampling-cost'), short.cost);
  assert.ok(short.cost <= native.cost);

  // The screenshot of the tree mid-growth, right after an improvement.
  await afterReplan(page, () => page.uncheck('#sampling-shortcut'));
  const glowAt = await page.evaluate(() => {
    const s = window.planlabGrid.sampling();
    // Just after the first improvement past 40 % of the run: its path glows.
    const at = s.solutionAt.find((i) => i > s.events * 0.4) ?? s.solutionAt.at(-1);
    return at + 8;
  });
  await page.evaluate((k) => window.planlabGrid.seek(k), glowAt);
  await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
  assert.ok((await sampling(page)).solutions >= 1);
  await page.screenshot({ path: path.join(REPO, 'docs/sampling-tree-screenshot.png') });
  assert.deepEqual(problems, []);
  await page.close();
});

test('a budget in milliseconds stops, and the CLI with the iterations it reached gives the same path', async () => {
  const { page, problems } = await openPage(session);
  await chooseSampler(page, 'bit-star', { seed: 5, budget: 120, kind: 'ms' });
  assert.equal(await errorText(page), null);
  const ms = Number(await page.getAttribute('body', 'data-sampling-ms'));
  const iterations = Number(await page.getAttribute('body', 'data-sampling-iterations'));
  // Stepped until the page's clock passed the budget (or the planner was done).
  assert.ok(iterations > 0 && iterations < 200_000, `${iterations} iterations`);
  assert.ok(ms >= 120 || (await sampling(page)).done, `${ms} ms`);
  assert.match(await page.textContent('#status'), /120 ms budget/);
  const native = cliPlan([ARENA, '--start', START.join(','), '--goal', GOAL.join(','), '--algo', 'bit-star', '--iterations', String(iterations), '--seed', '5']);
  assert.equal(await value(page, 'sampling-cost'), native.cost);
  assert.equal(await value(page, 'sampling-iterations'), native.iterations);
  assert.deepEqual(problems, []);
  await page.close();
});

test('bad input is one line on the page: radius too big, start in a wall, no path within the budget, bad budget', async () => {
  const { page, problems } = await openPage(session);
  await chooseSampler(page, 'rrt', { seed: 1, budget: 1 });
  assert.match(await errorText(page), /^RRT: no path after 1 iterations \(\d+ nodes\): give it a larger budget/);
  assert.equal(await page.getAttribute('body', 'data-state'), 'error');

  await afterReplan(page, () => page.fill('#sampling-budget', '0'));
  assert.match(await errorText(page), /^budget 0: must be a whole number of iterations from 1 to 200,000$/);
  await afterReplan(page, () => page.fill('#sampling-budget', '500'));
  assert.equal(await errorText(page), null);

  await afterReplan(page, () => page.fill('#sampling-radius', '30'));
  assert.match(await errorText(page), /^robot radius 30 m: must be a finite number of metres ≥ 0 and less than half the map's smaller side$/);
  await afterReplan(page, () => page.fill('#sampling-radius', ''));
  assert.equal(await errorText(page), null);

  await chooseTool(page, 'start');
  await clickCell(page, 0, 24);
  assert.match(await errorText(page), /^the start \(cell 0, 24\) is too close to a wall or the map's edge for a robot of radius 0\.400 m/);
  for (const e of [await errorText(page)]) assert.ok(!e.includes('\n'));
  assert.equal(await sampling(page), null, 'no run to play');
  assert.deepEqual(problems, []);
  await page.close();
});

test('the race plays RRT-Connect beside A* with its cost (the CLI’s) and time', async () => {
  const page = await session.context.newPage();
  const problems = [];
  page.on('pageerror', (e) => problems.push(e.message));
  page.on('console', (m) => m.type() === 'error' && problems.push(m.text()));
  await page.goto(session.base + 'race.html');
  await page.waitForFunction(() => document.body.dataset.raceState === 'ready', null, { timeout: 30_000 });
  await page.selectOption('#pick-1', 'rrt-connect');
  await page.selectOption('#pick-2', '');
  await page.selectOption('#pick-3', '');
  await page.waitForFunction(() => document.querySelectorAll('.lane').length === 2);
  assert.deepEqual(await page.$$eval('.lane', (ls) => ls.map((l) => l.dataset.algorithm)), ['astar', 'rrt-connect']);
  assert.match(await page.textContent('.lane[data-algorithm="rrt-connect"] header b'), /RRT-Connect \(seed 1, 2,000 iterations\)/);
  await page.click('#race-go');
  await page.waitForFunction(() => document.body.dataset.raceState === 'finished', null, { timeout: 60_000 });
  const rows = await page.$$eval('#race-table tbody tr', (trs) => trs.map((tr) => ({ algo: tr.dataset.algorithm, cells: Array.from(tr.cells, (td) => td.textContent) })));
  const rc = rows.find((r) => r.algo === 'rrt-connect').cells;
  const astar = rows.find((r) => r.algo === 'astar').cells;
  const native = cliPlan([ARENA, '--start', START.join(','), '--goal', GOAL.join(','), '--algo', 'rrt-connect', '--iterations', '2000', '--seed', '1']);
  assert.equal(rc[4], native.cost.toFixed(4), 'RRT-Connect’s cost is the CLI’s');
  assert.match(rc[1], /^\d+ nodes$/);
  assert.equal(rc[1], `${native.nodes} nodes`);
  assert.ok(Number(astar[4]) > 0);
  for (const r of [rc, astar]) assert.ok(Number(r[7]) >= 0, `plan time ${r[7]}`);
  assert.notEqual(rc[6], '—', 'RRT-Connect finished at a frame');
  assert.match(await page.textContent('#race-winner'), /Lowest cost: .+ · sampling lanes: any-angle paths/);
  assert.equal(await page.textContent('.lane[data-algorithm="rrt-connect"] .lane-error'), '');
  assert.deepEqual(problems, []);
  await page.close();
});

test('a link ?algorithm=rrt-connect opens the grid page with the sampling planner chosen', async () => {
  const { page, problems } = await openPage(session, '?algorithm=rrt-connect');
  await page.waitForFunction(() => document.getElementById('algorithm').value === 'rrt-connect');
  assert.equal(await errorText(page), null);
  // The run happened: its best-cost plot has a point and the player a tree.
  await page.waitForFunction(() => JSON.parse(document.getElementById('sampling-plot')?.dataset.points ?? '[]').length > 0, null, { timeout: 30_000 });
  assert.ok((await sampling(page)) !== null, 'the player holds the sampling run');
  // An unknown name lists the sampling planners among the choices.
  const bad = await openPage(session, '?algorithm=rrt-starr');
  assert.match((await errorText(bad.page)) ?? '', /not one of .*rrt-star/);
  assert.deepEqual(problems, []);
  await page.close();
  await bad.page.close();
});
