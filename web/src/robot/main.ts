// Robot page wiring: loads a scenario into a wasm SimHandle, steps it from
// the animation frame at the chosen speed, and paints what it reports (DWA
// fan, paths, goals, movers with their classes, the robot, its trail) plus
// the v/ω/clearance plots and the metrics. User edits (goal, movers,
// planner and its parameters) go to the SimHandle as scenario edits; this
// file plans, collides and measures nothing itself.

import init, { SimHandle, planners as plannerListJson, rosImageName } from '../../pkg/planlab_wasm.js';
import presets from 'virtual:robot-presets';
import { fillPresetSelect } from '../shell/preset-select';
import { RobotView, emptyScene, CLASS_NAMES, COLORS, type RobotShape } from './view';
import { SeriesPlots } from './plots';
import { ParamPanel, type PlannerInfo } from './params';
import { applyRun, runParams, variantParams } from '../shell/runlink';
import { loadVariant } from '../shell/variant';
import { installShell } from '../shell/help';
import { robotHelp } from '../shell/help-content';
import { showGalleryNote } from '../shell/gallery-note';
import { Timeline } from './timeline';
import { Editor, type EditTool } from './edit';
import { FilesMenu } from './files';
import { el, messageOf, errorBanner } from '../shell/dom';
import { appendTrail, lidarOf, pullState } from './pull';

type Tool = 'goal' | 'mover' | 'remove' | EditTool;

/** A mover the user placed, kept so that Reset puts it back (at t = 0). */
interface Placement {
  id: number;
  model: string;
  radius: number;
  x: number;
  y: number;
  vx: number;
  vy: number;
  span: number;
}

interface MoverJson {
  id: number;
  radius: number;
  motion: { model: string };
}

/** Most control steps run in one animation frame (8× on a 0.1 s step is
 *  80 steps/s, about 1.3 a frame). */
const MAX_STEPS_PER_FRAME = 8;
/** Simulation time budget per frame, ms: when the steps due would take
 *  longer (a slow machine, a heavy planner) the sim runs slower than the
 *  chosen speed instead of dropping frames. */
const SIM_BUDGET_MS = 6;
/** Metrics, mover list and status refresh interval while running, ms. */
const SLOW_REFRESH_MS = 250;



const ui = {
  body: document.body,
  hint: el('hint'),
  preset: el<HTMLSelectElement>('preset'),
  file: el<HTMLInputElement>('file-input'),
  description: el('scenario-description'),
  mapSize: el('map-size'),
  robotDesc: el('robot-desc'),
  simDt: el('sim-dt'),
  play: el<HTMLButtonElement>('play'),
  step: el<HTMLButtonElement>('step'),
  reset: el<HTMLButtonElement>('reset'),
  speed: el<HTMLSelectElement>('speed'),
  speedOut: el<HTMLOutputElement>('speed-out'),
  showFan: el<HTMLInputElement>('show-fan'),
  showPath: el<HTMLInputElement>('show-path'),
  showTrail: el<HTMLInputElement>('show-trail'),
  showLidar: el<HTMLInputElement>('show-lidar'),
  showFog: el<HTMLInputElement>('show-fog'),
  lidarLegend: el('lidar-legend'),
  planner: el<HTMLSelectElement>('planner'),
  plannerSummary: el('planner-summary'),
  params: el('params'),
  paramsDefault: el<HTMLButtonElement>('params-default'),
  tools: Array.from(document.querySelectorAll<HTMLButtonElement>('#tools [data-tool]')),
  motionModel: el<HTMLSelectElement>('motion-model'),
  moverRadius: el<HTMLInputElement>('mover-radius'),
  moverSpan: el<HTMLInputElement>('mover-span'),
  spanField: el('span-field'),
  moverList: el<HTMLUListElement>('mover-list'),
  clearMovers: el<HTMLButtonElement>('clear-movers'),
  error: el('error'),
  status: el('status'),
  canvas: el<HTMLCanvasElement>('sim-canvas'),
  hover: el('hover'),
  metric: {
    outcome: el('metric-outcome'),
    time: el('metric-time'),
    length: el('metric-length'),
    clearance: el('metric-clearance'),
    turn: el('metric-turn'),
    drops: el('metric-drops'),
    tracking: el('metric-tracking'),
    mode: el('metric-mode'),
  },
};

// ------------------------------------------------------------------ errors
const { showError, clearError, guard } = errorBanner(ui.error, ui.body);

