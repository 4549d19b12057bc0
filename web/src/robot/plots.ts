// Time plots of the run with uPlot (bundled, no CDN): v(t) (and v_y for an
// omnidirectional robot), ω(t), clearance(t), tracking error(t) (distance
// to the global path, shown when the planner has one) and the four wheel
// loads(t) (shown when the scenario has a vehicle model). Rows come from
// the SimHandle since the last pull and are appended into growable
// Float64Arrays; the charts get subarray views, redrawn at most every
// `minIntervalMs`.
//
// The charts are linked to the timeline: their cursors are synced (hover
// one, all show the values at that time in their legends), a marker line
// and the cursor sit at the timeline's frame when the pointer is
// elsewhere, and pressing or dragging in a chart scrubs the timeline
// (`onScrub`). Row i of every chart is trace row i, i.e. frame i.

import uPlot from 'uplot';
import 'uplot/dist/uPlot.min.css';
import type { SimHandle } from '../../pkg/planlab_wasm.js';

/** Columns held per row. */
const T = 0,
  V = 1,
  VY = 2,
  W = 3,
  CLR = 4,
  TRACK = 5,
  FL = 6;
const NCOLS = 10;

const AXIS = { stroke: '#64748b', grid: { stroke: 'rgba(100,116,139,0.15)', width: 1 }, ticks: { show: false }, size: 38 };

interface Spec {
  key: string;
  title: string;
  cols: number[];
  labels: string[];
  colours: string[];
  /** Whether the y range starts at zero (false: fit the data, for loads). */
  zero: boolean;
}

const SPECS: Spec[] = [
  { key: 'v', title: 'Speed v(t), m/s', cols: [V, VY], labels: ['v', 'v_y'], colours: ['#4f46e5', '#db2777'], zero: true },
  { key: 'w', title: 'Turn rate ω(t), rad/s', cols: [W], labels: ['ω'], colours: ['#0891b2'], zero: true },
  { key: 'clearance', title: 'Clearance(t), m', cols: [CLR], labels: ['clearance'], colours: ['#059669'], zero: true },
  { key: 'tracking', title: 'Tracking error(t), m', cols: [TRACK], labels: ['to path'], colours: ['#e11d48'], zero: true },
  {
    key: 'loads',
    title: 'Wheel loads(t), N',
    cols: [FL, FL + 1, FL + 2, FL + 3],
    labels: ['FL', 'FR', 'RL', 'RR'],
    colours: ['#4f46e5', '#0891b2', '#ea580c', '#65a30d'],
    zero: false,
  },
];

/** The chart elements by key (`v`, `w`, `clearance`, `tracking`, `loads`). */
export type PlotElements = Record<string, HTMLElement>;

export class SeriesPlots {
  private cols: Float64Array[] = Array.from({ length: NCOLS }, () => new Float64Array(1024));
  private n = 0;
  private plots: (uPlot | null)[] = SPECS.map(() => null);
  private els: HTMLElement[];
  private dirty = false;
  private lastDraw = 0;
  private omni = false;
  private vehicle = false;
  private tracking = false;
  /** Rows whose tracking error is known, and the path it was measured to. */
  private trackN = 0;
  private pathKey = '';
  /** The timeline's frame (row); null = the live end. */
  private frame: number | null = null;
  private hovering = false;
  private scrubbing = false;
  minIntervalMs = 100;
  /** Called with a row when the user presses or drags in a chart. */
  onScrub: (row: number) => void = () => {};

  constructor(elements: PlotElements) {
    this.els = SPECS.map((s) => {
      const e = elements[s.key];
      if (!e) throw new Error(`missing plot element ${s.key}`);
      return e;
    });
    this.build();
    const ro = new ResizeObserver(() => {
      this.plots.forEach((_, i) => this.fit(i));
      this.placeCursors();
    });
    for (const e of this.els) ro.observe(e);
    window.addEventListener('pointerup', () => (this.scrubbing = false));
  }

  private size(el: HTMLElement): { width: number; height: number } {
    return { width: Math.max(100, el.clientWidth - 12), height: Math.max(70, el.clientHeight - 54) };
  }

  private visible(i: number): boolean {
    const key = SPECS[i].key;
    if (key === 'loads') return this.vehicle;
    if (key === 'tracking') return this.tracking;
    return true;
  }

  /** Series shown by chart i (v_y only for an omnidirectional robot). */
  private shown(i: number): number[] {
    return SPECS[i].key === 'v' && !this.omni ? [V] : SPECS[i].cols;
  }

