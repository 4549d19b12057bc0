// A sampling planner's run played back (wasm `SamplingRun`'s events, the
// core's `Event::flat` columns): the player seeks through the events (back
// = replay from the start: a few hundred thousand simple updates at most),
// and the view asks the playback to paint the tree (or roadmap) as it
// stands at the current event: the samples so far, the nodes and edges,
// the last sample and the step grown towards it, RRT-Connect's two trees
// in two colours and where they met, the latest rewirings (RRT*, BIT*),
// and the best path so far, glowing right after an improvement. Nothing
// here plans: every number comes from the core's events.

import type { SamplingRun } from '../../pkg-grid/planlab_wasm.js';

/** Event kinds (core `Event::flat`). */
export const EV = { sample: 0, node: 1, edge: 2, removeEdge: 3, connect: 4, rewire: 5, prune: 6, solution: 7 } as const;

/** Colours of the tree (the legend's swatches use the same). */
export const TREE_CSS = {
  sample: 'rgba(71, 85, 105, 0.7)',
  edge: 'rgba(13, 148, 136, 0.75)',
  edgeGoal: 'rgba(217, 119, 6, 0.8)',
  node: 'rgba(15, 118, 110, 0.9)',
  latest: '#7c3aed',
  rewire: '#f97316',
  connect: '#a21caf',
  removed: 'rgba(220, 38, 38, 0.7)',
  path: '#e11d48',
  glow: 'rgba(250, 204, 21, 0.85)',
} as const;

/** Rewirings highlighted: the last this many. */
const RECENT_REWIRES = 24;
/** Events after an improvement during which its path glows: at least this
 *  many, or 2 % of the run (a long run plays many events per frame). */
const GLOW_EVENTS = 96;

/** Cell coordinates to canvas pixels. */
export type ToScreen = (x: number, y: number) => [number, number];

const KEY = 4194304; // 2^22 > the core's 2 000 000 iterations' node ids
const key = (a: number, b: number) => a * KEY + b;

export interface SamplingCounters {
  step: number;
  events: number;
  nodes: number;
  samples: number;
  /** Best cost at the step (NaN before the first path). */
  cost: number;
  rewires: number;
  /** Improvements played so far. */
  solutions: number;
}

export class SamplingPlayback {
  readonly n: number;
  readonly kinds: Uint8Array;
  readonly ids: Uint32Array;
  readonly nums: Float64Array;
  /** The path of each improvement (flat x, y, cells). */
  readonly paths: Float64Array[];
  /** The final path to show at the end (shortcut when asked). */
  readonly finalPath: Float64Array;
  readonly algorithm: string;
  private k = 0;
  private x: Float64Array;
  private y: Float64Array;
  private alive: Uint8Array;
  private parent: Int32Array;
  /** 0: grown from the start, 1: from the goal (RRT-Connect). */
  private side: Uint8Array;
  private edges = new Map<number, number>();
  private nodes = 0;
  private samples = 0;
  private rewires = 0;
  private solutions = 0;
  private lastSolutionAt = -1;
  private cost = NaN;
  private connect: [number, number] | null = null;
  private totals: SamplingCounters;
  /** Edges painted by the last paint (the tests read it). */
  drawnEdges = 0;
  /** Event index of each improvement. */
  readonly solutionAt: number[] = [];

  constructor(run: SamplingRun, shortcut: boolean) {
    const ev = run.takeEvents();
    try {
      this.kinds = ev.kinds();
      this.ids = ev.ids();
      this.nums = ev.nums();
    } finally {
      ev.free();
    }
    this.n = this.kinds.length;
    this.algorithm = run.algorithm;
    const count = run.solutions().length / 2;
    this.paths = Array.from({ length: count }, (_, i) => run.solutionPath(i));
    this.finalPath = count ? run.path(shortcut) : new Float64Array();
    let maxId = 1;
    for (let i = 0; i < this.n; i++) {
      if (this.kinds[i] === EV.node) maxId = Math.max(maxId, this.ids[3 * i]);
      if (this.kinds[i] === EV.solution) this.solutionAt.push(i);
    }
    this.x = new Float64Array(maxId + 1);
    this.y = new Float64Array(maxId + 1);
    this.alive = new Uint8Array(maxId + 1);
    this.parent = new Int32Array(maxId + 1).fill(-1);
    this.side = new Uint8Array(maxId + 1);
    this.seek(this.n);
    this.totals = this.counters();
    this.seek(0);
  }

