// The grid page's planner controls as the core's GridPlanOptions: read from
// the form (empty boxes give NaN, which the core rejects with its own
// message), set from an options object (the defaults, a scenario's, a
// link's), and only the controls the chosen algorithm reads shown.

import { el } from '../shell/dom';
import { isSampling, type SamplingSettings } from '../scene/sampling-run';

const ui = {
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
  budget: el<HTMLInputElement>('sampling-budget'),
  budgetKind: el<HTMLSelectElement>('sampling-budget-kind'),
  seed: el<HTMLInputElement>('sampling-seed'),
  radius: el<HTMLInputElement>('sampling-radius'),
  shortcut: el<HTMLInputElement>('sampling-shortcut'),
};

/** The core's defaults (`defaultPlanOptions()`), under every read. */
let defaults: Record<string, unknown> = {};

export function setDefaults(d: Record<string, unknown>): void {
  defaults = d;
}

export function getDefaults(): Record<string, unknown> {
  return defaults;
}

function num(input: HTMLInputElement): number {
  // An empty box gives NaN, which the core rejects with its own message.
  return input.value.trim() === '' ? Number.NaN : Number(input.value);
}

/** Whether the expanded cells are asked for. */
export function showExpanded(): boolean {
  return ui.showExpanded.checked;
}

/** The control values as the core's GridPlanOptions. */
export function readOptions(): Record<string, unknown> {
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

/** The sampling planner's settings (the chosen algorithm, whatever it
 *  is); an empty radius is the core's default, an empty seed or budget
 *  NaN (refused with a one-line error). */
export function readSampling(): SamplingSettings {
  const radius = ui.radius.value.trim();
  return {
    algorithm: ui.algorithm.value,
    seed: num(ui.seed),
    radiusM: radius === '' ? undefined : Number(radius),
    budget: { kind: ui.budgetKind.value === 'ms' ? 'ms' : 'iterations', value: num(ui.budget) },
    shortcut: ui.shortcut.checked,
    allowUnknown: ui.allowUnknown.checked,
  };
}

/** Whether the chosen algorithm is a sampling planner. */
export function samplingChosen(): boolean {
  return isSampling(ui.algorithm.value);
}

/** Shows only the controls that the chosen algorithm reads. */
export function syncControls(): void {
  const algo = ui.algorithm.value;
  const sampling = isSampling(algo);
  document.querySelectorAll<HTMLElement>('.grid-box').forEach((e) => (e.dataset.hidden = String(sampling)));
  document.querySelectorAll<HTMLElement>('[data-for]').forEach((e) => {
    const forAlgos = (e.dataset.for ?? '').split(' ');
    if (e.classList.contains('safe-box') || e.classList.contains('sampling-box')) e.dataset.hidden = String(!forAlgos.includes(algo));
    else {
      // A grid search's controls leave the card while a sampling planner
      // is chosen (they would all be dimmed).
      e.dataset.hidden = String(sampling);
      e.dataset.dim = String(!forAlgos.includes(algo));
    }
  });
  ui.weightOut.textContent = Number(ui.weight.value).toFixed(1);
  ui.bottomUpEps.disabled = !ui.bottomUp.checked;
}

/** Sets the controls from a GridPlanOptions object (defaults or a scenario's). */
export function applyOptions(d: Record<string, unknown>): void {
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

/** `changed` after any control's input. */
export function onOptionInput(changed: () => void): void {
  for (const c of Object.values(ui)) {
    if (c === ui.weightOut) continue;
    c.addEventListener('input', () => {
      syncControls();
      changed();
    });
  }
}