// ------------------------------------------------------------------- state
const view = new RobotView(ui.canvas);
const plots = new SeriesPlots({
  v: el('plot-v'),
  w: el('plot-w'),
  clearance: el('plot-clearance'),
  tracking: el('plot-tracking'),
  loads: el('plot-loads'),
});
let sim: SimHandle | null = null;
let infos = new Map<string, PlannerInfo>();
/** The loaded scenario's text and label, for Reset. */
let scenarioText = '';
let scenarioLabel = '';
let scenarioFiles: Record<string, Uint8Array> = {};
/** Edits made since loading, replayed by Reset. */
let goalEdit: [number, number] | null = null;
let plannerEdit: { name: string; config: Record<string, unknown> } | null = null;
let placed: Placement[] = [];
let removed = new Set<number>();
let tool: Tool = 'goal';
let playing = false;
let speed = 1;
let accum = 0;
let lastFrame = 0;
let lastSlow = 0;
let dt = 0.1;
let outcome = 'running';
let drag: { x: number; y: number; pointer: number } | null = null;
let panning: { x: number; y: number } | null = null;
let plannerQueued = false;

/** Frame meter: rAF intervals and per-frame work (sim + paint), ms. */
const meter = {
  intervals: [] as number[],
  work: [] as number[],
  sim: [] as number[],
  paint: [] as number[],
  reset() {
    this.intervals.length = 0;
    this.work.length = 0;
    this.sim.length = 0;
    this.paint.length = 0;
  },
};
let paintMs = 0;
view.onPaint = (ms) => (paintMs = ms);

const timeline = new Timeline(el('timeline'), {
  sim: () => sim,
  view,
  plots,
  pause: () => playing && setPlaying(false),
  branch: (next) => install(next),
  refreshLive: () => pull(),
  speed: () => speed,
});

// Map editing, start, mover paths, generators, undo/redo (edit.ts).
const editor = new Editor({
  sim: () => sim,
  view,
  refresh: () => sim && install(sim, true),
  showError,
  clearError,
  setTool: (t) => setTool(t as Tool),
});

const params = new ParamPanel(ui.params, (config) => {
  if (!sim) return;
  plannerEdit = { name: ui.planner.value, config };
  schedulePlanner();
});

// ------------------------------------------------------------------ scene
/** Footprint, a one-line description and whether the drive is omnidirectional. */
function robotShape(json: string): [RobotShape, string, boolean] {
  const r = JSON.parse(json) as {
    drive?: string;
    footprint?: { shape?: string; radius?: number; length?: number; width?: number };
    limits?: { v_max?: number };
  };
  const fp = r.footprint ?? {};
  const shape: RobotShape =
    fp.shape === 'rectangle'
      ? { kind: 'rect', length: fp.length ?? 0.4, width: fp.width ?? 0.3 }
      : { kind: 'circle', radius: fp.radius ?? 0.2 };
  const size = shape.kind === 'circle' ? `⌀ ${(2 * shape.radius).toFixed(2)} m` : `${shape.length}×${shape.width} m`;
  const vmax = r.limits?.v_max;
  return [shape, `${r.drive ?? '?'} · ${size}${vmax !== undefined ? ` · ≤ ${vmax} m/s` : ''}`, r.drive === 'omnidirectional'];
}

/** Copies what the SimHandle reports into the scene (after steps/edits). */
function pull(): void {
  if (!sim) return;
  const S = view.scene;
  pullState(sim, S);
  pullLidar();
  appendTrail(sim, S);
  plots.pull(sim, S.globalPath);
  outcome = sim.outcome;
  ui.body.dataset.outcome = outcome;
  ui.body.dataset.steps = String(sim.steps);
  ui.body.dataset.time = String(sim.time);
  timeline.afterPull();
}

/** LiDAR layers and the fog of war (LiDAR planners only). */
function pullLidar(): void {
  if (!sim) return;
  const S = view.scene;
  const has = sim.hasLidar;
  ui.lidarLegend.hidden = !has;
  ui.body.dataset.lidar = has ? '1' : '0';
  if (!has) {
    S.lidar = null;
    S.seen = null;
    S.seenCount = 0;
    return;
  }
  S.lidar = lidarOf(sim);
  const count = sim.seenCount;
  if (count !== S.seenCount || S.seen === null) {
    S.seen = sim.seenCells();
    S.seenCount = count;
  }
  ui.body.dataset.seen = String(count);
}


// ----------------------------------------------------------------- metrics
function setMetric(e: HTMLElement, text: string, value: number | null): void {
  e.textContent = text;
  if (value === null) delete e.dataset.value;
  else e.dataset.value = String(value);
}

function clearMetrics(): void {
  for (const e of Object.values(ui.metric)) setMetric(e, '—', null);
  delete ui.metric.outcome.dataset.outcome;
}

