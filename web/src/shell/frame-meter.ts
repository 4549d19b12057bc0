// Frame statistics for the e2e tests and the curious: per-frame samples
// (rAF interval, simulation and paint time, whole frame work, ms) summed
// up as median, 95th percentile and maximum.

/** The q-quantile of `xs` (nearest rank); NaN when empty. */
export function quantile(xs: number[], q: number): number {
  if (!xs.length) return Number.NaN;
  const s = [...xs].sort((a, b) => a - b);
  return s[Math.min(s.length - 1, Math.floor(q * (s.length - 1) + 0.5))];
}

/** Median, 95th percentile and maximum. */
export function summary(xs: number[]): { median: number; p95: number; max: number } {
  return { median: quantile(xs, 0.5), p95: quantile(xs, 0.95), max: Math.max(...xs) };
}

/** Samples kept at most (a long run does not grow without bound). */
const MAX_SAMPLES = 100_000;

export class FrameMeter {
  readonly intervals: number[] = [];
  readonly work: number[] = [];
  readonly sim: number[] = [];
  readonly paint: number[] = [];

  reset(): void {
    for (const xs of [this.intervals, this.work, this.sim, this.paint]) xs.length = 0;
  }

  /** One played frame; `paint` null when it painted nothing. */
  push(interval: number, sim: number, paint: number | null, work: number): void {
    if (this.intervals.length >= MAX_SAMPLES) return;
    this.intervals.push(interval);
    this.sim.push(sim);
    if (paint !== null) this.paint.push(paint);
    this.work.push(work);
  }

  stats() {
    return {
      frames: this.intervals.length,
      interval: summary(this.intervals.slice(1)),
      work: summary(this.work),
      sim: summary(this.sim),
      paint: summary(this.paint),
    };
  }
}
