// The robot page's timeline: every run is recorded (the SimHandle keeps its
// trace plus the setup and the live edits, see core `sim::Recording`), and
// this bar under the canvas scrubs through it.
//
// - Slider drag, ←/→ (Shift: 10 steps), Home/End, the step buttons and a
//   press or drag in any plot move to a frame. A past frame is drawn from
//   the trace row (pose, movers, classes, the goal steered to, the trail up
//   to then) at once, and a scratch SimHandle re-simulated to that step
//   (the core is deterministic: same setup, seed and edits, same trace)
//   adds that step's DWA fan, LiDAR, fog and global path. Short forward
//   moves take the scratch on at once; other moves rebuild it from the
//   start (one step per frame, ≈ 0.3 s for 120 DWA-demo steps on a busy
//   machine), so that waits until the frame rests.
// - Replay re-runs the recorded run from its setup and seed (edits applied
//   at the steps they were made), plays it back on the canvas and checks
//   at the end that the trace hash is identical to the original's.
// - Play or Step from a past frame branches: the run is cut at that frame
//   and continues live from there (edits up to then kept); the cut-off
//   future is dropped and the bar says where the branch started. Edits
//   (goal, movers, planner) always go to the live end of the run: making
//   one while a past frame is shown returns the view to the live end.

import { hexHash } from '../shell/hash';
import type { SimHandle } from '../../pkg/planlab_wasm.js';
import type { RobotView } from '../scene/view';
import type { SeriesPlots } from './plots';
import './timeline.css';
import { pullReplayed } from '../scene/pull';
import { DrawList, EMPTY, LIDAR, Layer, mask } from '../scene/draw';

/** What the timeline needs from the page (main.ts). */
export interface TimelineHost {
  sim(): SimHandle | null;
  view: RobotView;
  plots: SeriesPlots;
  /** Stops live play. */
  pause(): void;
  /** Installs `next` as the live run (paused). */
  branch(next: SimHandle): void;
  /** Repaints the live end (main's pull). */
  refreshLive(): void;
  /** Playback speed factor. */
  speed(): number;
}

/** What a trace row draws: the robot, movers and goals of that time. */
const ROW = mask(Layer.Robot, Layer.Movers, Layer.Goals);

/** Rebuilding the scratch while dragging waits this long after the last
 *  slider move, ms. */
const SETTLE_MS = 90;
/** Forward moves of up to this many steps re-simulate at once. */
const CHEAP_STEPS = 20;

function button(text: string, title: string, id: string): HTMLButtonElement {
  const b = document.createElement('button');
  b.type = 'button';
  b.textContent = text;
  b.title = title;
  b.id = id;
  return b;
}

export class Timeline {
  readonly root: HTMLElement;
  private slider: HTMLInputElement;
  private readout: HTMLOutputElement;
  private note: HTMLElement;
  private replayBtn: HTMLButtonElement;
  private ticks: HTMLElement;
  /** Frame shown; null = the live end. */
  private frame: number | null = null;
  /** A replay of the run at some step, for the fan / LiDAR of past frames. */
  private scratch: SimHandle | null = null;
  private settle = 0;
  private lastSim: SimHandle | null = null;
  private lastRun = -1;
  private edits = 0;
  private branchedAt: number | null = null;
  private playback: { target: number; hash: string; raf: number; last: number; accum: number } | null = null;
  /** Time of the last scratch rebuild / advance, ms (for the tests and
   *  the curious). */
  lastScratchMs = 0;

