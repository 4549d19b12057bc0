// The arm page's planner comparison: `planlab batch` of the loaded arm
// scenario in the browser. Each (variant, planner) row is drawn and run by
// the core (wasm `armBatchRun`, the CLI's row exactly); this file only
// times each call, yields to the browser between calls and takes medians.

import { armBatchRun, editScenario } from '../../pkg-arm/planlab_wasm_arm.js';
import { recipeJson } from '../shell/runlink';
import { el, messageOf } from '../shell/dom';

/** The planners compared, in the table's order, with their page labels. */
const PLANNERS: [string, string][] = [
  ['apf', 'APF (thesis)'],
  ['rrt-connect', 'RRT-Connect'],
];
/** The arm batch's default jitter, m (the core's ARM_JITTER_M). */
const JITTER_M = 0.02;

/** One run as the core reports it (the fields the table uses). */
interface ArmRun {
  metrics: { outcome: string; min_obstacle_distance_m: number };
  joint_path_length_rad: number;
  gripper_path_length_m: number;
  trace_hash: string;
}

/** A planner's row of the table, also what the end-to-end test reads. */
export interface CompareRow {
  planner: string;
  runs: number;
  reached: number;
  joint_median_rad: number | null;
  gripper_median_m: number | null;
  hand_median_m: number;
  hand_min_m: number;
  compute_median_ms: number;
  hashes: string[];
}

function median(v: number[]): number | null {
  if (v.length === 0) return null;
  const s = [...v].sort((a, b) => a - b);
  const m = s.length >> 1;
  return s.length % 2 ? s[m] : 0.5 * (s[m - 1] + s[m]);
}

const fmt = (v: number | null, unit: string, digits = 3) => (v === null ? '—' : `${v.toFixed(digits)} ${unit}`);

/** The `--set` edits that give the scene the page's predictor. */
function predictorSets(predictor: string): [string, string][] {
  if (predictor === 'none') return [['arm.apf.mode', 'sampling']];
  return [
    ['arm.apf.mode', 'sampling-prediction'],
    ['arm.apf.predictor', predictor],
  ];
}

/** Wires the comparison card. `scene` gives the loaded preset's file name
 *  and text and the predictor chosen on the page. */
export function installCompare(
  scene: () => Promise<{ file: string; text: string; predictor: string; tableZ: number }>,
  showError: (msg: string | null) => void,
): { last: () => CompareRow[] } {
  const run = el<HTMLButtonElement>('compare-run');
  const variants = el<HTMLInputElement>('compare-variants');
  const seed = el<HTMLInputElement>('compare-seed');
  const progress = el('compare-progress');
  const table = el<HTMLTableElement>('compare-table');
  const cli = el('compare-cli');
  let rows: CompareRow[] = [];

  run.addEventListener('click', async () => {
    const n = Number(variants.value);
    const s = Number(seed.value);
    if (!Number.isInteger(n) || n < 1 || n > 100) {
      showError(`Variants ${variants.value}: must be a whole number from 1 to 100`);
      return;
    }
    if (!Number.isInteger(s) || s < 0 || s > 4294967295) {
      showError(`Seed ${seed.value}: must be a whole number from 0 to 4294967295`);
      return;
    }
    showError(null);
    run.disabled = true;
    document.body.dataset.compare = 'running';
    try {
      const { file, text, predictor, tableZ } = await scene();
      const sets: [string, string][] = [['arm.table_z_m', String(tableZ)], ...predictorSets(predictor)];
      const edited = editScenario(text, recipeJson(null, sets));
      const acc = PLANNERS.map(() => ({ runs: [] as ArmRun[], ms: [] as number[] }));
      for (let k = 0; k < n; k++) {
        for (let p = 0; p < PLANNERS.length; p++) {
          progress.textContent = `variant ${k + 1} of ${n}: ${PLANNERS[p][1]}…`;
          // Let the browser paint the progress before the next episode.
          await new Promise((r) => setTimeout(r, 0));
          const t0 = performance.now();
          const out = armBatchRun(edited, k, s, JITTER_M, PLANNERS[p][0]);
          acc[p].ms.push(performance.now() - t0);
          acc[p].runs.push(JSON.parse(out));
        }
      }
      rows = PLANNERS.map(([name], p) => {
        const ok = acc[p].runs.filter((r) => r.metrics.outcome === 'reached');
        const hand = acc[p].runs.map((r) => r.metrics.min_obstacle_distance_m);
        return {
          planner: name,
          runs: acc[p].runs.length,
          reached: ok.length,
          joint_median_rad: median(ok.map((r) => r.joint_path_length_rad)),
          gripper_median_m: median(ok.map((r) => r.gripper_path_length_m)),
          hand_median_m: median(hand) ?? 0,
          hand_min_m: Math.min(...hand),
          compute_median_ms: median(acc[p].ms) ?? 0,
          hashes: acc[p].runs.map((r) => r.trace_hash),
        };
      });
      const body = table.tBodies[0];
      body.replaceChildren();
      rows.forEach((r, p) => {
        const tr = body.insertRow();
        const cells = [
          PLANNERS[p][1],
          `${r.reached}/${r.runs}`,
          fmt(r.joint_median_rad, 'rad'),
          fmt(r.gripper_median_m, 'm'),
          `${fmt(r.hand_median_m, 'm')} (min ${fmt(r.hand_min_m, 'm')})`,
          fmt(r.compute_median_ms, 'ms', 1),
        ];
        for (const c of cells) tr.insertCell().textContent = c;
        tr.dataset.planner = r.planner;
      });
      table.hidden = false;
      const setArgs = sets.map(([k, v]) => ` --set ${k}=${v}`).join('');
      cli.innerHTML = '';
      cli.append('The same rows from the command line: ');
      const code = document.createElement('code');
      code.textContent = `planlab batch assets/scenarios/${file} --planners apf,rrt-connect --variants ${n} --seed ${s}${setArgs}`;
      cli.append(code, ' (its compute times are native, these are this browser\u2019s).');
      cli.hidden = false;
      progress.textContent = `${n * PLANNERS.length} episodes`;
      document.body.dataset.compare = 'done';
    } catch (e) {
      showError(`Comparison failed: ${messageOf(e)}`);
      progress.textContent = '';
      document.body.dataset.compare = 'error';
    } finally {
      run.disabled = false;
    }
  });
  return { last: () => rows };
}
