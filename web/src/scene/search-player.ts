// A recorded grid search played back: the events of `planRecorded` (open,
// close, line checks) applied one by one to per-cell states, so the page can
// play, pause, step forward and back and scrub. Applying or undoing an event
// touches one cell, and the touched cells are collected for the painter, so
// a frame costs the events it plays, not the map size. The counters
// (expanded, open-set size, f of the last expanded cell) are prefix arrays
// built once, read at any step in O(1).

/** Event kinds as the wasm `RecordedPlan.kinds()` gives them. */
export const EV = { open: 0, close: 1, lineClear: 2, lineBlocked: 3 } as const;

/** Cell states as painted. */
export const ST = { none: 0, open: 1, closed: 2 } as const;

/** "No cell" in `others`. */
const NO_CELL = 0xffffffff;

export interface SearchEvents {
  kinds: Uint8Array;
  /** col,row per event: the opened/closed cell, or a line's start. */
  cells: Uint32Array;
  /** col,row per event: the parent of an open, a line's end. */
  others: Uint32Array;
  g: Float64Array;
  h: Float64Array;
}

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

export class SearchPlayback {
  readonly n: number;
  readonly w: number;
  readonly h: number;
  readonly ev: SearchEvents;
  /** Events applied: 0 (nothing) … n (the whole search). */
  step = 0;
  readonly state: Uint8Array;
  /** Per cell: index of its latest applied open event, -1 none. */
  private lastOpen: Int32Array;
  private firstOpen: Int32Array;
  private closedAt: Int32Array;
  /** Per event: what it overwrote (restored by stepping back). */
  private prevIndex: Int32Array;
  private prevState: Uint8Array;
  /** Prefix counters, index = step. */
  readonly expandedAt: Int32Array;
  readonly openAt: Int32Array;
  readonly fAt: Float64Array;
  readonly linesAt: Int32Array;
  /** Cells changed since the painter last took them (may repeat). */
  private dirty: number[] = [];
  /** Every cell is dirty (a reset). */
  private allDirty = true;
  /** Heuristic weight: f = g + weight·h. */
  private weight: number;

  constructor(w: number, h: number, ev: SearchEvents, weight = 1) {
    this.weight = weight;
    this.w = w;
    this.h = h;
    this.ev = ev;
    this.n = ev.kinds.length;
    const cells = w * h;
    this.state = new Uint8Array(cells);
    this.lastOpen = new Int32Array(cells).fill(-1);
    this.firstOpen = new Int32Array(cells).fill(-1);
    this.closedAt = new Int32Array(cells).fill(-1);
    this.prevIndex = new Int32Array(this.n);
    this.prevState = new Uint8Array(this.n);
    this.expandedAt = new Int32Array(this.n + 1);
    this.openAt = new Int32Array(this.n + 1);
    this.fAt = new Float64Array(this.n + 1).fill(Number.NaN);
    this.linesAt = new Int32Array(this.n + 1);
    // Counters by a dry run over a scratch state.
    const st = new Uint8Array(cells);
    const fOf = new Float64Array(cells).fill(Number.NaN);
    let [expanded, open, lines, f] = [0, 0, 0, Number.NaN];
    for (let i = 0; i < this.n; i++) {
      const k = this.index(i);
      const kind = ev.kinds[i];
      if (kind === EV.open) {
        if (st[k] !== ST.open) open++;
        st[k] = ST.open;
        fOf[k] = ev.g[i] + weight * ev.h[i];
      } else if (kind === EV.close) {
        if (st[k] === ST.open) open--;
        st[k] = ST.closed;
        expanded++;
        f = fOf[k];
      } else {
        lines++;
      }
      this.expandedAt[i + 1] = expanded;
      this.openAt[i + 1] = open;
      this.fAt[i + 1] = f;
      this.linesAt[i + 1] = lines;
    }
  }

  /** Map index of event i's cell (off-map cells clamp; the core never sends them). */
  private index(i: number): number {
    const c = Math.min(this.ev.cells[2 * i], this.w - 1);
    const r = Math.min(this.ev.cells[2 * i + 1], this.h - 1);
    return r * this.w + c;
  }

