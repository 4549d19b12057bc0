// The grid page's "Explain this step" panel, beside the search player: for
// the player's current step, the expanded cell with f = g + w·h in
// numbers, the neighbours the expansion opened or improved (old g → new g),
// the first entries of the open list after it (in the planner's own order)
// and the planner's pseudo-code with the current event's line highlighted.
// All of it comes from the core (wasm `SearchReplay.explain`); where a
// planner's events lack a value the panel says so (`order.missing`).

import type { SearchPlayer } from './player-ui';
import { readOptions } from './options';
import { pseudoCode, type Role } from './explain-code';
import './explain.css';
import { isSampling } from '../scene/sampling-run';

interface Cell {
  col: number;
  row: number;
}
interface OpenEntry {
  cell: Cell;
  g: number;
  h: number;
  priority: number;
}
interface Relaxed {
  entry: OpenEntry;
  old_g: number;
  parent?: Cell;
  played: boolean;
}
type Priority = { kind: 'f'; weight: number } | { kind: 'h' } | { kind: 'fifo' } | { kind: 'unrecorded' };
/** What wasm `SearchReplay.explain` returns. */
export interface Explained {
  kind: 'none' | 'start' | 'expand' | 'open' | 'line';
  expanded_at?: number;
  expanded?: OpenEntry;
  relaxed: Relaxed[];
  lines: number;
  open: OpenEntry[];
  open_len: number;
  next_expanded?: Cell;
  next_at?: number;
  order: { priority: Priority; ties?: string; missing: string };
}

/** Open-list entries shown. */
const TOP = 5;
/** While playing, the panel is refreshed at most this often (ms). */
const PLAYING_EVERY = 200;

// Three decimals, as the hover text: the shown f then adds up to 0.01.
const n2 = (v: number) => (Number.isFinite(v) ? v.toFixed(3) : '—');
const at = (c: Cell) => `(${c.col}, ${c.row})`;

function h<K extends keyof HTMLElementTagNameMap>(tag: K, cls = '', text = ''): HTMLElementTagNameMap[K] {
  const e = document.createElement(tag);
  if (cls) e.className = cls;
  if (text) e.textContent = text;
  return e;
}

/** The expanded cell's numbers as the planner combines them. */
function formula(algorithm: string, p: Priority, e: OpenEntry): string {
  const [f, g, hh] = [n2(e.priority), n2(e.g), n2(e.h)];
  switch (p.kind) {
    case 'f':
      if (algorithm === 'dijkstra') return `f ${f} = g ${g}  (no h: Dijkstra's f is g)`;
      if (p.weight !== 1) return `f ${f} = g ${g} + ${p.weight} · h ${hh}`;
      return `f ${f} = g ${g} + h ${hh}`;
    case 'h':
      return `key h ${hh}  (greedy orders by h alone; g ${g} is kept for the path)`;
    case 'fifo':
      return `g ${g} (path cost so far) · no f and no h: breadth-first takes cells first in, first out`;
    case 'unrecorded':
      if (algorithm === 'dstar-lite') return `rhs ${g}, h ${hh} (to the start) · key not recorded`;
      return `g ${g} + h ${hh} + ε·L(n) · the safety term ε·L is not recorded, so f is unknown`;
  }
}

/** The role of the current event's pseudo-code line. */
function roleOf(x: Explained): Role | null {
  if (x.kind === 'none') return null;
  // Line checks after the last expansion are the key points' / Bottom-Up's.
  if (x.kind === 'line' && x.next_at === undefined && x.expanded) return 'post';
  return x.kind;
}

export class ExplainPanel {
  private root: HTMLDetailsElement;
  private head = h('p', 'explain-head');
  private f = h('p', 'explain-f');
  private missing = h('p', 'explain-missing');
  private relaxed = h('table', 'explain-relaxed');
  private openHead = h('h4');
  private open = h('ol', 'explain-open');
  private code = h('pre', 'explain-code');
  private codeKey = '';
  private last: Explained | null = null;
  private timer: number | null = null;
  private lastAt = 0;
  /** Time of the last wasm explain call, ms (the tests print it). */
  private ms = 0;

