// The grid page's plan metrics (cost, length, expanded, path cells, key
// points, time): text for people, `data-value` for the tests.

import type { PlanResult } from '../../pkg-grid/planlab_wasm.js';
import { el } from '../shell/dom';

const metric = {
  cost: el('metric-cost'),
  length: el('metric-length'),
  expanded: el('metric-expanded'),
  nodes: el('metric-nodes'),
  keypoints: el('metric-keypoints'),
  time: el('metric-time'),
};

export function setMetric(e: HTMLElement, text: string, value: number | null): void {
  e.textContent = text;
  if (value === null) delete e.dataset.value;
  else e.dataset.value = String(value);
}

const costNote = el('metric-cost-note');

/**
 * Why a path's cost cannot be set beside 8-connected A*'s, when the
 * planner's moves are other than the 8 neighbours: safe A*'s 24-cell
 * neighbourhood (knight-like moves of length √5 cut corners of the 8-cell
 * lattice, so its cost can be lower than the "optimal" A*'s), Theta*'s
 * any-angle segments, 4-connected moves. `[short, long]`, or null.
 */
export function movesNote(opts: Record<string, unknown>): [string, string] | null {
  const algo = String(opts.algorithm);
  if (algo === 'safe-astar') {
    const n = Number((opts.safe as Record<string, unknown> | undefined)?.neighbourhood ?? 24);
    if (n === 24)
      return [
        '24-neighbourhood moves: not comparable with A*',
        "safe A* moves to any of the 24 cells of the 5×5 block around a cell (knight-like moves of length √5 too), so its cost can be lower than 8-connected A*'s optimum: the costs are not comparable",
      ];
    if (n === 4) return ['4-neighbourhood moves: not comparable with A*', "safe A* moves to the 4 side neighbours only, so its cost is not comparable with 8-connected A*'s"];
    return null;
  }
  if (algo === 'theta-star')
    return ['any-angle path: not comparable with A*', "Theta*'s segments run at any angle, so its cost can be lower than 8-connected A*'s optimum: the costs are not comparable"];
  if (opts.diagonal === 'never')
    return ['4-connected moves: not comparable with A*', "with diagonal moves off the moves are 4-connected, so the cost is not comparable with 8-connected A*'s"];
  return null;
}

function showCostNote(opts: Record<string, unknown> | null): void {
  const note = opts ? movesNote(opts) : null;
  costNote.hidden = !note;
  costNote.textContent = note?.[0] ?? '';
  costNote.title = note?.[1] ?? '';
}

export function clearMetrics(): void {
  for (const e of Object.values(metric)) setMetric(e, '—', null);
  showCostNote(null);
}

/** Shows a plan's figures; `ms` is the wasm call's time. */
export function showMetrics(res: PlanResult, opts: Record<string, unknown>, ms: number, keyPoints: Uint32Array, featureNodes: Uint32Array): void {
  setMetric(metric.cost, res.cost.toFixed(4), res.cost);
  showCostNote(opts);
  setMetric(metric.length, `${res.lengthM.toFixed(2)} m`, res.lengthM);
  setMetric(metric.expanded, res.expandedCount.toLocaleString('en-US'), res.expandedCount);
  setMetric(metric.nodes, String(res.pathLen), res.pathLen);
  const kp = keyPoints.length / 2;
  const fn = featureNodes.length / 2;
  const parts = [];
  if (opts.keypoints) parts.push(String(kp));
  if (opts.bottom_up_eps !== null) parts.push(`${fn} BU`);
  setMetric(metric.keypoints, parts.length ? parts.join(' · ') : '—', opts.keypoints ? kp : null);
  setMetric(metric.time, `${ms.toFixed(2)} ms`, ms);
}
