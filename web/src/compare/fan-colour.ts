// What colours the compare page's fans: the total score, or one critic by
// name. The names are those the lanes' planners report (never a fixed
// list), each lane colours by its own critic of that name (its normalised
// value), and a lane whose planner has no such critic keeps the total; its
// head says which. The colour scale under the select is the painter's.

import { fanGradient } from '../scene/paint';
import type { Lane } from './lane';

export interface FanColourHost {
  lanes(): Lane[];
  /** Pull the lanes and repaint after a change. */
  redraw(): void;
}

export class FanColours {
  constructor(
    private readonly select: HTMLSelectElement,
    scale: HTMLElement,
    private readonly host: FanColourHost,
  ) {
    scale.style.background = fanGradient();
    select.addEventListener('change', () => {
      this.apply();
      host.redraw();
    });
  }

  /** The lanes changed: lists every critic any of them has (a choice
   *  they still have stays) and colours their fans by it. */
  update(): void {
    const names: string[] = [];
    for (const l of this.host.lanes()) for (const n of critics(l)) if (!names.includes(n)) names.push(n);
    const keep = names.includes(this.select.value) ? this.select.value : '';
    const total = new Option('total score', '');
    this.select.replaceChildren(total, ...names.map((n) => new Option(n, n)));
    this.select.value = keep;
    this.apply();
  }

  private apply(): void {
    const name = this.select.value;
    document.body.dataset.fanColour = name || 'total';
    for (const l of this.host.lanes()) {
      const k = name ? critics(l).indexOf(name) : -1;
      l.sim.setFanColour(k < 0 ? undefined : k);
      l.fanColour = k < 0 ? 'total score' : name;
    }
  }
}

function critics(l: Lane): string[] {
  return (JSON.parse(l.sim.critics()) as { name: string }[]).map((c) => c.name);
}
