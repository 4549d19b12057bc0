// End-to-end tests of the experiment families on the pages:
// - the gallery cards show the family results of
//   assets/reproduce-results.jsonl: a verdict badge, each run's success
//   rate with its interval, each clause's share and effect, the
//   deviations, and a "random variant" link per run;
// - the robot page on variant 3 of T-fig3-2's family (run `improved`,
//   seed 0) runs the registry's tree of that variant: its trace hash equals
//   the one `planlab reproduce T-fig3-2 --variants 4 --seed 0 --json`
//   reports for k = 3, and the note names "variant 3 of 30, seed 0" with
//   controls that open another variant;
// - the APF page opens a variant of T-fig4-6 and runs it;
// - a bad variant link shows the core's message over the preset.
// Screenshots: tests/e2e/screenshots/variant-*.png.

import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { REPO, SCREENSHOTS, startSession, screenshot, errorText } from './harness.mjs';

const CLI = path.join(REPO, 'target/release/planlab');

let session;
before(async () => {
  session = await startSession();
});
after(async () => {
  await session?.close();
});

async function newPage() {
  const page = await session.context.newPage();
  const problems = [];
  page.on('console', (m) => {
    if (m.type() === 'error') problems.push(`console.error: ${m.text()}`);
  });
  page.on('pageerror', (e) => problems.push(`pageerror: ${e.message}`));
  return { page, problems };
}

const ready = (page) =>
  page.waitForFunction(() => ['ready', 'done', 'error'].includes(document.body.dataset.state), null, { timeout: 60_000 });
const ended = (page, timeout = 120_000) =>
  page.waitForFunction(() => document.body.dataset.outcome && document.body.dataset.outcome !== 'running', null, { timeout });

/** The CLI's trace hashes of variant `k` of `id`'s family. */
function cliRow(id, variants, seed, k) {
  const r = spawnSync(CLI, ['reproduce', id, '--variants', String(variants), '--seed', String(seed), '--json'], {
    encoding: 'utf8',
    timeout: 300_000,
  });
  assert.equal(r.status, 0, r.stderr);
  const row = JSON.parse(r.stdout.trim().split('\n')[0]).rows.find((x) => x.k === k);
  assert.ok(row, `row k=${k}`);
  return row;
}