interface Metrics {
  outcome: string;
  time_s: number;
  path_length_m: number;
  min_clearance_m: number;
  mean_clearance_m: number;
  total_turn_rad: number;
  max_turn_rad: number;
  speed_drops: number;
  mean_tracking_error_m: number | null;
  max_tracking_error_m: number | null;
}

function refreshSlow(): void {
  if (!sim) return;
  const m = JSON.parse(sim.metricsJson()) as Metrics;
  setMetric(ui.metric.outcome, m.outcome, null);
  ui.metric.outcome.dataset.outcome = m.outcome;
  setMetric(ui.metric.time, `${m.time_s.toFixed(1)} s`, m.time_s);
  setMetric(ui.metric.length, `${m.path_length_m.toFixed(2)} m`, m.path_length_m);
  setMetric(ui.metric.clearance, `${m.min_clearance_m.toFixed(2)} / ${m.mean_clearance_m.toFixed(2)}`, m.min_clearance_m);
  ui.metric.clearance.dataset.mean = String(m.mean_clearance_m);
  setMetric(ui.metric.turn, `${m.total_turn_rad.toFixed(2)} / ${m.max_turn_rad.toFixed(2)}`, m.total_turn_rad);
  ui.metric.turn.dataset.max = String(m.max_turn_rad);
  setMetric(ui.metric.drops, String(m.speed_drops), m.speed_drops);
  if (m.mean_tracking_error_m === null || m.max_tracking_error_m === null) setMetric(ui.metric.tracking, 'n/a', null);
  else {
    setMetric(ui.metric.tracking, `${m.mean_tracking_error_m.toFixed(2)} / ${m.max_tracking_error_m.toFixed(2)}`, m.mean_tracking_error_m);
    ui.metric.tracking.dataset.max = String(m.max_tracking_error_m);
  }
  const mode = sim.mode;
  setMetric(ui.metric.mode, `${mode || '—'} · ${sim.goalKind}`, null);
  ui.metric.mode.title = ui.metric.mode.textContent ?? '';
  const s = view.scene.state;
  ui.status.textContent =
    `t = ${sim.time.toFixed(1)} s · v = ${s[3].toFixed(2)} m/s · ω = ${s[5].toFixed(2)} rad/s · ` +
    `${view.scene.movers.length / 6} movers · ${Math.max(0, view.scene.fan.offsets.length - 1)} rollouts` +
    (outcome === 'running' ? (playing ? ' · playing' : ' · paused') : ` · ${describeOutcome(outcome)}`);
  renderMoverList();
}

function describeOutcome(o: string): string {
  switch (o) {
    case 'reached':
      return 'goal reached';
    case 'collision':
      return 'collision';
    case 'timeout':
      return 'time out';
    case 'stuck':
      return 'stuck (no progress)';
    default:
      return o;
  }
}

/** What the mover list shows, to rebuild it only when that changes (a
 *  rebuild under the pointer would swallow a click on ×). */
let moverListKey = '';

function renderMoverList(): void {
  if (!sim) return;
  const json = sim.moversJson();
  const key = `${json}|${Array.from(view.scene.classes).join(';')}`;
  if (key === moverListKey) return;
  moverListKey = key;
  const movers = JSON.parse(json) as MoverJson[];
  const items = movers.map((m) => {
    const li = document.createElement('li');
    li.dataset.id = String(m.id);
    const dot = document.createElement('i');
    dot.className = 'dot';
    const cls = view.scene.classes.get(m.id);
    dot.style.background = COLORS.classes[cls ?? 3];
    const text = document.createElement('span');
    text.textContent = `#${m.id} · ${m.motion.model} · r ${m.radius} m${cls !== undefined ? ` · ${CLASS_NAMES[cls]}` : ''}`;
    const b = document.createElement('button');
    b.type = 'button';
    b.textContent = '×';
    b.title = `Remove mover ${m.id}`;
    b.addEventListener('click', guard(() => removeMover(m.id)));
    li.append(dot, text, b);
    return li;
  });
  ui.moverList.replaceChildren(...items);
}

// ------------------------------------------------------------- simulation
function setPlaying(on: boolean): void {
  playing = on && !!sim && outcome === 'running';
  ui.play.textContent = playing ? '❚❚ Pause' : '▶ Play';
  ui.play.dataset.playing = String(playing);
  ui.body.dataset.playing = String(playing);
  // The status line and metrics say what state the run is in right away.
  if (sim) {
    refreshSlow();
    plots.flush(true);
  }
  if (playing) {
    lastFrame = performance.now();
    accum = 0;
    meter.reset();
    requestAnimationFrame(frame);
  }
}

