// Canvas painter for the robot page. The map is one offscreen image (a
// pixel per cell) scaled into view; everything else is drawn in world
// metres under one canvas transform, so the DWA fan's typed arrays go
// straight into lineTo without per-point JS arithmetic, and the fan is one
// path per colour bucket (a dozen strokes for hundreds of rollouts).
// Nothing here plans, collides or measures: it paints what the wasm
// SimHandle reports.

export interface MapInfo {
  width: number;
  height: number;
  /** Metres per cell. */
  resolution: number;
  /** World position of the bottom-left corner of the map, metres. */
  originX: number;
  originY: number;
  /** Row-major cell kinds, row 0 at the top: 0 free, 1 occupied, 2 unknown. */
  cells: Uint8Array;
}

export type RobotShape = { kind: 'circle'; radius: number } | { kind: 'rect'; length: number; width: number };

/** Obstacle classes as the wasm layer numbers them. */
export const CLASS_NAMES = ['ordinary-dynamic', 'ordinary-static', 'special'] as const;

export const COLORS = {
  free: [248, 250, 252],
  occupied: [30, 41, 59],
  unknown: [184, 194, 209],
  path: '#e11d48',
  keypoint: '#7c3aed',
  start: '#16a34a',
  goal: '#2563eb',
  subgoal: '#7c3aed',
  virtual: '#db2777',
  chosen: '#059669',
  trail: '#0ea5e9',
  robot: '#0f172a',
  inadmissible: 'rgba(148, 163, 184, 0.28)',
  /** Mover fill by class index (CLASS_NAMES), then unclassified. */
  classes: ['#ea580c', '#0891b2', '#c026d3', '#64748b'],
} as const;

/** Score buckets of the fan: one stroke each. */
export const FAN_BUCKETS = 10;

/** Colour of bucket b (0 = worst admissible score, FAN_BUCKETS-1 = best). */
function bucketColour(b: number): string {
  // sky-400 → violet-500 → orange-500
  const stops = [
    [56, 189, 248],
    [139, 92, 246],
    [249, 115, 22],
  ];
  const t = FAN_BUCKETS > 1 ? b / (FAN_BUCKETS - 1) : 1;
  const s = t < 0.5 ? 0 : 1;
  const u = t < 0.5 ? t * 2 : (t - 0.5) * 2;
  const c = stops[s].map((v, i) => Math.round(v + (stops[s + 1][i] - v) * u));
  return `rgba(${c[0]}, ${c[1]}, ${c[2]}, 0.6)`;
}
const BUCKET_COLOURS = Array.from({ length: FAN_BUCKETS }, (_, b) => bucketColour(b));
/** Inadmissible (bucket FAN_BUCKETS) underneath, then worst to best. */
const BUCKET_ORDER = [FAN_BUCKETS, ...Array.from({ length: FAN_BUCKETS }, (_, b) => b)];

export interface Fan {
  /** Rollout points, x,y interleaved, all rollouts back to back. */
  points: Float32Array;
  /** Rollout k is points [offsets[k], offsets[k+1]) (counted in points). */
  offsets: Uint32Array;
  scores: Float32Array;
  /** 1 admissible, 0 not. */
  admissible: Uint8Array;
  /** Index of the chosen rollout, -1 for none. */
  chosen: number;
}

/** What the LiDAR navigator saw and chose in the last step (world frame);
 *  every number comes from the core. */
export interface LidarScene {
  /** Sensor x, y, then each beam's end point x, y. */
  rays: Float32Array;
  /** 1 per beam that returned. */
  returns: Uint8Array;
  /** Stride 3: x, y, type (1 SR, 2 WR, 3 SF, 4 WF), after gap removal. */
  edges: Float32Array;
  opsRaw: Float32Array;
  opsRawOffsets: Uint32Array;
  ops: Float32Array;
  opsOffsets: Uint32Array;
  /** Index of the OP blocking the goal, -1 for none. */
  blocking: number;
  /** Stride 4: x, y, cost, iteration. */
  candidates: Float64Array;
  /** x, y, kind (0 goal, 1 temporary, 2 held), hold left s, hold period s. */
  target: Float64Array;
}

