// End-to-end tests of the gallery and the shared shell (help overlay,
// presentation mode) in headless Chromium, with real clicks and keys:
// - the gallery has one card per `planlab reproduce` id (the ids read from
//   the reproduce sources, not from gallery.json), each with a paper tag,
//   an explanation, the claimed relation and a Run link per run;
// - a robot card's Run link opens the robot page with the run's planner and
//   edits and runs it to the goal; an APF card runs on the APF page; the arm
//   card opens the arm page with the run's predictor;
// - `?` opens the help overlay with the planners and the current planner's
//   parameters from the registry, Esc and a click outside close it, F1 opens it;
// - `P` switches presentation mode, remembered across reloads;
// - every page at 1366×768 and 1920×1080 has no horizontal overflow and
//   every top-bar control in view.
// No console errors anywhere. Screenshots: tests/e2e/screenshots/gallery*.png,
// docs/gallery-screenshot.png.

import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { REPO, SCREENSHOTS, startSession, screenshot, errorText } from './harness.mjs';

let session;
before(async () => {
  session = await startSession();
});
after(async () => {
  await session?.close();
});

/** The reproduce ids as the Rust registry spells them. */
function registryIds() {
  const dir = path.join(REPO, 'crates/planlab-core/src/reproduce');
  const ids = new Set();
  for (const f of fs.readdirSync(dir).filter((f) => f.endsWith('.rs'))) {
    const text = fs.readFileSync(path.join(dir, f), 'utf8');
    for (const m of text.matchAll(/\bid: "([TSCL]-[^"]+)"|\(\s*"([TSCL]-sim\d+)",/g)) ids.add(m[1] ?? m[2]);
  }
  return [...ids].sort();
}

async function newPage() {
  const page = await session.context.newPage();
  const problems = [];
  page.on('console', (m) => {
    if (m.type() === 'error') problems.push(`console.error: ${m.text()}`);
  });
  page.on('pageerror', (e) => problems.push(`pageerror: ${e.message}`));
  return { page, problems };
}

async function openGallery(page) {
  await page.goto(`${session.base}gallery.html`);
  await page.waitForFunction(() => ['ready', 'error'].includes(document.body.dataset.state), null, { timeout: 30_000 });
  assert.equal(await page.evaluate(() => document.body.dataset.state), 'ready');
}

// The grid page counts its plans instead of a state.
const ready = (page) =>
  page.waitForFunction(
    () => ['ready', 'done', 'empty', 'error'].includes(document.body.dataset.state) || Number(document.body.dataset.planSeq) > 0,
    null,
    { timeout: 30_000 },
  );

test('gallery: one card per reproduce id, with paper, explanation, relation and Run links', async () => {
  const ids = registryIds();
  assert.equal(ids.length, 27, `ids from the reproduce sources: ${ids}`);
  const { page, problems } = await newPage();
  await page.setViewportSize({ width: 1440, height: 900 });
  await openGallery(page);
  const cards = await page.$$eval('.gcard', (cs) =>
    cs.map((c) => ({
      id: c.dataset.id,
      tag: c.querySelector('.tag')?.textContent,
      title: c.querySelector('.gtitle')?.textContent ?? '',
      expl: c.querySelector('.gexpl')?.textContent ?? '',
      rel: c.querySelector('.grel')?.textContent ?? '',
      runs: [...c.querySelectorAll('a.run')].map((a) => a.getAttribute('href')),
    })),
  );
  assert.deepEqual(cards.map((c) => c.id).sort(), ids);
  for (const c of cards) {
    assert.equal(c.tag, `[${c.id[0]}]`, `${c.id}: paper tag`);
    assert.ok(c.title.length > 5 && c.expl.length > 200 && c.rel.length > 20, `${c.id}: text`);
    assert.ok(c.runs.length >= 1, `${c.id}: runs`);
    const page_ = c.id.startsWith('T-fig4') || c.id === 'T-tab4-1' ? 'apf' : c.id === 'T-tab5-3' ? 'arm' : 'robot';
    for (const href of c.runs) {
      assert.match(href, new RegExp(`^\\./${page_}\\.html\\?scenario=[^&]+\\.json.*&run=1&exp=${c.id}&as=[^&]+$`), c.id);
    }
  }
  // L-tab2 offers all eight runs of sims 5–8.
  assert.equal(cards.find((c) => c.id === 'L-tab2').runs.length, 8);
  // Paper filter: [L] only, by a real click.
  await page.click('#filters button[data-tag="[L]"]');
  const shown = await page.$$eval('.gcard', (cs) => cs.filter((c) => !c.hidden).map((c) => c.dataset.id));
  assert.deepEqual(shown.sort(), ids.filter((i) => i.startsWith('L-')));
  assert.match(await page.textContent('#count'), /^10 of 27/);
  await page.click('#filters button[data-tag=""]');
  // Thumbnails drawn (a card's canvas is not blank).
  await page.waitForTimeout(300);
  const inked = await page.$eval('#exp-T-fig3-2 canvas', (c) => {
    const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
    let dark = 0;
    for (let i = 0; i < d.length; i += 4) if (d[i] < 100) dark++;
    return dark;
  });
  assert.ok(inked > 50, `thumbnail ink ${inked}`);
  await screenshot(page, 'gallery.png');
  await page.screenshot({ path: path.join(REPO, 'docs/gallery-screenshot.png') });
  assert.deepEqual(problems, []);
  await page.close();
});

