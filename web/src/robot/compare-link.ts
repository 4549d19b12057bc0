// The robot page's "Compare planners…" link: opens the compare page on the
// current preset with the planner in use and a second one to compare with
// (and the edits of the run link that opened this page, if any).
// Kept out of main.ts: it only reads the preset and planner selects.

const link = document.getElementById('compare-link') as HTMLAnchorElement | null;
const preset = document.getElementById('preset') as HTMLSelectElement | null;
const planner = document.getElementById('planner') as HTMLSelectElement | null;

/** The compare page URL for what the robot page shows now. */
function compareHref(): string {
  const q = new URLSearchParams();
  // An edited preset: its preset (the compare page has no edits of it).
  const scenario = preset?.value || preset?.dataset.from;
  if (scenario) q.set('scenario', scenario);
  const current = planner?.value || 'dwa';
  // Baseline DWA against the planner in use; improved DWA against DWA.
  const other = current === 'dwa' ? 'improved-dwa' : 'dwa';
  q.set('planners', `${current},${other}`);
  // A run link's edits (`set=path=value`, e.g. from the gallery) go along
  // while its preset is still the one shown.
  const here = new URLSearchParams(location.search);
  if (preset?.value && here.get('scenario') === preset.value) for (const e of here.getAll('set')) q.append('set', e);
  return `./compare.html?${q.toString().replaceAll('%2C', ',')}`;
}

if (link) {
  const update = () => (link.href = compareHref());
  for (const ev of ['pointerenter', 'focus', 'pointerdown', 'click']) link.addEventListener(ev, update);
  preset?.addEventListener('change', update);
  planner?.addEventListener('change', update);
}
