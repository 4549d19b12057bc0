// How each layer of the core's draw list looks on the robot view: colours,
// widths and markers per layer. World-space painters run under the view's
// world transform (widths in CSS px times `px` metres), marker painters in
// screen space through `toScreen`. The fan is one path per colour bucket (a
// dozen strokes for hundreds of rollouts).

import { Layer, Shape, type DrawList, type Frame } from './draw';
import { COLORS, EDGE_COLOURS, type Scene } from './view';

/** Score buckets of the fan: one stroke each. */
export const FAN_BUCKETS = 10;
/** Beams up to which laser rays keep their full alpha. */
const RAYS_FULL_ALPHA = 360;

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

/** The fan's colour scale, worst to best, as a CSS gradient (for legends). */
export function fanGradient(): string {
  return `linear-gradient(90deg, ${BUCKET_COLOURS.join(', ')})`;
}
/** Inadmissible (bucket FAN_BUCKETS) underneath, then worst to best. */
const BUCKET_ORDER = [FAN_BUCKETS, ...Array.from({ length: FAN_BUCKETS }, (_, b) => b)];
/** Per-rollout bucket, reused between frames (grown when needed). */
let buckets = new Uint8Array(1024);

/** Which LiDAR layers a frame holds (for tests), comma-separated. */
export function lidarLayers(f: Frame): string {
  const out: string[] = [];
  const has = (l: (typeof Layer)[keyof typeof Layer]) => f.of(l).count(l) > 0;
  if (has(Layer.LidarRays)) out.push('rays');
  if (has(Layer.LidarEdges)) out.push('edges');
  if (has(Layer.LidarOpsRaw)) out.push('ops-raw');
  if (has(Layer.LidarOps)) out.push('ops');
  if (has(Layer.LidarCandidates)) out.push('candidates');
  const t = f.of(Layer.LidarTarget);
  const first = t.first(Layer.LidarTarget);
  if (t.count(Layer.LidarTarget) > 0 && t.tag(first) > 0) out.push('temp-goal');
  if (timerOf(t) >= 0) out.push('hold');
  return out.join(',');
}

/** The robot's heading (rad), from its heading line; 0 without one. */
export function headingOf(d: DrawList): number {
  for (let i = d.first(Layer.Robot); i < d.end(Layer.Robot); i++) {
    if (d.shape(i) !== Shape.Segments) continue;
    const [x0, y0, x1, y1] = d.numbers(i);
    return Math.atan2(y1 - y0, x1 - x0);
  }
  return 0;
}

/** The hold timer item of a LidarTarget layer, or -1. */
function timerOf(d: DrawList): number {
  for (let i = d.first(Layer.LidarTarget); i < d.end(Layer.LidarTarget); i++) if (d.shape(i) === Shape.Timer) return i;
  return -1;
}

export class Painter {
  constructor(
    private ctx: CanvasRenderingContext2D,
    private S: Scene,
    /** Metres per CSS pixel. */
    private px: number,
    private toScreen: (x: number, y: number) => [number, number],
  ) {}

  /** Points `[from, n)` of `xy` as one stroke, `width` in CSS px. */
  polyline(xy: Float64Array, from: number, n: number, colour: string, width: number): void {
    if (n - from < 2) return;
    const ctx = this.ctx;
    ctx.beginPath();
    ctx.moveTo(xy[2 * from], xy[2 * from + 1]);
    for (let i = from + 1; i < n; i++) ctx.lineTo(xy[2 * i], xy[2 * i + 1]);
    ctx.strokeStyle = colour;
    ctx.lineWidth = width * this.px;
    ctx.stroke();
  }

  /** Item `i` of `d` as a polyline. */
  private item(d: DrawList, i: number, colour: string, width: number): void {
    this.polyline(d.data, d.start(i) / 2, d.stop(i) / 2, colour, width);
  }

  globalPath(): void {
    const d = this.S.frame.of(Layer.GlobalPath);
    for (let i = d.first(Layer.GlobalPath); i < d.end(Layer.GlobalPath); i++) {
      this.item(d, i, 'rgba(255,255,255,0.8)', 4.5);
      this.item(d, i, 'rgba(225, 29, 72, 0.75)', 2.5);
    }
  }

