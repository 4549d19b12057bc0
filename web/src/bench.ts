// Benchmark page. For people: a Run button that times planlab's A* (wasm)
// against PathFinding.js's A* on the same maps and queries
// (bench/versus.ts) and the reference DWA step, into tables. For scripts
// (scripts/bench-browser.mjs, scripts/bench-replan.mjs): window hooks that
// time ScenBatch.solveAll (one wasm call solving every query of a .scen)
// with performance.now(), so the boundary is crossed once per repetition and
// the figure is the planner's own speed in wasm.

import init, { MapHandle, PlanSession, ScenBatch, plan } from '../pkg-grid/planlab_wasm.js';
import { version as pfVersion } from 'pathfinding/package.json';
import { SIZES, loadCases, type Size } from './bench/cases';
import { RULES, median, type RowResult, type RunRequest, type WorkerMessage } from './bench/shared';

export interface BenchResult {
  rows: number;
  /** Whole-scenario passes per timed block. */
  inner: number;
  totalCost: number;
  optimalSum: number;
  timesMs: number[];
}

async function planlabBench(
  mapText: string,
  scenText: string,
  reps: number,
  inner = 1,
  options?: Record<string, unknown>,
  warmMs = 0,
): Promise<BenchResult> {
  const map = MapHandle.fromMovingAi(mapText);
  const batch = new ScenBatch(map, scenText, options ?? { algorithm: 'astar' });
  try {
    // Untimed passes (at least one, as the native side; then until warmMs)
    // let V8 tier the hot functions up from its baseline compiler.
    const totalCost = batch.solveAll();
    for (const w0 = performance.now(); performance.now() - w0 < warmMs; ) batch.solveAll();
    const timesMs: number[] = [];
    for (let i = 0; i < reps; i++) {
      const t0 = performance.now();
      let t = 0;
      // `inner` whole-scenario passes per timed block keep small maps well
      // above the timer's resolution.
      for (let k = 0; k < Math.max(1, inner); k++) t = batch.solveAll();
      timesMs.push(performance.now() - t0);
      if (Math.abs(t - totalCost) > 1e-9) throw new Error('non-deterministic total cost');
    }
    return { rows: batch.rows, inner: Math.max(1, inner), totalCost, optimalSum: batch.optimalSum, timesMs };
  } finally {
    batch.free();
    map.free();
  }
}

export interface DwaBenchResult {
  /** Steps per timed block. */
  steps: number;
  timesMs: number[];
  /** Sum of the chosen v + ω over one block; `planlab bench step` must agree. */
  checksum: number;
}

/** Times the reference DWA step (the scene of `planlab bench step`) in
 *  `blocks` blocks of `steps` steps, one wasm call per block. The DWA lives
 *  in the robot pages' module (web/pkg), loaded on first use so the page's
 *  first load stays the grid module's. */
async function planlabDwaBench(steps: number, blocks: number, warmMs = 0): Promise<DwaBenchResult> {
  const robot = await import('../pkg/planlab_wasm.js');
  await robot.default();
  const bench = new robot.DwaBench();
  try {
    // Untimed blocks (at least one, as the native side; then until warmMs)
    // let V8 tier the hot functions up from its baseline compiler.
    const checksum = bench.run(steps);
    for (const w0 = performance.now(); performance.now() - w0 < warmMs; ) bench.run(steps);
    const timesMs: number[] = [];
    for (let i = 0; i < blocks; i++) {
      const t0 = performance.now();
      const c = bench.run(steps);
      timesMs.push(performance.now() - t0);
      if (c !== checksum) throw new Error('non-deterministic DWA step');
    }
    return { steps, timesMs, checksum };
  } finally {
    bench.free();
  }
}

export interface ReplanBenchResult {
  rows: number;
  /** ms per query, fastest of `reps` passes over the rows, per way of planning. */
  fresh: number;
  session: number;
  recorded: number;
  batch: number;
}

/**
 * The grid page's replan cost per query, three ways over the same `.scen`
 * rows: the free `plan()` (builds the passability grid every call, as the
 * page did), `PlanSession.plan()` (grid kept between calls, as the page does
 * now), `PlanSession.planRecorded()` (plus the search events) and, for the
 * search alone, ScenBatch.solveAll. Rows: every `every`-th of the file.
 */
