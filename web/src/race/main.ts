// The race: one map, one query, 2–4 grid planners side by side. Each lane
// plans through its own wasm PlanSession with the search recorded, then the
// lanes play in step: every animation frame gives each lane the same budget
// of search events, so a planner that needs fewer events finishes first.
// The table compares the counters; the winners are the fewest expanded
// cells and the lowest path cost. A lane can also run a sampling planner
// (RRT … BIT*): a seeded run to the stated iteration budget, whose events
// (samples, tree edges, rewirings) play in step with the searches'. Nothing
// here plans.

import init, { MapHandle, defaultPlanOptions, gridAlgorithms } from '../../pkg-grid/planlab_wasm.js';
import { MAP_LAYERS, MapView, PLAN_LAYERS } from '../scene/grid-view';
import { DrawList, Layer, mask } from '../scene/draw';
import type { Cell } from '../shell/cells';
import { GridSession } from '../scene/grid-session';
import { loadPreset, type MapHost } from '../shell/grid-maps';
import { SearchPlayback } from '../scene/search-player';
import { SamplingPlayback } from '../scene/sampling-tree';
import { SAMPLING_PLANNERS, isSampling, runSampling, samplingLabel, noPathLine, type SamplingSettings } from '../scene/sampling-run';
import { GRID_PLANNERS, movesNote, plannerLabel } from '../shell/grid-planners';
import { el, errorBanner, messageOf } from '../shell/dom';
import { panZoom } from '../shell/canvas-input';
import { installShell } from '../shell/help';
import { installKeys } from '../shell/keys';
import { raceHelp } from './help';
import type { CorePlanner } from '../shell/help-content';

const ui = {
  body: document.body,
  hint: el('hint'),
  preset: el<HTMLSelectElement>('preset'),
  picks: el('lane-picks'),
  diagonal: el<HTMLSelectElement>('diagonal'),
  seed: el<HTMLInputElement>('race-seed'),
  iterations: el<HTMLInputElement>('race-iterations'),
  speed: el<HTMLSelectElement>('speed'),
  go: el<HTMLButtonElement>('race-go'),
  finish: el<HTMLButtonElement>('race-finish'),
  lanes: el('lanes'),
  table: el<HTMLTableElement>('race-table'),
  winner: el('race-winner'),
  error: el('error'),
  status: el('status'),
};
const { showError, clearError, guard } = errorBanner(ui.error, ui.body, () => (ui.body.dataset.state = 'error'));

interface Lane {
  algorithm: string;
  root: HTMLElement;
  view: MapView;
  session: GridSession;
  playback: SearchPlayback | SamplingPlayback | null;
  /** Time of the lane's plan (wasm call or stepped run), ms. */
  ms: number;
  cost: number;
  pathLen: number;
  error: string | null;
  /** Frame at which its playback ended (null: still going). */
  doneAt: number | null;
}

/** The default line-up; "" = no lane. */
const DEFAULT_PICKS = ['astar', 'dijkstra', 'jps', 'greedy'];
let defaults: Record<string, unknown> = {};
let map: MapHandle | null = null;
let start: Cell | null = null;
let goal: Cell | null = null;
let lanes: Lane[] = [];
let frame = 0;
let racing = false;

const pickers: HTMLSelectElement[] = DEFAULT_PICKS.map((name, i) => {
  const s = document.createElement('select');
  s.id = `pick-${i}`;
  s.setAttribute('aria-label', `Lane ${i + 1} planner`);
  const none = i >= 2 ? '<option value="">— no lane —</option>' : '';
  s.innerHTML =
    none +
    `<optgroup label="Grid searches">${GRID_PLANNERS.map((p) => `<option value="${p.name}">${p.label}</option>`).join('')}</optgroup>` +
    `<optgroup label="Sampling planners (seeded)">${SAMPLING_PLANNERS.map((p) => `<option value="${p.name}">${p.label}</option>`).join('')}</optgroup>`;
  s.value = name;
  ui.picks.append(s);
  return s;
});

function options(algorithm: string): Record<string, unknown> {
  return { ...defaults, algorithm, diagonal: ui.diagonal.value };
}