/** Edge colours by type code (1 SR … 4 WF); the legend uses the same. */
export const EDGE_COLOURS: Record<number, string> = {
  1: '#dc2626',
  2: '#f97316',
  3: '#2563eb',
  4: '#06b6d4',
};

/** What one frame shows; main.ts fills it from the SimHandle. */
export interface Scene {
  robot: RobotShape;
  /** x, y, theta, v, vy, w. */
  state: Float64Array;
  start: [number, number, number];
  goal: [number, number];
  currentGoal: [number, number];
  goalKind: string;
  /** Stride 6: id, radius, x, y, vx, vy. */
  movers: Float64Array;
  /** Class index (CLASS_NAMES) by mover id; missing = unclassified. */
  classes: Map<number, number>;
  fan: Fan;
  globalPath: Float64Array;
  keypoints: Float64Array;
  /** Trail x,y pairs; only the first `trailLen` points are used. */
  trail: Float64Array;
  trailLen: number;
  /** The mover being placed by a drag: centre, velocity, radius. */
  preview: { x: number; y: number; vx: number; vy: number; radius: number } | null;
  show: { fan: boolean; path: boolean; trail: boolean; lidar: boolean; fog: boolean };
  /** LiDAR data of the last step (LiDAR planners only). */
  lidar: LidarScene | null;
  /** Seen cells (1) of the map, row 0 at the top; null = none reported. */
  seen: Uint8Array | null;
  seenCount: number;
}

export function emptyScene(): Scene {
  return {
    robot: { kind: 'circle', radius: 0.2 },
    state: new Float64Array(6),
    start: [0, 0, 0],
    goal: [0, 0],
    currentGoal: [0, 0],
    goalKind: 'final',
    movers: new Float64Array(0),
    classes: new Map(),
    fan: {
      points: new Float32Array(0),
      offsets: new Uint32Array(0),
      scores: new Float32Array(0),
      admissible: new Uint8Array(0),
      chosen: -1,
    },
    globalPath: new Float64Array(0),
    keypoints: new Float64Array(0),
    trail: new Float64Array(0),
    trailLen: 0,
    preview: null,
    show: { fan: true, path: true, trail: true, lidar: true, fog: false },
    lidar: null,
    seen: null,
    seenCount: 0,
  };
}

function offscreen(w: number, h: number): [HTMLCanvasElement, CanvasRenderingContext2D] {
  const c = document.createElement('canvas');
  c.width = w;
  c.height = h;
  const ctx = c.getContext('2d');
  if (!ctx) throw new Error('this browser cannot draw on a 2D canvas');
  return [c, ctx];
}

/** Known-cell bounding box [c0, r0, c1, r1) padded by a few cells; the
 *  whole map when every cell is unknown (ROS maps are mostly unknown).
 *  The canvas view and the SVG export frame the same part of the map. */
export function knownBox(m: MapInfo): [number, number, number, number] {
  const { width: w, height: h, cells } = m;
  let [c0, r0, c1, r1] = [w, h, -1, -1];
  for (let r = 0; r < h; r++) {
    for (let c = 0; c < w; c++) {
      if (cells[r * w + c] === 2) continue;
      if (c < c0) c0 = c;
      if (c > c1) c1 = c;
      if (r < r0) r0 = r;
      if (r > r1) r1 = r;
    }
  }
  if (c1 < 0) return [0, 0, w, h];
  const pad = Math.max(2, Math.round(0.04 * Math.max(c1 - c0, r1 - r0)));
  return [Math.max(0, c0 - pad), Math.max(0, r0 - pad), Math.min(w, c1 + 1 + pad), Math.min(h, r1 + 1 + pad)];
}

export class RobotView {
  readonly canvas: HTMLCanvasElement;
  private ctx: CanvasRenderingContext2D;
  private map: MapInfo | null = null;
  private base: HTMLCanvasElement | null = null;
  /** Fog overlay (unseen cells shaded) and the seen count it was built for. */
  private fog: HTMLCanvasElement | null = null;
  private fogCount = -1;
  /** CSS pixels per metre and CSS position of the map's top-left corner. */
  private k = 1;
  private ox = 0;
  private oy = 0;
  private fitted = true;
  /** Cell box [c0, r0, c1, r1) of the known (not unknown) cells. */
  private known: [number, number, number, number] = [0, 0, 1, 1];
  private cssW = 0;
  private cssH = 0;
  private pending = false;
  /** Per-rollout bucket, reused between frames (grown when needed). */
  private buckets = new Uint8Array(1024);
  scene: Scene = emptyScene();
  /** Called after each paint with its duration in ms (for the frame meter). */
  onPaint: ((ms: number) => void) | null = null;
  /** Extra layer painted last in screen space (CSS px): edit previews. */
  overlay: ((ctx: CanvasRenderingContext2D) => void) | null = null;

