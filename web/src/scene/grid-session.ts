// The grid page's plans through one wasm PlanSession per map: the planner
// and its passability grid stay built between plans, edits reach the
// session cell by cell, so a replan while dragging an endpoint or painting
// costs about the search alone. With the search shown, the plan comes with
// its events as typed arrays for the player.
//
// D* Lite keeps its own search (a DStarSession) while the goal and options
// stay: a painted wall or a moved start is then repaired, not replanned,
// and the repair's expansions are reported beside a fresh A*'s on the same
// edited map (through the PlanSession, which has the same edits).

import { DStarSession, PlanSession, type MapHandle, type PlanResult, type RecordedPlan } from '../../pkg-grid/planlab_wasm.js';
import { SearchPlayback } from './search-player';
import type { Cell } from '../shell/cells';

export interface Planned {
  result: PlanResult;
  playback: SearchPlayback | null;
  /** Time of the wasm call, ms. */
  ms: number;
  /** The recording stopped at the wasm side's event limit. */
  truncated?: boolean;
  /** D* Lite only: this plan repaired the kept search. */
  repair?: { expanded: number; freshAStar: number };
}

/** The kept D* Lite search and what it was built for. */
interface DStar {
  s: DStarSession;
  start: Cell;
  goal: Cell;
  key: string;
}

const same = (a: Cell, b: Cell) => a[0] === b[0] && a[1] === b[1];

export class GridSession {
  private s: PlanSession | null = null;
  private d: DStar | null = null;
  /** The map the session plans on (the page's handle). */
  private map: MapHandle | null = null;

  private dropDStar(): void {
    this.d?.s.free();
    this.d = null;
  }

  /** A new map: a new session over a copy of it (the options arrive with
   *  each plan, so a bad one is reported by the plan). */
  attach(map: MapHandle): void {
    this.s?.free();
    this.dropDStar();
    this.s = new PlanSession(map, undefined);
    this.map = map;
  }

  /** The map was replaced wholesale (reset edits). */
  reload(map: MapHandle): void {
    this.s?.setMap(map);
    this.map = map;
    this.dropDStar();
  }

  /** The same stroke as the page's MapHandle got. */
  paint(from: Cell, to: Cell, kind: number): void {
    this.s?.paintSegment(from[0], from[1], to[0], to[1], kind);
    this.d?.s.paintSegment(from[0], from[1], to[0], to[1], kind);
  }

  /** The same cost-brush stroke as the page's MapHandle got. */
  paintWeight(from: Cell, to: Cell, weight: number): void {
    this.s?.paintWeight(from[0], from[1], to[0], to[1], weight);
    this.d?.s.paintWeight(from[0], from[1], to[0], to[1], weight);
  }

  /** Times the grid was (re)built (edits without inflation keep it). */
  get rebuilds(): number {
    return this.s?.rebuilds ?? 0;
  }

  /** Plans with `opts`; with `record`, also the search events. Throws the
   *  core's error. */
  plan(start: Cell, goal: Cell, opts: Record<string, unknown>, record: boolean, map?: MapHandle): Planned {
    const s = this.s;
    if (!s) throw new Error('no map loaded');
    if (opts.algorithm === 'dstar-lite' && map) return this.planDStar(s, map, start, goal, opts, record);
    this.dropDStar();
    s.setOptions(opts);
    const t0 = performance.now();
    if (!record) {
      const result = s.plan(start[0], start[1], goal[0], goal[1], false);
      return { result, playback: null, ms: performance.now() - t0 };
    }
    const rec = s.planRecorded(start[0], start[1], goal[0], goal[1]);
    return this.unpack(rec, performance.now() - t0, opts, record);
  }

  /** The search `plan` would run with `opts`, as a Posthoc trace (JSON
   *  text); D* Lite's is a fresh search's. Throws the core's error. */
  posthoc(start: Cell, goal: Cell, opts: Record<string, unknown>): string {
    const s = this.s;
    if (!s) throw new Error('no map loaded');
    s.setOptions(opts);
    return s.posthocTrace(start[0], start[1], goal[0], goal[1]);
  }

  /** D* Lite: a new search for a new goal or options, else a repair of
   *  the kept one (after edits or a moved start). */
  private planDStar(s: PlanSession, map: MapHandle, start: Cell, goal: Cell, opts: Record<string, unknown>, record: boolean): Planned {
    const key = JSON.stringify(opts);
    const d = this.d;
    const t0 = performance.now();
    let rec: RecordedPlan;
    let repaired = false;
    const fresh = (): RecordedPlan => {
      this.dropDStar();
      const n = new DStarSession(map, opts, start[0], start[1], goal[0], goal[1]);
      this.d = { s: n, start, goal, key };
      return n.plan();
    };
    try {
      if (d && d.key === key && same(d.goal, goal)) {
        // The repair's own answer, errors included (no fresh search behind
        // it: a wrong "unreachable" would show, not hide).
        if (!same(d.start, start)) d.s.moveStart(start[0], start[1]);
        d.start = start;
        rec = d.s.plan();
        repaired = true;
      } else {
        rec = fresh();
      }
    } catch (e) {
      this.dropDStar();
      throw e;
    }
    const out = this.unpack(rec, performance.now() - t0, opts, record);
    if (repaired) {
      // A fresh A* on the same edited map, for the comparison.
      s.setOptions({ ...opts, algorithm: 'astar' });
      const astar = s.plan(start[0], start[1], goal[0], goal[1], false);
      out.repair = { expanded: out.result.expandedCount, freshAStar: astar.expandedCount };
      astar.free();
    }
    return out;
  }

  private unpack(rec: RecordedPlan, ms: number, opts: Record<string, unknown>, record: boolean): Planned {
    if (!record) {
      const result = rec.plan;
      rec.free();
      return { result, playback: null, ms };
    }
    try {
      const weight = opts.algorithm === 'astar' && typeof opts.weight === 'number' ? opts.weight : 1;
      if (!this.map) throw new Error('no map loaded');
      const playback = new SearchPlayback(rec.replay(this.map, weight));
      return { result: rec.plan, playback, ms, truncated: rec.truncated };
    } finally {
      rec.free();
    }
  }
}