/** Running mean of one control step's cost, ms (for the frame budget). */
let stepMs = 1;

/** Runs up to `n` control steps (at least one) within the frame budget and
 *  refreshes everything that follows from them; returns how many ran. */
function advance(n: number, budgetMs = Infinity): number {
  if (!sim || n <= 0) return 0;
  const t0 = performance.now();
  let done = 0;
  while (done < n && outcome === 'running') {
    if (done > 0 && performance.now() - t0 + stepMs > budgetMs) break;
    const t = performance.now();
    outcome = sim.step(1);
    stepMs = 0.8 * stepMs + 0.2 * (performance.now() - t);
    done += 1;
  }
  pull();
  if (outcome !== 'running') finish();
  return done;
}

function finish(): void {
  setPlaying(false);
  plots.flush(true);
  refreshSlow();
  if (sim) ui.body.dataset.traceHash = sim.traceHash();
  ui.body.dataset.state = 'done';
  ui.hint.textContent = `Episode over: ${describeOutcome(outcome)}. Reset to run it again.`;
}

function frame(now: number): void {
  if (!playing || !sim) return;
  requestAnimationFrame(frame);
  const interval = now - lastFrame;
  lastFrame = now;
  const t0 = performance.now();
  try {
    accum += (Math.min(interval, 100) / 1000) * speed;
    const due = Math.floor(accum / dt + 1e-9);
    const n = Math.min(due, MAX_STEPS_PER_FRAME);
    const ran = n > 0 ? advance(n, SIM_BUDGET_MS) : 0;
    // Steps that did not fit are dropped, not owed: the sim slows down.
    accum = ran < due ? 0 : accum - ran * dt;
    const t1 = performance.now();
    plots.flush();
    // Everything drawn changes only when the sim steps (edits and view
    // changes ask for their own paint), so frames without a step are free.
    paintMs = 0;
    if (ran > 0) view.paint();
    if (now - lastSlow > SLOW_REFRESH_MS) {
      lastSlow = now;
      refreshSlow();
    }
    const t2 = performance.now();
    if (meter.intervals.length < 100000) {
      meter.intervals.push(interval);
      meter.sim.push(t1 - t0);
      if (ran > 0) meter.paint.push(paintMs);
      meter.work.push(t2 - t0);
    }
  } catch (e) {
    setPlaying(false);
    showError(messageOf(e));
  }
}

function install(next: SimHandle, keepView = false): void {
  setPlaying(false);
  // An edit changes the handle in place: the same object comes back.
  if (sim !== next) sim?.free();
  sim = next;
  dt = sim.dt;
  const map = sim.map();
  try {
    const origin = map.origin();
    view.scene = { ...emptyScene(), show: view.scene.show };
    view.setMap({
      width: map.width,
      height: map.height,
      resolution: map.resolution,
      originX: origin[0],
      originY: origin[1],
      cells: map.cells(),
    }, keepView);
    ui.mapSize.textContent = `${map.width} × ${map.height} · ${map.resolution} m`;
  } finally {
    map.free();
  }
  const [shape, desc, omni] = robotShape(sim.robot());
  view.scene.robot = shape;
  const st = sim.start();
  view.scene.start = [st[0], st[1], st[2]];
  ui.robotDesc.textContent = desc;
  ui.robotDesc.title = desc;
  ui.simDt.textContent = `${dt} s`;
  const choice = JSON.parse(sim.plannerChoice()) as { name: string; config: Record<string, unknown> };
  selectPlanner(choice.name, choice.config);
  plots.clear(omni, sim.hasVehicle);
  clearMetrics();
  FilesMenu.forgetNote();
  delete ui.body.dataset.traceHash;
  outcome = sim.outcome;
  pull();
  refreshSlow();
  plots.flush(true);
  view.request();
  ui.body.dataset.state = 'ready';
  ui.body.dataset.loadSeq = String(Number(ui.body.dataset.loadSeq ?? 0) + 1);
  ui.hint.textContent = hintForTool();
  editor.installed();
}

/** Loads scenario JSON as a fresh episode (edits forgotten); `files` holds
 *  the map files it refers to, by base name. */
function loadScenario(text: string, label: string, files: Record<string, Uint8Array> = {}): void {
  const next = SimHandle.fromScenario(text, files);
  scenarioText = text;
  scenarioFiles = files;
  scenarioLabel = label;
  goalEdit = null;
  plannerEdit = null;
  placed = [];
  removed = new Set();
  editor.reset();
  clearError();
  try {
    const s = JSON.parse(text) as { name?: string; description?: string };
    ui.description.textContent = s.description || s.name || label;
    ui.description.title = s.description ?? '';
  } catch {
    ui.description.textContent = label;
  }
  install(next);
  filesMenu.noteLoaded(text, label);
}

