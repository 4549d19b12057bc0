// The core's draw list (planlab_core::draw) as the pages read it: layers of
// polylines, points, discs, segments and cell grids in world metres, over
// one Float64Array. The painters only paint these items and toggle layers;
// every number in them comes from the core.

/** Layer codes, as `planlab_core::draw::Layer` numbers them (the page
 *  checks this table against the wasm module's at start, `checkLayers`). */
export const Layer = {
  Map: 0,
  Seen: 1,
  GlobalPath: 2,
  KeyPoints: 3,
  Fan: 4,
  Chosen: 5,
  Trail: 6,
  Movers: 7,
  Robot: 8,
  Goals: 9,
  LidarRays: 10,
  LidarEdges: 11,
  LidarOpsRaw: 12,
  LidarOps: 13,
  LidarCandidates: 14,
  LidarTarget: 15,
  Inflation: 16,
  FeatureNodes: 17,
  SearchCells: 18,
  SearchLines: 19,
  SearchCurrent: 20,
  Field: 21,
  Obstacles: 22,
  Predicted: 23,
  Candidates: 24,
  Links: 25,
  Hand: 26,
  HandPath: 27,
  Costmap: 28,
  Weights: 29,
} as const;
export type LayerCode = (typeof Layer)[keyof typeof Layer];
const LAYER_COUNT = 30;

/** Shape codes (`planlab_core::draw::Shape`). */
export const Shape = {
  Polyline: 0,
  Polygon: 1,
  Points: 2,
  Discs: 3,
  Segments: 4,
  Cells: 5,
  Timer: 6,
  CellPatch: 7,
  Vectors: 8,
  Polyline3: 9,
  Points3: 10,
  Spheres: 11,
  Capsules: 12,
} as const;

/** Numbers per item in `items`: layer, shape, start, end, tag, value. */
const STRIDE = 6;

/** The bit set of `layers`, as `SimHandle.draw` takes it. */
export function mask(...layers: LayerCode[]): number {
  let m = 0;
  for (const l of layers) m |= 1 << l;
  return m;
}

/** Every LiDAR layer. */
export const LIDAR = mask(Layer.LidarRays, Layer.LidarEdges, Layer.LidarOpsRaw, Layer.LidarOps, Layer.LidarCandidates, Layer.LidarTarget);

/** Throws when the wasm module numbers its layers differently. */
export function checkLayers(names: string[]): void {
  const kebab = (k: string) => k.replace(/([a-z])([A-Z])/g, '$1-$2').toLowerCase();
  const mine = Object.entries(Layer)
    .sort((a, b) => a[1] - b[1])
    .map(([k]) => kebab(k));
  if (names.join() !== mine.join()) throw new Error(`draw layers differ from the wasm module's: ${names.join()}`);
}

/** What `SimHandle.draw` returns. */
export interface DrawArrays {
  data: Float64Array;
  items: Float64Array;
  cells: Uint8Array;
}

/** A draw list with per-layer item ranges (the core emits items in layer
 *  order). */
export class DrawList {
  readonly data: Float64Array;
  readonly items: Float64Array;
  readonly cells: Uint8Array;
  /** First item of each layer, then one past the last. */
  private readonly bounds = new Int32Array(LAYER_COUNT + 1);

  constructor(a: DrawArrays = { data: new Float64Array(0), items: new Float64Array(0), cells: new Uint8Array(0) }) {
    this.data = a.data;
    this.items = a.items;
    this.cells = a.cells;
    const n = this.items.length / STRIDE;
    let i = 0;
    for (let l = 0; l <= LAYER_COUNT; l++) {
      while (i < n && this.items[i * STRIDE] < l) i++;
      this.bounds[l] = i;
    }
  }

