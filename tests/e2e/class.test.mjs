// What a class sees on the pages, in headless Chromium at 1440×900 (and
// 1366×768 for the compare page): generated maps that drive, notes that
// say why, presentation mode, the gallery's relations, and the beginner's
// help beside each paper. Each test checks what once failed in front of a
// class.

import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { startSession, screenshot, errorText, openRobotPage, watchedPage } from './harness.mjs';

let session;
before(async () => {
  session = await startSession();
});
after(async () => {
  await session?.close();
});

const ended = (page, timeout = 150_000) =>
  page.waitForFunction(() => document.body.dataset.outcome && document.body.dataset.outcome !== 'running', null, { timeout });

/** Plays at 8× until the episode ends; returns the metrics. */
async function playToEnd(page) {
  await page.selectOption('#speed', '8');
  await page.click('#play');
  await ended(page);
  return page.evaluate(() => window.planlabRobot.metrics());
}

async function openAt(url) {
  const { page, problems } = await watchedPage(session);
  await page.goto(session.base + url);
  await page.waitForFunction(() => ['ready', 'error', 'done'].includes(document.body.dataset.state), null, { timeout: 30_000 });
  return { page, problems };
}

async function openFile(page, name, text) {
  const n = await page.evaluate(() => Number(document.body.dataset.loadSeq ?? 0));
  await page.setInputFiles('#file-input', { name, mimeType: 'application/octet-stream', buffer: Buffer.from(text) });
  await page.waitForFunction((k) => Number(document.body.dataset.loadSeq) > k || !document.getElementById('error').hidden, n, { timeout: 30_000 });
}

/** A 6 × 4 m room split by a wall at x = 3 m with a gap `gap` cells tall. */
function splitRoom(gap) {
  const rows = [];
  for (let r = 0; r < 40; r++) rows.push('.'.repeat(30) + (r >= 20 && r < 20 + gap ? '.' : '#') + '.'.repeat(29));
  return JSON.stringify({
    version: 1,
    name: `split room, ${gap}-cell gap`,
    map: { width: 60, height: 40, resolution: 0.1, cells: rows },
    start: { col: 10, row: 19, world: { x: 1.05, y: 2.05 } },
    goal: { col: 50, row: 19, world: { x: 5.05, y: 2.05 } },
    local_planner: { name: 'dwa' },
  });
}

test('a generated maze (defaults, seed 7) is driven to the goal by improved-dwa and safe-dual-dwa', async () => {
  const { page, problems } = await openRobotPage(session, 'robot.html');
  await page.click('#generate');
  await page.waitForFunction(() => document.body.dataset.generatedHash, null, { timeout: 10_000 });
  for (const planner of ['improved-dwa', 'safe-dual-dwa']) {
    await page.selectOption('#planner', planner);
    await page.waitForTimeout(200);
    const m = await playToEnd(page);
    assert.equal(m.outcome, 'reached', `${planner}: ${m.outcome} after ${m.path_length_m} m`);
    await page.click('#reset');
  }
  assert.deepEqual(problems, []);
  await page.close();
});

test('a path that exists only without inflation is said in the status line', async () => {
  const { page, problems } = await openRobotPage(session, 'robot.html');
  await openFile(page, 'narrow.json', splitRoom(2));
  assert.equal(await errorText(page), null);
  const status = await page.textContent('#status');
  assert.match(status, /only without inflation/, status);
  assert.match(status, /radius 0\.20 m/, status);
  // A gap the robot fits through: nothing said.
  await openFile(page, 'wide.json', splitRoom(15));
  assert.doesNotMatch(await page.textContent('#status'), /inflation/);
  assert.deepEqual(problems, []);
  await page.close();
});

test('presentation mode (P) makes the map larger at 1440×900, panels on demand', async () => {
  const { page, problems } = await openRobotPage(session, 'robot.html');
  const box = () => page.locator('#sim-canvas').boundingBox();
  const normal = await box();
  await page.keyboard.press('p');
  await page.waitForTimeout(300);
  const large = await box();
  assert.ok(large.width > normal.width && large.height > normal.height, `normal ${JSON.stringify(normal)} large ${JSON.stringify(large)}`);
  assert.equal(await page.isVisible('.layout > .panel'), false, 'side panel folded');
  assert.equal(await page.isVisible('#plots'), false, 'plots folded');
  await screenshot(page, 'class-present.png');
  // On demand: the Panels button brings them back; P again leaves.
  await page.click('#panels-button');
  assert.equal(await page.isVisible('.layout > .panel'), true);
  await page.click('#panels-button');
  await page.keyboard.press('p');
  await page.waitForTimeout(300);
  const back = await box();
  assert.ok(Math.abs(back.width - normal.width) < 2, 'normal mode again');
  assert.deepEqual(problems, []);
  await page.close();
});

