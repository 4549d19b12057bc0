// Robot page wiring: loads a scenario into a wasm SimHandle, steps it from
// the animation frame at the chosen speed (shell/sim-clock.ts), and paints
// the core's draw list of each frame (scene/) plus the v/ω/clearance plots
// and the metrics. User edits (goal, movers, planner and its parameters)
// go to the SimHandle as scenario edits, and Reset is the core's restart;
// this file plans, collides and measures nothing itself.

import init, { SimHandle, drawLayerNames, planners as plannerListJson } from '../../pkg/planlab_wasm.js';
import { fillPresetSelect } from '../shell/preset-select';
import { RobotView, emptyScene, mapOf } from '../scene/view';
import { DrawList, Layer, checkLayers, mask } from '../scene/draw';
import { pullLive } from '../scene/pull';
import { SeriesPlots } from './plots';
import type { PlannerInfo } from '../shell/planner-info';
import { PlannerPicker } from './planner';
import { GlobalPicker } from './global';
import { installShell } from '../shell/help';
import { installLegend } from '../shell/legend';
import { robotHelp } from '../shell/help-content';
import { galleryRunEnded, showGalleryNote } from '../shell/gallery-note';
import { Timeline } from './timeline';
import { Editor } from './edit';
import { FilesMenu } from './files';
import { el, messageOf, errorBanner } from '../shell/dom';
import { SimClock } from '../shell/sim-clock';
import { FrameMeter } from '../shell/frame-meter';
import { panZoom } from '../shell/canvas-input';
import { installKeys } from '../shell/keys';
import { bindSpeed } from '../shell/speed';
import { loadPreset, openFirst, type OpenHost } from './open';
import { StatusPanel, endText } from './status';
import { CanvasTools, type Tool } from './tools';
import { CriticsPanel } from './critics';
import { installToggles } from './toggles';
import { installRobotHooks } from './hooks';

/** Most control steps run in one animation frame (8× on a 0.1 s step is
 *  80 steps/s, about 1.3 a frame). */
const MAX_STEPS_PER_FRAME = 8;
/** Simulation time budget per frame, ms (see SimClock). */
const SIM_BUDGET_MS = 6;
/** Metrics, mover list and status refresh interval while running, ms. */
const SLOW_REFRESH_MS = 250;

const ui = {
  body: document.body,
  hint: el('hint'),
  preset: el<HTMLSelectElement>('preset'),
  description: el('scenario-description'),
  play: el<HTMLButtonElement>('play'),
  step: el<HTMLButtonElement>('step'),
  reset: el<HTMLButtonElement>('reset'),
  toEnd: el<HTMLButtonElement>('to-end'),
  speed: el<HTMLSelectElement>('speed'),
  speedOut: el<HTMLOutputElement>('speed-out'),
  lidarLegend: el('lidar-legend'),
  error: el('error'),
  canvas: el<HTMLCanvasElement>('sim-canvas'),
};

const { showError, clearError, guard } = errorBanner(ui.error, ui.body);

// ------------------------------------------------------------------- state
const view = new RobotView(ui.canvas);
// Before the tools' pointer handlers: a pan gesture goes no further.
panZoom(ui.canvas, () => [view]);
const plots = new SeriesPlots({
  v: el('plot-v'),
  w: el('plot-w'),
  clearance: el('plot-clearance'),
  tracking: el('plot-tracking'),
  loads: el('plot-loads'),
});
let sim: SimHandle | null = null;
let outcome = 'running';
let lastSlow = 0;

/** Frame meter: rAF intervals and per-frame work (sim + paint), ms. */
const meter = new FrameMeter();
let paintMs = 0;
view.onPaint = (ms) => (paintMs = ms);

const clock = new SimClock(
  {
    advance: (n, budget) => advance(n, budget),
    afterFrame(ran, now, interval, t0) {
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
      meter.push(interval, t1 - t0, ran > 0 ? paintMs : null, performance.now() - t0);
    },
    onError(e) {
      setPlaying(false);
      showError(messageOf(e));
    },
  },
  MAX_STEPS_PER_FRAME,
  SIM_BUDGET_MS,
);

