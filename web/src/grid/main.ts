// Playground wiring: loads maps through the wasm readers, turns clicks and
// drags into map edits and endpoint moves (the S and G markers can be
// dragged with any tool), and re-plans through the page's wasm PlanSession
// after every edit (scene/grid-session.ts); the search plays in player-ui.ts. No
// planning happens in this file: it converts control values into the core's
// GridPlanOptions and paints what comes back.

import init, { MapHandle, ScenarioHandle, defaultPlanOptions, gridAlgorithms, inflationMask, inflationNote, rosImageName, samplingAlgorithms } from '../../pkg-grid/planlab_wasm.js';
import { MAP_LAYERS, MapView, PLAN_LAYERS } from '../scene/grid-view';
import { DrawList, EMPTY, Layer, mask } from '../scene/draw';
import type { Cell } from '../shell/cells';
import { GridSession } from '../scene/grid-session';
import { SearchPlayer, exposeForTests } from './player-ui';
import { ExplainPanel } from './explain';
import { installShell } from '../shell/help';
import { gridHelp, type CorePlanner } from '../shell/help-content';
import { gridUrl } from './grid-url';
import { loadPresetFiles } from '../shell/scenario-files';
import { el, errorBanner, messageOf } from '../shell/dom';
import { panZoom } from '../shell/canvas-input';
import { applyOptions, getDefaults, onOptionInput, readOptions, readSampling, samplingChosen, setDefaults, showExpanded, syncControls } from './options';
import { cliCommand, noPathLine, runSampling, samplingLabel } from '../scene/sampling-run';
import { clearSamplingMetrics, drawPlot, explainSampler, setSamplers, showSamplingMetrics, showSamplingMode, type CoreSampler } from './sampling';
import { installScenario, loadFiles, loadPreset, type MapHost } from '../shell/grid-maps';
import { describeSearch } from './inspect';
import { clearMetrics, showMetrics } from './metrics';
import { Driver } from './drive';
import { download, onFileDrop } from '../shell/download';
import { TOOL_HINTS, type Tool } from './tools';
import { installClassroom } from './classroom';
import { costWeight, describeWeight, weightNote } from './weights';

const CELL_NAMES = ['free', 'occupied', 'unknown'];

// ---------------------------------------------------------------- elements
const ui = {
  body: document.body,
  hint: el('hint'),
  preset: el<HTMLSelectElement>('preset'),
  file: el<HTMLInputElement>('file-input'),
  mapName: el('map-name'),
  mapSize: el('map-size'),
  mapRes: el('map-resolution'),
  reset: el<HTMLButtonElement>('reset-map'),
  fitView: el<HTMLButtonElement>('fit-view'),
  savePosthoc: el<HTMLButtonElement>('save-posthoc'),
  tools: Array.from(document.querySelectorAll<HTMLButtonElement>('#tools [data-tool]')),
  error: el('error'),
  canvas: el<HTMLCanvasElement>('map-canvas'),
  hover: el('hover'),
  status: el('status'),
};

// ------------------------------------------------------------------ errors
// A shown error also sets body[data-state=error] (the tests wait on it).
const { showError, clearError, guard } = errorBanner(ui.error, ui.body, () => (ui.body.dataset.state = 'error'));

// ------------------------------------------------------------------- state
const view = new MapView(ui.canvas);
const session = new GridSession();
const player = new SearchPlayer(view);
new ExplainPanel(player);
let map: MapHandle | null = null;
/** The map as loaded, for "Reset edits". */
let loaded: MapHandle | null = null;
let start: Cell | null = null;
let goal: Cell | null = null;
let tool: Tool = 'start';
let mapVersion = 0;
/** The D* Lite repair on screen and the map version it repaired (replan
 *  keeps it while only the start moves). */
let keptRepair: { expanded: number; freshAStar: number; version: number } | null = null;
let inflationKey = '';
let inflation: Uint8Array | null = null;
let planSeq = 0;
let cellsDirty = false;
let replanQueued = false;
/** The plan's cells, for the driving robot. */
let currentPath: Cell[] | null = null;

function setTool(t: Tool): void {
  tool = t;
  for (const b of ui.tools) b.setAttribute('aria-checked', String(b.dataset.tool === t));
  ui.hint.textContent = TOOL_HINTS[tool];
}