  /** The fan: rollouts bucketed by score, one path per bucket; then the
   *  chosen rollout on top. */
  fan(): void {
    const d = this.S.frame.of(Layer.Fan);
    const f0 = d.first(Layer.Fan);
    const n = d.count(Layer.Fan);
    if (n === 0) return;
    if (buckets.length < n) buckets = new Uint8Array(n * 2);
    let lo = Infinity;
    let hi = -Infinity;
    for (let i = 0; i < n; i++) {
      if (!d.tag(f0 + i)) continue;
      const s = d.value(f0 + i);
      if (s < lo) lo = s;
      if (s > hi) hi = s;
    }
    const span = hi - lo;
    const NONE = FAN_BUCKETS; // inadmissible
    for (let i = 0; i < n; i++) {
      const s = d.value(f0 + i);
      if (!d.tag(f0 + i) || !Number.isFinite(s)) buckets[i] = NONE;
      else buckets[i] = span > 0 ? Math.min(FAN_BUCKETS - 1, Math.floor(((s - lo) / span) * FAN_BUCKETS)) : FAN_BUCKETS - 1;
    }
    const ctx = this.ctx;
    const pts = d.data;
    ctx.lineWidth = 1 * this.px;
    for (const b of BUCKET_ORDER) {
      ctx.beginPath();
      let any = false;
      for (let i = 0; i < n; i++) {
        if (buckets[i] !== b) continue;
        const a = d.start(f0 + i);
        const e = d.stop(f0 + i);
        if (e - a < 4) continue;
        ctx.moveTo(pts[a], pts[a + 1]);
        for (let j = a + 2; j < e; j += 2) ctx.lineTo(pts[j], pts[j + 1]);
        any = true;
      }
      if (any) {
        ctx.strokeStyle = b === NONE ? COLORS.inadmissible : BUCKET_COLOURS[b];
        ctx.stroke();
      }
    }
    const c = this.S.frame.of(Layer.Chosen);
    for (let i = c.first(Layer.Chosen); i < c.end(Layer.Chosen); i++) {
      this.item(c, i, 'rgba(255,255,255,0.9)', 5);
      this.item(c, i, COLORS.chosen, 3);
    }
  }

  /** Rays, then obstacle patterns after (wide) and before (thin) expansion. */
  lidar(): void {
    const ctx = this.ctx;
    const f = this.S.frame;
    const rays = f.of(Layer.LidarRays);
    let beams = 0;
    for (let i = rays.first(Layer.LidarRays); i < rays.end(Layer.LidarRays); i++) beams += rays.numbers(i).length / 4;
    // A dense scan (a UST-10's 1081 beams) would paint a solid wedge: fade
    // it to the tint of a 360-beam one.
    const fade = Math.min(1, RAYS_FULL_ALPHA / Math.max(1, beams));
    for (let i = rays.first(Layer.LidarRays); i < rays.end(Layer.LidarRays); i++) {
      const s = rays.numbers(i);
      ctx.beginPath();
      for (let j = 0; j + 3 < s.length; j += 4) {
        ctx.moveTo(s[j], s[j + 1]);
        ctx.lineTo(s[j + 2], s[j + 3]);
      }
      ctx.strokeStyle = rays.tag(i) ? `rgba(234, 88, 12, ${0.22 * fade})` : `rgba(148, 163, 184, ${0.14 * fade})`;
      ctx.lineWidth = 1 * this.px;
      ctx.stroke();
    }
    const ops = f.of(Layer.LidarOps);
    for (let i = ops.first(Layer.LidarOps); i < ops.end(Layer.LidarOps); i++) {
      this.item(ops, i, ops.value(i) ? 'rgba(190, 24, 93, 0.45)' : 'rgba(124, 58, 237, 0.3)', 7);
    }
    const raw = f.of(Layer.LidarOpsRaw);
    for (let i = raw.first(Layer.LidarOpsRaw); i < raw.end(Layer.LidarOpsRaw); i++) this.item(raw, i, 'rgba(30, 41, 59, 0.9)', 2);
  }

  /** Edge markers by type, candidates, the chosen temporary goal, hold timer. */
  lidarMarkers(): void {
    const ctx = this.ctx;
    const f = this.S.frame;
    const edges = f.of(Layer.LidarEdges);
    for (let i = edges.first(Layer.LidarEdges); i < edges.end(Layer.LidarEdges); i++) {
      const [x, y] = this.screenPoint(edges, i);
      ctx.beginPath();
      ctx.arc(x, y, 3.5, 0, Math.PI * 2);
      ctx.fillStyle = EDGE_COLOURS[edges.tag(i)] ?? '#000';
      ctx.fill();
    }
    const cands = f.of(Layer.LidarCandidates);
    for (let i = cands.first(Layer.LidarCandidates); i < cands.end(Layer.LidarCandidates); i++) {
      const [x, y] = this.screenPoint(cands, i);
      ctx.beginPath();
      ctx.moveTo(x, y - 6);
      ctx.lineTo(x + 5.5, y + 4);
      ctx.lineTo(x - 5.5, y + 4);
      ctx.closePath();
      ctx.lineWidth = 1.5;
      ctx.strokeStyle = cands.tag(i) > 0 ? '#a855f7' : '#7c3aed';
      ctx.stroke();
    }
    const t = f.of(Layer.LidarTarget);
    const first = t.first(Layer.LidarTarget);
    if (t.count(Layer.LidarTarget) > 0 && t.tag(first) > 0) {
      const [x, y] = this.screenPoint(t, first);
      star(ctx, x, y, 8, t.tag(first) === 2 ? '#f59e0b' : '#16a34a');
    }
    const h = timerOf(t);
    if (h >= 0) {
      const [rx, ry, left, period] = t.numbers(h);
      if (period > 0) {
        const [x, y] = this.toScreen(rx, ry);
        const frac = Math.min(1, left / period);
        ctx.beginPath();
        ctx.arc(x, y, 18, -Math.PI / 2, -Math.PI / 2 + frac * Math.PI * 2);
        ctx.lineWidth = 3;
        ctx.strokeStyle = '#f59e0b';
        ctx.stroke();
        ctx.font = '600 11px system-ui, sans-serif';
        ctx.fillStyle = '#b45309';
        ctx.fillText(`hold ${left.toFixed(1)} s`, x + 22, y - 12);
      }
    }
  }

