// Playground wiring: loads maps through the wasm readers, turns clicks and
// drags into map edits and endpoint moves, and re-plans through the wasm
// `plan` after every edit. No planning happens in this file: it converts
// control values into the core's GridPlanOptions and paints what comes back.

import init, {
  MapHandle,
  plan,
  ScenarioHandle,
  defaultPlanOptions,
  inflationMask,
  rosImageName,
} from '../pkg/planlab_wasm.js';
import { MapView, type Cell } from './render';
import { installShell } from './shell/help';
import { gridHelp } from './shell/help-content';
import { gridUrl } from './grid-url';
import { checkSizes, loadPresetFiles } from './shell/scenario-files';
import { el, messageOf } from './shell/dom';

type Tool = 'start' | 'goal' | 'wall' | 'erase';

interface Preset {
  name: string;
  kind: 'movingai' | 'ros' | 'scenario';
  files: string[];
  /** Endpoints to place (a scenario brings its own). */
  start?: Cell;
  goal?: Cell;
}

const PRESETS: Record<string, Preset> = {
  arena: {
    name: 'arena.map',
    kind: 'movingai',
    files: ['maps/arena.map'],
    start: [1, 45],
    goal: [47, 9],
  },
  turtlebot3: {
    name: 'turtlebot3.yaml',
    kind: 'ros',
    files: ['maps/turtlebot3.yaml', 'maps/turtlebot3.pgm'],
    start: [152, 182],
    goal: [235, 215],
  },
  'grid-demo': {
    name: 'grid-demo.json',
    kind: 'scenario',
    files: ['scenarios/grid-demo.json'],
  },
};

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
  tools: Array.from(document.querySelectorAll<HTMLButtonElement>('#tools [data-tool]')),
  algorithm: el<HTMLSelectElement>('algorithm'),
  heuristic: el<HTMLSelectElement>('heuristic'),
  weight: el<HTMLInputElement>('weight'),
  weightOut: el<HTMLOutputElement>('weight-out'),
  diagonal: el<HTMLSelectElement>('diagonal'),
  safeEpsilon: el<HTMLInputElement>('safe-epsilon'),
  safeNeighbourhood: el<HTMLSelectElement>('safe-neighbourhood'),
  safeAdmissible: el<HTMLInputElement>('safe-admissible'),
  inflate: el<HTMLInputElement>('inflate'),
  allowUnknown: el<HTMLInputElement>('allow-unknown'),
  keypoints: el<HTMLInputElement>('keypoints'),
  bottomUp: el<HTMLInputElement>('bottom-up'),
  bottomUpEps: el<HTMLInputElement>('bottom-up-eps'),
  showExpanded: el<HTMLInputElement>('show-expanded'),
  error: el('error'),
  canvas: el<HTMLCanvasElement>('map-canvas'),
  hover: el('hover'),
  status: el('status'),
  metric: {
    cost: el('metric-cost'),
    length: el('metric-length'),
    expanded: el('metric-expanded'),
    nodes: el('metric-nodes'),
    keypoints: el('metric-keypoints'),
    time: el('metric-time'),
  },
};

// ------------------------------------------------------------------ errors
function showError(text: string): void {
  ui.error.textContent = text;
  ui.error.title = text;
  ui.error.hidden = false;
  ui.body.dataset.state = 'error';
}

function clearError(): void {
  ui.error.hidden = true;
  ui.error.textContent = '';
}

// Whatever slips through a handler still lands in the error box, never in a
// dead page.
window.addEventListener('error', (ev) => showError(`Unexpected error: ${messageOf(ev.error ?? ev.message)}`));
window.addEventListener('unhandledrejection', (ev) => showError(`Unexpected error: ${messageOf(ev.reason)}`));

/** Runs an event handler, sending any exception to the error box. */
function guard<A extends unknown[]>(fn: (...args: A) => void | Promise<void>): (...args: A) => void {
  return (...args: A) => {
    try {
      const r = fn(...args);
      if (r instanceof Promise) r.catch((e) => showError(messageOf(e)));
    } catch (e) {
      showError(messageOf(e));
    }
  };
}

// ------------------------------------------------------------------- state
const view = new MapView(ui.canvas);
let map: MapHandle | null = null;
/** The map as loaded, for "Reset edits". */
let loaded: MapHandle | null = null;
let start: Cell | null = null;
let goal: Cell | null = null;
let tool: Tool = 'start';
let mapVersion = 0;
let inflationKey = '';
let inflation: Uint8Array | null = null;
let planSeq = 0;
let cellsDirty = false;
let replanQueued = false;

