// Compare page wiring: one scenario, 2–4 planners, each on its own wasm
// SimHandle built from the same scenario JSON (the planner swapped in the
// way `planlab run --planner` does it), stepped together from the animation
// frame (shell/sim-clock.ts) so they stay at the same simulated time; drawn
// side by side (a RobotView each) or overlaid (one view, a colour per
// planner), with the `planlab run` metrics in a table and the winner of
// each row marked.
// URL: ?scenario=FILE&planners=a,b&set=path=value (repeatable, as `planlab
// run --set`)&view=side|overlay&speed=X&autorun=1|instant

import init, { drawLayerNames, planners as plannerListJson, rosImageName } from '../../pkg/planlab_wasm.js';
import { fillPresetSelect, showOpened } from '../shell/preset-select';
import { mapOf, type RobotView } from '../scene/view';
import { DrawList, Layer, checkLayers, mask } from '../scene/draw';
import type { PlannerInfo } from '../shell/planner-info';
import { Race } from './race';
import { OverlayView } from './overlay';
import { compareHelp } from './help';
import { installShell } from '../shell/help';
import { installLegend } from '../shell/legend';
import { loadPresetFiles, readPicked } from '../shell/scenario-files';
import { ComparedScenario } from './scenario';
import { openFromUrl } from './open';
import { el, messageOf, errorBanner } from '../shell/dom';
import { SimClock } from '../shell/sim-clock';
import { panZoom } from '../shell/canvas-input';
import { installKeys } from '../shell/keys';
import { showDone, showPlaying, wireTransport } from '../shell/transport';
import { bindSpeed } from '../shell/speed';
import { summary } from '../shell/frame-meter';
import { buildLanes, lanesCsv, renderHeads, renderTable } from './render';
import { MIN_PLANNERS, PlannerPicks } from './picks';
import { wireCopyCsv } from './clipboard';
import { FanColours } from './fan-colour';

/** Most synchronised control steps (one per planner) in one frame. */
const MAX_ROUNDS_PER_FRAME = 16;
/** Simulation budget per frame, ms (slower than the speed rather than dropping frames). */
const SIM_BUDGET_MS = 10;
const SLOW_REFRESH_MS = 250;

type ViewMode = 'side' | 'overlay';

const ui = {
  body: document.body,
  hint: el('hint'),
  preset: el<HTMLSelectElement>('preset'),
  file: el<HTMLInputElement>('file-input'),
  mapSize: el('map-size'),
  simDt: el('sim-dt'),
  play: el<HTMLButtonElement>('play'),
  step: el<HTMLButtonElement>('step'),
  reset: el<HTMLButtonElement>('reset'),
  instant: el<HTMLButtonElement>('instant'),
  speed: el<HTMLSelectElement>('speed'),
  speedOut: el<HTMLOutputElement>('speed-out'),
  views: Array.from(document.querySelectorAll<HTMLButtonElement>('#views [data-view]')),
  showFan: el<HTMLInputElement>('show-fan'),
  showPath: el<HTMLInputElement>('show-path'),
  error: el('error'),
  status: el('status'),
  stage: el('stage-views'),
  lanes: el('lanes'),
  overlayCanvas: el<HTMLCanvasElement>('overlay-canvas'),
  overlayLegend: el<HTMLUListElement>('overlay-legend'),
  table: el<HTMLTableElement>('metrics-table'),
  copyCsv: el<HTMLButtonElement>('copy-csv'),
  csvStatus: el('csv-status'),
};

const { showError, clearError, guard } = errorBanner(ui.error, ui.body);

