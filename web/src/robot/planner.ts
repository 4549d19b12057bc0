// The robot page's planner card: the registry's planners in a select, the
// chosen one's summary and its parameter panel (params.ts). A pick swaps
// the planner in at the robot's current state; a parameter edit re-tunes it
// at the next frame (one swap for a burst of slider events). Both are live
// edits of the SimHandle, which the core validates.

import type { SimHandle } from '../../pkg/planlab_wasm.js';
import { ParamPanel } from './params';
import type { PlannerInfo } from '../shell/planner-info';
import { el, messageOf, type ErrorBanner } from '../shell/dom';

type Choice = { name: string; config: Record<string, unknown> };

export interface PlannerHost {
  sim(): SimHandle | null;
  /** After a swap: clear the banner, pull and repaint. */
  refresh(): void;
  showError(text: string): void;
  guard: ErrorBanner['guard'];
}

export class PlannerPicker {
  /** The registry's planners by name. */
  infos = new Map<string, PlannerInfo>();
  private readonly select = el<HTMLSelectElement>('planner');
  private readonly summary = el('planner-summary');
  private readonly panel: ParamPanel;
  /** The edit the panel queued for the next frame. */
  private pending: Choice | null = null;

  constructor(private readonly host: PlannerHost) {
    this.panel = new ParamPanel(el('params'), (config) => this.queue({ name: this.select.value, config }));
    el<HTMLButtonElement>('params-default').addEventListener('click', host.guard(() => this.panel.resetDefaults()));
    this.select.addEventListener('change', host.guard(() => this.pick(this.select.value)));
  }

  /** The planner shown. */
  get value(): string {
    return this.select.value;
  }

  /** Fills the select from the registry's list. */
  setList(list: PlannerInfo[]): void {
    this.infos = new Map(list.map((p) => [p.name, p]));
    for (const p of list) {
      const o = document.createElement('option');
      o.value = p.name;
      o.textContent = p.name;
      o.title = p.summary;
      this.select.append(o);
    }
  }

  /** Shows planner `name` with `config` (an unknown name gets an option). */
  show(name: string, config: Record<string, unknown>): void {
    if (!Array.from(this.select.options).some((o) => o.value === name)) {
      const o = document.createElement('option');
      o.value = name;
      o.textContent = name;
      this.select.append(o);
    }
    this.select.value = name;
    const info = this.infos.get(name) ?? { name, paper: '', summary: '', fields: [] };
    this.summary.textContent = [info.summary, info.paper].filter(Boolean).join(' — ') || '—';
    this.panel.show(info, config);
  }

  /** Shows the planner in force in `sim`. */
  showChoiceOf(sim: SimHandle): void {
    const c = JSON.parse(sim.plannerChoice()) as Choice;
    this.show(c.name, c.config);
  }

  /** A pick in the select: swap it in with the paper's defaults; a refusal
   *  puts the old one back on show. */
  private pick(name: string): void {
    const sim = this.host.sim();
    if (!sim) return;
    const prev = JSON.parse(sim.plannerChoice()) as Choice;
    try {
      sim.setPlanner(name, '{}');
    } catch (e) {
      this.show(prev.name, prev.config);
      throw e;
    }
    this.show(name, {});
    this.host.refresh();
  }

  private queue(c: Choice): void {
    if (!this.host.sim()) return;
    const first = this.pending === null;
    this.pending = c;
    if (!first) return;
    requestAnimationFrame(() => {
      const sim = this.host.sim();
      const p = this.pending;
      this.pending = null;
      if (!sim || !p) return;
      try {
        sim.setPlanner(p.name, JSON.stringify(p.config));
        this.host.refresh();
      } catch (e) {
        this.host.showError(messageOf(e));
      }
    });
  }
}