  /** Item indexes `[first, end)` of layer `l`. */
  first(l: LayerCode): number {
    return this.bounds[l];
  }
  end(l: LayerCode): number {
    return this.bounds[l + 1];
  }
  count(l: LayerCode): number {
    return this.bounds[l + 1] - this.bounds[l];
  }
  shape(i: number): number {
    return this.items[i * STRIDE + 1];
  }
  /** First index of item `i`'s numbers in `data`. */
  start(i: number): number {
    return this.items[i * STRIDE + 2];
  }
  /** One past the last. */
  stop(i: number): number {
    return this.items[i * STRIDE + 3];
  }
  tag(i: number): number {
    return this.items[i * STRIDE + 4];
  }
  value(i: number): number {
    return this.items[i * STRIDE + 5];
  }
  /** Item `i`'s numbers (a view, no copy). */
  numbers(i: number): Float64Array {
    return this.data.subarray(this.start(i), this.stop(i));
  }
  /** Points in item `i` (x, y pairs). */
  points(i: number): number {
    return (this.stop(i) - this.start(i)) / 2;
  }
  /** The bytes of a cells item (one per cell) or a cell patch (one per
   *  listed index, the indexes being `numbers(i)` from 6 on). */
  cellBytes(i: number): Uint8Array {
    const h = this.numbers(i);
    const n = this.shape(i) === Shape.CellPatch ? h.length - 6 : h[0] * h[1];
    return this.cells.subarray(h[5], h[5] + n);
  }
  /** The first item of layer `l` with `tag`, or -1. */
  find(l: LayerCode, tag: number): number {
    for (let i = this.first(l); i < this.end(l); i++) if (this.tag(i) === tag) return i;
    return -1;
  }
}

export const EMPTY = new DrawList();

/** What one frame shows, layer by layer: each layer from the draw list
 *  that last brought it (the live end, a trace row, a re-simulated step). */
export class Frame {
  private by: DrawList[] = new Array<DrawList>(LAYER_COUNT).fill(EMPTY);

  /** Takes the layers in `layers` (a mask) from `d`. */
  put(d: DrawList, layers: number): void {
    for (let l = 0; l < LAYER_COUNT; l++) if (layers & (1 << l)) this.by[l] = d;
  }

  /** The draw list that holds layer `l`. */
  of(l: LayerCode): DrawList {
    return this.by[l];
  }

  /** Movers as `id, radius, x, y, vx, vy` rows (the e2e hooks' shape). */
  movers(): number[] {
    const d = this.of(Layer.Movers);
    const out: number[] = [];
    for (let i = d.first(Layer.Movers); i < d.end(Layer.Movers); i++) {
      const n = d.numbers(i);
      out.push(d.tag(i), n[2], n[0], n[1], n[3], n[4]);
    }
    return out;
  }

  /** Class code by mover id (0 dynamic, 1 static, 2 special); absent = none. */
  classes(): Map<number, number> {
    const d = this.of(Layer.Movers);
    const out = new Map<number, number>();
    for (let i = d.first(Layer.Movers); i < d.end(Layer.Movers); i++) {
      if (!Number.isNaN(d.value(i))) out.set(d.tag(i), d.value(i));
    }
    return out;
  }

  /** Point `tag` of the Goals layer (0 start, 1 goal, 2 the goal steered to). */
  goal(tag: number): [number, number] {
    const d = this.of(Layer.Goals);
    const i = d.find(Layer.Goals, tag);
    return i < 0 ? [0, 0] : [d.data[d.start(i)], d.data[d.start(i) + 1]];
  }

  /** The steered-to goal's kind name. */
  goalKind(): string {
    const d = this.of(Layer.Goals);
    const i = d.find(Layer.Goals, 2);
    return GOAL_KINDS[i < 0 ? 0 : d.value(i)] ?? 'final';
  }

  /** The global path's points, x, y flat (empty without one). */
  globalPath(): Float64Array {
    const d = this.of(Layer.GlobalPath);
    const i = d.first(Layer.GlobalPath);
    return i < d.end(Layer.GlobalPath) ? d.numbers(i) : EMPTY.data;
  }

  /** Whether the last step reported LiDAR data (the target is always there). */
  hasLidar(): boolean {
    return this.of(Layer.LidarTarget).count(Layer.LidarTarget) > 0;
  }

  /** Whether there are laser rays to draw: a LiDAR planner's, or the
   *  simulated laser's of a robot that perceives its map (`perception`). */
  hasRays(): boolean {
    return this.hasLidar() || this.of(Layer.LidarRays).count(Layer.LidarRays) > 0;
  }
}

/** A frame of the layers `layers` of one draw. */
export function drawnFrame(a: DrawArrays, layers: number): Frame {
  const f = new Frame();
  f.put(new DrawList(a), layers);
  return f;
}

export const GOAL_KINDS = ['final', 'intermediate', 'virtual', 'temporary'];