  private build(): void {
    for (const p of this.plots) p?.destroy();
    this.plots = SPECS.map((spec, i) => {
      const el = this.els[i];
      el.hidden = !this.visible(i);
      el.dataset.plot = spec.key;
      if (el.hidden) return null;
      const shown = this.shown(i);
      const marker = (u: uPlot) => {
        const row = this.frameRow();
        if (row < 0) return;
        const x = Math.round(u.valToPos(this.cols[T][row], 'x', true));
        const ctx = u.ctx;
        ctx.save();
        ctx.strokeStyle = 'rgba(15, 23, 42, 0.55)';
        ctx.lineWidth = Math.max(1, devicePixelRatio);
        ctx.setLineDash([4 * devicePixelRatio, 3 * devicePixelRatio]);
        ctx.beginPath();
        ctx.moveTo(x, u.bbox.top);
        ctx.lineTo(x, u.bbox.top + u.bbox.height);
        ctx.stroke();
        ctx.restore();
      };
      const u = new uPlot(
        {
          title: spec.title,
          ...this.size(el),
          legend: { show: true, live: true },
          cursor: {
            drag: { x: false, y: false, setScale: false },
            sync: { key: 'planlab-robot', setSeries: false },
            points: { size: 5 },
          },
          // Fixed-from-zero ranges: one row does not blow the axes up to
          // uPlot's defaults, and the time axis grows with the episode.
          scales: {
            x: { time: false, range: (_u, _lo, hi) => [0, Math.max(5, hi ?? 0)] },
            y: {
              range: (_u, lo, hi) => {
                let l = lo ?? 0;
                let h = hi ?? 0;
                if (!spec.zero) {
                  // Own extent: the start row has no loads (NaN), which
                  // uPlot's data range does not skip.
                  [l, h] = this.extent(shown);
                  const pad = Math.max(1, (h - l) * 0.1);
                  return [l - pad, h + pad];
                }
                const a = Math.min(0, l);
                const b = Math.max(0, h);
                const pad = Math.max(0.05, (b - a) * 0.08);
                return [a < 0 ? a - pad : 0, b + pad];
              },
            },
          },
          axes: [{ ...AXIS, size: 22, values: (_u, ticks) => ticks.map((t) => `${t}s`) }, { ...AXIS }],
          series: [
            { label: 't (s)', value: (_u, v) => (v == null ? '—' : v.toFixed(1)) },
            ...shown.map((c) => {
              const k = spec.cols.indexOf(c);
              return {
                label: spec.labels[k],
                stroke: spec.colours[k],
                width: 1.5,
                fill: k === 0 && spec.zero ? `${spec.colours[k]}14` : undefined,
                value: (_u: uPlot, v: number | null) => (v == null || Number.isNaN(v) ? '—' : v.toFixed(spec.zero ? 3 : 1)),
              };
            }),
          ],
          hooks: { draw: [marker] },
        },
        this.data(i),
        el,
      );
      // Press or drag in the chart: the timeline goes to that time.
      const scrubTo = (ev: PointerEvent) => {
        const r = u.over.getBoundingClientRect();
        const idx = u.posToIdx(ev.clientX - r.left);
        if (idx !== null && idx >= 0 && idx < this.n) this.onScrub(idx);
      };
      u.over.addEventListener('pointerdown', (ev) => {
        if (ev.button !== 0) return;
        this.scrubbing = true;
        scrubTo(ev);
      });
      u.over.addEventListener('pointermove', (ev) => {
        if (this.scrubbing && ev.buttons & 1) scrubTo(ev);
      });
      u.over.addEventListener('pointerenter', () => (this.hovering = true));
      u.over.addEventListener('pointerleave', () => {
        this.hovering = false;
        // Back to the timeline's frame once the pointer leaves.
        requestAnimationFrame(() => this.placeCursors());
      });
      return u;
    });
    this.plots.forEach((_, i) => this.fit(i));
  }

  /** Smallest and largest finite value of the columns `cols`. */
  private extent(cols: number[]): [number, number] {
    let lo = Infinity;
    let hi = -Infinity;
    for (const c of cols) {
      const d = this.cols[c];
      for (let i = 0; i < this.n; i++) {
        const v = d[i];
        if (v < lo) lo = v;
        if (v > hi) hi = v;
      }
    }
    return lo <= hi ? [lo, hi] : [0, 1];
  }

  /** Sizes chart i to its element, below its title and legend. */
  private fit(i: number): void {
    const u = this.plots[i];
    if (!u) return;
    const el = this.els[i];
    const title = u.root.querySelector<HTMLElement>('.u-title')?.offsetHeight ?? 0;
    const legend = u.root.querySelector<HTMLElement>('.u-legend')?.offsetHeight ?? 0;
    u.setSize({ width: Math.max(100, el.clientWidth - 12), height: Math.max(60, el.clientHeight - 8 - title - legend) });
  }

  private data(i: number): uPlot.AlignedData {
    const t = this.cols[T].subarray(0, this.n);
    return [t, ...this.shown(i).map((c) => this.cols[c].subarray(0, this.n))];
  }

  /** Number of rows held. */
  get length(): number {
    return this.n;
  }

  /** Which charts are shown, by key. */
  get shownKeys(): string[] {
    return SPECS.filter((_, i) => this.visible(i)).map((s) => s.key);
  }

  /** Empties the charts; `omni` adds v_y to the speed chart, `vehicle`
   *  shows the wheel loads. */
  clear(omni = false, vehicle = false): void {
    this.n = 0;
    this.trackN = 0;
    this.pathKey = '';
    this.frame = null;
    if (omni !== this.omni || vehicle !== this.vehicle) {
      this.omni = omni;
      this.vehicle = vehicle;
      this.build();
    }
    this.dirty = true;
    this.flush(true);
  }

