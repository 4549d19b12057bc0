// The arm page's distance-to-the-hand plot (uPlot): the nearest link's
// distance (what the APF keeps away and the metric's minimum is taken of)
// and the gripper's, per 0.1 s sample, as the ArmHandle records them.
// Hover to read both at any time; a dashed line marks the run's minimum.

import uPlot from 'uplot';
import 'uplot/dist/uPlot.min.css';
import type { ArmHandle } from '../../pkg-arm/planlab_wasm_arm.js';

const AXIS = { stroke: '#64748b', grid: { stroke: 'rgba(100,116,139,0.15)', width: 1 }, ticks: { show: false }, size: 40 };

export class DistancePlot {
  private cols = [new Float64Array(1024), new Float64Array(1024), new Float64Array(1024)];
  private n = 0;
  private handle: ArmHandle | null = null;
  private plot: uPlot;

  constructor(private el: HTMLElement) {
    const fmt = (_u: uPlot, v: number | null) => (v == null ? '—' : `${v.toFixed(4)} m`);
    this.plot = new uPlot(
      {
        title: 'Distance to the hand(t), m',
        ...this.size(),
        legend: { show: true, live: true },
        cursor: { drag: { x: false, y: false, setScale: false } },
        scales: {
          x: { time: false, range: (_u, _lo, hi) => [0, Math.max(5, hi ?? 0)] },
          y: { range: (_u, _lo, hi) => [0, Math.max(0.1, (hi ?? 0) * 1.08)] },
        },
        axes: [{ ...AXIS, size: 22, values: (_u, t) => t.map((x) => `${x}s`) }, { ...AXIS }],
        series: [
          { label: 't (s)', value: (_u, v) => (v == null ? '—' : v.toFixed(1)) },
          { label: 'arm (nearest link)', stroke: '#ea580c', width: 1.6, fill: '#ea580c14', value: fmt },
          { label: 'gripper', stroke: '#2563eb', width: 1.4, dash: [5, 3], value: fmt },
        ],
        hooks: {
          draw: [
            (u) => {
              // The run's minimum so far.
              if (!this.n) return;
              let m = Infinity;
              for (let i = 0; i < this.n; i++) m = Math.min(m, this.cols[1][i]);
              const y = Math.round(u.valToPos(m, 'y', true));
              const c = u.ctx;
              c.save();
              c.strokeStyle = 'rgba(220, 38, 38, 0.6)';
              c.setLineDash([3 * devicePixelRatio, 3 * devicePixelRatio]);
              c.beginPath();
              c.moveTo(u.bbox.left, y);
              c.lineTo(u.bbox.left + u.bbox.width, y);
              c.stroke();
              c.restore();
            },
          ],
        },
      },
      this.data(),
      el,
    );
    new ResizeObserver(() => this.plot.setSize(this.size())).observe(el);
  }

  private size(): { width: number; height: number } {
    return { width: Math.max(120, this.el.clientWidth - 12), height: Math.max(80, this.el.clientHeight - 52) };
  }

  private data(): uPlot.AlignedData {
    return this.cols.map((c) => c.subarray(0, this.n)) as unknown as uPlot.AlignedData;
  }

  /** Rows held. */
  get length(): number {
    return this.n;
  }

  /** The last row: t, arm distance, gripper distance. */
  last(): number[] {
    return this.n ? this.cols.map((c) => c[this.n - 1]) : [];
  }

  /** Fetches the samples since the last call (all of them after a new
   *  handle, a reset or a hand change) and redraws. */
  pull(h: ArmHandle): void {
    if (h !== this.handle || (this.n > 0 && h.time < this.cols[0][this.n - 1] - 1e-9)) {
      this.handle = h;
      this.n = 0;
    }
    let s = h.distanceSeries(this.n);
    // A restart at the same time (a reset before any step) shows as a
    // series shorter than what is held.
    if (this.n > 0 && s.length === 0 && h.distanceSeries(0).length / 3 < this.n) {
      this.n = 0;
      s = h.distanceSeries(0);
    }
    const m = Math.floor(s.length / 3);
    if (m === 0 && this.n > 0) return;
    if (this.n + m > this.cols[0].length) {
      const cap = Math.max(2 * this.cols[0].length, this.n + m);
      this.cols = this.cols.map((c) => {
        const d = new Float64Array(cap);
        d.set(c.subarray(0, this.n));
        return d;
      });
    }
    for (let i = 0; i < m; i++) for (let c = 0; c < 3; c++) this.cols[c][this.n + i] = s[3 * i + c];
    this.n += m;
    this.plot.setData(this.data());
    this.el.dataset.rows = String(this.n);
  }
}