  /** The first point of item `i`, on screen. */
  private screenPoint(d: DrawList, i: number): [number, number] {
    const a = d.start(i);
    return this.toScreen(d.data[a], d.data[a + 1]);
  }

  /** The footprint (disc or polygon) and its heading line. */
  robot(): void {
    const ctx = this.ctx;
    const d = this.S.frame.of(Layer.Robot);
    const heading = headingOf(d);
    for (let i = d.first(Layer.Robot); i < d.end(Layer.Robot); i++) {
      const n = d.numbers(i);
      ctx.beginPath();
      if (d.shape(i) === Shape.Segments) {
        ctx.moveTo(n[0], n[1]);
        ctx.lineTo(n[2], n[3]);
        ctx.lineWidth = 2.5 * this.px;
        ctx.strokeStyle = '#fbbf24';
        ctx.stroke();
        continue;
      }
      // The circle starts at the heading, as a rotated body's would.
      if (d.shape(i) === Shape.Discs) ctx.arc(n[0], n[1], n[2], heading, heading + Math.PI * 2);
      else {
        ctx.moveTo(n[0], n[1]);
        for (let j = 2; j + 1 < n.length; j += 2) ctx.lineTo(n[j], n[j + 1]);
        ctx.closePath();
      }
      ctx.fillStyle = 'rgba(15, 23, 42, 0.82)';
      ctx.fill();
      ctx.lineWidth = 2 * this.px;
      ctx.strokeStyle = '#fff';
      ctx.stroke();
    }
  }

  keypoints(): void {
    const d = this.S.frame.of(Layer.KeyPoints);
    const ctx = this.ctx;
    for (let i = d.first(Layer.KeyPoints); i < d.end(Layer.KeyPoints); i++) {
      const kp = d.numbers(i);
      for (let j = 0; j + 1 < kp.length; j += 2) {
        const [x, y] = this.toScreen(kp[j], kp[j + 1]);
        ctx.beginPath();
        ctx.arc(x, y, 5, 0, Math.PI * 2);
        ctx.fillStyle = '#fff';
        ctx.fill();
        ctx.lineWidth = 2.5;
        ctx.strokeStyle = COLORS.keypoint;
        ctx.stroke();
      }
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

  /** Movers by class colour with their 1 s velocity arrow and id label;
   *  `k` px per metre. */
  movers(k: number): void {
    const d = this.S.frame.of(Layer.Movers);
    const ctx = this.ctx;
    ctx.font = '600 11px system-ui, sans-serif';
    ctx.textAlign = 'center';
    ctx.textBaseline = 'middle';
    for (let i = d.first(Layer.Movers); i < d.end(Layer.Movers); i++) {
      const id = d.tag(i);
      const [mx, my, mr, vx, vy] = d.numbers(i);
      const [x, y] = this.toScreen(mx, my);
      const r = mr * k;
      const v = d.value(i);
      const cls = this.S.show.classes && !Number.isNaN(v) ? v : undefined;
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
      const [ex, ey] = this.toScreen(mx + vx, my + vy);
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

  /** The start marker (painted before the robot, so a robot at its start
   *  is seen on top of it). */
  startMarker(): void {
    const f = this.S.frame;
    if (f.of(Layer.Goals).count(Layer.Goals) === 0) return;
    const [sx, sy] = this.toScreen(...f.goal(0));
    this.marker(sx, sy, COLORS.start, 'S', 7);
  }

  /** The goal marker and the goal steered to (the start: startMarker). */
  goals(): void {
    const f = this.S.frame;
    const d = f.of(Layer.Goals);
    if (d.count(Layer.Goals) === 0) return;
    const ctx = this.ctx;
    const [gx, gy] = this.toScreen(...f.goal(1));
    this.marker(gx, gy, COLORS.goal, 'G', 10);
    if (!this.S.show.subgoal) return;
    const [cx, cy] = this.toScreen(...f.goal(2));
    const kind = f.goalKind();
    if (kind === 'intermediate') {
      ctx.save();
      ctx.translate(cx, cy);
      ctx.rotate(Math.PI / 4);
      ctx.fillStyle = COLORS.subgoal;
      ctx.strokeStyle = '#fff';
      ctx.lineWidth = 2;
      ctx.fillRect(-6, -6, 12, 12);
      ctx.strokeRect(-6, -6, 12, 12);
      ctx.restore();
    } else if (kind === 'virtual') {
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

  /** The mover being placed by a drag; `k` px per metre. */
  preview(k: number): void {
    const p = this.S.preview;
    if (!p) return;
    const ctx = this.ctx;
    const [x, y] = this.toScreen(p.x, p.y);
    ctx.beginPath();
    ctx.arc(x, y, Math.max(2, p.radius * k), 0, Math.PI * 2);
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
