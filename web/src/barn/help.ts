// The BARN page's help overlay: what BARN is, what the robot knows, how the
// score works, the page's controls and keys; the planners with the
// registry's plain words (from wasm, like the robot and compare pages).

import type { HelpContent } from '../shell/help';
import type { PlannerInfo } from '../shell/planner-info';

export function barnHelp(planners: PlannerInfo[], current: string | undefined): HelpContent {
  return {
    page: 'barn',
    intro:
      'BARN (Benchmark Autonomous Robot Navigation, Perille et al. 2020, the BARN Challenge) is 300 generated worlds of 0.15 m cylinders a Clearpath Jackal must cross; the 250 public ones are here. The robot knows only what its laser sees: the planner gets a costmap built from the scans (grey never seen, violet the cost decaying from a laser mark, rose inscribed, black a mark), never the true map (the True cylinders toggle shows it to you, not to the planner). A run succeeds when the robot’s centre comes within 1 m of the goal (the dashed circle) without a collision within 100 s, and scores success · OT / clip(T, 2·OT, 8·OT), at most 0.5, where OT is the reference path’s length at 2 m/s. Every run here is `planlab run barn:N --planner P --seed S` (same trace hash); `planlab barn` runs the whole benchmark with confidence intervals. Link to a run with `barn.html?world=12&planner=dwb&seed=3&autorun=1`, to a race with `barn.html?world=12&planners=dwb,move-base-dwa&autorun=instant`.',
    planners: planners.map((p) => ({ name: p.name, paper: p.paper, summary: p.summary, plain: p.plain })),
    current,
    params: [
      { name: 'World', unit: '', default: 1, doc: 'The BARN world number (1–299 without the multiples of 6, the challenge’s held-back test set). Difficulty: the world’s clutter class (terciles of occupied grid cells); Next and Random pick within it.' },
      { name: 'Seed', unit: '', default: 1, doc: 'Seeds the laser noise: the same world, planner and seed give the same run.' },
      { name: 'Laser noise σ', unit: 'm', default: 0.01, doc: 'Standard deviation of the laser’s range noise.' },
      { name: 'Race 2–4', unit: '', doc: 'The picked planners on the same world and seed, side by side, stepped together; the table has each one’s outcome, time and score.' },
      { name: 'Speed', unit: '×', default: '4×', doc: 'Simulated seconds per real second; slower when the steps do not fit in a frame. Run to end: at top speed.' },
    ],
    shortcuts: [
      { keys: 'Space', action: 'run / pause' },
      { keys: '.', action: 'one control step (every lane)' },
      { keys: 'R', action: 'reset to the start' },
      { keys: 'E', action: 'run to the end at top speed' },
      { keys: 'wheel / right drag', action: 'zoom / pan every lane' },
      { keys: 'double click', action: 'fit the world into every lane' },
    ],
  };
}