test('gallery → robot page: T-fig3-2 improved runs to the goal; S-fig12 and C-tab3 runs carry their edits', async () => {
  const { page, problems } = await newPage();
  await openGallery(page);
  await page.click('#exp-T-fig3-2 a.run[data-run="improved"]');
  await page.waitForURL(/robot\.html/);
  await ready(page);
  assert.equal(await errorText(page), null);
  assert.equal(await page.inputValue('#preset'), 'T-fig3-2.json');
  assert.equal(await page.inputValue('#planner'), 'improved-dwa');
  // It started by itself; run faster to the end.
  await page.selectOption('#speed', '8');
  await page.waitForFunction(() => document.body.dataset.outcome && document.body.dataset.outcome !== 'running', null, {
    timeout: 60_000,
  });
  assert.equal(await page.evaluate(() => document.body.dataset.outcome), 'reached');
  const m = await page.evaluate(() => window.planlabRobot.metrics());
  assert.equal(m.outcome, 'reached');
  assert.ok(m.min_clearance_m > 0, 'no contact');
  // The note names the experiment and run and the relation to look for.
  const note = await page.textContent('#gallery-note');
  assert.match(note, /T-fig3-2 · improved/);
  assert.match(note, /the paper claims: plain DWA ends trapped in the C/);
  await screenshot(page, 'gallery-robot-run.png');

  // Back to the card by the note's link; the plain DWA run of the same
  // card ends stuck in the trap ([T] Fig 3-2).
  await page.click('#gallery-note a');
  await page.waitForURL(/gallery\.html#exp-T-fig3-2$/);
  await page.waitForFunction(() => document.body.dataset.state === 'ready');
  await page.click('#exp-T-fig3-2 a.run[data-run="dwa"]');
  await page.waitForURL(/robot\.html/);
  await ready(page);
  assert.equal(await page.inputValue('#planner'), 'dwa');
  await page.selectOption('#speed', '8');
  await page.waitForFunction(() => document.body.dataset.outcome && document.body.dataset.outcome !== 'running', null, {
    timeout: 90_000,
  });
  assert.equal(await page.evaluate(() => document.body.dataset.outcome), 'stuck');

  // S-fig12's reference run has no movers (`--set movers=[]`).
  await page.goto(`${session.base}gallery.html`);
  await page.waitForFunction(() => document.body.dataset.state === 'ready');
  await page.click('#exp-S-fig12 a.run[data-run="dual-no-movers"]');
  await page.waitForURL(/robot\.html/);
  await ready(page);
  assert.deepEqual(await page.evaluate(() => window.planlabRobot.movers()), []);
  assert.equal(await page.inputValue('#planner'), 'safe-dual-dwa');

  // C-tab3's baseline: the planner renamed, its config (waypoints) kept.
  await page.goto(`${session.base}gallery.html`);
  await page.waitForFunction(() => document.body.dataset.state === 'ready');
  await page.click('#exp-C-tab3 a.run[data-run="asphalt-traditional"]');
  await page.waitForURL(/robot\.html/);
  await ready(page);
  const choice = await page.evaluate(() => window.planlabRobot.plannerChoice());
  assert.equal(choice.name, 'traditional-dwa');
  assert.ok(Object.keys(choice.config).length > 0, 'the preset config is kept');
  assert.deepEqual(problems, []);
  await page.close();
});

test('gallery → compare page: a card whose runs differ only by planner compares them; T-fig3-2 dwa stuck, improved reached', async () => {
  const { page, problems } = await newPage();
  await page.setViewportSize({ width: 1440, height: 900 });
  await openGallery(page);
  const links = await page.$$eval('.gcard', (cs) =>
    Object.fromEntries(cs.map((c) => [c.dataset.id, [...c.querySelectorAll('a.compare')].map((a) => a.getAttribute('href'))])),
  );
  const planners = (href) => new URLSearchParams(href.split('?')[1]).get('planners');
  assert.deepEqual(links['T-fig3-2'].map(planners), ['dwa,fusion-53,improved-dwa']);
  // S-fig12: the no-movers run has its own edit (movers=[]), so only the two that share none are compared.
  assert.deepEqual(links['S-fig12'].map(planners), ['safe-dual-dwa,preliminary-fusion']);
  assert.deepEqual(new URLSearchParams(links['S-fig12'][0].split('?')[1]).getAll('set'), []);
  // One run, or runs that differ by edits (C-tab3 renames the planner with `set`): no comparison.
  for (const id of ['S-fig6', 'C-tab3', 'L-sim4', 'T-fig4-6', 'T-tab5-3']) assert.deepEqual(links[id], [], id);
  // L-tab2 compares per preset: four links, lidar planner vs its baseline.
  assert.deepEqual(links['L-tab2'].map((h) => new URLSearchParams(h.split('?')[1]).get('scenario')), [
    'L-sim5.json',
    'L-sim6.json',
    'L-sim7.json',
    'L-sim8.json',
  ]);
  for (const h of links['L-tab2']) assert.equal(planners(h).split(',').length, 2, h);

  await page.$eval('#exp-T-fig3-2', (c) => c.scrollIntoView());
  await (await page.$('#exp-T-fig3-2')).screenshot({ path: path.join(SCREENSHOTS, 'gallery-card-compare.png') });
  await page.click('#exp-T-fig3-2 a.compare');
  await page.waitForURL(/compare\.html/);
  await page.waitForFunction(() => document.body.dataset.playing === 'true', null, { timeout: 30_000 });
  assert.equal(await errorText(page), null);
  assert.equal(await page.inputValue('#preset'), 'T-fig3-2.json');
  await page.selectOption('#speed', '16');
  await page.waitForFunction(() => document.body.dataset.done === 'true', null, { timeout: 180_000 });
  const outcomes = await page.$$eval('#metrics-table tr[data-metric="outcome"] td[data-planner]', (tds) =>
    Object.fromEntries(tds.map((td) => [td.dataset.planner, td.textContent.trim()])),
  );
  assert.equal(outcomes['improved-dwa'], 'reached', JSON.stringify(outcomes));
  assert.equal(outcomes.dwa, 'stuck', JSON.stringify(outcomes));
  assert.ok('fusion-53' in outcomes, 'the third run of the card is compared too');
  await screenshot(page, 'gallery-compare.png');
  assert.deepEqual(problems, []);
  await page.close();
});

test('gallery → grid page: S-fig6 as a pure global plan (safe A*, key points, feature nodes); bad URL values show the banner', async () => {
  const { page, problems } = await newPage();
  await page.setViewportSize({ width: 1440, height: 900 });
  await openGallery(page);
  await page.click('#exp-S-fig6 a.alt');
  await page.waitForURL(/index\.html\?scenario=S-fig6\.json/);
  await page.waitForFunction(() => document.body.dataset.state === 'ok' || document.body.dataset.state === 'error', null, {
    timeout: 30_000,
  });
  assert.equal(await errorText(page), null);
  assert.equal(await page.inputValue('#algorithm'), 'safe-astar');
  assert.equal(await page.isChecked('#keypoints'), true);
  assert.equal(await page.isChecked('#bottom-up'), true);
  assert.equal(await page.$eval('#preset', (s) => s.selectedOptions[0].textContent), 'S-fig6.json (linked)');
  assert.equal(await page.textContent('#map-size'), '480 × 320');
  // Start and goal are the scenario's (col,row).
  const sc = JSON.parse(fs.readFileSync(path.join(REPO, 'assets/scenarios/S-fig6.json'), 'utf8'));
  assert.equal(await page.getAttribute('#map-canvas', 'data-start'), `${sc.start.col},${sc.start.row}`);
  assert.equal(await page.getAttribute('#map-canvas', 'data-goal'), `${sc.goal.col},${sc.goal.row}`);
  const pathLen = Number(await page.getAttribute('#map-canvas', 'data-path-len'));
  assert.ok(pathLen > 100, `safe A* path of ${pathLen} cells`);
  const kp = Number(await page.getAttribute('#metric-keypoints', 'data-value'));
  assert.ok(kp > 0 && kp < pathLen, `${kp} key points of ${pathLen} nodes`);
  // The Bottom-Up feature nodes: at most 5 % of the path nodes, as the S-fig6 relation asks.
  const bu = Number((await page.textContent('#metric-keypoints')).match(/(\d+) BU/)?.[1]);
  assert.ok(bu >= 2 && bu <= 0.05 * pathLen, `${bu} feature nodes of ${pathLen}`);
  await screenshot(page, 'gallery-grid-sfig6.png');
  // Unknown values in the URL: the banner names them, the scenario still opens.
  await page.goto(`${session.base}index.html?scenario=S-fig6.json&algorithm=teleport&inflate=NaN`);
  await page.waitForFunction(() => Number(document.body.dataset.planSeq) > 0, null, { timeout: 30_000 });
  await page.waitForSelector('#error:not([hidden])');
  assert.match(await errorText(page), /algorithm “teleport”.*inflate “NaN”/);
  assert.equal(await page.textContent('#map-size'), '480 × 320');
  await page.goto(`${session.base}index.html?scenario=..%2Fsecret.json`);
  await page.waitForSelector('#error:not([hidden])');
  assert.match(await errorText(page), /not a scenario file name/);
  await page.goto(`${session.base}index.html?scenario=nope.json`);
  await page.waitForSelector('#error:not([hidden])');
  // (planlab serve answers 404; vite preview its index.html, which is no JSON)
  assert.match(await errorText(page), /^nope\.json: (cannot load|scenario JSON error)/);
  assert.deepEqual(problems.filter((p) => !/404|Not Found/i.test(p)), []);
  await page.close();
});

test('gallery → APF page and arm page', async () => {
  const { page, problems } = await newPage();
  await openGallery(page);
  await page.click('#exp-T-fig4-6 a.run[data-run="sampling"]');
  await page.waitForURL(/apf\.html/);
  await ready(page);
  assert.equal(await page.inputValue('#mode'), 'sampling');
  await page.waitForFunction(() => document.body.dataset.outcome && document.body.dataset.outcome !== 'running', null, {
    timeout: 60_000,
  });
  assert.equal(await page.evaluate(() => document.body.dataset.outcome), 'reached');
  // T-fig4-8 without the relative distance rule stalls before the goal.
  await page.goto(`${session.base}gallery.html`);
  await page.waitForFunction(() => document.body.dataset.state === 'ready');
  await page.click('#exp-T-fig4-8 a.run[data-run="sampling-no-rule"]');
  await page.waitForURL(/apf\.html/);
  await ready(page);
  await page.waitForFunction(() => document.body.dataset.outcome && document.body.dataset.outcome !== 'running', null, {
    timeout: 60_000,
  });
  assert.notEqual(await page.evaluate(() => document.body.dataset.outcome), 'reached');
  await screenshot(page, 'gallery-apf-run.png');

  // T-tab4-1 is 3D: the APF page runs it in top view to the goal.
  await page.goto(`${session.base}gallery.html`);
  await page.waitForFunction(() => document.body.dataset.state === 'ready');
  await page.click('#exp-T-tab4-1 a.run[data-run="sampling+prediction"]');
  await page.waitForURL(/apf\.html/);
  await ready(page);
  assert.equal(await errorText(page), null);
  assert.equal(await page.evaluate(() => document.body.dataset.dims), '3');
  assert.equal(await page.isVisible('#dims-note'), true);
  await page.waitForFunction(() => document.body.dataset.outcome && document.body.dataset.outcome !== 'running', null, {
    timeout: 60_000,
  });
  assert.equal(await page.evaluate(() => document.body.dataset.outcome), 'reached');
  assert.equal(await page.getAttribute('#metric-spikes', 'data-value'), '0', 'Table 4-1: no spikes with prediction');

  await page.goto(`${session.base}gallery.html`);
  await page.waitForFunction(() => document.body.dataset.state === 'ready');
  await page.click('#exp-T-tab5-3 a.run[data-run="no-prediction"]');
  await page.waitForURL(/arm\.html/);
  await ready(page);
  assert.equal(await page.inputValue('#predictor'), 'none');
  assert.equal((await page.textContent('#play')).includes('Pause'), true, 'the arm runs');
  assert.deepEqual(problems, []);
  await page.close();
});

test('help overlay: ? opens planners and parameters, Esc and a click outside close it; P = presentation', async () => {
  const { page, problems } = await newPage();
  await page.setViewportSize({ width: 1366, height: 768 });
  await page.goto(`${session.base}robot.html?scenario=T-fig3-2.json`);
  await ready(page);
  assert.equal(await page.isVisible('#help'), false);
  await page.keyboard.press('?');
  await page.waitForSelector('#help', { state: 'visible' });
  // Every registered planner, the current one open with all its fields.
  const planners = await page.$$eval('#help .help-planner', (ds) => ds.map((d) => d.dataset.planner));
  const current = await page.inputValue('#planner');
  const registry = await page.$$eval('#planner option', (os) => os.map((o) => o.value));
  assert.deepEqual(planners, registry);
  assert.ok(await page.$eval(`#help .help-planner[data-planner="${current}"]`, (d) => d.open));
  const fields = await page.evaluate((n) => window.planlabRobot.plannerFields(n), current);
  const rows = await page.$$eval(`#help .help-planner[data-planner="${current}"] tr[data-param]`, (rs) =>
    rs.map((r) => ({ name: r.dataset.param, unit: r.querySelector('.punit').textContent, doc: r.querySelector('.pdoc').textContent })),
  );
  assert.deepEqual(rows.map((r) => r.name), fields);
  assert.ok(rows.every((r) => r.doc.length > 5), 'each parameter documented');
  assert.ok(rows.some((r) => r.unit === 'm/s'), 'units shown');
  assert.match(await page.textContent('#help .help-keys'), /play \/ pause/);
  // Space while the help is open does not start the sim.
  await page.keyboard.press(' ');
  assert.equal(await page.isVisible('#help'), true, 'Space leaves the help open');
  assert.equal(await page.evaluate(() => document.body.dataset.outcome), 'running');
  assert.equal((await page.textContent('#play')).includes('Play'), true);
  await screenshot(page, 'gallery-help.png');
  await page.screenshot({ path: path.join(REPO, 'docs/help-screenshot.png') });
  await page.keyboard.press('Escape');
  await page.waitForSelector('#help', { state: 'hidden' });
  // The ? button, then a click on the backdrop outside the dialog.
  await page.click('#help-button');
  await page.waitForSelector('#help', { state: 'visible' });
  await page.mouse.click(8, 760);
  await page.waitForSelector('#help', { state: 'hidden' });
  // F1 on the APF page: the variants with their paper sections.
  await page.goto(`${session.base}apf.html`);
  await ready(page);
  await page.keyboard.press('F1');
  await page.waitForSelector('#help', { state: 'visible' });
  assert.match(await page.textContent('#help'), /§4\.2\.1/);
  await page.keyboard.press('Escape');

  // Presentation mode by key, remembered after a reload, off again by the button.
  await page.goto(`${session.base}gallery.html`);
  await page.waitForFunction(() => document.body.dataset.state === 'ready');
  await page.setViewportSize({ width: 1920, height: 1080 });
  const before_ = await page.$eval('.gtitle', (e) => e.getBoundingClientRect().height);
  await page.keyboard.press('p');
  assert.equal(await page.evaluate(() => document.documentElement.classList.contains('present')), true);
  const after_ = await page.$eval('.gtitle', (e) => e.getBoundingClientRect().height);
  assert.ok(after_ > before_ * 1.2, `title ${before_} → ${after_}`);
  await page.reload();
  await page.waitForFunction(() => document.body.dataset.state === 'ready');
  assert.equal(await page.evaluate(() => document.documentElement.classList.contains('present')), true);
  assert.equal(await page.getAttribute('#present-button', 'aria-pressed'), 'true');
  await screenshot(page, 'gallery-present.png');
  await page.goto(`${session.base}robot.html?scenario=T-tab3-2.json`);
  await ready(page);
  await screenshot(page, 'gallery-present-robot.png');
  await page.click('#present-button');
  assert.equal(await page.evaluate(() => document.documentElement.classList.contains('present')), false);
  assert.deepEqual(problems, []);
  await page.close();
});

test('robot page metric cards: every label and value whole (no "…") at 1366×768, and in presentation mode at 1920×1080', async () => {
  const { page, problems } = await newPage();
  // Labels and values wider than their card (cut by overflow), sampled while the run goes on.
  const cut = () =>
    page.evaluate(() => {
      const out = [];
      for (const m of document.querySelectorAll('.robot-metrics .metric')) {
        for (const c of m.children) {
          if (c.scrollWidth > c.clientWidth + 0.5) out.push(`${c.textContent} (${c.scrollWidth} > ${c.clientWidth} px)`);
        }
        const b = m.getBoundingClientRect();
        if (b.right > window.innerWidth) out.push(`${m.textContent} beyond the right edge`);
      }
      return out;
    });
  for (const [w, hgt, present, runs] of [
    [1366, 768, false, ['T-fig3-2.json&planner=improved-dwa', 'L-sim1.json']],
    [1920, 1080, true, ['T-fig3-2.json&planner=improved-dwa']],
  ]) {
    await page.setViewportSize({ width: w, height: hgt });
    await page.goto(`${session.base}gallery.html`);
    await page.evaluate((on) => localStorage.setItem('planlab.present', on ? '1' : '0'), present);
    for (const run of runs) {
      await page.goto(`${session.base}robot.html?scenario=${run}&run=1`);
      await ready(page);
      // Presentation mode folds the side panel: set the
      // speed through its select without unfolding it.
      await page.evaluate(() => {
        const sp = document.getElementById('speed');
        sp.value = '8';
        sp.dispatchEvent(new Event('input'));
      });
      const seen = new Set();
      for (;;) {
        for (const c of await cut()) seen.add(c);
        if (!['running', undefined].includes(await page.evaluate(() => document.body.dataset.outcome))) break;
        await page.waitForTimeout(250);
      }
      for (const c of await cut()) seen.add(c);
      assert.deepEqual([...seen], [], `${run} at ${w}×${hgt}${present ? ' (presentation)' : ''}`);
      // At the laptop size the cards stay one row, so the map does not move when values grow.
      const tops = await page.$$eval('.robot-metrics .metric', (ms) => new Set(ms.map((m) => Math.round(m.getBoundingClientRect().top))).size);
      if (!present) assert.equal(tops, 1, `${run}: metric cards in one row`);
      assert.notEqual(await page.textContent('#metric-time'), '—');
    }
    await screenshot(page, present ? 'robot-metrics-1920-present.png' : 'robot-metrics-1366.png');
  }
  await page.evaluate(() => localStorage.removeItem('planlab.present'));
  assert.deepEqual(problems, []);
  await page.close();
});

test('layout: no horizontal overflow, top-bar controls in view at 1366×768 and 1920×1080', async () => {
  const { page, problems } = await newPage();
  // Laptop and full HD as they are, and a projector's full HD in presentation mode.
  for (const [w, hgt, present] of [
    [1366, 768, false],
    [1920, 1080, false],
    [1920, 1080, true],
  ]) {
    await page.setViewportSize({ width: w, height: hgt });
    await page.goto(session.base + 'gallery.html');
    await page.evaluate((on) => localStorage.setItem('planlab.present', on ? '1' : '0'), present);
    for (const p of ['gallery.html', 'index.html', 'robot.html', 'compare.html', 'apf.html', 'arm.html']) {
      await page.goto(session.base + p);
      await ready(page);
      const r = await page.evaluate(() => {
        const out = [];
        const W = window.innerWidth;
        const H = window.innerHeight;
        if (document.documentElement.scrollWidth > W + 1) out.push(`page ${document.documentElement.scrollWidth} wide`);
        for (const e of document.querySelectorAll('.topbar a, .topbar button, .panel button, .panel select, .panel input')) {
          const b = e.getBoundingClientRect();
          if (!b.width || getComputedStyle(e).visibility === 'hidden') continue;
          if (b.left < -1 || b.right > W + 1) out.push(`${e.id || e.textContent.trim()} at x ${b.left}..${b.right}`);
          if (e.closest('.topbar') && (b.top < -1 || b.bottom > H + 1)) out.push(`${e.id} at y ${b.top}..${b.bottom}`);
        }
        const stage = document.querySelector('.stage canvas, #view, .stage');
        if (stage) {
          const b = stage.getBoundingClientRect();
          if (b.width < 200 || b.height < 150) out.push(`stage ${b.width}×${b.height}`);
        }
        return out;
      });
      assert.equal(await page.evaluate(() => document.documentElement.classList.contains('present')), present);
      assert.deepEqual(r, [], `${p} at ${w}×${hgt}${present ? ' (presentation)' : ''}`);
      if (w === 1366 && p === 'robot.html') await screenshot(page, 'gallery-robot-1366.png');
      if (present && p === 'apf.html') await screenshot(page, 'gallery-present-apf.png');
    }
  }
  await page.evaluate(() => localStorage.removeItem('planlab.present'));
  assert.deepEqual(problems, []);
  await page.close();
});
