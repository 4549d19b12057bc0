// A recorded grid search played back for the page's player: the core's
// replay (wasm `SearchReplay`) seeks forward and back, counts and answers
// what a cell holds; its draw list carries the search layers with only the
// cells changed since the last draw, so a frame costs the events it plays,
// not the map size. This wrapper only reshapes its answers.

import type { SearchReplay } from '../../pkg-grid/planlab_wasm.js';
import { DrawList } from './draw';

/** What hovering a cell shows. */
export interface CellInfo {
  state: 'unseen' | 'open' | 'closed';
  g: number;
  h: number;
  f: number;
  parent: [number, number] | null;
  /** 1-based step of the first open event, or null. */
  openedAt: number | null;
  /** 1-based step of the close event, or null. */
  closedAt: number | null;
}

export interface Counters {
  step: number;
  events: number;
  expanded: number;
  open: number;
  f: number;
  lines: number;
}

const STATES = ['unseen', 'open', 'closed'] as const;
const orNull = (x: number) => (Number.isNaN(x) ? null : x);

export class SearchPlayback {
  /** Events in the recording. */
  readonly n: number;

  constructor(private r: SearchReplay) {
    this.n = r.length;
  }

  /** Events applied: 0 (nothing) … n (the whole search). */
  get step(): number {
    return this.r.step;
  }

  get done(): boolean {
    return this.r.done;
  }

  /** Moves to `step` (clamped to 0…n), forward or back. */
  seek(step: number): void {
    this.r.seek(step);
  }

  /** The search layers of `layers` at the current step (cells changed
   *  since the last draw only, every cell on the first). */
  draw(layers: number): DrawList {
    return new DrawList(this.r.draw(layers));
  }

  /** The cell being expanded, or null. */
  expanding(): [number, number] | null {
    const c = this.r.expanding();
    return c ? [c[0], c[1]] : null;
  }

  /** g, h, f, parent and steps of a cell at the current step. */
  info(c: number, r: number): CellInfo | null {
    const i = this.r.info(c, r);
    if (!i) return null;
    return {
      state: STATES[i[0]] ?? 'unseen',
      g: i[1],
      h: i[2],
      f: i[3],
      parent: Number.isNaN(i[4]) ? null : [i[4], i[5]],
      openedAt: orNull(i[6]),
      closedAt: orNull(i[7]),
    };
  }

  /** Counters at `step` (default the current one). */
  counters(step = this.step): Counters {
    const [s, events, expanded, open, f, lines] = this.r.countersAt(step);
    return { step: s, events, expanded, open, f, lines };
  }

  /** The current step explained for the planner `options` choose, with
   *  the open list's first `top` entries (grid/explain.ts reads it). */
  explain(options: Record<string, unknown>, top: number): unknown {
    return this.r.explain(options, top);
  }

  /** Releases the wasm side. */
  free(): void {
    this.r.free();
  }
}
