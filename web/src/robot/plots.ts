// v(t), ω(t) and clearance(t) with uPlot (bundled, no CDN). The series
// arrive from the SimHandle as rows (t, v, ω, clearance) since the last
// call and are appended into growable Float64Arrays; the charts get
// subarray views, redrawn at most every `minIntervalMs`.

import uPlot from 'uplot';
import 'uplot/dist/uPlot.min.css';

interface Chart {
  plot: uPlot;
  el: HTMLElement;
}

const AXIS = { stroke: '#64748b', grid: { stroke: 'rgba(100,116,139,0.15)', width: 1 }, ticks: { show: false }, size: 34 };

export class SeriesPlots {
  private cols: Float64Array[] = [new Float64Array(1024), new Float64Array(1024), new Float64Array(1024), new Float64Array(1024)];
  private n = 0;
  private charts: Chart[] = [];
  private dirty = false;
  private lastDraw = 0;
  minIntervalMs = 100;

  constructor(elements: [HTMLElement, HTMLElement, HTMLElement]) {
    const specs: [string, string, string][] = [
      ['Speed v(t), m/s', 'v (m/s)', '#4f46e5'],
      ['Turn rate ω(t), rad/s', 'ω (rad/s)', '#0891b2'],
      ['Clearance(t), m', 'clearance (m)', '#059669'],
    ];
    specs.forEach(([title, label, colour], i) => {
      const el = elements[i];
      const plot = new uPlot(
        {
          title,
          width: Math.max(100, el.clientWidth - 12),
          height: Math.max(80, el.clientHeight - 34),
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
          axes: [
            { ...AXIS, size: 22, values: (_u, ticks) => ticks.map((t) => `${t}s`) },
            { ...AXIS, label: undefined },
          ],
          series: [{}, { label, stroke: colour, width: 1.5, fill: `${colour}14` }],
        },
        [new Float64Array(0), new Float64Array(0)],
        el,
      );
      this.charts.push({ plot, el });
    });
    const ro = new ResizeObserver(() => {
      for (const c of this.charts) c.plot.setSize({ width: Math.max(100, c.el.clientWidth - 12), height: Math.max(80, c.el.clientHeight - 34) });
    });
    for (const e of elements) ro.observe(e);
  }

  /** Number of rows held. */
  get length(): number {
    return this.n;
  }

  clear(): void {
    this.n = 0;
    this.dirty = true;
    this.flush(true);
  }

  /** Appends rows given as stride-4 (t, v, ω, clearance) values. */
  append(rows: Float64Array): void {
    const m = Math.floor(rows.length / 4);
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
      for (let c = 0; c < 4; c++) this.cols[c][this.n + i] = rows[4 * i + c];
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
    const t = this.cols[0].subarray(0, this.n);
    this.charts.forEach((c, i) => c.plot.setData([t, this.cols[i + 1].subarray(0, this.n)]));
  }
}
