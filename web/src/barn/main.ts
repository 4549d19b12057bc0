// BARN page wiring: a BARN world (Perille et al. 2020) from the site's
// worlds file, one planner or a race of 2–4 on the same world and seed,
// each a SimHandle built from the core's BARN scenario (`barnScenario`, the
// JSON `planlab run barn:N --planner P --seed S` runs, so the trace hashes
// agree), stepped in lock-step from the animation frame (shell/sim-clock.ts)
// and drawn by the robot pages' view: laser rays, the costmap the planner
// gets (scene/costmap.ts), robot, trail, start and goal; the goal's success
// circle and the true cylinders on request (overlay.ts). The score is the
// core's (`barnScore`).
// URL: ?world=N&planner=P&seed=S&noise=σ&mode=single|race&planners=a,b&autorun=1|instant

import init, {
  SimHandle,
  barnCylinders,
  barnPlanners,
  barnScenario,
  barnScore,
  drawLayerNames,
  planners as plannerListJson,
} from '../../pkg/planlab_wasm.js';
import { DrawList, Layer, checkLayers, mask } from '../scene/draw';
import { COST } from '../scene/costmap';
import { mapOf, type MapInfo, type RobotView } from '../scene/view';
import type { PlannerInfo } from '../shell/planner-info';
import { Race } from '../compare/race';
import { buildLanes, renderHeads } from '../compare/render';
import { MIN_PLANNERS, PlannerPicks } from '../compare/picks';
import { installShell } from '../shell/help';
import { installLegend } from '../shell/legend';
import { el, errorBanner, messageOf } from '../shell/dom';
import { SimClock } from '../shell/sim-clock';
import { bindSpeed } from '../shell/speed';
import { panZoom } from '../shell/canvas-input';
import { showDone, showPlaying, wireTransport } from '../shell/transport';
import { Worlds } from './worlds';
import { drawTruth } from './overlay';
import { renderResults, resultOf, scoreFormula } from './results';
import { barnHelp } from './help';

/** Most lock-step rounds (one control step per lane) in one frame. */
const MAX_ROUNDS_PER_FRAME = 16;
/** Simulation budget per frame, ms. */
const SIM_BUDGET_MS = 12;
const SLOW_REFRESH_MS = 250;
/** BARN's cylinder radius, m (core `barn::RADIUS`). */
const CYLINDER_RADIUS = 0.075;
const COSTMAP = mask(Layer.Costmap);

type Mode = 'single' | 'race';

const ui = {
  body: document.body,
  hint: el('hint'),
  world: el<HTMLInputElement>('world'),
  difficulty: el<HTMLSelectElement>('difficulty'),
  nextWorld: el<HTMLButtonElement>('next-world'),
  randomWorld: el<HTMLButtonElement>('random-world'),
  worldDifficulty: el('world-difficulty'),
  worldOt: el('world-ot'),
  worldCylinders: el('world-cylinders'),
  modes: Array.from(document.querySelectorAll<HTMLButtonElement>('#modes [data-mode]')),
  singleBox: el('single-box'),
  raceBox: el('race-box'),
  planner: el<HTMLSelectElement>('planner'),
  plannerSummary: el('planner-summary'),
  seed: el<HTMLInputElement>('seed'),
  noise: el<HTMLInputElement>('noise'),
  play: el<HTMLButtonElement>('play'),
  step: el<HTMLButtonElement>('step'),
  reset: el<HTMLButtonElement>('reset'),
  instant: el<HTMLButtonElement>('instant'),
  speed: el<HTMLSelectElement>('speed'),
  speedOut: el<HTMLOutputElement>('speed-out'),
  showLidar: el<HTMLInputElement>('show-lidar'),
  showCostmap: el<HTMLInputElement>('show-costmap'),
  showTrail: el<HTMLInputElement>('show-trail'),
  showTruth: el<HTMLInputElement>('show-truth'),
  error: el('error'),
  status: el('status'),
  stage: el('stage'),
  lanes: el('lanes'),
  results: el<HTMLTableElement>('results'),
  formula: el('score-formula'),
};

const { showError, clearError, guard } = errorBanner(ui.error, ui.body);

// ------------------------------------------------------------------- state
let worlds: Worlds | null = null;
let mode: Mode = 'single';
const picks = new PlannerPicks(el<HTMLUListElement>('planner-list'), el('planner-count'), el('planner-hint'));
const race = new Race();
let views: RobotView[] = [];
let infos: PlannerInfo[] = [];
/** The world the lanes run and its OT. */
let current = { id: 0, ot: 0 };
/** Lanes not shown in any overlay legend (the compare page's heads need one). */
const noLegend = document.createElement('ul');
let lastSlow = 0;