test('after Replay the note does not squeeze the timeline (one line, slider ≥ 300 px)', async () => {
  const { page, problems } = await openRobotPage(session, 'robot.html?scenario=T-fig3-2.json&planner=improved-dwa');
  await playToEnd(page);
  await page.click('#tl-replay');
  await page.waitForFunction(() => document.getElementById('timeline').dataset.replayMatch !== undefined, null, { timeout: 120_000 });
  const m = await page.evaluate(() => {
    const tops = Array.from(document.querySelectorAll('#timeline button')).map((b) => Math.round(b.getBoundingClientRect().top));
    const heights = Array.from(document.querySelectorAll('#timeline button')).map((b) => Math.round(b.getBoundingClientRect().height));
    return {
      tops,
      heights,
      slider: document.getElementById('tl-slider').getBoundingClientRect().width,
      note: document.getElementById('tl-note').textContent,
    };
  });
  assert.match(m.note, /replay identical/);
  // The hash in the form `planlab run` and the compare page print: hex.
  const dec = await page.getAttribute('body', 'data-trace-hash');
  assert.match(m.note, new RegExp(`trace hash ${BigInt(dec).toString(16).padStart(16, '0')}\\)`));
  assert.equal(new Set(m.tops).size, 1, `buttons on one line: ${m.tops}`);
  assert.ok(Math.max(...m.heights) < 30, `no button wraps: ${m.heights}`);
  assert.ok(m.slider >= 300, `slider ${m.slider} px`);
  assert.deepEqual(problems, []);
  await page.close();
});

test('preliminary-fusion on T-fig3-2 ending stuck while driving is named circling, not "stuck (no progress)"', async () => {
  const { page, problems } = await openRobotPage(session, 'robot.html?scenario=T-fig3-2.json&planner=preliminary-fusion');
  const m = await playToEnd(page);
  const v = (await page.evaluate(() => window.planlabRobot.state()))[3];
  const status = await page.textContent('#status');
  assert.equal(m.outcome, 'stuck', 'the outcome value is unchanged');
  assert.doesNotMatch(status, /stuck \(no progress\)/);
  if (Math.abs(v) >= 0.05) assert.match(status, /no progress toward the goal \(still moving at \d\.\d\d m\/s: circling\)/, status);
  else assert.match(status, /stopped: no progress toward the goal/, status);
  assert.deepEqual(problems, []);
  await page.close();
});

test('digits enough to check the relations; the gallery run ends with the relation ✓/✗', async () => {
  // Tracking error: three decimals (0.012 vs 0.031, not 0.01 vs 0.03).
  const { page, problems } = await openRobotPage(session, 'robot.html?scenario=T-fig3-2.json&planner=improved-dwa&run=1&exp=T-fig3-2&as=improved');
  await page.waitForSelector('#gallery-note');
  await page.click('#to-end');
  await ended(page);
  assert.match(await page.textContent('#metric-tracking'), /^\d\.\d{3} \/ \d\.\d{3}$/);
  await page.waitForFunction(() => document.body.dataset.relation, null, { timeout: 120_000 });
  assert.equal(await page.evaluate(() => document.body.dataset.relation), 'holds');
  const check = await page.textContent('.gallery-note-check');
  assert.match(check, /^✓ relation holds on the presets \(planlab reproduce T-fig3-2\)/, check);
  assert.match(check, /✓ improved reaches/);
  assert.match(check, /improved: reached · \d+\.\d\d s · \d+\.\d{3} m · tracking \d\.\d{4} m/, check);
  await screenshot(page, 'class-gallery-end.png');
  assert.deepEqual(problems, []);
  await page.close();
  // The potential-field and arm pages' gallery runs end with their relation too.
  for (const [url, id] of [
    ['apf.html?scenario=T-fig4-8.json&run=1&exp=T-fig4-8&as=apf', 'T-fig4-8'],
    ['arm.html?scenario=T-tab5-3.json&run=1&exp=T-tab5-3&as=rnn', 'T-tab5-3'],
  ]) {
    const g = await openAt(url);
    await g.page.waitForSelector('#gallery-note');
    await g.page.waitForFunction(() => document.body.dataset.relation, null, { timeout: 180_000 });
    const rel = await g.page.evaluate(() => document.body.dataset.relation);
    const text = await g.page.textContent('.gallery-note-check');
    assert.ok(rel === 'holds' || rel === 'fails', `${id}: ${rel}: ${text}`);
    assert.match(text, new RegExp(`^[✓✗] relation (holds|does not hold) on the presets \\(planlab reproduce ${id}\\)`), text);
    assert.match(text, /min distance \d\.\d{4} m/, text);
    assert.deepEqual(g.problems, []);
    await g.page.close();
  }
  // The arm's minimum distance to the hand: 0.1 mm (RNN vs constant velocity).
  const arm = await openAt('arm.html?scenario=T-tab5-3.json');
  await arm.page.waitForFunction(() => /\d\.\d{4} m/.test(document.getElementById('metric-min')?.textContent ?? ''), null, { timeout: 30_000 }).catch(() => {});
  const min = await arm.page.evaluate(() => Array.from(document.querySelectorAll('.metric b, .metrics b')).map((b) => b.textContent).join(' | '));
  assert.match(min, /\d\.\d{4} m/, min);
  await arm.page.close();
});

