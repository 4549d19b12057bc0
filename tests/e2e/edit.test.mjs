// End-to-end tests of the robot page's editing tools in headless Chromium,
// with real mouse drags and keys: a wall drawn across the route makes the
// replanned run go around it to the goal; a wall over the start is refused
// in the banner; rectangles and discs land in the episode's map and undo /
// redo take them out and back (map hash); a waypoint mover path is built by
// clicks; the start is placed with a heading; a seeded maze is the same map
// twice and the same as `planlab generate`'s; a generated rooms map is run
// to the goal. No console errors; screenshots saved.

import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { REPO, startSession, screenshot, errorText, openRobotPage } from './harness.mjs';

const PRESET = 'T-fig3-2.json';

let session;
before(async () => {
  session = await startSession();
});
after(async () => {
  await session?.close();
});

async function openRobot(scenario = PRESET) {
  return openRobotPage(session, `robot.html?scenario=${scenario}`);
}

const edit = (page, fn, ...args) => page.evaluate(([f, a]) => window.planlabEdit[f](...a), [fn, args]);
const robot = (page, fn, ...args) => page.evaluate(([f, a]) => window.planlabRobot[f](...a), [fn, args]);
const bodyData = (page, key) => page.evaluate((k) => document.body.dataset[k], key);

/** Waits until the world → page mapping holds still over two frames: a
 *  tool key changes the hint above the canvas, and the canvas is re-laid
 *  out and the view re-fitted a frame later, so a point read straight after
 *  the key can be a few pixels off by the time the mouse goes down. */
async function settled(page) {
  const mapping = () =>
    page.evaluate(async () => {
      await new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r)));
      return JSON.stringify([window.planlabRobot.toScreen(0, 0), window.planlabRobot.toScreen(1, 1)]);
    });
  let last = await mapping();
  for (let i = 0; i < 50; i++) {
    const now = await mapping();
    if (now === last) return;
    last = now;
  }
  throw new Error('the robot view never settled');
}

/** Drags with the real mouse between world points (m). */
async function drag(page, from, to, steps = 12) {
  await settled(page);
  const a = await robot(page, 'toScreen', from[0], from[1]);
  const b = await robot(page, 'toScreen', to[0], to[1]);
  await page.mouse.move(a.x, a.y);
  await page.mouse.down();
  await page.mouse.move(b.x, b.y, { steps });
  await page.mouse.up();
}

async function clickWorld(page, p) {
  await settled(page);
  const a = await robot(page, 'toScreen', p[0], p[1]);
  await page.mouse.click(a.x, a.y);
}

async function key(page, k) {
  // Keys go to the page, not a focused form field.
  await page.evaluate(() => document.activeElement instanceof HTMLElement && document.activeElement.blur());
  await page.keyboard.press(k);
}

async function runToEnd(page, timeout = 150_000) {
  await page.selectOption('#speed', '8');
  await page.click('#play');
  await page.waitForFunction(() => document.body.dataset.outcome && document.body.dataset.outcome !== 'running', null, {
    timeout,
  });
  return bodyData(page, 'outcome');
}