// ---------------------------------------------------------------- planning
function scheduleReplan(): void {
  if (replanQueued) return;
  replanQueued = true;
  requestAnimationFrame(() => {
    replanQueued = false;
    try {
      if (cellsDirty && map) {
        cellsDirty = false;
        showMap(mask(Layer.Map, Layer.Weights));
      }
      replan();
    } catch (e) {
      showError(messageOf(e));
    }
  });
}

/** The map's draw list (its layers `layers`: map, inflation, endpoints)
 *  to the view. */
function showMap(layers: number): void {
  if (!map) return;
  const d = map.draw(layers, inflation ?? undefined, start ?? undefined, goal ?? undefined);
  view.show(new DrawList(d), layers);
}

/** Recomputes the inflation mask when its inputs changed; says whether. */
function updateInflation(opts: Record<string, unknown>): boolean {
  if (!map) return false;
  const r = opts.inflate_m as number;
  const key = `${mapVersion}|${r}|${opts.allow_unknown}`;
  if (key === inflationKey) return false;
  inflationKey = key;
  inflation = null;
  if (Number.isFinite(r) && r > 0) {
    try {
      inflation = inflationMask(map, opts);
    } catch {
      // plan() reports the same problem with the core's message.
      inflation = null;
    }
  }
  return true;
}

function replan(): void {
  if (!map) return;
  const opts = readOptions();
  showMap(updateInflation(opts) ? mask(Layer.Goals, Layer.Inflation) : mask(Layer.Goals));
  ui.canvas.dataset.start = start ? start.join(',') : '';
  ui.canvas.dataset.goal = goal ? goal.join(',') : '';
  planSeq += 1;
  ui.body.dataset.planSeq = String(planSeq);
  currentPath = null;
  if (!start || !goal) {
    view.show(EMPTY, PLAN_LAYERS);
    player.load(null);
    clearMetrics();
    clearSamplingMetrics();
    clearError();
    ui.body.dataset.state = 'idle';
    ui.canvas.dataset.pathLen = '0';
    ui.status.textContent = !start ? 'Place the start: click a free cell.' : 'Place the goal: click a free cell.';
    return;
  }
  if (samplingChosen()) {
    planSampling(start, goal);
    return;
  }
  showSamplingMode(false);
  ui.status.title = '';
  let planned;
  try {
    planned = session.plan(start, goal, opts, showExpanded(), map);
  } catch (e) {
    view.show(EMPTY, PLAN_LAYERS);
    player.load(null);
    clearMetrics();
    ui.canvas.dataset.pathLen = '0';
    ui.status.textContent = 'No path.';
    showError(messageOf(e));
    return;
  }
  const { result: res, playback, ms, repair, truncated } = planned;
  // D* Lite while driving: a moved start alone re-expands next to nothing,
  // so the repair of the last edit (its figures and its search in the
  // player) stays on screen until the next edit or a fresh search.
  const keep = !!repair && keptRepair !== null && keptRepair.version === mapVersion;
  if (!repair) keptRepair = null;
  else if (!keep) keptRepair = { ...repair, version: mapVersion };
  try {
    const path = res.path();
    const keyPoints = res.keyPoints();
    const featureNodes = res.featureNodes();
    const safety = res.safety();
    view.show(new DrawList(res.draw(map, PLAN_LAYERS)), PLAN_LAYERS);
    if (keep) playback?.free();
    else player.load(playback);
    clearError();
    ui.body.dataset.state = 'ok';
    showMetrics(res, opts, ms, keyPoints, featureNodes);
    ui.canvas.dataset.pathLen = String(res.pathLen);
    ui.canvas.dataset.path = Array.from(path).join(',');
    currentPath = Array.from({ length: path.length / 2 }, (_, i): Cell => [path[2 * i], path[2 * i + 1]]);
    let status = `Path found: ${res.pathLen} cells, ${res.lengthM.toFixed(2)} m`;
    if (safety.length) status += ` · min safety index ${safety.reduce((a, b) => Math.min(a, b), Infinity).toFixed(2)}/10`;
    const shown = keep ? keptRepair : repair;
    if (shown) {
      status += ` · D* Lite repair: ${shown.expanded.toLocaleString('en-US')} cells expanded (a fresh A*: ${shown.freshAStar.toLocaleString('en-US')})`;
      if (keep && repair) status += ` after the last edit; moving the start since: ${repair.expanded.toLocaleString('en-US')}`;
    }
    if (truncated) status += ` · the search recording stopped at ${playback?.n.toLocaleString('en-US')} events`;
    const note = inflationNote(Number(opts.inflate_m), map.resolution);
    if (note) status += ` · note: ${note}`;
    status += weightNote(res, map);
    ui.body.dataset.repair = shown ? `${shown.expanded},${shown.freshAStar}` : '';
    ui.status.textContent = status;
  } finally {
    res.free();
  }
}

