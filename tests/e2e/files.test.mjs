// End-to-end tests of the robot page's Files menu in headless Chromium:
// a scenario saved after editing (goal moved, mover added) re-opens to the
// identical trace, which `planlab run` on the saved file reproduces too;
// a ROS map (.yaml + .pgm) and a Moving AI map (dropped on the canvas) open
// with default start/goal and run; malformed files land in the error
// banner; a share link reproduces scenario and trace in a new page; the SVG
// export is a real vector drawing with the trail; the PNG is an image.

import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { REPO, DATA, SCREENSHOTS, startSession, screenshot, errorText } from './harness.mjs';

const DEMO = 'dwa-demo.json';
const CLI = path.join(REPO, 'target/release/planlab');
const TB3 = path.join(DATA, 'rosmaps/turtlebot3');
const ARENA = path.join(DATA, 'movingai/dao/arena.map');

let session;
let tmp;
before(async () => {
  session = await startSession();
  tmp = fs.mkdtempSync(path.join(os.tmpdir(), 'planlab-files-'));
});
after(async () => {
  await session?.close();
  if (tmp) fs.rmSync(tmp, { recursive: true, force: true });
});

function watch(page) {
  const problems = [];
  page.on('console', (m) => {
    if (m.type() === 'error') problems.push(`console.error: ${m.text()}`);
  });
  page.on('pageerror', (e) => problems.push(`pageerror: ${e.message}`));
  return problems;
}

async function waitReady(page) {
  await page.waitForFunction(() => ['ready', 'error'].includes(document.body.dataset.state), null, { timeout: 30_000 });
}

async function openRobot(url = `robot.html?scenario=${DEMO}`) {
  const page = await session.context.newPage();
  const problems = watch(page);
  await page.goto(session.base + url);
  await waitReady(page);
  assert.equal(await errorText(page), null, 'no error after loading');
  return { page, problems };
}

const hooks = (page, fn, ...args) => page.evaluate(([f, a]) => window.planlabRobot[f](...a), [fn, args]);
const bodyData = (page, key) => page.evaluate((k) => document.body.dataset[k], key);
const screenOf = (page, x, y) => hooks(page, 'toScreen', x, y);
const loadSeq = async (page) => Number(await bodyData(page, 'loadSeq'));

/** Runs `action` and waits until the page has loaded another scenario. */
async function afterLoad(page, action) {
  const n = await loadSeq(page);
  await action();
  await page.waitForFunction((k) => Number(document.body.dataset.loadSeq) > k, n, { timeout: 30_000 });
}

/** Plays at 8× until the episode ends; returns outcome and trace hash. */
async function runToEnd(page) {
  await page.selectOption('#speed', '8');
  await page.click('#play');
  await page.waitForFunction(() => document.body.dataset.state === 'done', null, { timeout: 180_000 });
  return { outcome: await bodyData(page, 'outcome'), hash: await bodyData(page, 'traceHash') };
}

/** Clicks a save button and returns the download's name and bytes. */
async function save(page, button) {
  const [dl] = await Promise.all([page.waitForEvent('download'), page.click(button)]);
  const file = await dl.path();
  return { name: dl.suggestedFilename(), bytes: fs.readFileSync(file) };
}

function cliHash(file) {
  assert.ok(fs.existsSync(CLI), 'build target/release/planlab first (cargo build --release -p planlab-cli)');
  const run = spawnSync(CLI, ['run', file, '--json'], { encoding: 'utf8', timeout: 180_000 });
  assert.equal(run.status, 0, run.stderr);
  const native = JSON.parse(run.stdout);
  return { ...native, dec: BigInt(`0x${native.trace_hash}`).toString() };
}

