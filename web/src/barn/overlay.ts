// What the BARN page draws over each lane's view in screen space: the
// goal's success circle (the run ends there) and, on request, the true
// cylinders — the world the planner never sees (it gets only the costmap
// its laser scans build). Positions come from the core (`barnCylinders`,
// the Goals layer); nothing here decides anything.

import type { RobotView } from '../scene/view';
import { COLORS } from '../scene/view';

export interface TruthOverlay {
  /** Cylinder centres x, y flat, m. */
  cylinders: Float64Array;
  /** Cylinder radius, m. */
  radius: number;
  /** The goal and its success radius, m. */
  goal: [number, number];
  tolerance: number;
  /** Whether the true cylinders are shown. */
  show: () => boolean;
}

/** Installs the overlay on `view`. */
export function drawTruth(view: RobotView, t: TruthOverlay): void {
  view.overlay = (ctx) => {
    const k = view.scale;
    const [gx, gy] = view.toScreen(t.goal[0], t.goal[1]);
    ctx.beginPath();
    ctx.arc(gx, gy, t.tolerance * k, 0, Math.PI * 2);
    ctx.fillStyle = 'rgba(37, 99, 235, 0.08)';
    ctx.fill();
    ctx.setLineDash([6, 4]);
    ctx.lineWidth = 1.5;
    ctx.strokeStyle = COLORS.goal;
    ctx.stroke();
    ctx.setLineDash([]);
    const on = t.show();
    view.canvas.dataset.truth = on ? 'on' : 'off';
    if (!on) return;
    const r = Math.max(1.5, t.radius * k);
    ctx.beginPath();
    for (let i = 0; i + 1 < t.cylinders.length; i += 2) {
      const [x, y] = view.toScreen(t.cylinders[i], t.cylinders[i + 1]);
      ctx.moveTo(x + r, y);
      ctx.arc(x, y, r, 0, Math.PI * 2);
    }
    ctx.lineWidth = 1.2;
    ctx.strokeStyle = 'rgba(13, 148, 136, 0.95)';
    ctx.stroke();
  };
}
