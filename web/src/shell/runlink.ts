// Run links: the URL a gallery card opens (`robot.html?scenario=T-fig3-2.json
// &planner=dwa&set=movers%3D%5B%5D&run=1`) and what a page does with it.
// A run is the reproduce registry's RunSpec (preset, planner, `--set`
// edits), so the page runs exactly what `planlab reproduce` runs; the edits
// are applied to the scenario JSON by the core's recipe through wasm
// (`editScenario(text, recipeJson(planner, set))`), as `planlab run` applies them.

/** One run of a gallery entry (assets/gallery.json). */
export interface GalleryRun {
  name: string;
  preset: string;
  planner: string | null;
  set: [string, string][];
}

/** One gallery entry: a `planlab reproduce` id. */
export interface GalleryEntry {
  id: string;
  title: string;
  page: 'robot' | 'apf' | 'arm' | 'grid';
  paper: string;
  section: string;
  what: string;
  relation: string;
  explanation: string;
  runs: GalleryRun[];
  /** Secondary links of the card (another page's view of the experiment). */
  also?: { label: string; href: string; title?: string }[];
}

/** The run parameters of a page's URL. */
export interface RunParams {
  scenario: string | null;
  planner: string | null;
  set: [string, string][];
  run: boolean;
}

/** A variant link's experiment, run, variant index and family seed. */
export interface VariantParams {
  exp: string;
  as: string;
  k: number;
  /** Decimal u64 (a JS number would round large seeds). */
  seed: string;
  of: number | null;
}

const PAGE_FILE: Record<GalleryEntry['page'], string> = {
  robot: 'robot.html',
  apf: 'apf.html',
  arm: 'arm.html',
  grid: 'index.html',
};

/** The link that opens `run` on `page` and starts it; `exp` names the
 *  gallery entry for the page's note (experiment, run, claimed relation). */
export function runUrl(page: GalleryEntry['page'], run: GalleryRun, exp?: string): string {
  const q = new URLSearchParams();
  q.set('scenario', run.preset);
  if (run.planner) q.set('planner', run.planner);
  for (const [p, v] of run.set) q.append('set', `${p}=${v}`);
  q.set('run', '1');
  if (exp) {
    q.set('exp', exp);
    q.set('as', run.name);
  }
  return `./${PAGE_FILE[page]}?${q.toString()}`;
}

/** Reads `scenario`, `planner`, every `set=path=value` and `run=1`. */
export function runParams(search: string = location.search): RunParams {
  const q = new URLSearchParams(search);
  const set: [string, string][] = [];
  for (const s of q.getAll('set')) {
    const i = s.indexOf('=');
    if (i > 0) set.push([s.slice(0, i), s.slice(i + 1)]);
  }
  const run = q.get('run');
  return {
    scenario: q.get('scenario'),
    planner: q.get('planner'),
    set,
    run: run === '1' || run === 'true',
  };
}

/** `exp=ID&as=RUN&variant=K&seed=S[&of=N]`: run RUN of variant K of
 *  experiment ID's family seeded S (N: the family size of the gallery's
 *  results) instead of the preset; null when the link names no variant. Malformed values
 *  are errors (the page shows them), not silently the preset. */
export function variantParams(q: URLSearchParams = new URLSearchParams(location.search)): VariantParams | null {
  const k = q.get('variant');
  if (k === null) return null;
  const exp = q.get('exp');
  const as = q.get('as');
  if (!exp || !as) throw new Error('a variant link needs exp=ID and as=RUN');
  if (!/^\d{1,9}$/.test(k)) throw new Error(`variant “${k}” is not a variant index (0, 1, 2 …)`);
  const seed = q.get('seed') ?? '0';
  if (!/^\d{1,20}$/.test(seed) || BigInt(seed) >= 2n ** 64n) throw new Error(`seed “${seed}” is not a seed (0 to 2⁶⁴ − 1)`);
  const of = q.get('of');
  const n = of !== null && /^\d{1,9}$/.test(of) ? Number(of) : null;
  return { exp, as, k: Number(k), seed, of: n };
}

/** The same page's URL on variant `k` instead (other parameters kept). */
export function withVariant(k: number, search: string = location.search): string {
  const q = new URLSearchParams(search);
  q.set('variant', String(k));
  q.set('run', '1');
  return `${location.pathname}?${q.toString()}`;
}

/** A run link's planner and edits as the core's recipe (its JSON form),
 *  for the page's wasm `editScenario(text, recipe)`. */
export function recipeJson(planner: string | null, set: [string, string][]): string {
  return JSON.stringify({ planner, set });
}
