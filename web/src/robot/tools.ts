// The robot page's own canvas tools (the map-editing ones are edit.ts's):
// the goal (a click moves it, also Shift+click with any tool but a shape),
// movers (a press drops one where it is, the drag says where it will be in
// 1 s) and remove (click a mover; or the × of its row; or clear them all).
// Each is a recorded live edit of the SimHandle (undo/redo through
// edit.ts); the core builds a mover's motion from the drop.

import type { SimHandle } from '../../pkg/planlab_wasm.js';
import type { RobotView } from '../scene/view';
import { Layer } from '../scene/draw';
import type { EditTool, Editor } from './edit';
import { el, type ErrorBanner } from '../shell/dom';

interface MoverJson {
  id: number;
}

export type Tool = 'goal' | 'mover' | 'remove' | EditTool;

function hintFor(tool: Tool): string {
  switch (tool) {
    case 'goal':
      return 'Click the map to move the goal, even while the robot runs.';
    case 'mover':
      return 'Press where a mover should be and drag toward where it will be in 1 s.';
    case 'remove':
      return 'Click a mover to remove it.';
    default:
      return ''; // edit.ts's tools set their own hint
  }
}

export interface ToolHost {
  sim(): SimHandle | null;
  view: RobotView;
  editor: Editor;
  /** After an edit: clear the banner, pull and repaint (`slow`: the
   *  metrics and mover list too). */
  refresh(slow: boolean): void;
  /** The page's handler guard (errors to the banner). */
  guard: ErrorBanner['guard'];
}

function num(input: HTMLInputElement): number {
  return input.value.trim() === '' ? Number.NaN : Number(input.value);
}

export class CanvasTools {
  private tool: Tool = 'goal';
  private readonly ui = {
    tools: Array.from(document.querySelectorAll<HTMLButtonElement>('#tools [data-tool]')),
    hint: el('hint'),
    hover: el('hover'),
    model: el<HTMLSelectElement>('motion-model'),
    radius: el<HTMLInputElement>('mover-radius'),
    span: el<HTMLInputElement>('mover-span'),
    spanField: el('span-field'),
    clear: el<HTMLButtonElement>('clear-movers'),
  };
  /** The drop point and pointer of a drag in progress. */
  private drop: { x: number; y: number; pointer: number } | null = null;

  constructor(private readonly host: ToolHost) {
    const sync = () => (this.ui.spanField.dataset.dim = String(this.ui.model.value === 'constant-velocity'));
    this.ui.model.addEventListener('input', sync);
    sync();
    this.ui.clear.addEventListener('click', host.guard(() => this.clearAll()));
    for (const b of this.ui.tools) b.addEventListener('click', () => this.set(b.dataset.tool as Tool));
    const canvas = host.view.canvas;
    canvas.addEventListener('pointerdown', host.guard((ev: PointerEvent) => this.down(ev)));
    canvas.addEventListener(
      'pointermove',
      host.guard((ev: PointerEvent) => {
        const [x, y] = this.world(ev);
        this.ui.hover.textContent = host.view.onMap(x, y) ? `world (${x.toFixed(2)}, ${y.toFixed(2)}) m` : '—';
        this.drag(x, y);
      }),
    );
    const end = host.guard((ev: PointerEvent) => {
      if (canvas.hasPointerCapture(ev.pointerId)) canvas.releasePointerCapture(ev.pointerId);
      this.release(ev);
    });
    canvas.addEventListener('pointerup', end);
    canvas.addEventListener('pointercancel', end);
    canvas.addEventListener('pointerleave', () => (this.ui.hover.textContent = '—'));
    window.addEventListener('keydown', (ev) => {
      const t = ev.target as HTMLElement | null;
      if (t && (t.tagName === 'INPUT' || t.tagName === 'SELECT' || t.tagName === 'TEXTAREA')) return;
      if (ev.ctrlKey || ev.metaKey || ev.altKey) return;
      const keys: Record<string, Tool> = { g: 'goal', m: 'mover', x: 'remove' };
      const k = keys[ev.key.toLowerCase()];
      if (k) this.set(k);
    });
  }

  /** The tool's hint (empty for edit.ts's, which set their own). */
  get hint(): string {
    return hintFor(this.tool);
  }

  set(t: Tool): void {
    this.tool = t;
    for (const b of this.ui.tools) b.setAttribute('aria-checked', String(b.dataset.tool === t));
    this.host.view.canvas.dataset.tool = t;
    this.ui.hint.textContent = hintFor(t);
  }

