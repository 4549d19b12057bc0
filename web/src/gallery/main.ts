// Gallery page: one card per `planlab reproduce` id, built from
// assets/gallery.json (a Rust test keeps it equal to the reproduce
// registry). Each run of an experiment gets a Run link that opens its preset
// on the right page with the run's planner and edits and starts it. The
// thumbnails are drawn from the presets' inline maps. The family results
// (assets/reproduce-results.jsonl: verdict, success rates, effects,
// deviations) are shown on each card, with links to run a random variant.

import entries from 'virtual:gallery';
import { runUrl, type GalleryEntry, type GalleryRun } from '../shell/runlink';
import { installShell } from '../shell/help';
import { installLegend } from '../shell/legend';
import presets from 'virtual:robot-presets';
import { compareGroups, compareUrl } from './compare-links';
import { el } from '../shell/dom';
import results from 'virtual:reproduce-results';
import { resultsSection } from './results';


const ui = {
  cards: el('cards'),
  filters: el('filters'),
  count: el('count'),
  error: el('error'),
};

const PAGE_LABEL: Record<GalleryEntry['page'], string> = {
  robot: 'robot simulation',
  apf: 'potential fields',
  arm: 'arm + hand',
  grid: 'grid planners',
};

/** A readable button label for a run: its name, and the planner when it
 *  is not the name already. */
function runLabel(r: GalleryRun): string {
  const planner = r.planner ?? r.set.find(([p]) => p === 'local_planner.name' || p === 'apf.config.mode')?.[1];
  return planner && planner !== r.name ? `${r.name} (${planner})` : r.name;
}

function h<K extends keyof HTMLElementTagNameMap>(tag: K, cls: string, text?: string): HTMLElementTagNameMap[K] {
  const e = document.createElement(tag);
  if (cls) e.className = cls;
  if (text !== undefined) e.textContent = text;
  return e;
}

function card(e: GalleryEntry): HTMLElement {
  const c = h('article', 'gcard');
  c.id = `exp-${e.id}`;
  c.dataset.id = e.id;
  c.dataset.tag = e.paper.slice(0, 3);
  const thumb = h('canvas', 'thumb');
  thumb.width = 240;
  thumb.height = 150;
  thumb.setAttribute('aria-hidden', 'true');
  c.append(thumb);
  const body = h('div', 'gbody');
  const head = h('header', 'ghead');
  head.append(h('span', `tag tag-${e.paper[1]}`, e.paper.slice(0, 3)), h('code', 'gid', e.id));
  body.append(head, h('h2', 'gtitle', e.title));
  body.append(h('p', 'gpaper', `${e.paper.slice(4)} · ${e.section.replace(/^\[[TSCL]\]\s*/, '')}`));
  body.append(h('p', 'gexpl', e.explanation));
  const dl = h('dl', 'gfacts');
  dl.append(h('dt', '', 'Scene'), h('dd', '', e.what), h('dt', '', 'Paper claims'), h('dd', 'grel', e.relation));
  body.append(dl);
  body.append(resultsSection(e, results[e.id]));
  const runs = h('div', 'gruns');
  runs.append(h('span', 'gon', `Run on the ${PAGE_LABEL[e.page]} page:`));
  for (const r of e.runs) {
    const a = h('a', 'run', `▶ ${runLabel(r)}`);
    a.href = runUrl(e.page, r, e.id);
    a.dataset.run = r.name;
    a.title = `Open ${r.preset} on the ${PAGE_LABEL[e.page]} page and run it` + (r.planner ? ` with ${r.planner}` : '') +
      (r.set.length ? ` (${r.set.map(([p, v]) => `${p}=${v}`).join(', ')})` : '');
    runs.append(a);
  }
  const own = (f: string) => presets.find((p) => p.file === f)?.planner;
  const groups = compareGroups(e, own);
  for (const g of groups) {
    const names = g.runs.map((r) => r.name);
    const a = h('a', 'compare', groups.length === 1 ? '⇄ Compare these runs' : `⇄ Compare ${names.join(' vs ')}`);
    a.href = compareUrl(g);
    a.dataset.runs = names.join(',');
    a.title = `Open ${g.preset} on the compare page and run ${g.planners.join(', ')} side by side` +
      (g.set.length ? ` (${g.set.map(([p, v]) => `${p}=${v}`).join(', ')})` : '');
    runs.append(a);
  }
  for (const l of e.also ?? []) {
    const a = h('a', 'alt', `↗ ${l.label}`);
    a.href = l.href;
    if (l.title) a.title = l.title;
    runs.append(a);
  }
  body.append(runs);
  c.append(body);
  void drawThumb(thumb, e).catch(() => {
    /* a thumbnail is decoration: the card works without it */
  });
  return c;
}

interface ScenarioJson {
  map?: { width: number; height: number; resolution: number; origin?: { x: number; y: number }; cells?: string[]; rle?: string[] };
  start?: { col: number; row: number };
  goal?: { col: number; row: number };
  movers?: { radius: number; motion: { start?: number[] } }[];
  apf?: { obstacles?: { centre: number[]; radius: number }[]; start?: number[]; goal?: number[] };
  arm?: unknown;
}