test('gallery cards: verdict badge, success intervals, clauses with effects, deviations, random-variant links', async () => {
  const { page, problems } = await newPage();
  await page.setViewportSize({ width: 1366, height: 768 });
  await page.goto(`${session.base}gallery.html`);
  await page.waitForFunction(() => document.body.dataset.state === 'ready', null, { timeout: 30_000 });
  const results = Object.fromEntries(
    fs
      .readFileSync(path.join(REPO, 'assets/reproduce-results.jsonl'), 'utf8')
      .split('\n')
      .filter((l) => l.trim())
      .map((l) => JSON.parse(l))
      .map((r) => [r.id, r]),
  );
  const cards = await page.$$eval('.gcard', (cs) =>
    cs.map((c) => ({
      id: c.dataset.id,
      verdict: c.querySelector('.verdict')?.dataset.verdict ?? null,
      none: !!c.querySelector('.gnores'),
      runs: [...c.querySelectorAll('.grunsuccess tr[data-run]')].map((tr) => ({
        run: tr.dataset.run,
        text: tr.querySelector('td.num').textContent,
        href: tr.querySelector('a.variant')?.getAttribute('href') ?? null,
      })),
      clauses: [...c.querySelectorAll('.gclauses li')].map((li) => li.textContent),
      deviations: c.querySelectorAll('.gdev li').length,
      sensitivity: c.querySelector('.gsensum')?.textContent ?? null,
      splits: [...c.querySelectorAll('.gsenslist li[data-perturbation]')].map((li) => ({
        name: li.dataset.perturbation,
        why: li.querySelector('.gwhy').textContent,
        below: li.querySelector('.gbelow')?.textContent ?? null,
        above: li.querySelector('.gabove')?.textContent ?? null,
      })),
    })),
  );
  assert.equal(cards.length, 27);
  for (const c of cards) {
    const r = results[c.id];
    if (!r) {
      // A card without results says so.
      assert.equal(c.none, true, `${c.id}: no results, and says so`);
      continue;
    }
    assert.equal(c.verdict, r.verdict, `${c.id}: verdict badge`);
    // Every run of the results is shown (a gallery run the results lack shows "—").
    for (const n of Object.keys(r.runs)) assert.ok(c.runs.some((x) => x.run === n), `${c.id}: run ${n} shown`);
    for (const run of c.runs) {
      if (!r.runs[run.run]) {
        assert.equal(run.text, '—', `${c.id} ${run.run}: not in the results`);
        continue;
      }
      const s = r.runs[run.run].success;
      assert.ok(run.text.startsWith(`${s.k}/${s.n} · ${Math.round(100 * s.rate)} % [`), `${c.id} ${run.run}: ${run.text}`);
      if (run.href) {
        assert.match(run.href, new RegExp(`&exp=${c.id}&as=[^&]+&variant=\\d+&seed=${r.seed}&of=${r.variants}$`), run.href);
        const k = Number(new URLSearchParams(run.href.split('?')[1]).get('variant'));
        assert.ok(k >= 1 && k < r.variants, `${c.id}: variant ${k} in 1…${r.variants - 1}`);
      }
    }
    assert.equal(c.clauses.length, r.clauses.length, `${c.id}: clauses`);
    r.clauses.forEach((cl, i) => {
      assert.ok(c.clauses[i].includes(`holds on ${cl.holds.k}/${cl.holds.n}`), `${c.id}: ${c.clauses[i]}`);
      if (cl.effect) assert.match(c.clauses[i], /median|no variant had both/, `${c.id}: effect shown`);
    });
    assert.equal(c.deviations, r.deviations.length, `${c.id}: deviations`);
    // Sensitivity: the summary, and per perturbation its reason and both halves.
    assert.equal(c.sensitivity, `Most sensitive to: ${r.sensitivity.summary}`, `${c.id}: sensitivity summary`);
    assert.equal(c.splits.length, r.sensitivity.perturbations.length, `${c.id}: one row per perturbation`);
    r.sensitivity.perturbations.forEach((p, i) => {
      assert.equal(c.splits[i].name, p.perturbation);
      assert.equal(c.splits[i].why, p.why);
      assert.ok(p.why.length > 0, `${c.id} ${p.perturbation}: a reason for its range`);
      if (p.split) {
        assert.ok(c.splits[i].below.startsWith(`${p.split.below.k}/${p.split.below.n} · `), c.splits[i].below);
        assert.ok(c.splits[i].above.startsWith(`${p.split.above.k}/${p.split.above.n} · `), c.splits[i].above);
      }
    });
  }
  // T-fig3-2 has results and a badge, colour-coded.
  const t32 = cards.find((c) => c.id === 'T-fig3-2');
  assert.ok(t32.verdict, 'T-fig3-2 shows a verdict badge');
  const badge = await page.$eval('#exp-T-fig3-2 .verdict', (b) => ({ bg: getComputedStyle(b).backgroundColor, text: b.textContent }));
  assert.notEqual(badge.bg, 'rgba(0, 0, 0, 0)', 'the badge is coloured');
  // Deviations fold open.
  await page.$eval('#exp-T-fig3-2', (c) => c.scrollIntoView());
  await page.click('#exp-T-fig3-2 .gdev summary');
  assert.equal(await page.$eval('#exp-T-fig3-2 .gdev', (d) => d.open), true);
  await page.click('#exp-T-fig3-2 .gsensdet summary');
  assert.equal(await page.$eval('#exp-T-fig3-2 .gsensdet', (d) => d.open), true);
  // The card stays inside the page width (no horizontal overflow).
  assert.ok((await page.evaluate(() => document.documentElement.scrollWidth)) <= 1367);
  await (await page.$('#exp-T-fig3-2')).screenshot({ path: path.join(SCREENSHOTS, 'variant-gallery-card.png') });
  // A card whose verdict hangs on one perturbation says which.
  await page.$eval('#exp-T-fig4-8', (c) => c.scrollIntoView());
  assert.match(await page.textContent('#exp-T-fig4-8 .gsensum'), /fails mostly when goal x shift m/);
  await page.click('#exp-T-fig4-8 .gsensdet summary');
  await (await page.$('#exp-T-fig4-8 .gresults')).screenshot({ path: path.join(SCREENSHOTS, 'variant-gallery-sensitivity.png') });
  await screenshot(page, 'variant-gallery-1366.png');

  // A random-variant link opens the robot page on that variant.
  await page.click('#exp-T-fig3-2 .grunsuccess tr[data-run="improved"] a.variant');
  await page.waitForURL(/robot\.html\?.*&variant=\d+&seed=0/);
  await ready(page);
  assert.equal(await errorText(page), null);
  const k = new URL(page.url()).searchParams.get('variant');
  assert.equal(await page.evaluate(() => document.body.dataset.variant), k);
  assert.deepEqual(problems, []);
  await page.close();
});