  constructor(canvas: HTMLCanvasElement) {
    this.canvas = canvas;
    const ctx = canvas.getContext('2d');
    if (!ctx) throw new Error('this browser cannot draw on a 2D canvas');
    this.ctx = ctx;
    new ResizeObserver(() => this.resize()).observe(canvas);
    this.resize();
  }

  /** A new map: paint its image and fit it into the view (`keepView`: keep
   *  the zoom and pan when the size is unchanged, after an edit). */
  setMap(m: MapInfo, keepView = false): void {
    const same = !!this.map && this.map.width === m.width && this.map.height === m.height && this.map.resolution === m.resolution;
    this.map = m;
    const [c, ctx] = offscreen(m.width, m.height);
    const img = ctx.createImageData(m.width, m.height);
    const px = img.data;
    const palette = [COLORS.free, COLORS.occupied, COLORS.unknown];
    for (let i = 0; i < m.cells.length; i++) {
      const col = palette[m.cells[i]] ?? COLORS.unknown;
      const o = i * 4;
      px[o] = col[0];
      px[o + 1] = col[1];
      px[o + 2] = col[2];
      px[o + 3] = 255;
    }
    ctx.putImageData(img, 0, 0);
    this.base = c;
    this.fog = null;
    this.fogCount = -1;
    this.known = knownBox(m);
    if (keepView && same) this.request();
    else this.fit();
  }

  private get mapW(): number {
    return this.map ? this.map.width * this.map.resolution : 1;
  }

  private get mapH(): number {
    return this.map ? this.map.height * this.map.resolution : 1;
  }

  private get x0(): number {
    return this.map?.originX ?? 0;
  }

  /** World y of the map's top edge. */
  private get y1(): number {
    return this.map ? this.map.originY + this.mapH : 0;
  }

  /**
   * Fits the known part of the map into the canvas with a small margin
   * (ROS maps are mostly unknown space around the explored area).
   */
  fit(): void {
    if (!this.map || !this.cssW || !this.cssH) return;
    const margin = 16;
    const res = this.map.resolution;
    const [c0, r0, c1, r1] = this.known;
    const bw = (c1 - c0) * res;
    const bh = (r1 - r0) * res;
    this.k = Math.max(1e-3, Math.min((this.cssW - 2 * margin) / bw, (this.cssH - 2 * margin) / bh));
    this.ox = (this.cssW - bw * this.k) / 2 - c0 * res * this.k;
    this.oy = (this.cssH - bh * this.k) / 2 - r0 * res * this.k;
    this.fitted = true;
    this.publishView();
    this.request();
  }

  zoomAt(x: number, y: number, factor: number): void {
    const k = Math.min(2000, Math.max(0.5, this.k * factor));
    const f = k / this.k;
    this.ox = x - (x - this.ox) * f;
    this.oy = y - (y - this.oy) * f;
    this.k = k;
    this.fitted = false;
    this.publishView();
    this.request();
  }

  panBy(dx: number, dy: number): void {
    this.ox += dx;
    this.oy += dy;
    this.fitted = false;
    this.publishView();
    this.request();
  }

  /** World point (m) under a canvas point (CSS px). */
  toWorld(x: number, y: number): [number, number] {
    return [this.x0 + (x - this.ox) / this.k, this.y1 - (y - this.oy) / this.k];
  }

  /** Canvas point (CSS px) of a world point (m). */
  toScreen(x: number, y: number): [number, number] {
    return [this.ox + (x - this.x0) * this.k, this.oy + (this.y1 - y) * this.k];
  }

  /** Whether a world point lies on the map. */
  onMap(x: number, y: number): boolean {
    return !!this.map && x >= this.x0 && x <= this.x0 + this.mapW && y >= this.y1 - this.mapH && y <= this.y1;
  }

