// Grid page URL: `index.html?scenario=FILE` opens a scenario of the site
// (./scenarios/FILE, its map and start/goal) as a pure global plan, and
// optional parameters pick the planner options, e.g. the gallery's S-fig6
// link `?scenario=S-fig6.json&algorithm=safe-astar&keypoints=1&bottom_up=20
// &inflate=0.3` (safe A* with key points and Bottom-Up feature nodes on the
// map inflated as safe-dual-dwa inflates it).

import { GRID_PLANNER_NAMES as ALGORITHMS } from '../shell/grid-planners';

/** What the URL asks for; `problems` are the parameters it could not take. */
export interface GridUrl {
  scenario: string | null;
  /** GridPlanOptions fields to set over the scenario's own. */
  options: Record<string, unknown>;
  problems: string[];
}


function flag(v: string): boolean | null {
  if (['1', 'true', 'on', 'yes'].includes(v)) return true;
  if (['0', 'false', 'off', 'no'].includes(v)) return false;
  return null;
}

/** Reads `scenario`, `algorithm` (a grid planner or one of `samplers`, the
 *  core's sampling planners), `keypoints`, `bottom_up` (cells, or 0/off)
 *  and `inflate` (m). */
export function gridUrl(search: string = location.search, samplers: string[] = []): GridUrl {
  const q = new URLSearchParams(search);
  const out: GridUrl = { scenario: null, options: {}, problems: [] };
  const s = q.get('scenario');
  if (s !== null) {
    // A file of ./scenarios/, nothing else of the site or beyond it.
    if (/^[\w.-]+\.json$/.test(s) && !s.startsWith('.')) out.scenario = s;
    else out.problems.push(`scenario “${s}” is not a scenario file name (FILE.json from ./scenarios/)`);
  }
  const algo = q.get('algorithm');
  if (algo !== null) {
    const known = [...ALGORITHMS, ...samplers];
    if (known.includes(algo)) out.options.algorithm = algo;
    else out.problems.push(`algorithm “${algo}” is not one of ${known.join(', ')}`);
  }
  const kp = q.get('keypoints');
  if (kp !== null) {
    const f = flag(kp);
    if (f === null) out.problems.push(`keypoints “${kp}”: use 1 or 0`);
    else out.options.keypoints = f;
  }
  const number = (name: string, key: string, offIsNull: boolean) => {
    const v = q.get(name);
    if (v === null) return;
    if (offIsNull && flag(v) === false) {
      out.options[key] = null;
      return;
    }
    const n = v.trim() === '' ? Number.NaN : Number(v);
    if (!Number.isFinite(n) || n < 0) out.problems.push(`${name} “${v}” is not a number ≥ 0`);
    else out.options[key] = n;
  };
  number('bottom_up', 'bottom_up_eps', true);
  number('inflate', 'inflate_m', false);
  return out;
}
