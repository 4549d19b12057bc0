// Map editing on the robot page: walls (freehand brush), erase, rectangles,
// discs, the start pose, mover paths, seeded map generators, and undo/redo
// over every edit. The shapes go to the wasm SimHandle, which rasterises
// them in the core and restarts the episode on the edited map (the core
// rebuilds the clearance field and the planner replans), so an export of
// the scenario afterwards is the edited one. This file only collects
// pointer gestures, draws their previews and keeps the history.

import type { SimHandle } from '../../pkg/planlab_wasm.js';
import type { RobotView } from '../scene/view';
import { Layer, drawnFrame, mask, type Frame } from '../scene/draw';
import { History, type Snapshot } from './history';
import { el, messageOf } from '../shell/dom';
import { restoreShown, showEdited, showGenerated, shownLabel } from '../shell/preset-select';

/** The Preset select, which says what is shown (edits change its entry). */
const presetSelect = () => document.getElementById('preset') as HTMLSelectElement | null;

/** The handle's path and goals now, as the core draws them. */
function drawnNow(sim: SimHandle | null): Frame | null {
  const layers = mask(Layer.GlobalPath, Layer.Goals);
  return sim ? drawnFrame(sim.draw(layers, 0), layers) : null;
}

export type EditTool = 'wall' | 'erase' | 'rect' | 'disc' | 'start' | 'path';

/** Keyboard shortcut → tool (shown in the buttons' tooltips). */
export const EDIT_KEYS: Record<string, EditTool> = { w: 'wall', e: 'erase', b: 'rect', c: 'disc', s: 'start', l: 'path' };

const HINTS: Record<EditTool, string> = {
  wall: 'Drag to draw walls with the brush ([ and ] change its size). The run restarts on the new map.',
  erase: 'Drag to erase walls with the brush ([ and ] change its size).',
  rect: 'Drag a rectangle of wall (Shift: erase it).',
  disc: 'Press at the centre and drag out the radius of a round obstacle (Shift: erase).',
  start: 'Click to place the start; drag to give its heading.',
  path: 'Click waypoints of a mover path; Enter or double-click finishes it, Esc drops it.',
};

/** What the editor needs from the page (main.ts). */
export interface EditHost {
  sim(): SimHandle | null;
  view: RobotView;
  /** Re-reads the edited SimHandle (same object) into the page. */
  refresh(): void;
  showError(text: string): void;
  clearError(): void;
  /** Switches the page's tool (main.ts's own tools too). */
  setTool(t: string): void;
}

interface MoverJson {
  id: number;
  radius: number;
  motion: Record<string, unknown>;
}



function num(input: HTMLInputElement): number {
  return input.value.trim() === '' ? Number.NaN : Number(input.value);
}

type Gesture =
  | { kind: 'stroke'; points: [number, number][]; cell: 'occupied' | 'free' }
  | { kind: 'rect'; a: [number, number]; b: [number, number]; cell: 'occupied' | 'free' }
  | { kind: 'disc'; c: [number, number]; r: number; cell: 'occupied' | 'free' }
  | { kind: 'start'; p: [number, number]; yaw: number | null };

export class Editor {
  private readonly history = new History<Snapshot>(100);
  private gesture: Gesture | null = null;
  private pointer = -1;
  /** Waypoints of the mover path being built. */
  private path: [number, number][] = [];
  private hover: [number, number] | null = null;
  /** A map/start/path edit or an undo happened: Reset restarts the
   *  edited episode instead of reloading the scenario. */
  dirty = false;