/** Builds the lanes for the chosen planners on the current map. */
function buildLanes(): void {
  for (const l of lanes) {
    l.view.setSearch(null);
    l.playback?.free();
  }
  lanes = [];
  ui.lanes.replaceChildren();
  if (!map) return;
  for (const algorithm of pickers.map((p) => p.value).filter(Boolean)) {
    const root = document.createElement('div');
    root.className = 'lane';
    root.dataset.algorithm = algorithm;
    root.innerHTML = `<header><b>${laneLabel(algorithm)}</b><span class="lane-counts">—</span></header><div class="lane-error" hidden></div><div class="lane-canvas"><canvas></canvas></div>`;
    ui.lanes.append(root);
    const view = new MapView(root.querySelector('canvas')!);
    view.setMap(new DrawList(map.draw(MAP_LAYERS, undefined, undefined, undefined)));
    const session = new GridSession();
    session.attach(map);
    lanes.push({ algorithm, root, view, session, playback: null, ms: NaN, cost: NaN, pathLen: 0, error: null, doneAt: null });
  }
  ui.lanes.dataset.count = String(lanes.length);
  replan();
}

/** Plans every lane (search recorded) and shows them at step 0. */
function replan(): void {
  racing = false;
  frame = 0;
  for (const l of lanes) {
    if (map) l.view.show(new DrawList(map.draw(mask(Layer.Goals), undefined, start ?? undefined, goal ?? undefined)), mask(Layer.Goals));
    l.view.setSearch(null);
    l.view.setTree(null);
    l.playback?.free();
    l.playback = null;
    l.ms = NaN;
    l.error = null;
    l.doneAt = null;
    l.cost = NaN;
    l.pathLen = 0;
    if (start && goal && isSampling(l.algorithm)) {
      planSampling(l, start, goal);
    } else if (start && goal) {
      try {
        const { result, playback, ms } = l.session.plan(start, goal, options(l.algorithm), true);
        l.ms = ms;
        try {
          l.cost = result.cost;
          l.pathLen = result.pathLen;
          l.view.show(new DrawList(result.draw(map!, PLAN_LAYERS)), PLAN_LAYERS);
        } finally {
          result.free();
        }
        l.playback = playback;
        playback?.seek(0);
      } catch (e) {
        l.error = messageOf(e);
      }
    }
    l.view.setSearch(l.playback instanceof SearchPlayback ? l.playback : null);
    l.view.setTree(l.playback instanceof SamplingPlayback ? l.playback : null);
    const err = l.root.querySelector<HTMLElement>('.lane-error')!;
    err.hidden = l.error === null;
    err.textContent = l.error ?? '';
    showLane(l);
  }
  ui.body.dataset.raceState = 'ready';
  ui.status.textContent = start && goal ? `${lanes.length} planners ready: press Race (Space).` : 'Click a map to place the start, Shift+click for the goal.';
  showTable();
}

/** The race's sampling settings: the seed and iteration budget stated
 *  in the Race card, the core's default robot radius (0.4 cell). */
function samplingSettings(algorithm: string): SamplingSettings {
  const num = (i: HTMLInputElement) => (i.value.trim() === '' ? NaN : Number(i.value));
  return { algorithm, seed: num(ui.seed), radiusM: undefined, budget: { kind: 'iterations', value: num(ui.iterations) }, shortcut: false, allowUnknown: false };
}

/** A sampling lane: the seeded run to its iteration budget. */
function planSampling(l: Lane, s: Cell, g: Cell): void {
  if (!map) return;
  const settings = samplingSettings(l.algorithm);
  try {
    const r = runSampling(map, s, g, settings);
    l.playback = r.playback;
    l.ms = r.ms;
    l.cost = r.cost;
    l.pathLen = r.playback.finalPath.length / 2;
    r.playback.seek(0);
    if (!Number.isFinite(r.cost)) l.error = noPathLine(settings, r);
  } catch (e) {
    l.error = messageOf(e);
  }
}

const laneLabel = (name: string) => (isSampling(name) ? `${samplingLabel(name)} (seed ${ui.seed.value}, ${Number(ui.iterations.value).toLocaleString('en-US')} iterations)` : plannerLabel(name));

