// End-to-end tests of the playground in headless Chromium: real mouse
// clicks on the canvas, costs checked against the Moving AI optimum, errors
// shown on the page without killing it, and no console errors anywhere.

import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
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
  clickCell,
  dragCells,
  afterReplan,
  cellPoint,
  metric,
  pathCells,
  pixelAt,
  errorText,
  readScen,
} from './harness.mjs';

const ARENA_SCEN = path.join(DATA, 'movingai/dao/arena.map.scen');
const ROS_DIR = path.join(DATA, 'rosmaps/turtlebot3');

/** A long query of the arena scenario (the first with optimum > 55 cells). */
const ROW = readScen(ARENA_SCEN).find((r) => r.optimal > 55);

let session;
before(async () => {
  session = await startSession();
});
after(async () => {
  await session?.close();
});

function near(actual, expected, tol, what) {
  assert.ok(Math.abs(actual - expected) <= tol, `${what}: ${actual} not within ${tol} of ${expected}`);
}

test('preset map is drawn and a clicked query costs the Moving AI optimum', async () => {
  assert.ok(ROW, 'arena.map.scen has a row with optimum > 55');
  const { page, problems } = await openPage(session);
  assert.match(await page.textContent('#map-size'), /^49\s*×\s*49$/);
  assert.equal(await page.textContent('#map-name'), 'arena.map');
  // The map is painted: a border wall cell is dark, an interior cell light.
  const wall = await pixelAt(page, 0, 0);
  assert.ok(wall[0] < 80 && wall[1] < 80 && wall[2] < 100, `wall pixel ${wall}`);

  await setEndpoints(page, ROW.start, ROW.goal);
  assert.equal(await errorText(page), null);
  near(await metric(page, 'cost'), ROW.optimal, 1e-3, 'A* cost');
  assert.ok((await metric(page, 'expanded')) > 0, 'expansions > 0');
  const lengthM = await metric(page, 'length');
  near(lengthM, ROW.optimal * 1.0, 1e-3, 'length in m (1 m cells)');
  assert.ok((await metric(page, 'time')) >= 0);

  const cells = await pathCells(page);
  assert.deepEqual(cells[0], ROW.start);
  assert.deepEqual(cells.at(-1), ROW.goal);
  // The path is drawn in the path colour (#e11d48) over its middle cells.
  for (const k of [0.3, 0.5, 0.7]) {
    const [c, r] = cells[Math.floor(cells.length * k)];
    const [R, G, B] = await pixelAt(page, c, r);
    assert.ok(Math.abs(R - 225) < 30 && G < 70 && Math.abs(B - 72) < 40, `pixel at (${c}, ${r}) is ${R},${G},${B}`);
  }
  await screenshot(page, '01-arena-astar.png');
  assert.deepEqual(problems, []);
  await page.close();
});

test('JPS finds the same cost with fewer expansions', async () => {
  const { page, problems } = await openPage(session);
  await setEndpoints(page, ROW.start, ROW.goal);
  const astarCost = await metric(page, 'cost');
  const astarExpanded = await metric(page, 'expanded');
  await afterReplan(page, () => page.selectOption('#algorithm', 'jps'));
  assert.equal(await errorText(page), null);
  near(await metric(page, 'cost'), astarCost, 1e-6, 'JPS cost');
  near(await metric(page, 'cost'), ROW.optimal, 1e-3, 'JPS cost vs optimum');
  const jpsExpanded = await metric(page, 'expanded');
  assert.ok(jpsExpanded > 0 && jpsExpanded < astarExpanded, `JPS ${jpsExpanded} vs A* ${astarExpanded}`);
  // Dijkstra: same cost, more expansions than A*.
  await afterReplan(page, () => page.selectOption('#algorithm', 'dijkstra'));
  near(await metric(page, 'cost'), astarCost, 1e-6, 'Dijkstra cost');
  assert.ok((await metric(page, 'expanded')) > astarExpanded);
  await afterReplan(page, () => page.selectOption('#algorithm', 'jps'));
  await screenshot(page, '02-arena-jps.png');
  assert.deepEqual(problems, []);
  await page.close();
});