/** Restarts from the scenario with the goal, movers and planner edits. */
function resetEpisode(): void {
  if (!scenarioText) return;
  // After map edits the SimHandle holds the edited scenario: restart it.
  if (editor.dirty && sim) {
    sim.restart();
    install(sim, true);
    clearError();
    return;
  }
  const next = SimHandle.fromScenario(scenarioText, scenarioFiles);
  const problems: string[] = [];
  const attempt = (what: string, f: () => void) => {
    try {
      f();
    } catch (e) {
      problems.push(`${what}: ${messageOf(e)}`);
    }
  };
  if (plannerEdit) {
    const p = plannerEdit;
    attempt('planner', () => next.setPlanner(p.name, JSON.stringify(p.config)));
  }
  if (goalEdit) {
    const g = goalEdit;
    attempt('goal', () => next.setGoal(g[0], g[1]));
  }
  if (removed.size) {
    const keep = (JSON.parse(next.moversJson()) as MoverJson[]).filter((m) => !removed.has(m.id));
    attempt('movers', () => next.setMovers(JSON.stringify(keep)));
  }
  for (const p of placed) {
    attempt(`mover ${p.id}`, () => {
      p.id = next.placeMover(p.model, p.radius, p.x, p.y, p.vx, p.vy, p.span);
    });
  }
  install(next);
  if (problems.length) showError(problems.join(' · '));
  else clearError();
  void scenarioLabel;
}

// --------------------------------------------------------------- planners
function selectPlanner(name: string, config: Record<string, unknown>): void {
  if (!Array.from(ui.planner.options).some((o) => o.value === name)) {
    const o = document.createElement('option');
    o.value = name;
    o.textContent = name;
    ui.planner.append(o);
  }
  ui.planner.value = name;
  const info = infos.get(name) ?? { name, paper: '', summary: '', fields: [] };
  ui.plannerSummary.textContent = [info.summary, info.paper].filter(Boolean).join(' — ') || '—';
  params.show(info, config);
}

function schedulePlanner(): void {
  if (plannerQueued) return;
  plannerQueued = true;
  requestAnimationFrame(() => {
    plannerQueued = false;
    if (!sim || !plannerEdit) return;
    try {
      sim.setPlanner(plannerEdit.name, JSON.stringify(plannerEdit.config));
      clearError();
      pull();
      view.request();
    } catch (e) {
      showError(messageOf(e));
    }
  });
}

// ------------------------------------------------------------------ movers
function removeMover(id: number): void {
  if (!sim) return;
  const s = sim;
  const keep = (JSON.parse(s.moversJson()) as MoverJson[]).filter((m) => m.id !== id);
  editor.recorded(`removing mover ${id}`, () => s.setMovers(JSON.stringify(keep)), false);
  const before = placed.length;
  placed = placed.filter((p) => p.id !== id);
  if (placed.length === before) removed.add(id);
  pull();
  refreshSlow();
  view.request();
}

function num(input: HTMLInputElement): number {
  return input.value.trim() === '' ? Number.NaN : Number(input.value);
}

function placeMover(x: number, y: number, vx: number, vy: number): void {
  if (!sim) return;
  // A tiny drag is a click: a standing mover.
  if (Math.hypot(vx, vy) < 0.02) {
    vx = 0;
    vy = 0;
  }
  const p: Placement = {
    id: -1,
    model: ui.motionModel.value,
    radius: num(ui.moverRadius),
    x,
    y,
    vx,
    vy,
    span: num(ui.moverSpan),
  };
  const s = sim;
  editor.recorded('mover', () => (p.id = s.placeMover(p.model, p.radius, p.x, p.y, p.vx, p.vy, p.span)), false);
  placed.push(p);
  clearError();
  pull();
  refreshSlow();
  view.request();
  ui.body.dataset.movers = String(view.scene.movers.length / 6);
}

/** The mover under a canvas point (within its disc or 6 px of it). */
function moverAt(cx: number, cy: number): number | null {
  const m = view.scene.movers;
  let best: number | null = null;
  let bestD = Infinity;
  for (let i = 0; i + 5 < m.length; i += 6) {
    const [x, y] = view.toScreen(m[i + 2], m[i + 3]);
    const d = Math.hypot(cx - x, cy - y) - m[i + 1] * view.scale;
    if (d < 6 && d < bestD) {
      bestD = d;
      best = m[i];
    }
  }
  return best;
}