// ----------------------------------------------------------------- options
let defaults: Record<string, unknown> = {};

function num(input: HTMLInputElement): number {
  // An empty box gives NaN, which the core rejects with its own message.
  return input.value.trim() === '' ? Number.NaN : Number(input.value);
}

/** The control values as the core's GridPlanOptions. */
function readOptions(): Record<string, unknown> {
  const safeDefaults = (defaults.safe as Record<string, unknown>) ?? {};
  return {
    ...defaults,
    algorithm: ui.algorithm.value,
    heuristic: ui.heuristic.value,
    weight: num(ui.weight),
    diagonal: ui.diagonal.value,
    allow_unknown: ui.allowUnknown.checked,
    inflate_m: num(ui.inflate),
    keypoints: ui.keypoints.checked,
    bottom_up_eps: ui.bottomUp.checked ? num(ui.bottomUpEps) : null,
    safe: {
      ...safeDefaults,
      epsilon: num(ui.safeEpsilon),
      neighbourhood: Number(ui.safeNeighbourhood.value),
      admissible: ui.safeAdmissible.checked,
    },
  };
}

/** Shows only the controls that the chosen algorithm reads. */
function syncControls(): void {
  const algo = ui.algorithm.value;
  document.querySelectorAll<HTMLElement>('[data-for]').forEach((e) => {
    const forAlgos = (e.dataset.for ?? '').split(' ');
    if (e.classList.contains('safe-box')) e.dataset.hidden = String(!forAlgos.includes(algo));
    else e.dataset.dim = String(!forAlgos.includes(algo));
  });
  ui.weightOut.textContent = Number(ui.weight.value).toFixed(1);
  ui.bottomUpEps.disabled = !ui.bottomUp.checked;
}

/** Sets the controls from a GridPlanOptions object (defaults or a scenario's). */
function applyOptions(d: Record<string, unknown>): void {
  const set = (s: HTMLSelectElement, v: unknown) => {
    if (typeof v === 'string' && Array.from(s.options).some((o) => o.value === v)) s.value = v;
  };
  set(ui.algorithm, d.algorithm);
  set(ui.heuristic, d.heuristic);
  set(ui.diagonal, d.diagonal);
  if (typeof d.weight === 'number') ui.weight.value = String(d.weight);
  if (typeof d.inflate_m === 'number') ui.inflate.value = String(d.inflate_m);
  ui.allowUnknown.checked = d.allow_unknown === true;
  ui.keypoints.checked = d.keypoints === true;
  ui.bottomUp.checked = typeof d.bottom_up_eps === 'number';
  if (typeof d.bottom_up_eps === 'number') ui.bottomUpEps.value = String(d.bottom_up_eps);
  const safe = d.safe as Record<string, unknown> | undefined;
  if (safe) {
    if (typeof safe.epsilon === 'number') ui.safeEpsilon.value = String(safe.epsilon);
    if (typeof safe.neighbourhood === 'number') ui.safeNeighbourhood.value = String(safe.neighbourhood);
    ui.safeAdmissible.checked = safe.admissible === true;
  }
  syncControls();
}

// ----------------------------------------------------------------- metrics
function setMetric(e: HTMLElement, text: string, value: number | null): void {
  e.textContent = text;
  if (value === null) delete e.dataset.value;
  else e.dataset.value = String(value);
}

function clearMetrics(): void {
  for (const e of Object.values(ui.metric)) setMetric(e, '—', null);
}

function hintForTool(): string {
  switch (tool) {
    case 'start':
      return 'Click a free cell to place the start.';
    case 'goal':
      return 'Click a free cell to place the goal.';
    case 'wall':
      return 'Drag on the map to paint walls.';
    case 'erase':
      return 'Drag on the map to erase walls.';
  }
}

function setTool(t: Tool): void {
  tool = t;
  for (const b of ui.tools) b.setAttribute('aria-checked', String(b.dataset.tool === t));
  ui.hint.textContent = hintForTool();
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
        view.updateCells(map.cells());
      }
      replan();
    } catch (e) {
      showError(messageOf(e));
    }
  });
}

function updateInflation(opts: Record<string, unknown>): void {
  if (!map) return;
  const r = opts.inflate_m as number;
  const key = `${mapVersion}|${r}|${opts.allow_unknown}`;
  if (key === inflationKey) return;
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
}

