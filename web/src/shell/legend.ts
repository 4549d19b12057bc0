// "What am I looking at?": a folded legend under the canvas of the
// simulation pages (and on the gallery) that says in plain words what the
// colours, marks and outcome words mean. Colours come from the same
// constants the canvas is painted with.

import { COLORS } from '../scene/view';
import { COSTMAP_SWATCHES } from '../scene/costmap';
import './legend.css';

type Item = [swatch: string, shape: 'dot' | 'line' | 'star' | 'ring' | 'text', words: string];

const GOALS: Item[] = [
  [COLORS.start, 'dot', 'Start: where the robot begins.'],
  [COLORS.goal, 'dot', 'Goal: where it must get to (click the map to move it).'],
  [COLORS.path, 'line', 'Global path: the route a grid planner (A*, safe A*) found on the map grown by the robot\'s radius. Plain DWA has none.'],
  [COLORS.keypoint, 'star', 'Key points / feature nodes / temporary goal: the corners of the global path the local planner steers to one after another.'],
  [COLORS.virtual, 'ring', 'Virtual goal: a goal the planner invented to get round an obstacle or out of a trap.'],
  [COLORS.trail, 'line', 'Trail: where the robot has driven.'],
];

const FAN: Item[] = [
  ['linear-gradient(90deg,#3b82f6,#f59e0b)', 'line', 'DWA fan: every speed pair the planner tried this step, driven ahead for a second or two. Coloured by the total score, or by the one critic picked in the Critics list: blue low, orange high.'],
  [COLORS.chosen, 'line', 'Chosen rollout: the one the robot actually drives this step.'],
  [COLORS.inadmissible, 'line', 'Grey rollouts would hit something or could not stop in time: not allowed.'],
];

const CLASSES: Item[] = [
  [COLORS.classes[0], 'dot', 'Ordinary dynamic obstacle: moves; the planner predicts where it will be.'],
  [COLORS.classes[1], 'dot', 'Ordinary static obstacle: a mover that stands still; treated like a wall.'],
  [COLORS.classes[2], 'dot', 'Special obstacle (e.g. a person): given a wider berth.'],
  [COLORS.classes[3], 'dot', 'Not classified (the planner does not classify movers).'],
];

const OUTCOMES: Item[] = [
  ['#15803d', 'text', 'goal reached: the robot\'s centre came within the goal tolerance.'],
  ['#b91c1c', 'text', 'collision: the robot\'s outline touched a wall, the map edge or a mover.'],
  ['#b45309', 'text', 'stopped / no progress toward the goal: the distance to the goal did not shrink by 0.2 m for 15 s (60 s on generated maps). "Still moving … circling" means the robot drives but gets no closer; "stopped" means it stands.'],
  ['#b45309', 'text', 'time out: the episode hit its time limit.'],
];

const APF: Item[] = [
  [COLORS.start, 'dot', 'Start.'],
  [COLORS.goal, 'dot', 'Goal: it attracts the robot.'],
  ['#64748b', 'dot', 'Obstacles: each pushes the robot away within its range of influence.'],
  [COLORS.trail, 'line', 'Path: the steps the robot took along the resultant force.'],
  ['#b45309', 'text', 'stuck: the forces cancel (a local minimum) or the robot oscillates without getting closer.'],
];

const ARM: Item[] = [
  ['#475569', 'line', 'The arm: seven joints; the gripper must reach the target.'],
  ['#f472b6', 'dot', 'The hand (the moving obstacle): the arm keeps away from it.'],
  ['#f59e0b', 'line', 'Predicted hand path (with prediction): where the planner expects the hand to be.'],
  ['#334155', 'text', 'Min distance: the closest the arm came to the hand; larger is safer.'],
];

const BARN: Item[] = [
  [COSTMAP_SWATCHES.unknown, 'dot', 'Grey: space the laser has never seen (costmap 255).'],
  [`linear-gradient(90deg,${COSTMAP_SWATCHES.decayLow},${COSTMAP_SWATCHES.decayHigh})`, 'line', 'Pale to deep violet: the cost decaying away from a laser mark (1–252); the planner prefers low cost.'],
  [COSTMAP_SWATCHES.inscribed, 'dot', 'Rose: inscribed (253): the robot\'s centre here would touch an obstacle.'],
  [COSTMAP_SWATCHES.lethal, 'dot', 'Black: a laser mark (254), an obstacle the scans hit.'],
  ['rgba(234, 88, 12, 0.6)', 'line', 'Laser rays: orange where a beam hit something, grey where it saw nothing in range.'],
  ['#0d9488', 'dot', 'True cylinders (toggle): the world as it is; the planner never sees it.'],
  [COLORS.goal, 'dot', 'Goal, with its dashed 1 m success circle.'],
  [COLORS.trail, 'line', 'Trail: where the robot has driven.'],
];

const BARN_OUTCOMES: Item[] = [
  ['#15803d', 'text', 'reached: the robot\'s centre came within 1 m of the goal; scored OT / clip(T, 2·OT, 8·OT).'],
  ['#b91c1c', 'text', 'collision: the robot touched a cylinder; score 0.'],
  ['#b45309', 'text', 'timeout: 100 s went by; score 0.'],
];

const SECTIONS: Record<string, [string, Item[]][]> = {
  barn: [['What the planner knows', BARN], ['How a BARN run ends', BARN_OUTCOMES]],
  robot: [['Goals and paths', GOALS], ['The fan', FAN], ['Obstacle classes (improved DWA)', CLASSES], ['How a run ends', OUTCOMES]],
  compare: [['Goals and paths', GOALS], ['The fan', FAN], ['Obstacle classes (improved DWA)', CLASSES], ['How a run ends', OUTCOMES]],
  gallery: [['On every run page', GOALS], ['The fan', FAN], ['How a run ends', OUTCOMES]],
  apf: [['The scene', APF]],
  arm: [['The scene', ARM]],
};

/** Adds the folded legend of `page` to `parent`, before `before` (null:
 *  at the end), once. */
export function installLegend(page: keyof typeof SECTIONS, parent: Element | null, before: Element | null = null): HTMLDetailsElement | null {
  if (!parent || document.getElementById('explain')) return null;
  const d = document.createElement('details');
  d.className = 'explain';
  d.id = 'explain';
  const s = document.createElement('summary');
  s.textContent = 'What am I looking at?';
  d.append(s);
  const grid = document.createElement('div');
  grid.className = 'explain-grid';
  for (const [title, items] of SECTIONS[page]) {
    const sec = document.createElement('section');
    const h = document.createElement('h3');
    h.textContent = title;
    const ul = document.createElement('ul');
    for (const [sw, shape, words] of items) {
      const li = document.createElement('li');
      const i = document.createElement('i');
      i.className = `explain-swatch ${shape}`;
      if (shape === 'text') i.style.color = sw;
      else i.style.background = sw;
      if (shape === 'text') i.textContent = '●';
      const t = document.createElement('span');
      t.textContent = words;
      li.append(i, t);
      ul.append(li);
    }
    sec.append(h, ul);
    grid.append(sec);
  }
  d.append(grid);
  // Opening or closing changes the room left for the canvas.
  d.addEventListener('toggle', () => window.dispatchEvent(new Event('resize')));
  parent.insertBefore(d, before);
  return d;
}
