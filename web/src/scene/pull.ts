// Copying what a SimHandle draws into a scene: one `draw` call per frame
// for the robot page, its timeline's scratch handle and the compare page's
// lanes.

import type { SimHandle } from '../../pkg/planlab_wasm.js';
import { DrawList, EMPTY, LIDAR, Layer, mask } from './draw';
import type { Scene } from './view';

/** What every live frame draws (the fan when shown, the trail since the
 *  last pull and the fog when it grew come on top). */
const LIVE = mask(Layer.GlobalPath, Layer.KeyPoints, Layer.Movers, Layer.Robot, Layer.Goals) | LIDAR;
const FAN = mask(Layer.Fan, Layer.Chosen);
const TRAIL = mask(Layer.Trail);
const SEEN = mask(Layer.Seen);

/** The live end of `h` into `S`: pose, movers, goals, paths, fan (when
 *  shown), LiDAR, the new trail rows and (`fog`) the seen cells when their
 *  count changed. */
export function pullLive(h: SimHandle, S: Scene, fog = false): void {
  const layers = LIVE | TRAIL | (S.show.fan ? FAN : 0);
  const d = new DrawList(h.draw(layers, S.trailLen));
  // A hidden fan is an empty one (nothing recorded to draw).
  S.frame.put(d, layers | FAN);
  S.state = h.state();
  appendTrail(d, S);
  if (!fog || !S.frame.hasLidar()) {
    S.frame.put(EMPTY, SEEN);
    S.seenCount = -1;
    return;
  }
  const count = h.seenCount;
  if (count !== S.seenCount) {
    S.frame.put(new DrawList(h.draw(SEEN, 0)), SEEN);
    S.seenCount = count;
  }
}

/** Takes what re-simulated step `h` drew (fan, LiDAR and fog, paths,
 *  goals) over a frame drawn from the trace. */
export function pullReplayed(h: SimHandle, S: Scene): void {
  const layers = mask(Layer.GlobalPath, Layer.KeyPoints, Layer.Goals) | LIDAR | SEEN | (S.show.fan ? FAN : 0);
  const d = new DrawList(h.draw(layers, 0));
  S.frame.put(d, (layers | FAN) & ~SEEN);
  if (d.count(Layer.Seen) > 0 && S.frame.hasLidar()) {
    S.frame.put(d, SEEN);
    S.seenCount = d.value(d.first(Layer.Seen));
  }
}

/** The trail grows: append the Trail layer's rows (those since the last pull). */
function appendTrail(d: DrawList, S: Scene): void {
  const i = d.first(Layer.Trail);
  if (i >= d.end(Layer.Trail)) return;
  const rows = d.numbers(i);
  const m = rows.length / 2;
  if (S.trailLen + m > S.trail.length / 2) {
    const t = new Float64Array(Math.max(S.trail.length * 2, (S.trailLen + m) * 2, 1024));
    t.set(S.trail.subarray(0, S.trailLen * 2));
    S.trail = t;
  }
  S.trail.set(rows, S.trailLen * 2);
  S.trailLen += m;
}