function replan(): void {
  if (!map) return;
  const opts = readOptions();
  updateInflation(opts);
  view.setEndpoints(start, goal);
  const empty = { path: null, expanded: null, keyPoints: null, featureNodes: null, inflation };
  ui.canvas.dataset.start = start ? start.join(',') : '';
  ui.canvas.dataset.goal = goal ? goal.join(',') : '';
  planSeq += 1;
  ui.body.dataset.planSeq = String(planSeq);
  if (!start || !goal) {
    view.setLayers(empty);
    clearMetrics();
    clearError();
    ui.body.dataset.state = 'idle';
    ui.canvas.dataset.pathLen = '0';
    ui.status.textContent = !start ? 'Place the start: click a free cell.' : 'Place the goal: click a free cell.';
    return;
  }
  const t0 = performance.now();
  let res;
  try {
    res = plan(map, start[0], start[1], goal[0], goal[1], opts, ui.showExpanded.checked);
  } catch (e) {
    view.setLayers(empty);
    clearMetrics();
    ui.canvas.dataset.pathLen = '0';
    ui.status.textContent = 'No path.';
    showError(messageOf(e));
    return;
  }
  const ms = performance.now() - t0;
  try {
    const path = res.path();
    const keyPoints = res.keyPoints();
    const featureNodes = res.featureNodes();
    const safety = res.safety();
    view.setLayers({ path, expanded: res.expanded(), keyPoints, featureNodes, inflation });
    clearError();
    ui.body.dataset.state = 'ok';
    setMetric(ui.metric.cost, res.cost.toFixed(4), res.cost);
    setMetric(ui.metric.length, `${res.lengthM.toFixed(2)} m`, res.lengthM);
    setMetric(ui.metric.expanded, res.expandedCount.toLocaleString('en-US'), res.expandedCount);
    setMetric(ui.metric.nodes, String(res.pathLen), res.pathLen);
    const kp = keyPoints.length / 2;
    const fn = featureNodes.length / 2;
    const parts = [];
    if (opts.keypoints) parts.push(String(kp));
    if (opts.bottom_up_eps !== null) parts.push(`${fn} BU`);
    setMetric(ui.metric.keypoints, parts.length ? parts.join(' · ') : '—', opts.keypoints ? kp : null);
    setMetric(ui.metric.time, `${ms.toFixed(2)} ms`, ms);
    ui.canvas.dataset.pathLen = String(res.pathLen);
    ui.canvas.dataset.path = Array.from(path).join(',');
    let status = `Path found: ${res.pathLen} cells, ${res.lengthM.toFixed(2)} m`;
    if (safety.length) status += ` · min safety index ${safety.reduce((a, b) => Math.min(a, b), Infinity).toFixed(2)}/10`;
    ui.status.textContent = status;
  } finally {
    res.free();
  }
}

// -------------------------------------------------------------- map loading
function installMap(m: MapHandle, name: string, s: Cell | null, g: Cell | null): void {
  map?.free();
  loaded?.free();
  map = m;
  loaded = m.clone();
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
  view.setMap(m.width, m.height, m.cells());
  setTool(s && g ? tool : 'start');
  replan();
}

async function fetchText(path: string): Promise<string> {
  const r = await fetch(new URL(path, document.baseURI));
  if (!r.ok) throw new Error(`cannot load ${path}: HTTP ${r.status}`);
  return r.text();
}

async function fetchBytes(path: string): Promise<Uint8Array> {
  const r = await fetch(new URL(path, document.baseURI));
  if (!r.ok) throw new Error(`cannot load ${path}: HTTP ${r.status}`);
  return new Uint8Array(await r.arrayBuffer());
}

async function loadPreset(key: string): Promise<void> {
  const p = PRESETS[key];
  if (!p) throw new Error(`unknown preset ${key}`);
  if (p.kind === 'scenario') {
    installScenario(ScenarioHandle.fromJson(await fetchText(p.files[0])), p.name, {});
    return;
  }
  let m: MapHandle;
  if (p.kind === 'movingai') {
    m = MapHandle.fromMovingAi(await fetchText(p.files[0]));
  } else {
    const [yaml, pgm] = await Promise.all([fetchText(p.files[0]), fetchBytes(p.files[1])]);
    m = MapHandle.fromRos(yaml, pgm);
  }
  installMap(m, p.name, p.start ?? null, p.goal ?? null);
}

/**
 * Installs a scenario: its map (inline, or a referenced file looked up in
 * `files` by name), endpoints and planner options.
 */
function installScenario(
  sc: ScenarioHandle,
  name: string,
  files: Record<string, Uint8Array>,
  extra: Record<string, unknown> = {},
): void {
  try {
    const m = sc.loadMap(files);
    applyOptions({ ...defaults, ...(sc.plannerOptions() as Record<string, unknown>), ...extra });
    const s = sc.start();
    const g = sc.goal();
    installMap(m, sc.name ? `${sc.name} (${name})` : name, [s[0], s[1]], [g[0], g[1]]);
  } finally {
    sc.free();
  }
}

