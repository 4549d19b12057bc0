// Canvas painter of the grid pages, from the core's draw lists: the map
// (and inflation) is drawn into an offscreen canvas (one pixel per cell)
// once per edit, the search into a second one as it plays (only the cells
// the played events touched; search-tint.ts); each frame only scales those
// two images and strokes the line checks, the current cell, the path, key
// points, feature nodes and the start and goal on top, all in world metres
// mapped through the map item's frame, so 512×512 maps pan, zoom and
// animate smoothly. Nothing here plans.

import { knownBox, offscreen, sizeToBox, type Cell } from '../shell/cells';
import type { SearchPlayback } from './search-player';
import type { SamplingPlayback } from './sampling-tree';
import { SEARCH_CSS, SearchTint } from './search-tint';
import { EMPTY, Frame, Layer, mask, type DrawList, type LayerCode } from './draw';
import { labelWeights, weightColor } from './weight-shade';

/** The layers a grid view shows from the map's and the plan's lists. */
export const MAP_LAYERS = mask(Layer.Map, Layer.Inflation, Layer.Goals, Layer.Weights);
export const PLAN_LAYERS = mask(Layer.GlobalPath, Layer.KeyPoints, Layer.FeatureNodes);
const SEARCH_LAYERS = mask(Layer.SearchCells, Layer.SearchLines, Layer.SearchCurrent);

export const COLORS = {
  free: [248, 250, 252],
  occupied: [30, 41, 59],
  unknown: [184, 194, 209],
  inflated: [252, 217, 165],
  path: '#e11d48',
  start: '#16a34a',
  goal: '#2563eb',
  keypoint: '#7c3aed',
  feature: '#f59e0b',
} as const;

interface View {
  /** CSS pixels per cell. */
  scale: number;
  /** CSS-pixel position of the map's top-left corner in the canvas. */
  ox: number;
  oy: number;
}

/** Map frame of a cells item: width, height, resolution, origin x, y. */
type GridFrame = [number, number, number, number, number];

export class MapView {
  readonly canvas: HTMLCanvasElement;
  private ctx: CanvasRenderingContext2D;
  private w = 0;
  private h = 0;
  private grid: GridFrame = [0, 0, 1, 0, 0];
  private base: HTMLCanvasElement | null = null;
  private baseCtx: CanvasRenderingContext2D | null = null;
  private tint: SearchTint | null = null;
  private search: SearchPlayback | null = null;
  /** A sampling planner's tree, painted over the map (cells). */
  private tree: SamplingPlayback | null = null;
  /** The search layers of the last frame (lines, current cell). */
  private searchDraw: DrawList = EMPTY;
  /** Each layer from the draw list that last brought it. */
  private frame = new Frame();
  private cells: Uint8Array | null = null;
  private view: View = { scale: 1, ox: 0, oy: 0 };
  /** The view is the fitted one (no zoom or pan since): refit on resize. */
  private fitted = true;
  private pending = false;
  private cssW = 0;
  private cssH = 0;
  /** Bounding box [c0, r0, c1, r1) of the known (not unknown) cells. */
  private known: [number, number, number, number] = [0, 0, 0, 0];

  constructor(canvas: HTMLCanvasElement) {
    this.canvas = canvas;
    const ctx = canvas.getContext('2d');
    if (!ctx) throw new Error('this browser cannot draw on a 2D canvas');
    this.ctx = ctx;
    new ResizeObserver(() => this.resize()).observe(canvas);
    this.resize();
  }

  get mapWidth(): number {
    return this.w;
  }

  get mapHeight(): number {
    return this.h;
  }