const clock = new SimClock(
  {
    advance: (n, budget) => advance(n, budget),
    afterFrame(ran, now) {
      if (ran > 0) paint(true);
      if (now - lastSlow > SLOW_REFRESH_MS) {
        lastSlow = now;
        renderSlow();
      }
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

// ------------------------------------------------------------------ inputs
/** A whole number from `input`, or a one-line error naming `what`. */
function wholeNumber(input: HTMLInputElement, what: string): number {
  const v = Number(input.value);
  if (input.value.trim() === '' || !Number.isInteger(v) || v < 0) throw new Error(`${what} “${input.value}” is not a whole number ≥ 0`);
  return v;
}

function chosen(): string[] {
  return mode === 'single' ? [ui.planner.value] : picks.chosen;
}

// ------------------------------------------------------------------ lanes
/** Builds a lane per chosen planner on the world, seed and noise of the
 *  inputs. Bad input throws a one-line error and keeps the lanes. */
function rebuild(): void {
  if (!worlds) return;
  setPlaying(false);
  const w = worlds;
  const id = wholeNumber(ui.world, 'World');
  const seed = wholeNumber(ui.seed, 'Seed');
  const noise = Number(ui.noise.value);
  const names = chosen();
  // One check with the first planner, so a bad world, seed or noise is
  // one message rather than one per lane.
  const probe = JSON.parse(barnScenario(w.text, id, names[0] ?? 'dwb', seed, noise)) as {
    goal: { world: { x: number; y: number } };
    sim: { goal_tolerance: number };
  };
  const info = w.get(id);
  current = { id, ot: info?.optimal_time ?? 0 };
  showWorld();
  const problems = race.rebuild({ text: w.text, build: (p) => SimHandle.fromScenario(barnScenario(w.text, id, p, seed, noise)) }, names, false);
  if (problems.length) showError(problems.join(' · '));
  else clearError();
  const first = race.lanes[0];
  const truth = first ? mapOf(new DrawList(first.sim.draw(mask(Layer.Map), 0))) : null;
  // The planner does not know the map: the view's base is blank ground in
  // the map's frame, and what the planner knows is the costmap over it.
  const blank: MapInfo | null = truth ? { ...truth, cells: new Uint8Array(truth.cells.length) } : null;
  if (first) clock.dt = first.sim.dt;
  views = buildLanes(ui.lanes, race.lanes, blank, true);
  const cylinders = barnCylinders(w.text, id);
  for (const v of views) {
    drawTruth(v, {
      cylinders,
      radius: CYLINDER_RADIUS,
      goal: [probe.goal.world.x, probe.goal.world.y],
      tolerance: probe.sim.goal_tolerance,
      show: () => ui.showTruth.checked,
    });
  }
  applyToggles();
  pull();
  ui.body.dataset.state = race.lanes.length ? 'ready' : 'empty';
  ui.body.dataset.buildSeq = String(Number(ui.body.dataset.buildSeq ?? 0) + 1);
  delete ui.body.dataset.done;
  updateUrl();
  renderAll();
}

function applyToggles(): void {
  for (const l of race.lanes) {
    const s = l.scene.show;
    s.fan = false;
    s.fog = false;
    s.lidar = ui.showLidar.checked;
    s.costmap = ui.showCostmap.checked;
    s.trail = ui.showTrail.checked;
  }
}

/** The live end of every lane, and its costmap when shown. */
function pull(): void {
  race.pull();
  pullCostmaps();
}

function pullCostmaps(): void {
  for (const l of race.lanes) {
    if (l.scene.show.costmap) l.scene.frame.put(new DrawList(l.sim.draw(COSTMAP, 0)), COSTMAP);
  }
}

// ------------------------------------------------------------- rendering
function paint(now = false): void {
  for (const v of views) now ? v.paint() : v.request();
}

function showWorld(): void {
  const info = worlds?.get(current.id);
  ui.worldDifficulty.textContent = info?.difficulty ?? '—';
  ui.worldOt.textContent = info ? `${info.optimal_time.toFixed(2)} s` : '—';
  ui.worldCylinders.textContent = info ? String(info.cylinders) : '—';
}

function renderStatus(): void {
  const lanes = race.lanes;
  if (!lanes.length) {
    ui.status.textContent = mode === 'race' ? 'Pick 2 to 4 planners to race.' : '—';
    ui.formula.textContent = 'score = success · OT / clip(T, 2·OT, 8·OT)';
    return;
  }
  const state = race.instant ? 'running to the end…' : race.allDone() ? 'done' : clock.playing ? 'playing' : 'paused';
  const t = Math.max(...lanes.map((l) => l.sim.time));
  if (lanes.length === 1) {
    const r = resultOf(lanes[0], current.ot);
    ui.status.textContent =
      r.score === null
        ? `World ${current.id} · ${lanes[0].name} · t = ${r.time.toFixed(1)} s · ${state}`
        : `World ${current.id} · ${lanes[0].name} · ${r.outcome} · T = ${r.time.toFixed(2)} s · OT = ${r.ot.toFixed(2)} s · score ${r.score.toFixed(3)}`;
    ui.formula.textContent = scoreFormula(r) || 'score = success · OT / clip(T, 2·OT, 8·OT)';
  } else {
    const parts = lanes.map((l) => `${l.name} ${l.running ? 'running' : `${l.outcome} at ${l.sim.time.toFixed(1)} s`}`);
    ui.status.textContent = `World ${current.id} · t = ${t.toFixed(1)} s · ${parts.join(' · ')} · ${state}`;
    ui.formula.textContent = 'score = success · OT / clip(T, 2·OT, 8·OT)';
  }
  ui.body.dataset.time = String(t);
  ui.body.dataset.outcomes = lanes.map((l) => `${l.name}:${l.outcome}`).join(',');
}

function renderControls(): void {
  const [hint] = picks.render(race.instant);
  const ready = (mode === 'single' ? race.lanes.length === 1 : race.lanes.length >= MIN_PLANNERS) && !race.instant;
  ui.play.disabled = !ready || race.allDone();
  ui.step.disabled = !ready || race.allDone();
  ui.instant.disabled = !ready || race.allDone();
  ui.reset.disabled = !race.lanes.length || race.instant;
  if (!race.instant && ui.body.dataset.state !== 'done') {
    ui.hint.textContent = ready ? (race.lanes.length > 1 ? 'Run: the planners step together, at the same simulated time.' : 'Run: the robot sees only its laser scans.') : hint;
  }
}

/** What changes at the table's pace (heads, results, status). */
function renderSlow(): void {
  renderHeads(ui.lanes, noLegend, race.lanes);
  renderResults(ui.results, race.lanes, current.ot);
  renderStatus();
}

function renderAll(): void {
  renderSlow();
  renderControls();
  paint();
}

// ------------------------------------------------------------ simulation
function ready(): boolean {
  return race.lanes.length > 0 && !race.allDone() && !race.instant;
}

function setPlaying(on: boolean): void {
  const playing = on && ready();
  showPlaying(ui.play, ui.body, playing);
  clock.play(playing);
  // Paused: heads, table and status all say the time the lanes stopped at.
  renderSlow();
}

/** Up to `n` lock-step rounds within the budget; returns how many ran. */
function advance(n: number, budgetMs = Infinity): number {
  const done = race.rounds(clock, n, budgetMs);
  pull();
  if (race.allDone()) finish();
  return done;
}

function finish(): void {
  clock.play(false);
  showDone(ui.play, ui.body);
  ui.hint.textContent = 'Run over: the table has the outcome, time and BARN score. Reset to run again.';
  renderAll();
}

/** Runs every lane to its end in slices that yield to the page. */
async function runToEnd(): Promise<void> {
  if (!ready()) return;
  setPlaying(false);
  race.instant = true;
  ui.body.dataset.state = 'running';
  renderControls();
  const slice = () => {
    pullCostmaps();
    renderSlow();
    paint(true);
  };
  if (!(await race.runToEnd(slice, () => false))) return;
  finish();
}

// ------------------------------------------------------------- controls
function setMode(m: Mode): void {
  mode = m;
  for (const b of ui.modes) b.setAttribute('aria-checked', String(b.dataset.mode === m));
  ui.singleBox.hidden = m !== 'single';
  ui.raceBox.hidden = m !== 'race';
  ui.body.dataset.mode = m;
  if (m === 'race' && picks.chosen.length === 0) {
    picks.chosen = [ui.planner.value, ...barnPlanners().filter((p) => p !== ui.planner.value).slice(0, 1)];
  }
  rebuild();
}

function showPlanner(): void {
  const p = infos.find((i) => i.name === ui.planner.value);
  ui.plannerSummary.textContent = p ? (p.plain ?? p.summary) : '—';
  ui.plannerSummary.title = p?.paper ?? '';
}

function updateUrl(): void {
  const q = new URLSearchParams();
  q.set('world', String(current.id));
  q.set('mode', mode);
  if (mode === 'single') q.set('planner', ui.planner.value);
  else q.set('planners', picks.chosen.join(','));
  q.set('seed', ui.seed.value);
  q.set('noise', ui.noise.value);
  history.replaceState(null, '', `${location.pathname}?${q.toString().replaceAll('%2C', ',')}`);
}

function pickWorld(id: number): void {
  ui.world.value = String(id);
  rebuild();
}

ui.world.addEventListener('change', guard(rebuild));
ui.seed.addEventListener('change', guard(rebuild));
ui.noise.addEventListener('change', guard(rebuild));
ui.planner.addEventListener(
  'change',
  guard(() => {
    showPlanner();
    rebuild();
  }),
);
ui.nextWorld.addEventListener('click', guard(() => (worlds ? pickWorld(worlds.next(current.id, ui.difficulty.value).id) : undefined)));
ui.randomWorld.addEventListener('click', guard(() => (worlds ? pickWorld(worlds.random(ui.difficulty.value).id) : undefined)));
ui.difficulty.addEventListener(
  'change',
  guard(() => {
    const info = worlds?.get(current.id);
    // A world of another class: take the first of the chosen one.
    if (worlds && ui.difficulty.value && info?.difficulty !== ui.difficulty.value) pickWorld(worlds.next(0, ui.difficulty.value).id);
  }),
);
for (const b of ui.modes) b.addEventListener('click', guard(() => setMode(b.dataset.mode as Mode)));
wireTransport(
  ui,
  {
    toggle: () => setPlaying(!clock.playing),
    step: () => {
      setPlaying(false);
      advance(1);
      renderAll();
    },
    reset: rebuild,
    instant: runToEnd,
  },
  guard,
);
bindSpeed(ui.speed, ui.speedOut, clock);
for (const box of [ui.showLidar, ui.showCostmap, ui.showTrail, ui.showTruth]) {
  box.addEventListener(
    'change',
    guard(() => {
      applyToggles();
      pull();
      paint();
    }),
  );
}
panZoom(ui.stage, (c) => (c.classList.contains('lane-canvas') ? views : null));
ui.stage.addEventListener('dblclick', (ev) => {
  if (ev.target instanceof HTMLCanvasElement && ev.target.classList.contains('lane-canvas')) for (const v of views) v.fit();
});

/** For the e2e tests (and the console): the core's score, each lane's
 *  trace hash and what its costmap layer holds. */
(window as unknown as { planlabBarn: unknown }).planlabBarn = {
  score: (success: boolean, time: number, ot: number) => barnScore(success, time, ot),
  hashes: () => Object.fromEntries(race.lanes.map((l) => [l.name, l.hash])),
  worldCount: () => worlds?.list.length ?? 0,
  /** Cells of lane `i`'s costmap by kind: free, decay, inscribed, lethal, unknown. */
  costmapCounts: (i = 0) => {
    const l = race.lanes[i];
    if (!l) return null;
    const d = new DrawList(l.sim.draw(COSTMAP, 0));
    const k = d.first(Layer.Costmap);
    if (k >= d.end(Layer.Costmap)) return null;
    const n = { free: 0, decay: 0, inscribed: 0, lethal: 0, unknown: 0 };
    for (const c of d.cellBytes(k)) {
      if (c === COST.free) n.free++;
      else if (c === COST.inscribed) n.inscribed++;
      else if (c === COST.lethal) n.lethal++;
      else if (c === COST.unknown) n.unknown++;
      else n.decay++;
    }
    return n;
  },
};

// -------------------------------------------------------------------- boot
async function boot(): Promise<void> {
  await init();
  checkLayers(drawLayerNames());
  const names = barnPlanners();
  const all = JSON.parse(plannerListJson()) as PlannerInfo[];
  infos = names.map((n) => all.find((p) => p.name === n) ?? { name: n, paper: '', summary: '', fields: [] });
  ui.planner.replaceChildren(
    ...names.map((n) => {
      const o = document.createElement('option');
      o.value = n;
      o.textContent = n;
      return o;
    }),
  );
  ui.planner.value = 'dwb';
  picks.build(infos, guard, () => rebuild());
  worlds = await Worlds.fetch();
  ui.world.max = String(Math.max(...worlds.list.map((w) => w.id)));

  const q = new URLSearchParams(location.search);
  const problems: string[] = [];
  if (q.get('world')) ui.world.value = q.get('world') ?? '';
  if (q.get('seed')) ui.seed.value = q.get('seed') ?? '';
  if (q.get('noise')) ui.noise.value = q.get('noise') ?? '';
  const p = q.get('planner');
  if (p) {
    if (names.includes(p)) ui.planner.value = p;
    else problems.push(`unknown BARN planner “${p}” (known: ${names.join(', ')})`);
  }
  showPlanner();
  if (q.get('planners')) {
    try {
      picks.apply((q.get('planners') ?? '').split(','));
    } catch (e) {
      problems.push(messageOf(e));
    }
  }
  const m = q.get('mode') === 'race' || (q.get('planners') && !q.get('mode')) ? 'race' : 'single';
  try {
    setMode(m);
  } catch (e) {
    problems.push(messageOf(e));
  }
  if (problems.length) showError(problems.join(' · '));
  const auto = q.get('autorun');
  if (auto === 'instant') await runToEnd();
  else if (auto) setPlaying(true);
}

installShell(() => barnHelp(infos, ui.planner.value));
installLegend('barn', ui.stage);

boot().catch((e) => {
  ui.body.dataset.state = 'error';
  showError(`Could not start the BARN page: ${messageOf(e)}`);
});
