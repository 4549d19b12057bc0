// End-to-end tests of the grid page's "Explain this step" panel
// (web/src/grid/explain.ts): stepping an A* search, the panel's f is g + h
// (and g + w·h weighted), the highlighted pseudo-code line is the expand
// line, and the open list's first entry is the cell expanded next; every
// planner in the menu gets its pseudo-code and says what its events lack;
// the help gives every planner's properties in plain words.

import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import path from 'node:path';
import { DATA, startSession, openPage, screenshot, setEndpoints, afterReplan, errorText, readScen } from './harness.mjs';

const ARENA = path.join(DATA, 'movingai/dao/arena.map');
const ROW = readScen(`${ARENA}.scen`).find((r) => r.optimal > 55);

let session;
before(async () => {
  session = await startSession();
});
after(async () => {
  await session?.close();
});

const state = (page) => page.evaluate(() => window.planlabExplain.state());

/** Steps forward with the player's button until the current event is an
 *  expansion; returns the panel's state then. */
async function stepToExpansion(page) {
  for (let i = 0; i < 200; i++) {
    await page.click('#step-fwd');
    const s = await state(page);
    if (s?.kind === 'expand') return s;
  }
  throw new Error('no expansion within 200 steps');
}

/** What the panel shows: the f line (text and data), the lit pseudo-code
 *  lines and the open list. */
function panel(page) {
  return page.evaluate(() => {
    const f = document.querySelector('#explain .explain-f');
    const lit = Array.from(document.querySelectorAll('#explain .explain-code .line.current'));
    return {
      fText: f.textContent,
      f: Number(f.dataset.f),
      g: Number(f.dataset.g),
      h: Number(f.dataset.h),
      w: Number(f.dataset.w),
      cell: [Number(f.dataset.col), Number(f.dataset.row)],
      lit: lit.map((l) => ({ role: l.dataset.role, text: l.textContent })),
      open: Array.from(document.querySelectorAll('#explain .explain-open li')).map((li) => [Number(li.dataset.col), Number(li.dataset.row)]),
      missing: document.querySelector('#explain .explain-missing').hidden ? '' : document.querySelector('#explain .explain-missing').textContent,
      code: document.querySelector('#explain .explain-code').dataset.algorithm,
    };
  });
}

/** The three numbers of a shown "f A = g B + [w ·] h C" line. */
function shownNumbers(text) {
  const m = text.match(/f (-?[\d.]+) = g (-?[\d.]+) \+ (?:([\d.]+) · )?h (-?[\d.]+)/);
  assert.ok(m, `an "f = g + h" line: ${text}`);
  return { f: Number(m[1]), g: Number(m[2]), w: m[3] ? Number(m[3]) : 1, h: Number(m[4]) };
}

/** Opens the panel (closed by default). */
async function openPanel(page) {
  await page.click('#explain > summary');
  await page.waitForFunction(() => document.getElementById('explain').open);
}

async function setAlgorithm(page, value) {
  await afterReplan(page, () => page.selectOption('#algorithm', value));
}

test('stepping an A* search: f = g + h, the expand line is lit, the open list starts with the next expanded cell', async () => {
  const { page, problems } = await openPage(session);
  assert.equal(await page.evaluate(() => document.getElementById('explain').open), false, 'closed until asked for');
  await openPanel(page);
  await setEndpoints(page, ROW.start, ROW.goal);
  assert.equal(await errorText(page), null);
  await page.evaluate(() => window.planlabGrid.seek(60));
  let before = await stepToExpansion(page);
  let shown = await panel(page);
  for (let k = 0; k < 4; k++) {
    // f = g + h, in the data and in the numbers shown.
    assert.ok(Math.abs(shown.f - (shown.g + shown.h)) <= 0.01, `f ${shown.f} = g ${shown.g} + h ${shown.h}`);
    const n = shownNumbers(shown.fText);
    assert.equal(n.w, 1);
    assert.ok(Math.abs(n.f - (n.g + n.h)) <= 0.01, shown.fText);
    // The lit line is the expand line.
    assert.deepEqual(
      shown.lit.map((l) => l.role),
      ['expand'],
      JSON.stringify(shown.lit),
    );
    assert.match(shown.lit[0].text, /lowest f = g \+ w·h/);
    // The expanded cell is the player's current cell.
    assert.deepEqual(shown.cell, await page.evaluate(() => window.planlabGrid.current()));
    assert.ok(shown.open.length > 0 && shown.open.length <= 5, `open list ${JSON.stringify(shown.open)}`);
    const first = shown.open[0];
    // Its first entry is expanded at the next expansion step.
    const after = await stepToExpansion(page);
    const next = await panel(page);
    assert.deepEqual(next.cell, first, `after step ${before.expanded_at}: expanded ${next.cell}, the open list began with ${first}`);
    assert.equal(after.expanded_at, before.next_at);
    before = after;
    shown = next;
  }
  await page.locator('#explain').screenshot({ path: path.join(path.dirname(new URL(import.meta.url).pathname), 'screenshots/explain-astar-panel.png') });
  await screenshot(page, 'explain-astar-page.png');

  // Weighted A*: f = g + w·h with the planner's weight.
  await afterReplan(page, () =>
    page.evaluate(() => {
      const w = document.getElementById('weight');
      w.value = '1.5';
      w.dispatchEvent(new Event('input', { bubbles: true }));
    }),
  );
  await page.evaluate(() => window.planlabGrid.seek(30));
  await stepToExpansion(page);
  const weighted = await panel(page);
  assert.equal(weighted.w, 1.5);
  assert.ok(Math.abs(weighted.f - (weighted.g + 1.5 * weighted.h)) <= 0.01, JSON.stringify(weighted));
  const wn = shownNumbers(weighted.fText);
  assert.equal(wn.w, 1.5);
  assert.ok(Math.abs(wn.f - (wn.g + 1.5 * wn.h)) <= 0.01, weighted.fText);
  assert.deepEqual(problems, []);
  await page.close();
});