  /** Pixels per metre. */
  get scale(): number {
    return this.k;
  }

  /** Exposes the view so tests can click a given world point. */
  private publishView(): void {
    const d = this.canvas.dataset;
    d.scale = String(this.k);
    d.offsetX = String(this.ox);
    d.offsetY = String(this.oy);
    d.x0 = String(this.x0);
    d.y1 = String(this.y1);
  }

  private resize(): void {
    const rect = this.canvas.getBoundingClientRect();
    const dpr = window.devicePixelRatio || 1;
    const [oldW, oldH] = [this.cssW, this.cssH];
    this.cssW = rect.width;
    this.cssH = rect.height;
    this.canvas.width = Math.max(1, Math.round(rect.width * dpr));
    this.canvas.height = Math.max(1, Math.round(rect.height * dpr));
    if (this.fitted) this.fit();
    else {
      this.ox += (rect.width - oldW) / 2;
      this.oy += (rect.height - oldH) / 2;
      this.publishView();
    }
    this.request();
  }

  /** Asks for a paint in the next animation frame (coalesced). */
  request(): void {
    if (this.pending) return;
    this.pending = true;
    requestAnimationFrame(() => {
      this.pending = false;
      this.paint();
    });
  }

  /** Paints now (main.ts calls this from its own frame loop). */
  paint(): void {
    const t0 = performance.now();
    this.pending = false;
    this.draw();
    this.onPaint?.(performance.now() - t0);
  }

  /** Sets the world transform (metres, y up) on the context. */
  private worldTransform(): void {
    const dpr = window.devicePixelRatio || 1;
    const k = this.k * dpr;
    this.ctx.setTransform(k, 0, 0, -k, dpr * (this.ox - this.x0 * this.k), dpr * (this.oy + this.y1 * this.k));
  }

  private screenTransform(): void {
    const dpr = window.devicePixelRatio || 1;
    this.ctx.setTransform(dpr, 0, 0, dpr, 0, 0);
  }

  private draw(): void {
    const ctx = this.ctx;
    ctx.setTransform(1, 0, 0, 1, 0, 0);
    ctx.clearRect(0, 0, this.canvas.width, this.canvas.height);
    if (!this.map || !this.base) return;
    const S = this.scene;
    this.screenTransform();
    const [w, h] = [this.mapW * this.k, this.mapH * this.k];
    ctx.save();
    ctx.shadowColor = 'rgba(15, 23, 42, 0.25)';
    ctx.shadowBlur = 12;
    ctx.fillStyle = '#fff';
    ctx.fillRect(this.ox, this.oy, w, h);
    ctx.restore();
    ctx.imageSmoothingEnabled = false;
    ctx.drawImage(this.base, this.ox, this.oy, w, h);
    const fogged = S.show.fog && S.seen !== null;
    if (fogged) {
      const fog = this.fogImage();
      if (fog) ctx.drawImage(fog, this.ox, this.oy, w, h);
    }
    this.canvas.dataset.fog = fogged ? 'on' : 'off';

    // World-space layers: widths in metres = CSS px / k.
    this.worldTransform();
    const px = 1 / this.k;
    ctx.lineJoin = 'round';
    ctx.lineCap = 'round';
    if (S.show.path && S.globalPath.length >= 4) {
      this.polyline(S.globalPath, S.globalPath.length / 2, 'rgba(255,255,255,0.8)', 4.5 * px);
      this.polyline(S.globalPath, S.globalPath.length / 2, 'rgba(225, 29, 72, 0.75)', 2.5 * px);
    }
    if (S.show.trail && S.trailLen >= 2) this.polyline(S.trail, S.trailLen, COLORS.trail, 2.5 * px);
    if (S.show.fan) this.drawFan(px);
    const lidarOn = S.show.lidar && S.lidar !== null;
    if (lidarOn) this.drawLidar(px);
    this.drawRobot(px);

    // Screen-space layers: markers and labels stay readable at any zoom.
    this.screenTransform();
    if (lidarOn) this.drawLidarMarkers();
    this.canvas.dataset.lidarLayers = lidarOn ? this.lidarLayers() : '';
    if (S.show.path) this.drawKeypoints();
    this.drawMovers();
    this.drawGoals();
    this.drawPreview();
    this.overlay?.(ctx);
  }