  get step(): number {
    return this.k;
  }

  get done(): boolean {
    return this.k >= this.n;
  }

  /** Moves to `step` (clamped to 0…n), forward or back. */
  seek(step: number): void {
    const to = Math.max(0, Math.min(this.n, Math.floor(step)));
    if (to < this.k) this.reset();
    for (let i = this.k; i < to; i++) this.apply(i);
    this.k = to;
  }

  private reset(): void {
    this.k = 0;
    this.alive.fill(0);
    this.parent.fill(-1);
    this.side.fill(0);
    this.edges.clear();
    this.nodes = this.samples = this.rewires = this.solutions = 0;
    this.lastSolutionAt = -1;
    this.cost = NaN;
    this.connect = null;
  }

  private apply(i: number): void {
    const a = this.ids[3 * i];
    const b = this.ids[3 * i + 1];
    switch (this.kinds[i]) {
      case EV.sample:
        this.samples++;
        break;
      case EV.node:
        this.x[a] = this.nums[2 * i];
        this.y[a] = this.nums[2 * i + 1];
        if (!this.alive[a]) this.nodes++;
        this.alive[a] = 1;
        // RRT-Connect's node 1 is the goal tree's root.
        this.side[a] = this.algorithm === 'rrt-connect' && a === 1 ? 1 : 0;
        break;
      case EV.edge:
        this.edges.set(key(a, b), 1);
        this.parent[b] = a;
        this.side[b] = this.side[a];
        break;
      case EV.removeEdge:
        this.edges.delete(key(a, b));
        break;
      case EV.connect:
        this.connect = [a, b];
        break;
      case EV.rewire: {
        const c = this.ids[3 * i + 2];
        this.edges.delete(key(b, a));
        this.edges.set(key(c, a), 1);
        this.parent[a] = c;
        this.rewires++;
        break;
      }
      case EV.prune:
        if (this.parent[a] >= 0) this.edges.delete(key(this.parent[a], a));
        this.parent[a] = -1;
        if (this.alive[a]) this.nodes--;
        this.alive[a] = 0;
        break;
      case EV.solution:
        this.solutions++;
        this.cost = this.nums[2 * i];
        this.lastSolutionAt = i;
        break;
    }
  }

  /** Counters at the current step; `end`: at the end of the run. */
  counters(end = false): SamplingCounters {
    if (end && this.totals) return this.totals;
    return { step: this.k, events: this.n, nodes: this.nodes, samples: this.samples, cost: this.cost, rewires: this.rewires, solutions: this.solutions };
  }

  /** The path shown at the current step (flat x, y, cells), or null. */
  pathNow(): Float64Array | null {
    if (this.done) return this.finalPath.length ? this.finalPath : null;
    return this.solutions ? this.paths[this.solutions - 1] ?? null : null;
  }

  /** Paints the tree at the current step; `scale` is pixels per cell. */
  paint(ctx: CanvasRenderingContext2D, at: ToScreen, scale: number): void {
    const thin = Math.max(0.75, Math.min(2, scale * 0.06));
    // Samples: small grey dots (the last one larger, violet).
    let lastSample = -1;
    ctx.fillStyle = TREE_CSS.sample;
    const dot = Math.max(2, Math.min(3.5, scale * 0.16));
    for (let i = 0; i < this.k; i++) {
      if (this.kinds[i] !== EV.sample) continue;
      const [sx, sy] = at(this.nums[2 * i], this.nums[2 * i + 1]);
      ctx.fillRect(sx - dot / 2, sy - dot / 2, dot, dot);
      lastSample = i;
    }
    // Edges, by tree side.
    let drawn = 0;
    for (const side of [0, 1]) {
      ctx.beginPath();
      for (const k of this.edges.keys()) {
        const a = Math.floor(k / KEY);
        const b = k - a * KEY;
        if (this.side[a] !== side) continue;
        ctx.moveTo(...at(this.x[a], this.y[a]));
        ctx.lineTo(...at(this.x[b], this.y[b]));
        drawn++;
      }
      ctx.strokeStyle = side ? TREE_CSS.edgeGoal : TREE_CSS.edge;
      ctx.lineWidth = thin;
      ctx.stroke();
    }
    this.drawnEdges = drawn;
    // Nodes.
    const nd = Math.max(2, Math.min(4, scale * 0.16));
    ctx.fillStyle = TREE_CSS.node;
    for (let a = 0; a < this.alive.length; a++) {
      if (!this.alive[a]) continue;
      const [nx, ny] = at(this.x[a], this.y[a]);
      ctx.fillRect(nx - nd / 2, ny - nd / 2, nd, nd);
    }
    if (!this.done) this.paintRecent(ctx, at, scale, lastSample, thin);
    const path = this.pathNow();
    if (path && path.length >= 4) {
      const lw = Math.min(6, Math.max(2.5, scale * 0.3));
      const glow = !this.done && this.lastSolutionAt >= 0 && this.k - this.lastSolutionAt <= Math.max(GLOW_EVENTS, this.n * 0.02);
      if (glow) this.polyline(ctx, at, path, TREE_CSS.glow, lw + 8);
      this.polyline(ctx, at, path, 'rgba(255,255,255,0.85)', lw + 2.5);
      this.polyline(ctx, at, path, TREE_CSS.path, lw);
    }
  }

