// Compare page wiring: one scenario, 2–4 planners, each on its own wasm
// SimHandle built from the same scenario JSON (the planner swapped in the
// way `planlab run --planner` does it), stepped together from the animation
// frame so they stay at the same simulated time; drawn side by side (a
// RobotView each) or overlaid (one view, a colour per planner), with the
// `planlab run` metrics in a table and the winner of each row marked.
// URL: ?scenario=FILE&planners=a,b&set=path=value (repeatable, as `planlab
// run --set`)&view=side|overlay&speed=X&autorun=1|instant

import init, { SimHandle, planners as plannerListJson } from '../../pkg/planlab_wasm.js';
import presets from 'virtual:robot-presets';
import { fillPresetSelect } from '../shell/preset-select';
import { RobotView, type RobotShape } from '../robot/view';
import type { PlannerInfo } from '../robot/params';
import { Lane, LANE_COLOURS } from './lane';
import { OverlayView } from './overlay';
import { ROWS, cellText, tableCsv, winners } from './table';
import { compareHelp } from './help';
import { installShell } from '../shell/help';
import { loadPresetFiles, readPicked } from '../shell/scenario-files';
import { applyRun, runParams } from '../shell/runlink';
import { el, messageOf, errorBanner } from '../shell/dom';

/** Planners compared at once. */
const MIN_PLANNERS = 2;
const MAX_PLANNERS = 4;
/** Most synchronised control steps (one per planner) in one frame. */
const MAX_ROUNDS_PER_FRAME = 16;
/** Simulation budget per frame, ms (slower than the speed rather than dropping frames). */
const SIM_BUDGET_MS = 10;
/** "Run to end": work per slice before the page gets a frame, ms. */
const INSTANT_SLICE_MS = 40;
const SLOW_REFRESH_MS = 250;

type ViewMode = 'side' | 'overlay';