  /** A new map (a draw list with its Map layer, and any of MAP_LAYERS):
   *  rebuild the images and fit it into the view. */
  setMap(d: DrawList): void {
    const i = d.first(Layer.Map);
    if (i >= d.end(Layer.Map)) throw new Error('the draw list has no map');
    const n = d.numbers(i);
    this.grid = [n[0], n[1], n[2], n[3], n[4]];
    [this.w, this.h] = [n[0], n[1]];
    [this.base, this.baseCtx] = offscreen(this.w, this.h);
    this.tint = new SearchTint(this.w, this.h);
    this.search = null;
    this.tree = null;
    this.searchDraw = EMPTY;
    this.frame = new Frame();
    this.show(d, MAP_LAYERS);
    this.known = knownBox(this.w, this.h, this.cells!);
    this.fit();
  }

  /** Shows the layers `layers` of `d` (the map's: MAP_LAYERS, the plan's:
   *  PLAN_LAYERS); the map image is repainted when the map or the
   *  inflation come. */
  show(d: DrawList, layers: number): void {
    this.frame.put(d, layers);
    if (layers & mask(Layer.Map)) {
      const i = d.first(Layer.Map);
      this.cells = i < d.end(Layer.Map) ? d.cellBytes(i) : null;
    }
    if (layers & mask(Layer.Map, Layer.Inflation, Layer.Weights)) this.paintBase();
    this.request();
  }

  /** The search to show (null: none); the path is drawn once it is played out. */
  setSearch(p: SearchPlayback | null): void {
    this.search = p;
    this.searchDraw = EMPTY;
    if (!p) this.tint?.clear();
    this.request();
  }

  /** The sampling run to show (null: none); it paints its own path. */
  setTree(t: SamplingPlayback | null): void {
    this.tree = t;
    this.request();
  }

  /** Paints the played events and draws the frame now (the player's
   *  animation loop calls this inside its own frame); returns the cells
   *  repainted. */
  drawNow(): number {
    let n = 0;
    if (this.search && this.tint) {
      this.searchDraw = this.search.draw(SEARCH_LAYERS);
      n = this.tint.paint(this.searchDraw);
    }
    this.draw();
    return n;
  }

  /**
   * Fits the known part of the map into the canvas with a small margin
   * (ROS maps are mostly unknown space around a small explored area).
   */
  fit(): void {
    if (!this.w || !this.h || !this.cssW || !this.cssH) return;
    const margin = 16;
    const [c0, r0, c1, r1] = this.known;
    const bw = c1 - c0;
    const bh = r1 - r0;
    const scale = Math.max(0.05, Math.min((this.cssW - 2 * margin) / bw, (this.cssH - 2 * margin) / bh));
    this.view = {
      scale,
      ox: (this.cssW - bw * scale) / 2 - c0 * scale,
      oy: (this.cssH - bh * scale) / 2 - r0 * scale,
    };
    this.fitted = true;
    this.publishView();
    this.request();
  }

  /** Zooms by `factor` keeping the canvas point (x, y) fixed. */
  zoomAt(x: number, y: number, factor: number): void {
    const v = this.view;
    const scale = Math.min(96, Math.max(0.05, v.scale * factor));
    const f = scale / v.scale;
    this.view = { scale, ox: x - (x - v.ox) * f, oy: y - (y - v.oy) * f };
    this.fitted = false;
    this.publishView();
    this.request();
  }

  panBy(dx: number, dy: number): void {
    this.view = { ...this.view, ox: this.view.ox + dx, oy: this.view.oy + dy };
    this.fitted = false;
    this.publishView();
    this.request();
  }

  /** The cell under a canvas point (CSS pixels), or null off the map. */
  cellAt(x: number, y: number): Cell | null {
    const c = Math.floor((x - this.view.ox) / this.view.scale);
    const r = Math.floor((y - this.view.oy) / this.view.scale);
    if (c < 0 || r < 0 || c >= this.w || r >= this.h) return null;
    return [c, r];
  }

