// The robot page's Global planner card: none (the local planner steers on
// its own) or Hybrid A*, a car path of a minimum turning radius (and, with
// "may reverse", cusps) that the local planner follows. A change restarts
// the episode from the scenario in force (every edit kept) with the
// scenario's `global_planner` section set or removed, so the run is the one
// `planlab run` gives for the saved scenario. Hybrid A* guides only local
// planners that steer to the goal they are given (the core's list); with
// another one in force the local planner becomes `dwa`, and the card says so.

import { globalFollowers, type SimHandle } from '../../pkg/planlab_wasm.js';
import { el, type ErrorBanner } from '../shell/dom';

/** What `SimHandle.globalPath()` returns. */
export interface GlobalPathInfo {
  spec: { algorithm: string; turning_radius_m: number; reverse: boolean };
  length_m: number;
  cusps: number;
  expanded: number;
  replans: number;
}

export interface GlobalHost {
  sim(): SimHandle | null;
  /** The episode in force as scenario JSON (Save's text). */
  scenarioJson(): string;
  /** Loads scenario JSON as a fresh episode (throws the core's error). */
  load(text: string): void;
  guard: ErrorBanner['guard'];
}

/** The car path of `sim`, if it follows one. */
export function globalPathOf(sim: SimHandle): GlobalPathInfo | null {
  const j = sim.globalPath();
  return j ? (JSON.parse(j) as GlobalPathInfo) : null;
}

export class GlobalPicker {
  private readonly select = el<HTMLSelectElement>('global-planner');
  private readonly fields = el('car-fields');
  private readonly radius = el<HTMLInputElement>('turning-radius');
  private readonly reverse = el<HTMLInputElement>('car-reverse');
  private readonly summary = el('global-summary');
  private followers: string[] | null = null;
  /** Set when the last restart swapped the local planner for `dwa`. */
  private swapped = '';

  constructor(private readonly host: GlobalHost) {
    const apply = host.guard(() => this.apply());
    this.select.addEventListener('change', apply);
    this.radius.addEventListener('change', apply);
    this.reverse.addEventListener('change', apply);
  }

  /** Shows the global planner of `sim` (after a load or restart). */
  showOf(sim: SimHandle): void {
    const g = globalPathOf(sim);
    this.select.value = g ? g.spec.algorithm : '';
    this.fields.hidden = !g;
    const body = document.body.dataset;
    if (g) {
      this.radius.value = String(g.spec.turning_radius_m);
      this.reverse.checked = g.spec.reverse;
      body.globalLength = String(g.length_m);
      const swap = this.swapped ? ` The local planner ${this.swapped} plans its own route, so dwa follows the path.` : '';
      this.summary.textContent =
        `Hybrid A* car path (red): ${g.length_m.toFixed(3)} m, ${g.cusps} cusp${g.cusps === 1 ? '' : 's'}, ${g.expanded} poses expanded; turns no tighter than ${g.spec.turning_radius_m} m${g.spec.reverse ? ', may reverse' : ''}.${swap}`;
    } else {
      delete body.globalLength;
      this.summary.textContent = 'None: the local planner finds its own way to the goal.';
    }
    this.swapped = '';
  }

  /** Restarts with the card's choice. */
  private apply(): void {
    const doc = JSON.parse(this.host.scenarioJson()) as Record<string, unknown>;
    const algorithm = this.select.value;
    if (!algorithm) {
      delete doc.global_planner;
    } else {
      // An empty or non-numeric field goes to the core as null: its typed
      // error names turning_radius_m.
      const r = this.radius.value.trim() === '' ? null : Number(this.radius.value);
      doc.global_planner = { algorithm, turning_radius_m: r !== null && Number.isFinite(r) ? r : null, reverse: this.reverse.checked };
      this.followers ??= JSON.parse(globalFollowers()) as string[];
      const local = (doc.local_planner as { name?: string } | undefined)?.name ?? 'dwa';
      if (!this.followers.includes(local)) {
        doc.local_planner = { name: 'dwa', config: {} };
        this.swapped = local;
      }
    }
    try {
      this.host.load(JSON.stringify(doc));
    } catch (e) {
      // The run in force goes on: show its choice again.
      this.swapped = '';
      const sim = this.host.sim();
      if (sim) this.showOf(sim);
      throw e;
    }
  }
}
