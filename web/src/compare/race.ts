// The planners of a comparison as one race: a lane (SimHandle) per picked
// planner on the same scenario, stepped in rounds (one control step each,
// so all stay at the same simulated time), or run to the end at once in
// slices that yield to the page.

import { Lane } from './lane';
import { laneColour } from './render';
import type { ComparedScenario } from './scenario';
import { messageOf } from '../shell/dom';
import type { SimClock } from '../shell/sim-clock';

/** "Run to end": work per slice before the page gets a frame, ms. */
const INSTANT_SLICE_MS = 40;

export class Race {
  lanes: Lane[] = [];
  /** Bumped by every rebuild: a running "run to end" stops. */
  private generation = 0;
  /** A "run to end" is under way. */
  instant = false;

  /** A lane per planner in `chosen` on `scenario` (fan recorded when
   *  `fan`); returns the planners that cannot run it, with the reason. */
  rebuild(scenario: Pick<ComparedScenario, 'text' | 'build'>, chosen: string[], fan: boolean): string[] {
    this.generation += 1;
    this.instant = false;
    for (const l of this.lanes) l.free();
    this.lanes = [];
    const problems: string[] = [];
    if (!scenario.text) return problems;
    for (const name of chosen) {
      try {
        const lane = new Lane(name, laneColour(chosen, name), scenario.build(name));
        lane.setRecordRollouts(fan);
        this.lanes.push(lane);
      } catch (e) {
        problems.push(`${name}: ${messageOf(e)}`);
      }
    }
    return problems;
  }

  allDone(): boolean {
    return this.lanes.length > 0 && this.lanes.every((l) => !l.running);
  }

  /** One control step for every planner still running. */
  round(): void {
    for (const l of this.lanes) l.step(1);
  }

  /** Up to `n` rounds on `clock` within `budgetMs` (`SimClock.run`);
   *  returns how many ran. */
  rounds(clock: SimClock, n: number, budgetMs: number): number {
    return clock.run(n, () => !this.allDone(), () => this.round(), budgetMs);
  }

  pull(): void {
    for (const l of this.lanes) l.pull();
  }

  /** Runs every lane to its end in slices, `slice()` after each (progress
   *  shows); false when a rebuild stopped it. Rollouts are not recorded
   *  meanwhile (`fan()`: whether to record them again after). */
  async runToEnd(slice: () => void, fan: () => boolean): Promise<boolean> {
    const gen = this.generation;
    this.instant = true;
    for (const l of this.lanes) l.sim.setRecordRollouts(false);
    try {
      while (!this.allDone()) {
        const t0 = performance.now();
        while (!this.allDone() && performance.now() - t0 < INSTANT_SLICE_MS) this.round();
        this.pull();
        slice();
        await new Promise((r) => setTimeout(r, 0));
        if (gen !== this.generation) return false;
      }
    } finally {
      if (gen === this.generation) {
        this.instant = false;
        for (const l of this.lanes) l.sim.setRecordRollouts(fan());
      }
    }
    return true;
  }
}
