// The bench page's maps and queries: the Moving AI arena map the site
// bundles (maps/arena.map) with rows of its .scen, an open grid made here
// (no obstacles, so the octile distance is the exact optimum), and the
// Moving AI maze512-1-0 with rows of its .scen. The .scen files and the
// maze are fetched on Run only (Vite emits them as assets), so they add
// nothing to the page's first load.

import arenaScenUrl from '../../../tests/data/movingai/dao/arena.map.scen?url';
import mazeMapUrl from '../../../tests/data/movingai/maze/maze512-1-0.map?url';
import mazeScenUrl from '../../../tests/data/movingai/maze/maze512-1-0.map.scen?url';

export type Size = 'tiny' | 'small' | 'full';

export interface Query {
  sx: number;
  sy: number;
  gx: number;
  gy: number;
  /** Reference optimum, or null when the map has none. */
  optimal: number | null;
  /** Where `optimal` comes from. */
  optimumSource: string;
  /** A one-query Moving AI .scen (what planlab's ScenBatch reads). */
  scen: string;
}

export interface MapCase {
  /** Short id: arena, open or maze. */
  key: string;
  name: string;
  /** Moving AI .map text. */
  mapText: string;
  queries: Query[];
}

interface SizePlan {
  arenaRows: number;
  openSide: number;
  openQueries: number;
  mazeRows: number;
  /** Maze rows are picked from the first `mazeSpan` of the .scen (its rows
   *  run from short to long), so small sizes stay quick. */
  mazeSpan: number;
}

export const SIZES: Record<Size, SizePlan> = {
  tiny: { arenaRows: 3, openSide: 64, openQueries: 2, mazeRows: 2, mazeSpan: 0.05 },
  small: { arenaRows: 6, openSide: 256, openQueries: 3, mazeRows: 4, mazeSpan: 0.25 },
  full: { arenaRows: 10, openSide: 512, openQueries: 4, mazeRows: 6, mazeSpan: 1 },
};

const SQRT2 = Math.SQRT2;

/** Octile distance: the exact shortest 8-connected path with √2 diagonals
 *  when nothing is in the way. */
export function octile(dx: number, dy: number): number {
  const a = Math.abs(dx);
  const b = Math.abs(dy);
  return Math.max(a, b) + (SQRT2 - 1) * Math.min(a, b);
}

async function fetchText(url: string): Promise<string> {
  const r = await fetch(url);
  if (!r.ok) throw new Error(`could not load ${url}: HTTP ${r.status}`);
  return r.text();
}

/** `k` rows spread evenly over the first `span` of a .scen's rows, the
 *  last of them included and the first (often a one-step query) not. */
function pickScenRows(scenText: string, k: number, span: number, source: string): Query[] {
  const rows = scenText
    .split('\n')
    .slice(1)
    .filter((l) => l.trim());
  const m = Math.max(1, Math.ceil(rows.length * span));
  const idx = [...new Set(Array.from({ length: k }, (_, i) => Math.round(((i + 1) * (m - 1)) / k)))];
  return idx.map((i) => {
    const f = rows[i].trim().split(/\s+/);
    if (f.length < 9) throw new Error(`${source}: row ${i + 1} has ${f.length} fields, expected 9`);
    const [sx, sy, gx, gy, optimal] = f.slice(4, 9).map(Number);
    return { sx, sy, gx, gy, optimal, optimumSource: 'Moving AI .scen', scen: `version 1\n${rows[i].trim()}\n` };
  });
}

function openGrid(side: number, k: number): MapCase {
  const mapText = `type octile\nheight ${side}\nwidth ${side}\nmap\n${`${'.'.repeat(side)}\n`.repeat(side)}`;
  const n = side - 1;
  const h = side >> 1;
  const q = side >> 2;
  // Long queries in different directions (diagonal, shallow, steep, back).
  const ends: [number, number, number, number][] = [
    [0, 0, n, n],
    [0, h, n, q],
    [side / 3 | 0, 0, h, n],
    [n, 0, 0, side / 3 | 0],
  ];
  const queries = ends.slice(0, k).map(([sx, sy, gx, gy]) => {
    const optimal = octile(gx - sx, gy - sy);
    return {
      sx,
      sy,
      gx,
      gy,
      optimal,
      optimumSource: 'octile distance (no obstacles)',
      scen: `version 1\n0\topen${side}.map\t${side}\t${side}\t${sx}\t${sy}\t${gx}\t${gy}\t${optimal.toFixed(8)}\n`,
    };
  });
  return { key: 'open', name: `open ${side}×${side}`, mapText, queries };
}

/** The maps and queries of one size. */
export async function loadCases(size: Size): Promise<MapCase[]> {
  const plan = SIZES[size];
  const [arenaMap, arenaScen, mazeMap, mazeScen] = await Promise.all([
    fetchText('./maps/arena.map'),
    fetchText(arenaScenUrl),
    fetchText(mazeMapUrl),
    fetchText(mazeScenUrl),
  ]);
  return [
    { key: 'arena', name: 'arena (Moving AI)', mapText: arenaMap, queries: pickScenRows(arenaScen, plan.arenaRows, 1, 'arena.map.scen') },
    openGrid(plan.openSide, plan.openQueries),
    {
      key: 'maze',
      name: 'maze512-1-0 (Moving AI)',
      mapText: mazeMap,
      queries: pickScenRows(mazeScen, plan.mazeRows, plan.mazeSpan, 'maze512-1-0.map.scen'),
    },
  ];
}
