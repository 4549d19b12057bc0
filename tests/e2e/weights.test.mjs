// End-to-end test of the grid page's weighted cells (docs/algorithms.md
// §weights) in headless Chromium, with real mouse drags: a band of
// weight-9 cells painted with the cost brush across the straight line makes
// A* go round its end at Dijkstra's cost; breadth-first search crosses it
// and says it ignores weights; Jump Point Search refuses the weighted map in
// the banner; erasing the band (weight 1) gives the unit map back. No
// console errors; a screenshot of the weighted map and its path is saved.

import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { startSession, openPage, setEndpoints, chooseTool, afterReplan, dragCells, metric, pathCells, errorText, screenshot, cellPoint } from './harness.mjs';

let session;
before(async () => {
  session = await startSession();
});
after(async () => {
  await session?.close();
});

const body = (page, key) => page.evaluate((k) => document.body.dataset[k], key);
// The arena's open middle: row 24 is free from column 2 to 47, and so is
// column 24 from row 19 to row 30.
const START = [8, 24];
const GOAL = [40, 24];
const BAND = { col: 24, rows: [20, 28] };
const inBand = ([c, r]) => c === BAND.col && r >= BAND.rows[0] && r <= BAND.rows[1];

/** RGBA of the canvas pixel a third of a cell left of a cell's centre (the
 *  centre may hold the weight's digit). */
async function pixelBeside(page, col, row) {
  const { x, y } = await cellPoint(page, col, row);
  return page.evaluate(
    ([px, py]) => {
      const cv = document.getElementById('map-canvas');
      const rect = cv.getBoundingClientRect();
      const k = cv.width / rect.width;
      const off = Number(cv.dataset.scale) / 3;
      const data = cv.getContext('2d').getImageData(Math.floor((px - off - rect.left) * k), Math.floor((py - rect.top) * k), 1, 1).data;
      return Array.from(data);
    },
    [x, y],
  );
}

test('a heavy band across the line: A* goes round it at Dijkstra’s cost, BFS crosses it and says so, JPS refuses', async () => {
  const { page, problems } = await openPage(session);
  await setEndpoints(page, START, GOAL);
  assert.equal(await metric(page, 'cost'), 32, 'unit map: the straight line');
  assert.equal(await body(page, 'weighted'), 'false');

  await chooseTool(page, 'cost');
  assert.equal(await page.getAttribute('#tool-cost', 'aria-checked'), 'true');
  await page.selectOption('#cost-weight', '9');
  await afterReplan(page, () => dragCells(page, [BAND.col, BAND.rows[0]], [BAND.col, BAND.rows[1]]));
  assert.equal(await errorText(page), null);
  assert.equal(await body(page, 'weighted'), 'true');

  // A*: round the band's end (≈ 36.1: two octile legs of 16 by 5), not
  // through it (32 + 8 = 40).
  const astar = await metric(page, 'cost');
  assert.ok(astar > 32 && astar < 40, `A* cost ${astar}`);
  const cells = await pathCells(page);
  assert.deepEqual([cells[0], cells.at(-1)], [START, GOAL]);
  assert.ok(!cells.some(inBand), `A* crossed the band: ${JSON.stringify(cells)}`);
  assert.match(await page.textContent('#status'), /weighted cost 36\.\d{3}/);
  assert.equal(await body(page, 'planNote'), '');
  // The band is drawn amber (under the search tint too); a free cell is not.
  const [R, G, B] = await pixelBeside(page, BAND.col, 22);
  assert.ok(R > 150 && R - B > 60, `band cell pixel ${R},${G},${B}`);
  const [fr, , fb] = await pixelBeside(page, 30, 40);
  assert.ok(Math.abs(fr - fb) < 20, `free cell pixel ${fr},${fb}`);
  await screenshot(page, 'weights-astar-round-band.png');

  await afterReplan(page, () => page.selectOption('#algorithm', 'dijkstra'));
  assert.ok(Math.abs((await metric(page, 'cost')) - astar) < 1e-9, 'Dijkstra: the same optimum');

  // 4-connected, breadth-first search takes the fewest moves, straight
  // through the band: 31 moves of 1 and one of 9.
  await afterReplan(page, () => page.selectOption('#diagonal', 'never'));
  await afterReplan(page, () => page.selectOption('#algorithm', 'bfs'));
  assert.equal(await errorText(page), null);
  assert.ok((await pathCells(page)).some(inBand), 'BFS goes through the band');
  assert.ok(Math.abs((await metric(page, 'cost')) - 40) < 1e-9, `BFS weighted cost ${await metric(page, 'cost')}`);
  assert.match(await body(page, 'planNote'), /breadth-first search ignores cell weights/);
  assert.match(await page.textContent('#status'), /ignores cell weights/);
  // A* 4-connected: crossing (40) beats going round (42), at Dijkstra's cost.
  await afterReplan(page, () => page.selectOption('#algorithm', 'astar'));
  assert.ok(Math.abs((await metric(page, 'cost')) - 40) < 1e-9);

  await afterReplan(page, () => page.selectOption('#diagonal', 'no_corner_cutting'));
  await afterReplan(page, () => page.selectOption('#algorithm', 'jps'));
  assert.match(await errorText(page), /needs uniform cell costs.*weighted cells/);

  // Erasing the band with weight 1: a unit map again, JPS plans the line.
  await page.selectOption('#cost-weight', '1');
  await afterReplan(page, () => dragCells(page, [BAND.col, BAND.rows[0]], [BAND.col, BAND.rows[1]]));
  assert.equal(await errorText(page), null);
  assert.equal(await body(page, 'weighted'), 'false');
  assert.equal(await metric(page, 'cost'), 32);
  assert.deepEqual(problems, []);
  await page.close();
});
