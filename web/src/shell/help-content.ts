// What the help overlay says on each page. The robot page's planners and
// parameters come from the wasm planner registry (name, paper, summary and
// every config field's unit, default and doc), so they cannot drift from
// the core; the other pages' controls are few and fixed, described here
// with their paper sections (docs/algorithms.md).

import type { HelpContent, HelpParam, HelpPlanner } from './help';
import { plannerLabel } from './grid-planners';

/** The registry's planner info as the robot page receives it from wasm. */
export interface RegistryPlanner {
  name: string;
  paper: string;
  summary: string;
  /** Plain words for a beginner (core `planners::plain_words`). */
  plain?: string;
  fields: { name: string; label?: string; unit: string; default: unknown; doc: string }[];
}

/** The robot page: every registered local planner with its fields. */
export function robotHelp(planners: RegistryPlanner[], current: string): HelpContent {
  return {
    page: 'robot',
    intro:
      'The robot simulation runs a local planner (the DWA family, the LiDAR navigator, the cleaning DWA, APF on a scan) on a scenario: a map, a robot, movers, a goal. Every control step the planner sees an observation and chooses a command; the core simulates the motion, checks collisions with the exact footprint and measures the run. Pick a planner and change its parameters in the Local planner card; the current planner is open below. Click the canvas to move the goal, drag to place a mover.',
    planners: planners.map(
      (p): HelpPlanner => ({
        name: p.name,
        paper: p.paper,
        summary: p.summary,
        plain: p.plain,
        params: p.fields.map((f) => ({ name: f.name, label: f.label, unit: f.unit, default: f.default, doc: f.doc })),
      }),
    ),
    current,
    params: [
      { name: 'Speed', unit: '×', default: '1×', doc: 'Simulated seconds per real second; the sim slows down rather than drop frames when a step takes too long.' },
      {
        name: 'Critics',
        unit: '',
        default: 'total score',
        doc: 'A DWA-family planner judges every rollout of the fan with a few critics (for plain DWA: heading toward the goal, distance from obstacles, speed), scales each so the rollouts of one step can be compared (its normalised value), multiplies it by the critic’s weight and adds them up: the rollout with the best total is driven. The Critics list in the Local planner card shows each critic with the weight it had in the last step (improved DWA switches weights with the situation, so they change as the run goes). Pick a critic to colour the fan by that critic alone, blue for its lowest value, orange for its highest; pick “total score” to colour by the sum the planner ranks by. Grey rollouts were not allowed.',
      },
      { name: 'Motion model', unit: '', default: 'constant velocity', doc: 'How a placed mover moves: straight on (bouncing off walls and the map edge), back and forth over Span, or round a square.' },
      { name: 'Radius', unit: 'm', default: 0.3, doc: 'Radius of the next mover placed.' },
      { name: 'Span', unit: 'm', default: 3, doc: 'Back-and-forth distance of the next mover.' },
    ],
    shortcuts: [
      { keys: 'Space', action: 'play / pause' },
      { keys: '.', action: 'one control step' },
      { keys: 'R', action: 'reset: restart with the current goal, movers and planner' },
      { keys: '← / →', action: 'timeline: one frame back / forward (with Shift: 10 frames)' },
      { keys: 'Home / End', action: 'timeline: first frame / the live end' },
      { keys: 'G', action: 'tool: move the goal' },
      { keys: 'M', action: 'tool: place a mover (drag gives its velocity)' },
      { keys: 'X', action: 'tool: remove a mover' },
      { keys: 'W / E', action: 'tool: draw / erase walls with the brush' },
      { keys: '[ / ]', action: 'brush smaller / larger' },
      { keys: 'B', action: 'tool: rectangle of wall (Shift while dragging: erase)' },
      { keys: 'C', action: 'tool: disc obstacle, centre then radius (Shift while dragging: erase)' },
      { keys: 'S', action: 'tool: place the start (drag gives the heading)' },
      { keys: 'L', action: 'tool: mover path by waypoints (Enter or double-click finishes, Esc drops)' },
      { keys: 'Ctrl + Z', action: 'undo the last edit' },
      { keys: 'Ctrl + Shift + Z / Ctrl + Y', action: 'redo' },
      { keys: 'F', action: 'fit the map into the view' },
      { keys: 'Shift + click', action: 'move the goal with any tool' },
      { keys: 'wheel', action: 'zoom' },
      { keys: 'right or middle drag', action: 'pan' },
    ],
  };
}

