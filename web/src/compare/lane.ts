// One planner of a comparison: its own SimHandle on the shared scenario,
// the scene the robot page's painter draws from it, and the trail kept in
// JS (grown incrementally, as on the robot page) for the overlay.

import type { SimHandle } from '../../pkg/planlab_wasm.js';
import { emptyScene, type Scene } from '../scene/view';
import type { Metrics } from '../shell/metrics';
import { pullLive } from '../scene/pull';

/** Planner colours, in the order the planners were picked: apart from the
 *  start (green), goal (blue), path (rose) and mover colours of the view. */
export const LANE_COLOURS = ['#f97316', '#7c3aed', '#0d9488', '#db2777'] as const;

export class Lane {
  readonly name: string;
  readonly colour: string;
  readonly sim: SimHandle;
  readonly scene: Scene;
  outcome: string;
  metrics: Metrics | null = null;
  /** The trace hash (decimal) once the episode is over. */
  hash: string | null = null;
  /** What colours its fan (fan-colour.ts): a critic's name or the total. */
  fanColour = 'total score';

  constructor(name: string, colour: string, sim: SimHandle) {
    this.name = name;
    this.colour = colour;
    this.sim = sim;
    this.scene = emptyScene();
    this.outcome = sim.outcome;
    if (!this.running) this.hash = sim.traceHash();
  }

  get running(): boolean {
    return this.outcome === 'running';
  }

  /** One control step (a no-op once the episode is over). */
  step(n = 1): void {
    if (!this.running) return;
    this.outcome = this.sim.step(n);
    if (!this.running) this.hash = this.sim.traceHash();
  }

  /** Copies what the SimHandle draws into the scene. */
  pull(): void {
    pullLive(this.sim, this.scene);
    this.outcome = this.sim.outcome;
  }

  /** The `planlab run` metrics so far (a pass over the trace: call it at
   *  the table's pace, not every frame). */
  updateMetrics(): Metrics {
    this.metrics = JSON.parse(this.sim.metricsJson()) as Metrics;
    return this.metrics;
  }

  /** Records the rollouts for drawing (side by side) or not (faster). */
  setRecordRollouts(on: boolean): void {
    this.scene.show.fan = on;
    this.sim.setRecordRollouts(on);
  }

  free(): void {
    this.sim.free();
  }
}

