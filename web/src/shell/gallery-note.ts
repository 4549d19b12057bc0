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