/** The map file the CLI would read for the map on screen (the presets'
 *  files; an opened file by its name). */
function mapFileForCli(): string {
  const presetFiles: Record<string, string> = { arena: 'assets/maps/arena.map', turtlebot3: 'assets/maps/turtlebot3.yaml', 'grid-demo': 'assets/scenarios/grid-demo.json' };
  return presetFiles[ui.preset.value] ?? (ui.mapName.textContent || 'MAP');
}

/** A sampling planner's run to its budget: the tree in the player, the
 *  metrics and the cost plot; bad input or no path within the budget is
 *  one line in the error bar. */
function planSampling(s: Cell, g: Cell): void {
  if (!map) return;
  showSamplingMode(true);
  view.show(EMPTY, PLAN_LAYERS);
  const settings = readSampling();
  explainSampler(settings.algorithm);
  let r;
  try {
    r = runSampling(map, s, g, settings);
  } catch (e) {
    player.load(null);
    clearSamplingMetrics();
    ui.canvas.dataset.pathLen = '0';
    ui.canvas.dataset.path = '';
    ui.status.textContent = `${samplingLabel(settings.algorithm)}: not run.`;
    showError(messageOf(e));
    return;
  }
  player.load(r.playback);
  showSamplingMetrics(r);
  const path = r.playback.finalPath;
  ui.canvas.dataset.pathLen = String(path.length / 2);
  ui.canvas.dataset.path = Array.from(path).join(',');
  ui.body.dataset.samplingIterations = String(r.iterations);
  ui.body.dataset.samplingMs = String(r.ms);
  const cli = cliCommand(mapFileForCli(), s, g, settings, r.iterations);
  ui.body.dataset.samplingCli = cli;
  const budget = settings.budget.kind === 'ms' ? `${settings.budget.value} ms budget` : `${settings.budget.value.toLocaleString('en-US')}-iteration budget`;
  const stopped = r.finished && r.iterations < (settings.budget.kind === 'iterations' ? settings.budget.value : Infinity) ? ' (it stopped by itself)' : '';
  if (!Number.isFinite(r.cost)) {
    ui.body.dataset.state = 'error';
    ui.status.textContent = `${samplingLabel(settings.algorithm)}: ${r.iterations.toLocaleString('en-US')} iterations in ${r.ms.toFixed(1)} ms (${budget}), no path.`;
    showError(noPathLine(settings, r));
    return;
  }
  clearError();
  ui.body.dataset.state = 'ok';
  ui.status.title = cli;
  ui.status.textContent = `${samplingLabel(settings.algorithm)}: path ${r.cost.toFixed(4)} cells (${r.lengthM.toFixed(2)} m), ${r.iterations.toLocaleString('en-US')} iterations in ${r.ms.toFixed(1)} ms (${budget})${stopped}, robot radius ${r.radiusCells.toFixed(3)} cells · the same run: ${cli}`;
}

player.onShow(() => drawPlot(player.sampling));

// -------------------------------------------------------------- map loading
function installMap(m: MapHandle, name: string, s: Cell | null, g: Cell | null): void {
  map?.free();
  loaded?.free();
  map = m;
  loaded = m.clone();
  session.attach(m);
  mapVersion += 1;
  inflationKey = '';
  start = s;
  goal = g;
  ui.mapName.textContent = name;
  ui.mapName.title = name;
  ui.mapSize.textContent = `${m.width} × ${m.height}`;
  ui.mapRes.textContent = `${m.resolution} m / cell`;
  ui.body.dataset.mapWidth = String(m.width);
  ui.body.dataset.mapHeight = String(m.height);
  inflation = null;
  view.setMap(new DrawList(m.draw(MAP_LAYERS, undefined, s ?? undefined, g ?? undefined)));
  setTool(s && g ? tool : 'start');
  replan();
}

const maps: MapHost = { install: installMap, applyOptions, defaults: getDefaults };
const driver = new Driver(el<HTMLButtonElement>('drive'), {
  path: () => currentPath,
  moveStart: guard((c: Cell) => {
    start = c;
    replan();
  }),
});

// ------------------------------------------------------------------- input
function canvasPoint(ev: MouseEvent): [number, number] {
  const r = ui.canvas.getBoundingClientRect();
  return [ev.clientX - r.left, ev.clientY - r.top];
}

