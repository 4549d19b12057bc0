// The comparison table: the metrics `planlab run` prints (same rows, order,
// units and digits as its text table), one column per planner, and the
// winner of each row. Pure functions, no DOM: main.ts renders them.

import type { Metrics } from '../shell/metrics';

/** Which way a row is better. */
export type Better = 'lower' | 'higher' | 'reached';

export interface Row {
  /** Field of {@link Metrics}. */
  key: keyof Metrics;
  /** Label and unit as `planlab run` prints them. */
  label: string;
  unit: string;
  /** Digits shown (and compared: values equal when shown are a tie). */
  digits: number;
  /** Shown value = field × scale (the load share is printed in %). */
  scale: number;
  better: Better;
  /** Only planners that reached the goal compete, even when none did (a
   *  robot stuck at the start is not "faster"). The other rows are also
   *  compared among the planners that reached the goal when any did (a
   *  robot that crashed after 4 s has not "turned less"), else among all. */
  reachedOnly: boolean;
  /** Why, for the row's tooltip. */
  doc: string;
}

/** The rows of `planlab run`'s table, in its order. */
export const ROWS: readonly Row[] = [
  { key: 'outcome', label: 'outcome', unit: '', digits: 0, scale: 1, better: 'reached', reachedOnly: false, doc: 'How the episode ended; reached beats collision, timeout and stuck.' },
  { key: 'time_s', label: 'time', unit: 's', digits: 2, scale: 1, better: 'lower', reachedOnly: true, doc: 'Episode duration; only planners that reached the goal compete.' },
  { key: 'path_length_m', label: 'path length', unit: 'm', digits: 3, scale: 1, better: 'lower', reachedOnly: true, doc: 'Driven path length; only planners that reached the goal compete.' },
  { key: 'min_clearance_m', label: 'min clearance', unit: 'm', digits: 3, scale: 1, better: 'higher', reachedOnly: false, doc: 'Smallest footprint clearance over the episode.' },
  { key: 'mean_clearance_m', label: 'mean clearance', unit: 'm', digits: 3, scale: 1, better: 'higher', reachedOnly: false, doc: 'Mean footprint clearance over the episode.' },
  { key: 'total_turn_rad', label: 'total turning', unit: 'rad', digits: 3, scale: 1, better: 'lower', reachedOnly: false, doc: 'Sum of the turning angles of the driven path (resampled every 0.1 m).' },
  { key: 'max_turn_rad', label: 'max turning', unit: 'rad', digits: 3, scale: 1, better: 'lower', reachedOnly: false, doc: 'Largest turning angle at one resampled point.' },
  { key: 'speed_drops', label: 'speed drops', unit: '', digits: 0, scale: 1, better: 'lower', reachedOnly: false, doc: 'Falls by more than 30% of the peak speed followed by a rise.' },
  { key: 'temp_goal_switches', label: 'temp-goal switches', unit: '', digits: 0, scale: 1, better: 'lower', reachedOnly: false, doc: 'Switches between the goal and temporary goals ([L] planners).' },
  { key: 'mean_tracking_error_m', label: 'mean tracking error', unit: 'm', digits: 3, scale: 1, better: 'lower', reachedOnly: false, doc: 'Mean distance to the global path (n/a without one).' },
  { key: 'max_tracking_error_m', label: 'max tracking error', unit: 'm', digits: 3, scale: 1, better: 'lower', reachedOnly: false, doc: 'Largest distance to the global path.' },
  { key: 'tracking_error_var_m2', label: 'tracking error var', unit: 'm²', digits: 4, scale: 1, better: 'lower', reachedOnly: false, doc: 'Variance of the distance to the global path.' },
  { key: 'load_ok_share', label: 'wheel loads > 40 N', unit: '%', digits: 1, scale: 100, better: 'higher', reachedOnly: false, doc: 'Share of rows with every wheel load above 40 N ([C] Table 5; n/a without a vehicle model).' },
];

/** A row's value for one planner as shown (rounded), or null (n/a). */
export function shownValue(row: Row, m: Metrics): number | null {
  if (row.better === 'reached') return null;
  const v = m[row.key] as number | null;
  if (v === null || v === undefined || !Number.isFinite(v)) return null;
  return Number((v * row.scale).toFixed(row.digits));
}

/** The cell text with the digits `planlab run` prints (the unit is in the
 *  row's label). */
export function cellText(row: Row, m: Metrics): string {
  if (row.key === 'outcome') return m.outcome;
  const v = m[row.key] as number | null;
  if (v === null || v === undefined || !Number.isFinite(v)) return 'n/a';
  return (v * row.scale).toFixed(row.digits);
}

/**
 * Indices of the planners that win `row` (all of them on a tie), empty when
 * nobody does: fewer than two planners have a value, or (for the outcome,
 * time and path length) nobody reached the goal. See {@link Row.reachedOnly}
 * for who competes.
 */
export function winners(row: Row, ms: readonly Metrics[]): number[] {
  if (row.better === 'reached') {
    const r = ms.flatMap((m, i) => (m.outcome === 'reached' ? [i] : []));
    return ms.length >= 2 ? r : [];
  }
  const values = ms.map((m) => shownValue(row, m));
  if (values.filter((v) => v !== null).length < 2) return [];
  const anyReached = ms.some((m) => m.outcome === 'reached');
  const competes = (i: number) => ms[i].outcome === 'reached' || (!row.reachedOnly && !anyReached);
  const eligible = values.flatMap((v, i) => (v !== null && competes(i) ? [i] : []));
  if (!eligible.length) return [];
  const pick = row.better === 'lower' ? Math.min : Math.max;
  const best = pick(...eligible.map((i) => values[i] as number));
  return eligible.filter((i) => values[i] === best);
}

function csvField(s: string): string {
  return /[",\n]/.test(s) ? `"${s.replaceAll('"', '""')}"` : s;
}

/**
 * The table as CSV: `metric,unit,<planner>…,winner`, full-precision values
 * (as `planlab run --json` prints them, empty for n/a), the winners' names
 * separated by spaces; then `steps` and `trace_hash` rows.
 */
export function tableCsv(
  names: readonly string[],
  ms: readonly Metrics[],
  extra: { steps: number[]; hashes: string[] },
  final: boolean,
): string {
  const lines = [['metric', 'unit', ...names, 'winner'].map(csvField).join(',')];
  for (const row of ROWS) {
    const cells = ms.map((m) => {
      const v = m[row.key];
      if (v === null || v === undefined) return '';
      return typeof v === 'number' ? String(v * row.scale) : String(v);
    });
    const win = final ? winners(row, ms).map((i) => names[i]).join(' ') : '';
    lines.push([row.key === 'load_ok_share' ? 'load_ok_pct' : row.key, row.unit, ...cells, win].map(csvField).join(','));
  }
  lines.push(['steps', '', ...extra.steps.map(String), ''].map(csvField).join(','));
  lines.push(['trace_hash', '', ...extra.hashes, ''].map(csvField).join(','));
  return lines.join('\n') + '\n';
}
