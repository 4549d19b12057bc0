// Arm page wiring: loads an arm scenario into a wasm ArmHandle, steps it
// from the animation frame at the chosen speed and shows the core's draw
// list of it in the 3D view (links, target, tool and hand paths,
// predictions, sampled steps) plus
// the joint readout and the metrics. The target sliders, the hand's motion
// and the predictor go to the handle as edits; this file computes no
// kinematics, distances or plans.

import { recipeJson, runParams, variantParams } from '../shell/runlink';
import { loadVariant } from '../shell/variant';
import { installShell } from '../shell/help';
import { installLegend } from '../shell/legend';
import { armHelp } from '../shell/help-content';
import { galleryRunEnded, showGalleryNote } from '../shell/gallery-note';
import init, { ArmHandle, armChoices, editScenario } from '../../pkg-arm/planlab_wasm_arm.js';
import { ArmView } from './view';
import { DrawList, Layer, mask } from '../scene/draw';
import { DistancePlot } from './distplot';
import { el, messageOf } from '../shell/dom';

/** At most this many 0.1 s samples per animation frame. */
const MAX_STEPS_PER_FRAME = 8;
/** Target slider ranges, m (the arm's front workspace). */
const RANGES: [string, number, number][] = [
  ['x', 0.1, 1.0],
  ['y', -0.5, 0.7],
  ['z', 0.5, 1.3],
];

const ui = {
  body: document.body,
  hint: el('hint'),
  preset: el<HTMLSelectElement>('preset'),
  description: el('scenario-description'),
  play: el<HTMLButtonElement>('play'),
  step: el<HTMLButtonElement>('step'),
  reset: el<HTMLButtonElement>('reset'),
  speed: el<HTMLSelectElement>('speed'),
  predictor: el<HTMLSelectElement>('predictor'),
  planner: el<HTMLSelectElement>('planner'),
  showPred: el<HTMLInputElement>('show-pred'),
  showCand: el<HTMLInputElement>('show-cand'),
  showScript: el<HTMLInputElement>('show-script'),
  handPreset: el<HTMLSelectElement>('hand-preset'),
  handSpeed: el<HTMLInputElement>('hand-speed'),
  handSeed: el<HTMLInputElement>('hand-seed'),
  target: el('target'),
  joints: el<HTMLTableElement>('joints'),
  error: el('error'),
  status: el('status'),
  view: el('view'),
  m: {
    outcome: el('metric-outcome'),
    time: el('metric-time'),
    length: el('metric-length'),
    points: el('metric-points'),
    spikes: el('metric-spikes'),
    min: el('metric-min'),
    now: el('metric-now'),
    joint: el('metric-joint'),
    plans: el('metric-plans'),
  },
};

/** Page labels of the core's arm planners. */
const PLANNER_LABELS: Record<string, string> = { apf: 'APF (thesis)', 'rrt-connect': 'RRT-Connect (joint space)' };
/** Table top for RRT-Connect on the page, m: planlab's value for T-tab5-3
 *  (below the hand's and the goal's heights), as `--set arm.table_z_m=0.72`. */
const RRT_TABLE_Z_M = 0.72;

let handle: ArmHandle | null = null;
let view: ArmView | null = null;
let playing = false;
let carry = 0;
let lastFrame = 0;
const sliders: { input: HTMLInputElement; out: HTMLOutputElement }[] = [];
let jointCells: { val: HTMLElement; mark: HTMLElement }[] = [];

function showError(msg: string | null): void {
  ui.error.hidden = msg === null;
  ui.error.textContent = msg ?? '';
}

function setPlaying(on: boolean): void {
  playing = on;
  ui.play.dataset.playing = String(on);
  ui.play.textContent = on ? '❚❚ Pause' : '▶ Play';
  ui.body.dataset.playing = String(on);
  carry = 0;
}

/** Every layer of the arm's draw list. */
const ARM_LAYERS = mask(Layer.Trail, Layer.Goals, Layer.Predicted, Layer.Candidates, Layer.Links, Layer.Hand, Layer.HandPath);
/** Instants of the hand's scripted motion drawn. */
const SCRIPT_SAMPLES = 120;

