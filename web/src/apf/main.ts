// APF page: loads a 2D potential-field preset into a wasm ApfHandle, steps
// it and paints the core's draw list of the run (paint.ts) — the force
// field as a heat map with arrows, obstacles with their repulsion ranges,
// the predicted obstacles with their virtual ranges, the 13 sampled
// directions and the chosen one, and the path. Goal drags, variant and
// predictor go to the handle as edits; this file computes no forces.

import init, { ApfHandle, editScenario } from '../../pkg/planlab_wasm.js';
import { recipeJson, runParams, variantParams } from '../shell/runlink';
import { loadVariant } from '../shell/variant';
import { installShell } from '../shell/help';
import { installLegend } from '../shell/legend';
import { apfHelp } from '../shell/help-content';
import { galleryRunEnded, showGalleryNote } from '../shell/gallery-note';
import { el, messageOf } from '../shell/dom';
import { DrawList, Layer, mask } from '../scene/draw';
import { fitFrame, paintApf } from './paint';

const ui = {
  hint: el('hint'),
  preset: el<HTMLSelectElement>('preset'),
  mode: el<HTMLSelectElement>('mode'),
  predictor: el<HTMLSelectElement>('predictor'),
  play: el<HTMLButtonElement>('play'),
  step: el<HTMLButtonElement>('step'),
  reset: el<HTMLButtonElement>('reset'),
  showField: el<HTMLInputElement>('show-field'),
  showCand: el<HTMLInputElement>('show-cand'),
  showPred: el<HTMLInputElement>('show-pred'),
  error: el('error'),
  canvas: el<HTMLCanvasElement>('view'),
};

let handle: ApfHandle | null = null;
/** The draw list last painted (the e2e hooks read it). */
let lastDraw: DrawList | null = null;
let playing = false;
const FIELD_NX = 64;
const FIELD_NY = 48;

function showError(msg: string | null): void {
  ui.error.hidden = msg === null;
  ui.error.textContent = msg ?? '';
}

function setPlaying(on: boolean): void {
  playing = on;
  ui.play.textContent = on ? '❚❚ Pause' : '▶ Play';
}

function setMetric(id: string, value: string, raw: string | number): void {
  const e = el(id);
  e.textContent = value;
  e.dataset.value = String(raw);
}

function draw(): void {
  const h = handle;
  if (!h) return;
  let layers = mask(Layer.Trail, Layer.Goals, Layer.Obstacles);
  if (ui.showField.checked) layers |= mask(Layer.Field);
  if (ui.showPred.checked) layers |= mask(Layer.Predicted);
  if (ui.showCand.checked) layers |= mask(Layer.Candidates);
  const d = new DrawList(h.draw(layers, FIELD_NX, FIELD_NY));
  paintApf(ui.canvas, h.bounds(), d);
  const t = d.first(Layer.Trail);
  const pathPoints = t < d.end(Layer.Trail) ? d.points(t) : 0;
  // Metrics from the core.
  const m = JSON.parse(h.metrics());
  setMetric('metric-outcome', m.outcome, m.outcome);
  setMetric('metric-length', `${m.path_length_m.toFixed(3)} m`, m.path_length_m);
  setMetric('metric-points', String(m.path_points), m.path_points);
  setMetric('metric-spikes', String(m.spikes), m.spikes);
  setMetric('metric-min', `${m.min_obstacle_distance_m.toFixed(4)} m`, m.min_obstacle_distance_m);
  setMetric('metric-time', `${m.time_s.toFixed(1)} s`, m.time_s);
  el('metric-kind').textContent = h.stepKind();
  document.body.dataset.outcome = m.outcome;
  // A run opened from a gallery card: the ✓/✗ of its relation when it ends.
  if (m.outcome !== 'running') galleryRunEnded(m.outcome);
  document.body.dataset.pathPoints = String(pathPoints);
  lastDraw = d;
}

function tick(): void {
  if (playing && handle) {
    try {
      const out = handle.step(1);
      if (out !== 'running') setPlaying(false);
    } catch (e) {
      showError(messageOf(e));
      setPlaying(false);
    }
    draw();
  }
  requestAnimationFrame(tick);
}

async function load(file: string, edit: (text: string) => string = (t) => t): Promise<void> {
  loadText(edit(await (await fetch(`./scenarios/${file}`)).text()));
}

/** A variant's tree: its mode and predictor are the run's, so the page's
 *  selects take them before the handle is built from the tree. */
