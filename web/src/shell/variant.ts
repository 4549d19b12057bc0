// Variant links (`…&exp=T-fig3-2&as=improved&variant=3&seed=0&of=30`): the
// scenario of run `as` of variant k of the experiment's family, drawn by the
// core's reproduce registry in its own wasm module (web/pkg-reproduce, built
// from crates/planlab-wasm-reproduce). The module embeds every preset, so
// it is imported only when a link names a variant: pages opened otherwise
// keep their first-load size. The tree is the one `planlab reproduce ID
// --variants N --seed S` runs as variant k, so the page's trace hash is the
// CLI's.

import type { VariantParams } from './runlink';

/** What variant k drew (core `VariantScene`, seeds as decimal strings). */
export interface VariantInfo {
  id: string;
  k: number;
  seed: string;
  variant_seed: string;
  redraws: number;
  draws: { what: string; value: unknown }[];
  runs: string[];
}

export interface LoadedVariant {
  /** The run's scenario JSON. */
  text: string;
  info: VariantInfo;
  /** k < max (core `MAX_VARIANTS`). */
  max: number;
}

/** The scenario of the link's variant, or the core's error message. */
export async function loadVariant(v: VariantParams): Promise<LoadedVariant> {
  const m = await import('../../pkg-reproduce/planlab_wasm_reproduce.js');
  await m.default();
  const seed = BigInt(v.seed);
  const text = m.reproduceVariant(v.exp, v.as, v.k, seed);
  const info = JSON.parse(m.reproduceVariantInfo(v.exp, v.k, seed)) as VariantInfo;
  const loaded = { text, info, max: m.maxVariants() };
  variantLoaded(v, loaded);
  return loaded;
}

/** A short account of the draws: `start +0.12,−0.05 m; mover 1 speed ×0.9 …`. */
export function drawsText(info: VariantInfo): string {
  if (info.k === 0) return 'the preset as written';
  const val = (x: unknown): string => {
    if (typeof x === 'number') return String(Number(x.toPrecision(3)));
    if (Array.isArray(x)) return x.map(val).join(', ');
    return typeof x === 'string' ? x : JSON.stringify(x);
  };
  return info.draws.map((d) => `${d.what} ${val(d.value)}`).join('; ');
}

// The gallery note is added when gallery.json has arrived; the variant may
// load before or after it. Whichever comes second fills the note's line.
let pending: { v: VariantParams; loaded: LoadedVariant } | null = null;
let slot: HTMLElement | null = null;

function variantLoaded(v: VariantParams, loaded: LoadedVariant): void {
  pending = { v, loaded };
  if (slot) fill(slot, v, loaded);
}

/** The note's variant line and controls (gallery-note.ts calls it). */
export function variantSlot(v: VariantParams): HTMLElement {
  const el = document.createElement('span');
  el.className = 'gallery-note-variant';
  el.id = 'variant-note';
  slot = el;
  if (pending) fill(el, pending.v, pending.loaded);
  else el.textContent = `variant ${v.k}${ofText(v)}, seed ${v.seed}`;
  return el;
}

/** ` of N` for a variant of the family the gallery's results cover. */
function ofText(v: VariantParams): string {
  if (v.of === null) return '';
  return v.k < v.of ? ` of ${v.of}` : ` (past the ${v.of} of the gallery's results)`;
}

function fill(el: HTMLElement, v: VariantParams, loaded: LoadedVariant): void {
  el.replaceChildren();
  const label = document.createElement('b');
  label.id = 'variant-label';
  label.textContent = `variant ${v.k}${ofText(v)}, seed ${v.seed}`;
  label.title =
    `planlab reproduce ${v.exp} --variants ${v.of ?? v.k + 1} --seed ${v.seed}: variant ${v.k}` +
    ` (its own seed ${loaded.info.variant_seed}${loaded.info.redraws ? `, ${loaded.info.redraws} draws rejected` : ''}):` +
    ` ${drawsText(loaded.info)}`;
  const input = document.createElement('input');
  input.type = 'number';
  input.id = 'variant-k';
  input.min = '0';
  input.max = String(loaded.max - 1);
  input.step = '1';
  input.value = String(v.k);
  input.setAttribute('aria-label', 'Variant index (0 is the preset)');
  input.title = 'Variant index: 0 is the preset, 1 and up perturb it';
  const go = document.createElement('button');
  go.type = 'button';
  go.id = 'variant-run';
  go.textContent = 'Run';
  go.title = 'Run this variant';
  const open = (k: number) => {
    const q = new URLSearchParams(location.search);
    q.set('variant', String(k));
    q.set('run', '1');
    location.search = q.toString();
  };
  go.addEventListener('click', () => {
    const k = Number(input.value);
    if (Number.isInteger(k) && k >= 0 && k < loaded.max) {
      open(k);
    } else {
      input.setCustomValidity(`a variant from 0 to ${loaded.max - 1}`);
      input.reportValidity();
    }
  });
  input.addEventListener('input', () => input.setCustomValidity(''));
  input.addEventListener('keydown', (ev) => {
    if (ev.key === 'Enter') go.click();
  });
  const rnd = document.createElement('button');
  rnd.type = 'button';
  rnd.id = 'variant-random';
  rnd.textContent = 'random';
  const n = v.of ?? 30;
  rnd.title = `Run a random variant (1–${n - 1}) of this family`;
  rnd.addEventListener('click', () => {
    // Another variant than this one, among the family the results cover.
    let k = v.k;
    while (n > 2 && k === v.k) k = 1 + Math.floor(Math.random() * (n - 1));
    open(n > 2 ? k : 1);
  });
  el.append(label, input, go, rnd);
}