  private readonly ui = {
    tools: Array.from(document.querySelectorAll<HTMLButtonElement>('#edit-tools [data-tool]')),
    brush: el<HTMLInputElement>('brush-size'),
    brushOut: el<HTMLOutputElement>('brush-out'),
    pathModel: el<HTMLSelectElement>('path-model'),
    pathSpeed: el<HTMLInputElement>('path-speed'),
    pathRadius: el<HTMLInputElement>('path-radius'),
    pathFinish: el<HTMLButtonElement>('path-finish'),
    undo: el<HTMLButtonElement>('undo'),
    redo: el<HTMLButtonElement>('redo'),
    genKind: el<HTMLSelectElement>('gen-kind'),
    genWidth: el<HTMLInputElement>('gen-width'),
    genHeight: el<HTMLInputElement>('gen-height'),
    genRes: el<HTMLInputElement>('gen-resolution'),
    genSeed: el<HTMLInputElement>('gen-seed'),
    genCorridor: el<HTMLInputElement>('gen-corridor'),
    genDensity: el<HTMLInputElement>('gen-density'),
    generate: el<HTMLButtonElement>('generate'),
    hint: el('hint'),
  };

  constructor(private readonly host: EditHost) {
    const canvas = host.view.canvas;
    canvas.addEventListener('pointerdown', (ev) => this.guard(() => this.down(ev)));
    canvas.addEventListener('pointermove', (ev) => this.guard(() => this.move(ev)));
    canvas.addEventListener('pointerup', (ev) => this.guard(() => this.up(ev)));
    canvas.addEventListener('pointercancel', () => this.cancelGesture());
    canvas.addEventListener('dblclick', (ev) => {
      if (this.tool === 'path') {
        ev.preventDefault();
        this.guard(() => this.finishPath());
      }
    });
    // main.ts owns the tool state (data-tool on the canvas): follow it.
    new MutationObserver(() => this.syncTool()).observe(canvas, { attributes: true, attributeFilter: ['data-tool'] });
    for (const b of this.ui.tools) b.addEventListener('click', () => this.setTool(b.dataset.tool as EditTool));
    this.ui.brush.addEventListener('input', () => this.syncBrush());
    this.ui.pathFinish.addEventListener('click', () => this.guard(() => this.finishPath()));
    this.ui.undo.addEventListener('click', () => this.guard(() => this.step('undo')));
    this.ui.redo.addEventListener('click', () => this.guard(() => this.step('redo')));
    this.ui.generate.addEventListener('click', () => this.guard(() => this.generate()));
    this.ui.genKind.addEventListener('input', () => this.syncGenerator());
    window.addEventListener('keydown', (ev) => this.key(ev));
    host.view.overlay = (ctx) => this.drawOverlay(ctx);
    this.syncBrush();
    this.syncGenerator();
    this.syncButtons();
    this.installHooks();
  }

  /** For the e2e tests: what the edited episode holds. */
  private installHooks(): void {
    const sim = () => this.host.sim();
    (window as unknown as { planlabEdit: unknown }).planlabEdit = {
      occupied: (x: number, y: number) => {
        const s = sim();
        if (!s) return null;
        const m = s.map();
        try {
          const o = m.origin();
          const col = Math.floor((x - o[0]) / m.resolution);
          const row = m.height - 1 - Math.floor((y - o[1]) / m.resolution);
          if (col < 0 || row < 0 || col >= m.width || row >= m.height) return null;
          return m.cells()[row * m.width + col] === 1;
        } finally {
          m.free();
        }
      },
      gridHash: () => sim()?.gridHash() ?? null,
      globalPath: () => Array.from(drawnNow(sim())?.globalPath() ?? []),
      start: () => Array.from(sim()?.start() ?? []),
      goal: () => drawnNow(sim())?.goal(1) ?? [],
      movers: () => JSON.parse(sim()?.moversJson() ?? '[]'),
      mapSize: () => {
        const s = sim();
        if (!s) return null;
        const m = s.map();
        try {
          return [m.width, m.height, m.resolution];
        } finally {
          m.free();
        }
      },
      undoDepth: () => this.history.undoDepth,
      redoDepth: () => this.history.redoDepth,
    };
  }

  // ------------------------------------------------------------ state
  private get tool(): string {
    return this.host.view.canvas.dataset.tool ?? '';
  }

  private isEditTool(t: string): t is EditTool {
    return t in HINTS;
  }

  setTool(t: EditTool): void {
    this.host.setTool(t);
    this.syncTool();
  }

