// The BARN page's read-outs of a lane: its result (outcome, time T, the
// world's OT, the challenge's score from the core's `barnScore`) and the
// results table, a row per lane. T is the `planlab run` metrics' time, as
// `planlab barn` scores it.

import { barnScore } from '../../pkg/planlab_wasm.js';
import type { Lane } from '../compare/lane';
import { hexHash } from '../shell/hash';

export interface BarnResult {
  outcome: string;
  time: number;
  ot: number;
  /** Null while the run goes on. */
  score: number | null;
}

export function resultOf(l: Lane, ot: number): BarnResult {
  if (l.running) return { outcome: 'running', time: l.sim.time, ot, score: null };
  const time = (l.metrics ?? l.updateMetrics()).time_s;
  return { outcome: l.outcome, time, ot, score: barnScore(l.outcome === 'reached', time, ot) };
}

/** `OT / clip(T, 2·OT, 8·OT) = …` with the run's numbers. */
export function scoreFormula(r: BarnResult): string {
  if (r.score === null) return '';
  if (r.outcome !== 'reached') return `score = 0 (${r.outcome}: only a run that reaches the goal scores)`;
  const clipped = Math.min(Math.max(r.time, 2 * r.ot), 8 * r.ot);
  return `score = OT / clip(T, 2·OT, 8·OT) = ${r.ot.toFixed(2)} / clip(${r.time.toFixed(2)}, ${(2 * r.ot).toFixed(2)}, ${(8 * r.ot).toFixed(2)}) = ${r.ot.toFixed(2)} / ${clipped.toFixed(2)} = ${r.score.toFixed(3)}`;
}

function cell(text: string, data: Record<string, string> = {}): HTMLTableCellElement {
  const td = document.createElement('td');
  td.textContent = text;
  Object.assign(td.dataset, data);
  return td;
}

/** A row per lane: planner, outcome, T, OT, score, trace hash; the
 *  exact numbers ride in `data-value` for tests and copy-paste. */
export function renderResults(table: HTMLTableElement, lanes: Lane[], ot: number): void {
  const rows = lanes.map((l) => {
    const r = resultOf(l, ot);
    const tr = document.createElement('tr');
    tr.dataset.planner = l.name;
    const th = document.createElement('th');
    th.scope = 'row';
    const sw = document.createElement('i');
    sw.className = 'lane-swatch';
    sw.style.background = l.colour;
    th.append(sw, document.createTextNode(l.name));
    tr.append(
      th,
      cell(r.outcome, { outcome: r.outcome, key: 'outcome' }),
      cell(r.time.toFixed(2), { key: 'time', value: String(r.time) }),
      cell(ot.toFixed(2), { key: 'ot', value: String(ot) }),
      cell(r.score === null ? '—' : r.score.toFixed(3), { key: 'score', value: r.score === null ? '' : String(r.score) }),
      cell(l.hash ? hexHash(l.hash) : '—', { key: 'hash' }),
    );
    return tr;
  });
  table.tBodies[0].replaceChildren(...rows);
  table.dataset.final = String(lanes.length > 0 && lanes.every((l) => !l.running));
}
