// The grid page's search player: play, pause, step forward and back, speed
// and a scrubber over the recorded search, the counters at the current
// step, and the animation loop with its frame meter. Each frame plays
// `speed` events (an event budget per frame), repaints only the cells they
// touched and draws; the frame's work is measured for the tests and the
// README (window.planlabGrid.frameStats()).

import { el } from '../shell/dom';
import { FrameMeter } from '../shell/frame-meter';
import { SearchPlayback } from '../scene/search-player';
import { SamplingPlayback } from '../scene/sampling-tree';
import type { MapView } from '../scene/grid-view';
import { Layer } from '../scene/draw';

const ui = {
  play: el<HTMLButtonElement>('play'),
  back: el<HTMLButtonElement>('step-back'),
  fwd: el<HTMLButtonElement>('step-fwd'),
  speed: el<HTMLSelectElement>('speed'),
  scrub: el<HTMLInputElement>('scrub'),
  step: el('count-step'),
  expanded: el('count-expanded'),
  open: el('count-open'),
  f: el('count-f'),
  lines: el('count-lines'),
  labels: ['count-expanded', 'count-open', 'count-f', 'count-lines'].map((id) => el(id).previousElementSibling as HTMLElement),
};

/** The counters' labels and tips: a grid search's, a sampling run's. */
const SEARCH_LABELS: [string, string][] = [
  ['Expanded', 'Cells taken from the open set so far'],
  ['Open', 'Cells waiting in the open set'],
  ['Best f', 'f = g + w·h of the cell expanded last: the best f so far'],
  ['Lines', 'Straight-line checks (JPS scans, line of sight)'],
];
const SAMPLING_LABELS: [string, string][] = [
  ['Nodes', 'Points in the tree or roadmap at this step'],
  ['Samples', 'Random points drawn so far'],
  ['Best cost', 'Length of the best path found so far, cells'],
  ['Rewires', 'Nodes that moved to a cheaper parent so far (RRT*, Informed RRT*, BIT*)'],
];

/** What the player plays: a grid search or a sampling planner's run. */
export type Playable = SearchPlayback | SamplingPlayback;

function setCount(e: HTMLElement, text: string, value: number | null): void {
  e.textContent = text;
  if (value === null || Number.isNaN(value)) delete e.dataset.value;
  else e.dataset.value = String(value);
}

export class SearchPlayer {
  private view: MapView;
  private p: Playable | null = null;
  private labelled: 'search' | 'sampling' = 'search';
  private playing = false;
  private last = 0;
  private shown: Array<() => void> = [];
  readonly meter = new FrameMeter();

  constructor(view: MapView) {
    this.view = view;
    ui.play.addEventListener('click', () => this.toggle());
    ui.back.addEventListener('click', () => this.stepBy(-1));
    ui.fwd.addEventListener('click', () => this.stepBy(1));
    ui.scrub.addEventListener('input', () => {
      this.pause();
      this.seek(Number(ui.scrub.value));
    });
    this.show();
  }

  /** The grid search played (null for none or a sampling run). */
  get playback(): SearchPlayback | null {
    return this.p instanceof SearchPlayback ? this.p : null;
  }

  /** The sampling run played, or null. */
  get sampling(): SamplingPlayback | null {
    return this.p instanceof SamplingPlayback ? this.p : null;
  }

  get isPlaying(): boolean {
    return this.playing;
  }

  /** Calls `f` after every change of step or recording (the explain panel). */
  onShow(f: () => void): void {
    this.shown.push(f);
  }

  /** Events played per animation frame. */
  get speed(): number {
    return Math.max(1, Number(ui.speed.value) || 1);
  }

  /** A new recording (null: none), shown played out unless `fromStart`. */
  load(p: Playable | null, fromStart = false): void {
    this.pause();
    if (this.p !== p) this.p?.free();
    this.p = p;
    if (p) p.seek(fromStart ? 0 : p.n);
    this.view.setSearch(p instanceof SearchPlayback ? p : null);
    this.view.setTree(p instanceof SamplingPlayback ? p : null);
    this.show();
  }

  toggle(): void {
    if (this.playing) this.pause();
    else this.play();
  }

  play(): void {
    if (!this.p || this.playing) return;
    if (this.p.done) this.p.seek(0);
    this.playing = true;
    this.meter.reset();
    this.last = performance.now();
    document.body.dataset.playing = 'true';
    requestAnimationFrame((t) => this.frame(t));
    this.show();
  }

  pause(): void {
    this.playing = false;
    document.body.dataset.playing = 'false';
    ui.play.textContent = '▶ Play';
  }