test('save after editing, re-open: identical trace, also from planlab run; SVG, PNG and CSVs', async () => {
  const { page, problems } = await openRobot();
  const moversBefore = (await hooks(page, 'movers')).length / 6;
  // Move the goal and add a mover, with real clicks and a drag.
  await page.click('#tool-goal');
  const goal = [10.6, 1.2];
  const g = await screenOf(page, ...goal);
  await page.mouse.click(g.x, g.y);
  await page.click('#tool-mover');
  await page.selectOption('#motion-model', 'back-and-forth');
  const from = [2.5, 4.5];
  const a = await screenOf(page, ...from);
  const b = await screenOf(page, from[0] + 0.6, from[1] - 0.3);
  await page.mouse.move(a.x, a.y);
  await page.mouse.down();
  await page.mouse.move(b.x, b.y, { steps: 10 });
  await page.mouse.up();
  assert.equal((await hooks(page, 'movers')).length / 6, moversBefore + 1);
  assert.equal(await errorText(page), null);

  // Save the scenario as it is now.
  const saved = await save(page, '#save-json');
  assert.match(saved.name, /^dwa-demo-room\.json$/);
  // Edits before Play reproduce exactly: no warning.
  assert.equal(await bodyData(page, 'liveEdits'), '0');
  assert.equal(await page.isVisible('#files-note'), false);
  const text = saved.bytes.toString('utf8');
  const s = JSON.parse(text);
  assert.equal(s.version, 1);
  assert.ok(s.map.rle || s.map.cells, 'map inline');
  assert.equal(s.map.file, undefined);
  const [gx, gy] = (await bodyData(page, 'goal')).split(',').map(Number);
  assert.deepEqual([s.goal.world.x, s.goal.world.y], [gx, gy], 'the moved goal');
  assert.ok(Math.hypot(gx - goal[0], gy - goal[1]) < 0.05);
  assert.equal(s.movers.length, moversBefore + 1, 'the added mover');
  assert.equal(s.local_planner.name, 'dwa');

  // Run the edited episode on the page.
  const first = await runToEnd(page);
  assert.equal(first.outcome, 'reached');

  // Exports of the finished run.
  const trace = await save(page, '#save-trace');
  assert.match(trace.name, /-trace\.csv$/);
  const traceRows = trace.bytes.toString('utf8').trim().split('\n');
  assert.ok(traceRows.length > 20, `${traceRows.length} trace rows`);
  assert.equal(traceRows.length - 1, Number(await bodyData(page, 'steps')) + 1, 'a row per step plus the start');
  const metrics = await save(page, '#save-metrics');
  const mrows = metrics.bytes.toString('utf8').trim().split('\n').map((l) => l.split(','));
  assert.deepEqual(mrows[0], ['name', 'value', 'unit']);
  const m = await hooks(page, 'metrics');
  const mget = (k) => mrows.find((r) => r[0] === k)?.[1];
  assert.equal(mget('outcome'), 'reached');
  assert.equal(Number(mget('path_length_m')), m.path_length_m);
  assert.equal(Number(mget('time_s')), m.time_s);

  const svg = await save(page, '#save-svg');
  assert.match(svg.name, /\.svg$/);
  const svgText = svg.bytes.toString('utf8');
  const parsed = await page.evaluate((t) => {
    const d = new DOMParser().parseFromString(t, 'image/svg+xml');
    const pts = (id) => (d.getElementById(id)?.getAttribute('points') ?? '').trim().split(/\s+/).filter(Boolean).length;
    return {
      error: d.getElementsByTagName('parsererror').length > 0,
      root: d.documentElement.nodeName,
      ns: d.documentElement.namespaceURI,
      trail: pts('trail'),
      path: pts('global-path'),
      walls: (d.getElementById('walls')?.getAttribute('d') ?? '').split('Z').length - 1,
      movers: d.querySelectorAll('#movers .mover').length,
      robot: !!d.getElementById('robot'),
      goal: !!d.getElementById('goal'),
      images: d.getElementsByTagName('image').length,
    };
  }, svgText);
  assert.equal(parsed.error, false, 'SVG parses');
  assert.equal(parsed.root, 'svg');
  assert.equal(parsed.ns, 'http://www.w3.org/2000/svg');
  assert.equal(parsed.trail, traceRows.length - 1, 'the trail has every trace position');
  assert.ok(parsed.walls >= 4, `${parsed.walls} merged wall rectangles`);
  assert.ok(parsed.walls < 200, `walls merged into few rectangles, not a rect per cell: ${parsed.walls}`);
  assert.equal(parsed.movers, moversBefore + 1);
  assert.ok(parsed.robot && parsed.goal);
  assert.equal(parsed.images, 0, 'vector, no embedded raster');
  fs.mkdirSync(SCREENSHOTS, { recursive: true });
  fs.writeFileSync(path.join(SCREENSHOTS, 'files-export.svg'), svgText);
  // Look at it: render the SVG on its own page.
  const viewer = await session.context.newPage();
  await viewer.setContent(`<body style="margin:0;background:#fff">${svgText}</body>`);
  await viewer.setViewportSize({ width: 1000, height: 760 });
  await screenshot(viewer, 'files-03-svg-export.png');
  await viewer.close();

  const png = await save(page, '#save-png');
  assert.match(png.name, /\.png$/);
  assert.ok(png.bytes.length > 1000, `PNG of ${png.bytes.length} bytes`);
  assert.deepEqual([...png.bytes.subarray(0, 8)], [0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a], 'PNG signature');
  await screenshot(page, 'files-01-edited-run.png');

  // Re-open the saved file: same scenario, same trace.
  await afterLoad(page, () => page.setInputFiles('#file-input', { name: 'exported.json', mimeType: 'application/json', buffer: saved.bytes }));
  assert.equal(await errorText(page), null);
  assert.equal((await hooks(page, 'movers')).length / 6, moversBefore + 1);
  const again = await runToEnd(page);
  assert.equal(again.outcome, first.outcome);
  assert.equal(again.hash, first.hash, 'identical trace after re-opening the saved scenario');

  // The CLI accepts the saved file and gives the same trace.
  const file = path.join(tmp, 'exported.json');
  fs.writeFileSync(file, saved.bytes);
  const native = cliHash(file);
  console.log(`exported scenario: page ${first.hash}, re-opened ${again.hash}, planlab run ${native.trace_hash} (= ${native.dec}); ${native.outcome} after ${native.steps} steps`);
  assert.equal(native.dec, first.hash, 'planlab run on the saved file gives the page trace');
  assert.deepEqual(problems, []);
  await page.close();
});