/** A brush stroke: a cell kind (walls, erase) or, for the cost brush, a
 *  traversal weight. */
let painting: { kind: number; weight?: number; last: Cell | null } | null = null;
/** The endpoint marker being dragged (replans at every new cell). */
let dragging: 'start' | 'goal' | null = null;
// Before the tools' handlers: a pan gesture goes no further.
panZoom(ui.canvas, () => [view]);

function paintTo(cell: Cell | null): void {
  if (!map || !painting) return;
  if (!cell) {
    painting.last = null;
    return;
  }
  const from = painting.last ?? cell;
  const w = painting.weight;
  const changed = w === undefined ? map.paintSegment(from[0], from[1], cell[0], cell[1], painting.kind) : map.paintWeight(from[0], from[1], cell[0], cell[1], w);
  painting.last = cell;
  if (changed > 0) {
    if (w === undefined) session.paint(from, cell, painting.kind);
    else session.paintWeight(from, cell, w);
    mapVersion += 1;
    cellsDirty = true;
    scheduleReplan();
  }
}

function describeCell(cell: Cell | null): string {
  if (!cell || !map) return '—';
  const kind = CELL_NAMES[view.cellKind(cell[0], cell[1]) ?? 0];
  const [x, y] = map.cellToWorld(cell[0], cell[1]);
  const where = `cell (${cell[0]}, ${cell[1]}) · ${kind}${describeWeight(map, cell)} · world (${x.toFixed(2)}, ${y.toFixed(2)}) m`;
  const search = player.playback ? describeSearch(player.playback.info(cell[0], cell[1])) : '';
  ui.hover.dataset.search = search;
  return search ? `${where} · ${search}` : where;
}

ui.canvas.addEventListener(
  'pointerdown',
  guard((ev: PointerEvent) => {
    if (!map || ev.button !== 0) return;
    const [x, y] = canvasPoint(ev);
    const cell = view.cellAt(x, y);
    if (!cell) return;
    const grab = view.markerAt(x, y, start, goal);
    if (grab && !ev.shiftKey) {
      dragging = grab;
      ui.canvas.setPointerCapture(ev.pointerId);
      ui.body.dataset.dragging = grab;
    } else if (ev.shiftKey || tool === 'goal') {
      goal = cell;
      scheduleReplan();
    } else if (tool === 'start') {
      start = cell;
      scheduleReplan();
    } else {
      painting = tool === 'cost' ? { kind: 0, weight: costWeight(), last: null } : { kind: tool === 'wall' ? 1 : 0, last: null };
      ui.canvas.setPointerCapture(ev.pointerId);
      paintTo(cell);
    }
  }),
);

ui.canvas.addEventListener(
  'pointermove',
  guard((ev: PointerEvent) => {
    const [x, y] = canvasPoint(ev);
    const cell = view.cellAt(x, y);
    ui.hover.textContent = describeCell(cell);
    if (painting) paintTo(cell);
    if (dragging && cell && view.cellKind(cell[0], cell[1]) !== 1) {
      const at = dragging === 'start' ? start : goal;
      if (!at || at[0] !== cell[0] || at[1] !== cell[1]) {
        if (dragging === 'start') start = cell;
        else goal = cell;
        scheduleReplan();
      }
    }
  }),
);

const endStroke = guard((ev: PointerEvent) => {
  painting = null;
  dragging = null;
  delete ui.body.dataset.dragging;
  if (ui.canvas.hasPointerCapture(ev.pointerId)) ui.canvas.releasePointerCapture(ev.pointerId);
});
ui.canvas.addEventListener('pointerup', endStroke);
ui.canvas.addEventListener('pointercancel', endStroke);
ui.canvas.addEventListener('pointerleave', () => (ui.hover.textContent = '—'));

for (const b of ui.tools) b.addEventListener('click', () => setTool(b.dataset.tool as Tool));

window.addEventListener('keydown', (ev) => {
  const t = ev.target as HTMLElement | null;
  if (t && (t.tagName === 'INPUT' || t.tagName === 'SELECT' || t.tagName === 'TEXTAREA')) return;
  if (ev.ctrlKey || ev.metaKey || ev.altKey) return;
  const keys: Record<string, Tool> = { s: 'start', g: 'goal', w: 'wall', e: 'erase', k: 'cost' };
  const k = ev.key.toLowerCase();
  if (keys[k]) setTool(keys[k]);
  else if (k === ' ') {
    ev.preventDefault();
    player.toggle();
  } else if (k === ',' || k === '.') player.stepBy(k === '.' ? 1 : -1);
  else if (k === 'f') view.fit();
  else if (k === 'd') driver.toggle();
});

