// The robot page's read-outs: the metric cards (the `planlab run` metrics
// of the episode so far), the status line, the mover list, and the
// scenario card's map size, robot description and control period. All
// numbers come from the SimHandle and the scene the core drew.

import type { SimHandle } from '../../pkg/planlab_wasm.js';
import { Layer } from '../scene/draw';
import { CLASS_NAMES, COLORS, type MapInfo, type Scene } from '../scene/view';
import { el } from '../shell/dom';
import { describeOutcome } from '../shell/outcome';
import type { Metrics } from '../shell/metrics';

interface MoverJson {
  id: number;
  radius: number;
  motion: { model: string };
}

export { describeOutcome } from '../shell/outcome';

/** The status line's words for an ended run: a collision as the core words
 *  it (`collision`: "hit by mover 3 while at rest", …), else the outcome. */
export function endText(outcome: string, speed: number, collision: string | undefined): string {
  return outcome === 'collision' && collision ? collision : describeOutcome(outcome, speed);
}

/** A one-line description of the robot JSON and whether it drives
 *  omnidirectionally. */
export function describeRobot(json: string): [string, boolean] {
  const r = JSON.parse(json) as {
    drive?: string;
    footprint?: { shape?: string; radius?: number; length?: number; width?: number };
    limits?: { v_max?: number };
  };
  const fp = r.footprint ?? {};
  const size = fp.shape === 'rectangle' ? `${fp.length ?? 0.4}×${fp.width ?? 0.3} m` : `⌀ ${(2 * (fp.radius ?? 0.2)).toFixed(2)} m`;
  const vmax = r.limits?.v_max;
  return [`${r.drive ?? '?'} · ${size}${vmax !== undefined ? ` · ≤ ${vmax} m/s` : ''}`, r.drive === 'omnidirectional'];
}

function setMetric(e: HTMLElement, text: string, value: number | null): void {
  e.textContent = text;
  if (value === null) delete e.dataset.value;
  else e.dataset.value = String(value);
}

export class StatusPanel {
  private readonly metric = {
    outcome: el('metric-outcome'),
    time: el('metric-time'),
    length: el('metric-length'),
    clearance: el('metric-clearance'),
    turn: el('metric-turn'),
    drops: el('metric-drops'),
    tracking: el('metric-tracking'),
    mode: el('metric-mode'),
  };
  private readonly status = el('status');
  private readonly setup = { mapSize: el('map-size'), robotDesc: el('robot-desc'), simDt: el('sim-dt') };
  private readonly moverList = el<HTMLUListElement>('mover-list');
  /** What the mover list shows, to rebuild it only when that changes (a
   *  rebuild under the pointer would swallow a click on ×). */
  private moverListKey = '';

  /** What the status line adds after the run state (the episode's route
   *  note: a path exists only without inflation). */
  note = '';

  /** `remove(id)`: the × of a mover's row. */
  constructor(private readonly remove: (id: number) => void) {}

  /** The scenario card's read-outs of a new run (map size, robot, control
   *  period); returns whether the robot drives omnidirectionally. */
  showSetup(sim: SimHandle, map: MapInfo | null): boolean {
    if (map) this.setup.mapSize.textContent = `${map.width} × ${map.height} · ${map.resolution} m`;
    const [desc, omni] = describeRobot(sim.robot());
    this.setup.robotDesc.textContent = desc;
    this.setup.robotDesc.title = desc;
    this.setup.simDt.textContent = `${sim.dt} s`;
    return omni;
  }

  clear(): void {
    for (const e of Object.values(this.metric)) setMetric(e, '—', null);
    delete this.metric.outcome.dataset.outcome;
  }

  /** Metrics, status line and mover list of `sim` as `S` shows it. */
  refresh(sim: SimHandle, S: Scene, outcome: string, playing: boolean): void {
    const M = this.metric;
    const m = JSON.parse(sim.metricsJson()) as Metrics;
    setMetric(M.outcome, m.outcome, null);
    M.outcome.dataset.outcome = m.outcome;
    M.outcome.title = outcome === 'collision' && sim.collision ? sim.collision : '';
    setMetric(M.time, `${m.time_s.toFixed(1)} s`, m.time_s);
    setMetric(M.length, `${m.path_length_m.toFixed(2)} m`, m.path_length_m);
    setMetric(M.clearance, `${m.min_clearance_m.toFixed(2)} / ${m.mean_clearance_m.toFixed(2)}`, m.min_clearance_m);
    M.clearance.dataset.mean = String(m.mean_clearance_m);
    setMetric(M.turn, `${m.total_turn_rad.toFixed(2)} / ${m.max_turn_rad.toFixed(2)}`, m.total_turn_rad);
    M.turn.dataset.max = String(m.max_turn_rad);
    setMetric(M.drops, String(m.speed_drops), m.speed_drops);
    if (m.mean_tracking_error_m === null || m.max_tracking_error_m === null) setMetric(M.tracking, 'n/a', null);
    else {
      setMetric(M.tracking, `${m.mean_tracking_error_m.toFixed(3)} / ${m.max_tracking_error_m.toFixed(3)}`, m.mean_tracking_error_m);
      M.tracking.dataset.max = String(m.max_tracking_error_m);
    }
    const mode = sim.mode;
    setMetric(M.mode, `${mode || '—'} · ${S.frame.goalKind()}`, null);
    M.mode.title = M.mode.textContent ?? '';
    const s = S.state;
    const movers = S.frame.of(Layer.Movers).count(Layer.Movers);
    const rollouts = S.frame.of(Layer.Fan).count(Layer.Fan);
    // The route note first: the line is cut with "…" at its end.
    this.status.textContent =
      (this.note ? `⚠ ${this.note} · ` : '') +
      `t = ${sim.time.toFixed(1)} s · v = ${s[3].toFixed(2)} m/s · ω = ${s[5].toFixed(2)} rad/s · ` +
      `${movers} movers · ${rollouts} rollouts` +
      (outcome === 'running' ? (playing ? ' · playing' : ' · paused') : ` · ${endText(outcome, s[3], sim.collision)}`);
    this.status.title = this.status.textContent;
    this.renderMovers(sim, S);
  }

  private renderMovers(sim: SimHandle, S: Scene): void {
    const json = sim.moversJson();
    const classes = S.frame.classes();
    const key = `${json}|${Array.from(classes).join(';')}`;
    if (key === this.moverListKey) return;
    this.moverListKey = key;
    const movers = JSON.parse(json) as MoverJson[];
    const items = movers.map((m) => {
      const li = document.createElement('li');
      li.dataset.id = String(m.id);
      const dot = document.createElement('i');
      dot.className = 'dot';
      const cls = classes.get(m.id);
      dot.style.background = COLORS.classes[cls ?? 3];
      const text = document.createElement('span');
      text.textContent = `#${m.id} · ${m.motion.model} · r ${m.radius} m${cls !== undefined ? ` · ${CLASS_NAMES[cls]}` : ''}`;
      const b = document.createElement('button');
      b.type = 'button';
      b.textContent = '×';
      b.title = `Remove mover ${m.id}`;
      b.addEventListener('click', () => this.remove(m.id));
      li.append(dot, text, b);
      return li;
    });
    this.moverList.replaceChildren(...items);
  }
}