  private apply(i: number): void {
    const kind = this.ev.kinds[i];
    if (kind !== EV.open && kind !== EV.close) return;
    const k = this.index(i);
    this.prevState[i] = this.state[k];
    if (kind === EV.open) {
      this.prevIndex[i] = this.lastOpen[k];
      this.lastOpen[k] = i;
      if (this.firstOpen[k] < 0) this.firstOpen[k] = i;
      this.state[k] = ST.open;
    } else {
      this.prevIndex[i] = this.closedAt[k];
      this.closedAt[k] = i;
      this.state[k] = ST.closed;
    }
    this.dirty.push(k);
  }

  private undo(i: number): void {
    const kind = this.ev.kinds[i];
    if (kind !== EV.open && kind !== EV.close) return;
    const k = this.index(i);
    this.state[k] = this.prevState[i];
    if (kind === EV.open) {
      this.lastOpen[k] = this.prevIndex[i];
      if (this.firstOpen[k] === i) this.firstOpen[k] = -1;
    } else {
      this.closedAt[k] = this.prevIndex[i];
    }
    this.dirty.push(k);
  }

  /** Moves to `step` (clamped to 0…n), forward or back. */
  seek(step: number): void {
    const to = Math.max(0, Math.min(this.n, Math.floor(step)));
    if (Math.abs(to - this.step) > to) {
      // Replaying from the start is cheaper than undoing most of the way.
      this.reset();
    }
    while (this.step < to) this.apply(this.step++);
    while (this.step > to) this.undo(--this.step);
  }

  /** Back to step 0, every cell unseen. */
  reset(): void {
    this.state.fill(0);
    this.lastOpen.fill(-1);
    this.firstOpen.fill(-1);
    this.closedAt.fill(-1);
    this.step = 0;
    this.dirty.length = 0;
    this.allDirty = true;
  }

  get done(): boolean {
    return this.step >= this.n;
  }

  /** The changed cells since the last call (null: all of them). */
  takeDirty(): number[] | null {
    if (this.allDirty) {
      this.allDirty = false;
      this.dirty.length = 0;
      return null;
    }
    const d = this.dirty;
    this.dirty = [];
    return d;
  }

  /** The cell of the last applied event (the "current" cell), or null. */
  current(): [number, number] | null {
    if (this.step === 0) return null;
    const i = this.step - 1;
    return [this.ev.cells[2 * i], this.ev.cells[2 * i + 1]];
  }

  /** The last applied open/close event's cell: the one being expanded. */
  expanding(): [number, number] | null {
    for (let i = this.step - 1; i >= 0 && i >= this.step - 64; i--) {
      if (this.ev.kinds[i] === EV.close) return [this.ev.cells[2 * i], this.ev.cells[2 * i + 1]];
    }
    return null;
  }

  /** Line checks among the last `max` applied events: [c0, r0, c1, r1, clear]. */
  recentLines(max: number): [number, number, number, number, boolean][] {
    const out: [number, number, number, number, boolean][] = [];
    for (let i = Math.max(0, this.step - max); i < this.step; i++) {
      const k = this.ev.kinds[i];
      if (k !== EV.lineClear && k !== EV.lineBlocked) continue;
      out.push([this.ev.cells[2 * i], this.ev.cells[2 * i + 1], this.ev.others[2 * i], this.ev.others[2 * i + 1], k === EV.lineClear]);
    }
    return out;
  }

  /** g, h, f, parent and steps of a cell at the current step. */
  info(c: number, r: number): CellInfo | null {
    if (c < 0 || r < 0 || c >= this.w || r >= this.h) return null;
    const k = r * this.w + c;
    const s = this.state[k];
    const o = this.lastOpen[k];
    const g = o >= 0 ? this.ev.g[o] : Number.NaN;
    const h = o >= 0 ? this.ev.h[o] : Number.NaN;
    const pc = o >= 0 ? this.ev.others[2 * o] : NO_CELL;
    return {
      state: s === ST.open ? 'open' : s === ST.closed ? 'closed' : 'unseen',
      g,
      h,
      f: g + this.weight * h,
      parent: pc === NO_CELL ? null : [pc, this.ev.others[2 * o + 1]],
      openedAt: this.firstOpen[k] >= 0 ? this.firstOpen[k] + 1 : null,
      closedAt: this.closedAt[k] >= 0 ? this.closedAt[k] + 1 : null,
    };
  }

  /** Counters at the current step. */
  counters(): { step: number; events: number; expanded: number; open: number; f: number; lines: number } {
    const s = this.step;
    return { step: s, events: this.n, expanded: this.expandedAt[s], open: this.openAt[s], f: this.fAt[s], lines: this.linesAt[s] };
  }
}