// ------------------------------------------------------------------- input
function hintForTool(): string {
  switch (tool) {
    case 'goal':
      return 'Click the map to move the goal, even while the robot runs.';
    case 'mover':
      return 'Press where a mover should be and drag toward where it will be in 1 s.';
    case 'remove':
      return 'Click a mover to remove it.';
    default:
      return ''; // edit.ts's tools set their own hint
  }
}

function setTool(t: Tool): void {
  tool = t;
  for (const b of ui.tools) b.setAttribute('aria-checked', String(b.dataset.tool === t));
  ui.canvas.dataset.tool = t;
  ui.hint.textContent = hintForTool();
}

function canvasPoint(ev: MouseEvent): [number, number] {
  const r = ui.canvas.getBoundingClientRect();
  return [ev.clientX - r.left, ev.clientY - r.top];
}

function moveGoal(x: number, y: number): void {
  if (!sim) return;
  const s = sim;
  editor.recorded('goal', () => s.setGoal(x, y), false);
  goalEdit = [x, y];
  clearError();
  pull();
  view.request();
  ui.body.dataset.goal = `${x},${y}`;
}

ui.canvas.addEventListener(
  'pointerdown',
  guard((ev: PointerEvent) => {
    if (!sim) return;
    if (ev.button === 1 || ev.button === 2 || (ev.button === 0 && ev.altKey)) {
      panning = { x: ev.clientX, y: ev.clientY };
      ui.canvas.classList.add('panning');
      ui.canvas.setPointerCapture(ev.pointerId);
      ev.preventDefault();
      return;
    }
    if (ev.button !== 0) return;
    const [cx, cy] = canvasPoint(ev);
    const [x, y] = view.toWorld(cx, cy);
    if ((ev.shiftKey && !['rect', 'disc', 'wall', 'erase'].includes(tool)) || tool === 'goal') {
      moveGoal(x, y);
    } else if (tool === 'mover') {
      if (!view.onMap(x, y)) return;
      drag = { x, y, pointer: ev.pointerId };
      ui.canvas.setPointerCapture(ev.pointerId);
      view.scene.preview = { x, y, vx: 0, vy: 0, radius: num(ui.moverRadius) || 0.1 };
      view.request();
    } else if (tool === 'remove') {
      const id = moverAt(cx, cy);
      if (id !== null) removeMover(id);
    }
  }),
);

ui.canvas.addEventListener(
  'pointermove',
  guard((ev: PointerEvent) => {
    if (panning) {
      view.panBy(ev.clientX - panning.x, ev.clientY - panning.y);
      panning = { x: ev.clientX, y: ev.clientY };
      return;
    }
    const [cx, cy] = canvasPoint(ev);
    const [x, y] = view.toWorld(cx, cy);
    ui.hover.textContent = view.onMap(x, y) ? `world (${x.toFixed(2)}, ${y.toFixed(2)}) m` : '—';
    if (drag && view.scene.preview) {
      view.scene.preview.vx = x - drag.x;
      view.scene.preview.vy = y - drag.y;
      view.request();
    }
  }),
);

const endPointer = guard((ev: PointerEvent) => {
  panning = null;
  ui.canvas.classList.remove('panning');
  if (ui.canvas.hasPointerCapture(ev.pointerId)) ui.canvas.releasePointerCapture(ev.pointerId);
  if (drag && ev.pointerId === drag.pointer) {
    const d = drag;
    drag = null;
    const p = view.scene.preview;
    view.scene.preview = null;
    view.request();
    if (ev.type === 'pointerup' && p) placeMover(d.x, d.y, p.vx, p.vy);
  }
});
ui.canvas.addEventListener('pointerup', endPointer);
ui.canvas.addEventListener('pointercancel', endPointer);
ui.canvas.addEventListener('pointerleave', () => (ui.hover.textContent = '—'));
ui.canvas.addEventListener('contextmenu', (ev) => ev.preventDefault());
ui.canvas.addEventListener(
  'wheel',
  (ev) => {
    ev.preventDefault();
    const [x, y] = canvasPoint(ev);
    view.zoomAt(x, y, Math.exp(-ev.deltaY * 0.0015));
  },
  { passive: false },
);

for (const b of ui.tools) b.addEventListener('click', () => setTool(b.dataset.tool as Tool));

