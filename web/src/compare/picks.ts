// The compare page's planner picks: a checkbox per registered planner, at
// most MAX_PLANNERS ticked, in the order picked (which gives each its
// colour and column), and the hint that says how many more to pick.

import type { PlannerInfo } from '../shell/planner-info';
import { laneColour } from './render';

/** Planners compared at once. */
export const MIN_PLANNERS = 2;
export const MAX_PLANNERS = 4;

export class PlannerPicks {
  /** Picked planner names, in the order picked. */
  chosen: string[] = [];
  infos: PlannerInfo[] = [];

  constructor(
    private readonly list: HTMLUListElement,
    private readonly count: HTMLElement,
    private readonly hint: HTMLElement,
  ) {}

  /** A checkbox per planner; `changed` after each (un)tick (the guard
   *  shows what it throws). */
  build(infos: PlannerInfo[], guard: (f: () => void) => () => void, changed: () => void): void {
    this.infos = infos;
    const items = infos.map((p) => {
      const li = document.createElement('li');
      li.dataset.planner = p.name;
      const label = document.createElement('label');
      label.className = 'check';
      const box = document.createElement('input');
      box.type = 'checkbox';
      box.value = p.name;
      box.id = `pick-${p.name}`;
      box.addEventListener(
        'change',
        guard(() => {
          if (box.checked) {
            if (this.chosen.length >= MAX_PLANNERS) {
              box.checked = false;
              throw new Error(`At most ${MAX_PLANNERS} planners can be compared at once.`);
            }
            this.chosen.push(p.name);
          } else {
            this.chosen = this.chosen.filter((n) => n !== p.name);
          }
          changed();
        }),
      );
      const sw = document.createElement('i');
      sw.className = 'lane-swatch';
      const name = document.createElement('span');
      name.textContent = p.name;
      label.append(box, sw, name);
      li.append(label);
      return li;
    });
    this.list.replaceChildren(...items);
  }

  /** Picks `names` (a URL's list): unknown names and more than the maximum
   *  are reported, the rest kept. */
  apply(names: string[]): void {
    const known = new Set(this.infos.map((p) => p.name));
    const problems: string[] = [];
    const out: string[] = [];
    for (const n of names) {
      if (!n) continue;
      if (!known.has(n)) problems.push(`unknown planner “${n}” (known: ${[...known].join(', ')})`);
      else if (!out.includes(n)) out.push(n);
    }
    if (out.length > MAX_PLANNERS) {
      problems.push(`at most ${MAX_PLANNERS} planners can be compared; kept ${out.slice(0, MAX_PLANNERS).join(', ')}`);
      out.length = MAX_PLANNERS;
    }
    this.chosen = out;
    if (problems.length) throw new Error(problems.join(' · '));
  }

  /** Marks the scenario's own planner in the list. */
  markOwn(own: string | null): void {
    for (const li of Array.from(this.list.children) as HTMLElement[]) li.dataset.own = String(li.dataset.planner === own);
  }

  /** Ticks, colours, the count and the hint; returns the hint and whether
   *  it warns (fewer than the minimum). `locked`: nothing can change now. */
  render(locked: boolean): [string, boolean] {
    const n = this.chosen.length;
    this.count.textContent = `${n} / ${MAX_PLANNERS}`;
    for (const li of Array.from(this.list.children) as HTMLElement[]) {
      const box = li.querySelector('input') as HTMLInputElement;
      const name = li.dataset.planner ?? '';
      const idx = this.chosen.indexOf(name);
      box.checked = idx >= 0;
      box.disabled = locked || (idx < 0 && n >= MAX_PLANNERS);
      li.title = idx < 0 && n >= MAX_PLANNERS ? `At most ${MAX_PLANNERS} planners at once: untick one first.` : (this.infos.find((p) => p.name === name)?.summary ?? '');
      const sw = li.querySelector('.lane-swatch') as HTMLElement;
      sw.style.background = idx >= 0 ? laneColour(this.chosen, name) : 'transparent';
    }
    let hint: string;
    let warn = false;
    if (n < MIN_PLANNERS) {
      hint = n === 0 ? 'Pick 2 to 4 planners to compare.' : `Pick at least one more planner: a comparison needs ${MIN_PLANNERS} to ${MAX_PLANNERS}.`;
      warn = true;
    } else if (n >= MAX_PLANNERS) {
      hint = `${MAX_PLANNERS} planners picked (the most at once): untick one to pick another.`;
    } else {
      hint = `${n} planners picked; up to ${MAX_PLANNERS}.`;
    }
    this.hint.textContent = hint;
    this.hint.dataset.warn = String(warn);
    return [hint, warn];
  }
}