  private syncTool(): void {
    const t = this.tool;
    for (const b of this.ui.tools) b.setAttribute('aria-checked', String(b.dataset.tool === t));
    if (this.isEditTool(t)) this.ui.hint.textContent = HINTS[t];
    if (t !== 'path' && this.path.length) {
      this.path = [];
      this.host.view.request();
    }
  }

  private guard(f: () => void): void {
    try {
      f();
    } catch (e) {
      this.host.showError(messageOf(e));
    }
  }

  /** Brush radius, m: `size` cells across. */
  private brushRadius(): number {
    const res = this.resolution();
    const size = Math.max(1, Math.round(num(this.ui.brush) || 1));
    return 0.5 * size * res;
  }

  private resolution(): number {
    const sim = this.host.sim();
    if (!sim) return 0.1;
    const m = sim.map();
    try {
      return m.resolution;
    } finally {
      m.free();
    }
  }

  private syncBrush(): void {
    const size = Math.max(1, Math.round(num(this.ui.brush) || 1));
    this.ui.brushOut.textContent = `${size} cell${size > 1 ? 's' : ''}`;
  }

  private syncGenerator(): void {
    const k = this.ui.genKind.value;
    el('gen-corridor-field').dataset.dim = String(k === 'random');
    el('gen-density-field').dataset.dim = String(k !== 'random');
  }

  private syncButtons(): void {
    const h = this.history;
    this.ui.undo.disabled = h.undoDepth === 0;
    this.ui.redo.disabled = h.redoDepth === 0;
    this.ui.undo.title = `Undo${h.nextUndo ? ` ${h.nextUndo}` : ''} (Ctrl+Z)`;
    this.ui.redo.title = `Redo${h.nextRedo ? ` ${h.nextRedo}` : ''} (Ctrl+Shift+Z or Ctrl+Y)`;
    const d = document.body.dataset;
    d.undo = String(h.undoDepth);
    d.redo = String(h.redoDepth);
    const sim = this.host.sim();
    if (sim) d.gridHash = sim.gridHash();
  }

  /** Forgets the history (a new scenario was loaded). */
  reset(): void {
    this.history.clear();
    this.dirty = false;
    this.path = [];
    this.gesture = null;
    this.syncButtons();
  }

  /** After main.ts installed a SimHandle. */
  installed(): void {
    this.syncButtons();
  }

  // --------------------------------------------------------- history
  private snapshot(label: string): Snapshot | null {
    const sim = this.host.sim();
    if (!sim) return null;
    const m = sim.map();
    try {
      const select = presetSelect();
      return { state: sim.editState(), cells: m.cells(), label, shown: select ? shownLabel(select) : undefined };
    } finally {
      m.free();
    }
  }

  /**
   * Runs one edit with a snapshot taken before it; a refused edit (the
   * SimHandle throws and stays as it was) records nothing. `restarts`:
   * the edit rebuilt the episode at t = 0.
   */
  recorded(label: string, edit: () => void, restarts = true): void {
    const before = this.snapshot(label);
    edit();
    if (before) this.history.push(before);
    showEdited(presetSelect());
    if (restarts) {
      this.dirty = true;
      this.host.refresh();
    }
    this.host.clearError();
    this.syncButtons();
  }

  private step(kind: 'undo' | 'redo'): void {
    const sim = this.host.sim();
    if (!sim) return;
    const now = this.snapshot('');
    if (!now) return;
    const target = kind === 'undo' ? this.history.undo(now) : this.history.redo(now);
    if (!target) return;
    try {
      sim.restoreEdit(target.state, target.cells);
    } catch (e) {
      this.history.cancel(kind, target);
      throw e;
    }
    const select = presetSelect();
    if (select && target.shown) restoreShown(select, target.shown);
    this.dirty = true;
    this.host.refresh();
    this.host.clearError();
    this.syncButtons();
    this.ui.hint.textContent = `${kind === 'undo' ? 'Undid' : 'Redid'} ${target.label}.`;
  }