ui.play.addEventListener(
  'click',
  guard(() => {
    // From a past frame of the timeline: branch there and go on.
    if (!playing && timeline.scrubbed) timeline.branchHere();
    else if (!playing && outcome !== 'running') resetEpisode();
    setPlaying(!playing);
  }),
);
ui.step.addEventListener(
  'click',
  guard(() => {
    setPlaying(false);
    if (timeline.scrubbed) timeline.branchHere();
    advance(1);
    plots.flush(true);
    refreshSlow();
    view.request();
  }),
);
ui.reset.addEventListener('click', guard(() => resetEpisode()));
ui.speed.addEventListener('input', () => {
  speed = Number(ui.speed.value) || 1;
  ui.speedOut.textContent = `${speed}×`;
});
for (const [box, key] of [
  [ui.showFan, 'fan'],
  [ui.showPath, 'path'],
  [ui.showTrail, 'trail'],
  [ui.showLidar, 'lidar'],
  [ui.showFog, 'fog'],
] as const) {
  box.addEventListener(
    'change',
    guard(() => {
      view.scene.show[key] = box.checked;
      if (key === 'fan') sim?.setRecordRollouts(box.checked);
      pull();
      view.request();
    }),
  );
}
ui.planner.addEventListener(
  'change',
  guard(() => {
    if (!sim) return;
    const name = ui.planner.value;
    const prev = JSON.parse(sim.plannerChoice()) as { name: string; config: Record<string, unknown> };
    try {
      sim.setPlanner(name, '{}');
    } catch (e) {
      selectPlanner(prev.name, prev.config);
      throw e;
    }
    plannerEdit = { name, config: {} };
    selectPlanner(name, {});
    clearError();
    pull();
    view.request();
  }),
);
ui.paramsDefault.addEventListener('click', guard(() => params.resetDefaults()));
ui.motionModel.addEventListener('input', () => {
  ui.spanField.dataset.dim = String(ui.motionModel.value === 'constant-velocity');
});
ui.clearMovers.addEventListener(
  'click',
  guard(() => {
    if (!sim) return;
    for (const m of JSON.parse(sim.moversJson()) as MoverJson[]) {
      if (!placed.some((p) => p.id === m.id)) removed.add(m.id);
    }
    placed = [];
    const s = sim;
    editor.recorded('removing all movers', () => s.setMovers('[]'), false);
    pull();
    refreshSlow();
    view.request();
  }),
);

async function fetchText(path: string): Promise<string> {
  const r = await fetch(new URL(path, document.baseURI));
  if (!r.ok) throw new Error(`cannot load ${path}: HTTP ${r.status}`);
  return r.text();
}

async function fetchBytes(url: URL): Promise<Uint8Array> {
  const r = await fetch(url);
  if (!r.ok) throw new Error(`cannot load ${url.pathname}: HTTP ${r.status}`);
  return new Uint8Array(await r.arrayBuffer());
}

const baseName = (p: string) => p.split(/[\\/]/).pop() ?? p;

/** The map files a preset refers to (a ROS yaml brings its image), fetched
 *  relative to the scenario, keyed by base name as SimHandle looks them up. */
async function mapFilesOf(text: string, scenarioUrl: URL): Promise<Record<string, Uint8Array>> {
  let ref: unknown;
  try {
    ref = (JSON.parse(text) as { map?: { file?: unknown } }).map?.file;
  } catch {
    return {}; // SimHandle reports the JSON error with its position
  }
  if (typeof ref !== 'string') return {};
  const files: Record<string, Uint8Array> = {};
  const url = new URL(ref, scenarioUrl);
  files[baseName(ref)] = await fetchBytes(url);
  if (/\.ya?ml$/i.test(ref)) {
    const image = rosImageName(new TextDecoder().decode(files[baseName(ref)]));
    files[baseName(image)] = await fetchBytes(new URL(image, url));
  }
  return files;
}

async function loadPreset(file: string, edit: (text: string) => string = (t) => t): Promise<void> {
  const url = new URL(`scenarios/${file}`, document.baseURI);
  try {
    const text = await fetchText(`scenarios/${file}`);
    loadScenario(edit(text), file, await mapFilesOf(text, url));
  } catch (e) {
    throw new Error(`${file}: ${messageOf(e)}`);
  }
}

ui.preset.addEventListener(
  'change',
  guard(async () => {
    if (ui.preset.value) await loadPreset(ui.preset.value);
  }),
);
// Open (file button, drop on the canvas), save, share: files.ts.
const filesMenu = new FilesMenu({
  sim: () => sim,
  load: (text, label, files) => loadScenario(text, label, files),
  scene: () => view.scene,
  canvas: ui.canvas,
  showError,
  clearError,
});