  /** The fog overlay: unseen cells shaded (rebuilt when the count changes). */
  private fogImage(): HTMLCanvasElement | null {
    const S = this.scene;
    if (!this.map || !S.seen || S.seen.length !== this.map.width * this.map.height) return null;
    if (this.fog && this.fogCount === S.seenCount) return this.fog;
    const [c, ctx] = offscreen(this.map.width, this.map.height);
    const img = ctx.createImageData(this.map.width, this.map.height);
    const px = img.data;
    for (let i = 0; i < S.seen.length; i++) {
      const o = i * 4;
      // Unseen: a cool grey, lighter than the walls so they stay apart.
      px[o] = 148;
      px[o + 1] = 163;
      px[o + 2] = 184;
      px[o + 3] = S.seen[i] ? 0 : 230;
    }
    ctx.putImageData(img, 0, 0);
    this.fog = c;
    this.fogCount = S.seenCount;
    return c;
  }

  /** Which LiDAR layers the last paint drew (for tests), comma-separated. */
  private lidarLayers(): string {
    const L = this.scene.lidar;
    if (!L) return '';
    const out: string[] = [];
    if (L.rays.length > 2) out.push('rays');
    if (L.edges.length > 0) out.push('edges');
    if (L.opsRawOffsets.length > 1) out.push('ops-raw');
    if (L.opsOffsets.length > 1) out.push('ops');
    if (L.candidates.length > 0) out.push('candidates');
    if (L.target.length >= 5 && L.target[2] > 0) out.push('temp-goal');
    if (L.target.length >= 5 && L.target[3] > 0) out.push('hold');
    return out.join(',');
  }

  /** Rays, then obstacle patterns before (thin) and after (wide) expansion. */
  private drawLidar(px: number): void {
    const L = this.scene.lidar;
    if (!L) return;
    const ctx = this.ctx;
    const n = L.rays.length / 2 - 1;
    const [sx, sy] = [L.rays[0], L.rays[1]];
    for (const hit of [0, 1]) {
      ctx.beginPath();
      for (let i = 0; i < n; i++) {
        if ((L.returns[i] ?? 0) !== hit) continue;
        ctx.moveTo(sx, sy);
        ctx.lineTo(L.rays[2 + 2 * i], L.rays[3 + 2 * i]);
      }
      ctx.strokeStyle = hit ? 'rgba(234, 88, 12, 0.22)' : 'rgba(148, 163, 184, 0.14)';
      ctx.lineWidth = 1 * px;
      ctx.stroke();
    }
    const polys = (xy: Float32Array, off: Uint32Array, colour: (k: number) => string, width: number) => {
      for (let k = 0; k + 1 < off.length; k++) {
        const sub = xy.subarray(2 * off[k], 2 * off[k + 1]);
        this.polyline(sub, off[k + 1] - off[k], colour(k), width);
      }
    };
    polys(L.ops, L.opsOffsets, (k) => (k === L.blocking ? 'rgba(190, 24, 93, 0.45)' : 'rgba(124, 58, 237, 0.3)'), 7 * px);
    polys(L.opsRaw, L.opsRawOffsets, () => 'rgba(30, 41, 59, 0.9)', 2 * px);
  }