/** A grid planner as the core describes it (wasm `gridAlgorithms()`). */
export interface CorePlanner {
  name: string;
  optimal: boolean;
  reference: string;
  summary: string;
  /** Optimal, complete, any-angle, incremental; `words`: the four in a sentence. */
  properties?: { optimal: boolean; complete: boolean; any_angle: boolean; incremental: boolean; words: string };
}

const GRID_PLANNERS: HelpPlanner[] = [
  { name: 'A*', paper: '[T] Wu 2022 §3.2.1, eq 3-6', summary: 'Best-first search on f = g + h with a weight w on h (w = 1 is optimal). Diagonal moves cost √2 and may not cut corners by default (the Moving AI rule).' },
  { name: 'Dijkstra', paper: 'baseline (not in the papers)', summary: 'A* with h = 0: optimal, expands every cell cheaper than the goal.' },
  { name: 'Jump Point Search', paper: 'baseline (Harabor & Grastien 2011)', summary: 'The same optimal costs as A* on an 8-connected grid, expanding far fewer cells by jumping along straight lines.' },
  { name: 'Safe A*', paper: '[S] Ge & Li 2022 §1', summary: "24-neighbourhood search with h′ = h + ε·L, L = k/s (k occupied cells in the 5×5 window, s the distance to the nearest): keeps the path away from walls. h′ is inadmissible by design; the admissible variant adds the safety cost to g instead." },
  { name: 'Key points', paper: '[T] Wu 2022 §3.2.1, Fig 3-8/3-9', summary: 'Reduces a path to its turning points, then drops every point whose neighbours see each other on the inflated map (46 → 11 → 3 nodes in the thesis). The improved DWA uses them as intermediate goals.' },
  { name: 'Bottom-Up segmentation', paper: '[S] Ge & Li 2022 §4.1, Fig 6', summary: "Keogh's Bottom-Up: merges adjacent path segments while the merged segment's largest perpendicular error stays below ε and it stays collision-free; the segment ends are the feature nodes (80 → 7 in [S] Fig 6)." },
];

/** Post-processing steps the grid page offers beside the planners. */
const GRID_EXTRAS = GRID_PLANNERS.slice(-2);

/** The grid planners' help: the core's reference and plain-language
 *  summary for each (`Algorithm::ALL`), then key points and Bottom-Up;
 *  without the core's list, the fixed entries above. */
/** Planners whose moves are not A*'s 8 neighbours: their cost is not
 *  comparable (the grid page says so under the cost too). */
const COST_NOTES: Record<string, string> = {
  'safe-astar':
    " Its cost is not comparable with A*'s: it moves to any of the 24 cells of the 5×5 block (knight-like moves of length √5 too), so its path can cost less than 8-connected A*'s optimum (which is optimal over 8 neighbours only).",
  'theta-star': " Its cost is not comparable with A*'s: its segments run at any angle, so it can cost less than 8-connected A*'s optimum.",
};

export function gridPlannerHelp(core: CorePlanner[] = []): HelpPlanner[] {
  if (!core.length) return GRID_PLANNERS;
  return [
    ...core.map((p) => ({
      name: plannerLabel(p.name),
      paper: p.reference,
      summary: `${p.summary}${p.optimal ? '' : ' (Not optimal: its path can be longer than the shortest.)'}${COST_NOTES[p.name] ?? ''}`,
      properties: p.properties?.words,
      key: p.name,
    })),
    ...GRID_EXTRAS,
  ];
}

/** A sampling planner as the core describes it (wasm `samplingAlgorithms()`). */
export interface CoreSamplerInfo {
  name: string;
  optimizing: boolean;
  reference: string;
  summary: string;
}