  /** Which endpoint marker is under the canvas point (x, y), if any
   *  (the marker's disc, at least its cell). */
  markerAt(x: number, y: number, start: Cell | null, goal: Cell | null): 'start' | 'goal' | null {
    const rad = this.markerRadius() + 2;
    for (const [which, cell] of [['goal', goal], ['start', start]] as const) {
      if (!cell) continue;
      const [cx, cy] = this.centre(cell[0], cell[1]);
      if (Math.hypot(x - cx, y - cy) <= Math.max(rad, this.view.scale / 2)) return which;
    }
    return null;
  }

  private markerRadius(): number {
    return Math.min(13, Math.max(6, this.view.scale * 0.6));
  }

  cellKind(c: number, r: number): number | null {
    if (!this.cells || c < 0 || r < 0 || c >= this.w || r >= this.h) return null;
    return this.cells[r * this.w + c];
  }

  /** Exposes the view so tests can click a given cell. */
  private publishView(): void {
    const d = this.canvas.dataset;
    d.scale = String(this.view.scale);
    d.offsetX = String(this.view.ox);
    d.offsetY = String(this.view.oy);
  }

  private resize(): void {
    const [oldW, oldH] = [this.cssW, this.cssH];
    [this.cssW, this.cssH] = sizeToBox(this.canvas);
    if (this.fitted) {
      this.fit();
    } else {
      // Keep what is in the middle of the view in the middle.
      this.view = {
        ...this.view,
        ox: this.view.ox + (this.cssW - oldW) / 2,
        oy: this.view.oy + (this.cssH - oldH) / 2,
      };
      this.publishView();
    }
    this.request();
  }

  private paintBase(): void {
    if (!this.baseCtx || !this.cells) return;
    const img = this.baseCtx.createImageData(this.w, this.h);
    const px = img.data;
    const cells = this.cells;
    const inf = this.frame.of(Layer.Inflation);
    const ii = inf.first(Layer.Inflation);
    const infl = ii < inf.end(Layer.Inflation) ? inf.cellBytes(ii) : null;
    const palette = [COLORS.free, COLORS.occupied, COLORS.unknown];
    const weights = this.weights();
    for (let i = 0; i < cells.length; i++) {
      let col: readonly number[] = infl && infl[i] ? COLORS.inflated : palette[cells[i]] ?? COLORS.unknown;
      if (weights && cells[i] === 0 && !(infl && infl[i])) col = weightColor(col, weights[i]);
      const o = i * 4;
      px[o] = col[0];
      px[o + 1] = col[1];
      px[o + 2] = col[2];
      px[o + 3] = 255;
    }
    this.baseCtx.putImageData(img, 0, 0);
  }

  /** The map's traversal weights (Weights layer), or null on a unit map. */
  private weights(): Uint8Array | null {
    const d = this.frame.of(Layer.Weights);
    const i = d.first(Layer.Weights);
    return i < d.end(Layer.Weights) ? d.cellBytes(i) : null;
  }

  request(): void {
    if (this.pending) return;
    this.pending = true;
    requestAnimationFrame(() => {
      this.pending = false;
      this.drawNow();
    });
  }

  /** Canvas (CSS px) centre of a cell. */
  private centre(c: number, r: number): [number, number] {
    return [this.view.ox + (c + 0.5) * this.view.scale, this.view.oy + (r + 0.5) * this.view.scale];
  }

  /** Canvas (CSS px) point of a world point (m) in the map's frame. */
  private toScreen(x: number, y: number): [number, number] {
    const [, h, res, fx, fy] = this.grid;
    const { scale, ox, oy } = this.view;
    return [ox + ((x - fx) / res) * scale, oy + (h - (y - fy) / res) * scale];
  }

  /** The map's frame: width, height, resolution, origin x, y. */
  get mapFrame(): GridFrame {
    return this.grid;
  }

  /** The points of the first item of layer `l` shown (x, y flat, m), or
   *  null. */
  pointsOf(l: LayerCode): Float64Array | null {
    const d = this.frame.of(l);
    const i = d.first(l);
    return i < d.end(l) ? d.numbers(i) : null;
  }