const ext = (f: File) => f.name.toLowerCase().split('.').pop() ?? '';

/** Reads the files the user picked: one `.map`, or a ROS `.yaml` + `.pgm`. */
async function loadFiles(list: FileList | null): Promise<void> {
  const files = Array.from(list ?? []);
  if (!files.length) return;
  checkSizes(files);
  const yaml = files.find((f) => ext(f) === 'yaml' || ext(f) === 'yml');
  const pgms = files.filter((f) => ext(f) === 'pgm');
  const movingai = files.find((f) => ext(f) === 'map');
  const ascii = files.find((f) => ext(f) === 'txt');
  const json = files.find((f) => ext(f) === 'json');
  let m: MapHandle;
  let name: string;
  if (json) {
    // A scenario; the map files it references may be among the others.
    const bytes: Record<string, Uint8Array> = {};
    for (const f of files) if (f !== json) bytes[f.name] = new Uint8Array(await f.arrayBuffer());
    try {
      installScenario(ScenarioHandle.fromJson(await json.text()), json.name, bytes);
    } catch (e) {
      throw new Error(`${json.name}: ${messageOf(e)}`);
    }
    ui.preset.value = '';
    return;
  }
  if (yaml) {
    name = yaml.name;
    const yamlText = await yaml.text();
    let image = '';
    try {
      image = rosImageName(yamlText);
    } catch (e) {
      throw new Error(`${yaml.name}: ${messageOf(e)}`);
    }
    const base = image.split(/[\\/]/).pop() ?? image;
    const pgm = pgms.length === 1 ? pgms[0] : pgms.find((f) => f.name === base);
    if (!pgm) {
      throw new Error(
        pgms.length
          ? `${yaml.name} names the image "${image}", but none of the opened .pgm files is called ${base}.`
          : `${yaml.name} needs its image "${image}": select the .yaml and the .pgm file together.`,
      );
    }
    try {
      m = MapHandle.fromRos(yamlText, new Uint8Array(await pgm.arrayBuffer()));
    } catch (e) {
      throw new Error(`${yaml.name} + ${pgm.name}: ${messageOf(e)}`);
    }
  } else if (movingai) {
    name = movingai.name;
    try {
      m = MapHandle.fromMovingAi(await movingai.text());
    } catch (e) {
      throw new Error(`${movingai.name}: ${messageOf(e)}`);
    }
  } else if (ascii) {
    name = ascii.name;
    try {
      m = MapHandle.fromAscii(await ascii.text());
    } catch (e) {
      throw new Error(`${ascii.name}: ${messageOf(e)}`);
    }
  } else if (pgms.length) {
    throw new Error(
      `${pgms[0].name} is only the image of a ROS map: select it together with its .yaml (resolution, origin, thresholds).`,
    );
  } else {
    throw new Error(
      `Cannot open ${files.map((f) => f.name).join(', ')}: expected a Moving AI .map, a ROS .yaml with its .pgm, or a planlab scenario .json.`,
    );
  }
  installMap(m, name, null, null);
  ui.preset.value = '';
}

// ------------------------------------------------------------------- input
function canvasPoint(ev: MouseEvent): [number, number] {
  const r = ui.canvas.getBoundingClientRect();
  return [ev.clientX - r.left, ev.clientY - r.top];
}

let painting: { kind: number; last: Cell | null } | null = null;
let panning: { x: number; y: number } | null = null;

function paintTo(cell: Cell | null): void {
  if (!map || !painting) return;
  if (!cell) {
    painting.last = null;
    return;
  }
  const from = painting.last ?? cell;
  const changed = map.paintSegment(from[0], from[1], cell[0], cell[1], painting.kind);
  painting.last = cell;
  if (changed > 0) {
    mapVersion += 1;
    cellsDirty = true;
    scheduleReplan();
  }
}

function describeCell(cell: Cell | null): string {
  if (!cell || !map) return '—';
  const kind = CELL_NAMES[view.cellKind(cell[0], cell[1]) ?? 0];
  const [x, y] = map.cellToWorld(cell[0], cell[1]);
  return `cell (${cell[0]}, ${cell[1]}) · ${kind} · world (${x.toFixed(2)}, ${y.toFixed(2)}) m`;
}

