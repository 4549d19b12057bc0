// How the APF page paints the core's draw list of a run: the force field
// as a heat map with arrows, obstacles with their repulsion ranges, the
// predicted obstacles with their virtual ranges, the path, the sampled
// directions with the chosen one bold, start and goal. Every number comes
// from the list; this only maps metres to canvas pixels and picks colours.

import { Layer, type DrawList } from '../scene/draw';

/** World → canvas transform for a drawing extent (x0, y0, x1, y1), m. */
export function fitFrame(canvas: HTMLCanvasElement, bounds: ArrayLike<number>) {
  const [x0, y0, x1, y1] = [bounds[0], bounds[1], bounds[2], bounds[3]];
  const s = Math.min(canvas.width / (x1 - x0), canvas.height / (y1 - y0));
  const ox = (canvas.width - s * (x1 - x0)) / 2;
  const oy = (canvas.height - s * (y1 - y0)) / 2;
  return {
    s,
    x: (x: number) => ox + (x - x0) * s,
    y: (y: number) => canvas.height - oy - (y - y0) * s,
    inv: (px: number, py: number): [number, number] => [x0 + (px - ox) / s, y0 + (canvas.height - oy - py) / s],
  };
}
type Fit = ReturnType<typeof fitFrame>;

function disc(ctx: CanvasRenderingContext2D, f: Fit, x: number, y: number, rPx: number): void {
  ctx.beginPath();
  ctx.arc(f.x(x), f.y(y), rPx, 0, 2 * Math.PI);
}

/** The heat map of |F| and an arrow on every 4th lattice point. */
function field(ctx: CanvasRenderingContext2D, f: Fit, d: DrawList): void {
  const i0 = d.first(Layer.Field);
  if (i0 >= d.end(Layer.Field)) return;
  const [nx, ny] = [d.tag(i0), d.value(i0)];
  const v = d.numbers(i0);
  if (nx < 1 || ny < 1 || v.length < 8) return;
  // Lattice spacing from the first cell centres (m).
  const cw = nx > 1 ? v[4] - v[0] : 2 * Math.abs(v[0]);
  const ch = ny > 1 ? v[4 * nx + 1] - v[1] : cw;
  const mix = (c: number, bg: number) => Math.round(0.55 * c + 0.45 * bg);
  for (let k = 0; k < v.length; k += 4) {
    const m = Math.hypot(v[k + 2], v[k + 3]);
    const t = Math.max(0, Math.min(1, Math.log10(1 + m) / 2));
    // Opaque (pre-blended over the background) so cell seams do not show.
    ctx.fillStyle = `rgb(${mix(40 + 215 * t, 11)}, ${mix(60 + 60 * t, 16)}, ${mix(140 - 100 * t, 32)})`;
    ctx.fillRect(f.x(v[k] - cw / 2), f.y(v[k + 1] + ch / 2), cw * f.s + 1, ch * f.s + 1);
  }
  ctx.strokeStyle = 'rgba(226, 232, 240, 0.55)';
  ctx.lineWidth = 1;
  const len = 0.8 * Math.min(cw, ch) * f.s * 2;
  for (let j = 2; j < ny; j += 4) {
    for (let i = 2; i < nx; i += 4) {
      const k = 4 * (j * nx + i);
      const m = Math.hypot(v[k + 2], v[k + 3]);
      if (!(m > 0)) continue;
      const [cx, cy] = [f.x(v[k]), f.y(v[k + 1])];
      const dx = (v[k + 2] / m) * len;
      const dy = (-v[k + 3] / m) * len;
      ctx.beginPath();
      ctx.moveTo(cx, cy);
      ctx.lineTo(cx + dx, cy + dy);
      ctx.lineTo(cx + dx * 0.7 - dy * 0.2, cy + dy * 0.7 + dx * 0.2);
      ctx.stroke();
    }
  }
}

/** Paints `d` (the layers it holds) on `canvas`, whose extent is `bounds`. */
export function paintApf(canvas: HTMLCanvasElement, bounds: ArrayLike<number>, d: DrawList): void {
  const ctx = canvas.getContext('2d');
  if (!ctx) return;
  const f = fitFrame(canvas, bounds);
  ctx.fillStyle = '#0b1020';
  ctx.fillRect(0, 0, canvas.width, canvas.height);
  field(ctx, f, d);
  // Obstacles and their repulsion ranges.
  for (let i = d.first(Layer.Obstacles); i < d.end(Layer.Obstacles); i++) {
    const [x, y, r] = d.numbers(i);
    ctx.setLineDash([4, 4]);
    ctx.strokeStyle = '#60a5fa';
    disc(ctx, f, x, y, d.value(i) * f.s);
    ctx.stroke();
    ctx.setLineDash([]);
    ctx.fillStyle = '#94a3b8';
    disc(ctx, f, x, y, Math.max(2, r * f.s));
    ctx.fill();
  }
  for (let i = d.first(Layer.Predicted); i < d.end(Layer.Predicted); i++) {
    const [x, y, range] = d.numbers(i);
    ctx.setLineDash([2, 3]);
    ctx.strokeStyle = d.tag(i) === 1 ? '#a78bfa' : '#f472b6';
    disc(ctx, f, x, y, range * f.s);
    ctx.stroke();
    ctx.setLineDash([]);
    ctx.fillStyle = ctx.strokeStyle;
    disc(ctx, f, x, y, 3);
    ctx.fill();
  }
  // Path.
  const t = d.first(Layer.Trail);
  const path = t < d.end(Layer.Trail) ? d.numbers(t) : new Float64Array(0);
  ctx.strokeStyle = '#fbbf24';
  ctx.lineWidth = 2;
  ctx.beginPath();
  for (let i = 0; i < path.length; i += 2) {
    if (i === 0) ctx.moveTo(f.x(path[i]), f.y(path[i + 1]));
    else ctx.lineTo(f.x(path[i]), f.y(path[i + 1]));
  }
  ctx.stroke();
  ctx.fillStyle = '#fbbf24';
  for (let i = 0; i < path.length; i += 2) {
    disc(ctx, f, path[i], path[i + 1], 2);
    ctx.fill();
  }
  // Sampled directions from the point stepped from, the chosen one bold.
  for (let i = d.first(Layer.Candidates); i < d.end(Layer.Candidates); i++) {
    const [bx, by, x, y] = d.numbers(i);
    const best = d.tag(i) === 1;
    ctx.strokeStyle = best ? '#22c55e' : 'rgba(148, 163, 184, 0.8)';
    ctx.lineWidth = best ? 3 : 1;
    ctx.beginPath();
    ctx.moveTo(f.x(bx), f.y(by));
    ctx.lineTo(f.x(x), f.y(y));
    ctx.stroke();
  }
  ctx.lineWidth = 1;
  for (let i = d.first(Layer.Goals); i < d.end(Layer.Goals); i++) {
    const [x, y] = d.numbers(i);
    const start = d.tag(i) === 0;
    ctx.fillStyle = start ? '#38bdf8' : '#ef4444';
    disc(ctx, f, x, y, start ? 6 : 7);
    ctx.fill();
  }
}
