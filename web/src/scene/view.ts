// Canvas view of a robot scene (robot page, its timeline, the compare
// page's lanes): the map is one offscreen image (a pixel per cell) scaled
// into view; the core's draw list (scene/draw.ts) is painted in world
// metres under one canvas transform (paint.ts), so its typed arrays go
// straight into lineTo without per-point JS arithmetic. Nothing here plans,
// collides or measures: it paints what the wasm SimHandle reports.

import { DrawList, Frame, Layer } from './draw';
import { Painter, lidarLayers } from './paint';
import { knownBox as knownCells, offscreen, sizeToBox } from '../shell/cells';
import { COSTMAP_RGBA } from './costmap';

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

/** Obstacle classes as the core numbers them. */
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

/** Edge colours by type code (1 SR … 4 WF); the legend uses the same. */
export const EDGE_COLOURS: Record<number, string> = {
  1: '#dc2626',
  2: '#f97316',
  3: '#2563eb',
  4: '#06b6d4',
};

/** What one frame shows; the page fills it from the SimHandle (pull.ts). */
export interface Scene {
  /** The core's draw list of this frame, layer by layer. */
  frame: Frame;
  /** The robot: x, y, theta, v, vy, w (the status line reads it). */
  state: Float64Array;
  /** Trail x,y pairs (grown from the Trail layer); only the first
   *  `trailLen` points are used. */
  trail: Float64Array;
  trailLen: number;
  /** Seen count of the fog the frame holds (-1: none fetched yet). */
  seenCount: number;
  /** The mover being placed by a drag: centre, velocity, radius. */
  preview: { x: number; y: number; vx: number; vy: number; radius: number } | null;
  /** Layer toggles; `classes` colours movers by class and `subgoal` marks
   *  the goal steered to (the overlay view shows neither); `costmap` paints
   *  the perceived map's costs when the frame holds them (BARN page). */
  show: { fan: boolean; path: boolean; trail: boolean; lidar: boolean; fog: boolean; classes: boolean; subgoal: boolean; costmap: boolean };
}

export function emptyScene(): Scene {
  return {
    frame: new Frame(),
    state: new Float64Array(6),
    trail: new Float64Array(0),
    trailLen: 0,
    seenCount: -1,
    preview: null,
    show: { fan: true, path: true, trail: true, lidar: true, fog: false, classes: true, subgoal: true, costmap: false },
  };
}

/** The map a draw list's Map layer holds (null without one). */
export function mapOf(d: DrawList): MapInfo | null {
  const i = d.first(Layer.Map);
  if (i >= d.end(Layer.Map)) return null;
  const [width, height, resolution, originX, originY] = d.numbers(i);
  return { width, height, resolution, originX, originY, cells: d.cellBytes(i) };
}

/** Known-cell bounding box [c0, r0, c1, r1) of the map padded by a few
 *  cells: the canvas view and the SVG export frame the same part of it. */
export function knownBox(m: MapInfo): [number, number, number, number] {
  return knownCells(m.width, m.height, m.cells);
}

export class RobotView {
  readonly canvas: HTMLCanvasElement;
  private ctx: CanvasRenderingContext2D;
  private map: MapInfo | null = null;
  private base: HTMLCanvasElement | null = null;
  /** Fog overlay (unseen cells shaded) and the seen count it was built for. */
  private fog: HTMLCanvasElement | null = null;
  private fogCount = -1;
  /** Costmap image and the draw list it was built from. */
  private costmap: HTMLCanvasElement | null = null;
  private costmapOf: DrawList | null = null;
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
    const [oldW, oldH] = [this.cssW, this.cssH];
    [this.cssW, this.cssH] = sizeToBox(this.canvas);
    if (this.fitted) this.fit();
    else {
      // Keep what is in the middle of the view in the middle.
      this.ox += (this.cssW - oldW) / 2;
      this.oy += (this.cssH - oldH) / 2;
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
    const seen = S.frame.of(Layer.Seen);
    const fogged = S.show.fog && seen.count(Layer.Seen) > 0;
    if (fogged) {
      const fog = this.fogImage(seen);
      if (fog) ctx.drawImage(fog, this.ox, this.oy, w, h);
    }
    this.canvas.dataset.fog = fogged ? 'on' : 'off';
    this.canvas.dataset.costmap = S.show.costmap && this.paintCostmap(S.frame.of(Layer.Costmap)) ? 'on' : 'off';

    // World-space layers: widths in metres = CSS px / k.
    this.worldTransform();
    const p = new Painter(ctx, S, 1 / this.k, (x, y) => this.toScreen(x, y));
    ctx.lineJoin = 'round';
    ctx.lineCap = 'round';
    if (S.show.path) p.globalPath();
    if (S.show.trail && S.trailLen >= 2) p.polyline(S.trail, 0, S.trailLen, COLORS.trail, 2.5);
    if (S.show.fan) p.fan();
    const lidarOn = S.show.lidar && S.frame.hasRays();
    if (lidarOn) p.lidar();
    // The start marker under the robot, which stands on it at t = 0.
    this.screenTransform();
    p.startMarker();
    this.worldTransform();
    p.robot();

    // Screen-space layers: markers and labels stay readable at any zoom.
    this.screenTransform();
    if (lidarOn) p.lidarMarkers();
    this.canvas.dataset.lidarLayers = lidarOn ? lidarLayers(S.frame) : '';
    if (S.show.path) p.keypoints();
    p.movers(this.k);
    p.goals();
    p.preview(this.k);
    this.overlay?.(ctx);
  }

  /** Paints the Costmap layer of `d` (its own frame: the perceived map's)
   *  over the map; false without one. The image is rebuilt only for a new
   *  draw list. */
  private paintCostmap(d: DrawList): boolean {
    const i = d.first(Layer.Costmap);
    if (i >= d.end(Layer.Costmap)) return false;
    const [w, h, res, x0, y0] = d.numbers(i);
    if (this.costmapOf !== d || !this.costmap) {
      const costs = d.cellBytes(i);
      const [c, ctx] = offscreen(w, h);
      const img = ctx.createImageData(w, h);
      const px = img.data;
      for (let k = 0; k < costs.length; k++) px.set(COSTMAP_RGBA.subarray(costs[k] * 4, costs[k] * 4 + 4), k * 4);
      ctx.putImageData(img, 0, 0);
      this.costmap = c;
      this.costmapOf = d;
    }
    const [sx, sy] = this.toScreen(x0, y0 + h * res);
    this.ctx.drawImage(this.costmap, sx, sy, w * res * this.k, h * res * this.k);
    return true;
  }

  /** The fog overlay: unseen cells shaded (rebuilt when the count changes). */
  private fogImage(d: DrawList): HTMLCanvasElement | null {
    const i = d.first(Layer.Seen);
    const count = d.value(i);
    const seen = d.cellBytes(i);
    if (!this.map || seen.length !== this.map.width * this.map.height) return null;
    if (this.fog && this.fogCount === count) return this.fog;
    const [c, ctx] = offscreen(this.map.width, this.map.height);
    const img = ctx.createImageData(this.map.width, this.map.height);
    const px = img.data;
    for (let i = 0; i < seen.length; i++) {
      const o = i * 4;
      // Unseen: a cool grey, lighter than the walls so they stay apart.
      px[o] = 148;
      px[o + 1] = 163;
      px[o + 2] = 184;
      px[o + 3] = seen[i] ? 0 : 230;
    }
    ctx.putImageData(img, 0, 0);
    this.fog = c;
    this.fogCount = count;
    return c;
  }
}