test('saving after a goal move during the run says the file runs differently, and it does', async () => {
  const { page, problems } = await openRobot();
  await page.click('#play');
  await page.waitForFunction(() => Number(document.body.dataset.time) >= 2.0, null, { timeout: 30_000 });
  await page.click('#play');
  await page.click('#tool-goal');
  const goal = [10.6, 1.2];
  const g = await screenOf(page, ...goal);
  await page.mouse.click(g.x, g.y);
  const saved = await save(page, '#save-json');
  assert.equal(await bodyData(page, 'liveEdits'), '1');
  const note = await page.textContent('#files-note');
  assert.ok(await page.isVisible('#files-note'), 'the note is shown');
  assert.match(note, /1 edit made while this run went on \(t > 0\) is saved as in force from t = 0/);
  await screenshot(page, 'files-live-edit-note.png');
  const s = JSON.parse(saved.bytes.toString('utf8'));
  assert.ok(Math.hypot(s.goal.world.x - goal[0], s.goal.world.y - goal[1]) < 0.05, 'the file has the new goal');
  // The run on the page (old goal for 2 s, then the new one) and the file's
  // run (new goal from t = 0) differ, as the note says.
  const page_ = await runToEnd(page);
  const file = path.join(tmp, 'live-edit.json');
  fs.writeFileSync(file, saved.bytes);
  const native = cliHash(file);
  assert.notEqual(native.dec, page_.hash);
  // A new run forgets the note.
  await page.click('#reset');
  await page.waitForFunction(() => document.body.dataset.outcome === 'running');
  assert.equal(await page.isVisible('#files-note'), false);
  assert.deepEqual(problems, []);
  await page.close();
});

test('a ROS map (.yaml + .pgm) opens with default start and goal, and DWA runs on it', async () => {
  const { page, problems } = await openRobot();
  const files = ['map.yaml', 'map.pgm'].map((f) => path.join(TB3, f));
  await afterLoad(page, () => page.setInputFiles('#file-input', files));
  assert.equal(await errorText(page), null);
  assert.match(await page.textContent('#map-size'), /^384 × 384 · 0\.05 m/);
  assert.equal(await page.inputValue('#planner'), 'dwa');
  assert.equal(await bodyData(page, 'opened'), 'map.yaml');
  await screenshot(page, 'files-04-ros-map.png');
  const r = await runToEnd(page);
  assert.equal(r.outcome, 'reached', 'DWA reaches the default goal on the TurtleBot3 world');
  await screenshot(page, 'files-05-ros-map-reached.png');
  // A 384×384 map still fits a share link.
  await page.click('#share-link');
  await page.waitForFunction(() => document.getElementById('share-url').value.includes('#s='));
  assert.ok(Number(await bodyData(page, 'shareLength')) < 64 * 1024);
  assert.deepEqual(problems, []);
  await page.close();
});