// ------------------------------------------------------------------- state
const picks = new PlannerPicks(el<HTMLUListElement>('planner-list'), el('planner-count'), el('planner-hint'));
const scenario = new ComparedScenario();
let sideViews: RobotView[] = [];
const overlay = new OverlayView(ui.overlayCanvas);
let viewMode: ViewMode = 'side';
const race = new Race();
// What colours the fans: the total or a critic of the lanes' planners (fan-colour.ts).
const fans = new FanColours(el<HTMLSelectElement>('fan-colour'), el('fan-scale'), {
  lanes: () => race.lanes,
  redraw: () => {
    race.pull();
    renderHeads(ui.lanes, ui.overlayLegend, race.lanes);
    paintViews();
  },
});
let lastSlow = 0;
/** Per-frame work (all planners' steps + paint), ms, while playing. */
const frameWork: number[] = [];

const clock = new SimClock(
  {
    advance: (n, budget) => advance(n, budget),
    afterFrame(ran, now, _interval, t0) {
      if (ran > 0) paintViews(true);
      if (now - lastSlow > SLOW_REFRESH_MS) {
        lastSlow = now;
        renderHeads(ui.lanes, ui.overlayLegend, race.lanes);
        renderTable(ui.table, race.lanes, isFinal());
        renderStatus();
      }
      if (frameWork.length < 100_000) frameWork.push(performance.now() - t0);
    },
    onError(e) {
      setPlaying(false);
      showError(messageOf(e));
    },
  },
  MAX_ROUNDS_PER_FRAME,
  SIM_BUDGET_MS,
);
clock.speed = 4;

// ------------------------------------------------------------------ lanes
/** Builds a SimHandle per picked planner from the scenario; a planner that
 *  cannot run the scenario is reported and left out. */
function rebuild(): void {
  setPlaying(false);
  const problems = race.rebuild(scenario, picks.chosen, ui.showFan.checked);
  if (problems.length) showError(problems.join(' · '));
  else clearError();
  const first = race.lanes[0];
  const map = first ? mapOf(new DrawList(first.sim.draw(mask(Layer.Map), 0))) : null;
  if (first) {
    clock.dt = first.sim.dt;
    ui.simDt.textContent = `${clock.dt} s`;
  }
  if (map) ui.mapSize.textContent = `${map.width} × ${map.height} · ${map.resolution} m`;
  sideViews = buildLanes(ui.lanes, race.lanes, map, ui.showPath.checked);
  if (map) overlay.setMap(map);
  fans.update();
  race.pull();
  overlay.setLanes(race.lanes);
  ui.body.dataset.state = race.lanes.length ? 'ready' : 'empty';
  renderAll();
  ui.body.dataset.lanes = String(race.lanes.length);
  ui.body.dataset.buildSeq = String(Number(ui.body.dataset.buildSeq ?? 0) + 1);
  delete ui.body.dataset.done;
}

// ------------------------------------------------------------- rendering
function paintViews(now = false): void {
  if (viewMode === 'side') for (const v of sideViews) now ? v.paint() : v.request();
  else now ? overlay.paint() : overlay.request();
}

const allDone = () => race.allDone();

function isFinal(): boolean {
  return allDone() && race.lanes.length >= MIN_PLANNERS;
}

function renderStatus(): void {
  if (!race.lanes.length) {
    ui.status.textContent = scenario.text ? 'No planner to run: pick 2 to 4.' : '—';
    return;
  }
  const t = Math.max(...race.lanes.map((l) => l.sim.time));
  const parts = race.lanes.map((l) => `${l.name} ${l.running ? 'running' : `${l.outcome} at ${l.sim.time.toFixed(1)} s`}`);
  const state = race.instant ? 'running to the end…' : allDone() ? 'all done' : clock.playing ? 'playing' : 'paused';
  ui.status.textContent = `t = ${t.toFixed(1)} s · ${parts.join(' · ')} · ${state}`;
  ui.body.dataset.time = String(t);
  ui.body.dataset.outcomes = race.lanes.map((l) => `${l.name}:${l.outcome}`).join(',');
}