const ui = {
  body: document.body,
  hint: el('hint'),
  preset: el<HTMLSelectElement>('preset'),
  file: el<HTMLInputElement>('file-input'),
  description: el('scenario-description'),
  mapSize: el('map-size'),
  seed: el('seed'),
  edits: el('edits'),
  simDt: el('sim-dt'),
  plannerList: el<HTMLUListElement>('planner-list'),
  plannerCount: el('planner-count'),
  plannerHint: el('planner-hint'),
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

// ------------------------------------------------------------------ errors
const { showError, clearError, guard } = errorBanner(ui.error, ui.body);

// ------------------------------------------------------------------- state
let infos: PlannerInfo[] = [];
/** Picked planner names, in the order picked (= colours and columns). */
let chosen: string[] = [];
let scenarioText = '';
let scenarioFile = '';
let scenarioFiles: Record<string, Uint8Array> = {};
/** `set=path=value` edits from the URL (as `planlab run --set`), applied
 *  to the scenario for every planner; dropped when another scenario opens. */
let edits: [string, string][] = [];
let lanes: Lane[] = [];
let sideViews: RobotView[] = [];
const overlay = new OverlayView(ui.overlayCanvas);
let viewMode: ViewMode = 'side';
let playing = false;
/** Bumped by every rebuild / reset: a running "run to end" stops. */
let generation = 0;
let instantRunning = false;
let speed = 4;
let dt = 0.1;
let accum = 0;
let lastFrame = 0;
let lastSlow = 0;

// --------------------------------------------------------------- scenario
/** The scenario's own planner (null when it names none or is not JSON). */
function scenarioPlanner(text: string): string | null {
  try {
    const n = (JSON.parse(text) as { local_planner?: { name?: unknown } }).local_planner?.name;
    return typeof n === 'string' ? n : null;
  } catch {
    return null;
  }
}

function robotShape(json: string): RobotShape {
  const r = JSON.parse(json) as { footprint?: { shape?: string; radius?: number; length?: number; width?: number } };
  const fp = r.footprint ?? {};
  return fp.shape === 'rectangle'
    ? { kind: 'rect', length: fp.length ?? 0.4, width: fp.width ?? 0.3 }
    : { kind: 'circle', radius: fp.radius ?? 0.2 };
}

function hexHash(dec: string | null): string {
  if (!dec) return '';
  try {
    return BigInt(dec).toString(16).padStart(16, '0');
  } catch {
    return dec;
  }
}

// ------------------------------------------------------------------ lanes
/** Builds a SimHandle per picked planner from the scenario; a planner that
 *  cannot run the scenario is reported and left out. */
function rebuild(): void {
  setPlaying(false);
  generation += 1;
  instantRunning = false;
  for (const l of lanes) l.free();
  lanes = [];
  sideViews = [];
  const problems: string[] = [];
  if (scenarioText) {
    for (const name of chosen) {
      try {
        // The CLI's edits: `--planner NAME`, then every `--set`.
        const sim = SimHandle.fromScenario(applyRun(scenarioText, name, edits), scenarioFiles);
        const colour = LANE_COLOURS[chosen.indexOf(name) % LANE_COLOURS.length];
        const lane = new Lane(name, colour, sim, robotShape(sim.robot()));
        lane.setRecordRollouts(ui.showFan.checked);
        lanes.push(lane);
      } catch (e) {
        problems.push(`${name}: ${messageOf(e)}`);
      }
    }
  }
  if (problems.length) showError(problems.join(' · '));
  else clearError();
  const first = lanes[0];
  if (first) {
    dt = first.sim.dt;
    ui.simDt.textContent = `${dt} s`;
    const map = first.sim.map();
    try {
      const origin = map.origin();
      const info = {
        width: map.width,
        height: map.height,
        resolution: map.resolution,
        originX: origin[0],
        originY: origin[1],
        cells: map.cells(),
      };
      ui.mapSize.textContent = `${map.width} × ${map.height} · ${map.resolution} m`;
      buildLaneDom(info);
      overlay.setMap(info);
    } finally {
      map.free();
    }
  } else {
    buildLaneDom(null);
  }
  for (const l of lanes) l.pull();
  overlay.setLanes(lanes);
  accum = 0;
  ui.body.dataset.state = lanes.length ? 'ready' : 'empty';
  renderAll();
  ui.body.dataset.lanes = String(lanes.length);
  ui.body.dataset.buildSeq = String(Number(ui.body.dataset.buildSeq ?? 0) + 1);
  delete ui.body.dataset.done;
}

function buildLaneDom(map: Parameters<RobotView['setMap']>[0] | null): void {
  const nodes = lanes.map((lane, i) => {
    const box = document.createElement('div');
    box.className = 'lane';
    box.dataset.planner = lane.name;
    box.style.setProperty('--lane', lane.colour);
    const head = document.createElement('div');
    head.className = 'lane-head';
    const sw = document.createElement('i');
    sw.className = 'lane-swatch';
    const name = document.createElement('b');
    name.textContent = lane.name;
    const state = document.createElement('span');
    state.className = 'lane-state';
    head.append(sw, name, state);
    const wrap = document.createElement('div');
    wrap.className = 'canvas-wrap';
    const canvas = document.createElement('canvas');
    canvas.className = 'lane-canvas';
    canvas.id = `lane-canvas-${i}`;
    canvas.setAttribute('aria-label', `${lane.name} on the scenario`);
    wrap.append(canvas);
    box.append(head, wrap);
    return box;
  });
  ui.lanes.replaceChildren(...nodes);
  ui.lanes.dataset.count = String(lanes.length);
  sideViews = lanes.map((lane, i) => {
    const v = new RobotView(nodes[i].querySelector('canvas') as HTMLCanvasElement);
    v.scene = lane.scene;
    lane.scene.show.path = ui.showPath.checked;
    lane.scene.show.fog = false;
    if (map) v.setMap(map);
    return v;
  });
}

// ------------------------------------------------------------- rendering
function paintViews(now = false): void {
  if (viewMode === 'side') for (const v of sideViews) now ? v.paint() : v.request();
  else now ? overlay.paint() : overlay.request();
}

function describe(o: string): string {
  return o === 'reached' ? 'reached the goal' : o === 'stuck' ? 'stuck (no progress)' : o === 'timeout' ? 'time out' : o;
}

function renderLaneHeads(): void {
  lanes.forEach((l, i) => {
    const head = ui.lanes.children[i]?.querySelector('.lane-state');
    if (head) {
      head.textContent = l.running ? `t = ${l.sim.time.toFixed(1)} s` : `${l.outcome} · ${l.sim.time.toFixed(1)} s`;
      (head as HTMLElement).title = l.running ? 'running' : describe(l.outcome);
      (head as HTMLElement).dataset.outcome = l.outcome;
    }
  });
  const items = lanes.map((l) => {
    const li = document.createElement('li');
    li.dataset.planner = l.name;
    const sw = document.createElement('i');
    sw.style.background = l.colour;
    const t = document.createElement('span');
    t.textContent = `${l.name}${l.running ? '' : ` · ${l.outcome}`}`;
    li.append(sw, t);
    return li;
  });
  ui.overlayLegend.replaceChildren(...items);
}

function allDone(): boolean {
  return lanes.length > 0 && lanes.every((l) => !l.running);
}

function renderTable(): void {
  const final = allDone() && lanes.length >= MIN_PLANNERS;
  const ms = lanes.map((l) => l.updateMetrics());
  const headRow = document.createElement('tr');
  const corner = document.createElement('th');
  corner.scope = 'col';
  corner.textContent = 'Metric';
  headRow.append(corner);
  for (const l of lanes) {
    const th = document.createElement('th');
    th.scope = 'col';
    th.dataset.planner = l.name;
    const sw = document.createElement('i');
    sw.className = 'lane-swatch';
    sw.style.background = l.colour;
    th.append(sw, document.createTextNode(l.name));
    headRow.append(th);
  }
  ui.table.tHead?.replaceChildren(headRow);
  const body = ui.table.tBodies[0];
  const rows: HTMLTableRowElement[] = [];
  if (lanes.length) {
    for (const row of ROWS) {
      const tr = document.createElement('tr');
      tr.dataset.metric = row.key;
      const th = document.createElement('th');
      th.scope = 'row';
      th.textContent = row.unit ? `${row.label} (${row.unit})` : row.label;
      th.title = row.doc;
      tr.append(th);
      const win = final ? new Set(winners(row, ms)) : new Set<number>();
      ms.forEach((m, i) => {
        const td = document.createElement('td');
        td.dataset.planner = lanes[i].name;
        const v = m[row.key];
        td.dataset.value = v === null ? '' : String(v);
        if (row.key === 'outcome') td.dataset.outcome = m.outcome;
        td.textContent = cellText(row, m);
        if (win.has(i)) {
          td.dataset.win = 'true';
          td.title = 'best in this row';
        }
        tr.append(td);
      });
      rows.push(tr);
    }
    const extra: [string, string, (l: Lane) => string][] = [
      ['steps', 'steps', (l) => String(l.sim.steps)],
      ['trace_hash', 'trace hash', (l) => (l.hash ? hexHash(l.hash) : '—')],
    ];
    for (const [key, label, f] of extra) {
      const tr = document.createElement('tr');
      tr.dataset.metric = key;
      tr.className = 'extra';
      const th = document.createElement('th');
      th.scope = 'row';
      th.textContent = label;
      tr.append(th);
      for (const l of lanes) {
        const td = document.createElement('td');
        td.dataset.planner = l.name;
        td.textContent = f(l);
        td.dataset.value = td.textContent;
        tr.append(td);
      }
      rows.push(tr);
    }
  }
  body.replaceChildren(...rows);
  ui.table.dataset.final = String(final);
  ui.copyCsv.disabled = lanes.length === 0;
}

function renderStatus(): void {
  if (!lanes.length) {
    ui.status.textContent = scenarioText ? 'No planner to run: pick 2 to 4.' : '—';
    return;
  }
  const t = Math.max(...lanes.map((l) => l.sim.time));
  const parts = lanes.map((l) => `${l.name} ${l.running ? 'running' : `${l.outcome} at ${l.sim.time.toFixed(1)} s`}`);
  const state = instantRunning ? 'running to the end…' : allDone() ? 'all done' : playing ? 'playing' : 'paused';
  ui.status.textContent = `t = ${t.toFixed(1)} s · ${parts.join(' · ')} · ${state}`;
  ui.body.dataset.time = String(t);
  ui.body.dataset.outcomes = lanes.map((l) => `${l.name}:${l.outcome}`).join(',');
}

function renderAll(): void {
  renderLaneHeads();
  renderTable();
  renderStatus();
  renderControls();
  paintViews();
}

// ------------------------------------------------------------ simulation
function setPlaying(on: boolean): void {
  playing = on && lanes.length >= MIN_PLANNERS && !allDone() && !instantRunning;
  ui.play.textContent = playing ? '❚❚ Pause' : '▶ Run';
  ui.play.dataset.playing = String(playing);
  ui.body.dataset.playing = String(playing);
  if (playing) {
    lastFrame = performance.now();
    accum = 0;
    ui.body.dataset.state = 'running';
    requestAnimationFrame(frame);
  }
  renderStatus();
}

/** One control step for every planner still running: all stay at the same time. */
function round(): void {
  for (const l of lanes) l.step(1);
}

/** Up to `n` rounds within the budget; returns how many ran. */
function advance(n: number, budgetMs = Infinity): number {
  const t0 = performance.now();
  let done = 0;
  let per = 0;
  while (done < n && !allDone()) {
    if (done > 0 && performance.now() - t0 + per > budgetMs) break;
    const t = performance.now();
    round();
    per = performance.now() - t;
    done += 1;
  }
  for (const l of lanes) l.pull();
  if (allDone()) finish();
  return done;
}

function finish(): void {
  playing = false;
  ui.play.textContent = '▶ Run';
  ui.play.dataset.playing = 'false';
  ui.body.dataset.playing = 'false';
  ui.body.dataset.state = 'done';
  ui.body.dataset.done = 'true';
  ui.hint.textContent = 'All episodes over: the table marks the best planner per metric. Reset to run again.';
  renderAll();
}

/** Per-frame work (all planners' steps + paint), ms, while playing. */
const frameWork: number[] = [];

function frame(now: number): void {
  if (!playing) return;
  requestAnimationFrame(frame);
  const interval = now - lastFrame;
  lastFrame = now;
  const t0 = performance.now();
  try {
    accum += (Math.min(interval, 100) / 1000) * speed;
    const due = Math.floor(accum / dt + 1e-9);
    const n = Math.min(due, MAX_ROUNDS_PER_FRAME);
    const ran = n > 0 ? advance(n, SIM_BUDGET_MS) : 0;
    accum = ran < due ? 0 : accum - ran * dt;
    if (ran > 0) paintViews(true);
    if (now - lastSlow > SLOW_REFRESH_MS) {
      lastSlow = now;
      renderLaneHeads();
      renderTable();
      renderStatus();
    }
    if (frameWork.length < 100_000) frameWork.push(performance.now() - t0);
  } catch (e) {
    setPlaying(false);
    showError(messageOf(e));
  }
}

/** Runs every planner to the end of its episode, yielding to the page
 *  between slices (progress shows; Reset stops it). */
async function runToEnd(): Promise<void> {
  if (lanes.length < MIN_PLANNERS || allDone()) return;
  setPlaying(false);
  const gen = generation;
  const t0 = performance.now();
  instantRunning = true;
  ui.body.dataset.state = 'running';
  renderControls();
  // Rollouts are not drawn while racing to the end: recording them is work.
  for (const l of lanes) l.sim.setRecordRollouts(false);
  try {
    while (!allDone()) {
      const t0 = performance.now();
      while (!allDone() && performance.now() - t0 < INSTANT_SLICE_MS) round();
      for (const l of lanes) l.pull();
      renderLaneHeads();
      renderStatus();
      paintViews(true);
      await new Promise((r) => setTimeout(r, 0));
      if (gen !== generation) return;
    }
  } finally {
    if (gen === generation) {
      instantRunning = false;
      for (const l of lanes) l.sim.setRecordRollouts(ui.showFan.checked);
    }
  }
  // Wall time of the whole run (slices, pulls and paints included), for the curious and the e2e log.
  ui.body.dataset.instantMs = (performance.now() - t0).toFixed(0);
  finish();
}

// ------------------------------------------------------------- controls
function renderControls(): void {
  const n = chosen.length;
  ui.plannerCount.textContent = `${n} / ${MAX_PLANNERS}`;
  for (const li of Array.from(ui.plannerList.children) as HTMLElement[]) {
    const box = li.querySelector('input') as HTMLInputElement;
    const name = li.dataset.planner ?? '';
    const idx = chosen.indexOf(name);
    box.checked = idx >= 0;
    box.disabled = instantRunning || (idx < 0 && n >= MAX_PLANNERS);
    li.title = idx < 0 && n >= MAX_PLANNERS ? `At most ${MAX_PLANNERS} planners at once: untick one first.` : (infos.find((p) => p.name === name)?.summary ?? '');
    const sw = li.querySelector('.lane-swatch') as HTMLElement;
    sw.style.background = idx >= 0 ? LANE_COLOURS[idx % LANE_COLOURS.length] : 'transparent';
  }
  let hint: string;
  let warn = false;
  if (n < MIN_PLANNERS) {
    hint = n === 0 ? 'Pick 2 to 4 planners to compare.' : `Pick at least one more planner: a comparison needs ${MIN_PLANNERS} to ${MAX_PLANNERS}.`;
    warn = true;
  } else if (n >= MAX_PLANNERS) {
    hint = `${MAX_PLANNERS} planners picked (the most at once): untick one to pick another.`;
  } else {
    hint = `${n} planners picked; up to ${MAX_PLANNERS}.`;
  }
  ui.plannerHint.textContent = hint;
  ui.plannerHint.dataset.warn = String(warn);
  const ready = lanes.length >= MIN_PLANNERS && !instantRunning;
  ui.play.disabled = !ready || allDone();
  ui.step.disabled = !ready || allDone();
  ui.instant.disabled = !ready || allDone();
  ui.reset.disabled = !lanes.length || instantRunning;
  if (!instantRunning && ui.body.dataset.state !== 'done') {
    ui.hint.textContent = ready ? 'Run: every planner steps together, at the same simulated time.' : hint;
  }
}

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
  if (scenarioFile) q.set('scenario', scenarioFile);
  if (chosen.length) q.set('planners', chosen.join(','));
  for (const [p, v] of edits) q.append('set', `${p}=${v}`);
  q.set('view', viewMode);
  history.replaceState(null, '', `${location.pathname}?${q.toString().replaceAll('%2C', ',')}`);
}