test('robot page: variant 3 of T-fig3-2 (improved, seed 0) replays the CLI trace; the note runs another variant', async () => {
  const row = cliRow('T-fig3-2', 4, 0, 3);
  const { page, problems } = await newPage();
  await page.setViewportSize({ width: 1366, height: 768 });
  await page.goto(
    `${session.base}robot.html?scenario=T-fig3-2.json&planner=improved-dwa&run=1&exp=T-fig3-2&as=improved&variant=3&seed=0&of=30`,
  );
  await ready(page);
  assert.equal(await errorText(page), null);
  assert.equal(await page.evaluate(() => document.body.dataset.variant), '3');
  assert.equal(await page.inputValue('#planner'), 'improved-dwa');
  await page.waitForSelector('#variant-label');
  assert.equal(await page.textContent('#variant-label'), 'variant 3 of 30, seed 0');
  assert.match(await page.textContent('#gallery-note'), /T-fig3-2 · improved/);
  await page.selectOption('#speed', '8');
  await ended(page);
  const hash = await page.evaluate(() => document.body.dataset.traceHash);
  assert.equal(BigInt(hash).toString(16).padStart(16, '0'), row.trace_hashes.improved, 'the page ran the CLI variant');
  if (row.success.improved) assert.equal(await page.evaluate(() => document.body.dataset.outcome), 'reached');
  // The preset (variant 0) is another scene: another trace.
  assert.notEqual(BigInt(hash).toString(16).padStart(16, '0'), cliRow('T-fig3-2', 1, 0, 0).trace_hashes.improved);
  await screenshot(page, 'variant-robot-1366.png');

  // Another variant by its index, then a random one.
  await page.fill('#variant-k', '2');
  await page.click('#variant-run');
  await page.waitForURL(/variant=2/);
  await ready(page);
  assert.equal(await page.evaluate(() => document.body.dataset.variant), '2');
  await page.waitForSelector('#variant-label');
  assert.equal(await page.textContent('#variant-label'), 'variant 2 of 30, seed 0');
  await page.click('#variant-random');
  await page.waitForURL((u) => !/variant=2(&|$)/.test(u.search));
  await ready(page);
  const kr = Number(await page.evaluate(() => document.body.dataset.variant));
  assert.ok(kr >= 1 && kr < 30 && kr !== 2, `random variant ${kr}`);
  assert.deepEqual(problems, []);
  await page.close();
});

test('APF page: a variant of T-fig4-6 opens and runs; a bad variant link shows the core message', async () => {
  const { page, problems } = await newPage();
  await page.goto(`${session.base}apf.html?scenario=T-fig4-6.json&set=apf.config.mode%3Dsampling&run=1&exp=T-fig4-6&as=sampling&variant=2&seed=0&of=60`);
  await page.waitForFunction(() => ['ready', 'error'].includes(document.body.dataset.state), null, { timeout: 30_000 });
  assert.equal(await errorText(page), null);
  assert.equal(await page.evaluate(() => document.body.dataset.variant), '2');
  assert.equal(await page.inputValue('#mode'), 'sampling');
  await ended(page, 60_000);
  await page.waitForSelector('#variant-label');
  assert.equal(await page.textContent('#variant-label'), 'variant 2 of 60, seed 0');
  await screenshot(page, 'variant-apf.png');

  // Unknown run, and a variant past the family's bound: the core's words, the preset still open.
  await page.goto(`${session.base}robot.html?scenario=T-fig3-2.json&exp=T-fig3-2&as=nope&variant=3&seed=0`);
  await page.waitForSelector('#error:not([hidden])', { timeout: 30_000 });
  assert.match(await errorText(page), /Could not open the variant: T-fig3-2 has no run `nope`/);
  assert.equal(await page.evaluate(() => document.body.dataset.state), 'ready');
  await page.goto(`${session.base}robot.html?scenario=T-fig3-2.json&exp=T-fig3-2&as=improved&variant=99999&seed=0`);
  await page.waitForSelector('#error:not([hidden])', { timeout: 30_000 });
  assert.match(await errorText(page), /variant 99999/);
  assert.deepEqual(problems, []);
  await page.close();
});