onOptionInput(scheduleReplan);

ui.preset.addEventListener(
  'change',
  guard(async () => {
    if (ui.preset.value) await loadPreset(maps, ui.preset.value);
  }),
);
ui.file.addEventListener(
  'change',
  guard(async () => {
    try {
      if (await loadFiles(maps, ui.file.files)) ui.preset.value = '';
    } finally {
      // Lets the same file be picked again after fixing it.
      ui.file.value = '';
    }
  }),
);
// A map dropped on the canvas opens as if picked with the file button.
onFileDrop(
  el('canvas-wrap'),
  guard(async (files: File[]) => {
    if (await loadFiles(maps, files)) ui.preset.value = '';
  }),
);
/** The map's cells changed wholesale (reset, clear walls): replans. */
function mapReplaced(m: MapHandle): void {
  if (m !== map) map?.free();
  map = m;
  session.reload(m);
  mapVersion += 1;
  cellsDirty = true;
  scheduleReplan();
}
ui.reset.addEventListener(
  'click',
  guard(() => {
    if (loaded) mapReplaced(loaded.clone());
  }),
);
ui.fitView.addEventListener('click', () => view.fit());
// Empty grid, clear walls / path, generators (classroom.ts).
installClassroom({
  maps,
  preset: ui.preset,
  map: () => map,
  mapReplaced,
  clearPlan: () => {
    driver.stop();
    player.load(null);
    view.show(EMPTY, PLAN_LAYERS);
    clearMetrics();
    clearSamplingMetrics();
    currentPath = null;
    ui.canvas.dataset.pathLen = '0';
    ui.canvas.dataset.path = '';
  },
  guard,
  status: ui.status,
});
ui.savePosthoc.addEventListener('click', () => {
  if (!map || !start || !goal) {
    showError('Place the start and the goal first: the trace is of the search between them.');
    return;
  }
  const opts = readOptions();
  try {
    const text = session.posthoc(start, goal, opts);
    const stem = (ui.mapName.textContent || 'map').replace(/\.[^.]*$/, '').replace(/[^A-Za-z0-9_-]+/g, '-');
    download(`${stem}-${String(opts.algorithm ?? 'astar')}.trace.json`, text, 'application/json');
    clearError();
  } catch (e) {
    showError(messageOf(e));
  }
});

// -------------------------------------------------------------------- boot
async function boot(): Promise<void> {
  setTool('start');
  syncControls();
  clearMetrics();
  await init();
  corePlanners = gridAlgorithms() as CorePlanner[];
  coreSamplers = samplingAlgorithms() as CoreSampler[];
  setSamplers(coreSamplers);
  setDefaults(defaultPlanOptions() as Record<string, unknown>);
  applyOptions(getDefaults());
  syncControls();
  ui.hint.textContent = TOOL_HINTS[tool];
  // `?scenario=FILE` (+ planner options, `?algorithm=rrt-star` too): a site
  // scenario as a global plan.
  const url = gridUrl(location.search, coreSamplers.map((s) => s.name));
  if (url.scenario) {
    try {
      const { text, files } = await loadPresetFiles(url.scenario, rosImageName);
      installScenario(maps, ScenarioHandle.fromJson(text), url.scenario, files, url.options);
      const linked = ui.preset.querySelector<HTMLOptionElement>('option[value=""]');
      if (linked) linked.textContent = `${url.scenario} (linked)`;
      ui.preset.value = '';
    } catch (e) {
      url.problems.unshift(`${url.scenario}: ${messageOf(e)}`);
      await loadPreset(maps, ui.preset.value || 'arena');
    }
  } else {
    await loadPreset(maps, ui.preset.value || 'arena');
    if (Object.keys(url.options).length) {
      applyOptions({ ...readOptions(), ...url.options });
      replan();
    }
  }
  if (url.problems.length) showError(url.problems.join(' · '));
}

/** The core's planners with their references (for the help), after init. */
let corePlanners: CorePlanner[] = [];
let coreSamplers: CoreSampler[] = [];
installShell(() => gridHelp(corePlanners, coreSamplers));

exposeForTests(player, () => session.rebuilds, view);

boot().catch((e) => {
  showError(`Could not start the playground: ${messageOf(e)}`);
});