function buildPlannerList(): void {
  const items = infos.map((p) => {
    const li = document.createElement('li');
    li.dataset.planner = p.name;
    const label = document.createElement('label');
    label.className = 'check';
    const box = document.createElement('input');
    box.type = 'checkbox';
    box.value = p.name;
    box.id = `pick-${p.name}`;
    box.addEventListener(
      'change',
      guard(() => {
        if (box.checked) {
          if (chosen.length >= MAX_PLANNERS) {
            box.checked = false;
            throw new Error(`At most ${MAX_PLANNERS} planners can be compared at once.`);
          }
          chosen.push(p.name);
        } else {
          chosen = chosen.filter((n) => n !== p.name);
        }
        updateUrl();
        rebuild();
      }),
    );
    const sw = document.createElement('i');
    sw.className = 'lane-swatch';
    const name = document.createElement('span');
    name.textContent = p.name;
    label.append(box, sw, name);
    li.append(label);
    return li;
  });
  ui.plannerList.replaceChildren(...items);
}

/** Applies a planner list (URL or link): unknown names and more than the
 *  maximum are reported, the rest kept. */
function applyPlanners(names: string[]): void {
  const known = new Set(infos.map((p) => p.name));
  const problems: string[] = [];
  const out: string[] = [];
  for (const n of names) {
    if (!n) continue;
    if (!known.has(n)) problems.push(`unknown planner “${n}” (known: ${[...known].join(', ')})`);
    else if (!out.includes(n)) out.push(n);
  }
  if (out.length > MAX_PLANNERS) {
    problems.push(`at most ${MAX_PLANNERS} planners can be compared; kept ${out.slice(0, MAX_PLANNERS).join(', ')}`);
    out.length = MAX_PLANNERS;
  }
  chosen = out;
  if (problems.length) throw new Error(problems.join(' · '));
}

