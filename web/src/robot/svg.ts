// A vector export of the robot page's scene: the map as merged rectangles
// (one path per cell kind), the global path, the trail, the movers with
// their velocity, start, goal and the robot's footprint with its heading.
// Coordinates are world metres (y up) under one flipping transform, so the
// file measures in metres like the scenario; nothing is rasterised.

import { COLORS, knownBox, type MapInfo, type Scene } from '../scene/view';
import { Layer, Shape } from '../scene/draw';

const rgb = (c: readonly number[]) => `rgb(${c[0]},${c[1]},${c[2]})`;

/** Shortest decimal that is exact to 0.1 mm (keeps files small). */
function n(x: number): string {
  const r = Math.round(x * 1e4) / 1e4;
  return Object.is(r, -0) ? '0' : String(r);
}

function esc(s: string): string {
  return s.replace(/[&<>"]/g, (c) => ({ '&': '&amp;', '<': '&lt;', '>': '&gt;', '"': '&quot;' })[c] ?? c);
}

/**
 * Rectangles [c0, r0, c1, r1) (cells, r0 the top row) covering every cell of
 * `kind`: runs along each row, and a run continues the rectangle above it
 * when it spans the same columns (so walls and rooms become a few rects).
 */
export function mergeCells(m: MapInfo, kind: number): [number, number, number, number][] {
  const { width: w, height: h, cells } = m;
  const done: [number, number, number, number][] = [];
  /** Open rectangles by "c0,c1" of their run. */
  let open = new Map<string, [number, number, number, number]>();
  for (let r = 0; r < h; r++) {
    const next = new Map<string, [number, number, number, number]>();
    let c = 0;
    while (c < w) {
      if (cells[r * w + c] !== kind) {
        c++;
        continue;
      }
      const c0 = c;
      while (c < w && cells[r * w + c] === kind) c++;
      const key = `${c0},${c}`;
      const above = open.get(key);
      if (above) {
        above[3] = r + 1;
        open.delete(key);
        next.set(key, above);
      } else next.set(key, [c0, r, c, r + 1]);
    }
    for (const rect of open.values()) done.push(rect);
    open = next;
  }
  for (const rect of open.values()) done.push(rect);
  return done;
}

function polyline(xy: ArrayLike<number>, count: number): string {
  const pts: string[] = [];
  for (let i = 0; i < count; i++) pts.push(`${n(xy[2 * i])},${n(xy[2 * i + 1])}`);
  return pts.join(' ');
}

/** The scene as a standalone SVG document; `title` goes into <title>,
 *  the episode time `time` (s) into <desc>. */
export function sceneSvg(m: MapInfo, S: Scene, title: string, time: number): string {
  const res = m.resolution;
  const [c0, r0, c1, r1] = knownBox(m);
  // World extent of the exported box (y up: the top row has the largest y).
  const x0 = m.originX + c0 * res;
  const x1 = m.originX + c1 * res;
  const yTop = m.originY + (m.height - r0) * res;
  const yBot = m.originY + (m.height - r1) * res;
  const [vw, vh] = [x1 - x0, yTop - yBot];
  const px = Math.max(vw, vh) / 800; // one "screen pixel" at 800 px
  const scale = 1000 / Math.max(vw, vh);
  const cellX = (c: number) => m.originX + c * res;
  const cellY = (r: number) => m.originY + (m.height - r) * res;
  const rectPath = (rects: [number, number, number, number][]) =>
    rects
      .filter(([a, b, c, d]) => c > c0 && a < c1 && d > r0 && b < r1)
      .map(([a, b, c, d]) => `M${n(cellX(a))} ${n(cellY(b))}H${n(cellX(c))}V${n(cellY(d))}H${n(cellX(a))}Z`)
      .join('');
  const out: string[] = [];
  out.push(
    `<svg xmlns="http://www.w3.org/2000/svg" width="${n(vw * scale)}" height="${n(vh * scale)}" ` +
      `viewBox="${n(x0)} ${n(-yTop)} ${n(vw)} ${n(vh)}">`,
    `<title>${esc(title)}</title>`,
    `<desc>planlab robot scene, world metres (x right, y up); map ${m.width}×${m.height} cells at ${res} m per cell; t = ${n(time)} s</desc>`,
    // Flip y so everything below is in world coordinates.
    `<g id="world" transform="scale(1,-1)" stroke-linejoin="round" stroke-linecap="round">`,
    `<rect id="free" x="${n(x0)}" y="${n(yBot)}" width="${n(vw)}" height="${n(vh)}" fill="${rgb(COLORS.free)}"/>`,
  );
  const unknown = rectPath(mergeCells(m, 2));
  if (unknown) out.push(`<path id="unknown" fill="${rgb(COLORS.unknown)}" d="${unknown}"/>`);
  const walls = rectPath(mergeCells(m, 1));
  if (walls) out.push(`<path id="walls" fill="${rgb(COLORS.occupied)}" d="${walls}"/>`);
  const f = S.frame;
  const gp = f.globalPath();
  if (gp.length >= 4) {
    out.push(
      `<polyline id="global-path" fill="none" stroke="rgba(225,29,72,0.75)" stroke-width="${n(2.5 * px)}" points="${polyline(gp, gp.length / 2)}"/>`,
    );
  }
  if (S.trailLen >= 2) {
    out.push(
      `<polyline id="trail" fill="none" stroke="${COLORS.trail}" stroke-width="${n(2.5 * px)}" points="${polyline(S.trail, S.trailLen)}"/>`,
    );
  }
  out.push('<g id="movers">');
  const mv = f.of(Layer.Movers);
  for (let i = mv.first(Layer.Movers); i < mv.end(Layer.Movers); i++) {
    const cls = Number.isNaN(mv.value(i)) ? 3 : mv.value(i);
    const [x, y, r, vx, vy] = mv.numbers(i);
    out.push(
      `<g class="mover" data-id="${mv.tag(i)}"><circle cx="${n(x)}" cy="${n(y)}" r="${n(r)}" fill="${COLORS.classes[cls]}" fill-opacity="0.78" stroke="#fff" stroke-width="${n(1.5 * px)}"/>` +
        (Math.hypot(vx, vy) > 1e-9
          ? `<line x1="${n(x)}" y1="${n(y)}" x2="${n(x + vx)}" y2="${n(y + vy)}" stroke="#0f172a" stroke-width="${n(2 * px)}"/>`
          : '') +
        '</g>',
    );
  }
  out.push('</g>');
  const marker = (id: string, [x, y]: [number, number], r: number, fill: string) =>
    `<circle id="${id}" cx="${n(x)}" cy="${n(y)}" r="${n(r)}" fill="${fill}" stroke="#fff" stroke-width="${n(2 * px)}"/>`;
  out.push(marker('start', f.goal(0), 7 * px, COLORS.start));
  out.push(marker('goal', f.goal(1), 10 * px, COLORS.goal));
  // The footprint the core drew (disc or polygon) and its heading line.
  const rb = f.of(Layer.Robot);
  const parts: string[] = [];
  for (let i = rb.first(Layer.Robot); i < rb.end(Layer.Robot); i++) {
    const v = rb.numbers(i);
    if (rb.shape(i) === Shape.Segments) {
      parts.push(`<line x1="${n(v[0])}" y1="${n(v[1])}" x2="${n(v[2])}" y2="${n(v[3])}" stroke="#fbbf24" stroke-width="${n(2.5 * px)}"/>`);
    } else {
      const body = rb.shape(i) === Shape.Discs ? `<circle cx="${n(v[0])}" cy="${n(v[1])}" r="${n(v[2])}"/>` : `<polygon points="${polyline(v, v.length / 2)}"/>`;
      parts.push(`<g fill="rgba(15,23,42,0.82)" stroke="#fff" stroke-width="${n(2 * px)}">${body}</g>`);
    }
  }
  out.push(`<g id="robot">${parts.join('')}</g>`);
  out.push('</g>', '</svg>');
  return out.join('\n') + '\n';
}