test('painting a wall across the path re-plans around it', async () => {
  const { page, problems } = await openPage(session);
  await setEndpoints(page, ROW.start, ROW.goal);
  const before = await pathCells(page);
  const beforeCost = await metric(page, 'cost');
  const [mc, mr] = before[Math.floor(before.length / 2)];
  // A vertical wall 21 cells tall through the middle of the path.
  const top = Math.max(1, mr - 10);
  const bottom = Math.min(47, mr + 10);
  await chooseTool(page, 'wall');
  await dragCells(page, [mc, top], [mc, bottom]);
  assert.equal(await errorText(page), null);
  const wall = await pixelAt(page, mc, top);
  assert.ok(wall[0] < 80 && wall[1] < 80, `painted cell is dark: ${wall}`);
  const after = await pathCells(page);
  const afterCost = await metric(page, 'cost');
  assert.notDeepEqual(after, before, 'path changed');
  for (let r = top; r <= bottom; r++) {
    assert.ok(!after.some(([c, rr]) => c === mc && rr === r), `path avoids the wall at (${mc}, ${r})`);
  }
  assert.ok(afterCost > beforeCost + 1e-6, `cost rose: ${beforeCost} → ${afterCost}`);
  await screenshot(page, '03-arena-wall.png');

  // Erasing the wall restores the optimum.
  await chooseTool(page, 'erase');
  await dragCells(page, [mc, top], [mc, bottom]);
  near(await metric(page, 'cost'), beforeCost, 1e-9, 'cost after erase');
  assert.deepEqual(problems, []);
  await page.close();
});

test('errors are shown in the error box and the page recovers', async () => {
  const { page, problems } = await openPage(session);
  await setEndpoints(page, ROW.start, ROW.goal);
  // (0, 0) is a border wall of the arena.
  await chooseTool(page, 'start');
  await clickCell(page, 0, 0);
  assert.equal(await errorText(page), 'start (0, 0) is inside an obstacle');
  assert.equal(await page.getAttribute('body', 'data-state'), 'error');
  assert.equal(await page.textContent('#metric-cost'), '—');
  await screenshot(page, '04-error-start-in-wall.png');
  await clickCell(page, ...ROW.start);
  assert.equal(await errorText(page), null);
  near(await metric(page, 'cost'), ROW.optimal, 1e-3, 'cost after recovery');

  // JPS only supports some diagonal rules: the core's refusal is shown.
  await afterReplan(page, () => page.selectOption('#algorithm', 'jps'));
  await afterReplan(page, () => page.selectOption('#diagonal', 'always'));
  const jpsError = await errorText(page);
  assert.ok(jpsError && /diagonal|corner|jps|jump/i.test(jpsError), `JPS error: ${jpsError}`);
  await afterReplan(page, () => page.selectOption('#diagonal', 'no_corner_cutting'));
  assert.equal(await errorText(page), null);

  // Walling the goal in makes it unreachable.
  await chooseTool(page, 'wall');
  const [gc, gr] = ROW.goal;
  await dragCells(page, [gc - 1, gr - 1], [gc + 1, gr - 1]);
  await dragCells(page, [gc - 1, gr + 1], [gc + 1, gr + 1]);
  await dragCells(page, [gc - 1, gr], [gc - 1, gr]);
  await dragCells(page, [gc + 1, gr], [gc + 1, gr]);
  const unreachable = await errorText(page);
  assert.match(unreachable ?? '', /unreachable/);
  await page.click('#reset-map');
  await page.waitForFunction(() => document.getElementById('error').hidden);
  near(await metric(page, 'cost'), ROW.optimal, 1e-3, 'cost after reset');
  assert.deepEqual(problems, []);
  await page.close();
});

