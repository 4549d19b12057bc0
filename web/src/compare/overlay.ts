// The overlaid view: one RobotView paints the map, start, goal and movers
// (the movers follow time only, so any planner's are everyone's at the same
// time), then every planner's global path, trail and robot are drawn on top
// in the planner's colour, in screen space after the view's own paint.

import { RobotView, emptyScene, type MapInfo } from '../scene/view';
import { Layer, Shape, mask } from '../scene/draw';
import { headingOf } from '../scene/paint';
import type { Lane } from './lane';

export class OverlayView {
  readonly view: RobotView;
  private lanes: Lane[] = [];
  showPath = true;

  constructor(canvas: HTMLCanvasElement) {
    this.view = new RobotView(canvas);
    this.view.onPaint = () => this.drawLanes();
  }

  setMap(map: MapInfo): void {
    this.view.scene = this.baseScene();
    this.view.setMap(map);
  }

  private baseScene() {
    const s = emptyScene();
    // The view's own robot, fan, trail and paths are off: each planner's
    // are drawn by drawLanes (the frame never gets a Robot layer). Movers
    // are not coloured by one planner's classes, nor its subgoal marked.
    s.show = { fan: false, path: false, trail: false, lidar: false, fog: false, classes: false, subgoal: false, costmap: false };
    return s;
  }

  setLanes(lanes: Lane[]): void {
    this.lanes = lanes;
    this.sync();
  }

  /** Takes start, goal and movers from the planner furthest in time. */
  sync(): void {
    const S = this.view.scene;
    const lead = this.lanes.reduce<Lane | null>((a, l) => (!a || l.sim.time > a.sim.time ? l : a), null);
    if (!lead) return;
    for (const l of [Layer.Movers, Layer.Goals]) S.frame.put(lead.scene.frame.of(l), mask(l));
  }

  request(): void {
    this.sync();
    this.view.request();
  }

  paint(): void {
    this.sync();
    this.view.paint();
  }

  private drawLanes(): void {
    const cv = this.view.canvas;
    const ctx = cv.getContext('2d');
    if (!ctx) return;
    const dpr = window.devicePixelRatio || 1;
    ctx.save();
    ctx.setTransform(dpr, 0, 0, dpr, 0, 0);
    ctx.lineJoin = 'round';
    ctx.lineCap = 'round';
    const k = this.view.scale;
    if (this.showPath) {
      ctx.setLineDash([6, 5]);
      for (const l of this.lanes) {
        const gp = l.scene.frame.globalPath();
        this.line(ctx, gp, gp.length / 2, l.colour, 1.6, 0.7);
      }
      ctx.setLineDash([]);
    }
    // Earlier planners' trails are wider, so a later one driving the same
    // way leaves them visible as a border.
    const n = this.lanes.length;
    this.lanes.forEach((l, i) => {
      const w = 2.5 + 2 * (n - 1 - i);
      this.line(ctx, l.scene.trail, l.scene.trailLen, '#ffffff', w + 2.5, 0.85);
      this.line(ctx, l.scene.trail, l.scene.trailLen, l.colour, w, 1);
    });
    for (const l of this.lanes) this.robot(ctx, l, k);
    ctx.restore();
  }

  /** A planner's robot in its colour, in screen space: the footprint the
   *  core drew (a disc at least 4 px) and its heading. */
  private robot(ctx: CanvasRenderingContext2D, l: Lane, k: number): void {
    const d = l.scene.frame.of(Layer.Robot);
    ctx.beginPath();
    let nose: [number, number, number, number] | null = null;
    for (let i = d.first(Layer.Robot); i < d.end(Layer.Robot); i++) {
      const v = d.numbers(i);
      const at = (j: number) => this.view.toScreen(v[j], v[j + 1]);
      if (d.shape(i) === Shape.Segments) nose = [...at(0), ...at(2)];
      else if (d.shape(i) === Shape.Discs) {
        // Starts at the heading (screen y points down), as a rotated body's would.
        const [x, y] = at(0);
        const a = -headingOf(d);
        ctx.arc(x, y, Math.max(4, v[2] * k), a, a + Math.PI * 2);
      } else {
        for (let j = 0; j + 1 < v.length; j += 2) {
          const [x, y] = at(j);
          if (j === 0) ctx.moveTo(x, y);
          else ctx.lineTo(x, y);
        }
        ctx.closePath();
      }
    }
    ctx.globalAlpha = l.running ? 0.85 : 0.6;
    ctx.fillStyle = l.colour;
    ctx.fill();
    ctx.globalAlpha = 1;
    ctx.lineWidth = 2;
    ctx.strokeStyle = '#fff';
    ctx.stroke();
    if (!nose) return;
    // A disc drawn larger than its size keeps its heading line to the rim.
    const [x0, y0, x1, y1] = nose;
    const len = Math.hypot(x1 - x0, y1 - y0);
    const f = len > 0 && len < 4 ? 4 / len : 1;
    ctx.beginPath();
    ctx.moveTo(x0, y0);
    ctx.lineTo(x0 + (x1 - x0) * f, y0 + (y1 - y0) * f);
    ctx.lineWidth = 2.5;
    ctx.strokeStyle = '#0f172a';
    ctx.stroke();
  }

  /** A world polyline drawn in screen space. */
  private line(ctx: CanvasRenderingContext2D, xy: Float64Array, n: number, colour: string, width: number, alpha: number): void {
    if (n < 2) return;
    ctx.beginPath();
    for (let i = 0; i < n; i++) {
      const [x, y] = this.view.toScreen(xy[2 * i], xy[2 * i + 1]);
      if (i === 0) ctx.moveTo(x, y);
      else ctx.lineTo(x, y);
    }
    ctx.globalAlpha = alpha;
    ctx.strokeStyle = colour;
    ctx.lineWidth = width;
    ctx.stroke();
    ctx.globalAlpha = 1;
  }
}