const SAMPLER_LABELS: Record<string, string> = { rrt: 'RRT', 'rrt-connect': 'RRT-Connect', 'rrt-star': 'RRT*', 'informed-rrt-star': 'Informed RRT*', prm: 'PRM', 'prm-star': 'Lazy PRM*', 'bit-star': 'BIT*' };

/** The sampling planners' help: the core's reference and summary. */
export function samplerHelp(core: CoreSamplerInfo[] = []): HelpPlanner[] {
  return core.map((p) => ({
    name: SAMPLER_LABELS[p.name] ?? p.name,
    paper: p.reference,
    summary: `${p.summary}. Plans a round robot (a disc) in continuous space, not cell by cell: its cost is the path's length in cells, from the centre of the start cell to that of the goal cell (docs/algorithms.md §sampling).${p.optimizing ? '' : ' Stops at its first path, which is not short.'}`,
    properties: SAMPLER_PROPERTIES[p.name],
    key: p.name,
  }));
}

/** Optimal? complete? any-angle? incremental? for the sampling planners,
 *  in the words the grid planners' lines use (docs/algorithms.md §sampling). */
const SAMPLER_PROPERTIES: Record<string, string> = (() => {
  const tail = 'finds a path if one exists, with a probability that grows to 1 as it runs (probabilistically complete) · any-angle: straight segments in continuous space, not grid moves · not incremental: an edit plans again from scratch';
  const first = `not the shortest path: stops at its first · ${tail}`;
  const limit = `the shortest path in the limit: it keeps improving as it runs (asymptotically optimal) · ${tail}`;
  return {
    rrt: first,
    'rrt-connect': first,
    'rrt-star': limit,
    'informed-rrt-star': limit,
    prm: `not the shortest path: its roadmap paths stay a few per cent long · ${tail}`,
    'prm-star': limit,
    'bit-star': limit,
  };
})();