test('every grid search in the menu gets its pseudo-code and says what its events do not carry', async () => {
  const { page, problems } = await openPage(session);
  await openPanel(page);
  await setEndpoints(page, ROW.start, ROW.goal);
  const algorithms = await page.$$eval('#grid-searches option', (os) => os.map((o) => o.value));
  assert.ok(algorithms.length >= 10, algorithms.join(','));
  const seen = {};
  for (const a of algorithms) {
    await setAlgorithm(page, a);
    assert.equal(await errorText(page), null, a);
    await page.evaluate(() => window.planlabGrid.seek(20));
    await stepToExpansion(page);
    const p = await panel(page);
    assert.equal(p.code, a, `${a}: its own pseudo-code`);
    assert.deepEqual(
      p.lit.map((l) => l.role),
      ['expand'],
      `${a}: the expand line lit`,
    );
    seen[a] = p;
    if (['bidirectional-astar', 'ida-star', 'dstar-lite', 'safe-astar'].includes(a)) {
      assert.match(p.missing, /Not recorded: /, `${a} says what its events lack`);
      assert.deepEqual(p.open, [], `${a}: no open list it cannot rebuild`);
    } else {
      assert.equal(p.missing, '', a);
      assert.ok(p.open.length > 0, `${a}: an open list`);
    }
  }
  assert.match(seen.bfs.fText, /no f and no h/);
  assert.match(seen.greedy.fText, /key h [\d.]+/);
  assert.match(seen.dijkstra.fText, /f [\d.]+ = g [\d.]+ +\(no h/);
  assert.match(seen['safe-astar'].fText, /ε·L is not recorded/);
  assert.match(seen['dstar-lite'].fText, /rhs [\d.]+, h [\d.]+/);
  for (const a of ['jps', 'theta-star']) assert.ok(Math.abs(seen[a].f - (seen[a].g + seen[a].h)) <= 0.01, a);

  // Key-point A*: the segment checks after the search light the post line.
  await setAlgorithm(page, 'astar');
  await afterReplan(page, () => page.check('#keypoints'));
  const n = Number(await page.evaluate(() => document.body.dataset.searchEvents));
  await page.evaluate((k) => window.planlabGrid.seek(k), n);
  const end = await panel(page);
  assert.equal((await state(page)).kind, 'line');
  assert.deepEqual(
    end.lit.map((l) => l.role),
    ['post'],
    JSON.stringify(end.lit),
  );
  assert.match(end.lit[0].text, /key points/);
  assert.deepEqual(problems, []);
  await page.close();
});

test('the help lists every menu planner with its properties in plain words', async () => {
  const { page, problems } = await openPage(session);
  const algorithms = await page.$$eval('#algorithm option', (os) => os.map((o) => o.value));
  await page.click('#help-button');
  const props = await page.evaluate(
    (as) => Object.fromEntries(as.map((a) => [a, document.querySelector(`.help-planner[data-key="${a}"] .help-properties`)?.textContent ?? null])),
    algorithms,
  );
  for (const a of algorithms) {
    const p = props[a];
    assert.ok(p, `${a} has a properties line`);
    assert.match(p, /shortest/, `${a}: optimal? ${p}`);
    assert.match(p, /path if one exists/, `${a}: complete? ${p}`);
    assert.match(p, /grid|any-angle/, `${a}: any-angle? ${p}`);
    assert.match(p, /incremental/, `${a}: incremental? ${p}`);
  }
  assert.match(props['theta-star'], /any-angle/);
  assert.match(props['dstar-lite'], /incremental: after a wall/);
  assert.match(props.astar, /not incremental/);
  assert.match(props.greedy, /not the shortest/);
  assert.deepEqual(problems, []);
  await page.close();
});

test('on a 512 × 512 map the panel explains a mid-search step of Dijkstra (time printed)', async () => {
  const RANDOM512 = path.join(DATA, 'movingai/random/random512-10-0.map');
  const row = readScen(`${RANDOM512}.scen`).at(-1);
  const { page, problems } = await openPage(session);
  await openPanel(page);
  await afterReplan(page, () => page.setInputFiles('#file-input', RANDOM512));
  await setAlgorithm(page, 'dijkstra');
  await setEndpoints(page, row.start, row.goal);
  assert.equal(await errorText(page), null);
  const n = Number(await page.evaluate(() => document.body.dataset.searchEvents));
  assert.ok(n > 100_000, `${n} events`);
  await page.evaluate((k) => window.planlabGrid.seek(k), Math.floor(n / 2));
  const ms = [];
  const mid = await stepToExpansion(page);
  ms.push(await page.evaluate(() => window.planlabExplain.ms()));
  const first = (await panel(page)).open[0];
  await stepToExpansion(page);
  ms.push(await page.evaluate(() => window.planlabExplain.ms()));
  assert.deepEqual((await panel(page)).cell, first, 'the open list began with the cell expanded next');
  assert.ok(mid.open_len > 100, `${mid.open_len} open`);
  process.stderr.write(`random512 Dijkstra, ${n} events, ${mid.open_len} open at step ${mid.expanded_at}: explain ${ms.map((x) => x.toFixed(2)).join(', ')} ms\n`);
  assert.deepEqual(problems, []);
  await page.close();
});