  // ------------------------------------------------------------ input
  private world(ev: MouseEvent): [number, number] {
    const r = this.host.view.canvas.getBoundingClientRect();
    return this.host.view.toWorld(ev.clientX - r.left, ev.clientY - r.top);
  }

  private down(ev: PointerEvent): void {
    const t = this.tool;
    if (!this.isEditTool(t) || ev.button !== 0 || ev.altKey || !this.host.sim()) return;
    const p = this.world(ev);
    if (t === 'path') {
      if (!this.host.view.onMap(p[0], p[1])) return;
      // The second click of a double-click (finish) is not a new waypoint.
      const last = this.path[this.path.length - 1];
      if (last && Math.hypot(p[0] - last[0], p[1] - last[1]) * this.host.view.scale < 4) return;
      this.path.push(p);
      document.body.dataset.pathPoints = String(this.path.length);
      this.host.view.request();
      return;
    }
    const erase = t === 'erase' || ev.shiftKey;
    const cell = erase ? 'free' : 'occupied';
    if (t === 'wall' || t === 'erase') this.gesture = { kind: 'stroke', points: [p], cell };
    else if (t === 'rect') this.gesture = { kind: 'rect', a: p, b: p, cell };
    else if (t === 'disc') this.gesture = { kind: 'disc', c: p, r: 0, cell };
    else this.gesture = { kind: 'start', p, yaw: null };
    this.pointer = ev.pointerId;
    this.host.view.canvas.setPointerCapture(ev.pointerId);
    this.host.view.request();
  }

  private move(ev: PointerEvent): void {
    const p = this.world(ev);
    if (this.tool === 'path') {
      this.hover = p;
      if (this.path.length) this.host.view.request();
    }
    const g = this.gesture;
    if (!g || ev.pointerId !== this.pointer) return;
    if (g.kind === 'stroke') {
      const last = g.points[g.points.length - 1];
      if (Math.hypot(p[0] - last[0], p[1] - last[1]) > 0.3 * this.resolution()) g.points.push(p);
    } else if (g.kind === 'rect') g.b = p;
    else if (g.kind === 'disc') g.r = Math.hypot(p[0] - g.c[0], p[1] - g.c[1]);
    else {
      const [dx, dy] = [p[0] - g.p[0], p[1] - g.p[1]];
      g.yaw = Math.hypot(dx, dy) * this.host.view.scale > 8 ? Math.atan2(dy, dx) : null;
    }
    this.host.view.request();
  }

  private up(ev: PointerEvent): void {
    const g = this.gesture;
    if (!g || ev.pointerId !== this.pointer) return;
    this.gesture = null;
    this.host.view.request();
    const sim = this.host.sim();
    if (!sim) return;
    const verb = g.kind !== 'start' && g.cell === 'free' ? 'erase' : '';
    try {
      if (g.kind === 'stroke') {
        const json = JSON.stringify({ op: 'stroke', points: g.points, radius: this.brushRadius(), cell: g.cell });
        this.recorded(verb || 'wall', () => void sim.editMap(json));
      } else if (g.kind === 'rect') {
        const json = JSON.stringify({ op: 'rect', a: g.a, b: g.b, cell: g.cell });
        this.recorded(verb ? 'erase rectangle' : 'rectangle', () => void sim.editMap(json));
      } else if (g.kind === 'disc') {
        const json = JSON.stringify({ op: 'disc', centre: g.c, radius: g.r, cell: g.cell });
        this.recorded(verb ? 'erase disc' : 'disc', () => void sim.editMap(json));
      } else {
        const yaw = g.yaw ?? sim.start()[2] ?? 0;
        this.recorded('start', () => sim.setStart(g.p[0], g.p[1], yaw));
      }
    } catch (e) {
      const what = g.kind === 'stroke' ? (verb ? 'Erase' : 'Wall') : g.kind === 'start' ? 'Start' : g.kind === 'rect' ? 'Rectangle' : 'Disc';
      throw new Error(`${what} refused: ${messageOf(e)}`);
    }
  }

  private cancelGesture(): void {
    this.gesture = null;
    this.host.view.request();
  }

