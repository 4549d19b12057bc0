// v(t), ω(t) and clearance(t) with uPlot (bundled, no CDN). The series
// arrive from the SimHandle as rows (t, v, v_y, ω, clearance) since the
// last call and are appended into growable Float64Arrays; the charts get
// subarray views, redrawn at most every `minIntervalMs`. For an
// omnidirectional robot the speed chart also shows v_y.

import uPlot from 'uplot';
import 'uplot/dist/uPlot.min.css';

/** Values per row from SimHandle.series. */
const STRIDE = 5;

const AXIS = { stroke: '#64748b', grid: { stroke: 'rgba(100,116,139,0.15)', width: 1 }, ticks: { show: false }, size: 34 };

interface Spec {
  title: string;
  /** Columns of the row drawn, after t. */
  cols: number[];
  labels: string[];
  colours: string[];
}

const SPECS: Spec[] = [
  { title: 'Speed v(t), m/s', cols: [1, 2], labels: ['v (m/s)', 'v_y (m/s)'], colours: ['#4f46e5', '#db2777'] },
  { title: 'Turn rate ω(t), rad/s', cols: [3], labels: ['ω (rad/s)'], colours: ['#0891b2'] },
  { title: 'Clearance(t), m', cols: [4], labels: ['clearance (m)'], colours: ['#059669'] },
];

export class SeriesPlots {
  private cols: Float64Array[] = Array.from({ length: STRIDE }, () => new Float64Array(1024));
  private n = 0;
  private plots: uPlot[] = [];
  private els: HTMLElement[];
  private dirty = false;
  private lastDraw = 0;
  private omni = false;
  minIntervalMs = 100;

  constructor(elements: [HTMLElement, HTMLElement, HTMLElement]) {
    this.els = elements;
    this.build();
    const ro = new ResizeObserver(() => {
      this.plots.forEach((p, i) => p.setSize(this.size(this.els[i])));
    });
    for (const e of elements) ro.observe(e);
  }

  private size(el: HTMLElement): { width: number; height: number } {
    return { width: Math.max(100, el.clientWidth - 12), height: Math.max(80, el.clientHeight - 34) };
  }

  /** Series shown by chart i (v_y only for an omnidirectional robot). */
  private shown(i: number): number[] {
    return i === 0 && !this.omni ? [1] : SPECS[i].cols;
  }

  private build(): void {
    for (const p of this.plots) p.destroy();
    this.plots = SPECS.map((spec, i) => {
      const el = this.els[i];
      const shown = this.shown(i);
      return new uPlot(
        {
          title: i === 0 && this.omni ? 'Speed v (blue), v_y (pink) (t), m/s' : spec.title,
          ...this.size(el),
          legend: { show: false },
          cursor: { drag: { x: false, y: false } },
          // Fixed-from-zero ranges: one row does not blow the axes up to
          // uPlot's defaults, and the time axis grows with the episode.
          scales: {
            x: { time: false, range: (_u, _lo, hi) => [0, Math.max(5, hi ?? 0)] },
            y: {
              range: (_u, lo, hi) => {
                const a = Math.min(0, lo ?? 0);
                const b = Math.max(0, hi ?? 0);
                const pad = Math.max(0.05, (b - a) * 0.08);
                return [a < 0 ? a - pad : 0, b + pad];
              },
            },
          },
          axes: [{ ...AXIS, size: 22, values: (_u, ticks) => ticks.map((t) => `${t}s`) }, { ...AXIS }],
          series: [
            {},
            ...shown.map((c) => {
              const k = spec.cols.indexOf(c);
              return { label: spec.labels[k], stroke: spec.colours[k], width: 1.5, fill: k === 0 ? `${spec.colours[k]}14` : undefined };
            }),
          ],
        },
        this.data(i),
        el,
      );
    });
  }

  private data(i: number): uPlot.AlignedData {
    const t = this.cols[0].subarray(0, this.n);
    return [t, ...this.shown(i).map((c) => this.cols[c].subarray(0, this.n))];
  }

  /** Number of rows held. */
  get length(): number {
    return this.n;
  }

  /** Empties the charts; `omni` adds v_y to the speed chart. */
  clear(omni = false): void {
    this.n = 0;
    if (omni !== this.omni) {
      this.omni = omni;
      this.build();
    }
    this.dirty = true;
    this.flush(true);
  }

  /** Appends rows given as stride-5 (t, v, v_y, ω, clearance) values. */
  append(rows: Float64Array): void {
    const m = Math.floor(rows.length / STRIDE);
    if (m === 0) return;
    if (this.n + m > this.cols[0].length) {
      const cap = Math.max(this.cols[0].length * 2, this.n + m);
      this.cols = this.cols.map((c) => {
        const d = new Float64Array(cap);
        d.set(c.subarray(0, this.n));
        return d;
      });
    }
    for (let i = 0; i < m; i++) {
      for (let c = 0; c < STRIDE; c++) this.cols[c][this.n + i] = rows[STRIDE * i + c];
    }
    this.n += m;
    this.dirty = true;
  }

  /** Redraws the charts if rows arrived (throttled unless `force`). */
  flush(force = false): void {
    if (!this.dirty) return;
    const now = performance.now();
    if (!force && now - this.lastDraw < this.minIntervalMs) return;
    this.lastDraw = now;
    this.dirty = false;
    this.plots.forEach((p, i) => p.setData(this.data(i)));
  }
}