/** Distance from p to the segment a–b. */
function segDist(p, a, b) {
  const [dx, dy] = [b[0] - a[0], b[1] - a[1]];
  const t = Math.max(0, Math.min(1, ((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / (dx * dx + dy * dy)));
  return Math.hypot(a[0] + t * dx - p[0], a[1] + t * dy - p[1]);
}

test('a wall drawn across the route: the run replans around it and reaches the goal; a wall over the start is refused', async () => {
  const { page, problems } = await openRobot();
  const hash0 = await edit(page, 'gridHash');
  // Let the robot start, then edit: the run restarts from the start.
  await page.click('#step');
  await page.click('#step');
  await key(page, 'w');
  assert.equal(await page.getAttribute('#tool-wall', 'aria-checked'), 'true');
  assert.match(await page.getAttribute('#tool-wall', 'title'), /\(W\)/);
  const [a, b] = [
    [4.0, 2.2],
    [4.0, 5.8],
  ];
  await drag(page, a, b, 20);
  assert.equal(await errorText(page), null);
  assert.equal(await edit(page, 'occupied', 4.0, 4.0), true, 'the wall is in the episode map');
  assert.equal(await edit(page, 'occupied', 4.0, 6.5), false);
  assert.notEqual(await edit(page, 'gridHash'), hash0);
  assert.equal(await bodyData(page, 'steps'), '0', 'the edit restarted the episode');
  assert.deepEqual((await edit(page, 'start')).slice(0, 2), [1.5, 4.0]);
  // The global path (after one step) goes around the wall's ends.
  await page.click('#step');
  const gp = await edit(page, 'globalPath');
  assert.ok(gp.length >= 4, 'a global path');
  let nearest = Infinity;
  for (let i = 0; i + 1 < gp.length; i += 2) nearest = Math.min(nearest, segDist([gp[i], gp[i + 1]], a, b));
  assert.ok(nearest > 0.25, `global path keeps off the wall (${nearest.toFixed(2)} m)`);
  const ys = [];
  for (let i = 0; i + 1 < gp.length; i += 2) if (Math.abs(gp[i] - 4.0) < 0.3) ys.push(gp[i + 1]);
  assert.ok(ys.length && ys.every((y) => y < 2.2 || y > 5.8), `crosses x = 4 beyond the wall: ${ys}`);
  assert.equal(await runToEnd(page), 'reached');
  await screenshot(page, 'edit-wall-detour.png');
  // A disc over the start is refused with the core's message; nothing changes.
  const before = await edit(page, 'gridHash');
  await key(page, 'c');
  await drag(page, [1.5, 4.0], [1.9, 4.0]);
  const err = await errorText(page);
  assert.ok(err && /Disc refused/.test(err) && /starts in collision/.test(err) && /wall/.test(err), err ?? 'no error');
  assert.equal(await edit(page, 'gridHash'), before);
  assert.deepEqual(problems, []);
  await page.close();
});

test('rectangle and disc land in the map; undo removes them and redo brings them back', async () => {
  const { page, problems } = await openRobot();
  const h0 = await edit(page, 'gridHash');
  await page.click('#tool-rect');
  await drag(page, [8.5, 1.0], [9.6, 2.1]);
  assert.equal(await edit(page, 'occupied', 9.0, 1.5), true, 'rectangle painted');
  assert.equal(await edit(page, 'occupied', 10.0, 1.5), false);
  const h1 = await edit(page, 'gridHash');
  await key(page, 'c');
  await drag(page, [9.0, 6.2], [9.6, 6.2]);
  assert.equal(await edit(page, 'occupied', 9.0, 6.2), true, 'disc painted');
  assert.equal(await edit(page, 'occupied', 9.45, 6.2), true, 'disc radius 0.6 m');
  assert.equal(await edit(page, 'occupied', 9.0, 7.0), false);
  const h2 = await edit(page, 'gridHash');
  assert.ok(h0 !== h1 && h1 !== h2);
  assert.equal(await bodyData(page, 'undo'), '2');
  await screenshot(page, 'edit-rect-disc.png');
  // Undo with the keyboard, then the button.
  await key(page, 'Control+z');
  assert.equal(await edit(page, 'occupied', 9.0, 6.2), false, 'undo removed the disc');
  assert.equal(await edit(page, 'gridHash'), h1);
  await page.click('#undo');
  assert.equal(await edit(page, 'occupied', 9.0, 1.5), false, 'undo removed the rectangle');
  assert.equal(await edit(page, 'gridHash'), h0);
  assert.equal(await page.isDisabled('#undo'), true);
  // Redo both ways.
  await key(page, 'Control+Shift+z');
  assert.equal(await edit(page, 'gridHash'), h1);
  await key(page, 'Control+y');
  assert.equal(await edit(page, 'gridHash'), h2);
  assert.equal(await edit(page, 'occupied', 9.0, 6.2), true);
  assert.equal(await page.isDisabled('#redo'), true);
  // Reset keeps the edited map.
  await page.click('#reset');
  assert.equal(await edit(page, 'gridHash'), h2);
  // A new edit after an undo drops the redo branch.
  await key(page, 'Control+z');
  await key(page, 'e');
  await drag(page, [9.0, 1.2], [9.0, 1.8]);
  assert.equal(await edit(page, 'occupied', 9.0, 1.5), false, 'erased');
  assert.equal(await edit(page, 'redoDepth'), 0);
  assert.equal(await errorText(page), null);
  assert.deepEqual(problems, []);
  await page.close();
});

test('start with a heading and a waypoint mover path built by clicks', async () => {
  const { page, problems } = await openRobot();
  await key(page, 's');
  await drag(page, [2.0, 2.0], [3.0, 3.0]);
  const st = await edit(page, 'start');
  assert.ok(Math.abs(st[0] - 2.0) < 0.05 && Math.abs(st[1] - 2.0) < 0.05, `start ${st}`);
  assert.ok(Math.abs(st[2] - Math.PI / 4) < 0.1, `heading ${st[2]}`);
  // A start in the map's border wall: refused, the start stays.
  assert.equal(await edit(page, 'occupied', 0.05, 4.0), true);
  await clickWorld(page, [0.05, 4.0]);
  const err = await errorText(page);
  assert.ok(err && /Start refused/.test(err) && /starts in collision/.test(err), err ?? 'no error');
  assert.deepEqual(await edit(page, 'start'), st);
  await key(page, 'l');
  await page.fill('#path-speed', '0.5');
  await page.fill('#path-radius', '0.3');
  await key(page, 'l');
  for (const p of [
    [3.0, 6.5],
    [6.0, 6.8],
    [5.0, 7.2],
  ])
    await clickWorld(page, p);
  assert.equal(await bodyData(page, 'pathPoints'), '3');
  await key(page, 'Enter');
  const movers = await edit(page, 'movers');
  const loop = movers.find((m) => m.motion.model === 'waypoint-loop');
  assert.ok(loop, JSON.stringify(movers));
  assert.equal(loop.motion.points.length, 3);
  assert.equal(loop.motion.speed, 0.5);
  assert.equal(loop.radius, 0.3);
  assert.ok(Math.abs(loop.motion.points[1][0] - 6.0) < 0.05);
  // It moves along the path when the run plays.
  const m0 = await robot(page, 'movers');
  await page.click('#play');
  await page.waitForFunction(() => Number(document.body.dataset.time) >= 1.0, null, { timeout: 30_000 });
  await page.click('#play');
  const m1 = await robot(page, 'movers');
  const i = m0.findIndex((v, k) => k % 6 === 0 && v === loop.id);
  assert.ok(i >= 0);
  assert.ok(Math.hypot(m1[i + 2] - m0[i + 2], m1[i + 3] - m0[i + 3]) > 0.3, 'the path mover moved');
  await screenshot(page, 'edit-path-mover.png');
  // Undo removes the mover.
  await key(page, 'Control+z');
  assert.equal((await edit(page, 'movers')).filter((m) => m.motion.model === 'waypoint-loop').length, 0);
  assert.deepEqual(problems, []);
  await page.close();
});

/** The `planlab` binary with the generate command (release, else debug). */
function cli() {
  for (const p of ['target/release/planlab', 'target/debug/planlab']) {
    const bin = path.join(REPO, p);
    if (fs.existsSync(bin) && spawnSync(bin, ['generate', '--help']).status === 0) return bin;
  }
  throw new Error('build planlab (cargo build --release -p planlab-cli) for the CLI comparison');
}

test('generate: a seeded maze is the same map twice and the same as planlab generate; a rooms map runs to the goal', async () => {
  const { page, problems } = await openRobot();
  await page.selectOption('#gen-kind', 'maze');
  await page.fill('#gen-seed', '7');
  await page.click('#generate');
  assert.equal(await errorText(page), null);
  const h7 = await bodyData(page, 'generatedHash');
  assert.equal(await edit(page, 'gridHash'), h7);
  assert.deepEqual(await edit(page, 'mapSize'), [100, 80, 0.1]);
  await page.fill('#gen-seed', '8');
  await page.click('#generate');
  assert.notEqual(await bodyData(page, 'generatedHash'), h7);
  await page.fill('#gen-seed', '7');
  await page.click('#generate');
  assert.equal(await bodyData(page, 'generatedHash'), h7, 'same seed, same maze');
  await screenshot(page, 'edit-maze-seed7.png');
  const out = path.join(fs.mkdtempSync(path.join(os.tmpdir(), 'planlab-edit-')), 'maze7.json');
  const r = spawnSync(cli(), ['generate', 'maze', '--seed', '7', '--width', '10', '--height', '8', '--resolution', '0.1', '--out', out, '--json'], {
    encoding: 'utf8',
  });
  assert.equal(r.status, 0, r.stderr);
  const native = JSON.parse(r.stdout);
  assert.equal(native.grid_hash, h7, 'browser and CLI generate the same grid');
  const [sx, sy] = await edit(page, 'start');
  assert.ok(Math.abs(sx - native.start[0]) < 1e-9 && Math.abs(sy - native.start[1]) < 1e-9);
  // Bad settings: the banner, the map unchanged.
  await page.selectOption('#gen-kind', 'random');
  await page.fill('#gen-density', '95');
  await page.click('#generate');
  assert.match((await errorText(page)) ?? '', /density/);
  assert.equal(await edit(page, 'gridHash'), h7);
  // Rooms, run to the goal.
  await page.selectOption('#gen-kind', 'rooms');
  await page.fill('#gen-seed', '0');
  await page.click('#generate');
  assert.equal(await errorText(page), null);
  assert.equal(await runToEnd(page), 'reached');
  await screenshot(page, 'edit-rooms-reached.png');
  assert.deepEqual(problems, []);
  await page.close();
});

test('the Preset menu says what is shown: generated map, edited map, opened file; undo puts the name back', async () => {
  const { page, problems } = await openRobot();
  const shown = () => page.evaluate(() => {
    const s = document.getElementById('preset');
    return { value: s.value, text: s.selectedOptions[0]?.textContent };
  });
  const preset = await shown();
  assert.equal(preset.value, PRESET);
  assert.match(preset.text, /^\[T\] Fig 3-2/);
  // Generate: the preset's name no longer stands for the map.
  await page.selectOption('#gen-kind', 'maze');
  await page.fill('#gen-seed', '7');
  await page.click('#generate');
  await page.waitForFunction(() => document.body.dataset.generatedHash);
  assert.deepEqual(await shown(), { value: '', text: 'Generated: maze, seed 7' });
  // An edit of the generated map says so.
  await page.click('#tool-rect');
  await drag(page, [4.0, 3.0], [4.4, 3.4]);
  assert.equal(await errorText(page), null);
  assert.deepEqual(await shown(), { value: '', text: 'Edited: generated maze, seed 7' });
  // Undo walks the name back with the map.
  await key(page, 'Control+z');
  assert.deepEqual(await shown(), { value: '', text: 'Generated: maze, seed 7' });
  await key(page, 'Control+z');
  assert.deepEqual(await shown(), preset);
  // Moving the goal of the preset is an edit too; picking the preset again
  // reloads it as it was.
  await page.click('#tool-goal');
  await clickWorld(page, [9.0, 2.0]);
  assert.deepEqual(await shown(), { value: '', text: `Edited: ${preset.text}` });
  // The compare link still opens its preset.
  await page.dispatchEvent('#compare-link', 'pointerenter');
  assert.match(await page.getAttribute('#compare-link', 'href'), /scenario=T-fig3-2\.json/);
  const seq = () => page.evaluate(() => Number(document.body.dataset.loadSeq ?? 0));
  const k = await seq();
  await page.selectOption('#preset', PRESET);
  await page.waitForFunction((k) => Number(document.body.dataset.loadSeq) > k, k, { timeout: 30_000 });
  assert.deepEqual(await shown(), preset);
  // A file opened: its name.
  const n = await seq();
  await page.setInputFiles('#file-input', { name: 'mine.json', mimeType: 'application/json', buffer: fs.readFileSync(path.join(REPO, 'assets/scenarios', PRESET)) });
  await page.waitForFunction((k) => Number(document.body.dataset.loadSeq) > k, n, { timeout: 30_000 });
  assert.deepEqual(await shown(), { value: '', text: 'Opened: mine.json' });
  assert.deepEqual(problems, []);
  await page.close();
});