  constructor(private player: SearchPlayer) {
    this.root = h('details', 'explain');
    this.root.id = 'explain';
    // Closed until asked for: open, it takes height from the canvas (and
    // costs a pass over the map per step).
    this.root.open = false;
    const summary = h('summary', '', 'Explain this step');
    summary.title = 'What the planner does at the player\'s current step: the expanded cell and its f, the neighbours it opened or improved, the open list after it and the pseudo-code line';
    const facts = h('div', 'explain-facts');
    const relaxedHead = h('h4', '', 'Neighbours added or improved (old g → new g; grey: not played yet)');
    relaxedHead.title = 'Grey rows come later in this expansion: the player has not played them yet';
    facts.append(this.head, this.f, this.missing, relaxedHead, this.relaxed);
    const openList = h('div', 'explain-facts');
    openList.append(this.openHead, this.open);
    const body = h('div', 'explain-body');
    body.append(facts, openList, this.code);
    this.root.append(summary, body);
    document.getElementById('player')?.after(this.root);
    this.root.addEventListener('toggle', () => this.refresh());
    player.onShow(() => this.refresh());
    (window as unknown as Record<string, unknown>).planlabExplain = { state: () => this.last, ms: () => this.ms };
  }

  /** Re-explains the current step (throttled while the search plays). */
  refresh(): void {
    if (!this.player.isPlaying) {
      this.render();
      return;
    }
    // Outside the animation frame (its work is measured), at most every
    // PLAYING_EVERY ms.
    if (this.timer !== null) return;
    const wait = Math.max(0, this.lastAt + PLAYING_EVERY - performance.now());
    this.timer = window.setTimeout(() => {
      this.timer = null;
      this.render();
    }, wait);
  }

  private render(): void {
    const t0 = performance.now();
    this.lastAt = t0;
    const p = this.player.playback;
    const opts = readOptions();
    const algorithm = String(opts.algorithm ?? 'astar');
    // A sampling planner has no search step to explain: its card has
    // "Explain this planner" instead.
    this.root.hidden = isSampling(algorithm);
    if (this.root.hidden) return;
    this.showCode(algorithm, opts.keypoints === true || typeof opts.bottom_up_eps === 'number');
    if (!p || !this.root.open) {
      this.last = null;
      if (!p) this.clear();
      return;
    }
    let x: Explained;
    try {
      x = p.explain(opts, TOP) as Explained;
    } catch {
      // The options no longer parse; the replan that follows reports it.
      return;
    }
    this.last = x;
    this.ms = performance.now() - t0;
    this.root.dataset.kind = x.kind;
    this.showHead(x);
    this.showF(algorithm, x);
    this.missing.textContent = x.order.missing ? `Not recorded: ${x.order.missing}.` : '';
    this.missing.hidden = !x.order.missing;
    this.showRelaxed(x);
    this.showOpen(x);
    const role = roleOf(x);
    this.code.dataset.current = role ?? '';
    for (const line of Array.from(this.code.children) as HTMLElement[]) {
      line.classList.toggle('current', role !== null && line.dataset.role === role);
    }
  }

  private clear(): void {
    this.head.textContent = 'No search to explain: place the start and the goal, with "Show the search" on.';
    this.f.textContent = '';
    this.missing.hidden = true;
    this.relaxed.replaceChildren();
    this.openHead.textContent = '';
    this.open.replaceChildren();
    this.code.dataset.current = '';
    this.root.dataset.kind = 'none';
  }

  private showCode(algorithm: string, post: boolean): void {
    const key = `${algorithm}|${post}`;
    if (key === this.codeKey) return;
    this.codeKey = key;
    this.code.dataset.algorithm = algorithm;
    this.code.replaceChildren(
      ...pseudoCode(algorithm, post).map(([text, role]) => {
        const line = h('span', 'line', text);
        if (role) line.dataset.role = role;
        return line;
      }),
    );
  }