const timeline = new Timeline(el('timeline'), {
  sim: () => sim,
  view,
  plots,
  pause: () => clock.playing && setPlaying(false),
  branch: (next) => install(next),
  refreshLive: () => pull(),
  speed: () => clock.speed,
});

// Map editing, start, mover paths, generators, undo/redo (edit.ts).
const editor = new Editor({
  sim: () => sim,
  view,
  refresh: () => sim && install(sim, true),
  showError,
  clearError,
  setTool: (t) => tools.set(t as Tool),
});

// The goal and mover tools (tools.ts).
const tools = new CanvasTools({
  sim: () => sim,
  view,
  editor,
  guard,
  refresh: (slow) => {
    clearError();
    pull();
    if (slow) refreshSlow();
    view.request();
  },
});

const status = new StatusPanel(guard((id: number) => tools.remove(id)));

// The planner select and its parameter panel (planner.ts).
const planner = new PlannerPicker({
  sim: () => sim,
  refresh: () => {
    clearError();
    pull();
    view.request();
  },
  showError,
  guard,
});

// The global planner card: none or a Hybrid A* car path (global.ts).
const globalPicker = new GlobalPicker({
  sim: () => sim,
  scenarioJson: () => filesMenu.scenarioJson(),
  load: (text) => loadScenario(text, ui.preset.value || 'scenario'),
  guard,
});

// The critics of the planner in force and what colours the fan (critics.ts).
const critics = new CriticsPanel(el('critics'), el('legend-fan'), {
  changed: (k) => {
    timeline.fanColour(k);
    pull();
    view.request();
  },
});

// ------------------------------------------------------------- simulation
/** Copies what the SimHandle draws into the scene (after steps/edits). */
function pull(): void {
  if (!sim) return;
  const S = view.scene;
  critics.refresh(sim);
  pullLive(sim, S, true);
  const lidar = S.frame.hasLidar();
  ui.lidarLegend.hidden = !lidar;
  ui.body.dataset.lidar = lidar ? '1' : '0';
  if (lidar) ui.body.dataset.seen = String(S.seenCount);
  plots.pull(sim, S.frame.globalPath());
  outcome = sim.outcome;
  ui.body.dataset.outcome = outcome;
  ui.body.dataset.steps = String(sim.steps);
  ui.body.dataset.time = String(sim.time);
  timeline.afterPull();
}

function refreshSlow(): void {
  if (sim) status.refresh(sim, view.scene, outcome, clock.playing);
}

function setPlaying(on: boolean): void {
  const playing = on && !!sim && outcome === 'running';
  ui.play.textContent = playing ? '❚❚ Pause' : '▶ Play';
  ui.play.dataset.playing = String(playing);
  ui.body.dataset.playing = String(playing);
  if (playing && !clock.playing) meter.reset();
  clock.play(playing);
  // The status line and metrics say what state the run is in right away.
  if (sim) {
    refreshSlow();
    plots.flush(true);
  }
}

/** Runs up to `n` control steps (at least one) within the frame budget and
 *  refreshes everything that follows from them; returns how many ran. */
function advance(n: number, budgetMs = Infinity): number {
  const s = sim;
  if (!s || n <= 0) return 0;
  const done = clock.run(n, () => outcome === 'running', () => (outcome = s.step(1)), budgetMs);
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
  ui.hint.textContent = `Episode over: ${endText(outcome, sim?.state()[3] ?? 0, sim?.collision)}. Reset to run it again.`;
  galleryRunEnded(outcome);
}

/** Steps run per slice of "to end" (a slice per animation frame keeps the
 *  page responsive; the clock's frame budget would take minutes). */
const TO_END_SLICE_MS = 60;

/** Runs the episode to its end as fast as the machine steps it, a slice
 *  per animation frame, then shows the last frame. */
function runToEnd(): void {
  if (!sim) return;
  setPlaying(false);
  if (timeline.scrubbed) timeline.branchHere();
  if (outcome !== 'running') return;
  ui.body.dataset.toEnd = 'running';
  const slice = guard(() => {
    if (!sim || outcome !== 'running' || ui.body.dataset.toEnd !== 'running') {
      delete ui.body.dataset.toEnd;
      return;
    }
    advance(1_000_000, TO_END_SLICE_MS);
    refreshSlow();
    view.request();
    if (outcome === 'running') requestAnimationFrame(slice);
    else delete ui.body.dataset.toEnd;
  });
  requestAnimationFrame(slice);
}

