// End-to-end tests of the grid page's "Draw & generate" card (what a
// PathFinding.js user expects): the empty grid of large cells, Clear walls,
// Clear path, and the seeded generators, whose maps and A* costs must be
// the CLI's (`planlab generate`, `planlab plan`).

import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import {
  REPO,
  startSession,
  openPage,
  screenshot,
  chooseTool,
  dragCells,
  afterReplan,
  metric,
  pathCells,
  pixelAt,
  errorText,
} from './harness.mjs';

const PLANLAB = path.join(REPO, 'target/release/planlab');

let session;
let tmp;
before(async () => {
  session = await startSession();
  tmp = fs.mkdtempSync(path.join(os.tmpdir(), 'planlab-classgrid-'));
});
after(async () => {
  await session?.close();
  if (tmp) fs.rmSync(tmp, { recursive: true, force: true });
});

function planlab(args) {
  const r = spawnSync(PLANLAB, args, { encoding: 'utf8', timeout: 60_000 });
  assert.equal(r.status, 0, `planlab ${args.join(' ')}: ${r.stderr}`);
  return r.stdout;
}

/** The map on screen: one byte per cell (0 free, 1 occupied, 2 unknown). */
const mapCells = (page) => page.evaluate(() => window.planlabClassroom.cells());
const walls = async (page) => (await mapCells(page)).filter((k) => k === 1).length;
const endpoints = (page) =>
  page.evaluate(() => {
    const d = document.getElementById('map-canvas').dataset;
    return { start: d.start, goal: d.goal };
  });

async function openEmpty() {
  const { page, problems } = await openPage(session);
  await afterReplan(page, () => page.click('#empty-grid'));
  return { page, problems };
}

test('the empty grid is one click away, has no walls and cells of at least 24 px, start left and goal right', async () => {
  const { page, problems } = await openEmpty();
  assert.match(await page.textContent('#map-size'), /^30\s*×\s*18$/);
  assert.equal(await page.inputValue('#preset'), 'empty');
  const cells = await mapCells(page);
  assert.equal(cells.length, 30 * 18);
  assert.equal(await walls(page), 0, 'no walls');
  const scale = Number(await page.getAttribute('#map-canvas', 'data-scale'));
  assert.ok(scale >= 24, `a cell is ${scale} px on screen`);
  const { start, goal } = await endpoints(page);
  const [sc, sr] = start.split(',').map(Number);
  const [gc, gr] = goal.split(',').map(Number);
  assert.ok(sc < 6 && gc > 23 && sr === gr, `start ${start}, goal ${goal}`);
  // A straight path of 23 moves across the empty grid.
  assert.equal(await metric(page, 'cost'), gc - sc);

  // The preset menu loads it too (after another map).
  await afterReplan(page, () => page.selectOption('#preset', 'arena'));
  assert.match(await page.textContent('#map-size'), /^49\s*×\s*49$/);
  await afterReplan(page, () => page.selectOption('#preset', 'empty'));
  assert.match(await page.textContent('#map-size'), /^30\s*×\s*18$/);
  assert.equal(await walls(page), 0);
  assert.equal(await errorText(page), null);
  assert.deepEqual(problems, []);
  await page.close();
});

test('walls drawn on the empty grid go with Clear walls (button and X), the start and goal stay', async () => {
  const { page, problems } = await openEmpty();
  const ends = await endpoints(page);
  const straight = await metric(page, 'cost');
  await chooseTool(page, 'wall');
  await dragCells(page, [15, 2], [15, 15]);
  assert.equal(await walls(page), 14, 'a wall of 14 cells');
  const dark = await pixelAt(page, 15, 9);
  assert.ok(dark[0] < 80 && dark[1] < 80, `wall cell is dark: ${dark}`);
  assert.ok((await metric(page, 'cost')) > straight, 'the path goes round the wall');
  await screenshot(page, 'classgrid-empty-wall.png');

  await afterReplan(page, () => page.click('#clear-walls'));
  assert.equal(await walls(page), 0, 'no walls after Clear walls');
  assert.deepEqual(await endpoints(page), ends, 'start and goal stay');
  assert.equal(await metric(page, 'cost'), straight);
  const light = await pixelAt(page, 15, 3);
  assert.ok(light[0] > 150 && light[1] > 150, `cleared cell is light: ${light}`);

  await dragCells(page, [10, 0], [10, 17]);
  assert.equal(await walls(page), 18);
  assert.equal(await metric(page, 'cost'), null, 'no path through a full wall');
  await afterReplan(page, () => page.keyboard.press('x'));
  assert.equal(await walls(page), 0, 'no walls after X');
  assert.equal(await metric(page, 'cost'), straight);
  assert.deepEqual(await endpoints(page), ends);
  assert.equal(await errorText(page), null);
  assert.deepEqual(problems.filter((p) => !p.includes('No path')), []);
  await page.close();
});