test('ROS yaml+pgm opened from disk; malformed files show errors', async () => {
  const { page, problems } = await openPage(session);
  await afterReplan(page, () =>
    page.setInputFiles('#file-input', [path.join(ROS_DIR, 'map.yaml'), path.join(ROS_DIR, 'map.pgm')]),
  );
  assert.equal(await errorText(page), null);
  assert.match(await page.textContent('#map-size'), /^384\s*×\s*384$/);
  assert.equal(await page.textContent('#map-resolution'), '0.05 m / cell');
  await setEndpoints(page, [152, 182], [235, 215]);
  assert.equal(await errorText(page), null);
  const cost = await metric(page, 'cost');
  assert.ok(cost >= Math.hypot(235 - 152, 215 - 182) - 1e-9, `cost ${cost} ≥ straight line`);
  near(await metric(page, 'length'), cost * 0.05, 1e-9, 'length = cost × 0.05 m');
  // Key points and inflation on the real map.
  await afterReplan(page, () => page.check('#keypoints'));
  await afterReplan(page, () => page.fill('#inflate', '0.1'));
  assert.equal(await errorText(page), null);
  assert.ok((await metric(page, 'keypoints')) >= 2);
  await screenshot(page, '05-ros-turtlebot3.png');

  // The yaml without its pgm.
  await page.setInputFiles('#file-input', [path.join(ROS_DIR, 'map.yaml')]);
  await page.waitForFunction(() => !document.getElementById('error').hidden);
  assert.match(await errorText(page), /open the \.yaml together with its \.pgm/);
  // The yaml with another map's image: said, not loaded.
  await page.setInputFiles('#file-input', [
    { name: 'map.yaml', mimeType: 'application/x-yaml', buffer: fs.readFileSync(path.join(ROS_DIR, 'map.yaml')) },
    { name: 'other.pgm', mimeType: 'image/x-portable-graymap', buffer: fs.readFileSync(path.join(ROS_DIR, 'map.pgm')) },
  ]);
  await page.waitForFunction(() => /other\.pgm/.test(document.getElementById('error').textContent));
  assert.match(await errorText(page), /names the image "map\.pgm", but the \.pgm opened is other\.pgm/);
  // A malformed pgm.
  await page.setInputFiles('#file-input', [
    { name: 'map.yaml', mimeType: 'application/x-yaml', buffer: fs.readFileSync(path.join(ROS_DIR, 'map.yaml')) },
    { name: 'map.pgm', mimeType: 'image/x-portable-graymap', buffer: Buffer.from('P5\n384 384\n255\n\x00\x00') },
  ]);
  await page.waitForFunction(() => /PGM/i.test(document.getElementById('error').textContent));
  // A malformed Moving AI map: the error names the format, the old map stays.
  await page.setInputFiles('#file-input', {
    name: 'broken.map',
    mimeType: 'text/plain',
    buffer: Buffer.from('type octile\nheight 3\nwidth 3\nmap\n...\n.x.\n'),
  });
  await page.waitForFunction(() => /broken\.map/.test(document.getElementById('error').textContent));
  assert.match(await errorText(page), /Moving AI map/);
  await screenshot(page, '06-malformed-map.png');
  assert.match(await page.textContent('#map-size'), /^384\s*×\s*384$/);
  // Still alive: a new click plans again and clears the error.
  await chooseTool(page, 'start');
  await clickCell(page, 160, 182);
  assert.equal(await errorText(page), null);
  assert.ok((await metric(page, 'cost')) > 0);
  assert.deepEqual(problems, []);
  await page.close();
});

