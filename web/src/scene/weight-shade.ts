// Weighted cells on the grid page (docs/algorithms.md §weights): the
// core's Weights layer (one byte per cell, 1 ordinary … 9) shades free
// cells towards amber in proportion to their weight and, once cells are
// large enough on screen, prints the weight in each one. Painting only:
// the weights and every cost come from the core.

/** Colour of a free cell of weight `w` (1–9): the free colour for 1,
 *  deeper amber as the weight grows. */
export function weightColor(free: readonly number[], w: number): readonly number[] {
  if (w <= 1) return free;
  const heavy = [217, 119, 6];
  const t = 0.18 + (0.82 * (Math.min(w, 9) - 2)) / 7;
  return free.map((f, k) => Math.round(f + (heavy[k] - f) * t));
}

/** Washes each visible weighted cell in amber over the search tint (so a
 *  band stays visible while a search plays over it) and prints its weight
 *  at its centre when a cell is at least 9 CSS px wide (smaller, the
 *  digits would only be noise). */
export function labelWeights(
  ctx: CanvasRenderingContext2D,
  weights: Uint8Array,
  w: number,
  h: number,
  view: { scale: number; ox: number; oy: number },
  css: [number, number],
): void {
  const { scale, ox, oy } = view;
  if (scale < 2) return;
  const c0 = Math.max(0, Math.floor(-ox / scale));
  const r0 = Math.max(0, Math.floor(-oy / scale));
  const c1 = Math.min(w, Math.ceil((css[0] - ox) / scale));
  const r1 = Math.min(h, Math.ceil((css[1] - oy) / scale));
  ctx.save();
  ctx.font = `700 ${Math.round(Math.min(22, Math.max(8, scale * 0.62)))}px system-ui, sans-serif`;
  ctx.textAlign = 'center';
  ctx.textBaseline = 'middle';
  for (let r = r0; r < r1; r++) {
    for (let c = c0; c < c1; c++) {
      const v = weights[r * w + c];
      if (v <= 1) continue;
      ctx.fillStyle = `rgba(217, 119, 6, ${(0.2 + (0.45 * (v - 2)) / 7).toFixed(3)})`;
      ctx.fillRect(ox + c * scale, oy + r * scale, scale, scale);
      if (scale < 9) continue;
      ctx.fillStyle = v >= 6 ? '#fff7ed' : '#78350f';
      ctx.fillText(String(v), ox + (c + 0.5) * scale, oy + (r + 0.5) * scale + 0.5);
    }
  }
  ctx.restore();
}
