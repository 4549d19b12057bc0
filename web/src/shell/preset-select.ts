// The robot presets as the options of a page's Preset select (robot and
// compare pages), plus the hidden entry that says what is in force when it
// is no preset: a file or link opened, a generated map, an edited scenario.

import presets from 'virtual:robot-presets';

export function fillPresetSelect(select: HTMLSelectElement): void {
  for (const p of presets) {
    const o = document.createElement('option');
    o.value = p.file;
    o.textContent = `${p.name} — ${p.planner}`;
    o.title = p.description;
    select.append(o);
  }
  const opened = document.createElement('option');
  opened.value = '';
  opened.disabled = true;
  opened.hidden = true;
  opened.textContent = 'Opened from disk';
  select.append(opened);
}

/** What the Preset select says: a preset's value, or '' with the hidden
 *  entry's text (and `from`, the preset an edited scenario started from). */
export interface ShownLabel {
  value: string;
  text: string;
  from: string;
}

/** The select's state, to put back with `restoreShown` (undo / redo). */
export function shownLabel(select: HTMLSelectElement): ShownLabel {
  const hidden = select.querySelector<HTMLOptionElement>('option[value=""]');
  return { value: select.value, text: hidden?.textContent ?? '', from: select.dataset.from ?? '' };
}

export function restoreShown(select: HTMLSelectElement, s: ShownLabel): void {
  const hidden = select.querySelector<HTMLOptionElement>('option[value=""]');
  if (hidden) hidden.textContent = s.text;
  select.value = s.value;
  if (s.from) select.dataset.from = s.from;
  else delete select.dataset.from;
}

/** Selects the hidden entry with `text`: what is in force is no preset. */
function showHidden(select: HTMLSelectElement, text: string, from = ''): void {
  restoreShown(select, { value: '', text, from });
}

/** Selects the hidden entry, saying what is in force: `Opened: a shared
 *  link` or `Opened: NAME` for a file. */
export function showOpened(select: HTMLSelectElement | null, what: string): void {
  if (select) showHidden(select, `Opened: ${what}`);
}

/** After Generate: `Generated: maze, seed 7`. */
export function showGenerated(select: HTMLSelectElement | null, what: string): void {
  if (select) showHidden(select, `Generated: ${what}`);
}

/** After an edit of what is shown (walls, start, goal, movers): `Edited:`
 *  and its name, so a preset's name never stands for a changed map.
 *  `from` keeps the preset it started from (the compare link uses it). */
export function showEdited(select: HTMLSelectElement | null): void {
  if (!select) return;
  const now = shownLabel(select);
  if (now.value === '' && now.text.startsWith('Edited: ')) return;
  const name = now.value === '' ? now.text.replace(/^Opened: /, '').replace(/^Generated: /, 'generated ') : (select.selectedOptions[0]?.textContent ?? now.value);
  showHidden(select, `Edited: ${name}`, now.value || now.from);
}
