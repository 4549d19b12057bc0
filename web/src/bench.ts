// Benchmark page: times ScenBatch.solveAll (one wasm call solving every
// query of a .scen) with performance.now(), so the boundary is crossed once
// per repetition and the figure is the planner's own speed in wasm.

import init, { DwaBench, MapHandle, ScenBatch } from '../pkg/planlab_wasm.js';

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
 *  `blocks` blocks of `steps` steps, one wasm call per block. */
function planlabDwaBench(steps: number, blocks: number, warmMs = 0): DwaBenchResult {
  const bench = new DwaBench();
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

declare global {
  interface Window {
    planlabBench: typeof planlabBench;
    planlabDwaBench: typeof planlabDwaBench;
  }
}

init()
  .then(() => {
    window.planlabBench = planlabBench;
    window.planlabDwaBench = planlabDwaBench;
    document.body.dataset.state = 'ready';
  })
  .catch((e) => {
    document.body.dataset.state = 'error';
    const out = document.getElementById('out');
    if (out) out.textContent = String(e);
  });
