// The planner card's Critics list: every critic of the planner in force
// (names from the core's debug, never a fixed list, so new planners bring
// their own) with the weight it had in the last step, read again after
// every pull because planners like improved-dwa switch weight sets as the
// run goes; and the choice of what colours the rollout fan: the total
// score or one critic's normalised value (what its weight multiplies). The
// colour scale under the list says which.

import type { SimHandle } from '../../pkg/planlab_wasm.js';
import { fanGradient } from '../scene/paint';

/** One entry of `SimHandle.critics()`. */
interface Critic {
  name: string;
  /** Weight in the last step; null before the first step. */
  weight: number | null;
}

export interface CriticsHost {
  /** The fan colour changed to critic `k` (undefined: the total): the
   *  handle has it already; redraw. */
  changed(k: number | undefined): void;
}

function fmt(w: number | null): string {
  return w === null ? '—' : String(Number(w.toPrecision(4)));
}

export class CriticsPanel {
  /** The critic the fan is coloured by (its name, kept across planner
   *  swaps that have it), or null for the total score. */
  private chosen: string | null = null;
  /** The names last listed, to rebuild only when the planner changes. */
  private names: string[] | null = null;
  private sim: SimHandle | null = null;
  private readonly list = document.createElement('div');
  private readonly what = document.createElement('span');
  private readonly weights = new Map<string, HTMLElement>();

  /** `legend`: the status bar's fan entry, which names the colouring too. */
  constructor(
    private readonly root: HTMLElement,
    private readonly legend: HTMLElement,
    private readonly host: CriticsHost,
  ) {
    const head = document.createElement('div');
    head.className = 'param-group';
    head.textContent = 'Critics · weight this step';
    head.title = 'Each critic of the planner with the weight it had in the last step; pick one to colour the fan by it';
    this.list.className = 'critic-list';
    this.list.setAttribute('role', 'radiogroup');
    this.list.setAttribute('aria-label', 'Colour the fan by');
    const scale = document.createElement('div');
    scale.className = 'fan-scale';
    const bar = document.createElement('div');
    bar.className = 'fan-scale-bar';
    const ramp = document.createElement('i');
    ramp.style.background = fanGradient();
    const low = document.createElement('span');
    low.textContent = 'low';
    const high = document.createElement('span');
    high.textContent = 'high';
    bar.append(low, ramp, high);
    this.what.className = 'fan-scale-what';
    scale.append(this.what, bar);
    root.replaceChildren(head, this.list, scale);
  }

  /** Follows `sim` after a step, an edit or a swap: the critics of its
   *  planner, their weights now, and the fan colour (by name: a planner
   *  without the chosen critic falls back to the total). Call before
   *  drawing. */
  refresh(sim: SimHandle): void {
    const critics = JSON.parse(sim.critics()) as Critic[];
    const names = critics.map((c) => c.name);
    if (sim !== this.sim || !this.names || names.join('\n') !== this.names.join('\n')) {
      this.sim = sim;
      this.names = names;
      if (this.chosen !== null && !names.includes(this.chosen)) this.chosen = null;
      this.build(names);
      sim.setFanColour(this.index());
    }
    for (const c of critics) {
      const e = this.weights.get(c.name);
      const text = fmt(c.weight);
      if (!e || e.textContent === text) continue;
      e.textContent = text;
      e.parentElement!.dataset.weight = c.weight === null ? '' : String(c.weight);
    }
  }

  /** The chosen critic's index, undefined for the total. */
  private index(): number | undefined {
    const k = this.chosen === null ? -1 : (this.names ?? []).indexOf(this.chosen);
    return k < 0 ? undefined : k;
  }

  private build(names: string[]): void {
    this.weights.clear();
    const rows = [this.row(null, 'total score', 'Σ')];
    for (const n of names) rows.push(this.row(n, n, '—'));
    this.list.replaceChildren(...rows);
    if (!names.length) {
      const p = document.createElement('p');
      p.className = 'small muted';
      p.textContent = 'This planner reports no critics.';
      this.list.append(p);
    }
    this.caption();
  }

  private row(name: string | null, label: string, weight: string): HTMLElement {
    const l = document.createElement('label');
    l.className = 'critic';
    l.dataset.critic = name ?? 'total';
    const r = document.createElement('input');
    r.type = 'radio';
    r.name = 'fan-colour';
    r.value = name ?? '';
    r.checked = name === this.chosen;
    r.addEventListener('change', () => this.pick(name));
    const n = document.createElement('span');
    n.textContent = label;
    const w = document.createElement('span');
    w.className = 'weight';
    w.textContent = weight;
    if (name !== null) {
      w.title = 'The weight this critic had in the last step';
      this.weights.set(name, w);
    } else w.title = 'The total: every critic’s normalised value times its weight, summed';
    l.append(r, n, w);
    return l;
  }

  private pick(name: string | null): void {
    this.chosen = name;
    const k = this.index();
    this.sim?.setFanColour(k);
    this.caption();
    this.host.changed(k);
  }

  private caption(): void {
    const c = this.chosen;
    this.root.dataset.fanColour = c ?? 'total';
    this.legend.textContent = `Rollouts (${c ?? 'score'})`;
    this.what.textContent =
      c === null
        ? 'Fan coloured by the total score (grey: not allowed)'
        : `Fan coloured by ${c}: its normalised value (grey: not allowed)`;
  }
}
