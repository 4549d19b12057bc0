// The overlaid view: one RobotView paints the map, start, goal and movers
// (the movers follow time only, so any planner's are everyone's at the same
// time), then every planner's global path, trail and robot are drawn on top
// in the planner's colour, in screen space after the view's own paint.

import { RobotView, emptyScene, type MapInfo } from '../robot/view';
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
    // are drawn by drawLanes. A zero-radius robot draws nothing visible.
    s.robot = { kind: 'circle', radius: 0 };
    s.show = { fan: false, path: false, trail: false, lidar: false, fog: false };
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
    const L = lead.scene;
    S.start = L.start;
    S.goal = L.goal;
    S.currentGoal = L.goal;
    S.goalKind = 'final';
    S.movers = L.movers;
    S.state = L.state;
    S.classes.clear();
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
      for (const l of this.lanes) this.line(ctx, l.scene.globalPath, l.scene.globalPath.length / 2, l.colour, 1.6, 0.7);
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
    for (const l of this.lanes) {
      const s = l.scene.state;
      const [x, y] = this.view.toScreen(s[0], s[1]);
      const r = l.scene.robot;
      ctx.save();
      ctx.translate(x, y);
      ctx.rotate(-s[2]);
      ctx.beginPath();
      let nose: number;
      if (r.kind === 'circle') {
        const rr = Math.max(4, r.radius * k);
        ctx.arc(0, 0, rr, 0, Math.PI * 2);
        nose = rr;
      } else {
        const [len, wid] = [Math.max(6, r.length * k), Math.max(4, r.width * k)];
        ctx.rect(-len / 2, -wid / 2, len, wid);
        nose = len / 2;
      }
      ctx.globalAlpha = l.running ? 0.85 : 0.6;
      ctx.fillStyle = l.colour;
      ctx.fill();
      ctx.globalAlpha = 1;
      ctx.lineWidth = 2;
      ctx.strokeStyle = '#fff';
      ctx.stroke();
      ctx.beginPath();
      ctx.moveTo(0, 0);
      ctx.lineTo(nose, 0);
      ctx.lineWidth = 2.5;
      ctx.strokeStyle = '#0f172a';
      ctx.stroke();
      ctx.restore();
    }
    ctx.restore();
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