test('TurtleBot3 preset, safe A* and Bottom-Up run without console errors', async () => {
  const { page, problems } = await openPage(session);
  await afterReplan(page, () => page.selectOption('#preset', 'turtlebot3'));
  assert.match(await page.textContent('#map-size'), /^384\s*×\s*384$/);
  assert.equal(await errorText(page), null);
  assert.ok((await metric(page, 'cost')) > 0);
  await afterReplan(page, () => page.selectOption('#algorithm', 'safe-astar'));
  assert.equal(await errorText(page), null);
  assert.ok((await metric(page, 'cost')) > 0);
  // Safe A* reports the safety index of its path (10 = nothing in the window).
  const safety = Number((await page.textContent('#status')).match(/safety index ([\d.]+)/)?.[1]);
  assert.ok(safety > 0 && safety <= 10, `minimum safety index ${safety}`);
  await afterReplan(page, () => page.check('#bottom-up'));
  await afterReplan(page, () => page.check('#keypoints'));
  assert.equal(await errorText(page), null);
  assert.match(await page.textContent('#metric-keypoints'), /\d+ · \d+ BU/);
  await screenshot(page, '07-turtlebot3-safe-astar.png');
  assert.deepEqual(problems, []);
  await page.close();
});

test('a 512×512 Moving AI map opens from disk and plans the optimum', async () => {
  const { page, problems } = await openPage(session);
  const mapFile = path.join(DATA, 'movingai/random/random512-10-0.map');
  await afterReplan(page, () => page.setInputFiles('#file-input', mapFile));
  assert.equal(await errorText(page), null);
  assert.match(await page.textContent('#map-size'), /^512\s*×\s*512$/);
  // The longest query of the scenario, clicked at a fitted scale of ~1.3 px per cell.
  const rows = readScen(`${mapFile}.scen`);
  const row = rows.reduce((a, b) => (b.optimal > a.optimal ? b : a));
  await setEndpoints(page, row.start, row.goal);
  assert.equal(await page.getAttribute('#map-canvas', 'data-start'), row.start.join(','));
  assert.equal(await page.getAttribute('#map-canvas', 'data-goal'), row.goal.join(','));
  assert.equal(await errorText(page), null);
  near(await metric(page, 'cost'), row.optimal, 1e-3, 'A* cost on random512');
  // Dijkstra expands a large part of the map; the page keeps up.
  await afterReplan(page, () => page.selectOption('#algorithm', 'dijkstra'));
  near(await metric(page, 'cost'), row.optimal, 1e-3, 'Dijkstra cost on random512');
  assert.ok((await metric(page, 'expanded')) > 10_000);
  await screenshot(page, '08-random512-dijkstra.png');
  assert.deepEqual(problems, []);
  await page.close();
});

test('scenario JSON: preset with inline map, and a file reference opened with its map', async () => {
  const { page, problems } = await openPage(session);
  await afterReplan(page, () => page.selectOption('#preset', 'grid-demo'));
  assert.equal(await errorText(page), null);
  assert.match(await page.textContent('#map-size'), /^40\s*×\s*30$/);
  assert.equal(await page.textContent('#map-resolution'), '0.1 m / cell');
  const cost = await metric(page, 'cost');
  assert.ok(cost > 0);
  near(await metric(page, 'length'), cost * 0.1, 1e-9, 'length = cost × 0.1 m');
  await screenshot(page, '09-scenario-grid-demo.png');

  // A scenario naming a map file: alone it is an error, with the file it loads.
  const scen = JSON.stringify({
    version: 1,
    name: 'arena query',
    map: { file: 'maps/arena.map' },
    start: { col: ROW.start[0], row: ROW.start[1] },
    goal: { col: ROW.goal[0], row: ROW.goal[1] },
  });
  const scenFile = { name: 'arena-query.json', mimeType: 'application/json', buffer: Buffer.from(scen) };
  await page.setInputFiles('#file-input', [scenFile]);
  await page.waitForFunction(() => !document.getElementById('error').hidden);
  assert.match(await errorText(page), /arena\.map/);
  assert.match(await page.textContent('#map-size'), /^40\s*×\s*30$/);
  await afterReplan(page, () =>
    page.setInputFiles('#file-input', [
      scenFile,
      { name: 'arena.map', mimeType: 'text/plain', buffer: fs.readFileSync(path.join(REPO, 'assets/maps/arena.map')) },
    ]),
  );
  assert.equal(await errorText(page), null);
  assert.match(await page.textContent('#map-size'), /^49\s*×\s*49$/);
  near(await metric(page, 'cost'), ROW.optimal, 1e-3, 'scenario query cost');
  assert.deepEqual(problems, []);
  await page.close();
});

