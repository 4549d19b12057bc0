// Copying what a SimHandle reports into a RobotView scene: one place for the
// robot page, its timeline's scratch handle and the compare page's lanes.

import type { SimHandle } from '../../pkg/planlab_wasm.js';
import type { Fan, LidarScene, Scene } from './view';

export function pairOf(a: Float64Array): [number, number] {
  return [a[0] ?? 0, a[1] ?? 0];
}

/** The rollouts of the handle's last step. */
export function fanOf(h: SimHandle): Fan {
  return { points: h.fanPoints(), offsets: h.fanOffsets(), scores: h.fanScores(), admissible: h.fanAdmissible(), chosen: h.chosen };
}

/** The last scan and what the navigator made of it; null without LiDAR. */
export function lidarOf(h: SimHandle): LidarScene | null {
  if (!h.hasLidar) return null;
  return {
    rays: h.lidarRays(),
    returns: h.lidarReturns(),
    edges: h.lidarEdges(false),
    opsRaw: h.lidarOps(false),
    opsRawOffsets: h.lidarOpOffsets(false),
    ops: h.lidarOps(true),
    opsOffsets: h.lidarOpOffsets(true),
    blocking: h.lidarBlocking,
    candidates: h.lidarCandidates(),
    target: h.lidarTarget(),
  };
}

/** Pose, movers, goals, obstacle classes, fan (when shown), path and key points. */
export function pullState(h: SimHandle, S: Scene): void {
  S.state = h.state();
  S.movers = h.movers();
  S.goal = pairOf(h.goal());
  S.currentGoal = pairOf(h.currentGoal());
  S.goalKind = h.goalKind;
  const cls = h.classes();
  S.classes.clear();
  for (let i = 0; i + 1 < cls.length; i += 2) S.classes.set(cls[i], cls[i + 1]);
  if (S.show.fan) S.fan = fanOf(h);
  S.globalPath = h.globalPath();
  S.keypoints = h.keypoints();
}

/** The trail grows: fetch only the rows since the last pull. */
export function appendTrail(h: SimHandle, S: Scene): void {
  const rows = h.trail(S.trailLen);
  const m = rows.length / 2;
  if (m === 0) return;
  if (S.trailLen + m > S.trail.length / 2) {
    const t = new Float64Array(Math.max(S.trail.length * 2, (S.trailLen + m) * 2, 1024));
    t.set(S.trail.subarray(0, S.trailLen * 2));
    S.trail = t;
  }
  S.trail.set(rows, S.trailLen * 2);
  S.trailLen += m;
}