test('gallery runs at 4× with » To end; the note is whole; Run above the fold; shared link; NaN; garbage .map', async () => {
  // A gallery link opens at 4× and has a To end button.
  const g = await openAt('robot.html?scenario=S-tab1.json&planner=preliminary-fusion&run=1&exp=S-tab1&as=preliminary');
  await g.page.waitForSelector('#gallery-note');
  assert.equal(await g.page.inputValue('#speed'), '4');
  const t0 = Date.now();
  await g.page.click('#to-end');
  await ended(g.page, 60_000);
  assert.ok(Date.now() - t0 < 60_000);
  // The note shows its whole text (no "…" cut) at 1440 px.
  const cut = await g.page.evaluate(() => {
    const t = document.querySelector('.gallery-note-text');
    const s = getComputedStyle(t);
    return { over: t.scrollWidth > t.clientWidth + 1, ellipsis: s.textOverflow === 'ellipsis' && s.whiteSpace === 'nowrap' };
  });
  assert.deepEqual(cut, { over: false, ellipsis: false });
  await g.page.close();

  // Compare: Run is above the fold at 1366×768 and 1440×900.
  for (const [width, height] of [[1366, 768], [1440, 900]]) {
    const c = await session.context.newPage();
    await c.setViewportSize({ width, height });
    await c.goto(`${session.base}compare.html?scenario=T-fig3-2.json&planners=dwa,improved-dwa`);
    await c.waitForFunction(() => Number(document.body.dataset.buildSeq) > 0, null, { timeout: 30_000 });
    const b = await c.locator('#play').boundingBox();
    assert.ok(b && b.y + b.height <= height, `${width}×${height}: Run at y ${b?.y}`);
    await c.close();
  }

  // A shared link is not "Opened from disk".
  const { page, problems } = await openRobotPage(session, 'robot.html?scenario=T-fig3-2.json');
  await page.click('#share-link');
  await page.waitForFunction(() => document.getElementById('share-url').value.includes('#s='));
  const link = await page.inputValue('#share-url');
  const s = await openRobotPage(session, link.slice(session.base.length));
  const label = await s.page.evaluate(() => document.getElementById('preset').selectedOptions[0]?.textContent);
  assert.equal(label, 'Opened: a shared link');
  await s.page.close();

  // NaN in scenario JSON: the message names NaN.
  await openFile(page, 'nan.json', splitRoom(15).replace('"resolution":0.1', '"resolution":NaN'));
  const nan = await errorText(page);
  assert.match(nan ?? '', /NaN is not a number JSON allows/, nan);
  // A garbage .map: says what was expected, echoes no bytes.
  await openFile(page, 'garbage.map', '\u0089PNG\r\n\u001a\n\u0000\u0000garbage');
  const bad = await errorText(page);
  assert.match(bad ?? '', /not a Moving AI map: the first line should be `type octile`/, bad);
  assert.doesNotMatch(bad ?? '', /\\u\{|\\x|PNG/);
  assert.deepEqual(problems, []);
  await page.close();
});

test('plain-language planner help beside the paper; "What am I looking at?" on robot, compare, gallery, apf and arm', async () => {
  const { page, problems } = await openRobotPage(session, 'robot.html?scenario=T-fig3-2.json&planner=improved-dwa');
  await page.click('#help-button');
  const help = await page.evaluate(() => {
    const d = document.querySelector('.help-planner[open]');
    return { name: d?.dataset.planner, paper: d?.querySelector('.help-paper')?.textContent, plain: d?.querySelector('.help-plain')?.textContent };
  });
  assert.equal(help.name, 'improved-dwa');
  assert.match(help.paper, /\[T\] Wu 2022/);
  // Its citations of the algorithm notes are links that the site serves.
  const docs = await page.$$eval('.help-doc', (as) => as.map((a) => a.href));
  assert.ok(docs.length > 0, 'the help links docs/algorithms.md');
  const served = await page.evaluate(async (u) => {
    const r = await fetch(u);
    return { status: r.status, text: (await r.text()).slice(0, 200) };
  }, docs[0]);
  assert.equal(served.status, 200, docs[0]);
  assert.match(served.text, /^# /);
  assert.match(help.plain, /A\* finds a route/);
  assert.match(help.plain, /Watch/);
  await page.keyboard.press('Escape');
  await page.click('#explain summary');
  const legend = await page.textContent('#explain');
  for (const w of ['DWA fan', 'Chosen rollout', 'Ordinary dynamic obstacle', 'Special obstacle', 'Goal', 'collision', 'circling']) assert.ok(legend.includes(w), w);
  await screenshot(page, 'class-legend.png');
  assert.deepEqual(problems, []);
  await page.close();
  for (const url of ['compare.html?scenario=T-fig3-2.json', 'gallery.html', 'apf.html?scenario=T-fig4-6.json', 'arm.html?scenario=T-tab5-3.json']) {
    const p = await openAt(url);
    await p.page.waitForSelector('#explain summary', { timeout: 10_000 });
    await p.page.click('#explain summary');
    assert.ok((await p.page.textContent('#explain')).length > 150, url);
    assert.deepEqual(p.problems, [], url);
    await p.page.close();
  }
  // The compare page's help has the plain words too.
  const c = await openAt('compare.html?scenario=T-fig3-2.json&planners=dwa,improved-dwa');
  await c.page.click('#help-button');
  assert.match((await c.page.textContent('.help-planner[open] .help-plain')) ?? '', /imagines driving/);
  await c.page.close();
});

test('after » To end the plots\' cursors stand at the end of the run', async () => {
  const { page, problems } = await openRobotPage(session, 'robot.html');
  await page.click('#to-end');
  await page.waitForFunction(() => document.body.dataset.state === 'done', null, { timeout: 150_000 });
  const steps = Number(await page.getAttribute('body', 'data-steps'));
  await page.waitForFunction(
    (n) => Object.values(window.planlabTimeline.plotCursors()).every((r) => r === n),
    steps,
    { timeout: 5_000 },
  ).catch(() => {});
  const rows = await page.evaluate(() => window.planlabTimeline.plotCursors());
  assert.ok(Object.keys(rows).length >= 2, JSON.stringify(rows));
  for (const [k, r] of Object.entries(rows)) assert.equal(r, steps, `${k} cursor at row ${r} of ${steps}`);
  assert.deepEqual(problems, []);
  await page.close();
});

test('at t = 0 the robot is drawn on top of the start marker', async () => {
  const { page, problems } = await openRobotPage(session, 'robot.html');
  const [x, y] = await page.evaluate(() => window.planlabRobot.state());
  const at = await page.evaluate(([wx, wy]) => window.planlabRobot.toScreen(wx, wy), [x, y]);
  // The pixel at the robot's centre is the robot's (its body or heading
  // line), not the marker's green (#16a34a) drawn over it.
  const rgb = await page.evaluate(({ sx, sy }) => {
    const c = document.getElementById('sim-canvas');
    const r = c.getBoundingClientRect();
    const k = c.width / r.width;
    const d = c.getContext('2d').getImageData(Math.round((sx - r.left) * k), Math.round((sy - r.top) * k), 1, 1).data;
    return [d[0], d[1], d[2]];
  }, { sx: at.x, sy: at.y });
  const green = rgb[1] > rgb[0] + 30 && rgb[1] > rgb[2] + 20;
  assert.ok(!green, `pixel at the robot ${rgb} is the S marker's green: the marker hides the robot`);
  assert.deepEqual(problems, []);
  await page.close();
});

/** Every visible control's text in the page, whole: a value cut with "…",
 *  a menu narrower than its chosen entry, or anything past the window's
 *  right edge is listed. */
function cutControls(page) {
  return page.evaluate(() => {
    const ctx = document.createElement('canvas').getContext('2d');
    const out = [];
    for (const e of document.querySelectorAll('button, select, .metric b, .metric span, dt, dd, .speed')) {
      if (!e.getClientRects().length || e.closest('[hidden], .help-backdrop')) continue;
      const s = getComputedStyle(e);
      if (s.visibility === 'hidden') continue;
      const r = e.getBoundingClientRect();
      const name = `${e.id || e.tagName.toLowerCase()} "${(e.textContent || '').trim().slice(0, 20)}"`;
      if (s.overflowX !== 'visible' && e.tagName !== 'SELECT' && e.scrollWidth > e.clientWidth + 1) out.push(`${name} cut (${e.scrollWidth} > ${e.clientWidth})`);
      if (e.tagName === 'SELECT' && e.selectedOptions[0]) {
        ctx.font = s.font;
        const w = ctx.measureText(e.selectedOptions[0].textContent).width;
        if (e.clientWidth < w) out.push(`${name} menu ${e.clientWidth} px < its entry ${Math.round(w)} px`);
      }
      if (r.right > innerWidth + 1 || r.left < -1) out.push(`${name} outside the window (${Math.round(r.left)}–${Math.round(r.right)})`);
    }
    return out;
  });
}

test('presentation mode makes the map larger on every page with a map and cuts no control, at 1366×768 and 1440×900', async () => {
  const pages = [
    ['index.html', '#map-canvas'],
    ['race.html', '.lane-canvas canvas'],
    ['robot.html', '#sim-canvas'],
    ['compare.html?scenario=T-fig3-2.json&planners=dwa,improved-dwa', '#lane-canvas-0'],
    ['barn.html', '#lane-canvas-0'],
    ['apf.html?scenario=T-fig4-6.json', '#view'],
    ['arm.html?scenario=T-tab5-3.json', '#view canvas'],
  ];
  const settle = (page) => page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(() => setTimeout(r, 300)))));
  for (const [width, height] of [[1366, 768], [1440, 900]]) {
    for (const [url, canvas] of pages) {
      const { page, problems } = await watchedPage(session);
      await page.setViewportSize({ width, height });
      await page.goto(session.base + url);
      await page.waitForFunction(() => document.body.dataset.state && document.body.dataset.state !== 'loading', null, { timeout: 30_000 });
      await settle(page);
      const where = `${url} at ${width}×${height}`;
      const normal = await page.locator(canvas).first().boundingBox();
      await page.keyboard.press('p');
      await settle(page);
      const large = await page.locator(canvas).first().boundingBox();
      assert.ok(large.width > normal.width && large.height > normal.height, `${where}: map ${normal.width}×${normal.height} → ${large.width}×${large.height} in presentation mode`);
      assert.deepEqual(await cutControls(page), [], `${where}: controls cut in presentation mode`);
      assert.ok(await page.evaluate(() => document.documentElement.scrollWidth <= innerWidth), `${where}: no sideways scrolling`);
      if (url === 'index.html') {
        // What the class reads: the cost, the speed menu, the counters, all
        // inside the window.
        for (const sel of ['#metric-cost', '#speed', '#count-f', '#count-lines', '.counters dt:nth-of-type(4)', '.counters dt:nth-of-type(5)']) {
          const b = await page.locator(sel).boundingBox();
          assert.ok(b && b.x >= 0 && b.y >= 0 && b.x + b.width <= width && b.y + b.height <= height, `${where}: ${sel} at ${JSON.stringify(b)}`);
        }
        if (width === 1366) await screenshot(page, 'class-grid-present-1366.png');
      }
      await page.keyboard.press('p');
      assert.deepEqual(problems, [], where);
      await page.close();
    }
  }
});

