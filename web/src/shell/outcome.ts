// How the pages name a run's end. The core's outcome `stuck` means "the
// distance to the goal has not dropped by `sim.stuck_distance` within
// `sim.stuck_time`" (docs/algorithms.md §episode): a robot can be stuck by
// that rule while still driving (circling in a pocket), so the words say
// which — the outcome value itself (trace, hashes, CSV) stays `stuck`.

/** Speed below which a stuck robot counts as stopped, m/s. */
export const STOPPED_SPEED = 0.05;

/** The words for outcome `o`; `speed` (m/s, the robot's at the end) tells a
 *  stuck robot that still moves from one that stopped. */
export function describeOutcome(o: string, speed = 0): string {
  switch (o) {
    case 'reached':
      return 'goal reached';
    case 'collision':
      return 'collision';
    case 'timeout':
      return 'time out';
    case 'stuck':
      return Math.abs(speed) >= STOPPED_SPEED
        ? `no progress toward the goal (still moving at ${Math.abs(speed).toFixed(2)} m/s: circling)`
        : 'stopped: no progress toward the goal';
    default:
      return o;
  }
}

/** A short form for lane heads and legends: `stuck · circling` or `stuck ·
 *  stopped` for a stuck run, else the outcome itself. */
export function shortOutcome(o: string, speed = 0): string {
  if (o !== 'stuck') return o;
  return Math.abs(speed) >= STOPPED_SPEED ? 'stuck · circling' : 'stuck · stopped';
}
