// The grid page's plans through one wasm PlanSession per map: the planner
// and its passability grid stay built between plans, edits reach the
// session cell by cell, so a replan while dragging an endpoint or painting
// costs about the search alone. With the search shown, the plan comes with
// its events as typed arrays for the player.

import { PlanSession, type MapHandle, type PlanResult } from '../../pkg/planlab_wasm.js';
import { SearchPlayback } from '../scene/search-player';
import type { Cell } from './render';

export interface Planned {
  result: PlanResult;
  playback: SearchPlayback | null;
  /** Time of the wasm call, ms. */
  ms: number;
}

export class GridSession {
  private s: PlanSession | null = null;
  private w = 0;
  private h = 0;

  /** A new map: a new session over a copy of it (the options arrive with
   *  each plan, so a bad one is reported by the plan). */
  attach(map: MapHandle): void {
    this.s?.free();
    this.s = new PlanSession(map, undefined);
    this.w = map.width;
    this.h = map.height;
  }

  /** The map was replaced wholesale (reset edits). */
  reload(map: MapHandle): void {
    this.s?.setMap(map);
  }

  /** The same stroke as the page's MapHandle got. */
  paint(from: Cell, to: Cell, kind: number): void {
    this.s?.paintSegment(from[0], from[1], to[0], to[1], kind);
  }

  /** Times the grid was (re)built (edits without inflation keep it). */
  get rebuilds(): number {
    return this.s?.rebuilds ?? 0;
  }

  /** Plans with `opts`; with `record`, also the search events. Throws the
   *  core's error. */
  plan(start: Cell, goal: Cell, opts: Record<string, unknown>, record: boolean): Planned {
    const s = this.s;
    if (!s) throw new Error('no map loaded');
    s.setOptions(opts);
    const t0 = performance.now();
    if (!record) {
      const result = s.plan(start[0], start[1], goal[0], goal[1], false);
      return { result, playback: null, ms: performance.now() - t0 };
    }
    const rec = s.planRecorded(start[0], start[1], goal[0], goal[1]);
    const ms = performance.now() - t0;
    try {
      const weight = opts.algorithm === 'astar' && typeof opts.weight === 'number' ? opts.weight : 1;
      const playback = new SearchPlayback(this.w, this.h, { kinds: rec.kinds(), cells: rec.cells(), others: rec.others(), g: rec.g(), h: rec.h() }, weight);
      return { result: rec.plan, playback, ms };
    } finally {
      rec.free();
    }
  }
}