test('opening "What am I looking at?" on the robot page keeps the map at least 80 % of its area, legend inside the window (1366×768, 1440×900)', async () => {
  for (const [width, height] of [[1366, 768], [1440, 900]]) {
    const { page, problems } = await watchedPage(session);
    await page.setViewportSize({ width, height });
    await page.goto(`${session.base}robot.html?scenario=T-fig3-2.json`);
    await page.waitForFunction(() => ['ready', 'error'].includes(document.body.dataset.state), null, { timeout: 30_000 });
    const area = async () => {
      await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(() => setTimeout(r, 200)))));
      const b = await page.locator('#sim-canvas').boundingBox();
      return b.width * b.height;
    };
    const closed = await area();
    await page.click('#explain summary');
    const open = await area();
    assert.ok(open >= 0.8 * closed, `${width}×${height}: map ${Math.round(closed)} px² closed, ${Math.round(open)} px² with the legend open`);
    // The legend itself is on screen and shows its entries.
    const g = await page.locator('#explain .explain-grid').boundingBox();
    assert.ok(g && g.y >= 0 && g.y + g.height <= height && g.height > 100, `legend at ${JSON.stringify(g)}`);
    assert.ok(await page.isVisible('#explain li >> text=Chosen rollout'));
    if (width === 1366) await screenshot(page, 'class-robot-legend-open.png');
    // It closes again from its summary.
    await page.click('#explain summary');
    assert.equal(await page.isVisible('#explain .explain-grid'), false);
    assert.deepEqual(problems, []);
    await page.close();
  }
});