ui.canvas.addEventListener(
  'pointerdown',
  guard((ev: PointerEvent) => {
    if (!map) return;
    const [x, y] = canvasPoint(ev);
    if (ev.button === 1 || ev.button === 2 || (ev.button === 0 && ev.altKey)) {
      panning = { x: ev.clientX, y: ev.clientY };
      ui.canvas.classList.add('panning');
      ui.canvas.setPointerCapture(ev.pointerId);
      ev.preventDefault();
      return;
    }
    if (ev.button !== 0) return;
    const cell = view.cellAt(x, y);
    if (!cell) return;
    if (ev.shiftKey || tool === 'goal') {
      goal = cell;
      scheduleReplan();
    } else if (tool === 'start') {
      start = cell;
      scheduleReplan();
    } else {
      painting = { kind: tool === 'wall' ? 1 : 0, last: null };
      ui.canvas.setPointerCapture(ev.pointerId);
      paintTo(cell);
    }
  }),
);

ui.canvas.addEventListener(
  'pointermove',
  guard((ev: PointerEvent) => {
    const [x, y] = canvasPoint(ev);
    if (panning) {
      view.panBy(ev.clientX - panning.x, ev.clientY - panning.y);
      panning = { x: ev.clientX, y: ev.clientY };
      return;
    }
    const cell = view.cellAt(x, y);
    ui.hover.textContent = describeCell(cell);
    if (painting) paintTo(cell);
  }),
);

const endStroke = guard((ev: PointerEvent) => {
  painting = null;
  panning = null;
  ui.canvas.classList.remove('panning');
  if (ui.canvas.hasPointerCapture(ev.pointerId)) ui.canvas.releasePointerCapture(ev.pointerId);
});
ui.canvas.addEventListener('pointerup', endStroke);
ui.canvas.addEventListener('pointercancel', endStroke);
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

window.addEventListener('keydown', (ev) => {
  const t = ev.target as HTMLElement | null;
  if (t && (t.tagName === 'INPUT' || t.tagName === 'SELECT' || t.tagName === 'TEXTAREA')) return;
  if (ev.ctrlKey || ev.metaKey || ev.altKey) return;
  const keys: Record<string, Tool> = { s: 'start', g: 'goal', w: 'wall', e: 'erase' };
  const k = ev.key.toLowerCase();
  if (keys[k]) setTool(keys[k]);
  else if (k === 'f') view.fit();
});

for (const c of [
  ui.algorithm,
  ui.heuristic,
  ui.weight,
  ui.diagonal,
  ui.safeEpsilon,
  ui.safeNeighbourhood,
  ui.safeAdmissible,
  ui.inflate,
  ui.allowUnknown,
  ui.keypoints,
  ui.bottomUp,
  ui.bottomUpEps,
  ui.showExpanded,
]) {
  c.addEventListener('input', () => {
    syncControls();
    scheduleReplan();
  });
}

ui.preset.addEventListener(
  'change',
  guard(async () => {
    if (ui.preset.value) await loadPreset(ui.preset.value);
  }),
);
ui.file.addEventListener(
  'change',
  guard(async () => {
    try {
      await loadFiles(ui.file.files);
    } finally {
      // Lets the same file be picked again after fixing it.
      ui.file.value = '';
    }
  }),
);
ui.reset.addEventListener(
  'click',
  guard(() => {
    if (!loaded) return;
    map?.free();
    map = loaded.clone();
    mapVersion += 1;
    cellsDirty = true;
    scheduleReplan();
  }),
);
ui.fitView.addEventListener('click', () => view.fit());

// -------------------------------------------------------------------- boot
async function boot(): Promise<void> {
  setTool('start');
  syncControls();
  clearMetrics();
  await init();
  defaults = defaultPlanOptions() as Record<string, unknown>;
  applyOptions(defaults);
  syncControls();
  ui.hint.textContent = hintForTool();
  // `?scenario=FILE` (+ planner options): a site scenario as a global plan.
  const url = gridUrl();
  if (url.scenario) {
    try {
      const { text, files } = await loadPresetFiles(url.scenario);
      installScenario(ScenarioHandle.fromJson(text), url.scenario, files, url.options);
      const linked = ui.preset.querySelector<HTMLOptionElement>('option[value=""]');
      if (linked) linked.textContent = `${url.scenario} (linked)`;
      ui.preset.value = '';
    } catch (e) {
      url.problems.unshift(`${url.scenario}: ${messageOf(e)}`);
      await loadPreset(ui.preset.value || 'arena');
    }
  } else {
    await loadPreset(ui.preset.value || 'arena');
    if (Object.keys(url.options).length) {
      applyOptions({ ...readOptions(), ...url.options });
      replan();
    }
  }
  if (url.problems.length) showError(url.problems.join(' · '));
}

installShell(gridHelp());

boot().catch((e) => {
  showError(`Could not start the playground: ${messageOf(e)}`);
});
