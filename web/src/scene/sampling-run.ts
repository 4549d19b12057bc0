// One sampling planner's run for the grid and race pages: a wasm
// SamplingRun on the page's map, stepped to a budget of iterations or of
// milliseconds. The core has no clock, so a time budget is kept here: the
// run is stepped in chunks until performance.now() passes it (the tree does
// not depend on the chunking, only on the seed and the iterations run, so
// the CLI with --iterations N reproduces a timed run). Nothing here plans.

import { SamplingRun, type MapHandle } from '../../pkg-grid/planlab_wasm.js';
import { SamplingPlayback } from './sampling-tree';
import type { Cell } from '../shell/cells';

/** The core's sampling planners (`SamplingAlgorithm::ALL`) with the
 *  labels the menus show. */
export const SAMPLING_PLANNERS: { name: string; label: string }[] = [
  { name: 'rrt', label: 'RRT' },
  { name: 'rrt-connect', label: 'RRT-Connect' },
  { name: 'rrt-star', label: 'RRT*' },
  { name: 'informed-rrt-star', label: 'Informed RRT*' },
  { name: 'prm', label: 'PRM' },
  { name: 'prm-star', label: 'Lazy PRM*' },
  { name: 'bit-star', label: 'BIT*' },
];

export const isSampling = (name: unknown): boolean => SAMPLING_PLANNERS.some((p) => p.name === name);

export const samplingLabel = (name: string): string => SAMPLING_PLANNERS.find((p) => p.name === name)?.label ?? name;

/** Budget limits the page accepts. Iterations: the run's events are kept
 *  for the player (about five per iteration, 29 bytes each), so 200 000
 *  iterations stay near 30 MB. Milliseconds: the run blocks the page while
 *  it plans, so at most 10 s. */
export const MAX_BUDGET_ITERATIONS = 200_000;
export const MAX_BUDGET_MS = 10_000;
/** Iterations per chunk under a time budget: a chunk of the slowest
 *  planner (Lazy PRM* on arena, about 20 µs an iteration natively) stays
 *  near a millisecond, so the budget is overshot by about that. */
const CHUNK = 64;

export interface SamplingSettings {
  algorithm: string;
  seed: number;
  /** Robot (disc) radius, m; undefined: 0.4 of a cell (the CLI's default). */
  radiusM: number | undefined;
  budget: { kind: 'iterations' | 'ms'; value: number };
  shortcut: boolean;
  allowUnknown: boolean;
}

export interface SamplingResult {
  playback: SamplingPlayback;
  /** The shown path's length, cells (shortcut when asked; NaN: no path). */
  cost: number;
  lengthM: number;
  iterations: number;
  /** Iteration of the first path (NaN: none). */
  firstSolution: number;
  nodes: number;
  /** (iteration, cost) of every improvement. */
  solutions: Float64Array;
  /** Time spent stepping the run, ms. */
  ms: number;
  radiusCells: number;
  /** The run stopped by itself (RRT / RRT-Connect's first path, a
   *  straight-line path) before the budget. */
  finished: boolean;
}

/** Checks a budget; throws a one-line error. */
export function checkBudget(b: SamplingSettings['budget']): void {
  const [max, unit] = b.kind === 'ms' ? [MAX_BUDGET_MS, 'milliseconds'] : [MAX_BUDGET_ITERATIONS, 'iterations'];
  if (!Number.isInteger(b.value) || b.value < 1 || b.value > max) throw new Error(`budget ${Number.isNaN(b.value) ? '(empty)' : b.value}: must be a whole number of ${unit} from 1 to ${max.toLocaleString('en-US')}`);
}

/** Runs a planner to its budget. Throws the core's one-line error for bad
 *  input (radius, seed, start or goal in a wall). */
export function runSampling(map: MapHandle, start: Cell, goal: Cell, s: SamplingSettings): SamplingResult {
  checkBudget(s.budget);
  const run = new SamplingRun(map, s.algorithm, start[0], start[1], goal[0], goal[1], s.radiusM, s.seed, s.allowUnknown);
  try {
    const t0 = performance.now();
    if (s.budget.kind === 'iterations') run.step(s.budget.value);
    else while (!run.done && performance.now() - t0 < s.budget.value && run.step(CHUNK) > 0);
    const ms = performance.now() - t0;
    const cost = run.pathCost(s.shortcut);
    return {
      playback: new SamplingPlayback(run, s.shortcut),
      cost,
      lengthM: cost * run.resolution,
      iterations: run.iterations,
      firstSolution: run.firstSolution,
      nodes: run.nodeCount,
      solutions: run.solutions(),
      ms,
      radiusCells: run.radiusCells,
      finished: run.done,
    };
  } finally {
    run.free();
  }
}

/** The one line for a run without a path. */
export function noPathLine(s: SamplingSettings, r: SamplingResult): string {
  return `${samplingLabel(s.algorithm)}: no path after ${r.iterations.toLocaleString('en-US')} iterations (${r.nodes.toLocaleString('en-US')} nodes): give it a larger budget, another seed or a smaller robot radius.`;
}

/** The CLI command that reproduces a run (same map file, cells, seed and
 *  iterations). */
export function cliCommand(mapFile: string, start: Cell, goal: Cell, s: SamplingSettings, iterations: number): string {
  const parts = ['planlab plan', mapFile, `--start ${start[0]},${start[1]}`, `--goal ${goal[0]},${goal[1]}`, `--algo ${s.algorithm}`, `--iterations ${iterations}`, `--seed ${s.seed}`];
  if (s.radiusM !== undefined) parts.push(`--radius ${s.radiusM}`);
  if (s.shortcut) parts.push('--shortcut');
  if (s.allowUnknown) parts.push('--allow-unknown');
  return parts.join(' ');
}
