// Undo/redo for the robot page's edits: a snapshot history with a cap.
// A snapshot is the whole editable setup (start, goal, movers, map frame,
// sim settings as the SimHandle's editState JSON, plus the map's cells),
// taken before each edit; undo swaps the current setup for the last one.
// Whole snapshots (not inverse commands) make every edit undoable the same
// way, generators and map-size changes included; 100 snapshots of a
// 200 × 200 map are 4 MB.

import type { ShownLabel } from '../shell/preset-select';

export interface Snapshot {
  /** SimHandle.editState() JSON. */
  state: string;
  /** Map cells, row-major, one byte each. */
  cells: Uint8Array;
  /** What the edit was, for the button tooltips. */
  label: string;
  /** What the Preset select said then (undo puts the name back). */
  shown?: ShownLabel;
}

export class History<T extends { label: string }> {
  private undos: T[] = [];
  private redos: T[] = [];

  constructor(readonly cap = 100) {}

  /** Records the state before an edit; forgets the redo branch. */
  push(before: T): void {
    this.undos.push(before);
    if (this.undos.length > this.cap) this.undos.shift();
    this.redos = [];
  }

  /** The state to go back to, given the current one (kept for redo). */
  undo(current: T): T | null {
    const s = this.undos.pop();
    if (!s) return null;
    this.redos.push({ ...current, label: s.label });
    return s;
  }

  /** The state to go forward to, given the current one (kept for undo). */
  redo(current: T): T | null {
    const s = this.redos.pop();
    if (!s) return null;
    this.undos.push({ ...current, label: s.label });
    return s;
  }

  /** Puts a state taken by undo/redo back when restoring it failed. */
  cancel(kind: 'undo' | 'redo', s: T): void {
    if (kind === 'undo') {
      this.redos.pop();
      this.undos.push(s);
    } else {
      this.undos.pop();
      this.redos.push(s);
    }
  }

  clear(): void {
    this.undos = [];
    this.redos = [];
  }

  get undoDepth(): number {
    return this.undos.length;
  }

  get redoDepth(): number {
    return this.redos.length;
  }

  /** Label of the edit undo would revert. */
  get nextUndo(): string | null {
    return this.undos[this.undos.length - 1]?.label ?? null;
  }

  get nextRedo(): string | null {
    return this.redos[this.redos.length - 1]?.label ?? null;
  }
}