function buildJoints(h: ArmHandle): void {
  const names: string[] = JSON.parse(h.jointNames());
  ui.joints.replaceChildren();
  jointCells = names.map((n) => {
    const tr = ui.joints.insertRow();
    const name = tr.insertCell();
    name.className = 'name';
    name.textContent = n;
    const barCell = tr.insertCell();
    const bar = document.createElement('div');
    bar.className = 'bar';
    const mark = document.createElement('i');
    bar.append(mark);
    barCell.append(bar);
    const val = tr.insertCell();
    val.className = 'val';
    return { val, mark };
  });
}

function buildTarget(h: ArmHandle): void {
  ui.target.replaceChildren();
  sliders.length = 0;
  const g = h.goal();
  RANGES.forEach(([axis, lo, hi], i) => {
    const row = document.createElement('label');
    row.className = 'slider';
    const name = document.createElement('span');
    name.textContent = axis;
    const input = document.createElement('input');
    input.type = 'range';
    input.min = String(lo);
    input.max = String(hi);
    input.step = '0.005';
    input.value = String(g[i]);
    input.id = `target-${axis}`;
    const out = document.createElement('output');
    row.append(name, input, out);
    ui.target.append(row);
    sliders.push({ input, out });
    input.addEventListener('input', () => setTarget(sliders.map((s) => Number(s.input.value))));
  });
}

/** Sends a new target; an unreachable one is refused with the core's reason. */
function setTarget(p: number[]): void {
  if (!handle) return;
  try {
    handle.setGoal(p[0], p[1], p[2]);
    showError(null);
  } catch (e) {
    showError(`target refused: ${messageOf(e)}`);
  }
  refresh();
}

let distPlot: DistancePlot | null = null;

function refresh(): void {
  const h = handle;
  if (!h || !view) return;
  const d = new DrawList(h.draw(ARM_LAYERS, ui.showScript.checked ? SCRIPT_SAMPLES : 0));
  view.update(d);
  distPlot?.pull(h);
  const m = JSON.parse(h.metricsJson());
  const out: string = m.outcome;
  ui.m.outcome.textContent = out;
  ui.m.outcome.dataset.outcome = out;
  ui.m.time.textContent = `${h.time.toFixed(1)} s`;
  ui.m.length.textContent = `${m.path_length_m.toFixed(3)} m`;
  ui.m.points.textContent = String(m.path_points);
  ui.m.spikes.textContent = String(m.spikes);
  ui.m.min.textContent = `${m.min_obstacle_distance_m.toFixed(4)} m`;
  ui.m.now.textContent = `${h.distanceNow.toFixed(4)} m`;
  const eff = JSON.parse(h.plannerJson());
  ui.m.joint.textContent = `${eff.joint_path_rad.toFixed(2)} rad`;
  ui.m.joint.dataset.value = String(eff.joint_path_rad);
  ui.m.plans.textContent = `${eff.plans} (${eff.replans} replans), ${eff.collision_checks} checks`;
  ui.m.plans.title = `${eff.iterations} iterations, ${eff.failed_plans} failed plans, ${eff.holds} holds` +
    (eff.min_table_m === null ? '' : `; nearest the table ${eff.min_table_m.toFixed(3)} m`);
  ui.body.dataset.planner = eff.planner;
  ui.m.min.dataset.value = String(m.min_obstacle_distance_m);
  ui.m.now.dataset.value = String(h.distanceNow);
  ui.m.length.dataset.value = String(m.path_length_m);
  ui.m.time.dataset.value = String(h.time);
  ui.body.dataset.outcome = out;
  ui.body.dataset.time = h.time.toFixed(2);
  ui.body.dataset.minDistance = String(m.min_obstacle_distance_m);
  ui.body.dataset.goal = Array.from(h.goal()).join(',');
  ui.body.dataset.predictions = String(d.count(Layer.Predicted));
  const q = h.jointAngles();
  const lim = h.jointLimits();
  jointCells.forEach((c, i) => {
    c.val.textContent = `${((q[i] * 180) / Math.PI).toFixed(1)}°`;
    const f = (q[i] - lim[2 * i]) / Math.max(1e-9, lim[2 * i + 1] - lim[2 * i]);
    c.mark.style.left = `${(100 * f).toFixed(1)}%`;
  });
  const g = h.goal();
  sliders.forEach((s, i) => {
    if (document.activeElement !== s.input) s.input.value = String(g[i]);
    s.out.textContent = g[i].toFixed(3);
  });
  const pred = h.predictor;
  ui.status.textContent =
    `${h.name} — ${eff.planner === 'apf' ? 'APF' : 'RRT-Connect'}, predictor ${pred}, hand ${h.handPreset} ×${h.handSpeed} (seed ${h.seed}); ` +
    `t = ${h.time.toFixed(1)} s, ${out}`;
  if (out !== 'running' && playing) setPlaying(false);
  if (out !== 'running') galleryRunEnded(out);
}