/** The grid page (index.html). */
export function gridHelp(core: CorePlanner[] = [], samplers: CoreSamplerInfo[] = []): HelpContent {
  return {
    page: 'grid',
    intro:
      'The grid page plans global paths on an occupancy grid: Moving AI maps, ROS maps or scenario files. Place the start and goal (drag the S and G markers), paint walls, and every change replans at once. Pick a sampling planner (RRT … BIT*) to watch a tree grow from random samples instead: grey dots are samples, green lines the tree, orange lines rewired edges, and the best path so far glows when it improves; the small plot shows the best cost over the iterations. Press Play to watch the search: green cells are open (reached, waiting), blue cells closed (expanded), the orange square is the cell being expanded, violet lines are straight-line checks (JPS jump scans, Theta* line of sight; red when blocked), and the path appears when the search has played out. Step with , and . or drag the scrubber; hover a cell for its g, h, f, parent and the steps it was opened and expanded at. With D* Lite, painting a wall repairs the plan instead of starting over: the status line says how many cells the repair expanded against a fresh A*. The Draw & generate card gives an empty grid of large cells to draw on, Clear walls, Clear path, and seeded mazes, rooms and random fill (the same maps as planlab generate).',
    planners: [...gridPlannerHelp(core), ...samplerHelp(samplers)],
    params: [
      { name: 'Budget', unit: 'iterations or ms', default: '2000 iterations', doc: 'Sampling planners: how long the planner runs, a number of iterations (one random sample each; up to 200 000) or of milliseconds (up to 10 000, measured by the page: the core has no clock). A timed run is the same as the CLI with the iterations it reached, which the status line says.' },
      { name: 'Seed', unit: '', default: 1, doc: 'Sampling planners: the seed of the random numbers. The same seed and iterations give the same tree and path here, in the CLI and from Python.' },
      { name: 'Robot radius', unit: 'm', default: '0.4 cell', doc: 'Sampling planners: the robot is a disc of this radius that must keep clear of walls and the map edge (empty: 0.4 of a cell, the CLI default).' },
      { name: 'Shorten the path', unit: '', default: false, doc: 'Sampling planners: after planning, seeded random shortcuts between path points that the robot can drive straight (the CLI\'s --shortcut).' },
      { name: 'Heuristic', unit: 'cells', default: 'octile', doc: 'A* / JPS distance estimate: octile (exact on 8-connected grids), Euclidean, Manhattan, Chebyshev or zero.' },
      { name: 'Weight', unit: '—', default: 1, doc: 'w in f = g + w·h; above 1 the search is faster and the path at most w times longer.' },
      { name: 'Diagonal moves', unit: '', default: 'no corner cutting', doc: 'Never (4-connected), no corner cutting (both orthogonal neighbours free), one side free, or always.' },
      { name: 'Safety weight ε', unit: '—', default: 100, doc: '[S] §1: weight of the safety term L in h′ = h + ε·L; 0 gives plain A* over the 24-neighbourhood.' },
      { name: 'Neighbourhood', unit: 'cells', default: 24, doc: "[S] §1: successors of a cell: the 5×5 block (24), 8 or 4; a move must cross free cells only. With 24 (or 4) the cost is not comparable with A*'s, which is the optimum over 8 neighbours only: knight-like moves (length √5) can make safe A*'s path cheaper than A*'s; the card under the cost says so." },
      { name: 'Inflate radius', unit: 'm', default: 0, doc: 'Grows walls by the robot radius before planning, so the path keeps that clearance.' },
      { name: 'Allow unknown', unit: '', default: false, doc: 'Plan through unknown (?) cells.' },
      { name: 'Bottom-Up ε', unit: 'cells', default: 1, doc: '[S] §4.1: largest perpendicular error a merged segment may have.' },
    ],
    shortcuts: [
      { keys: 'S', action: 'tool: place the start' },
      { keys: 'G', action: 'tool: place the goal' },
      { keys: 'W', action: 'tool: paint walls' },
      { keys: 'E', action: 'tool: erase walls' },
      { keys: 'K', action: 'tool: cost brush (weighted cells)' },
      { keys: 'X', action: 'clear walls (the start and goal stay)' },
      { keys: 'C', action: 'clear path: remove the search and the path' },
      { keys: 'F', action: 'fit the map into the view' },
      { keys: 'Space', action: 'play / pause the search' },
      { keys: ', / .', action: 'one search event back / forward' },
      { keys: 'drag S or G', action: 'move the start or goal; replans live' },
      { keys: 'Shift + click', action: 'place the goal with any tool' },
      { keys: 'wheel', action: 'zoom' },
      { keys: 'right or middle drag', action: 'pan' },
    ],
  };
}

const APF_VARIANTS: HelpPlanner[] = [
  { name: 'basic APF', paper: '[T] Wu 2022 §4.1, eq 4-1…4-4', summary: 'Steps a fixed length along the resultant of the attraction (quadratic within ρ of the goal, conic beyond) and the repulsion k_r(1/p − 1/p₀)/p² of every obstacle within p₀. Gets stuck in local minima and short of goals near obstacles.', plain: 'The goal pulls the robot, each grey obstacle pushes it away once it is close enough, and the robot takes one step along the sum of the forces. Where the pull and the pushes cancel (an obstacle straight in front of the goal, a gap between two) it stops or shakes in place: a local minimum. Watch the path end short of the goal or zig-zag.' },
  { name: 'sampling APF', paper: '[T] Wu 2022 §4.2.1–4.2.2, eq 4-5…4-11', summary: 'Samples 13 directions from −90° to +90° of the resultant in 15° steps and takes the candidate with the least cost α‖F_attr‖ + β‖F_rep‖ (α 0.3, β 0.7); the relative distance rule sets β = 0 when the goal is nearer than the obstacle.', plain: 'Instead of following the sum of the forces blindly, the robot tries 13 directions around it and takes the one that best trades getting closer against being pushed, so it slides round an obstacle where basic APF stops. It can still be caught by a moving obstacle that steps into its path. Watch the path bend earlier than basic APF\'s.' },
  { name: 'sampling + prediction', paper: '[T] Wu 2022 §4.2.3, eq 4-13/4-14', summary: "Adds virtual repulsion at each mover's predicted positions at t+1 and t+2, with ranges scaled 0.75 and 0.75²: the robot turns away from where the mover will be.", plain: 'As sampling APF, but the robot also avoids where each moving obstacle is about to be (its next two predicted positions), so it turns away before the mover arrives. A wrong forecast (a mover that turns suddenly) can make it swerve for nothing. Watch the minimum distance: larger than without prediction.' },
  { name: 'constant velocity (predictor)', paper: '[T] Wu 2022 §4.2.3', summary: "Predicts a mover's next positions from its last velocity." },
  { name: 'SimpleRNN (predictor)', paper: '[T] Wu 2022 §5.2', summary: '6 inputs (position, velocity), 15 tanh units, 3 outputs: the position 0.5 s ahead from 5 past samples; trained on synthetic hand-reaching trajectories, runs in wasm.' },
];