  private grow(rows: number): void {
    if (rows <= this.cols[0].length) return;
    const cap = Math.max(this.cols[0].length * 2, rows);
    this.cols = this.cols.map((c) => {
      const d = new Float64Array(cap);
      d.set(c.subarray(0, this.n));
      return d;
    });
  }

  /** Fetches the rows since the last pull (series, loads, tracking error;
   *  the tracking error again from row 0 when the global path changed). */
  pull(sim: SimHandle, globalPath: Float64Array): void {
    // An edit that restarted the run in place: start over.
    if (sim.traceLen < this.n) {
      this.n = 0;
      this.trackN = 0;
      this.dirty = true;
    }
    const rows = sim.series(this.n);
    const m = Math.floor(rows.length / 5);
    if (m > 0) {
      this.grow(this.n + m);
      for (let i = 0; i < m; i++) {
        for (let c = 0; c < 5; c++) this.cols[c][this.n + i] = rows[5 * i + c];
      }
      if (this.vehicle) {
        const l = sim.wheelLoads(this.n);
        for (let i = 0; i < m && 5 * i + 4 < l.length; i++) {
          for (let w = 0; w < 4; w++) this.cols[FL + w][this.n + i] = l[5 * i + 1 + w];
        }
      }
      this.n += m;
      this.dirty = true;
    }
    // The tracking error is measured to the current global path (as the
    // metric is); a new path (a goal edit, a replan) re-measures it all.
    let key = `${globalPath.length}`;
    if (globalPath.length) {
      let sum = 0;
      for (let i = 0; i < globalPath.length; i++) sum += globalPath[i] * (1 + (i % 7));
      key += `:${sum}`;
    }
    const has = globalPath.length > 0;
    if (has !== this.tracking) {
      this.tracking = has;
      this.build();
      this.dirty = true;
    }
    if (key !== this.pathKey) {
      this.pathKey = key;
      this.trackN = 0;
    }
    if (has && this.trackN < this.n) {
      const d = sim.trackingErrors(this.trackN);
      for (let i = 0; i < d.length && this.trackN + i < this.n; i++) this.cols[TRACK][this.trackN + i] = d[i];
      this.trackN = Math.min(this.n, this.trackN + d.length);
      this.dirty = true;
    }
  }

  /** Redraws the charts if rows arrived (throttled unless `force`). */
  flush(force = false): void {
    if (!this.dirty) return;
    const now = performance.now();
    if (!force && now - this.lastDraw < this.minIntervalMs) return;
    this.lastDraw = now;
    this.dirty = false;
    this.plots.forEach((p, i) => p?.setData(this.data(i)));
    // uPlot applies new data's scales in a microtask: placed now, a cursor
    // would be put by the old x range (after "» To end": at 7 s of 27).
    queueMicrotask(() => this.placeCursors());
  }

  /** Row the marker and cursors show: the timeline's frame or the end. */
  private frameRow(): number {
    return this.frame === null ? this.n - 1 : Math.min(this.frame, this.n - 1);
  }

  /** Puts the marker and the cursors at `row` (null: the live end). */
  setFrame(row: number | null): void {
    // Following the live end costs nothing extra: flush places the cursors.
    if (row === null && this.frame === null) return;
    this.frame = row;
    if (this.dirty) this.flush(true);
    else {
      for (const p of this.plots) p?.redraw(false, false);
      this.placeCursors();
    }
  }

  private placeCursors(): void {
    if (this.hovering) return;
    const row = this.frameRow();
    if (row < 0) return;
    const t = this.cols[T][row];
    for (const p of this.plots) {
      if (!p) continue;
      p.setCursor({ left: p.valToPos(t, 'x'), top: p.bbox.height / devicePixelRatio / 2 }, false);
    }
  }

  /** Cursor row of every shown chart (for the tests). */
  cursorRows(): Record<string, number | null> {
    const out: Record<string, number | null> = {};
    this.plots.forEach((p, i) => {
      if (p) out[SPECS[i].key] = p.cursor.idx ?? null;
    });
    return out;
  }

  /** The y range each shown chart draws (for the tests). */
  yRanges(): Record<string, [number, number]> {
    const out: Record<string, [number, number]> = {};
    this.plots.forEach((p, i) => {
      if (p) out[SPECS[i].key] = [p.scales.y.min ?? Number.NaN, p.scales.y.max ?? Number.NaN];
    });
    return out;
  }

  /** Rows held per shown chart and the last value of each series. */
  summary(): Record<string, { rows: number; last: number[] }> {
    const out: Record<string, { rows: number; last: number[] }> = {};
    SPECS.forEach((_, i) => {
      if (!this.visible(i)) return;
      out[SPECS[i].key] = { rows: this.n, last: this.shown(i).map((c) => (this.n ? this.cols[c][this.n - 1] : Number.NaN)) };
    });
    return out;
  }
}
