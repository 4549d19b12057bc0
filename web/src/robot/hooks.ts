// `window.planlabRobot`: what the e2e tests (and the curious, from the
// console) read of the robot page: frame statistics, the trace and its
// hash, the metrics, the planner, and what the view draws (movers, the
// fan's rollouts and the values that colour them).

import type { SimHandle } from '../../pkg/planlab_wasm.js';
import { Layer, drawnFrame, mask } from '../scene/draw';
import type { RobotView } from '../scene/view';
import type { FrameMeter } from '../shell/frame-meter';
import type { PlannerInfo } from '../shell/planner-info';

export interface HookHost {
  sim(): SimHandle | null;
  view: RobotView;
  canvas: HTMLCanvasElement;
  meter: FrameMeter;
  /** The registry's planners by name (filled at boot). */
  infos(): Map<string, PlannerInfo>;
}

export function installRobotHooks(h: HookHost): void {
  const sim = h.sim;
  (window as unknown as { planlabRobot: unknown }).planlabRobot = {
    frameStats: () => h.meter.stats(),
    resetMeter: () => h.meter.reset(),
    traceHash: () => sim()?.traceHash() ?? null,
    traceCsv: () => sim()?.traceCsv() ?? null,
    metrics: () => parsed(sim()?.metricsJson()),
    toScreen: (x: number, y: number) => {
      const r = h.canvas.getBoundingClientRect();
      const [sx, sy] = h.view.toScreen(x, y);
      return { x: r.left + sx, y: r.top + sy };
    },
    state: () => (sim() ? Array.from(sim()!.state()) : null),
    plannerChoice: () => parsed(sim()?.plannerChoice()),
    plannerFields: (name: string) => h.infos().get(name)?.fields.map((f) => f.name) ?? null,
    plannerDefaults: (name: string) => Object.fromEntries(h.infos().get(name)?.fields.map((f) => [f.name, f.default]) ?? []),
    movers: () => {
      const s = sim();
      return s ? drawnFrame(s.draw(mask(Layer.Movers), 0), mask(Layer.Movers)).movers() : null;
    },
    rollouts: () => h.view.scene.frame.of(Layer.Fan).count(Layer.Fan),
    /** The global path as drawn: x0, y0, x1, y1, … (m). */
    globalPath: () => Array.from(h.view.scene.frame.globalPath()),
    /** The fan as drawn: per rollout its colouring value and whether it
     *  was admissible. */
    fan: () => {
      const d = h.view.scene.frame.of(Layer.Fan);
      const out: { value: number; admissible: boolean }[] = [];
      for (let i = d.first(Layer.Fan); i < d.end(Layer.Fan); i++) out.push({ value: d.value(i), admissible: d.tag(i) === 1 });
      return out;
    },
  };
}

function parsed(json: string | undefined): unknown {
  return json === undefined ? null : JSON.parse(json);
}