function showLane(l: Lane): void {
  const span = l.root.querySelector<HTMLElement>('.lane-counts')!;
  const p = l.playback;
  if (p instanceof SamplingPlayback) {
    const c = p.counters();
    span.textContent = `step ${c.step}/${c.events} · nodes ${c.nodes} · best ${Number.isNaN(c.cost) ? '—' : c.cost.toFixed(2)}`;
    return;
  }
  const c = p?.counters();
  span.textContent = c ? `step ${c.step}/${c.events} · expanded ${c.expanded} · open ${c.open}` : l.error ? 'error' : '—';
}

/** One frame: the same event budget for every lane. */
function tick(): void {
  if (!racing) return;
  frame++;
  const budget = Number(ui.speed.value) || 16;
  let running = 0;
  for (const l of lanes) {
    const p = l.playback;
    if (!p || l.doneAt !== null) continue;
    p.seek(p.step + budget);
    l.view.drawNow();
    showLane(l);
    if (p.done) l.doneAt = frame;
    else running++;
  }
  showTable();
  if (running === 0) {
    racing = false;
    ui.body.dataset.raceState = 'finished';
    ui.status.textContent = `Race finished after ${frame} frames.`;
    showTable();
    return;
  }
  requestAnimationFrame(tick);
}

function go(): void {
  if (!lanes.some((l) => l.playback)) return;
  frame = 0;
  for (const l of lanes) {
    l.playback?.seek(0);
    l.doneAt = null;
    l.view.drawNow();
    showLane(l);
  }
  racing = true;
  ui.body.dataset.raceState = 'racing';
  ui.status.textContent = 'Racing…';
  requestAnimationFrame(tick);
}

/** Every lane played out at once (the frame counts then stay empty). */
function finish(): void {
  racing = false;
  for (const l of lanes) {
    l.playback?.seek(l.playback.n);
    l.view.drawNow();
    showLane(l);
  }
  ui.body.dataset.raceState = 'finished';
  ui.status.textContent = 'Finished: every lane played to its end at once (no frame counts).';
  showTable();
}

/** The results table; winners once every lane has finished. */
function showTable(): void {
  const body = ui.table.tBodies[0];
  body.replaceChildren();
  const finished = ui.body.dataset.raceState === 'finished';
  const ok = lanes.filter((l) => l.playback && !l.error);
  // Expanded cells are a grid search's; a sampling lane counts nodes.
  const searches = ok.filter((l): l is Lane & { playback: SearchPlayback } => l.playback instanceof SearchPlayback);
  const fewest = Math.min(...searches.map((l) => l.playback.counters(l.playback.n).expanded));
  const cheapest = Math.min(...ok.map((l) => l.cost));
  for (const l of lanes) {
    const tr = body.insertRow();
    tr.dataset.algorithm = l.algorithm;
    const p = l.playback;
    const sp = p instanceof SamplingPlayback ? p : null;
    const gp = p instanceof SearchPlayback ? p : null;
    const end = gp ? gp.counters() : null;
    const expandedEnd = gp ? gp.counters(gp.n).expanded : NaN;
    // A lane's result is told once its search has played out, not before
    // the race shows it.
    const told = finished || l.doneAt !== null;
    const cells: [string, boolean][] = [
      [laneLabel(l.algorithm), false],
      [end ? String(end.expanded) : sp ? `${sp.counters().nodes} nodes` : '—', finished && expandedEnd === fewest],
      [end ? String(end.open) : '—', false],
      [p ? String(p.n) : '—', false],
      [l.error ? 'error (see the lane)' : told && Number.isFinite(l.cost) ? l.cost.toFixed(4) : '—', finished && Math.abs(l.cost - cheapest) < 1e-9],
      [l.error || !told ? '—' : String(l.pathLen), false],
      [l.doneAt === null ? '—' : String(l.doneAt), false],
      [Number.isFinite(l.ms) ? l.ms.toFixed(2) : '—', false],
    ];
    for (const [text, best] of cells) {
      const td = tr.insertCell();
      td.textContent = text;
      if (best) td.className = 'best';
    }
  }
  if (!finished || !ok.length) {
    ui.winner.textContent = '—';
    return;
  }
  const names = (xs: Lane[]) => xs.map((l) => (isSampling(l.algorithm) ? samplingLabel(l.algorithm) : plannerLabel(l.algorithm))).join(', ');
  const byExpanded = searches.filter((l) => l.playback.counters(l.playback.n).expanded === fewest);
  const byCost = ok.filter((l) => Math.abs(l.cost - cheapest) < 1e-9);
  // JPS and Theta* expand few cells but scan lines between them: said.
  const lines = byExpanded.map((l) => l.playback.counters(l.playback.n).lines);
  const scans = lines.some((n) => n > 0) ? `, with ${lines.join(' / ')} line checks` : '';
  // A lane whose moves differ from the others' (safe A*'s 24 cells,
  // Theta*'s any angle; the diagonal rule is every lane's) can win on
  // cost without being better: said.
  const caveat = ok
    .filter((l) => l.algorithm === 'safe-astar' || l.algorithm === 'theta-star')
    .map((l) => ` · ${plannerLabel(l.algorithm)}: ${movesNote(options(l.algorithm))?.[0] ?? ''}`)
    .join('');
  // A sampling lane plans a disc in continuous space (any angle, keeping
  // 0.4 cell from walls): said too.
  const sampled = ok.some((l) => isSampling(l.algorithm)) ? ' · sampling lanes: any-angle paths of a round robot, not comparable with A*' : '';
  const expandedText = searches.length ? `Fewest expanded: ${names(byExpanded)} (${fewest}${scans}) · ` : '';
  ui.winner.textContent = `${expandedText}Lowest cost: ${names(byCost)} (${cheapest.toFixed(4)})${caveat}${sampled}`;
  ui.winner.dataset.expanded = byExpanded.map((l) => l.algorithm).join(',');
  ui.winner.dataset.cost = byCost.map((l) => l.algorithm).join(',');
}

