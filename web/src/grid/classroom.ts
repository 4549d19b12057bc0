// The grid page's "Draw & generate" card, for teaching with it as with
// PathFinding.js: an empty grid of large cells in one click, Clear walls
// (the start and goal stay), Clear path (the search and path drawing go,
// the player is emptied; the next edit searches again), and the core's
// seeded generators (maze, rooms, random fill: same settings and seed give
// the map `planlab generate` writes). The map/preset menu then names what
// is shown. Planning and generating happen in wasm; this file only reads
// the form and hands the results to the page (main.ts).

import { generateGrid, type MapHandle } from '../../pkg-grid/planlab_wasm.js';
import type { Cell } from '../shell/cells';
import { el } from '../shell/dom';
import { loadPreset, type MapHost } from '../shell/grid-maps';
import { installKeys } from '../shell/keys';
import './classroom.css';

export interface ClassroomHost {
  maps: MapHost;
  /** The map/preset menu. */
  preset: HTMLSelectElement;
  /** The map on screen. */
  map(): MapHandle | null;
  /** `m`'s cells changed wholesale: re-plan on it. */
  mapReplaced(m: MapHandle): void;
  /** Removes the plan, its search and the player's recording. */
  clearPlan(): void;
  guard<A extends unknown[]>(fn: (...args: A) => void | Promise<void>): (...args: A) => void;
  status: HTMLElement;
}

const ui = {
  empty: el<HTMLButtonElement>('empty-grid'),
  clearWalls: el<HTMLButtonElement>('clear-walls'),
  clearPath: el<HTMLButtonElement>('clear-path'),
  kind: el<HTMLSelectElement>('gen-kind'),
  seed: el<HTMLInputElement>('gen-seed'),
  width: el<HTMLInputElement>('gen-width'),
  height: el<HTMLInputElement>('gen-height'),
  resolution: el<HTMLInputElement>('gen-resolution'),
  corridor: el<HTMLInputElement>('gen-corridor'),
  density: el<HTMLInputElement>('gen-density'),
  generate: el<HTMLButtonElement>('generate'),
  note: el('gen-note'),
};

/** The generator settings of the form: the core's `GenerateConfig` (the
 *  fields left out take the CLI's defaults). */
export function generatorSettings(): Record<string, number | string> {
  const num = (e: HTMLInputElement, what: string): number => {
    const v = e.value.trim() === '' ? Number.NaN : Number(e.value);
    if (!Number.isFinite(v)) throw new Error(`Generate: ${what} “${e.value}” is not a number.`);
    return v;
  };
  const seed = num(ui.seed, 'seed');
  if (!Number.isSafeInteger(seed) || seed < 0) throw new Error(`Generate: seed ${ui.seed.value} must be a whole number ≥ 0.`);
  const kind = ui.kind.value;
  const s: Record<string, number | string> = {
    kind,
    width_m: num(ui.width, 'width'),
    height_m: num(ui.height, 'height'),
    resolution: num(ui.resolution, 'cell size'),
    seed,
  };
  if (kind === 'random') s.density = num(ui.density, 'density') / 100;
  else s.corridor_m = num(ui.corridor, 'corridor');
  return s;
}

/** The `planlab generate` command that writes the same map. */
function cliCommand(s: Record<string, number | string>): string {
  const extra = s.kind === 'random' ? `--density ${s.density}` : `--corridor ${s.corridor_m}`;
  return `planlab generate ${s.kind} --width ${s.width_m} --height ${s.height_m} --resolution ${s.resolution} --seed ${s.seed} ${extra}`;
}

/** Shows `label` in the preset menu as the current entry (a disabled
 *  option: picking a real preset from the menu still loads it). */
function showInMenu(menu: HTMLSelectElement, label: string): void {
  let o = menu.querySelector<HTMLOptionElement>('option[value="generated"]');
  if (!o) {
    o = document.createElement('option');
    o.value = 'generated';
    o.disabled = true;
    o.hidden = true;
    menu.append(o);
  }
  o.textContent = label;
  menu.value = 'generated';
}

export function installClassroom(host: ClassroomHost): void {
  const syncKind = () => {
    const random = ui.kind.value === 'random';
    el('gen-corridor-field').dataset.dim = String(random);
    el('gen-density-field').dataset.dim = String(!random);
  };
  syncKind();
  ui.kind.addEventListener('input', syncKind);

  const emptyGrid = host.guard(async () => {
    host.preset.value = 'empty';
    await loadPreset(host.maps, 'empty');
  });
  const clearWalls = host.guard(() => {
    const m = host.map();
    if (!m) return;
    const n = m.clearWalls();
    document.body.dataset.clearedWalls = String(n);
    if (n > 0) host.mapReplaced(m);
  });
  const clearPath = host.guard(() => {
    host.clearPlan();
    host.status.textContent = 'Path cleared: move S or G, paint a wall or change a setting to search again.';
  });
  const generate = host.guard(() => {
    const s = generatorSettings();
    let g;
    try {
      g = generateGrid(JSON.stringify(s));
    } catch (e) {
      throw new Error(`Generate: ${e instanceof Error ? e.message : String(e)}`);
    }
    let m: MapHandle;
    let start: Cell;
    let goal: Cell;
    try {
      m = g.map();
      const [sc, sr] = g.start();
      const [gc, gr] = g.goal();
      start = [sc, sr];
      goal = [gc, gr];
    } finally {
      g.free();
    }
    const hash = m.contentHash();
    const size = `${m.width}×${m.height}`;
    host.maps.install(m, `${s.kind} seed ${s.seed}`, start, goal);
    showInMenu(host.preset, `${s.kind}, seed ${s.seed} (generated)`);
    document.body.dataset.generatedHash = hash;
    ui.note.textContent = `${s.kind} seed ${s.seed}, ${size} cells, grid hash ${hash}: the same map as ${cliCommand(s)}.`;
    ui.note.title = ui.note.textContent;
  });

  ui.empty.addEventListener('click', emptyGrid);
  ui.clearWalls.addEventListener('click', clearWalls);
  ui.clearPath.addEventListener('click', clearPath);
  ui.generate.addEventListener('click', generate);
  installKeys({ c: clearPath, x: clearWalls });
  // The tests compare the map on screen with the CLI's, cell by cell.
  (window as unknown as Record<string, unknown>).planlabClassroom = {
    cells: () => Array.from(host.map()?.cells() ?? []),
    hash: () => host.map()?.contentHash() ?? null,
  };
}