  private finishPath(): void {
    const sim = this.host.sim();
    if (!sim || this.path.length === 0) return;
    const model = this.ui.pathModel.value;
    const speed = num(this.ui.pathSpeed);
    const radius = num(this.ui.pathRadius);
    const pts = this.path;
    if (pts.length < 2) throw new Error('A mover path needs at least two waypoints: click another one.');
    if (model === 'back-and-forth' && pts.length !== 2) {
      throw new Error(`A back-and-forth path has two ends; this one has ${pts.length} waypoints (use a waypoint loop).`);
    }
    const movers = JSON.parse(sim.moversJson()) as MoverJson[];
    const id = movers.reduce((m, x) => Math.max(m, x.id + 1), 1);
    const motion =
      model === 'back-and-forth' ? { model, a: pts[0], b: pts[1], speed } : { model: 'waypoint-loop', points: pts, speed };
    const json = JSON.stringify([...movers, { id, radius, motion }]);
    try {
      this.recorded('mover path', () => sim.editMovers(json));
    } catch (e) {
      throw new Error(`Mover path refused: ${messageOf(e)}`);
    }
    this.path = [];
    document.body.dataset.pathPoints = '0';
    this.host.view.request();
  }

  private generate(): void {
    const sim = this.host.sim();
    if (!sim) return;
    const settings = this.generatorSettings();
    let hash = '';
    try {
      this.recorded(`${settings.kind} (seed ${settings.seed})`, () => {
        hash = sim.generateMap(JSON.stringify(settings));
      });
    } catch (e) {
      throw new Error(`Generate: ${messageOf(e)}`);
    }
    document.body.dataset.generatedHash = hash;
    showGenerated(presetSelect(), `${settings.kind}, seed ${settings.seed}`);
    const d = el('scenario-description');
    d.textContent = `Generated ${settings.kind} map, seed ${settings.seed} (grid hash ${hash}); the same as planlab generate ${settings.kind} --width ${settings.width_m} --height ${settings.height_m} --resolution ${settings.resolution} --seed ${settings.seed}${settings.kind === 'random' ? ` --density ${settings.density}` : ` --corridor ${settings.corridor_m}`}.`;
    d.title = d.textContent;
    this.host.view.fit();
  }

  /** The generator settings from the form (the core's GenerateConfig). */
  generatorSettings(): Record<string, unknown> & { kind: string; seed: number } {
    const seed = num(this.ui.genSeed);
    if (!Number.isInteger(seed) || seed < 0) throw new Error(`Generate: seed ${this.ui.genSeed.value} must be a whole number ≥ 0.`);
    return {
      kind: this.ui.genKind.value,
      width_m: num(this.ui.genWidth),
      height_m: num(this.ui.genHeight),
      resolution: num(this.ui.genRes),
      seed,
      corridor_m: num(this.ui.genCorridor),
      density: num(this.ui.genDensity) / 100,
    };
  }

  private key(ev: KeyboardEvent): void {
    const t = ev.target as HTMLElement | null;
    if (t && (t.tagName === 'INPUT' || t.tagName === 'SELECT' || t.tagName === 'TEXTAREA')) return;
    const k = ev.key.toLowerCase();
    if ((ev.ctrlKey || ev.metaKey) && !ev.altKey) {
      if (k === 'z' && !ev.shiftKey) {
        ev.preventDefault();
        this.guard(() => this.step('undo'));
      } else if ((k === 'z' && ev.shiftKey) || k === 'y') {
        ev.preventDefault();
        this.guard(() => this.step('redo'));
      }
      return;
    }
    if (ev.altKey) return;
    if (EDIT_KEYS[k] && !ev.shiftKey) this.setTool(EDIT_KEYS[k]);
    else if (k === '[' || k === ']') {
      const v = Math.max(1, Math.min(20, (Math.round(num(this.ui.brush)) || 1) + (k === ']' ? 1 : -1)));
      this.ui.brush.value = String(v);
      this.syncBrush();
    } else if (this.tool === 'path' && k === 'enter') {
      ev.preventDefault();
      this.guard(() => this.finishPath());
    } else if (this.tool === 'path' && k === 'escape') {
      this.path = [];
      this.host.view.request();
    }
  }