function stepOnce(n: number): void {
  if (!handle) return;
  try {
    handle.step(n);
  } catch (e) {
    showError(messageOf(e));
    setPlaying(false);
  }
  refresh();
}

function loop(ts: number): void {
  const h = handle;
  if (h && playing) {
    const dt = lastFrame ? Math.min(0.1, (ts - lastFrame) / 1000) : 0;
    carry += (dt * Number(ui.speed.value)) / h.dt;
    const n = Math.min(MAX_STEPS_PER_FRAME, Math.floor(carry));
    if (n > 0) {
      carry -= n;
      stepOnce(n);
    }
  }
  lastFrame = ts;
  view?.render();
  requestAnimationFrame(loop);
}

async function load(file: string, edit: (text: string) => string = (t) => t): Promise<void> {
  ui.body.dataset.state = 'loading';
  setPlaying(false);
  const r = await fetch(`./scenarios/${file}`);
  if (!r.ok) throw new Error(`cannot load scenarios/${file}: HTTP ${r.status}`);
  const text = edit(await r.text());
  handle?.free();
  handle = new ArmHandle(text);
  const json = JSON.parse(text);
  ui.description.textContent = json.description ?? '';
  ui.predictor.value = handle.predictor;
  ui.planner.value = JSON.parse(handle.plannerJson()).planner;
  ui.handPreset.value = handle.handPreset;
  ui.handSpeed.value = String(handle.handSpeed);
  ui.handSeed.value = String(handle.seed);
  buildJoints(handle);
  buildTarget(handle);
  showError(null);
  refresh();
  ui.body.dataset.state = 'ready';
}

function applyHand(): void {
  if (!handle) return;
  try {
    handle.setHand(ui.handPreset.value, Number(ui.handSpeed.value), Number(ui.handSeed.value));
      showError(null);
  } catch (e) {
    showError(`hand motion refused: ${messageOf(e)}`);
  }
  refresh();
}