  constructor(
    mount: HTMLElement,
    private host: TimelineHost,
  ) {
    this.root = mount;
    mount.classList.add('timeline');
    const start = button('|◀', 'Jump to the start (Home)', 'tl-start');
    const back = button('◀', 'One step back (←; Shift+←: 10)', 'tl-back');
    const fwd = button('▶', 'One step on (→; Shift+→: 10)', 'tl-fwd');
    const end = button('▶|', 'Jump to the end, the live run (End)', 'tl-end');
    this.replayBtn = button('⟲ Replay', 'Re-run the recorded run from its setup and seed, play it back and check the trace is identical', 'tl-replay');
    const track = document.createElement('div');
    track.className = 'tl-track';
    this.slider = document.createElement('input');
    this.slider.type = 'range';
    this.slider.id = 'tl-slider';
    this.slider.min = '0';
    this.slider.max = '0';
    this.slider.step = '1';
    this.slider.value = '0';
    this.slider.setAttribute('aria-label', 'Timeline: frame of the run');
    this.ticks = document.createElement('div');
    this.ticks.className = 'tl-ticks';
    track.append(this.ticks, this.slider);
    this.readout = document.createElement('output');
    this.readout.id = 'tl-readout';
    this.note = document.createElement('span');
    this.note.id = 'tl-note';
    this.note.className = 'tl-note';
    mount.replaceChildren(start, back, fwd, end, track, this.replayBtn, this.readout, this.note);

    start.addEventListener('click', () => this.seek(0));
    end.addEventListener('click', () => this.seek(Infinity));
    back.addEventListener('click', (ev) => this.stepBy(ev.shiftKey ? -10 : -1));
    fwd.addEventListener('click', (ev) => this.stepBy(ev.shiftKey ? 10 : 1));
    this.replayBtn.addEventListener('click', () => this.guard(() => this.replay()));
    this.slider.addEventListener('pointerdown', () => {
      this.stopPlayback();
      host.pause();
    });
    this.slider.addEventListener('input', () => this.seek(Number(this.slider.value), true));
    window.addEventListener('keydown', (ev) => this.onKey(ev));
    host.plots.onScrub = (row) => {
      this.stopPlayback();
      this.seek(row, true);
    };
    // For the e2e tests and the curious: what is drawn and plotted.
    (window as unknown as { planlabTimeline: unknown }).planlabTimeline = {
      frame: () => this.current,
      scrubbed: () => this.scrubbed,
      drawnPose: () => Array.from(host.view.scene.state),
      drawnMovers: () => host.view.scene.frame.movers(),
      drawnGoal: () => [...host.view.scene.frame.goal(2), host.view.scene.frame.goalKind()],
      trailLen: () => host.view.scene.trailLen,
      drawnLidar: () => {
        const S = host.view.scene;
        const d = S.frame.of(Layer.LidarRays);
        if (!S.frame.hasLidar() || d.count(Layer.LidarRays) === 0) return null;
        let rays = 0;
        for (let i = d.first(Layer.LidarRays); i < d.end(Layer.LidarRays); i++) rays += (d.stop(i) - d.start(i)) / 4;
        const a = d.start(d.first(Layer.LidarRays));
        return { rays, sensor: [d.data[a], d.data[a + 1]], seen: S.seenCount };
      },
      plotCursors: () => host.plots.cursorRows(),
      plotsShown: () => host.plots.shownKeys,
      plotSummary: () => host.plots.summary(),
      plotRanges: () => host.plots.yRanges(),
      scratchMs: () => this.lastScratchMs,
    };
  }

  private guard(f: () => void): void {
    try {
      f();
    } catch (e) {
      // The page's error banner catches what escapes a handler.
      queueMicrotask(() => {
        throw e;
      });
    }
  }

  /** Whether a past frame is shown. */
  get scrubbed(): boolean {
    return this.frame !== null;
  }

  /** The frame shown (the live end when not scrubbed). */
  get current(): number {
    const sim = this.host.sim();
    return this.frame ?? (sim ? sim.steps : 0);
  }

  private onKey(ev: KeyboardEvent): void {
    const t = ev.target as HTMLElement | null;
    if (t && t !== this.slider && (t.tagName === 'INPUT' || t.tagName === 'SELECT' || t.tagName === 'TEXTAREA')) return;
    if (ev.ctrlKey || ev.metaKey || ev.altKey) return;
    let done = true;
    if (ev.key === 'ArrowLeft') this.stepBy(ev.shiftKey ? -10 : -1);
    else if (ev.key === 'ArrowRight') this.stepBy(ev.shiftKey ? 10 : 1);
    else if (ev.key === 'Home') this.seek(0);
    else if (ev.key === 'End') this.seek(Infinity);
    else done = false;
    if (done) ev.preventDefault();
  }

  /** Moves `d` frames from the one shown. */
  stepBy(d: number): void {
    this.seek(this.current + d);
  }

