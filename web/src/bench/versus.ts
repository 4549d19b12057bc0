// planlab's A* (wasm) against PathFinding.js's AStarFinder on the same
// maps and queries: costs checked against each other and the optimum, then
// times, the median of alternating timed blocks. Runs in the bench page's
// worker (bench/worker.ts), both libraries on the same thread.

import PF from 'pathfinding';
import { MapHandle, ScenBatch, plan } from '../../pkg-grid/planlab_wasm.js';
import type { MapCase, Query } from './cases';
import { RULES, median, type RowResult } from './shared';

/** planlab's A*, spelled out (these are also its defaults). */
export const PLANLAB_OPTIONS = { algorithm: 'astar', heuristic: 'octile', weight: 1, diagonal: 'no_corner_cutting' };

/** PathFinding.js's strongest A* for this rule, per its docs: the octile
 *  heuristic (admissible and consistent with √2 diagonals) and
 *  OnlyWhenNoObstacles, its name for the no-corner-cutting rule. */
export const PF_OPTIONS = {
  heuristic: PF.Heuristic.octile,
  diagonalMovement: PF.DiagonalMovement.OnlyWhenNoObstacles,
  weight: 1,
};

/** A timed block lasts about this long, ms: well above performance.now()'s
 *  resolution (100 µs in a page that is not cross-origin isolated). */
const BLOCK_MS = 4;
const MAX_INNER = 2000;
/** PathFinding.js needs a fresh grid per search; the clones of one block are
 *  made before it is timed, up to this many cells in all. */
const CLONE_CELLS = 3_000_000;
/** .scen optima are printed to 5 or more decimals. */
export const OPTIMUM_TOL = 1e-4;

/** Cost of a PathFinding.js path (cells from start to goal), summed in the
 *  order its A* sums g; errors on a step that is not to a neighbour. */
export function pathCost(path: number[][]): number {
  let cost = 0;
  for (let i = 1; i < path.length; i++) {
    const dx = Math.abs(path[i][0] - path[i - 1][0]);
    const dy = Math.abs(path[i][1] - path[i - 1][1]);
    if (dx > 1 || dy > 1 || dx + dy === 0) throw new Error(`PathFinding.js path step ${i} is not to a neighbour`);
    cost += dx && dy ? Math.SQRT2 : 1;
  }
  return cost;
}

/** PathFinding.js's grid of a planlab map: free cells walkable, occupied
 *  and unknown ones not (planlab plans with allow_unknown off). */
function pfGrid(map: MapHandle): PF.Grid {
  const w = map.width;
  const cells = map.cells();
  const matrix: number[][] = [];
  for (let r = 0; r < map.height; r++) matrix.push(Array.from(cells.subarray(r * w, (r + 1) * w), (c) => (c === 0 ? 0 : 1)));
  return new PF.Grid(matrix);
}

/** One timed block of `n` planlab searches, ms. */
function blockPlanlab(batch: ScenBatch, n: number): number {
  const t0 = performance.now();
  for (let k = 0; k < n; k++) batch.solveAll();
  return performance.now() - t0;
}

/** One timed block of `n` PathFinding.js searches, ms; the fresh grids they
 *  need are cloned before the clock starts. */
function blockPf(finder: PF.AStarFinder, q: Query, grid: PF.Grid, n: number): number {
  const grids = Array.from({ length: n }, () => grid.clone());
  const t0 = performance.now();
  for (const g of grids) finder.findPath(q.sx, q.sy, q.gx, q.gy, g);
  return performance.now() - t0;
}

/**
 * Runs per block: doubled until a block lasts BLOCK_MS, judged both by the
 * latest block and by the fastest time per run seen so far. The fastest,
 * because a garbage collection or another process can make one trial slow;
 * the latest too, because the first trial runs cold (JIT, caches) and would
 * otherwise stop the doubling at n = 1 with blocks far shorter than the
 * timer's resolution (a 0 ms block and a ratio of 0 on a short query).
 */
function runsPerBlock(block: (n: number) => number, cap: number): number {
  block(1); // untimed warm-up
  let n = 1;
  let best = Infinity;
  for (;;) {
    const t = block(n);
    best = Math.min(best, t / n);
    if (n >= cap || (t >= BLOCK_MS && n * best >= BLOCK_MS)) return n;
    n = Math.min(cap, n * 2);
  }
}