  /** Edge markers by type, candidates, the chosen temporary goal, hold timer. */
  private drawLidarMarkers(): void {
    const L = this.scene.lidar;
    if (!L) return;
    const ctx = this.ctx;
    for (let i = 0; i + 2 < L.edges.length; i += 3) {
      const [x, y] = this.toScreen(L.edges[i], L.edges[i + 1]);
      ctx.beginPath();
      ctx.arc(x, y, 3.5, 0, Math.PI * 2);
      ctx.fillStyle = EDGE_COLOURS[L.edges[i + 2]] ?? '#000';
      ctx.fill();
    }
    for (let i = 0; i + 3 < L.candidates.length; i += 4) {
      const [x, y] = this.toScreen(L.candidates[i], L.candidates[i + 1]);
      ctx.beginPath();
      ctx.moveTo(x, y - 6);
      ctx.lineTo(x + 5.5, y + 4);
      ctx.lineTo(x - 5.5, y + 4);
      ctx.closePath();
      ctx.lineWidth = 1.5;
      ctx.strokeStyle = L.candidates[i + 3] > 0 ? '#a855f7' : '#7c3aed';
      ctx.stroke();
    }
    if (L.target.length >= 5 && L.target[2] > 0) {
      const [x, y] = this.toScreen(L.target[0], L.target[1]);
      star(ctx, x, y, 8, L.target[2] === 2 ? '#f59e0b' : '#16a34a');
    }
    if (L.target.length >= 5 && L.target[3] > 0 && L.target[4] > 0) {
      const s = this.scene.state;
      const [x, y] = this.toScreen(s[0], s[1]);
      const frac = Math.min(1, L.target[3] / L.target[4]);
      ctx.beginPath();
      ctx.arc(x, y, 18, -Math.PI / 2, -Math.PI / 2 + frac * Math.PI * 2);
      ctx.lineWidth = 3;
      ctx.strokeStyle = '#f59e0b';
      ctx.stroke();
      ctx.font = '600 11px system-ui, sans-serif';
      ctx.fillStyle = '#b45309';
      ctx.fillText(`hold ${L.target[3].toFixed(1)} s`, x + 22, y - 12);
    }
  }

  private polyline(xy: Float64Array | Float32Array, n: number, colour: string, width: number, from = 0): void {
    if (n - from < 2) return;
    const ctx = this.ctx;
    ctx.beginPath();
    ctx.moveTo(xy[2 * from], xy[2 * from + 1]);
    for (let i = from + 1; i < n; i++) ctx.lineTo(xy[2 * i], xy[2 * i + 1]);
    ctx.strokeStyle = colour;
    ctx.lineWidth = width;
    ctx.stroke();
  }

  /** The fan: rollouts bucketed by score, one path per bucket. */
  private drawFan(px: number): void {
    const { points, offsets, scores, admissible, chosen } = this.scene.fan;
    const n = Math.max(0, offsets.length - 1);
    if (n === 0) return;
    if (this.buckets.length < n) this.buckets = new Uint8Array(n * 2);
    let lo = Infinity;
    let hi = -Infinity;
    for (let i = 0; i < n; i++) {
      if (!admissible[i]) continue;
      const s = scores[i];
      if (s < lo) lo = s;
      if (s > hi) hi = s;
    }
    const span = hi - lo;
    const NONE = FAN_BUCKETS; // inadmissible
    for (let i = 0; i < n; i++) {
      if (!admissible[i] || !Number.isFinite(scores[i])) this.buckets[i] = NONE;
      else this.buckets[i] = span > 0 ? Math.min(FAN_BUCKETS - 1, Math.floor(((scores[i] - lo) / span) * FAN_BUCKETS)) : FAN_BUCKETS - 1;
    }
    const ctx = this.ctx;
    ctx.lineWidth = 1 * px;
    for (const b of BUCKET_ORDER) {
      ctx.beginPath();
      let any = false;
      for (let i = 0; i < n; i++) {
        if (this.buckets[i] !== b) continue;
        const a = offsets[i];
        const e = offsets[i + 1];
        if (e - a < 2) continue;
        ctx.moveTo(points[2 * a], points[2 * a + 1]);
        for (let j = a + 1; j < e; j++) ctx.lineTo(points[2 * j], points[2 * j + 1]);
        any = true;
      }
      if (any) {
        ctx.strokeStyle = b === NONE ? COLORS.inadmissible : BUCKET_COLOURS[b];
        ctx.stroke();
      }
    }
    if (chosen >= 0 && chosen < n) {
      const a = offsets[chosen];
      const e = offsets[chosen + 1];
      if (e - a >= 2) {
        const sub = points.subarray(2 * a, 2 * e);
        this.polyline(sub, e - a, 'rgba(255,255,255,0.9)', 5 * px);
        this.polyline(sub, e - a, COLORS.chosen, 3 * px);
      }
    }
  }