function planlabReplanBench(mapText: string, scenText: string, every: number, reps: number): ReplanBenchResult {
  const map = MapHandle.fromMovingAi(mapText);
  const lines = scenText.split('\n').slice(1).filter((l) => l.trim()).filter((_, i) => i % every === 0);
  const rows = lines.map((l) => l.trim().split(/\s+/).slice(4, 8).map(Number));
  const sub = ['version 1', ...lines].join('\n');
  const opts = { algorithm: 'astar' };
  const session = new PlanSession(map, opts);
  const batch = new ScenBatch(map, sub, opts);
  const time = (f: () => void) => {
    f(); // untimed: warms the JIT and the session's grid
    let best = Infinity;
    for (let i = 0; i < reps; i++) {
      const t0 = performance.now();
      f();
      best = Math.min(best, performance.now() - t0);
    }
    return best / rows.length;
  };
  try {
    return {
      rows: rows.length,
      fresh: time(() => rows.forEach(([a, b, c, d]) => plan(map, a, b, c, d, opts, false).free())),
      session: time(() => rows.forEach(([a, b, c, d]) => session.plan(a, b, c, d, false).free())),
      recorded: time(() => rows.forEach(([a, b, c, d]) => session.planRecorded(a, b, c, d).free())),
      batch: time(() => batch.solveAll()),
    };
  } finally {
    session.free();
    batch.free();
    map.free();
  }
}


// ---- The page: Run button, progress line, tables. ----

const $ = <T extends HTMLElement>(id: string) => {
  const el = document.getElementById(id);
  if (!el) throw new Error(`bench.html has no #${id}`);
  return el as T;
};

const DWA_STEPS = 40;
/** Untimed DWA work before its timed blocks, ms (V8 tiers the wasm up). */
const DWA_WARM_MS = 300;

function fmtCost(x: number): string {
  return Number.isFinite(x) ? x.toFixed(4) : '—';
}

function fmtUs(x: number): string {
  return x >= 100 ? x.toFixed(0) : x >= 10 ? x.toFixed(1) : x.toFixed(2);
}

function cell(tr: HTMLTableRowElement, text: string, cls = '', title = ''): HTMLTableCellElement {
  const td = tr.insertCell();
  td.textContent = text;
  if (cls) td.className = cls;
  if (title) td.title = title;
  return td;
}

function addRow(body: HTMLTableSectionElement, n: number, r: RowResult): void {
  const tr = body.insertRow();
  const q = r.query;
  tr.dataset.map = r.mapKey;
  tr.dataset.query = [q.sx, q.sy, q.gx, q.gy].join(',');
  tr.dataset.planlabCost = String(r.planlabCost);
  tr.dataset.pfCost = String(r.pfCost);
  if (q.optimal !== null) tr.dataset.optimal = String(q.optimal);
  tr.dataset.likeForLike = String(r.likeForLike);
  tr.dataset.ratio = String(r.ratio);
  tr.dataset.planlabExpanded = String(r.planlabExpanded);
  tr.dataset.pfExpanded = String(r.pfExpanded);
  cell(tr, String(n), 'num');
  cell(tr, r.map);
  cell(tr, `(${q.sx}, ${q.sy}) → (${q.gx}, ${q.gy})`, 'mono');
  cell(tr, q.optimal === null ? '—' : fmtCost(q.optimal), 'num', q.optimal === null ? 'no reference optimum' : q.optimumSource);
  cell(
    tr,
    fmtCost(r.planlabCost) + (r.optimalOk === null ? '' : r.optimalOk ? ' ✓' : ' ✗'),
    `num ${r.optimalOk === false ? 'bad' : ''}`,
    r.optimalOk === null ? '' : r.optimalOk ? 'equals the optimum' : 'differs from the optimum',
  );
  cell(tr, fmtCost(r.pfCost), 'num');
  cell(
    tr,
    r.costsEqual ? 'equal' : r.likeForLike ? 'DIFFER' : 'differ (other rule)',
    r.costsEqual ? 'ok' : 'bad',
    r.likeForLike ? 'same diagonal rule on both sides' : 'the libraries use different diagonal rules here',
  );
  cell(tr, String(r.planlabExpanded), 'num');
  cell(tr, String(r.pfExpanded), 'num');
  cell(tr, fmtUs(r.planlabUs), 'num', `median of the blocks; ${r.planlabInner} searches per block`);
  cell(tr, fmtUs(r.pfUs), 'num', `median of the blocks; ${r.pfInner} searches per block`);
  cell(tr, `${r.ratio.toFixed(1)}×`, 'num ratio', 'PathFinding.js time ÷ planlab time');
}