const nextTask = () => new Promise<void>((r) => setTimeout(r, 0));

export interface Progress {
  (message: string): void;
}

/**
 * Runs every query of `cases`: an untimed pass (costs, JIT warm-up, a time
 * estimate per query that sets the runs per block), then `reps` timed blocks
 * per library and row, alternating planlab and PathFinding.js. `onRow` gets
 * each finished row.
 */
export async function runVersus(
  cases: MapCase[],
  reps: number,
  progress: Progress,
  onRow: (r: RowResult) => void,
): Promise<RowResult[]> {
  const finder = new PF.AStarFinder(PF_OPTIONS);
  const maps: MapHandle[] = [];
  const batches: ScenBatch[] = [];
  try {
    const rows = cases.flatMap((c) => {
      const map = MapHandle.fromMovingAi(c.mapText);
      maps.push(map);
      const grid = pfGrid(map);
      return c.queries.map((q) => {
        const batch = new ScenBatch(map, q.scen, PLANLAB_OPTIONS);
        batches.push(batch);
        return { key: c.key, name: c.name, q, map, batch, grid, cells: map.width * map.height };
      });
    });

    // Untimed: each query's costs, then runs per block doubled until a
    // block lasts BLOCK_MS (which also warms both JITs up).
    const est = [];
    for (const [i, r] of rows.entries()) {
      progress(`Checking costs and warming up: query ${i + 1} of ${rows.length} (${r.name})…`);
      await nextTask();
      const planlabCost = r.batch.solveAll();
      const planned = plan(r.map, r.q.sx, r.q.sy, r.q.gx, r.q.gy, PLANLAB_OPTIONS, false);
      const planlabExpanded = planned.expandedCount;
      planned.free();
      const pfSearched = r.grid.clone();
      const path = finder.findPath(r.q.sx, r.q.sy, r.q.gx, r.q.gy, pfSearched);
      if (path.length === 0) {
        throw new Error(`PathFinding.js found no path on ${r.name} (${r.q.sx}, ${r.q.sy}) → (${r.q.gx}, ${r.q.gy})`);
      }
      const pfCost = pathCost(path);
      // PathFinding.js marks every node it expanded `closed`.
      const pfExpanded = (pfSearched as unknown as { nodes: { closed?: boolean }[][] }).nodes
        .reduce((n, row) => n + row.filter((v) => v.closed).length, 0);
      const planlabInner = runsPerBlock((n) => blockPlanlab(r.batch, n), MAX_INNER);
      const pfInner = runsPerBlock((n) => blockPf(finder, r.q, r.grid, n), Math.max(1, Math.floor(CLONE_CELLS / r.cells)));
      est.push({ planlabCost, pfCost, planlabExpanded, pfExpanded, planlabInner, pfInner });
    }

    const out: RowResult[] = [];
    for (const [i, r] of rows.entries()) {
      const e = est[i];
      const tP: number[] = [];
      const tF: number[] = [];
      for (let rep = 0; rep < reps; rep++) {
        progress(`Timing query ${i + 1} of ${rows.length} (${r.name}): block ${rep + 1} of ${reps}…`);
        await nextTask();
        tP.push(blockPlanlab(r.batch, e.planlabInner) / e.planlabInner);
        tF.push(blockPf(finder, r.q, r.grid, e.pfInner) / e.pfInner);
      }
      const planlabUs = median(tP) * 1e3;
      const pfUs = median(tF) * 1e3;
      const row: RowResult = {
        mapKey: r.key,
        map: r.name,
        query: r.q,
        planlabCost: e.planlabCost,
        pfCost: e.pfCost,
        costsEqual: Math.abs(e.planlabCost - e.pfCost) <= 1e-9 * Math.max(1, e.planlabCost),
        optimalOk: r.q.optimal === null ? null : Math.abs(e.planlabCost - r.q.optimal) <= OPTIMUM_TOL,
        likeForLike: RULES.same,
        planlabExpanded: e.planlabExpanded,
        pfExpanded: e.pfExpanded,
        planlabInner: e.planlabInner,
        pfInner: e.pfInner,
        planlabUs,
        pfUs,
        ratio: pfUs / planlabUs,
      };
      out.push(row);
      onRow(row);
    }
    return out;
  } finally {
    batches.forEach((b) => b.free());
    maps.forEach((m) => m.free());
  }
}
