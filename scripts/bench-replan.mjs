#!/usr/bin/env node
// The grid page's replan cost in headless Chromium: ms per
// A* query over the same Moving AI rows, planned four ways in one page —
// the free `plan()` (rebuilds the passability grid every call, as the page
// did before the session), `PlanSession.plan()` (grid kept, as the page
// does now), `PlanSession.planRecorded()` (plus the search events for the
// player) and ScenBatch.solveAll (the search alone, no boundary per query).
// Each figure is the fastest of --reps passes (other processes on a shared
// machine only ever add time). Builds nothing: needs web/dist.
//
// Usage: node scripts/bench-replan.mjs [--reps N] [--every K]

import fs from 'node:fs';
import path from 'node:path';
import { DATA, startSession } from '../tests/e2e/harness.mjs';

const args = process.argv.slice(2);
const opt = (name, dflt) => {
  const i = args.indexOf(name);
  return i >= 0 ? Number(args[i + 1]) : dflt;
};
const REPS = opt('--reps', 5);
const MAPS = [
  { name: 'dao/arena', every: 1 },
  { name: 'maze/maze512-1-0', every: opt('--every', 40) },
  { name: 'random/random512-10-0', every: opt('--every', 40) },
];

const session = await startSession();
try {
  const page = await session.context.newPage();
  await page.goto(session.base + 'bench.html');
  await page.waitForFunction(() => document.body.dataset.state === 'ready', null, { timeout: 30_000 });
  console.log('map                    rows  plan() ms  session ms  recorded ms  batch ms');
  for (const m of MAPS) {
    const file = path.join(DATA, 'movingai', `${m.name}.map`);
    const mapText = fs.readFileSync(file, 'utf8');
    const scenText = fs.readFileSync(`${file}.scen`, 'utf8');
    const r = await page.evaluate(([mt, st, every, reps]) => window.planlabReplanBench(mt, st, every, reps), [mapText, scenText, m.every, REPS]);
    const f = (x) => x.toFixed(3).padStart(10);
    console.log(`${m.name.padEnd(22)} ${String(r.rows).padStart(4)} ${f(r.fresh)} ${f(r.session)}  ${f(r.recorded)} ${f(r.batch)}`);
  }
} finally {
  await session.close();
}