// ----------------------------------------------------------------- files
/** Takes a scenario as the one compared on, with `newEdits` (`--set`)
 *  applied: checked by building it with its own planner first, so a broken
 *  file is reported as such; edits that break it are reported and dropped. */
function setScenario(text: string, file: string, label: string, files: Record<string, Uint8Array>, newEdits: [string, string][] = []): void {
  const problems: string[] = [];
  let kept = newEdits;
  if (kept.length) {
    try {
      SimHandle.fromScenario(applyRun(text, null, kept), files).free();
    } catch (e) {
      problems.push(`edits ${kept.map(([p, v]) => `${p}=${v}`).join(', ')} not applied: ${messageOf(e)}`);
      kept = [];
    }
  }
  if (!kept.length) SimHandle.fromScenario(text, files).free();
  scenarioText = text;
  scenarioFile = file;
  scenarioFiles = files;
  edits = kept;
  ui.edits.textContent = edits.length ? edits.map(([p, v]) => `${p}=${v}`).join(', ') : '—';
  ui.edits.title = ui.edits.textContent;
  try {
    const s = JSON.parse(text) as { name?: string; description?: string; seed?: number };
    ui.description.textContent = s.description || s.name || label;
    ui.description.title = s.description ?? '';
    ui.seed.textContent = String(s.seed ?? 0);
  } catch {
    ui.description.textContent = label;
  }
  const own = scenarioPlanner(text);
  for (const li of Array.from(ui.plannerList.children) as HTMLElement[]) {
    li.dataset.own = String(li.dataset.planner === own);
  }
  updateUrl();
  rebuild();
  if (problems.length) showError(problems.join(' · '));
}

