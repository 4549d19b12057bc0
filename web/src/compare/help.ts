// What the shared help overlay (shell/help.ts) says on the compare page:
// the registry's planners with their fields (from wasm, like the robot
// page), the page's controls, its URL parameters and its keys.

import type { HelpContent } from '../shell/help';
import type { PlannerInfo } from '../shell/planner-info';

export function compareHelp(planners: PlannerInfo[], current: string | undefined): HelpContent {
  return {
    page: 'compare',
    intro:
      'Compare runs 2 to 4 local planners on one scenario, each in its own simulation built from the same scenario and seed, stepped together so that all are at the same simulated time. The scenario’s own planner keeps the scenario’s parameters, the others run with the paper’s defaults, exactly as `planlab run SCENARIO --planner NAME`; the table shows the metrics that command prints (same rows, units and digits) and marks the best planner per row. Link to a comparison with `compare.html?scenario=T-fig3-2.json&planners=dwa,improved-dwa&view=overlay&autorun=1` (`autorun=instant` runs to the end at once; `set=movers=[]`, repeatable, edits the scenario as `planlab run --set`).',
    planners: planners.map((p) => ({
      name: p.name,
      paper: p.paper,
      summary: p.summary,
      plain: p.plain,
      params: p.fields.map((f) => ({ name: f.name, label: f.label, unit: f.unit, default: f.default, doc: f.doc })),
    })),
    current,
    params: [
      { name: 'Speed', unit: '×', default: '4×', doc: 'Simulated seconds per real second for all planners together; slower when the steps do not fit in a frame.' },
      { name: 'Run to end instantly', unit: '', doc: 'Runs every planner to the end of its episode without animating (rollouts not recorded); the result is the same episode.' },
      { name: 'Side by side / Overlaid', unit: '', default: 'side by side', doc: 'One canvas per planner with its rollout fan and global path, or one canvas with every planner’s trail, robot and global path (dashed) in its colour.' },
      { name: 'Colour the fans by', unit: '', default: 'total score', doc: 'What colours each planner’s rollout fan, blue low to orange high: the total score it ranks rollouts by, or one critic (every critic any picked planner reports) by its normalised value, the number its weight multiplies. A planner without that critic keeps the total; each lane’s head says what its fan shows.' },
      { name: '★ best', unit: '', doc: 'Reached beats any other outcome; lower time, path length, turning, speed drops, temporary-goal switches and tracking error; higher clearance and wheel-load share. Time and path length: only planners that reached the goal; the other rows: only those when any did. Equal values at the shown precision are all marked.' },
      { name: 'Copy CSV', unit: '', doc: 'The table with full-precision values (as `planlab run --json`), a winner column, steps and trace hashes.' },
    ],
    shortcuts: [
      { keys: 'Space', action: 'run / pause all planners' },
      { keys: '.', action: 'one control step for every planner' },
      { keys: 'R', action: 'reset: every planner back to the start' },
      { keys: 'E', action: 'run to the end instantly' },
      { keys: 'V', action: 'side by side ⇄ overlaid' },
      { keys: 'wheel', action: 'zoom every view together' },
      { keys: 'right or middle drag', action: 'pan every view together' },
      { keys: 'double click', action: 'fit the map into every view' },
    ],
  };
}