window.addEventListener('keydown', (ev) => {
  const t = ev.target as HTMLElement | null;
  if (t && (t.tagName === 'INPUT' || t.tagName === 'SELECT' || t.tagName === 'TEXTAREA')) return;
  if (ev.ctrlKey || ev.metaKey || ev.altKey) return;
  const k = ev.key.toLowerCase();
  const tools: Record<string, Tool> = { g: 'goal', m: 'mover', x: 'remove' };
  if (tools[k]) setTool(tools[k]);
  else if (k === ' ') {
    ev.preventDefault();
    ui.play.click();
  } else if (k === '.') ui.step.click();
  else if (k === 'r') ui.reset.click();
  else if (k === 'f') view.fit();
});

// ------------------------------------------------------------ test hooks
function quantile(xs: number[], q: number): number {
  if (!xs.length) return Number.NaN;
  const s = [...xs].sort((a, b) => a - b);
  return s[Math.min(s.length - 1, Math.floor(q * (s.length - 1) + 0.5))];
}

/** For the e2e tests and the curious: frame statistics and the trace. */
(window as unknown as { planlabRobot: unknown }).planlabRobot = {
  frameStats() {
    const f = (xs: number[]) => ({ median: quantile(xs, 0.5), p95: quantile(xs, 0.95), max: Math.max(...xs) });
    return {
      frames: meter.intervals.length,
      interval: f(meter.intervals.slice(1)),
      work: f(meter.work),
      sim: f(meter.sim),
      paint: f(meter.paint),
    };
  },
  resetMeter: () => meter.reset(),
  traceHash: () => sim?.traceHash() ?? null,
  traceCsv: () => sim?.traceCsv() ?? null,
  metrics: () => (sim ? JSON.parse(sim.metricsJson()) : null),
  toScreen: (x: number, y: number) => {
    const r = ui.canvas.getBoundingClientRect();
    const [sx, sy] = view.toScreen(x, y);
    return { x: r.left + sx, y: r.top + sy };
  },
  state: () => (sim ? Array.from(sim.state()) : null),
  plannerChoice: () => (sim ? JSON.parse(sim.plannerChoice()) : null),
  plannerFields: (name: string) => infos.get(name)?.fields.map((f) => f.name) ?? null,
  movers: () => (sim ? Array.from(sim.movers()) : null),
  rollouts: () => Math.max(0, view.scene.fan.offsets.length - 1),
};

// -------------------------------------------------------------------- boot
async function boot(): Promise<void> {
  setTool('goal');
  clearMetrics();
  ui.spanField.dataset.dim = 'true';
  fillPresetSelect(ui.preset);
  await init();
  const list = JSON.parse(plannerListJson()) as PlannerInfo[];
  infos = new Map(list.map((p) => [p.name, p]));
  for (const p of list) {
    const o = document.createElement('option');
    o.value = p.name;
    o.textContent = p.name;
    o.title = p.summary;
    ui.planner.append(o);
  }
  // A gallery link: preset, planner and `--set` edits of a reproduce run, and `run=1`.
  const link = runParams();
  const q = link.scenario;
  const first = q && presets.some((p) => p.file === q) ? q : presets[0]?.file;
  if (!first) throw new Error('no robot presets (assets/scenarios/*.json with a local_planner)');
  ui.preset.value = first;
  // A share link (#s=…) opens its scenario instead of the first preset.
  let shared: unknown = null;
  try {
    if (await filesMenu.loadFromHash()) return;
  } catch (e) {
    shared = e;
  }
  // A variant link: the registry's tree of that run on that variant (its
  // planner and edits included), instead of the preset; a bad one (unknown
  // id or run, k too large) shows the core's message over the preset.
  let variantError: unknown = null;
  try {
    const variant = variantParams();
    if (variant) {
      const v = await loadVariant(variant);
      const label = `${variant.exp} variant ${variant.k} (${variant.as})`;
      loadScenario(v.text, label, await mapFilesOf(v.text, new URL(`scenarios/${first}`, document.baseURI)));
      ui.body.dataset.variant = String(variant.k);
      if (link.run) ui.play.click();
      return;
    }
  } catch (e) {
    variantError = e;
  }
  await loadPreset(first, first === q ? (t) => applyRun(t, link.planner, link.set) : undefined);
  if (variantError !== null) showError(`Could not open the variant: ${messageOf(variantError)}`);
  else if (first === q && link.run) ui.play.click();
  if (shared !== null) showError(`Could not open the shared link: ${messageOf(shared)}`);
}

// Help overlay (planners and parameters from the wasm registry) and presentation mode.
installShell(() => robotHelp([...infos.values()], ui.planner.value));
showGalleryNote();

boot().catch((e) => {
  ui.body.dataset.state = 'error';
  showError(`Could not start the robot playground: ${messageOf(e)}`);
});
