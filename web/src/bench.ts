// Benchmark page: times ScenBatch.solveAll (one wasm call solving every
// query of a .scen) with performance.now(), so the boundary is crossed once
// per repetition and the figure is the planner's own speed in wasm.

import init, { MapHandle, PlanSession, ScenBatch, plan } from '../pkg-grid/planlab_wasm.js';

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
    document.body.dataset.state = 'ready';
  })
  .catch((e) => {
    document.body.dataset.state = 'error';
    const out = document.getElementById('out');
    if (out) out.textContent = String(e);
  });