function geomean(xs: number[]): number {
  return Math.exp(xs.reduce((s, x) => s + Math.log(x), 0) / xs.length);
}

/** What a reader needs to judge the figures: browser, machine, settings. */
function showEnvironment(size: Size, reps: number, timerUs: number): void {
  const env = $('env');
  env.replaceChildren();
  const uaData = (navigator as Navigator & { userAgentData?: { brands: { brand: string; version: string }[]; platform: string } })
    .userAgentData;
  const browser = uaData
    ? uaData.brands
        .filter((b) => !/not.?a.?brand/i.test(b.brand))
        .map((b) => `${b.brand} ${b.version}`)
        .join(', ')
    : navigator.userAgent;
  const facts: [string, string][] = [
    ['browser', browser],
    ['user agent', navigator.userAgent],
    ['platform', uaData?.platform || navigator.platform || 'unknown'],
    ['logical CPUs', String(navigator.hardwareConcurrency || 'unknown')],
    ['timer', `performance.now() steps of ${timerUs.toFixed(1)} µs${self.crossOriginIsolated ? ' (cross-origin isolated)' : ''}`],
    ['PathFinding.js', `${pfVersion}, AStarFinder: ${RULES.pathfinding}, Heuristic.octile, weight 1`],
    ['planlab', `A* in WebAssembly: diagonal ${RULES.planlab}, heuristic octile, weight 1`],
    ['size', `${size}: ${SIZES[size].arenaRows} arena rows, open ${SIZES[size].openSide}², ${SIZES[size].mazeRows} maze rows`],
    ['reps', `${reps} timed block${reps === 1 ? '' : 's'} per library and row; times are the medians of this run`],
    ['started', new Date().toISOString()],
  ];
  for (const [k, v] of facts) {
    const dt = document.createElement('dt');
    dt.textContent = k;
    const dd = document.createElement('dd');
    dd.textContent = v;
    dd.title = v;
    env.append(dt, dd);
  }
}

/** The smallest step performance.now() takes, µs. */
function timerResolutionUs(): number {
  let best = Infinity;
  for (let i = 0; i < 20; i++) {
    const a = performance.now();
    let b = a;
    while (b === a) b = performance.now();
    best = Math.min(best, b - a);
  }
  return best * 1e3;
}

/** Runs the A* comparison in a worker (bench/worker.ts): both libraries on
 *  one thread, the page free to repaint its progress line. */
function runInWorker(req: RunRequest, progress: (m: string) => void, onRow: (r: RowResult) => void): Promise<RowResult[]> {
  const worker = new Worker(new URL('./bench/worker.ts', import.meta.url), { type: 'module' });
  return new Promise<RowResult[]>((resolve, reject) => {
    worker.onmessage = (e: MessageEvent<WorkerMessage>) => {
      const m = e.data;
      if (m.type === 'progress') progress(m.message);
      else if (m.type === 'row') onRow(m.row);
      else if (m.type === 'done') resolve(m.rows);
      else reject(new Error(m.message));
    };
    worker.onerror = (e) => reject(new Error(`the benchmark worker failed: ${e.message}`));
    worker.postMessage(req);
  }).finally(() => worker.terminate());
}