test('a Moving AI map dropped on the canvas opens with start and goal far apart', async () => {
  const { page, problems } = await openRobot();
  const text = fs.readFileSync(ARENA, 'utf8');
  const dt = await page.evaluateHandle((t) => {
    const d = new DataTransfer();
    d.items.add(new File([t], 'arena.map', { type: 'text/plain' }));
    return d;
  }, text);
  await afterLoad(page, async () => {
    await page.dispatchEvent('#canvas-wrap', 'dragenter', { dataTransfer: dt });
    await page.dispatchEvent('#canvas-wrap', 'dragover', { dataTransfer: dt });
    await page.dispatchEvent('#canvas-wrap', 'drop', { dataTransfer: dt });
  });
  assert.equal(await errorText(page), null);
  assert.match(await page.textContent('#map-size'), /^49 × 49 · 1 m/);
  const [sx, sy] = await hooks(page, 'state');
  const goal = (await save(page, '#save-json')).bytes.toString('utf8');
  const s = JSON.parse(goal);
  const apart = Math.hypot(s.goal.world.x - sx, s.goal.world.y - sy);
  assert.ok(apart > 20, `start and goal ${apart.toFixed(1)} m apart on a 49 m map`);
  assert.equal(s.name, 'arena');
  // It runs.
  await page.click('#step');
  await page.click('#step');
  assert.equal(Number(await bodyData(page, 'steps')), 2);
  assert.equal(await errorText(page), null);
  await screenshot(page, 'files-06-movingai.png');
  assert.deepEqual(problems, []);
  await page.close();
});

test('malformed files show the error banner with the core message; the page keeps working', async () => {
  const { page, problems } = await openRobot();
  const cases = [
    [{ name: 'garbage.map', mimeType: 'text/plain', buffer: Buffer.from('type octile\nheight x\nwidth 3\nmap\n...\n') }, /garbage\.map: .*height/i],
    [{ name: 'broken.json', mimeType: 'application/json', buffer: Buffer.from('{"version": 1,\n "map": ') }, /broken\.json: scenario JSON error at line 2/],
    [{ name: 'alone.yaml', mimeType: 'text/yaml', buffer: Buffer.from('image: alone.pgm\nresolution: 0.05\norigin: [0, 0, 0]\nnegate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n') }, /alone\.pgm/],
    [{ name: 'image.pgm', mimeType: 'image/x-portable-graymap', buffer: Buffer.from('P5\n2 2\n255\n\x00') }, /\.yaml/],
    [{ name: 'notes.txt', mimeType: 'text/plain', buffer: Buffer.from('hello') }, /Cannot open notes\.txt/],
    [{ name: 'v2.json', mimeType: 'application/json', buffer: Buffer.from('{"version": 2}') }, /version 2 is not supported/],
  ];
  for (const [file, re] of cases) {
    await page.setInputFiles('#file-input', file);
    await page
      .waitForFunction(
        ([src, flags]) => !document.getElementById('error').hidden && new RegExp(src, flags).test(document.getElementById('error').textContent),
        [re.source, re.flags],
        { timeout: 5000 },
      )
      .catch(() => {});
    const msg = await errorText(page);
    assert.match(msg ?? '(no error shown)', re, file.name);
    console.log(`${file.name}: ${msg}`);
    if (file.name === 'garbage.map') await screenshot(page, 'files-07-error.png');
  }
  // A file over the page's 64 MB limit is refused by its size before it is
  // read (Playwright passes files over 50 MB by path, not as a buffer).
  const hugeDir = fs.mkdtempSync(path.join(os.tmpdir(), 'planlab-huge-'));
  const huge = path.join(hugeDir, 'huge.map');
  fs.writeFileSync(huge, Buffer.alloc(65 * 1024 * 1024, 0x2e));
  try {
    await page.setInputFiles('#file-input', huge);
    await page
      .waitForFunction(() => /huge\.map is 65 MB/.test(document.getElementById('error').textContent), null, { timeout: 5000 })
      .catch(() => {});
    assert.match((await errorText(page)) ?? '(no error shown)', /huge\.map is 65 MB: the page opens files up to 64 MB/);
  } finally {
    fs.rmSync(hugeDir, { recursive: true, force: true });
  }
  // A damaged share link on boot: the banner, and the preset loads anyway.
  const bad = await session.context.newPage();
  const badProblems = watch(bad);
  await bad.goto(`${session.base}robot.html#s=AAAA-not-deflate`);
  await waitReady(bad);
  assert.match((await errorText(bad)) ?? '', /shared link/);
  assert.deepEqual(badProblems, []);
  await bad.close();
  // Still alive.
  const t0 = Number(await bodyData(page, 'time'));
  await page.click('#step');
  assert.ok(Number(await bodyData(page, 'time')) > t0);
  assert.deepEqual(problems, []);
  await page.close();
});

