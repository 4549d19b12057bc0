// The shell every page shares: a Gallery link in the nav, a "?" button that
// opens the help overlay (also `?` and F1; Esc or a click outside closes
// it), and the presentation toggle (`P`, remembered in localStorage) that
// scales the page for a projector. The overlay's content comes from the
// page: its planners (paper, section, what they do), their parameters (unit,
// default, effect; on the robot page straight from the wasm planner
// registry's field infos) and its keyboard shortcuts.

import './help.css';

/** A planner (or variant / predictor) the page offers. */
export interface HelpPlanner {
  name: string;
  /** Paper and section, e.g. `[T] Wu 2022 §3.2`. */
  paper: string;
  summary: string;
  /** The same in plain words for a beginner (what it does, when it fails,
   *  what to look at on the canvas); shown first. */
  plain?: string;
  /** Optimal? complete? any-angle? incremental? in plain words, one line. */
  properties?: string;
  /** The name the page's menu uses for it (`data-key`), where it differs. */
  key?: string;
  /** Its parameters; shown in a table under the planner. */
  params?: HelpParam[];
}

/** One parameter: name, unit, default and what it does. */
export interface HelpParam {
  name: string;
  /** Its name in plain words, shown above the config name. */
  label?: string;
  unit: string;
  default?: unknown;
  doc: string;
}

/** One keyboard shortcut. */
export interface HelpShortcut {
  keys: string;
  action: string;
}

/** What the overlay shows for a page. */
export interface HelpContent {
  /** The page's name for the stable ids (`gallery`, `robot`, …). */
  page: string;
  /** One paragraph about the page; `code` in backticks. */
  intro: string;
  planners: HelpPlanner[];
  /** The planner whose details open first (the page's current one). */
  current?: string;
  /** Page-level parameters (not tied to a planner). */
  params: HelpParam[];
  shortcuts: HelpShortcut[];
}

const PRESENT_KEY = 'planlab.present';

/** Keys every page has (the shell's own). */
const SHELL_SHORTCUTS: HelpShortcut[] = [
  { keys: '? or F1', action: 'open this help' },
  { keys: 'Esc', action: 'close this help' },
  { keys: 'P', action: 'presentation mode on / off (larger text, the map takes the side panel\'s and plots\' room; Panels shows them)' },
];

function h<K extends keyof HTMLElementTagNameMap>(tag: K, cls = '', text?: string): HTMLElementTagNameMap[K] {
  const e = document.createElement(tag);
  if (cls) e.className = cls;
  if (text !== undefined) e.textContent = text;
  return e;
}

/** Text with `code` spans. */
/** The site's copy of the algorithm notes (the build copies
 *  docs/algorithms.md there): the help's citations of it are links. */
const ALGORITHMS_DOC = 'docs/algorithms.md';

/** `text` with every mention of the algorithm notes as a link to them. */
function linked(text: string): Node[] {
  return text.split(ALGORITHMS_DOC).flatMap((part, i) => {
    const out: Node[] = [];
    if (i > 0) {
      const a = h('a', 'help-doc', ALGORITHMS_DOC);
      a.href = ALGORITHMS_DOC;
      a.target = '_blank';
      a.rel = 'noopener';
      out.push(a);
    }
    if (part) out.push(document.createTextNode(part));
    return out;
  });
}

function rich(tag: 'p' | 'span', text: string, cls = ''): HTMLElement {
  const e = h(tag, cls);
  text.split('`').forEach((part, i) => {
    if (!part) return;
    e.append(...(i % 2 ? [h('code', '', part)] : linked(part)));
  });
  return e;
}

function fmtDefault(v: unknown): string {
  if (v === undefined) return '';
  if (typeof v === 'number') return Number.isInteger(v) ? String(v) : String(Number(v.toPrecision(6)));
  if (typeof v === 'string') return v;
  return JSON.stringify(v);
}