test('Clear path (button and C) empties the path, its drawing and the search player; an edit searches again', async () => {
  const { page, problems } = await openEmpty();
  await chooseTool(page, 'wall');
  await dragCells(page, [15, 4], [15, 14]);
  const cells = await pathCells(page);
  assert.ok(cells.length > 20, 'a path round the wall');
  const [mc, mr] = cells[Math.floor(cells.length / 2)];
  const isPath = ([R, G, B]) => Math.abs(R - 225) < 30 && G < 70 && Math.abs(B - 72) < 40;
  // Play the search out so the path is drawn.
  await page.evaluate(() => window.planlabGrid.seek(1e9));
  assert.ok(isPath(await pixelAt(page, mc, mr)), 'path drawn before');
  assert.notEqual(await page.evaluate(() => window.planlabGrid.counters()), null, 'the player holds a search');

  for (const [i, clear] of [() => page.click('#clear-path'), () => page.keyboard.press('c')].entries()) {
    const wallsBefore = await walls(page);
    await clear();
    assert.equal(await page.getAttribute('#map-canvas', 'data-path-len'), '0');
    assert.deepEqual(await pathCells(page), []);
    assert.equal(await metric(page, 'cost'), null);
    assert.equal(await page.evaluate(() => window.planlabGrid.counters()), null, 'the player is empty');
    assert.equal(await page.inputValue('#scrub'), '0');
    assert.ok(!isPath(await pixelAt(page, mc, mr)), 'no path drawn');
    assert.equal(await walls(page), wallsBefore, 'the walls stay');
    // Any edit plans again.
    await chooseTool(page, 'wall');
    await dragCells(page, [20 + i, 1], [20 + i, 2]);
    assert.ok((await pathCells(page)).length > 20, 'the next edit found a path again');
  }
  assert.equal(await errorText(page), null);
  assert.deepEqual(problems, []);
  await page.close();
});

test('Generate gives the map planlab generate writes for the same seed, and A* the cost of planlab plan on it', async () => {
  const { page, problems } = await openPage(session);
  for (const kind of ['maze', 'rooms', 'random']) {
    await page.selectOption('#gen-kind', kind);
    await page.fill('#gen-seed', '7');
    const out = path.join(tmp, `${kind}7.json`);
    const args = ['generate', kind, '--width', '10', '--height', '8', '--resolution', '0.2', '--seed', '7'];
    args.push(...(kind === 'random' ? ['--density', '0.2'] : ['--corridor', '0.6']));
    const cli = JSON.parse(planlab([...args, '--out', out, '--json']));
    await afterReplan(page, () => page.click('#generate'));
    assert.equal(await errorText(page), null, kind);
    // Same map: the hash and every cell.
    assert.equal(await page.evaluate(() => document.body.dataset.generatedHash), cli.grid_hash, `${kind} grid hash`);
    const scenario = JSON.parse(fs.readFileSync(out, 'utf8'));
    const expected = scenario.map.cells.join('').split('').map((c) => (c === '#' ? 1 : c === '?' ? 2 : 0));
    assert.deepEqual(await mapCells(page), expected, `${kind} cells`);
    assert.match(await page.textContent('#map-size'), new RegExp(`^${cli.width}\\s*×\\s*${cli.height}$`));
    // The menu shows what is shown.
    assert.equal(await page.inputValue('#preset'), 'generated');
    const label = await page.$eval('#preset', (s) => s.selectedOptions[0].textContent);
    assert.match(label, new RegExp(`${kind}, seed 7`));
    assert.equal(await page.textContent('#map-name'), `${kind} seed 7`);
    assert.match(await page.textContent('#gen-note'), new RegExp(`planlab generate ${kind} .*--seed 7`));
    // Same endpoints and the CLI's A* cost.
    const { start, goal } = await endpoints(page);
    assert.equal(start, cli.start_cell.join(','));
    assert.equal(goal, cli.goal_cell.join(','));
    const plan = JSON.parse(planlab(['plan', out, '--algo', 'astar', '--json']));
    const cost = await metric(page, 'cost');
    assert.ok(Math.abs(cost - plan.cost) < 1e-9, `${kind}: page A* cost ${cost}, planlab plan ${plan.cost}`);
    if (kind === 'maze') await screenshot(page, 'classgrid-generated-maze.png');
  }
  // Another seed, another map.
  await page.selectOption('#gen-kind', 'maze');
  await page.fill('#gen-seed', '8');
  await afterReplan(page, () => page.click('#generate'));
  const other = JSON.parse(planlab(['generate', 'maze', '--width', '10', '--height', '8', '--resolution', '0.2', '--seed', '8', '--corridor', '0.6', '--out', path.join(tmp, 'm8.map'), '--json']));
  assert.equal(await page.evaluate(() => document.body.dataset.generatedHash), other.grid_hash);
  assert.match(await page.$eval('#preset', (s) => s.selectedOptions[0].textContent), /maze, seed 8/);
  // A preset picked from the menu replaces the generated map again.
  await afterReplan(page, () => page.selectOption('#preset', 'arena'));
  assert.equal(await page.textContent('#map-name'), 'arena.map');
  assert.deepEqual(problems, []);
  await page.close();
});

test('bad generator settings give a one-line error and keep the map', async () => {
  const { page, problems } = await openPage(session);
  const before = await page.evaluate(() => window.planlabClassroom.hash());
  await page.fill('#gen-resolution', '0');
  await page.click('#generate');
  await page.waitForFunction(() => document.body.dataset.error === 'true');
  const text = await errorText(page);
  assert.match(text, /^Generate: .*resolution/);
  assert.ok(!text.includes('\n'), 'one line');
  await page.fill('#gen-resolution', '0.2');
  await page.fill('#gen-seed', '-1');
  await page.click('#generate');
  assert.match(await errorText(page), /seed -1 must be a whole number/);
  assert.equal(await page.evaluate(() => window.planlabClassroom.hash()), before, 'the map is unchanged');
  assert.equal(await page.textContent('#map-name'), 'arena.map');
  assert.deepEqual(problems, []);
  await page.close();
});
