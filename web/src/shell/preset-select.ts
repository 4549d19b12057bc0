// The robot presets as the options of a page's Preset select (robot and
// compare pages), plus the hidden "Opened from disk" entry shown while a
// file opened by the user is in force.

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

/** Selects the hidden entry, saying what is in force: `Opened: a shared
 *  link` or `Opened: NAME` for a file. */
export function showOpened(select: HTMLSelectElement | null, what: string): void {
  if (!select) return;
  const opened = select.querySelector<HTMLOptionElement>('option[value=""]');
  if (opened) opened.textContent = `Opened: ${what}`;
  select.value = '';
}
