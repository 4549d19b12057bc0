// APF page: loads a 2D potential-field preset into a wasm ApfHandle, steps
// it and paints what it reports — the force field as a heat map with
// arrows, obstacles with their repulsion ranges, the predicted obstacles
// with their virtual ranges, the 13 sampled directions and the chosen one,
// and the path. Goal drags, variant and predictor go to the handle as
// edits; this file computes no forces.

import init, { ApfHandle, editScenario } from '../../pkg/planlab_wasm.js';
import { recipeJson, runParams, variantParams } from '../shell/runlink';
import { loadVariant } from '../shell/variant';
import { installShell } from '../shell/help';
import { installLegend } from '../shell/legend';
import { apfHelp } from '../shell/help-content';
import { galleryRunEnded, showGalleryNote } from '../shell/gallery-note';
import { el, messageOf } from '../shell/dom';

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

/** World → canvas transform for the handle's bounds. */
function frame(h: ApfHandle) {
  const [x0, y0, x1, y1] = h.bounds();
  const c = ui.canvas;
  const s = Math.min(c.width / (x1 - x0), c.height / (y1 - y0));
  const ox = (c.width - s * (x1 - x0)) / 2;
  const oy = (c.height - s * (y1 - y0)) / 2;
  return {
    s,
    x: (x: number) => ox + (x - x0) * s,
    y: (y: number) => c.height - oy - (y - y0) * s,
    inv: (px: number, py: number): [number, number] => [x0 + (px - ox) / s, y0 + (c.height - oy - py) / s],
    x0,
    y0,
    x1,
    y1,
  };
}

function setMetric(id: string, value: string, raw: string | number): void {
  const e = el(id);
  e.textContent = value;
  e.dataset.value = String(raw);
}