async function loadPreset(file: string, withEdits: [string, string][] = []): Promise<void> {
  try {
    const { text, files } = await loadPresetFiles(file);
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
    ui.preset.value = '';
  }),
);
ui.play.addEventListener('click', guard(() => setPlaying(!playing)));
ui.step.addEventListener(
  'click',
  guard(() => {
    setPlaying(false);
    advance(1);
    renderAll();
  }),
);
ui.reset.addEventListener(
  'click',
  guard(() => {
    rebuild();
    ui.hint.textContent = 'Back at the start.';
  }),
);
ui.instant.addEventListener('click', guard(() => runToEnd()));
ui.speed.addEventListener('input', () => {
  speed = Number(ui.speed.value) || 1;
  ui.speedOut.textContent = `${speed}×`;
});
for (const b of ui.views) b.addEventListener('click', () => setView(b.dataset.view as ViewMode));
ui.showFan.addEventListener(
  'change',
  guard(() => {
    for (const l of lanes) {
      l.setRecordRollouts(ui.showFan.checked);
      if (!ui.showFan.checked) l.scene.fan = { ...l.scene.fan, offsets: new Uint32Array(0) };
      l.pull();
    }
    paintViews();
  }),
);
// Zoom and pan move every view together, so the planners stay comparable
// at the same place: wheel = zoom, right / middle / Alt drag = pan,
// double click = fit.
let panFrom: { x: number; y: number } | null = null;
function allViews(): RobotView[] {
  return viewMode === 'side' ? sideViews : [overlay.view];
}
function onCanvas(ev: Event): HTMLCanvasElement | null {
  const t = ev.target as HTMLElement | null;
  return t instanceof HTMLCanvasElement && (t.classList.contains('lane-canvas') || t === ui.overlayCanvas) ? t : null;
}
ui.stage.addEventListener(
  'wheel',
  (ev) => {
    const cv = onCanvas(ev);
    if (!cv) return;
    ev.preventDefault();
    const r = cv.getBoundingClientRect();
    const f = Math.exp(-ev.deltaY * 0.0015);
    for (const v of allViews()) v.zoomAt(ev.clientX - r.left, ev.clientY - r.top, f);
    overlay.sync();
  },
  { passive: false },
);
ui.stage.addEventListener('pointerdown', (ev) => {
  const cv = onCanvas(ev);
  if (!cv || !(ev.button === 1 || ev.button === 2 || (ev.button === 0 && ev.altKey))) return;
  panFrom = { x: ev.clientX, y: ev.clientY };
  cv.setPointerCapture(ev.pointerId);
  ev.preventDefault();
});
ui.stage.addEventListener('pointermove', (ev) => {
  if (!panFrom) return;
  for (const v of allViews()) v.panBy(ev.clientX - panFrom.x, ev.clientY - panFrom.y);
  panFrom = { x: ev.clientX, y: ev.clientY };
});
for (const type of ['pointerup', 'pointercancel'] as const) ui.stage.addEventListener(type, () => (panFrom = null));
ui.stage.addEventListener('contextmenu', (ev) => {
  if (onCanvas(ev)) ev.preventDefault();
});
ui.stage.addEventListener('dblclick', (ev) => {
  if (onCanvas(ev)) for (const v of allViews()) v.fit();
});

