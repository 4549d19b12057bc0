// A card's family results: what `planlab reproduce ID --variants N --seed S
// --json` measured (assets/reproduce-results.jsonl): the verdict, per run
// its success rate with the Wilson 95 % interval, per clause the share of
// variants where it holds and its paired effect (median, 95 % interval), and
// the declared deviations. Numbers are shown as measured, never recomputed.

import { runUrl, type GalleryEntry } from '../shell/runlink';

/** `Share` of the core: k of n, rate, Wilson 95 % interval. */
export interface Share {
  k: number;
  n: number;
  rate: number;
  ci95: [number, number];
}

export interface FamilyResult {
  id: string;
  relation: string;
  verdict: 'reproduced' | 'partly' | 'not reproduced';
  variants: number;
  seed: number;
  joint: Share;
  runs: Record<string, { success: Share; outcomes: Record<string, number> }>;
  clauses: {
    name: string;
    text: string;
    kind: 'outcome' | 'effect';
    holds: Share;
    effect?: {
      name: string;
      kind: 'difference' | 'ratio';
      unit: string;
      median: { n: number; median: number; ci95: [number, number] | null } | null;
    } | null;
  }[];
  deviations: { what: string; path: string | null; ours: string; paper: string }[];
  redraws: number;
  /** Which perturbation the whole relation is most sensitive to (median
   *  split of every drawn number); absent in results written before it. */
  sensitivity?: Sensitivity;
}

/** `Sensitivity` of the core (reproduce/sensitivity.rs). */
export interface Sensitivity {
  summary: string;
  perturbations: {
    perturbation: string;
    why: string;
    split: { value: string; at: number; below: Share; above: Share } | null;
  }[];
}

function h<K extends keyof HTMLElementTagNameMap>(tag: K, cls: string, text?: string): HTMLElementTagNameMap[K] {
  const e = document.createElement(tag);
  if (cls) e.className = cls;
  if (text !== undefined) e.textContent = text;
  return e;
}

const pct = (x: number) => `${Math.round(100 * x)}`;

/** `27/30 · 90 % [74–97 %]`. */
export function shareText(s: Share): string {
  return `${s.k}/${s.n} · ${pct(s.rate)} % [${pct(s.ci95[0])}–${pct(s.ci95[1])} %]`;
}

/** Three significant digits, no exponent for the sizes shown here. */
function num(x: number): string {
  if (!Number.isFinite(x)) return String(x);
  if (Math.abs(x) >= 100) return x.toFixed(0);
  return String(Number(x.toPrecision(3)));
}

/** An effect's median and interval: `×1.29 [1.00, 1.68]` for a ratio,
 *  `+0.596 m [0.517, 0.652]` for a difference. */
export function effectText(e: NonNullable<FamilyResult['clauses'][number]['effect']>): string {
  const m = e.median;
  if (!m) return 'no variant had both values';
  const unit = e.unit && e.unit !== '1' ? ` ${e.unit}` : '';
  const v = (x: number) => (e.kind === 'ratio' ? `×${num(x)}` : `${x > 0 ? '+' : ''}${num(x)}`);
  const ci = m.ci95 ? ` [${num(m.ci95[0])}, ${num(m.ci95[1])}]` : ' (too few variants for a 95 % interval)';
  return `median ${v(m.median)}${unit}${ci} · n = ${m.n}`;
}

/** "Most sensitive to" and, folded, every perturbation's range reason and
 *  how the whole relation splits at the median of its drawn number. */
export function sensitivitySection(sens: Sensitivity): HTMLElement {
  const box = h('div', 'gsens');
  const line = h('p', 'gsensum');
  line.append(h('b', '', 'Most sensitive to: '), document.createTextNode(sens.summary));
  box.append(line);
  const det = h('details', 'gsensdet');
  det.append(h('summary', '', `Per perturbation (${sens.perturbations.length}): why its range, where the relation holds`));
  // A list, not a table: the card is narrow and the reasons are sentences.
  const ul = h('ul', 'gsenslist');
  for (const p of sens.perturbations) {
    const li = h('li', '');
    li.dataset.perturbation = p.perturbation;
    li.append(h('b', '', p.perturbation));
    if (p.split) {
      li.append(
        h('span', 'gsplit', ` · ${p.split.value} split at ${num(p.split.at)}: holds `),
        h('span', 'gbelow num', shareText(p.split.below)),
        h('span', 'gsplit', ' below, '),
        h('span', 'gabove num', shareText(p.split.above)),
        h('span', 'gsplit', ' at or above'),
      );
    } else {
      li.append(h('span', 'gsplit', ' · nothing ordered drawn (a seed, or nothing to move)'));
    }
    li.append(h('div', 'gwhy', p.why));
    ul.append(li);
  }
  det.append(ul);
  box.append(det);
  return box;
}