function renderControls(): void {
  const [hint] = picks.render(race.instant);
  const ready = race.lanes.length >= MIN_PLANNERS && !race.instant;
  ui.play.disabled = !ready || allDone();
  ui.step.disabled = !ready || allDone();
  ui.instant.disabled = !ready || allDone();
  ui.reset.disabled = !race.lanes.length || race.instant;
  if (!race.instant && ui.body.dataset.state !== 'done') {
    ui.hint.textContent = ready ? 'Run: every planner steps together, at the same simulated time.' : hint;
  }
}

function renderAll(): void {
  renderHeads(ui.lanes, ui.overlayLegend, race.lanes);
  renderTable(ui.table, race.lanes, isFinal());
  ui.copyCsv.disabled = race.lanes.length === 0;
  renderStatus();
  renderControls();
  paintViews();
}

// ------------------------------------------------------------ simulation
function setPlaying(on: boolean): void {
  const playing = on && race.lanes.length >= MIN_PLANNERS && !allDone() && !race.instant;
  showPlaying(ui.play, ui.body, playing);
  clock.play(playing);
  renderStatus();
}

/** Up to `n` rounds within the budget; returns how many ran. */
function advance(n: number, budgetMs = Infinity): number {
  const done = race.rounds(clock, n, budgetMs);
  race.pull();
  if (allDone()) finish();
  return done;
}

function finish(): void {
  clock.play(false);
  showDone(ui.play, ui.body);
  ui.hint.textContent = 'All episodes over: the table marks the best planner per metric. Reset to run again.';
  renderAll();
}

/** Runs every planner to the end of its episode, yielding to the page
 *  between slices (progress shows; Reset stops it). */
async function runToEnd(): Promise<void> {
  if (race.lanes.length < MIN_PLANNERS || allDone()) return;
  setPlaying(false);
  const t0 = performance.now();
  const slice = () => {
    renderHeads(ui.lanes, ui.overlayLegend, race.lanes);
    renderStatus();
    paintViews(true);
  };
  race.instant = true;
  ui.body.dataset.state = 'running';
  renderControls();
  if (!(await race.runToEnd(slice, () => ui.showFan.checked))) return;
  // Wall time of the whole run (slices, pulls and paints included), for the curious and the e2e log.
  ui.body.dataset.instantMs = (performance.now() - t0).toFixed(0);
  finish();
}

// ------------------------------------------------------------- controls
function setView(v: ViewMode): void {
  viewMode = v;
  ui.stage.dataset.view = v;
  for (const b of ui.views) b.setAttribute('aria-checked', String(b.dataset.view === v));
  ui.body.dataset.view = v;
  updateUrl();
  // The hidden view's canvases had no size: paint after layout.
  requestAnimationFrame(() => paintViews(true));
}

function updateUrl(): void {
  const q = new URLSearchParams();
  if (scenario.file) q.set('scenario', scenario.file);
  if (picks.chosen.length) q.set('planners', picks.chosen.join(','));
  for (const [p, v] of scenario.edits) q.append('set', `${p}=${v}`);
  q.set('view', viewMode);
  history.replaceState(null, '', `${location.pathname}?${q.toString().replaceAll('%2C', ',')}`);
}

// ----------------------------------------------------------------- files
/** Compares on scenario `text` (see ComparedScenario.set). */
function setScenario(text: string, file: string, label: string, files: Record<string, Uint8Array>, newEdits: [string, string][] = []): void {
  const problems = scenario.set(text, file, label, files, newEdits);
  picks.markOwn(scenario.ownPlanner());
  updateUrl();
  rebuild();
  if (problems.length) showError(problems.join(' · '));
}

async function loadPreset(file: string, withEdits: [string, string][] = []): Promise<void> {
  try {
    const { text, files } = await loadPresetFiles(file, rosImageName);
    setScenario(text, file, file, files, withEdits);
  } catch (e) {
    throw new Error(`${file}: ${messageOf(e)}`);
  }
}