/** The potential-field page. */
export function apfHelp(): HelpContent {
  return {
    page: 'apf',
    intro:
      'The potential-field page runs the APF variants of [T] ch. 4 on the thesis scenes: a point robot stepping 0.04 m among discs. The heat map is the force field, arrows its direction, dashed circles the repulsion ranges, the fan the sampled directions (the chosen one green) and the violet / pink circles the predicted obstacles. Click or drag to move the goal.',
    planners: APF_VARIANTS,
    params: [
      { name: 'Variant', unit: '', default: 'sampling + prediction', doc: 'basic, sampling or sampling + prediction (apf.config.mode).' },
      { name: 'Predictor', unit: '', default: 'constant velocity', doc: 'How the prediction variant forecasts the movers.' },
    ],
    shortcuts: [{ keys: 'click / drag', action: 'move the goal (restarts the run)' }],
  };
}

/** The arm page. */
export function armHelp(): HelpContent {
  return {
    page: 'arm',
    intro:
      "The arm page runs [T] ch. 5's experiment: a TIAGo-like 7-DOF arm whose end effector is planned by the sampling APF in 0.04 m steps and followed by damped least-squares IK, beside a person's hand that reaches across its path. Links are capsules; the minimum distance to the hand is the metric of [T] Table 5-3.",
    planners: [
      { name: 'none', paper: '[T] Wu 2022 §4.2.1', summary: 'Sampling APF on the hand where it is now.', plain: 'The arm is pushed away from the hand where the hand is now. It reacts late to a hand coming toward it. Watch the min distance: the smallest of the three predictors here.' },
      { name: 'constant-velocity', paper: '[T] Wu 2022 §4.2.3, §5.3.3', summary: "Adds virtual repulsion at the hand's positions predicted at t+1 and t+2 from its last velocity: the arm keeps further away (paper: 0.171 m vs 0.077 m).", plain: 'The arm is also pushed away from where the hand will be in the next two steps, guessed from how it moved just now, so it moves aside early. Watch the min distance grow compared with none (the claim is a few millimetres at least; the value is shown to 0.1 mm).' },
      { name: 'rnn', paper: '[T] Wu 2022 §5.2', summary: 'The SimpleRNN predictor (15 tanh units, 0.5 s ahead) in place of constant velocity.', plain: 'A small neural network, trained on reaching motions, guesses where the hand will be half a second ahead. It helps when the hand moves as in its training and not otherwise. Compare the min distance with constant-velocity (shown to 0.1 mm: the two can differ by less than a millimetre).' },
    ],
    params: [
      { name: 'Speed', unit: '×', default: '1×', doc: 'Simulated seconds per real second.' },
      { name: 'Predictor', unit: '', default: 'constant-velocity', doc: 'How the hand is forecast (changes live).' },
      { name: 'Hand motion', unit: '', default: '', doc: 'The preset reach, its speed (m/s) and seed.' },
      { name: 'Target sliders', unit: 'm', default: '', doc: 'Where the end effector goes.' },
    ],
    shortcuts: [
      { keys: 'Space', action: 'play / pause' },
      { keys: '.', action: 'one sample (0.1 s)' },
      { keys: 'R', action: 'reset' },
      { keys: 'drag', action: 'orbit the 3D view' },
    ],
  };
}

/** Keeps HelpParam exported for pages that add their own. */
export type { HelpParam };
