// The fixed-step clock of the simulation pages: from the animation frame,
// simulated time advances by the wall time × speed, as whole control steps
// of `dt`; a frame runs at most `maxSteps` of them and stops early when the
// next would overrun `budgetMs` (a slow machine or heavy planner runs the
// sim slower than the speed instead of dropping frames). Steps that did not
// fit are dropped, not owed.

export interface ClockHost {
  /** Runs up to `n` steps within `budgetMs` (see `SimClock.run`) and
   *  refreshes what follows from them; returns how many ran. */
  advance(n: number, budgetMs: number): number;
  /** After each played frame: paint when `ran` > 0, slow refreshes, meters.
   *  `interval` is the time since the last frame, `t0` when this one's
   *  work began (ms). */
  afterFrame(ran: number, now: number, interval: number, t0: number): void;
  /** Something threw in a frame: play has stopped. */
  onError(e: unknown): void;
}

export class SimClock {
  /** Simulated seconds per wall second. */
  speed = 1;
  /** Control period, s. */
  dt = 0.1;
  private on = false;
  private accum = 0;
  private last = 0;
  /** Running mean of one step's cost, ms (for the budget). */
  private stepMs = 1;

  constructor(
    private readonly host: ClockHost,
    private readonly maxSteps: number,
    private readonly budgetMs: number,
  ) {}

  get playing(): boolean {
    return this.on;
  }

  /** Starts or stops play (a start begins a fresh accumulation). */
  play(on: boolean): void {
    const was = this.on;
    this.on = on;
    if (on && !was) {
      this.last = performance.now();
      this.accum = 0;
      requestAnimationFrame(this.tick);
    }
  }

  /** Runs `step` (one control step) up to `n` times while `running()`,
   *  the first always, the others while the next would not overrun
   *  `budgetMs`; returns how many ran. */
  run(n: number, running: () => boolean, step: () => void, budgetMs = Infinity): number {
    const t0 = performance.now();
    let done = 0;
    while (done < n && running()) {
      if (done > 0 && performance.now() - t0 + this.stepMs > budgetMs) break;
      const t = performance.now();
      step();
      this.stepMs = 0.8 * this.stepMs + 0.2 * (performance.now() - t);
      done += 1;
    }
    return done;
  }

  private readonly tick = (now: number): void => {
    if (!this.on) return;
    requestAnimationFrame(this.tick);
    const interval = now - this.last;
    this.last = now;
    const t0 = performance.now();
    try {
      this.accum += (Math.min(interval, 100) / 1000) * this.speed;
      const due = Math.floor(this.accum / this.dt + 1e-9);
      const n = Math.min(due, this.maxSteps);
      const ran = n > 0 ? this.host.advance(n, this.budgetMs) : 0;
      this.accum = ran < due ? 0 : this.accum - ran * this.dt;
      this.host.afterFrame(ran, now, interval, t0);
    } catch (e) {
      this.on = false;
      this.host.onError(e);
    }
  };
}