  private drawRobot(px: number): void {
    const ctx = this.ctx;
    const s = this.scene.state;
    const r = this.scene.robot;
    const [x, y, th] = [s[0], s[1], s[2]];
    ctx.save();
    ctx.translate(x, y);
    ctx.rotate(th);
    ctx.beginPath();
    let nose: number;
    if (r.kind === 'circle') {
      ctx.arc(0, 0, r.radius, 0, Math.PI * 2);
      nose = r.radius;
    } else {
      ctx.rect(-r.length / 2, -r.width / 2, r.length, r.width);
      nose = r.length / 2;
    }
    ctx.fillStyle = 'rgba(15, 23, 42, 0.82)';
    ctx.fill();
    ctx.lineWidth = 2 * px;
    ctx.strokeStyle = '#fff';
    ctx.stroke();
    ctx.beginPath();
    ctx.moveTo(0, 0);
    ctx.lineTo(nose, 0);
    ctx.lineWidth = 2.5 * px;
    ctx.strokeStyle = '#fbbf24';
    ctx.stroke();
    ctx.restore();
  }

  private drawKeypoints(): void {
    const kp = this.scene.keypoints;
    const ctx = this.ctx;
    for (let i = 0; i + 1 < kp.length; i += 2) {
      const [x, y] = this.toScreen(kp[i], kp[i + 1]);
      ctx.beginPath();
      ctx.arc(x, y, 5, 0, Math.PI * 2);
      ctx.fillStyle = '#fff';
      ctx.fill();
      ctx.lineWidth = 2.5;
      ctx.strokeStyle = COLORS.keypoint;
      ctx.stroke();
    }
  }

  private arrow(x0: number, y0: number, x1: number, y1: number, colour: string, width: number): void {
    const ctx = this.ctx;
    const dx = x1 - x0;
    const dy = y1 - y0;
    const len = Math.hypot(dx, dy);
    if (len < 2) return;
    const ux = dx / len;
    const uy = dy / len;
    const head = Math.min(9, len * 0.5);
    ctx.beginPath();
    ctx.moveTo(x0, y0);
    ctx.lineTo(x1 - ux * head * 0.6, y1 - uy * head * 0.6);
    ctx.strokeStyle = colour;
    ctx.lineWidth = width;
    ctx.stroke();
    ctx.beginPath();
    ctx.moveTo(x1, y1);
    ctx.lineTo(x1 - ux * head - uy * head * 0.5, y1 - uy * head + ux * head * 0.5);
    ctx.lineTo(x1 - ux * head + uy * head * 0.5, y1 - uy * head - ux * head * 0.5);
    ctx.closePath();
    ctx.fillStyle = colour;
    ctx.fill();
  }

  private drawMovers(): void {
    const m = this.scene.movers;
    const ctx = this.ctx;
    const k = this.k;
    ctx.font = '600 11px system-ui, sans-serif';
    ctx.textAlign = 'center';
    ctx.textBaseline = 'middle';
    for (let i = 0; i + 5 < m.length; i += 6) {
      const id = m[i];
      const [x, y] = this.toScreen(m[i + 2], m[i + 3]);
      const r = m[i + 1] * k;
      const cls = this.scene.classes.get(id);
      const colour = COLORS.classes[cls ?? 3];
      ctx.beginPath();
      ctx.arc(x, y, Math.max(2, r), 0, Math.PI * 2);
      ctx.globalAlpha = 0.78;
      ctx.fillStyle = colour;
      ctx.fill();
      ctx.globalAlpha = 1;
      ctx.lineWidth = 1.5;
      ctx.strokeStyle = '#fff';
      ctx.stroke();
      // Velocity arrow: where the mover will be in 1 s.
      const [ex, ey] = this.toScreen(m[i + 2] + m[i + 4], m[i + 3] + m[i + 5]);
      this.arrow(x, y, ex, ey, '#0f172a', 2);
      // Id and class letter (D dynamic, S static, ★ special) on a halo.
      const label = cls === undefined ? String(id) : `${id} ${['D', 'S', '★'][cls]}`;
      const ly = y - Math.max(2, r) - 8;
      ctx.strokeStyle = 'rgba(255,255,255,0.9)';
      ctx.lineWidth = 3.5;
      ctx.lineJoin = 'round';
      ctx.strokeText(label, x, ly);
      ctx.fillStyle = cls === undefined ? '#334155' : colour;
      ctx.fillText(label, x, ly);
    }
  }