  /** Shows frame `k` (clamped; the last frame is the live end). `dragging`:
   *  the fan / LiDAR wait until the frame rests. */
  seek(k: number, dragging = false): void {
    this.guard(() => {
      const sim = this.host.sim();
      if (!sim) return;
      if (!dragging) this.stopPlayback();
      this.host.pause();
      const n = sim.steps;
      k = Math.max(0, Math.min(n, Math.round(Number.isFinite(k) ? k : n)));
      if (k >= n) {
        this.frame = null;
        this.dropScratch();
        this.host.refreshLive();
        this.host.view.request();
        return;
      }
      this.frame = k;
      this.showFrame(k);
      clearTimeout(this.settle);
      // Forward a few steps from the scratch is cheap: at once. Anything
      // else re-simulates from the start (a step per frame): the trace
      // view is drawn now, the fan once the frame rests, so dragging or
      // holding ← stays responsive.
      const s = this.scratch;
      const cheap = !dragging && s !== null && s.steps <= k && k - s.steps <= CHEAP_STEPS;
      if (cheap) this.detail();
      else this.settle = window.setTimeout(() => this.guard(() => this.detail()), SETTLE_MS);
    });
  }

  /** The fan's colour changed to critic `k` (undefined: the total): a
   *  past frame's fan is drawn again in it. */
  fanColour(k: number | undefined): void {
    this.scratch?.setFanColour(k);
    if (this.frame !== null) this.showFrame(this.frame);
  }

  private dropScratch(): void {
    clearTimeout(this.settle);
    this.scratch?.free();
    this.scratch = null;
  }

  /** Re-simulates the scratch to the frame shown and draws what that step
   *  drew (fan, LiDAR, fog, global path, final goal). */
  private detail(): void {
    const sim = this.host.sim();
    const k = this.frame;
    if (!sim || k === null) return;
    const t0 = performance.now();
    if (!this.scratch || this.scratch.steps !== k) {
      if (!this.scratch || !sim.advanceReplay(this.scratch, k)) {
        this.scratch?.free();
        this.scratch = sim.replayTo(k);
      }
    }
    this.lastScratchMs = performance.now() - t0;
    this.showFrame(k);
  }

  /** Draws frame `k` from the trace (and from the scratch when it stands
   *  at `k`). */
  private showFrame(k: number): void {
    const sim = this.host.sim();
    if (!sim) return;
    const S = this.host.view.scene;
    // A replay in progress shows its own rows (the re-simulated run).
    const h = this.scratch && this.scratch.steps === k ? this.scratch : null;
    const src = this.playback && h ? h : sim;
    const r = src.traceRow(k);
    if (r.length < 19) return;
    S.state = Float64Array.of(r[1], r[2], r[3], r[4], r[5], r[6]);
    // Robot, movers (velocities from the neighbouring rows) and the goal
    // steered to, as the core draws that row.
    S.frame.put(new DrawList(src.drawRow(k, ROW)), ROW);
    S.trailLen = Math.min(k + 1, S.trail.length / 2);
    if (h) pullReplayed(h, S);
    else S.frame.put(EMPTY, mask(Layer.Fan, Layer.Chosen) | LIDAR);
    this.root.dataset.detail = h ? 'replayed' : 'trace';
    this.updateBar(sim, k, r, src.traceMode(k));
    this.host.plots.setFrame(k);
    this.host.view.request();
  }

  private updateBar(sim: SimHandle, k: number, r: Float64Array, mode: string): void {
    const n = sim.steps;
    this.slider.max = String(n);
    this.slider.value = String(k);
    const live = this.frame === null;
    this.root.dataset.frame = String(k);
    this.root.dataset.frames = String(n);
    this.root.dataset.live = String(live);
    this.root.dataset.t = String(r[0]);
    this.root.dataset.x = String(r[1]);
    this.root.dataset.y = String(r[2]);
    this.root.dataset.theta = String(r[3]);
    this.readout.textContent =
      `${live ? 'live · ' : ''}frame ${k}/${n} · t = ${r[0].toFixed(1)} s · ` +
      `(${r[1].toFixed(2)}, ${r[2].toFixed(2)}) m, θ ${r[3].toFixed(2)} · v ${r[4].toFixed(2)} m/s, ω ${r[6].toFixed(2)} rad/s` +
      (mode ? ` · ${mode}` : '');
    this.readout.title = this.readout.textContent;
  }