test('a share link reproduces the scenario and the trace in a new page', async () => {
  await session.context.grantPermissions(['clipboard-read', 'clipboard-write'], { origin: session.base });
  const { page, problems } = await openRobot();
  await page.click('#tool-goal');
  const g = await screenOf(page, 10.0, 7.2);
  await page.mouse.click(g.x, g.y);
  await page.click('#share-link');
  await page.waitForFunction(() => document.getElementById('share-url').value.includes('#s='));
  const link = await page.inputValue('#share-url');
  assert.ok(link.startsWith(`${session.base}robot.html`), link.slice(0, 80));
  const clip = await page.evaluate(() => navigator.clipboard.readText());
  assert.equal(clip, link, 'the link is on the clipboard');
  console.log(`share link: ${link.length} characters`);
  const mine = (await save(page, '#save-json')).bytes.toString('utf8');
  await screenshot(page, 'files-08-share.png');

  const other = await session.context.newPage();
  const otherProblems = watch(other);
  await other.goto(link);
  await waitReady(other);
  assert.equal(await errorText(other), null);
  assert.equal(await bodyData(other, 'opened'), 'shared link');
  const theirs = (await save(other, '#save-json')).bytes.toString('utf8');
  assert.equal(theirs, mine, 'the same scenario');
  const a = await runToEnd(page);
  const b = await runToEnd(other);
  assert.equal(b.hash, a.hash, 'the same trace');
  await screenshot(other, 'files-09-shared-run.png');
  assert.deepEqual(otherProblems, []);
  await other.close();

  // Too large for a link: a clear message, no link.
  // Seeded noise (an LCG): about a bit per cell, beyond any compression.
  const rows = [];
  let x = 12345;
  const W = 800;
  for (let r = 0; r < W; r++) {
    let row = '';
    for (let c = 0; c < W; c++) {
      x = (Math.imul(x, 1103515245) + 12345) >>> 0;
      row += r % 50 === 0 || (x >>> 16) & 1 ? '.' : '@';
    }
    rows.push(row);
  }
  const big = `type octile\nheight ${W}\nwidth ${W}\nmap\n${rows.join('\n')}\n`;
  await afterLoad(page, () => page.setInputFiles('#file-input', { name: 'noise.map', mimeType: 'text/plain', buffer: Buffer.from(big) }));
  await page.click('#share-link');
  await page.waitForFunction(() => !document.getElementById('error').hidden, null, { timeout: 10_000 });
  assert.match(await errorText(page), /too large for a share link/);
  assert.equal(await page.getAttribute('#share-url', 'hidden'), '');
  assert.deepEqual(problems, []);
  await page.close();
});

test('MCAP: the page saves the run as an MCAP file with the same messages as planlab run --mcap', async () => {
  const { page, problems } = await openRobot();
  const json = await save(page, '#save-json');
  const mcap = await save(page, '#save-mcap');
  assert.match(mcap.name, /\.mcap$/);
  const MAGIC = Buffer.from([0x89, 0x4d, 0x43, 0x41, 0x50, 0x30, 0x0d, 0x0a]);
  assert.deepEqual(mcap.bytes.subarray(0, 8), MAGIC, 'MCAP magic at the start');
  assert.deepEqual(mcap.bytes.subarray(-8), MAGIC, 'and at the end (a finished file)');
  for (const s of ['/robot/pose', '/plan/global', '/movers', 'foxglove.PoseInFrame', 'foxglove.Grid']) {
    assert.ok(mcap.bytes.includes(Buffer.from(s)), `${s} in the file`);
  }
  // The CLI on the saved scenario writes the same records (their order in
  // the summary is the writer's hash order, so compare sizes, not bytes).
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'planlab-mcap-'));
  const scen = path.join(dir, 'saved.json');
  fs.writeFileSync(scen, json.bytes);
  const out = path.join(dir, 'cli.mcap');
  const run = spawnSync(CLI, ['run', scen, '--mcap', out, '--json'], { encoding: 'utf8', timeout: 180_000 });
  assert.equal(run.status, 0, run.stderr);
  assert.equal(fs.statSync(out).size, mcap.bytes.length);
  assert.equal(await errorText(page), null);
  assert.deepEqual(problems, []);
  await page.close();
});