test('wheel zoom and right-drag pan keep clicks on the right cell', async () => {
  const { page, problems } = await openPage(session);
  const scale0 = Number(await page.getAttribute('#map-canvas', 'data-scale'));
  const centre = await cellPoint(page, 24, 24);
  await page.mouse.move(centre.x, centre.y);
  await page.mouse.wheel(0, -400);
  await page.waitForFunction((s) => Number(document.getElementById('map-canvas').dataset.scale) > s * 1.5, scale0);
  // Pan with the right button.
  const ox0 = Number(await page.getAttribute('#map-canvas', 'data-offset-x'));
  await page.mouse.down({ button: 'right' });
  await page.mouse.move(centre.x - 120, centre.y - 80, { steps: 8 });
  await page.mouse.up({ button: 'right' });
  near(Number(await page.getAttribute('#map-canvas', 'data-offset-x')), ox0 - 120, 1, 'pan x');
  // Clicks still land on the intended cells at the new zoom.
  await setEndpoints(page, [20, 20], [30, 26]);
  assert.equal(await page.getAttribute('#map-canvas', 'data-start'), '20,20');
  assert.equal(await page.getAttribute('#map-canvas', 'data-goal'), '30,26');
  // 10 across, 6 down on open floor: octile distance 4 + 6√2.
  near(await metric(page, 'cost'), 4 + 6 * Math.SQRT2, 1e-9, 'open-floor octile cost');
  await screenshot(page, '10-zoomed.png');
  // "Fit view" restores the whole map.
  await page.click('#fit-view');
  await page.waitForFunction((s) => Math.abs(Number(document.getElementById('map-canvas').dataset.scale) - s) < 1e-9, scale0);
  assert.deepEqual(problems, []);
  await page.close();
});

test('"Save Posthoc trace" saves the search as a Posthoc 1.4.0 trace that replays to the expanded count', async () => {
  const { page, problems } = await openPage(session);
  await setEndpoints(page, ROW.start, ROW.goal);
  const expanded = await metric(page, 'expanded');
  const [dl] = await Promise.all([page.waitForEvent('download'), page.click('#save-posthoc')]);
  assert.equal(dl.suggestedFilename(), 'arena-astar.trace.json');
  const file = await dl.path();
  const trace = JSON.parse(fs.readFileSync(file, 'utf8'));
  assert.equal(trace.version, '1.4.0');
  const count = (k) => trace.events.filter((e) => e.type === k).length;
  assert.equal(count('expanding'), expanded, 'expanding events = the page\'s expanded count');
  assert.deepEqual([trace.events[0].type, trace.events[0].x, trace.events[0].y], ['source', ...ROW.start]);
  const end = trace.events.at(-1);
  assert.equal(end.type, 'end');
  near(end.g, ROW.optimal, 1e-3, 'g at the end event');
  assert.equal(await errorText(page), null);
  assert.deepEqual(problems, []);
  await page.close();
});

