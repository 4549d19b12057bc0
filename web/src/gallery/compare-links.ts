// "Compare these runs": a gallery card whose robot runs differ only in the
// planner opens the compare page with the scenario and those planners.
// The compare page applies its `set` edits to every planner, so runs with
// different edits cannot be one comparison: the runs are grouped by preset
// and edits, and each group of ≥ 2 distinct planners gets its own link.

import type { GalleryEntry, GalleryRun } from '../shell/runlink';

/** Most planners the compare page shows at once. */
const MAX_PLANNERS = 4;

/** One comparison: runs sharing preset and edits, with distinct planners. */
export interface RunGroup {
  preset: string;
  set: [string, string][];
  runs: GalleryRun[];
  planners: string[];
}

/** The comparable groups of a robot entry; `ownPlanner(preset)` is the
 *  preset's own planner (a run without `planner` runs that one). Edits of
 *  `local_planner.*` stay edits: the compare page's planner swap resets the
 *  config, a `--set local_planner.name` keeps it, so they are not the same run. */
export function compareGroups(e: GalleryEntry, ownPlanner: (preset: string) => string | undefined): RunGroup[] {
  if (e.page !== 'robot') return [];
  const groups = new Map<string, RunGroup>();
  for (const r of e.runs) {
    const planner = r.planner ?? ownPlanner(r.preset);
    if (!planner) continue;
    const key = JSON.stringify([r.preset, r.set]);
    let g = groups.get(key);
    if (!g) groups.set(key, (g = { preset: r.preset, set: r.set, runs: [], planners: [] }));
    if (g.planners.includes(planner) || g.planners.length >= MAX_PLANNERS) continue;
    g.runs.push(r);
    g.planners.push(planner);
  }
  return [...groups.values()].filter((g) => g.planners.length >= 2);
}

/** The compare page URL of a group, started at once. */
export function compareUrl(g: RunGroup): string {
  const q = new URLSearchParams();
  q.set('scenario', g.preset);
  q.set('planners', g.planners.join(','));
  for (const [p, v] of g.set) q.append('set', `${p}=${v}`);
  q.set('autorun', '1');
  return `./compare.html?${q.toString().replaceAll('%2C', ',')}`;
}