function loadVariantText(text: string): void {
  const cfg = (JSON.parse(text) as { apf?: { config?: { mode?: string; predictor?: string } } }).apf?.config;
  const pick = (sel: HTMLSelectElement, v: string | undefined) => {
    if (v && [...sel.options].some((o) => o.value === v)) sel.value = v;
  };
  pick(ui.mode, cfg?.mode);
  pick(ui.predictor, cfg?.predictor);
  loadText(text);
}

function loadText(text: string): void {
  handle?.free();
  handle = new ApfHandle(text);
  document.body.dataset.dims = String(handle.dims());
  el('dims-note').hidden = handle.dims() !== 3;
  handle.setMode(ui.mode.value);
  handle.setPredictor(ui.predictor.value);
  showError(null);
  setPlaying(false);
  draw();
}

function guard(f: () => void): void {
  try {
    f();
    showError(null);
  } catch (e) {
    showError(messageOf(e));
  }
  draw();
}

async function main(): Promise<void> {
  await init();
  const params = new URLSearchParams(location.search);
  // A gallery link: preset, `--set` edits of a reproduce run (the variant
  // is `apf.config.mode`), and `run=1`.
  const link = runParams();
  const sc = link.scenario;
  if (sc) {
    if (![...ui.preset.options].some((o) => o.value === sc)) ui.preset.add(new Option(sc.replace(/\.json$/, ''), sc));
    ui.preset.value = sc;
  }
  const mode = link.set.find(([p]) => p === 'apf.config.mode')?.[1] ?? params.get('mode');
  if (mode) ui.mode.value = mode;
  // A variant link: the registry's tree of that run on that variant; a bad
  // one shows the core's message over the preset.
  let variantError: unknown = null;
  let variant = false;
  try {
    const v = variantParams();
    if (v) {
      loadVariantText((await loadVariant(v)).text);
      document.body.dataset.variant = String(v.k);
      variant = true;
    }
  } catch (e) {
    variantError = e;
  }
  if (!variant) await load(ui.preset.value, sc ? (t) => editScenario(t, recipeJson(null, link.set)) : undefined);
  if (variantError !== null) showError(`Could not open the variant: ${messageOf(variantError)}`);
  else if (sc && link.run) setPlaying(true);
  ui.preset.addEventListener('change', () => void load(ui.preset.value).catch((e) => showError(messageOf(e))));
  ui.mode.addEventListener('change', () => guard(() => handle?.setMode(ui.mode.value)));
  ui.predictor.addEventListener('change', () => guard(() => handle?.setPredictor(ui.predictor.value)));
  ui.play.addEventListener('click', () => setPlaying(!playing));
  ui.step.addEventListener('click', () => guard(() => void handle?.step(1)));
  ui.reset.addEventListener('click', () => guard(() => handle?.reset()));
  for (const t of [ui.showField, ui.showCand, ui.showPred]) t.addEventListener('change', draw);
  let dragging = false;
  const moveGoal = (ev: PointerEvent) => {
    if (!handle) return;
    const r = ui.canvas.getBoundingClientRect();
    const px = ((ev.clientX - r.left) / r.width) * ui.canvas.width;
    const py = ((ev.clientY - r.top) / r.height) * ui.canvas.height;
    const [x, y] = fitFrame(ui.canvas, handle.bounds()).inv(px, py);
    guard(() => handle?.setGoal(x, y));
  };
  ui.canvas.addEventListener('pointerdown', (ev) => {
    dragging = true;
    moveGoal(ev);
  });
  ui.canvas.addEventListener('pointermove', (ev) => {
    if (dragging) moveGoal(ev);
  });
  window.addEventListener('pointerup', () => {
    dragging = false;
  });
  ui.hint.textContent = 'Play, step, or drag the goal.';
  // Hooks for the end-to-end tests: a point of the last draw list and
  // where the page paints a world point (canvas pixels).
  (window as unknown as { planlabApf: unknown }).planlabApf = {
    goal: (tag: number) => {
      const i = lastDraw?.find(Layer.Goals, tag) ?? -1;
      return i < 0 || !lastDraw ? null : Array.from(lastDraw.numbers(i));
    },
    toCanvas: (x: number, y: number) => {
      const f = fitFrame(ui.canvas, handle ? handle.bounds() : [0, 0, 1, 1]);
      return [f.x(x), f.y(y)];
    },
  };
  document.body.dataset.state = 'ready';
  requestAnimationFrame(tick);
}

installShell(apfHelp());
installLegend('apf', document.querySelector('.stage'));
showGalleryNote();

main().catch((e) => {
  showError(messageOf(e));
  document.body.dataset.state = 'error';
});
