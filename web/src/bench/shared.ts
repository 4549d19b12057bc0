// What the bench page and its worker (bench/worker.ts) share: the rules as
// the page states them, a row of results, the messages between them. No
// PathFinding.js here: it is bundled into the worker only.

import type { MapCase, Query } from './cases';

/** Both rules, as the page states them. */
export const RULES = {
  planlab: 'no_corner_cutting (a diagonal needs both side cells free)',
  pathfinding: 'DiagonalMovement.OnlyWhenNoObstacles (a diagonal needs both side cells free)',
  /** The two rules are the same, so every row is like for like. */
  same: true,
};

export interface RowResult {
  /** The map's id and name (cases.ts). */
  mapKey: string;
  map: string;
  query: Query;
  planlabCost: number;
  pfCost: number;
  /** Costs equal up to float rounding. */
  costsEqual: boolean;
  /** planlab's cost equals the optimum; null when there is none. */
  optimalOk: boolean | null;
  /** The two libraries use the same diagonal rule on this row. */
  likeForLike: boolean;
  /** Cells each search expanded (planlab's `expandedCount`; the nodes
   *  PathFinding.js closed). */
  planlabExpanded: number;
  pfExpanded: number;
  /** Query runs per timed block. */
  planlabInner: number;
  pfInner: number;
  /** Median over the blocks, µs per query. */
  planlabUs: number;
  pfUs: number;
  /** PathFinding.js time ÷ planlab time. */
  ratio: number;
}

export const median = (xs: number[]): number => {
  const s = [...xs].sort((a, b) => a - b);
  const m = s.length >> 1;
  return s.length % 2 ? s[m] : (s[m - 1] + s[m]) / 2;
};

/** Page → worker: run these cases. */
export interface RunRequest {
  cases: MapCase[];
  reps: number;
}

/** Worker → page. */
export type WorkerMessage =
  | { type: 'progress'; message: string }
  | { type: 'row'; row: RowResult }
  | { type: 'done'; rows: RowResult[] }
  | { type: 'error'; message: string };
