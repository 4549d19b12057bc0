#!/usr/bin/env node
// Before/after on the benchmark page (bench.html) in headless Chromium: two
// or more built sites (web/dist of different commits) are served side by
// side and their bench pages run alternately, round after round, so load
// from other processes hits every build alike. Per build and map it prints
// planlab's A* time summed over the page's rows, in ns an expansion (the
// rows and expansions are the same for every build that searches alike),
// PathFinding.js ÷ planlab, and the DWA step; then the median over rounds.
//
// Builds nothing: each DIST is a site built by `npm --prefix web run
// build:wasm && npm --prefix web run build` (copy web/dist aside between
// commits); serving uses target/release/planlab (`planlab serve`).
//
// Usage: node scripts/bench-page-compare.mjs [--rounds N] [--size tiny|small|full]
//        [--reps 1|3|5|9|15] LABEL=DIST [LABEL=DIST …]
// e.g.   node scripts/bench-page-compare.mjs --rounds 3 before=/tmp/dist-old after=web/dist

import { spawn } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { CHROME_ARGS, REPO, freePort, waitForHttp } from '../tests/e2e/harness.mjs';
import { createRequire } from 'node:module';

const require = createRequire(path.join(REPO, 'web/package.json'));
const { chromium } = require('playwright-core');

const args = process.argv.slice(2);
const opt = (name, dflt) => {
  const i = args.indexOf(name);
  if (i < 0) return dflt;
  const v = args[i + 1];
  args.splice(i, 2);
  return v;
};
const ROUNDS = Number(opt('--rounds', '2'));
const SIZE = opt('--size', 'full');
const REPS = opt('--reps', '5');
const builds = args.map((a) => {
  const eq = a.indexOf('=');
  if (eq <= 0) throw new Error(`expected LABEL=DIST, got ${a}`);
  const dir = path.resolve(a.slice(eq + 1));
  if (!fs.existsSync(path.join(dir, 'bench.html'))) throw new Error(`${dir}: no bench.html (not a built site)`);
  return { label: a.slice(0, eq), dir };
});
if (builds.length < 1 || !Number.isInteger(ROUNDS) || ROUNDS < 1) {
  console.error('usage: node scripts/bench-page-compare.mjs [--rounds N] [--size S] [--reps R] LABEL=DIST …');
  process.exit(2);
}
const CLI = path.join(REPO, 'target/release/planlab');
if (!fs.existsSync(CLI)) throw new Error('target/release/planlab is missing: cargo build --release -p planlab-cli');

async function serve(dir) {
  const port = await freePort();
  const child = spawn(CLI, ['serve', '--dir', dir, '--port', String(port), '--host', '127.0.0.1'], { stdio: 'ignore' });
  const base = `http://127.0.0.1:${port}/`;
  try {
    await waitForHttp(base + 'bench.html', child);
  } catch (e) {
    child.kill();
    throw new Error(`planlab serve --dir ${dir}: ${e.message}`);
  }
  return { base, child };
}

/** One run of the bench page: per map { us, exp, pf, rows } and the DWA ms a step. */
async function runPage(browser, base) {
  const page = await browser.newPage();
  try {
    await page.goto(base + 'bench.html');
    await page.waitForFunction(() => document.body.dataset.state !== 'loading', null, { timeout: 60_000 });
    await page.selectOption('#size', SIZE);
    await page.selectOption('#reps', REPS);
    await page.click('#run');
    await page.waitForFunction(() => ['done', 'error'].includes(document.body.dataset.run), null, { timeout: 1_800_000 });
    if ((await page.getAttribute('body', 'data-run')) !== 'done') throw new Error(`bench page: ${await page.textContent('#error')}`);
    // Columns: n, map, query, optimum, planlab cost, PF cost, equal?,
    // planlab expanded, PF expanded, planlab µs, PF µs, ratio.
    const rows = await page.$$eval('#astar-rows tr', (trs) =>
      trs.map((tr) => ({
        map: tr.dataset.map,
        exp: Number(tr.dataset.planlabExpanded),
        us: Number(tr.cells[9].textContent),
        pf: Number(tr.cells[10].textContent),
      })),
    );
    const dwa = await page.$$eval('#dwa-rows tr', (trs) => trs.map((tr) => Number(tr.dataset.msPerStep)));
    const maps = {};
    for (const r of rows) {
      const m = (maps[r.map] ??= { us: 0, exp: 0, pf: 0, rows: 0 });
      m.us += r.us;
      m.exp += r.exp;
      m.pf += r.pf;
      m.rows += 1;
    }
    return { maps, dwa: dwa[0] };
  } finally {
    await page.close();
  }
}

const median = (xs) => {
  const s = [...xs].sort((a, b) => a - b);
  const k = s.length >> 1;
  return s.length % 2 ? s[k] : (s[k - 1] + s[k]) / 2;
};

const servers = [];
const browser = await chromium.launch({ executablePath: process.env.CHROMIUM || '/usr/bin/chromium', headless: true, args: CHROME_ARGS });
try {
  for (const b of builds) servers.push({ ...b, ...(await serve(b.dir)), runs: [] });
  for (let r = 1; r <= ROUNDS; r++) {
    for (const s of servers) {
      const run = await runPage(browser, s.base);
      s.runs.push(run);
      for (const [m, v] of Object.entries(run.maps)) {
        console.log(
          `round ${r} ${s.label.padEnd(10)} ${m.padEnd(6)} ${String(v.rows).padStart(2)} rows  planlab ${(1e3 * v.us / v.exp).toFixed(1)} ns/expansion  PathFinding.js ÷ planlab ${(v.pf / v.us).toFixed(1)}`,
        );
      }
      console.log(`round ${r} ${s.label.padEnd(10)} DWA    ${run.dwa.toFixed(3)} ms/step`);
    }
  }
  console.log(`\nmedian over ${ROUNDS} round(s), size ${SIZE}, reps ${REPS}:`);
  for (const s of servers) {
    for (const m of Object.keys(s.runs[0].maps)) {
      const ns = median(s.runs.map((x) => (1e3 * x.maps[m].us) / x.maps[m].exp));
      const ratio = median(s.runs.map((x) => x.maps[m].pf / x.maps[m].us));
      console.log(`${s.label.padEnd(10)} ${m.padEnd(6)} planlab ${ns.toFixed(1)} ns/expansion  PathFinding.js ÷ planlab ${ratio.toFixed(1)}`);
    }
    console.log(`${s.label.padEnd(10)} DWA    ${median(s.runs.map((x) => x.dwa)).toFixed(3)} ms/step`);
  }
} finally {
  await browser.close();
  for (const s of servers) s.child.kill();
}