const VERDICT_CLASS: Record<FamilyResult['verdict'], string> = {
  reproduced: 'v-yes',
  partly: 'v-partly',
  'not reproduced': 'v-no',
};

/** A variant k of 1…n−1 (0 is the preset), for "random variant" links. */
export function randomVariant(n: number): number {
  return n > 1 ? 1 + Math.floor(Math.random() * (n - 1)) : 0;
}

/** The Run link of `run` on variant `k` of the family. */
export function variantUrl(e: GalleryEntry, run: GalleryEntry['runs'][number], r: FamilyResult, k: number): string {
  const q = new URLSearchParams();
  q.set('variant', String(k));
  q.set('seed', String(r.seed));
  q.set('of', String(r.variants));
  return `${runUrl(e.page, run, e.id)}&${q.toString()}`;
}

/** The results section of a card; "no results" when `r` is missing. */
export function resultsSection(e: GalleryEntry, r: FamilyResult | undefined): HTMLElement {
  const sec = h('section', 'gresults');
  if (!r) {
    sec.classList.add('gnores');
    sec.append(h('p', 'gnote', `No family results for ${e.id} yet (scripts/reproduce-results.sh writes them).`));
    return sec;
  }
  const head = h('div', 'gverdict');
  const badge = h('span', `verdict ${VERDICT_CLASS[r.verdict] ?? ''}`, r.verdict);
  badge.dataset.verdict = r.verdict;
  head.append(
    badge,
    h('span', 'gfam', `${r.variants} variants, seed ${r.seed} · whole relation on ${shareText(r.joint)}`),
  );
  head.title = `planlab reproduce ${e.id} --variants ${r.variants} --seed ${r.seed}: variant 0 is the preset, 1…${r.variants - 1} perturb it`;
  sec.append(head);

  // Runs: success rate with its Wilson interval, and a random variant to run.
  const runs = h('table', 'gtable grunsuccess');
  const cap = h('caption', '', 'Success per run (reached without contact; Wilson 95 %)');
  runs.append(cap);
  // The card's runs, then any the results have that gallery.json does not
  // (a variant link needs only the experiment and run: the tree carries
  // the planner and edits; the first run's preset names the page's scene).
  const extra = Object.keys(r.runs)
    .filter((n) => !e.runs.some((x) => x.name === n))
    .map((name) => ({ ...e.runs[0], name, planner: null, set: [] }));
  for (const run of [...e.runs, ...extra]) {
    const s = r.runs[run.name];
    const tr = h('tr', '');
    tr.dataset.run = run.name;
    tr.append(h('th', '', run.name), h('td', 'num', s ? shareText(s.success) : '—'));
    const td = h('td', 'act');
    if (s && e.page !== 'grid') {
      const a = h('a', 'variant', '▶ random variant');
      a.dataset.run = run.name;
      const pick = () => {
        a.href = variantUrl(e, run, r, randomVariant(r.variants));
      };
      pick();
      // A fresh draw each time the link is used.
      a.addEventListener('pointerdown', pick);
      a.addEventListener('keydown', (ev) => {
        if (ev.key === 'Enter') pick();
      });
      a.title = `Run ${run.name} on a random variant (1–${r.variants - 1}) of this family`;
      td.append(a);
    }
    tr.append(td);
    if (s) tr.title = Object.entries(s.outcomes).map(([o, n]) => `${o} ${n}`).join(', ');
    runs.append(tr);
  }
  sec.append(runs);

  // Clauses: share holding and the paired effect.
  const ul = h('ul', 'gclauses');
  for (const c of r.clauses) {
    const li = h('li', '');
    li.dataset.clause = c.name;
    const good = c.holds.rate >= 0.8 ? 'c-yes' : c.holds.rate < 0.5 ? 'c-no' : 'c-partly';
    li.append(h('b', good, c.name), h('span', 'cshare', ` holds on ${shareText(c.holds)}`));
    li.title = c.text;
    if (c.effect) li.append(h('div', 'ceffect', `${c.effect.name}: ${effectText(c.effect)}`));
    ul.append(li);
  }
  sec.append(h('div', 'gsub', 'Clauses of the relation'), ul);

  if (r.sensitivity) sec.append(sensitivitySection(r.sensitivity));

  // Deviations: every value not from the paper.
  const det = h('details', 'gdev');
  det.append(h('summary', '', `Deviations from the paper (${r.deviations.length})`));
  const dl = h('ul', '');
  for (const d of r.deviations) {
    const li = h('li', '');
    li.append(h('b', '', d.what), h('span', '', `: ours ${d.ours}; paper ${d.paper}`));
    if (d.path) li.title = d.path;
    dl.append(li);
  }
  det.append(dl);
  sec.append(det);
  return sec;
}
