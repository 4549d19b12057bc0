// "Drive along the path": a robot follows the current path one cell per
// tick; each tick moves the start to the path's next cell and replans.
// With D* Lite the kept search is repaired (a wall painted ahead re-expands
// only what it affects, and the status compares that with a fresh A*);
// every other planner searches afresh from the new start.

import type { Cell } from '../shell/cells';

export interface DriveHost {
  /** The current path's cells (start first), or null when there is none. */
  path(): Cell[] | null;
  /** Moves the start to `cell` and replans at once. */
  moveStart(cell: Cell): void;
}

export class Driver {
  private timer = 0;

  constructor(
    private readonly button: HTMLButtonElement,
    private readonly host: DriveHost,
    private readonly periodMs = 150,
  ) {
    button.addEventListener('click', () => this.toggle());
  }

  get running(): boolean {
    return this.timer !== 0;
  }

  toggle(): void {
    if (this.running) this.stop();
    else this.start();
  }

  start(): void {
    if (this.running) return;
    // The button's data-period (ms per cell), when set, overrides the default
    // (the e2e tests drive fast).
    const period = Number(this.button.dataset.period) || this.periodMs;
    this.timer = window.setInterval(() => this.tick(), period);
    this.show();
  }

  /** Stops (the goal is reached, the path is gone, or the user asked). */
  stop(): void {
    window.clearInterval(this.timer);
    this.timer = 0;
    this.show();
  }

  private tick(): void {
    const p = this.host.path();
    if (!p || p.length < 2) {
      this.stop();
      return;
    }
    this.host.moveStart(p[1]);
  }

  private show(): void {
    this.button.textContent = this.running ? '■ Stop driving' : '▶ Drive along the path';
    this.button.setAttribute('aria-pressed', String(this.running));
    document.body.dataset.driving = String(this.running);
  }
}