/** Rows of a map, `rle` decoded. */
function rows(m: NonNullable<ScenarioJson['map']>): string[] {
  if (m.cells) return m.cells;
  return (m.rle ?? []).map((r) => r.replace(/(\d*)([.#?])/g, (_, n: string, c: string) => c.repeat(n ? Number(n) : 1)));
}

async function drawThumb(c: HTMLCanvasElement, e: GalleryEntry): Promise<void> {
  const ctx = c.getContext('2d');
  if (!ctx) return;
  ctx.fillStyle = '#f8fafc';
  ctx.fillRect(0, 0, c.width, c.height);
  const r = await fetch(`./scenarios/${e.runs[0].preset}`);
  if (!r.ok) return;
  const s = (await r.json()) as ScenarioJson;
  if (s.arm || !s.map) {
    // The arm scene has no map: a schematic arm and hand.
    ctx.strokeStyle = '#475569';
    ctx.lineWidth = 7;
    ctx.lineCap = 'round';
    ctx.beginPath();
    ctx.moveTo(60, 130);
    ctx.lineTo(80, 70);
    ctx.lineTo(140, 50);
    ctx.lineTo(180, 80);
    ctx.stroke();
    ctx.fillStyle = '#f472b6';
    ctx.beginPath();
    ctx.arc(170, 110, 12, 0, 2 * Math.PI);
    ctx.fill();
    ctx.fillStyle = '#64748b';
    ctx.font = '12px system-ui, sans-serif';
    ctx.fillText('7-DOF arm · hand', 12, 18);
    return;
  }
  const m = s.map;
  const g = rows(m);
  const scale = Math.min(c.width / m.width, c.height / m.height);
  const ox = (c.width - scale * m.width) / 2;
  const oy = (c.height - scale * m.height) / 2;
  ctx.fillStyle = '#ffffff';
  ctx.fillRect(ox, oy, scale * m.width, scale * m.height);
  ctx.fillStyle = '#1e293b';
  for (let row = 0; row < g.length; row++) {
    const line = g[row];
    for (let col = 0; col < line.length; col++) {
      if (line[col] === '#') ctx.fillRect(ox + col * scale, oy + row * scale, Math.max(1, scale), Math.max(1, scale));
    }
  }
  const o = m.origin ?? { x: 0, y: 0 };
  // World (m) → thumbnail px; row 0 is the top row.
  const px = (x: number) => ox + ((x - o.x) / m.resolution) * scale;
  const py = (y: number) => oy + (m.height - (y - o.y) / m.resolution) * scale;
  const disc = (x: number, y: number, rad: number, fill: string) => {
    ctx.fillStyle = fill;
    ctx.beginPath();
    ctx.arc(x, y, Math.max(2.5, rad), 0, 2 * Math.PI);
    ctx.fill();
  };
  for (const mv of s.movers ?? []) {
    const p = mv.motion.start;
    if (p) disc(px(p[0]), py(p[1]), (mv.radius / m.resolution) * scale, '#f59e0b');
  }
  for (const ob of s.apf?.obstacles ?? []) disc(px(ob.centre[0]), py(ob.centre[1]), (ob.radius / m.resolution) * scale, '#64748b');
  const cell = (p: { col: number; row: number }, fill: string) =>
    disc(ox + (p.col + 0.5) * scale, oy + (p.row + 0.5) * scale, 4, fill);
  if (s.apf?.start) disc(px(s.apf.start[0]), py(s.apf.start[1]), 4, '#16a34a');
  else if (s.start) cell(s.start, '#16a34a');
  if (s.apf?.goal) disc(px(s.apf.goal[0]), py(s.apf.goal[1]), 4, '#2563eb');
  else if (s.goal) cell(s.goal, '#2563eb');
}

function applyFilter(tag: string): void {
  let shown = 0;
  for (const c of ui.cards.querySelectorAll<HTMLElement>('.gcard')) {
    const on = !tag || c.dataset.tag === tag;
    c.hidden = !on;
    if (on) shown++;
  }
  for (const b of ui.filters.querySelectorAll<HTMLButtonElement>('button[data-tag]')) {
    b.setAttribute('aria-pressed', String(b.dataset.tag === tag));
  }
  ui.count.textContent = `${shown} of ${entries.length} experiments`;
}

function main(): void {
  for (const e of entries) ui.cards.append(card(e));
  for (const b of ui.filters.querySelectorAll<HTMLButtonElement>('button[data-tag]')) {
    b.addEventListener('click', () => applyFilter(b.dataset.tag ?? ''));
  }
  applyFilter('');
  installLegend('gallery', ui.cards.parentElement, ui.cards);
  installShell({
    page: 'gallery',
    intro:
      'The gallery lists every experiment of `planlab reproduce`. A Run button opens the scene on its page (robot simulation, potential fields or arm) with the run\'s planner and settings, and starts it.',
    planners: [],
    params: [],
    shortcuts: [],
  });
  document.body.dataset.state = 'ready';
}

try {
  main();
} catch (e) {
  ui.error.hidden = false;
  ui.error.textContent = `Could not build the gallery: ${e instanceof Error ? e.message : String(e)}`;
  document.body.dataset.state = 'error';
}
