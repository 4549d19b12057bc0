// The grid page's sampling planners: their metrics (cost, length,
// iterations, first path at, nodes), the small plot of the best cost over
// the iterations (every improvement the core reported, a step function
// that only goes down; the ones the player has reached are filled), and
// the "Explain this planner" text (the core's reference and summary,
// wasm `samplingAlgorithms()`). Text for people, `data-value` and
// `data-points` for the tests. Nothing here plans.

import { el } from '../shell/dom';
import { setMetric } from './metrics';
import type { SamplingResult } from '../scene/sampling-run';
import { samplingLabel } from '../scene/sampling-run';
import type { SamplingPlayback } from '../scene/sampling-tree';

/** A sampling planner as the core describes it. */
export interface CoreSampler {
  name: string;
  optimizing: boolean;
  reference: string;
  summary: string;
}

/** Plain words for each planner: what to watch (docs/algorithms.md
 *  §sampling, shortened). */
const PLAIN: Record<string, string> = {
  rrt: 'One tree grows from the start: each step picks a random point and grows the nearest branch a little towards it, until a branch reaches the goal. It stops at the first path, which is usually long and crooked.',
  'rrt-connect': 'Two trees, one from the start and one from the goal, take turns growing towards random points and greedily towards each other; it stops when they meet. Usually the fastest to a first path, not a short one.',
  'rrt-star': 'RRT that gives each new point the cheapest parent nearby and then offers it as a cheaper parent to its neighbours (rewiring, orange), so the path keeps getting shorter the longer it runs.',
  'informed-rrt-star': 'RRT* that, once it has a path, only samples the ellipse of points that could lie on a shorter one: the dots gather around the path and the cost drops faster.',
  prm: 'A roadmap: random free points each joined to their nearest neighbours by free straight lines; the shortest way through the roadmap is the path. Not optimal.',
  'prm-star': 'A roadmap whose lines are checked only when they lie on the best candidate path; lines that hit a wall are removed and the next candidate is tried. Keeps improving.',
  'bit-star': 'Batches of random points searched best-first like A*, checking lines only when the search takes them; each new batch focuses where a shorter path could be.',
};

const metric = {
  row: el('sampling-metrics'),
  searchRow: el('metrics'),
  cost: el('sampling-cost'),
  length: el('sampling-length'),
  iterations: el('sampling-iterations'),
  first: el('sampling-first'),
  nodes: el('sampling-nodes'),
  plot: el<HTMLCanvasElement>('sampling-plot'),
  summary: el('sampling-summary'),
  reference: el('sampling-reference'),
};

let core: CoreSampler[] = [];

export function setSamplers(list: CoreSampler[]): void {
  core = list;
}

/** Which metrics row shows: the sampling planners' or the searches'. */
export function showSamplingMode(on: boolean): void {
  metric.row.hidden = !on;
  metric.searchRow.hidden = on;
  document.body.dataset.plannerKind = on ? 'sampling' : 'search';
}

/** The explain text of `name`. */
export function explainSampler(name: string): void {
  const c = core.find((p) => p.name === name);
  metric.summary.textContent = `${samplingLabel(name)}: ${PLAIN[name] ?? c?.summary ?? ''}`;
  metric.reference.textContent = c ? `${c.summary}. Reference: ${c.reference}. More in the help (?) and docs/algorithms.md §sampling.` : '';
}

export function clearSamplingMetrics(): void {
  for (const e of [metric.cost, metric.length, metric.iterations, metric.first, metric.nodes]) setMetric(e, '—', null);
  plotted = null;
  drawPlot(null);
}

/** A run's figures. */
export function showSamplingMetrics(r: SamplingResult): void {
  const ok = Number.isFinite(r.cost);
  setMetric(metric.cost, ok ? r.cost.toFixed(4) : 'no path', ok ? r.cost : null);
  setMetric(metric.length, ok ? `${r.lengthM.toFixed(2)} m` : '—', ok ? r.lengthM : null);
  setMetric(metric.iterations, r.iterations.toLocaleString('en-US'), r.iterations);
  setMetric(metric.first, Number.isNaN(r.firstSolution) ? '—' : r.firstSolution.toLocaleString('en-US'), Number.isNaN(r.firstSolution) ? null : r.firstSolution);
  setMetric(metric.nodes, r.nodes.toLocaleString('en-US'), r.nodes);
  plotted = { solutions: r.solutions, iterations: r.iterations };
  metric.plot.dataset.points = JSON.stringify(Array.from({ length: r.solutions.length / 2 }, (_, i) => [r.solutions[2 * i], r.solutions[2 * i + 1]]));
  drawPlot(null);
}

let plotted: { solutions: Float64Array; iterations: number } | null = null;

/** Redraws the plot; improvements the player has played are filled. */
export function drawPlot(p: SamplingPlayback | null): void {
  const c = metric.plot;
  const dpr = window.devicePixelRatio || 1;
  const w = c.clientWidth || 160;
  const h = c.clientHeight || 44;
  if (c.width !== Math.round(w * dpr)) c.width = Math.round(w * dpr);
  if (c.height !== Math.round(h * dpr)) c.height = Math.round(h * dpr);
  const ctx = c.getContext('2d');
  if (!ctx) return;
  ctx.setTransform(dpr, 0, 0, dpr, 0, 0);
  ctx.clearRect(0, 0, w, h);
  const s = plotted?.solutions;
  if (!plotted || !s || s.length < 2) {
    ctx.fillStyle = '#94a3b8';
    ctx.font = '11px system-ui, sans-serif';
    ctx.fillText(plotted ? 'no path yet' : '—', 4, h / 2 + 4);
    return;
  }
  const n = s.length / 2;
  const played = p ? p.counters().solutions : n;
  const xMax = Math.max(plotted.iterations, s[2 * (n - 1)], 1);
  let lo = Infinity;
  let hi = -Infinity;
  for (let i = 0; i < n; i++) {
    lo = Math.min(lo, s[2 * i + 1]);
    hi = Math.max(hi, s[2 * i + 1]);
  }
  if (hi - lo < 1e-9) [lo, hi] = [lo - 1, hi + 1];
  const pad = 4;
  const X = (it: number) => pad + ((w - 2 * pad) * it) / xMax;
  const Y = (cost: number) => pad + ((h - 2 * pad) * (hi - cost)) / (hi - lo);
  ctx.beginPath();
  for (let i = 0; i < n; i++) {
    const x = X(s[2 * i]);
    const y = Y(s[2 * i + 1]);
    if (i === 0) ctx.moveTo(x, y);
    else ctx.lineTo(x, y);
    const nx = i + 1 < n ? X(s[2 * i + 2]) : X(xMax);
    ctx.lineTo(nx, y);
  }
  ctx.strokeStyle = '#e11d48';
  ctx.lineWidth = 1.5;
  ctx.stroke();
  for (let i = 0; i < n; i++) {
    ctx.beginPath();
    ctx.arc(X(s[2 * i]), Y(s[2 * i + 1]), 2.5, 0, Math.PI * 2);
    ctx.fillStyle = i < played ? '#e11d48' : '#fff';
    ctx.fill();
    ctx.strokeStyle = '#e11d48';
    ctx.lineWidth = 1;
    ctx.stroke();
  }
}