  // ------------------------------------------------------------ drawing
  /** Previews in screen space (CSS px), painted after the scene. */
  private drawOverlay(ctx: CanvasRenderingContext2D): void {
    const v = this.host.view;
    const g = this.gesture;
    const s = (p: [number, number]) => v.toScreen(p[0], p[1]);
    ctx.save();
    ctx.lineCap = 'round';
    ctx.lineJoin = 'round';
    if (g) {
      const fill = g.kind !== 'start' && g.cell === 'free' ? 'rgba(255,255,255,0.75)' : 'rgba(30,41,59,0.55)';
      const edge = g.kind !== 'start' && g.cell === 'free' ? '#64748b' : '#0f172a';
      if (g.kind === 'stroke') {
        ctx.strokeStyle = fill;
        ctx.lineWidth = Math.max(2, 2 * this.brushRadius() * v.scale);
        ctx.beginPath();
        g.points.forEach((p, i) => (i ? ctx.lineTo(...s(p)) : ctx.moveTo(...s(p))));
        if (g.points.length === 1) ctx.lineTo(...s(g.points[0]));
        ctx.stroke();
      } else if (g.kind === 'rect') {
        const [a, b] = [s(g.a), s(g.b)];
        ctx.fillStyle = fill;
        ctx.strokeStyle = edge;
        ctx.setLineDash([5, 4]);
        ctx.fillRect(Math.min(a[0], b[0]), Math.min(a[1], b[1]), Math.abs(a[0] - b[0]), Math.abs(a[1] - b[1]));
        ctx.strokeRect(Math.min(a[0], b[0]), Math.min(a[1], b[1]), Math.abs(a[0] - b[0]), Math.abs(a[1] - b[1]));
      } else if (g.kind === 'disc') {
        const c = s(g.c);
        ctx.fillStyle = fill;
        ctx.strokeStyle = edge;
        ctx.setLineDash([5, 4]);
        ctx.beginPath();
        ctx.arc(c[0], c[1], Math.max(2, g.r * v.scale), 0, 2 * Math.PI);
        ctx.fill();
        ctx.stroke();
        ctx.setLineDash([]);
        ctx.fillStyle = '#0f172a';
        ctx.font = '12px system-ui, sans-serif';
        ctx.fillText(`r ${g.r.toFixed(2)} m`, c[0] + 6, c[1] - 6);
      } else {
        const c = s(g.p);
        ctx.strokeStyle = '#16a34a';
        ctx.fillStyle = 'rgba(22,163,74,0.35)';
        ctx.lineWidth = 2;
        ctx.beginPath();
        ctx.arc(c[0], c[1], 9, 0, 2 * Math.PI);
        ctx.fill();
        ctx.stroke();
        if (g.yaw !== null) {
          ctx.beginPath();
          ctx.moveTo(c[0], c[1]);
          ctx.lineTo(c[0] + 26 * Math.cos(g.yaw), c[1] - 26 * Math.sin(g.yaw));
          ctx.stroke();
        }
      }
    }
    if (this.path.length) {
      const pts = this.path.map(s);
      ctx.strokeStyle = '#ea580c';
      ctx.lineWidth = 2;
      ctx.setLineDash([6, 4]);
      ctx.beginPath();
      pts.forEach((p, i) => (i ? ctx.lineTo(p[0], p[1]) : ctx.moveTo(p[0], p[1])));
      if (this.hover && this.tool === 'path') ctx.lineTo(...s(this.hover));
      ctx.stroke();
      ctx.setLineDash([]);
      ctx.fillStyle = '#ea580c';
      for (const [i, p] of pts.entries()) {
        ctx.beginPath();
        ctx.arc(p[0], p[1], 4, 0, 2 * Math.PI);
        ctx.fill();
        ctx.fillText(String(i + 1), p[0] + 6, p[1] - 6);
      }
    }
    ctx.restore();
  }
}