ui.showPath.addEventListener('change', () => {
  for (const l of lanes) l.scene.show.path = ui.showPath.checked;
  overlay.showPath = ui.showPath.checked;
  paintViews();
});

async function copyText(text: string): Promise<void> {
  try {
    await navigator.clipboard.writeText(text);
    return;
  } catch {
    // No clipboard permission (e.g. an http page): the old way.
  }
  const ta = document.createElement('textarea');
  ta.value = text;
  ta.style.position = 'fixed';
  ta.style.opacity = '0';
  document.body.append(ta);
  ta.select();
  const ok = document.execCommand('copy');
  ta.remove();
  if (!ok) throw new Error('the browser refused to copy to the clipboard');
}

function currentCsv(): string {
  return tableCsv(
    lanes.map((l) => l.name),
    lanes.map((l) => l.updateMetrics()),
    { steps: lanes.map((l) => l.sim.steps), hashes: lanes.map((l) => hexHash(l.hash)) },
    allDone(),
  );
}

ui.copyCsv.addEventListener(
  'click',
  guard(async () => {
    const csv = currentCsv();
    await copyText(csv);
    ui.csvStatus.textContent = `Copied ${csv.trim().split('\n').length - 1} rows as CSV.`;
    ui.body.dataset.copied = String(Number(ui.body.dataset.copied ?? 0) + 1);
  }),
);