  private polyline(xy: Float64Array, color: string, width: number, dash: number[] = []): void {
    if (xy.length < 4) return;
    const ctx = this.ctx;
    ctx.beginPath();
    for (let k = 0; k < xy.length; k += 2) {
      const [x, y] = this.toScreen(xy[k], xy[k + 1]);
      if (k === 0) ctx.moveTo(x, y);
      else ctx.lineTo(x, y);
    }
    ctx.setLineDash(dash);
    ctx.strokeStyle = color;
    ctx.lineWidth = width;
    ctx.lineJoin = 'round';
    ctx.lineCap = 'round';
    ctx.stroke();
    ctx.setLineDash([]);
  }

  private draw(): void {
    const ctx = this.ctx;
    const dpr = window.devicePixelRatio || 1;
    ctx.setTransform(1, 0, 0, 1, 0, 0);
    ctx.clearRect(0, 0, this.canvas.width, this.canvas.height);
    if (!this.base || !this.tint) return;
    ctx.setTransform(dpr, 0, 0, dpr, 0, 0);
    const { scale, ox, oy } = this.view;
    ctx.imageSmoothingEnabled = false;
    // Soft drop shadow under the map sheet.
    ctx.save();
    ctx.shadowColor = 'rgba(15, 23, 42, 0.25)';
    ctx.shadowBlur = 12;
    ctx.fillStyle = '#fff';
    ctx.fillRect(ox, oy, this.w * scale, this.h * scale);
    ctx.restore();
    ctx.drawImage(this.base, ox, oy, this.w * scale, this.h * scale);
    ctx.drawImage(this.tint.canvas, ox, oy, this.w * scale, this.h * scale);

    if (scale >= 9) this.gridLines();
    const weights = this.weights();
    if (weights) labelWeights(ctx, weights, this.w, this.h, this.view, [this.cssW, this.cssH]);

    const lw = Math.min(7, Math.max(2.5, scale * 0.4));
    const path = this.pointsOf(Layer.GlobalPath);
    const keyPoints = this.pointsOf(Layer.KeyPoints);
    const features = this.pointsOf(Layer.FeatureNodes);
    // Simplified polylines go under the path: where they leave it (the
    // shortcuts) they show; markers are drawn on top afterwards.
    const thin = Math.max(1.5, lw * 0.5);
    if (features) this.polyline(features, COLORS.feature, thin, [6, 4]);
    if (keyPoints) this.polyline(keyPoints, COLORS.keypoint, thin, [4, 4]);
    const playing = this.search !== null && !this.search.done;
    if (playing) this.searchOverlay();
    if (this.tree) this.tree.paint(ctx, (x, y) => [ox + x * scale, oy + y * scale], scale);
    const pathDrawn = String(this.tree ? this.tree.pathNow() !== null : path !== null && !playing);
    if (this.canvas.dataset.pathDrawn !== pathDrawn) this.canvas.dataset.pathDrawn = pathDrawn;
    if (path && !playing) {
      // White casing keeps the path readable over dark walls and tints.
      this.polyline(path, 'rgba(255,255,255,0.85)', lw + 2.5);
      this.polyline(path, COLORS.path, lw);
    }
    if (features && features.length >= 4) {
      const s = Math.min(11, Math.max(7, scale * 0.6));
      for (let k = 0; k < features.length; k += 2) {
        const [x, y] = this.toScreen(features[k], features[k + 1]);
        ctx.save();
        ctx.translate(x, y);
        ctx.rotate(Math.PI / 4);
        ctx.fillStyle = COLORS.feature;
        ctx.strokeStyle = '#fff';
        ctx.lineWidth = 1.5;
        ctx.fillRect(-s / 2, -s / 2, s, s);
        ctx.strokeRect(-s / 2, -s / 2, s, s);
        ctx.restore();
      }
    }
    if (keyPoints && keyPoints.length >= 4) {
      const rad = Math.min(9, Math.max(5, scale * 0.55));
      for (let k = 0; k < keyPoints.length; k += 2) {
        const [x, y] = this.toScreen(keyPoints[k], keyPoints[k + 1]);
        ctx.beginPath();
        ctx.arc(x, y, rad, 0, Math.PI * 2);
        ctx.fillStyle = '#fff';
        ctx.fill();
        ctx.lineWidth = 2.5;
        ctx.strokeStyle = COLORS.keypoint;
        ctx.stroke();
      }
    }
    const goals = this.frame.of(Layer.Goals);
    for (let i = goals.first(Layer.Goals); i < goals.end(Layer.Goals); i++) {
      const [x, y] = this.toScreen(goals.data[goals.start(i)], goals.data[goals.start(i) + 1]);
      const start = goals.tag(i) === 0;
      this.marker(x, y, start ? COLORS.start : COLORS.goal, start ? 'S' : 'G');
    }
  }

