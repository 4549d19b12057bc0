// Helpers of the map canvases (grid page, robot and compare views): an
// offscreen canvas for a map image (a pixel per cell) and the box of the
// known cells that a view fits to.

/** An offscreen canvas of `w` × `h` pixels and its 2D context. */
export function offscreen(w: number, h: number): [HTMLCanvasElement, CanvasRenderingContext2D] {
  const c = document.createElement('canvas');
  c.width = w;
  c.height = h;
  const ctx = c.getContext('2d');
  if (!ctx) throw new Error('this browser cannot draw on a 2D canvas');
  return [c, ctx];
}

/** Known-cell bounding box [c0, r0, c1, r1) of a `w` × `h` map (cells
 *  row-major, 2 = unknown) padded by a few cells; the whole map when every
 *  cell is unknown (ROS maps are mostly unknown around the explored area). */
export function knownBox(w: number, h: number, cells: Uint8Array): [number, number, number, number] {
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

/** Sizes `canvas`'s backing store to its CSS box at the device pixel
 *  ratio; returns the CSS width and height. */
export function sizeToBox(canvas: HTMLCanvasElement): [number, number] {
  const rect = canvas.getBoundingClientRect();
  const dpr = window.devicePixelRatio || 1;
  canvas.width = Math.max(1, Math.round(rect.width * dpr));
  canvas.height = Math.max(1, Math.round(rect.height * dpr));
  return [rect.width, rect.height];
}

/** A grid cell as `[col, row]` (row 0 at the top). */
export type Cell = [number, number];
