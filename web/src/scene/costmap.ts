// Colours of the costmap_2d costs the core's Costmap layer holds (0 free,
// 1–252 the inflation's decay, 253 inscribed, 254 a laser mark, 255 never
// seen), as one RGBA table so the view's image and the page's legend agree.

/** costmap_2d's named costs. */
export const COST = { free: 0, inscribed: 253, lethal: 254, unknown: 255 } as const;

/** Legend swatches: what each band of costs looks like. */
export const COSTMAP_SWATCHES = {
  decayLow: 'rgb(237, 233, 254)',
  decayHigh: 'rgb(124, 58, 237)',
  inscribed: 'rgb(190, 18, 60)',
  lethal: 'rgb(15, 23, 42)',
  unknown: 'rgb(148, 163, 184)',
} as const;

/** RGBA per cost, 256 × 4 bytes: free clear (the map shows through), the
 *  decay from pale to deep violet (apart from the laser's orange rays),
 *  inscribed rose, laser marks near black, never-seen space a grey veil. */
export const COSTMAP_RGBA: Uint8ClampedArray = (() => {
  const t = new Uint8ClampedArray(256 * 4);
  const set = (c: number, r: number, g: number, b: number, a: number) => t.set([r, g, b, a], c * 4);
  set(COST.free, 0, 0, 0, 0);
  for (let c = 1; c < COST.inscribed; c++) {
    const f = (c - 1) / (COST.inscribed - 2);
    set(c, 237 - 113 * f, 233 - 175 * f, 254 - 17 * f, 120 + 100 * f);
  }
  set(COST.inscribed, 190, 18, 60, 235);
  set(COST.lethal, 15, 23, 42, 255);
  set(COST.unknown, 148, 163, 184, 150);
  return t;
})();