async function main(): Promise<void> {
  await init();
  const choices: { hand_presets: string[]; predictors: string[]; planners: string[] } = JSON.parse(armChoices());
  for (const p of choices.planners) ui.planner.add(new Option(PLANNER_LABELS[p] ?? p, p));
  for (const p of choices.predictors) ui.predictor.add(new Option(p === 'none' ? 'none (sampling APF)' : p, p));
  for (const p of choices.hand_presets) ui.handPreset.add(new Option(p, p));
  view = new ArmView(ui.view);
  distPlot = new DistancePlot(el('plot-hand'));
  view.onTargetDrag = (x, y, z) => setTarget([x, y, z]);
  ui.play.addEventListener('click', () => setPlaying(!playing));
  ui.step.addEventListener('click', () => {
    setPlaying(false);
    stepOnce(1);
  });
  ui.reset.addEventListener('click', () => {
    setPlaying(false);
    try {
      handle?.reset();
      showError(null);
    } catch (e) {
      showError(messageOf(e));
    }
    refresh();
  });
  // A planner change restarts the preset with the scene's planner set; RRT-
  // Connect also gets the table top (planlab's value, as in the README's
  // comparison), which the APF does not know.
  ui.planner.addEventListener('change', () => {
    const set: [string, string][] =
      ui.planner.value === 'apf' ? [] : [['arm.planner', ui.planner.value], ['arm.table_z_m', String(RRT_TABLE_Z_M)]];
    const predictor = ui.predictor.value;
    load(ui.preset.value, (t) => editScenario(t, recipeJson(null, set)))
      .then(() => {
        handle?.setPredictor(predictor);
        ui.predictor.value = predictor;
        refresh();
      })
      .catch((e) => showError(messageOf(e)));
  });
  ui.predictor.addEventListener('change', () => {
    try {
      handle?.setPredictor(ui.predictor.value);
      showError(null);
    } catch (e) {
      showError(messageOf(e));
    }
    refresh();
  });
  ui.showPred.addEventListener('change', () => {
    if (view) view.showPredictions = ui.showPred.checked;
    refresh();
  });
  ui.showCand.addEventListener('change', () => {
    if (view) view.showCandidates = ui.showCand.checked;
    refresh();
  });
  ui.showScript.addEventListener('change', refresh);
  for (const i of [ui.handPreset, ui.handSpeed, ui.handSeed]) i.addEventListener('change', applyHand);
  ui.preset.addEventListener('change', () => load(ui.preset.value).catch((e) => showError(messageOf(e))));
  window.addEventListener('keydown', (ev) => {
    if (ev.target instanceof HTMLInputElement || ev.target instanceof HTMLSelectElement) return;
    if (ev.key === ' ') {
      ev.preventDefault();
      setPlaying(!playing);
    } else if (ev.key === '.') stepOnce(1);
    else if (ev.key === 'r' || ev.key === 'R') ui.reset.click();
  });
  // A gallery link: preset, `--set` edits, the run's predictor (a reproduce
  // run's `planner`) and `run=1`.
  const link = runParams();
  const q = link.scenario;
  if (q) {
    if (![...ui.preset.options].some((o) => o.value === q)) ui.preset.add(new Option(q, q));
    ui.preset.value = q;
  }
  // A variant link: the registry's tree of that run on that variant (its
  // predictor written into the tree); a bad one shows the core's message
  // over the preset.
  let variantError: unknown = null;
  let variantText: string | null = null;
  try {
    const v = variantParams();
    if (v) {
      variantText = (await loadVariant(v)).text;
      ui.body.dataset.variant = String(v.k);
    }
  } catch (e) {
    variantError = e;
  }
  if (variantText !== null) {
    const text = variantText;
    await load(ui.preset.value, () => text);
  } else {
    await load(ui.preset.value, q ? (t) => editScenario(t, recipeJson(null, link.set)) : undefined);
    if (q && link.planner) {
      ui.predictor.value = link.planner;
      ui.predictor.dispatchEvent(new Event('change'));
    }
  }
  if (variantError !== null) showError(`Could not open the variant: ${messageOf(variantError)}`);
  else if (q && link.run) setPlaying(true);
  ui.hint.textContent = 'Play to run; drag the target sliders, change the hand or the predictor at any time; the planner restarts the run.';
  // Hooks for the end-to-end tests.
  (window as unknown as { planlabArm: unknown }).planlabArm = {
    runToEnd(maxSteps = 2000): string {
      if (!handle) return 'none';
      const out = handle.step(maxSteps);
      refresh();
      return out;
    },
    metrics: () => (handle ? JSON.parse(handle.metricsJson()) : null),
    distancePlot: () => ({ rows: distPlot?.length ?? 0, last: distPlot?.last() ?? [], series: handle ? Array.from(handle.distanceSeries(0)) : [] }),
    planner: () => (handle ? JSON.parse(handle.plannerJson()) : null),
    setPlanner(name: string) {
      ui.planner.value = name;
      ui.planner.dispatchEvent(new Event('change'));
    },
    setPredictor(name: string) {
      ui.predictor.value = name;
      ui.predictor.dispatchEvent(new Event('change'));
    },
  };
  requestAnimationFrame(loop);
}

installShell(armHelp());
installLegend('arm', document.querySelector('.stage'));
showGalleryNote();

main().catch((e) => {
  ui.body.dataset.state = 'error';
  showError(messageOf(e));
  ui.hint.textContent = 'Failed to start.';
});