  private marker(x: number, y: number, colour: string, label: string, r = 9): void {
    const ctx = this.ctx;
    ctx.beginPath();
    ctx.arc(x, y, r, 0, Math.PI * 2);
    ctx.fillStyle = colour;
    ctx.fill();
    ctx.lineWidth = 2;
    ctx.strokeStyle = '#fff';
    ctx.stroke();
    ctx.fillStyle = '#fff';
    ctx.font = `700 ${Math.round(r * 1.1)}px system-ui, sans-serif`;
    ctx.textAlign = 'center';
    ctx.textBaseline = 'middle';
    ctx.fillText(label, x, y + 0.5);
  }

  private drawGoals(): void {
    const S = this.scene;
    const ctx = this.ctx;
    const [sx, sy] = this.toScreen(S.start[0], S.start[1]);
    this.marker(sx, sy, COLORS.start, 'S', 7);
    const [gx, gy] = this.toScreen(S.goal[0], S.goal[1]);
    this.marker(gx, gy, COLORS.goal, 'G', 10);
    const [cx, cy] = this.toScreen(S.currentGoal[0], S.currentGoal[1]);
    if (S.goalKind === 'intermediate') {
      ctx.save();
      ctx.translate(cx, cy);
      ctx.rotate(Math.PI / 4);
      ctx.fillStyle = COLORS.subgoal;
      ctx.strokeStyle = '#fff';
      ctx.lineWidth = 2;
      ctx.fillRect(-6, -6, 12, 12);
      ctx.strokeRect(-6, -6, 12, 12);
      ctx.restore();
    } else if (S.goalKind === 'virtual') {
      ctx.beginPath();
      ctx.arc(cx, cy, 9, 0, Math.PI * 2);
      ctx.fillStyle = 'rgba(255,255,255,0.85)';
      ctx.fill();
      ctx.setLineDash([3, 3]);
      ctx.lineWidth = 2.5;
      ctx.strokeStyle = COLORS.virtual;
      ctx.stroke();
      ctx.setLineDash([]);
      ctx.fillStyle = COLORS.virtual;
      ctx.font = '700 10px system-ui, sans-serif';
      ctx.textAlign = 'center';
      ctx.textBaseline = 'middle';
      ctx.fillText('V', cx, cy + 0.5);
    }
  }

  private drawPreview(): void {
    const p = this.scene.preview;
    if (!p) return;
    const ctx = this.ctx;
    const [x, y] = this.toScreen(p.x, p.y);
    ctx.beginPath();
    ctx.arc(x, y, Math.max(2, p.radius * this.k), 0, Math.PI * 2);
    ctx.setLineDash([4, 3]);
    ctx.lineWidth = 2;
    ctx.strokeStyle = '#0f172a';
    ctx.stroke();
    ctx.setLineDash([]);
    const [ex, ey] = this.toScreen(p.x + p.vx, p.y + p.vy);
    this.arrow(x, y, ex, ey, '#4f46e5', 2.5);
    const speed = Math.hypot(p.vx, p.vy);
    ctx.font = '600 12px system-ui, sans-serif';
    ctx.textAlign = 'left';
    ctx.textBaseline = 'bottom';
    const text = `${speed.toFixed(2)} m/s`;
    ctx.strokeStyle = 'rgba(255,255,255,0.92)';
    ctx.lineWidth = 4;
    ctx.lineJoin = 'round';
    ctx.strokeText(text, ex + 6, ey - 4);
    ctx.fillStyle = '#312e81';
    ctx.fillText(text, ex + 6, ey - 4);
  }
}

/** A five-pointed star marker (screen space). */
function star(ctx: CanvasRenderingContext2D, x: number, y: number, r: number, fill: string): void {
  ctx.beginPath();
  for (let i = 0; i < 10; i++) {
    const rr = i % 2 === 0 ? r : r * 0.45;
    const a = -Math.PI / 2 + (i * Math.PI) / 5;
    const [px, py] = [x + rr * Math.cos(a), y + rr * Math.sin(a)];
    if (i === 0) ctx.moveTo(px, py);
    else ctx.lineTo(px, py);
  }
  ctx.closePath();
  ctx.fillStyle = fill;
  ctx.fill();
  ctx.lineWidth = 1.5;
  ctx.strokeStyle = '#fff';
  ctx.stroke();
}