test('a long error is shown whole, over the map, without moving it', async () => {
  const { page, problems } = await openPage(session);
  const box = () => page.$eval('#map-canvas', (c) => JSON.stringify(c.getBoundingClientRect()));
  const before = await box();
  const name = `${'a-map-with-a-very-long-name-'.repeat(8)}end.map`;
  await page.setInputFiles('#file-input', { name, mimeType: 'text/plain', buffer: Buffer.from('type octile\nheight x\n') });
  await page.waitForFunction(() => !document.querySelector('#error').hidden);
  const e = await page.$eval('#error', (el) => ({ text: el.textContent, sw: el.scrollWidth, cw: el.clientWidth, sh: el.scrollHeight, ch: el.clientHeight, lines: Math.round(el.getBoundingClientRect().height / 20) }));
  assert.ok(e.text.includes('end.map'), `the whole message, to its end: ${e.text}`);
  assert.ok(e.sw <= e.cw + 1 && e.sh <= e.ch + 1, `nothing clipped: ${JSON.stringify(e)}`);
  assert.ok(e.lines >= 2, `wrapped over lines: ${JSON.stringify(e)}`);
  assert.equal(await box(), before, 'the map did not move');
  await screenshot(page, 'long-error.png');
  assert.deepEqual(problems, []);
  await page.close();
});

test('a map dropped on the grid canvas opens as if picked', async () => {
  const { page, problems } = await openPage(session);
  const text = fs.readFileSync(path.join(DATA, 'movingai/dao/arena.map'), 'utf8');
  const dt = await page.evaluateHandle((t) => {
    const d = new DataTransfer();
    d.items.add(new File([t], 'dropped-arena.map', { type: 'text/plain' }));
    return d;
  }, text);
  await afterReplan(page, async () => {
    await page.dispatchEvent('#canvas-wrap', 'dragenter', { dataTransfer: dt });
    await page.dispatchEvent('#canvas-wrap', 'dragover', { dataTransfer: dt });
    await page.dispatchEvent('#canvas-wrap', 'drop', { dataTransfer: dt });
  });
  assert.equal(await page.textContent('#map-name'), 'dropped-arena.map');
  assert.equal(await errorText(page), null);
  assert.deepEqual(problems, []);
  await page.close();
});

test('safe A*\'s cost says it comes from 24-neighbour moves and is not comparable with A*; A*\'s says nothing', async () => {
  const { page, problems } = await openPage(session);
  const note = () => page.evaluate(() => {
    const n = document.getElementById('metric-cost-note');
    return n && !n.hidden && n.getClientRects().length ? n.textContent : null;
  });
  const cost = () => page.evaluate(() => Number(document.getElementById('metric-cost').dataset.value));
  assert.equal(await page.inputValue('#algorithm'), 'astar');
  assert.equal(await note(), null, 'A* on 8 neighbours: no note');
  const astar = await cost();
  await afterReplan(page, () => page.selectOption('#algorithm', 'safe-astar'));
  // The case a class saw: safe A* cheaper than the "optimal" A*.
  assert.ok(await cost() < astar, `safe A* ${await cost()} vs A* ${astar}`);
  assert.match(await note(), /24-neighbourhood moves: not comparable with A\*/);
  assert.match(await page.getAttribute('#metric-cost-note', 'title'), /5×5 block/);
  // Safe A* on 8 neighbours: comparable, no note.
  await afterReplan(page, () => page.selectOption('#safe-neighbourhood', '8'));
  assert.equal(await note(), null);
  await afterReplan(page, () => page.selectOption('#safe-neighbourhood', '24'));
  assert.match(await note(), /24-neighbourhood/);
  // Theta*'s any-angle path too; back to A*: gone.
  await afterReplan(page, () => page.selectOption('#algorithm', 'theta-star'));
  assert.match(await note(), /any-angle/);
  await afterReplan(page, () => page.selectOption('#algorithm', 'astar'));
  assert.equal(await note(), null);
  // The help says it beside safe A*.
  await page.click('#help-button');
  const help = await page.textContent('.help-planner[data-planner="Safe A* (Ge & Li)"]');
  assert.match(help, /not comparable with A\*'s: it moves to any of the 24 cells/);
  await page.keyboard.press('Escape');
  assert.deepEqual(problems, []);
  await page.close();
});