/** Shows `next` as the run: its map, robot, planner and a fresh scene. */
function install(next: SimHandle, keepView = false): void {
  setPlaying(false);
  // An edit changes the handle in place: the same object comes back.
  if (sim !== next) sim?.free();
  sim = next;
  clock.dt = sim.dt;
  view.scene = { ...emptyScene(), show: view.scene.show };
  const map = mapOf(new DrawList(sim.draw(mask(Layer.Map), 0)));
  if (map) view.setMap(map, keepView);
  const omni = status.showSetup(sim, map);
  planner.showChoiceOf(sim);
  globalPicker.showOf(sim);
  plots.clear(omni, sim.hasVehicle);
  status.clear();
  status.note = sim.routeNote() ?? '';
  ui.body.dataset.routeNote = status.note;
  FilesMenu.forgetNote();
  delete ui.body.dataset.traceHash;
  outcome = sim.outcome;
  pull();
  refreshSlow();
  plots.flush(true);
  view.request();
  ui.body.dataset.state = 'ready';
  ui.body.dataset.loadSeq = String(Number(ui.body.dataset.loadSeq ?? 0) + 1);
  ui.hint.textContent = tools.hint;
  editor.installed();
}

/** Loads scenario JSON as a fresh episode (edits forgotten); `files` holds
 *  the map files it refers to, by base name. */
function loadScenario(text: string, label: string, files: Record<string, Uint8Array> = {}): void {
  const next = SimHandle.fromScenario(text, files);
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

/** Restarts at t = 0 with every edit kept (the core's restart: map, start,
 *  goal, movers and planner as they are now). */
function resetEpisode(): void {
  if (!sim) return;
  sim.restart();
  // After map edits the view stays where it is; otherwise it fits again.
  install(sim, editor.dirty);
  clearError();
}

ui.play.addEventListener(
  'click',
  guard(() => {
    const playing = clock.playing;
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
ui.toEnd.addEventListener('click', guard(() => runToEnd()));
const setSpeed = bindSpeed(ui.speed, ui.speedOut, clock);
installToggles({
  sim: () => sim,
  scene: () => view.scene,
  refresh: () => {
    pull();
    view.request();
  },
  guard,
});

ui.preset.addEventListener(
  'change',
  guard(async () => {
    if (ui.preset.value) await loadPreset(opener, ui.preset.value);
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

const opener: OpenHost = {
  load: (text, label, files) => loadScenario(text, label, files),
  loadFromHash: () => filesMenu.loadFromHash(),
  preset: ui.preset,
  play: () => {
    // A gallery run opens at 4×: a paper's run is one to three simulated
    // minutes (S-tab1's preliminary fusion over two at 1×); » To end skips.
    if (new URLSearchParams(location.search).has('exp')) setSpeed(4);
    ui.play.click();
  },
  showError,
};

installKeys({
  ' ': () => ui.play.click(),
  '.': () => ui.step.click(),
  r: () => ui.reset.click(),
  f: () => view.fit(),
});

installRobotHooks({ sim: () => sim, view, canvas: ui.canvas, meter, infos: () => planner.infos });

// -------------------------------------------------------------------- boot
async function boot(): Promise<void> {
  tools.set('goal');
  status.clear();
  fillPresetSelect(ui.preset);
  await init();
  checkLayers(drawLayerNames());
  planner.setList(JSON.parse(plannerListJson()) as PlannerInfo[]);
  await openFirst(opener);
}

// Help overlay (planners and parameters from the wasm registry) and presentation mode.
installShell(() => robotHelp([...planner.infos.values()], planner.value));
installLegend('robot', document.querySelector('.stage'));
showGalleryNote();

boot().catch((e) => {
  ui.body.dataset.state = 'error';
  showError(`Could not start the robot playground: ${messageOf(e)}`);
});