  /** Called by the page after every live pull: follows the live end,
   *  notices a new run (load, reset, branch) and edits. */
  afterPull(): void {
    const sim = this.host.sim();
    if (!sim) return;
    // A new run: another handle (load, reset, branch) or the same one
    // restarted in place by an editing tool.
    if (sim !== this.lastSim || sim.runId !== this.lastRun) {
      this.lastSim = sim;
      this.lastRun = sim.runId;
      this.stopPlayback();
      this.dropScratch();
      this.frame = null;
      this.edits = -1;
      this.note.textContent = this.branchedAt !== null ? `branched at frame ${this.branchedAt}` : '';
      this.root.dataset.branch = this.branchedAt !== null ? String(this.branchedAt) : '';
      this.branchedAt = null;
      delete this.root.dataset.replayMatch;
      delete this.root.dataset.replayHash;
      this.replayBtn.classList.remove('ok', 'bad');
    }
    const edits = sim.editSteps();
    if (edits.length !== this.edits) {
      this.edits = edits.length;
      this.drawTicks(edits, sim.steps);
      // An edit goes to the live end: show it.
      if (this.frame !== null && !this.playback) {
        this.frame = null;
        this.dropScratch();
      }
    }
    if (this.frame !== null) {
      // A pull while a past frame is shown (a display toggle): keep it.
      this.showFrame(this.frame);
      return;
    }
    const n = sim.steps;
    this.updateBar(sim, n, sim.traceRow(n), sim.mode);
    this.host.plots.setFrame(null);
  }

  private drawTicks(edits: Float64Array, n: number): void {
    const marks = Array.from(edits)
      .filter((s) => s > 0)
      .map((s) => {
        const i = document.createElement('i');
        i.style.left = `${(100 * s) / Math.max(1, n)}%`;
        i.title = `edit at frame ${s}`;
        return i;
      });
    this.ticks.replaceChildren(...marks);
  }

  /** Play / Step from a past frame: cut the run there and continue live. */
  branchHere(): void {
    const sim = this.host.sim();
    const k = this.frame;
    if (!sim || k === null) return;
    this.stopPlayback();
    let next: SimHandle;
    if (this.scratch && this.scratch.steps === k) {
      next = this.scratch;
      this.scratch = null;
    } else next = sim.replayTo(k);
    this.branchedAt = k;
    this.host.branch(next);
  }

  /** Re-runs the recorded run and plays it back; checks the trace hash. */
  replay(): void {
    const sim = this.host.sim();
    if (!sim || sim.steps === 0) return;
    this.host.pause();
    this.stopPlayback();
    this.dropScratch();
    delete this.root.dataset.replayMatch;
    this.replayBtn.classList.remove('ok', 'bad');
    this.note.textContent = 'replaying…';
    this.scratch = sim.replayTo(0);
    this.frame = 0;
    this.showFrame(0);
    const pb = { target: sim.steps, hash: sim.traceHash(), raf: 0, last: performance.now(), accum: 0 };
    this.playback = pb;
    this.root.dataset.playback = 'true';
    const tick = (now: number) => {
      if (this.playback !== pb) return;
      this.guard(() => {
        const s = this.host.sim();
        if (!s || !this.scratch) return this.stopPlayback();
        pb.accum += (Math.min(100, now - pb.last) / 1000) * this.host.speed();
        pb.last = now;
        const due = Math.floor(pb.accum / s.dt);
        if (due > 0) {
          pb.accum -= due * s.dt;
          const k = Math.min(pb.target, (this.frame ?? 0) + Math.min(due, 16));
          if (!s.advanceReplay(this.scratch, k)) throw new Error('replay lost its course');
          this.frame = k;
          this.showFrame(k);
          if (k >= pb.target || this.scratch.outcome !== 'running') return this.finishReplay(pb.hash);
        }
        pb.raf = requestAnimationFrame(tick);
      });
    };
    pb.raf = requestAnimationFrame(tick);
  }

  private finishReplay(hash: string): void {
    const got = this.scratch?.traceHash() ?? '';
    const ok = got === hash;
    this.root.dataset.replayHash = got;
    this.root.dataset.replayMatch = String(ok);
    this.replayBtn.classList.toggle('ok', ok);
    this.replayBtn.classList.toggle('bad', !ok);
    this.note.textContent = ok ? `✓ replay identical (trace hash ${hexHash(got)})` : `✗ replay differs: ${hexHash(got)} ≠ ${hexHash(hash)}`;
    this.stopPlayback();
    // The replay ends at the run's end: back to the live view of it.
    this.seek(Infinity);
  }

  private stopPlayback(): void {
    if (!this.playback) return;
    cancelAnimationFrame(this.playback.raf);
    this.playback = null;
    delete this.root.dataset.playback;
  }
}