  stepBy(d: number): void {
    if (!this.p) return;
    this.pause();
    this.seek(this.p.step + d);
  }

  seek(step: number): void {
    if (!this.p) return;
    this.p.seek(step);
    this.view.drawNow();
    this.show();
  }

  private frame(t: number): void {
    if (!this.playing || !this.p) return;
    const t0 = performance.now();
    this.p.seek(this.p.step + this.speed);
    const t1 = performance.now();
    this.view.drawNow();
    const t2 = performance.now();
    this.show();
    const t3 = performance.now();
    this.meter.push(t - this.last, t1 - t0, t2 - t1, t3 - t0);
    this.last = t;
    if (this.p.done) {
      this.pause();
      this.show();
      return;
    }
    requestAnimationFrame((tt) => this.frame(tt));
  }

  /** Scrubber, buttons, counters and the state the tests read; then the
   *  `onShow` listeners. */
  private show(): void {
    this.showCounters();
    for (const f of this.shown) f();
  }

  private showCounters(): void {
    const p = this.p;
    const d = document.body.dataset;
    for (const b of [ui.play, ui.back, ui.fwd, ui.scrub]) b.disabled = !p;
    if (this.playing) ui.play.textContent = '❚❚ Pause';
    if (!p) {
      ui.scrub.max = '0';
      ui.scrub.value = '0';
      for (const e of [ui.step, ui.expanded, ui.open, ui.f, ui.lines]) setCount(e, '—', null);
      d.searchStep = '0';
      d.searchEvents = '0';
      return;
    }
    const kind = p instanceof SamplingPlayback ? 'sampling' : 'search';
    if (kind !== this.labelled) {
      this.labelled = kind;
      (kind === 'sampling' ? SAMPLING_LABELS : SEARCH_LABELS).forEach(([text, tip], i) => {
        ui.labels[i].textContent = text;
        ui.labels[i].title = tip;
      });
    }
    ui.scrub.max = String(p.n);
    if (p instanceof SamplingPlayback) {
      const c = p.counters();
      ui.scrub.value = String(c.step);
      setCount(ui.step, `${c.step.toLocaleString('en-US')} / ${c.events.toLocaleString('en-US')}`, c.step);
      setCount(ui.expanded, c.nodes.toLocaleString('en-US'), c.nodes);
      setCount(ui.open, c.samples.toLocaleString('en-US'), c.samples);
      setCount(ui.f, Number.isNaN(c.cost) ? '—' : c.cost.toFixed(3), c.cost);
      setCount(ui.lines, c.rewires.toLocaleString('en-US'), c.rewires);
      d.searchStep = String(c.step);
      d.searchEvents = String(c.events);
      return;
    }
    const c = p.counters();
    ui.scrub.value = String(c.step);
    setCount(ui.step, `${c.step.toLocaleString('en-US')} / ${c.events.toLocaleString('en-US')}`, c.step);
    setCount(ui.expanded, c.expanded.toLocaleString('en-US'), c.expanded);
    setCount(ui.open, c.open.toLocaleString('en-US'), c.open);
    setCount(ui.f, Number.isNaN(c.f) ? '—' : c.f.toFixed(3), c.f);
    setCount(ui.lines, c.lines.toLocaleString('en-US'), c.lines);
    d.searchStep = String(c.step);
    d.searchEvents = String(c.events);
  }
}

/** `window.planlabGrid`: the player's state and its frame meter, for the
 *  e2e tests and the README's figures. */
export function exposeForTests(player: SearchPlayer, rebuilds: () => number, view: MapView): void {
  (window as unknown as Record<string, unknown>).planlabGrid = {
    seek: (k: number) => player.seek(k),
    play: () => player.play(),
    cellState: (c: number, r: number) => player.playback?.info(c, r)?.state ?? null,
    /** The sampling run at the player's step: counters, edges painted, the
     *  path shown (cells). */
    sampling: () => {
      const s = player.sampling;
      if (!s) return null;
      return { ...s.counters(), drawnEdges: s.drawnEdges, done: s.done, path: Array.from(s.pathNow() ?? []), solutionAt: s.solutionAt };
    },
    info: (c: number, r: number) => player.playback?.info(c, r) ?? null,
    current: () => player.playback?.expanding() ?? null,
    counters: () => player.playback?.counters() ?? null,
    frameStats: () => player.meter.stats(),
    rebuilds,
    /** The path as the view got it from the core's draw list (m), and
     *  the map frame it is drawn in. */
    drawnPath: () => Array.from(view.pointsOf(Layer.GlobalPath) ?? []),
    mapFrame: () => view.mapFrame,
  };
}