  /** The latest sample and the step towards it, the latest rewirings and
   *  RRT-Connect's meeting edge, while the run plays. */
  private paintRecent(ctx: CanvasRenderingContext2D, at: ToScreen, scale: number, lastSample: number, thin: number): void {
    let rewires = 0;
    let newest = -1;
    ctx.beginPath();
    for (let i = this.k - 1; i >= 0 && rewires < RECENT_REWIRES; i--) {
      const kind = this.kinds[i];
      if (kind === EV.node && newest < 0 && i > lastSample) newest = this.ids[3 * i];
      if (kind !== EV.rewire) continue;
      const a = this.ids[3 * i];
      const c = this.ids[3 * i + 2];
      if (this.parent[a] !== c) continue;
      ctx.moveTo(...at(this.x[c], this.y[c]));
      ctx.lineTo(...at(this.x[a], this.y[a]));
      rewires++;
    }
    ctx.strokeStyle = TREE_CSS.rewire;
    ctx.lineWidth = thin * 2.2;
    ctx.stroke();
    if (lastSample >= 0) {
      const [sx, sy] = at(this.nums[2 * lastSample], this.nums[2 * lastSample + 1]);
      const r = Math.max(3.5, Math.min(7, scale * 0.35));
      ctx.strokeStyle = TREE_CSS.latest;
      ctx.lineWidth = 2;
      ctx.beginPath();
      ctx.moveTo(sx - r, sy - r);
      ctx.lineTo(sx + r, sy + r);
      ctx.moveTo(sx - r, sy + r);
      ctx.lineTo(sx + r, sy - r);
      ctx.stroke();
      if (newest >= 0 && this.parent[newest] >= 0) {
        const p = this.parent[newest];
        ctx.setLineDash([4, 3]);
        ctx.beginPath();
        ctx.moveTo(...at(this.x[newest], this.y[newest]));
        ctx.lineTo(sx, sy);
        ctx.stroke();
        ctx.setLineDash([]);
        ctx.lineWidth = thin * 2.5;
        ctx.beginPath();
        ctx.moveTo(...at(this.x[p], this.y[p]));
        ctx.lineTo(...at(this.x[newest], this.y[newest]));
        ctx.stroke();
      }
    }
    if (this.connect) {
      const [a, b] = this.connect;
      ctx.strokeStyle = TREE_CSS.connect;
      ctx.lineWidth = thin * 3;
      ctx.beginPath();
      ctx.moveTo(...at(this.x[a], this.y[a]));
      ctx.lineTo(...at(this.x[b], this.y[b]));
      ctx.stroke();
    }
  }

  private polyline(ctx: CanvasRenderingContext2D, at: ToScreen, xy: Float64Array, color: string, width: number): void {
    ctx.beginPath();
    for (let k = 0; k < xy.length; k += 2) {
      const [px, py] = at(xy[k], xy[k + 1]);
      if (k === 0) ctx.moveTo(px, py);
      else ctx.lineTo(px, py);
    }
    ctx.strokeStyle = color;
    ctx.lineWidth = width;
    ctx.lineJoin = 'round';
    ctx.lineCap = 'round';
    ctx.stroke();
  }

  /** Nothing on the wasm side to release (the run is freed by its owner). */
  free(): void {}
}