function draw(): void {
  const h = handle;
  if (!h) return;
  const ctx = ui.canvas.getContext('2d');
  if (!ctx) return;
  const f = frame(h);
  ctx.fillStyle = '#0b1020';
  ctx.fillRect(0, 0, ui.canvas.width, ui.canvas.height);
  if (ui.showField.checked) {
    const field = h.field(FIELD_NX, FIELD_NY);
    const cw = (f.x1 - f.x0) / FIELD_NX;
    const ch = (f.y1 - f.y0) / FIELD_NY;
    for (let j = 0; j < FIELD_NY; j++) {
      for (let i = 0; i < FIELD_NX; i++) {
        const k = 2 * (j * FIELD_NX + i);
        const m = Math.hypot(field[k], field[k + 1]);
        const t = Math.max(0, Math.min(1, Math.log10(1 + m) / 2));
        // Opaque (pre-blended over the background) so cell seams do not show.
        const mix = (c: number, bg: number) => Math.round(0.55 * c + 0.45 * bg);
        ctx.fillStyle = `rgb(${mix(40 + 215 * t, 11)}, ${mix(60 + 60 * t, 16)}, ${mix(140 - 100 * t, 32)})`;
        const px = f.x(f.x0 + i * cw);
        const py = f.y(f.y0 + (j + 1) * ch);
        ctx.fillRect(px, py, cw * f.s + 1, ch * f.s + 1);
      }
    }
    // Arrows on every 4th lattice point: the resultant's direction.
    ctx.strokeStyle = 'rgba(226, 232, 240, 0.55)';
    ctx.lineWidth = 1;
    for (let j = 2; j < FIELD_NY; j += 4) {
      for (let i = 2; i < FIELD_NX; i += 4) {
        const k = 2 * (j * FIELD_NX + i);
        const m = Math.hypot(field[k], field[k + 1]);
        if (!(m > 0)) continue;
        const cx = f.x(f.x0 + (i + 0.5) * cw);
        const cy = f.y(f.y0 + (j + 0.5) * ch);
        const len = 0.8 * Math.min(cw, ch) * f.s * 2;
        const dx = (field[k] / m) * len;
        const dy = (-field[k + 1] / m) * len;
        ctx.beginPath();
        ctx.moveTo(cx, cy);
        ctx.lineTo(cx + dx, cy + dy);
        ctx.lineTo(cx + dx * 0.7 - dy * 0.2, cy + dy * 0.7 + dx * 0.2);
        ctx.stroke();
      }
    }
  }
  // Obstacles and their repulsion ranges.
  const obs = h.obstacles();
  for (let i = 0; i < obs.length; i += 4) {
    const [x, y, r, range] = [obs[i], obs[i + 1], obs[i + 2], obs[i + 3]];
    ctx.setLineDash([4, 4]);
    ctx.strokeStyle = '#60a5fa';
    ctx.beginPath();
    ctx.arc(f.x(x), f.y(y), range * f.s, 0, 2 * Math.PI);
    ctx.stroke();
    ctx.setLineDash([]);
    ctx.fillStyle = '#94a3b8';
    ctx.beginPath();
    ctx.arc(f.x(x), f.y(y), Math.max(2, r * f.s), 0, 2 * Math.PI);
    ctx.fill();
  }
  if (ui.showPred.checked) {
    const pred = h.predicted();
    for (let i = 0; i < pred.length; i += 4) {
      const [x, y, range, k] = [pred[i], pred[i + 1], pred[i + 2], pred[i + 3]];
      ctx.setLineDash([2, 3]);
      ctx.strokeStyle = k === 1 ? '#a78bfa' : '#f472b6';
      ctx.beginPath();
      ctx.arc(f.x(x), f.y(y), range * f.s, 0, 2 * Math.PI);
      ctx.stroke();
      ctx.setLineDash([]);
      ctx.fillStyle = ctx.strokeStyle;
      ctx.beginPath();
      ctx.arc(f.x(x), f.y(y), 3, 0, 2 * Math.PI);
      ctx.fill();
    }
  }
  // Path.
  const path = h.path();
  ctx.strokeStyle = '#fbbf24';
  ctx.lineWidth = 2;
  ctx.beginPath();
  for (let i = 0; i < path.length; i += 2) {
    const px = f.x(path[i]);
    const py = f.y(path[i + 1]);
    if (i === 0) ctx.moveTo(px, py);
    else ctx.lineTo(px, py);
  }
  ctx.stroke();
  ctx.fillStyle = '#fbbf24';
  for (let i = 0; i < path.length; i += 2) {
    ctx.beginPath();
    ctx.arc(f.x(path[i]), f.y(path[i + 1]), 2, 0, 2 * Math.PI);
    ctx.fill();
  }
  // Sampled directions from the previous point, the chosen one bold.
  if (ui.showCand.checked && path.length >= 4) {
    const cand = h.candidates();
    const chosen = h.chosen();
    const bx = path[path.length - 4];
    const by = path[path.length - 3];
    for (let i = 0; i < cand.length; i += 3) {
      const best = i / 3 === chosen;
      ctx.strokeStyle = best ? '#22c55e' : 'rgba(148, 163, 184, 0.8)';
      ctx.lineWidth = best ? 3 : 1;
      ctx.beginPath();
      ctx.moveTo(f.x(bx), f.y(by));
      ctx.lineTo(f.x(cand[i]), f.y(cand[i + 1]));
      ctx.stroke();
    }
    ctx.lineWidth = 1;
  }
  const [sx, sy, gx, gy] = h.endpoints();
  ctx.fillStyle = '#38bdf8';
  ctx.beginPath();
  ctx.arc(f.x(sx), f.y(sy), 6, 0, 2 * Math.PI);
  ctx.fill();
  ctx.fillStyle = '#ef4444';
  ctx.beginPath();
  ctx.arc(f.x(gx), f.y(gy), 7, 0, 2 * Math.PI);
  ctx.fill();
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
  document.body.dataset.pathPoints = String(path.length / 2);
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
    const [x, y] = frame(handle).inv(px, py);
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