function paramTable(params: HelpParam[]): HTMLTableElement {
  const t = h('table', 'help-params');
  const head = h('tr');
  for (const c of ['parameter', 'unit', 'default', 'effect']) head.append(h('th', '', c));
  t.createTHead().append(head);
  const body = t.createTBody();
  for (const p of params) {
    const tr = h('tr');
    tr.dataset.param = p.name;
    const name = h('td', 'pname');
    if (p.label) name.append(h('span', 'plabel', p.label), h('code', 'pconfig', p.name));
    else name.textContent = p.name;
    tr.append(name, h('td', 'punit', p.unit || '—'), h('td', 'pdef', fmtDefault(p.default)));
    const td = h('td', 'pdoc');
    td.append(rich('span', p.doc));
    tr.append(td);
    body.append(tr);
  }
  return t;
}

/** Presentation mode: on / off, remembered. */
export function setPresentation(on: boolean): void {
  document.documentElement.classList.toggle('present', on);
  try {
    localStorage.setItem(PRESENT_KEY, on ? '1' : '0');
  } catch {
    /* storage may be off (private mode): the mode still applies */
  }
  const b = document.getElementById('present-button');
  if (b) b.setAttribute('aria-pressed', String(on));
  // Canvases size themselves on resize.
  window.dispatchEvent(new Event('resize'));
}

function storedPresentation(): boolean {
  try {
    return localStorage.getItem(PRESENT_KEY) === '1';
  } catch {
    return false;
  }
}

let installed = false;

/**
 * Adds the help button, the presentation toggle and their keys to the
 * page. `content` is read each time the overlay opens, so it can follow
 * the page's state (the robot page's current planner).
 */
export function installShell(content: HelpContent | (() => HelpContent)): void {
  if (installed) return;
  installed = true;
  const get = typeof content === 'function' ? content : () => content;
  document.documentElement.classList.toggle('present', storedPresentation());

  const bar = document.querySelector('.topbar');
  const tools = h('div', 'shell-tools');
  const present = h('button', 'shell-button', 'Large');
  present.type = 'button';
  present.id = 'present-button';
  present.title = 'Presentation mode: larger text and lines for a projector (P)';
  present.setAttribute('aria-pressed', String(storedPresentation()));
  const help = h('button', 'shell-button help-button', '?');
  help.type = 'button';
  help.id = 'help-button';
  help.title = 'Help: planners, parameters, keyboard shortcuts (? or F1)';
  help.setAttribute('aria-label', 'Help');
  const panels = h('button', 'shell-button panels-button', 'Panels');
  panels.type = 'button';
  panels.id = 'panels-button';
  panels.title = 'Presentation mode: show or hide the side panel and plots (Space plays, R resets)';
  panels.setAttribute('aria-pressed', 'false');
  panels.addEventListener('click', () => {
    const on = document.documentElement.classList.toggle('present-panels');
    panels.setAttribute('aria-pressed', String(on));
    window.dispatchEvent(new Event('resize'));
  });
  tools.append(panels, present, help);
  bar?.append(tools);

  const backdrop = h('div', 'help-backdrop');
  backdrop.id = 'help';
  backdrop.hidden = true;
  const dialog = h('div', 'help-dialog');
  dialog.setAttribute('role', 'dialog');
  dialog.setAttribute('aria-modal', 'true');
  dialog.setAttribute('aria-labelledby', 'help-title');
  dialog.tabIndex = -1;
  backdrop.append(dialog);
  document.body.append(backdrop);

  let lastFocus: Element | null = null;
  const open = () => {
    lastFocus = document.activeElement;
    build(dialog, get());
    backdrop.hidden = false;
    document.body.dataset.help = 'open';
    // The dialog itself takes focus (not the close button, which Space
    // would press): Space / arrows scroll the help, Tab reaches the links.
    dialog.focus();
  };
  const close = () => {
    if (backdrop.hidden) return;
    backdrop.hidden = true;
    delete document.body.dataset.help;
    if (lastFocus instanceof HTMLElement) lastFocus.focus();
  };
  help.addEventListener('click', open);
  present.addEventListener('click', () => setPresentation(!document.documentElement.classList.contains('present')));
  backdrop.addEventListener('click', (ev) => {
    if (ev.target === backdrop) close();
  });
  dialog.addEventListener('click', (ev) => {
    if ((ev.target as HTMLElement).closest('.help-close')) close();
  });
  // Capture phase: the help keys win over the page's own, and while the
  // overlay is open the page's keys (Space = play, …) are held back.
  window.addEventListener(
    'keydown',
    (ev) => {
      const t = ev.target as HTMLElement | null;
      const typing = !!t && (t.tagName === 'INPUT' || t.tagName === 'SELECT' || t.tagName === 'TEXTAREA');
      if (!backdrop.hidden) {
        if (ev.key === 'Escape' || ev.key === 'F1' || ev.key === '?') {
          ev.preventDefault();
          close();
        }
        // Tab and clicks stay in the dialog; other keys do nothing on the page.
        if (ev.key !== 'Tab') ev.stopPropagation();
        return;
      }
      if (ev.ctrlKey || ev.metaKey || ev.altKey) return;
      if (ev.key === 'F1' || (ev.key === '?' && !typing)) {
        ev.preventDefault();
        ev.stopPropagation();
        open();
      } else if ((ev.key === 'p' || ev.key === 'P') && !typing) {
        ev.stopPropagation();
        setPresentation(!document.documentElement.classList.contains('present'));
      }
    },
    true,
  );
}

