// The grid page's plan metrics (cost, length, expanded, path cells, key
// points, time): text for people, `data-value` for the tests.

import type { PlanResult } from '../../pkg-grid/planlab_wasm.js';
import { el } from '../shell/dom';
import { movesNote } from '../shell/grid-planners';

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