window.addEventListener('keydown', (ev) => {
  const t = ev.target as HTMLElement | null;
  if (t && (t.tagName === 'INPUT' || t.tagName === 'SELECT' || t.tagName === 'TEXTAREA')) return;
  if (ev.ctrlKey || ev.metaKey || ev.altKey) return;
  const k = ev.key.toLowerCase();
  if (k === ' ') {
    ev.preventDefault();
    if (!ui.play.disabled) ui.play.click();
  } else if (k === '.') ui.step.click();
  else if (k === 'r') ui.reset.click();
  else if (k === 'e') ui.instant.click();
  else if (k === 'v') setView(viewMode === 'side' ? 'overlay' : 'side');
});

/** For the e2e tests: the metrics and hashes per planner, and the CSV. */
(window as unknown as { planlabCompare: unknown }).planlabCompare = {
  metrics: () => Object.fromEntries(lanes.map((l) => [l.name, l.metrics])),
  hashes: () => Object.fromEntries(lanes.map((l) => [l.name, l.hash])),
  csv: () => currentCsv(),
  chosen: () => [...chosen],
  frameStats: () => {
    const xs = [...frameWork].sort((a, b) => a - b);
    const q = (p: number) => (xs.length ? xs[Math.min(xs.length - 1, Math.floor(p * (xs.length - 1) + 0.5))] : Number.NaN);
    return { frames: xs.length, median: q(0.5), p95: q(0.95), max: xs.length ? xs[xs.length - 1] : Number.NaN };
  },
  resetMeter: () => (frameWork.length = 0),
};

// -------------------------------------------------------------------- boot
async function boot(): Promise<void> {
  fillPresetSelect(ui.preset);
  await init();
  infos = JSON.parse(plannerListJson()) as PlannerInfo[];
  buildPlannerList();

  // Read before anything rewrites the URL (updateUrl).
  const q = new URLSearchParams(location.search);
  const urlEdits = runParams(location.search).set;
  const v = q.get('view');
  setView(v === 'overlay' ? 'overlay' : 'side');
  const sp = q.get('speed');
  if (sp && Array.from(ui.speed.options).some((o) => o.value === sp)) {
    ui.speed.value = sp;
    ui.speed.dispatchEvent(new Event('input'));
  }
  const problems: string[] = [];
  const want = q.get('scenario');
  let file = presets[0]?.file;
  if (want) {
    if (presets.some((p) => p.file === want)) file = want;
    else problems.push(`no preset “${want}”; showing ${file}`);
  }
  if (!file) throw new Error('no robot presets (assets/scenarios/*.json with a local_planner)');
  const names = q.get('planners');
  const own = presets.find((p) => p.file === file)?.planner;
  try {
    if (names !== null) applyPlanners(names.split(','));
    else applyPlanners(own && own !== 'dwa' ? ['dwa', own] : ['dwa', 'improved-dwa']);
  } catch (e) {
    problems.push(messageOf(e));
  }
  ui.preset.value = file;
  // Edits belong to the scenario the URL names.
  await loadPreset(file, file === want ? urlEdits : []);
  if (problems.length) showError([...problems, ...(ui.error.hidden ? [] : [ui.error.textContent ?? ''])].join(' · '));
  const auto = q.get('autorun');
  if (lanes.length >= MIN_PLANNERS && auto === 'instant') await runToEnd();
  else if (lanes.length >= MIN_PLANNERS && auto !== null && auto !== '0') setPlaying(true);
}

installShell(() => compareHelp(infos, chosen[0]));

boot().catch((e) => {
  ui.body.dataset.state = 'error';
  showError(`Could not start the comparison: ${messageOf(e)}`);
});