function build(dialog: HTMLElement, c: HelpContent): void {
  dialog.replaceChildren();
  const head = h('header', 'help-head');
  const title = h('h2', '', 'Help');
  title.id = 'help-title';
  const x = h('button', 'help-close', '×');
  x.type = 'button';
  x.title = 'Close (Esc)';
  x.setAttribute('aria-label', 'Close help');
  head.append(title, x);
  dialog.append(head);
  const body = h('div', 'help-body');
  dialog.append(body);
  body.append(rich('p', c.intro, 'help-intro'));

  if (c.planners.length) {
    const sec = h('section', 'help-planners');
    sec.append(h('h3', '', 'Planners'));
    for (const p of c.planners) {
      const d = h('details', 'help-planner');
      d.dataset.planner = p.name;
      if (p.key) d.dataset.key = p.key;
      if (p.name === c.current || (!c.current && c.planners.length === 1)) d.open = true;
      const s = h('summary');
      const paper = h('span', 'help-paper');
      paper.append(...linked(p.paper));
      s.append(h('b', '', p.name), paper);
      d.append(s);
      if (p.plain) d.append(rich('p', p.plain, 'help-plain'));
      d.append(rich('p', p.summary, p.plain ? 'help-technical' : ''));
      if (p.properties) d.append(rich('p', `Properties: ${p.properties}.`, 'help-properties'));
      if (p.params?.length) d.append(paramTable(p.params));
      sec.append(d);
    }
    body.append(sec);
  }
  if (c.params.length) {
    const sec = h('section', 'help-page-params');
    sec.append(h('h3', '', 'Parameters'), paramTable(c.params));
    body.append(sec);
  }
  const sec = h('section', 'help-keys');
  sec.append(h('h3', '', 'Keyboard shortcuts'));
  const t = h('table', 'help-shortcuts');
  for (const k of [...c.shortcuts, ...SHELL_SHORTCUTS]) {
    const tr = h('tr');
    const td = h('td');
    td.append(...k.keys.split(' ').map((w) => (/^(or|\/|\+|,|·)$/.test(w) ? document.createTextNode(` ${w} `) : h('kbd', '', w))));
    tr.append(td, h('td', '', k.action));
    t.append(tr);
  }
  sec.append(t);
  body.append(sec);
  const foot = h('p', 'help-foot');
  foot.append(
    rich(
      'span',
      'Papers: [T] Wu 2022 (MEng thesis: improved DWA ch. 3, APF ch. 4, arm ch. 5), [S] Ge & Li 2022 (safe A* + dual-velocity DWA), [C] Zhang et al. 2020 (cleaning-robot DWA), [L] Chang et al. 2024 (LiDAR navigation). Every experiment: the Gallery page, or `planlab reproduce`.',
    ),
  );
  body.append(foot);
}
