// What the compare page's URL asks for at start: `view`, `speed`, the
// preset (`scenario`, with its `set=path=value` edits), the `planners`
// (else DWA against the preset's own, or improved DWA) and `autorun`
// (`instant` runs to the end at once, anything but 0 plays). A name it
// cannot take is reported, and the rest still opens.

import presets from 'virtual:robot-presets';
import { runParams } from '../shell/runlink';
import { messageOf } from '../shell/dom';
import type { PlannerPicks } from './picks';

export interface OpenHost {
  picks: PlannerPicks;
  speed: HTMLSelectElement;
  setView(v: 'side' | 'overlay'): void;
  loadPreset(file: string, edits: [string, string][]): Promise<void>;
  /** Shows `problems` (with what the banner already says). */
  report(problems: string[]): void;
  /** `instant`: run to the end at once; `play`: start playing. */
  autorun(how: 'instant' | 'play'): Promise<void>;
}

export async function openFromUrl(host: OpenHost): Promise<void> {
  // Read before anything rewrites the URL.
  const q = new URLSearchParams(location.search);
  const urlEdits = runParams(location.search).set;
  host.setView(q.get('view') === 'overlay' ? 'overlay' : 'side');
  const sp = q.get('speed');
  if (sp && Array.from(host.speed.options).some((o) => o.value === sp)) {
    host.speed.value = sp;
    host.speed.dispatchEvent(new Event('input'));
  }
  const problems: string[] = [];
  const want = q.get('scenario');
  let file = presets[0]?.file;
  if (want) {
    if (presets.some((p) => p.file === want)) file = want;
    else problems.push(`no preset “${want}”; showing ${file}`);
  }
  if (!file) throw new Error('no robot presets (assets/scenarios/*.json with a local_planner)');
  const names = q.get('planners');
  const own = presets.find((p) => p.file === file)?.planner;
  try {
    if (names !== null) host.picks.apply(names.split(','));
    else host.picks.apply(own && own !== 'dwa' ? ['dwa', own] : ['dwa', 'improved-dwa']);
  } catch (e) {
    problems.push(messageOf(e));
  }
  // Edits belong to the scenario the URL names.
  await host.loadPreset(file, file === want ? urlEdits : []);
  if (problems.length) host.report(problems);
  const auto = q.get('autorun');
  if (auto === 'instant') await host.autorun('instant');
  else if (auto !== null && auto !== '0') await host.autorun('play');
}
