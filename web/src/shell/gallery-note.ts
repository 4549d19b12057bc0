// The note a page shows when a gallery card opened it (`…&exp=T-fig3-2
// &as=improved`): which experiment and run this is, the relation the paper
// claims (what to look for in the metrics), and a way back to the card;
// on a variant link (`&variant=K&seed=S`) also which variant this is, with
// controls to run another (shell/variant.ts).

import { variantParams, type GalleryEntry, type VariantParams } from './runlink';
import { variantSlot } from './variant';
import './gallery-note.css';

/** Adds the note under the top bar when the URL names a gallery experiment
 *  (the gallery's JSON is fetched only then, so pages opened otherwise do
 *  not load it). A note is decoration: when it cannot be had, nothing shows. */
export function showGalleryNote(search: string = location.search): void {
  const q = new URLSearchParams(search);
  const id = q.get('exp');
  if (!id) return;
  fetch('./gallery.json')
    .then((r) => (r.ok ? r.json() : null))
    .then((g: { experiments?: GalleryEntry[] } | null) => {
      const e = g?.experiments?.find((x) => x.id === id);
      if (e) addNote(e, q.get('as'), variantOf(q));
    })
    .catch(() => {
      /* no note */
    });
}

/** The link's variant; a malformed one the page reports itself. */
function variantOf(q: URLSearchParams): VariantParams | null {
  try {
    return variantParams(q);
  } catch {
    return null;
  }
}

function addNote(e: GalleryEntry, run: string | null, variant: VariantParams | null): void {
  const note = document.createElement('div');
  note.className = 'gallery-note';
  note.id = 'gallery-note';
  note.setAttribute('role', 'note');
  const back = document.createElement('a');
  back.href = `./gallery.html#exp-${e.id}`;
  back.textContent = '← Gallery';
  const what = document.createElement('b');
  what.textContent = `${e.id}${run ? ` · ${run}` : ''}`;
  const claim = document.createElement('span');
  claim.textContent = ` ${e.paper} — the paper claims: ${e.relation}`;
  claim.title = e.explanation;
  const close = document.createElement('button');
  close.type = 'button';
  close.textContent = '×';
  close.title = 'Hide this note';
  close.setAttribute('aria-label', 'Hide the gallery note');
  close.addEventListener('click', () => {
    note.remove();
    window.dispatchEvent(new Event('resize'));
  });
  const text = document.createElement('span');
  text.className = 'gallery-note-text';
  text.append(what, claim);
  note.append(back, text);
  // A variant link: which variant, and controls to run another.
  if (variant) note.append(variantSlot(variant));
  note.append(close);
  document.querySelector('.topbar')?.after(note);
  // Canvases size themselves to what is left.
  window.dispatchEvent(new Event('resize'));
}

interface CheckJson {
  holds: boolean;
  clauses: [{ name: string; text: string }, boolean][];
  runs: Record<string, Record<string, unknown>>;
}

/** Digits enough to check a relation on screen (0.0123 vs 0.0311 m). */
function fig(x: unknown, digits: number): string {
  return typeof x === 'number' && Number.isFinite(x) ? x.toFixed(digits) : '—';
}

/** One run's figures: outcome, time, length, tracking error or distance. */
function runFigures(m: Record<string, unknown>): string {
  const parts = [String(m.outcome ?? '')];
  if (m.time_s !== undefined) parts.push(`${fig(m.time_s, 2)} s`);
  if (m.path_length_m !== undefined) parts.push(`${fig(m.path_length_m, 3)} m`);
  if (typeof m.mean_tracking_error_m === 'number') parts.push(`tracking ${fig(m.mean_tracking_error_m, 4)} m`);
  if (typeof m.min_obstacle_distance_m === 'number') parts.push(`min distance ${fig(m.min_obstacle_distance_m, 4)} m`);
  if (typeof m.speed_drops === 'number') parts.push(`${m.speed_drops} speed drops`);
  return parts.join(' · ');
}

/**
 * When a run opened from a gallery card ends: runs the experiment on its
 * presets as `planlab reproduce ID --json` does (the reproduce module, in
 * this tab) and adds the ✓/✗ of the paper's relation to the note, each
 * clause's ✓/✗, and every run's figures with enough digits to check it.
 */
export function galleryRunEnded(outcome: string): void {
  const note = document.getElementById('gallery-note');
  const id = new URLSearchParams(location.search).get('exp');
  if (!note || !id || outcome === 'running' || note.querySelector('.gallery-note-check')) return;
  const out = document.createElement('div');
  out.className = 'gallery-note-check';
  out.textContent = `This run ended: ${outcome}. Checking the paper's relation on the presets (planlab reproduce ${id})…`;
  note.append(out);
  window.dispatchEvent(new Event('resize'));
  void (async () => {
    try {
      const m = await import('../../pkg-reproduce/planlab_wasm_reproduce.js');
      await m.default();
      const r = JSON.parse(m.reproduceCheck(id)) as CheckJson;
      const mark = r.holds ? '✓' : '✗';
      const head = document.createElement('b');
      head.textContent = `${mark} relation ${r.holds ? 'holds' : 'does not hold'}`;
      head.className = r.holds ? 'ok' : 'bad';
      const clauses = r.clauses.map(([c, ok]) => `${ok ? '✓' : '✗'} ${c.name}`).join(' · ');
      const runs = Object.entries(r.runs).map(([n, x]) => `${n}: ${runFigures(x)}`).join(' | ');
      out.replaceChildren(head, document.createTextNode(` on the presets (planlab reproduce ${id}): ${clauses}. Runs — ${runs}`));
      out.title = r.clauses.map(([c, ok]) => `${ok ? '✓' : '✗'} ${c.text}`).join('\n');
      document.body.dataset.relation = r.holds ? 'holds' : 'fails';
    } catch (e) {
      out.textContent = `This run ended: ${outcome}. (The relation could not be checked here: ${e instanceof Error ? e.message : String(e)}.)`;
      document.body.dataset.relation = 'error';
    }
    window.dispatchEvent(new Event('resize'));
  })();
}