  /** Line checks of the last events (blocked ones red) and the cell being
   *  expanded, while the search plays. */
  private searchOverlay(): void {
    const ctx = this.ctx;
    const d = this.searchDraw;
    ctx.lineWidth = Math.min(3, Math.max(1, this.view.scale * 0.15));
    for (let i = d.first(Layer.SearchLines); i < d.end(Layer.SearchLines); i++) {
      const s = d.numbers(i);
      ctx.beginPath();
      for (let j = 0; j + 3 < s.length; j += 4) {
        ctx.moveTo(...this.toScreen(s[j], s[j + 1]));
        ctx.lineTo(...this.toScreen(s[j + 2], s[j + 3]));
      }
      ctx.strokeStyle = d.tag(i) ? SEARCH_CSS.lineClear : SEARCH_CSS.lineBlocked;
      ctx.stroke();
    }
    const c = d.first(Layer.SearchCurrent);
    if (c < d.end(Layer.SearchCurrent)) {
      const [x, y] = this.toScreen(d.data[d.start(c)], d.data[d.start(c) + 1]);
      const s = Math.max(7, this.view.scale);
      ctx.fillStyle = SEARCH_CSS.current;
      ctx.fillRect(x - s / 2, y - s / 2, s, s);
    }
  }

  private gridLines(): void {
    const ctx = this.ctx;
    const { scale, ox, oy } = this.view;
    const c0 = Math.max(0, Math.floor(-ox / scale));
    const c1 = Math.min(this.w, Math.ceil((this.cssW - ox) / scale));
    const r0 = Math.max(0, Math.floor(-oy / scale));
    const r1 = Math.min(this.h, Math.ceil((this.cssH - oy) / scale));
    ctx.beginPath();
    for (let c = c0; c <= c1; c++) {
      const x = Math.round(ox + c * scale) + 0.5;
      ctx.moveTo(x, oy + r0 * scale);
      ctx.lineTo(x, oy + r1 * scale);
    }
    for (let r = r0; r <= r1; r++) {
      const y = Math.round(oy + r * scale) + 0.5;
      ctx.moveTo(ox + c0 * scale, y);
      ctx.lineTo(ox + c1 * scale, y);
    }
    ctx.strokeStyle = 'rgba(100, 116, 139, 0.18)';
    ctx.lineWidth = 1;
    ctx.stroke();
  }

  private marker(x: number, y: number, color: string, label: string): void {
    const ctx = this.ctx;
    const rad = this.markerRadius();
    ctx.beginPath();
    ctx.arc(x, y, rad, 0, Math.PI * 2);
    ctx.fillStyle = color;
    ctx.fill();
    ctx.lineWidth = 2;
    ctx.strokeStyle = '#fff';
    ctx.stroke();
    if (rad >= 8) {
      ctx.fillStyle = '#fff';
      ctx.font = `700 ${Math.round(rad * 1.1)}px system-ui, sans-serif`;
      ctx.textAlign = 'center';
      ctx.textBaseline = 'middle';
      ctx.fillText(label, x, y + 0.5);
    }
  }
}