async function run(): Promise<void> {
  const size = $<HTMLSelectElement>('size').value as Size;
  const reps = Math.max(1, Number($<HTMLSelectElement>('reps').value));
  const button = $<HTMLButtonElement>('run');
  const progressLine = $('progress');
  const error = $('error');
  const progress = (m: string) => (progressLine.textContent = m);
  const body = $<HTMLTableSectionElement>('astar-rows');
  const foot = $<HTMLTableSectionElement>('astar-foot');
  const dwaBody = $<HTMLTableSectionElement>('dwa-rows');
  body.replaceChildren();
  foot.replaceChildren();
  dwaBody.replaceChildren();
  error.hidden = true;
  button.disabled = true;
  document.body.dataset.run = 'running';
  const t0 = performance.now();
  try {
    showEnvironment(size, reps, timerResolutionUs());
    progress('Loading the maps and scenarios…');
    const cases = await loadCases(size);
    let n = 0;
    const rows = await runInWorker({ cases, reps }, progress, (r) => addRow(body, ++n, r));

    const tr = foot.insertRow();
    const allEqual = rows.every((r) => r.costsEqual);
    const optimal = rows.filter((r) => r.optimalOk !== null);
    const td = cell(tr, '', 'summary');
    td.colSpan = 12;
    td.textContent =
      `${rows.length} queries: planlab's cost equals the optimum on ${optimal.filter((r) => r.optimalOk).length} of ` +
      `${optimal.length} rows with one; costs ${allEqual ? 'equal on every row' : 'DIFFER on some rows'} (same diagonal rule on both sides). ` +
      `Ratio (PathFinding.js ÷ planlab): median ${median(rows.map((r) => r.ratio)).toFixed(1)}×, ` +
      `geometric mean ${geomean(rows.map((r) => r.ratio)).toFixed(1)}×, range ${Math.min(...rows.map((r) => r.ratio)).toFixed(1)}–` +
      `${Math.max(...rows.map((r) => r.ratio)).toFixed(1)}×.`;

    progress(`Timing the DWA step: ${reps} block${reps === 1 ? '' : 's'} of ${DWA_STEPS} steps…`);
    await new Promise((r) => setTimeout(r, 0));
    const dwa = await planlabDwaBench(DWA_STEPS, reps, DWA_WARM_MS);
    const msPerStep = median(dwa.timesMs) / DWA_STEPS;
    const dr = dwaBody.insertRow();
    dr.dataset.msPerStep = String(msPerStep);
    dr.dataset.checksum = String(dwa.checksum);
    cell(dr, 'DWA step, reference scene (200 × 200 map, 20 movers, 20 × 40 samples, 3 s)');
    cell(dr, String(DWA_STEPS), 'num');
    cell(dr, dwa.checksum.toFixed(6), 'num mono');
    cell(dr, msPerStep.toFixed(3), 'num', `median of ${reps} blocks`);
    cell(dr, '— (no local planner)', 'muted');

    progress(`Done in ${((performance.now() - t0) / 1000).toFixed(1)} s: ${rows.length} A* queries and the DWA step, ${reps} timed block${reps === 1 ? '' : 's'} each; times are medians of this run.`);
    document.body.dataset.run = 'done';
  } catch (e) {
    error.textContent = `Benchmark failed: ${e instanceof Error ? e.message : String(e)}`;
    error.hidden = false;
    progress('Stopped by an error.');
    document.body.dataset.run = 'error';
  } finally {
    button.disabled = false;
  }
}

declare global {
  interface Window {
    planlabBench: typeof planlabBench;
    planlabDwaBench: typeof planlabDwaBench;
    planlabReplanBench: typeof planlabReplanBench;
  }
}

init()
  .then(() => {
    window.planlabBench = planlabBench;
    window.planlabDwaBench = planlabDwaBench;
    window.planlabReplanBench = planlabReplanBench;
    const button = $<HTMLButtonElement>('run');
    button.addEventListener('click', () => void run());
    button.disabled = false;
    $('progress').textContent = 'Ready: choose a size and reps, then press Run.';
    document.body.dataset.state = 'ready';
  })
  .catch((e) => {
    document.body.dataset.state = 'error';
    const error = document.getElementById('error');
    if (error) {
      error.textContent = `The wasm module failed to load: ${e instanceof Error ? e.message : String(e)}`;
      error.hidden = false;
    }
  });