  private world(ev: MouseEvent): [number, number] {
    const r = this.host.view.canvas.getBoundingClientRect();
    return this.host.view.toWorld(ev.clientX - r.left, ev.clientY - r.top);
  }

  private down(ev: PointerEvent): void {
    const sim = this.host.sim();
    if (!sim || ev.button !== 0) return;
    const r = this.host.view.canvas.getBoundingClientRect();
    const [cx, cy] = [ev.clientX - r.left, ev.clientY - r.top];
    const [x, y] = this.host.view.toWorld(cx, cy);
    const t = this.tool;
    if ((ev.shiftKey && !['rect', 'disc', 'wall', 'erase'].includes(t)) || t === 'goal') this.moveGoal(sim, x, y);
    else if (t === 'mover') this.press(ev, x, y);
    else if (t === 'remove') this.removeAt(cx, cy);
  }

  private moveGoal(sim: SimHandle, x: number, y: number): void {
    this.host.editor.recorded('goal', () => sim.setGoal(x, y), false);
    this.host.refresh(false);
    document.body.dataset.goal = `${x},${y}`;
  }

  /** A press of the mover tool at world (x, y): the drag begins. */
  private press(ev: PointerEvent, x: number, y: number): void {
    const v = this.host.view;
    if (!v.onMap(x, y)) return;
    this.drop = { x, y, pointer: ev.pointerId };
    v.canvas.setPointerCapture(ev.pointerId);
    v.scene.preview = { x, y, vx: 0, vy: 0, radius: num(this.ui.radius) || 0.1 };
    v.request();
  }

  /** The pointer at world (x, y): the dragged velocity follows it. */
  private drag(x: number, y: number): void {
    const p = this.host.view.scene.preview;
    if (!this.drop || !p) return;
    p.vx = x - this.drop.x;
    p.vy = y - this.drop.y;
    this.host.view.request();
  }

  /** The pointer went up (or was cancelled): place the dragged mover. */
  private release(ev: PointerEvent): void {
    const d = this.drop;
    if (!d || ev.pointerId !== d.pointer) return;
    this.drop = null;
    const v = this.host.view;
    const p = v.scene.preview;
    v.scene.preview = null;
    v.request();
    if (ev.type === 'pointerup' && p) this.place(d.x, d.y, p.vx, p.vy);
  }

  private place(x: number, y: number, vx: number, vy: number): void {
    const sim = this.host.sim();
    if (!sim) return;
    // A tiny drag is a click: a standing mover.
    if (Math.hypot(vx, vy) < 0.02) {
      vx = 0;
      vy = 0;
    }
    const [model, radius, span] = [this.ui.model.value, num(this.ui.radius), num(this.ui.span)];
    this.host.editor.recorded('mover', () => void sim.placeMover(model, radius, x, y, vx, vy, span), false);
    this.host.refresh(true);
    const f = this.host.view.scene.frame;
    document.body.dataset.movers = String(f.of(Layer.Movers).count(Layer.Movers));
  }

  remove(id: number): void {
    const sim = this.host.sim();
    if (!sim) return;
    const keep = (JSON.parse(sim.moversJson()) as MoverJson[]).filter((m) => m.id !== id);
    this.host.editor.recorded(`removing mover ${id}`, () => sim.setMovers(JSON.stringify(keep)), false);
    this.host.refresh(true);
  }

  /** Removes the mover under a canvas point (within its disc or 6 px of it). */
  private removeAt(cx: number, cy: number): void {
    const v = this.host.view;
    const d = v.scene.frame.of(Layer.Movers);
    let best: number | null = null;
    let bestD = Infinity;
    for (let i = d.first(Layer.Movers); i < d.end(Layer.Movers); i++) {
      const [mx, my, r] = d.numbers(i);
      const [x, y] = v.toScreen(mx, my);
      const dist = Math.hypot(cx - x, cy - y) - r * v.scale;
      if (dist < 6 && dist < bestD) {
        bestD = dist;
        best = d.tag(i);
      }
    }
    if (best !== null) this.remove(best);
  }

  private clearAll(): void {
    const sim = this.host.sim();
    if (!sim) return;
    this.host.editor.recorded('removing all movers', () => sim.setMovers('[]'), false);
    this.host.refresh(true);
  }
}