// ------------------------------------------------------------------ wiring
ui.preset.addEventListener(
  'change',
  guard(async () => {
    if (ui.preset.value) await loadPreset(ui.preset.value);
  }),
);
ui.file.addEventListener(
  'change',
  guard(async () => {
    const picked = Array.from(ui.file.files ?? []);
    ui.file.value = '';
    const got = await readPicked(picked);
    if (!got) return;
    try {
      setScenario(got.text, '', got.name, got.files);
    } catch (e) {
      throw new Error(`${got.name}: ${messageOf(e)}`);
    }
    showOpened(ui.preset, got.name);
  }),
);
wireTransport(
  ui,
  {
    toggle: () => setPlaying(!clock.playing),
    step: () => {
      setPlaying(false);
      advance(1);
      renderAll();
    },
    reset: () => {
      rebuild();
      ui.hint.textContent = 'Back at the start.';
    },
    instant: runToEnd,
  },
  guard,
);
bindSpeed(ui.speed, ui.speedOut, clock);
for (const b of ui.views) b.addEventListener('click', () => setView(b.dataset.view as ViewMode));
ui.showFan.addEventListener(
  'change',
  guard(() => {
    for (const l of race.lanes) {
      l.setRecordRollouts(ui.showFan.checked);
      l.pull();
    }
    paintViews();
  }),
);
ui.showPath.addEventListener('change', () => {
  for (const l of race.lanes) l.scene.show.path = ui.showPath.checked;
  overlay.showPath = ui.showPath.checked;
  paintViews();
});
// Zoom and pan move every view together, so the planners stay comparable
// at the same place: wheel = zoom, right / middle / Alt drag = pan,
// double click = fit.
const allViews = (): RobotView[] => (viewMode === 'side' ? sideViews : [overlay.view]);
const ours = (c: HTMLCanvasElement) => c.classList.contains('lane-canvas') || c === ui.overlayCanvas;
panZoom(ui.stage, (c) => (ours(c) ? allViews() : null), () => overlay.sync());
ui.stage.addEventListener('dblclick', (ev) => {
  if (ev.target instanceof HTMLCanvasElement && ours(ev.target)) for (const v of allViews()) v.fit();
});

const currentCsv = () => lanesCsv(race.lanes, allDone());

wireCopyCsv(ui.copyCsv, ui.csvStatus, currentCsv, guard);

installKeys({ v: () => setView(viewMode === 'side' ? 'overlay' : 'side') });

/** For the e2e tests: the metrics and hashes per planner, and the CSV. */
(window as unknown as { planlabCompare: unknown }).planlabCompare = {
  metrics: () => Object.fromEntries(race.lanes.map((l) => [l.name, l.metrics])),
  hashes: () => Object.fromEntries(race.lanes.map((l) => [l.name, l.hash])),
  csv: () => currentCsv(),
  chosen: () => [...picks.chosen],
  frameStats: () => ({ frames: frameWork.length, ...summary(frameWork) }),
  resetMeter: () => (frameWork.length = 0),
};

// -------------------------------------------------------------------- boot
async function boot(): Promise<void> {
  fillPresetSelect(ui.preset);
  await init();
  checkLayers(drawLayerNames());
  picks.build(JSON.parse(plannerListJson()) as PlannerInfo[], guard, () => {
    updateUrl();
    rebuild();
  });

  await openFromUrl({
    picks,
    speed: ui.speed,
    setView,
    loadPreset: async (file, edits) => {
      ui.preset.value = file;
      await loadPreset(file, edits);
    },
    report: (problems) => showError([...problems, ...(ui.error.hidden ? [] : [ui.error.textContent ?? ''])].join(' · ')),
    autorun: async (how) => {
      if (race.lanes.length < MIN_PLANNERS) return;
      if (how === 'instant') await runToEnd();
      else setPlaying(true);
    },
  });
}

installShell(() => compareHelp(picks.infos, picks.chosen[0]));
installLegend('compare', document.querySelector('.stage'));

boot().catch((e) => {
  ui.body.dataset.state = 'error';
  showError(`Could not start the comparison: ${messageOf(e)}`);
});
