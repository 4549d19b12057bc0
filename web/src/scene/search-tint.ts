// The search layer of a grid view: one pixel per cell in an offscreen
// canvas, coloured by the cell states of the core's SearchCells layer.
// After the first frame that layer holds only the cells the played events
// touched, so each frame repaints and uploads only their bounding box:
// animating a 512 × 512 search costs the events played, not the map.

import { offscreen } from '../shell/cells';
import { Layer, Shape, type DrawList } from './draw';

/** Open (green-400) and closed (sky-300) as RGBA, by state byte; see the
 *  legend. */
export const SEARCH_RGBA: Record<number, [number, number, number, number]> = {
  1: [74, 222, 128, 190],
  2: [125, 180, 252, 150],
};

/** CSS colours of the search overlay (legend, markers, lines). */
export const SEARCH_CSS = {
  open: 'rgb(74, 222, 128)',
  closed: 'rgb(125, 180, 252)',
  current: '#f97316',
  lineClear: 'rgba(124, 58, 237, 0.75)',
  lineBlocked: 'rgba(220, 38, 38, 0.7)',
} as const;

export class SearchTint {
  readonly canvas: HTMLCanvasElement;
  private ctx: CanvasRenderingContext2D;
  private img: ImageData;
  private w: number;
  private h: number;

  constructor(w: number, h: number) {
    this.w = w;
    this.h = h;
    [this.canvas, this.ctx] = offscreen(w, h);
    this.img = this.ctx.createImageData(w, h);
  }

  private set(k: number, s: number): void {
    const px = this.img.data;
    const o = k * 4;
    const c = SEARCH_RGBA[s];
    if (!c) {
      px[o + 3] = 0;
      return;
    }
    px[o] = c[0];
    px[o + 1] = c[1];
    px[o + 2] = c[2];
    px[o + 3] = c[3];
  }

  /** Paints the SearchCells items of `d`; returns the cells painted. */
  paint(d: DrawList): number {
    let n = 0;
    for (let i = d.first(Layer.SearchCells); i < d.end(Layer.SearchCells); i++) {
      const bytes = d.cellBytes(i);
      if (d.shape(i) === Shape.Cells) {
        for (let k = 0; k < this.w * this.h; k++) this.set(k, bytes[k]);
        this.ctx.putImageData(this.img, 0, 0);
        n += bytes.length;
        continue;
      }
      if (!bytes.length) continue;
      const idx = d.numbers(i);
      let [c0, r0, c1, r1] = [this.w, this.h, -1, -1];
      for (let j = 0; j < bytes.length; j++) {
        const k = idx[6 + j];
        this.set(k, bytes[j]);
        const c = k % this.w;
        const r = (k - c) / this.w;
        if (c < c0) c0 = c;
        if (c > c1) c1 = c;
        if (r < r0) r0 = r;
        if (r > r1) r1 = r;
      }
      // Only the touched box crosses to the canvas.
      this.ctx.putImageData(this.img, 0, 0, c0, r0, c1 - c0 + 1, r1 - r0 + 1);
      n += bytes.length;
    }
    return n;
  }

  /** Clears the image (no search shown). */
  clear(): void {
    this.img.data.fill(0);
    this.ctx.putImageData(this.img, 0, 0);
  }
}