  private showHead(x: Explained): void {
    const step = this.player.playback?.step ?? 0;
    const what: Record<Explained['kind'], string> = {
      none: 'Nothing played yet: step forward (.) or press Play.',
      start: 'The search begins: the first cell enters the open list.',
      expand: 'A cell is taken off the open list and expanded.',
      open: 'A neighbour of the expanded cell is opened or its g improved.',
      line: 'A straight-line check (jump scan, line of sight or key-point segment).',
    };
    let text = `Step ${step.toLocaleString('en-US')} · ${what[x.kind]}`;
    if (x.expanded) text += ` Expanding ${at(x.expanded.cell)} (its expansion began at step ${x.expanded_at}).`;
    this.head.textContent = text;
  }

  private showF(algorithm: string, x: Explained): void {
    const d = this.f.dataset;
    const e = x.expanded;
    if (!e) {
      this.f.textContent = 'No cell expanded yet.';
      for (const k of ['f', 'g', 'h', 'w', 'col', 'row']) delete d[k];
      return;
    }
    this.f.textContent = formula(algorithm, x.order.priority, e);
    d.f = String(e.priority);
    d.g = String(e.g);
    d.h = String(e.h);
    d.w = x.order.priority.kind === 'f' ? String(x.order.priority.weight) : '';
    d.col = String(e.cell.col);
    d.row = String(e.cell.row);
  }

  private showRelaxed(x: Explained): void {
    const rows = x.relaxed.map((r) => {
      const tr = h('tr', r.played ? '' : 'unplayed');
      tr.title = r.played ? '' : 'later in this expansion: not played yet';
      const old = Number.isFinite(r.old_g) ? `${n2(r.old_g)} → ${n2(r.entry.g)}` : `new, g ${n2(r.entry.g)}`;
      const pr = Number.isFinite(r.entry.priority) ? `f ${n2(r.entry.priority)}` : '';
      tr.append(h('td', '', at(r.entry.cell)), h('td', '', old), h('td', '', `h ${n2(r.entry.h)}`), h('td', '', pr));
      return tr;
    });
    if (!rows.length) {
      const tr = h('tr');
      tr.append(h('td', 'muted', x.expanded ? 'none (every neighbour was already as cheap, expanded or blocked)' : '—'));
      rows.push(tr);
    }
    if (x.lines) {
      const tr = h('tr');
      tr.append(h('td', 'muted', `${x.lines} line check${x.lines === 1 ? '' : 's'} in this expansion`));
      rows.push(tr);
    }
    this.relaxed.replaceChildren(...rows);
  }

  private showOpen(x: Explained): void {
    const count = x.open_len.toLocaleString('en-US');
    if (!x.order.ties) {
      this.openHead.textContent = `Open list after this step: ${count} cells (its order is not shown: see above)`;
      this.open.replaceChildren();
      return;
    }
    const by = x.order.priority.kind === 'fifo' ? 'first in, first out' : x.order.priority.kind === 'h' ? 'lowest h first' : 'lowest f first';
    this.openHead.textContent = `Open list after this step: first ${Math.min(TOP, x.open_len)} of ${count} (${by})`;
    this.open.replaceChildren(
      ...x.open.map((e, i) => {
        const li = h('li');
        li.dataset.col = String(e.cell.col);
        li.dataset.row = String(e.cell.row);
        const pr = Number.isFinite(e.priority) ? `f ${n2(e.priority)} · ` : '';
        li.textContent = `${at(e.cell)}  ${pr}g ${n2(e.g)} · h ${n2(e.h)}`;
        if (i === 0 && x.next_expanded) li.title = `expanded next, at step ${x.next_at}`;
        return li;
      }),
    );
  }
}
