// The grid page's weighted cells (docs/algorithms.md §weights): the cost
// brush's weight, the hover text and the status note. The weights live in
// the wasm map; costs and notes come from the core's plan.

import type { MapHandle, PlanResult } from '../../pkg-grid/planlab_wasm.js';
import type { Cell } from '../shell/cells';
import { el } from '../shell/dom';

const select = el<HTMLSelectElement>('cost-weight');

/** The weight the cost brush paints (1–9; 1 erases a weight). */
export function costWeight(): number {
  const w = Number(select.value);
  return Number.isInteger(w) && w >= 1 && w <= 9 ? w : 5;
}

/** ` · weight N` for a weighted cell, else nothing. */
export function describeWeight(map: MapHandle, cell: Cell): string {
  const w = map.weightAt(cell[0], cell[1]);
  return w > 1 ? ` · weight ${w}` : '';
}

/** What the status line adds about weights: that costs are weighted, and
 *  the core's note (e.g. BFS ignored the weights). Also published on the
 *  body for the tests (`data-weighted`, `data-plan-note`). */
export function weightNote(res: PlanResult, map: MapHandle): string {
  const weighted = map.weighted;
  const note = res.note ?? '';
  document.body.dataset.weighted = String(weighted);
  document.body.dataset.planNote = note;
  let out = weighted ? ` · weighted cost ${res.cost.toFixed(3)}` : '';
  if (note) out += ` · note: ${note}`;
  return out;
}