const host: MapHost = {
  install(m: MapHandle, _name: string, s: Cell | null, g: Cell | null) {
    map?.free();
    map = m;
    start = s;
    goal = g;
    buildLanes();
    clearError();
    ui.body.dataset.state = 'ok';
  },
  applyOptions: () => {},
  defaults: () => defaults,
};

// Click any lane: start; Shift+click: goal (pan and zoom move every lane).
panZoom(ui.lanes, (c) => (lanes.some((l) => l.view.canvas === c) ? lanes.map((l) => l.view) : null));
ui.lanes.addEventListener(
  'pointerdown',
  guard((ev: PointerEvent) => {
    const lane = lanes.find((l) => l.view.canvas === ev.target);
    if (!lane || ev.button !== 0) return;
    const r = lane.view.canvas.getBoundingClientRect();
    const cell = lane.view.cellAt(ev.clientX - r.left, ev.clientY - r.top);
    if (!cell) return;
    if (ev.shiftKey) goal = cell;
    else start = cell;
    replan();
  }),
);
ui.go.addEventListener('click', guard(go));
ui.finish.addEventListener('click', guard(finish));
// Keys too: in presentation mode the panel with these buttons is folded.
installKeys({ ' ': guard(go), f: guard(finish) });
for (const p of pickers) p.addEventListener('change', guard(buildLanes));
ui.diagonal.addEventListener('change', guard(replan));
// A new seed or budget: new sampling runs (and their lanes' titles).
for (const i of [ui.seed, ui.iterations]) i.addEventListener('change', guard(buildLanes));
ui.preset.addEventListener('change', guard(() => loadPreset(host, ui.preset.value)));

let corePlanners: CorePlanner[] = [];
installShell(() => raceHelp(corePlanners));

async function boot(): Promise<void> {
  await init();
  corePlanners = gridAlgorithms() as CorePlanner[];
  defaults = defaultPlanOptions() as Record<string, unknown>;
  ui.hint.textContent = 'Pick 2–4 planners and press Race.';
  await loadPreset(host, ui.preset.value || 'arena');
}

boot().catch((e) => showError(`Could not start the race: ${messageOf(e)}`));
