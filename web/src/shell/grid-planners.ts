// The core's grid planners (`Algorithm::ALL`) by their JSON names, with the
// labels the menus show.

export const GRID_PLANNERS: { name: string; label: string }[] = [
  { name: 'astar', label: 'A*' },
  { name: 'dijkstra', label: 'Dijkstra' },
  { name: 'bfs', label: 'Breadth-first search' },
  { name: 'greedy', label: 'Greedy best-first' },
  { name: 'bidirectional-astar', label: 'Bidirectional A*' },
  { name: 'ida-star', label: 'IDA*' },
  { name: 'jps', label: 'Jump Point Search' },
  { name: 'jps-plus', label: 'JPS+ (precomputed jumps)' },
  { name: 'theta-star', label: 'Theta* (any-angle)' },
  { name: 'dstar-lite', label: 'D* Lite (incremental)' },
  { name: 'safe-astar', label: 'Safe A* (Ge & Li)' },
];

export const GRID_PLANNER_NAMES = GRID_PLANNERS.map((p) => p.name);

export const plannerLabel = (name: string): string => GRID_PLANNERS.find((p) => p.name === name)?.label ?? name;

/**
 * Why a path's cost cannot be set beside 8-connected A*'s, when the
 * planner's moves are other than the 8 neighbours: safe A*'s 24-cell
 * neighbourhood (knight-like moves of length √5 cut corners of the 8-cell
 * lattice, so its cost can be lower than the "optimal" A*'s), Theta*'s
 * any-angle segments, 4-connected moves. `[short, long]`, or null.
 */
export function movesNote(opts: Record<string, unknown>): [string, string] | null {
  const algo = String(opts.algorithm);
  if (algo === 'safe-astar') {
    const n = Number((opts.safe as Record<string, unknown> | undefined)?.neighbourhood ?? 24);
    if (n === 24)
      return [
        '24-neighbourhood moves: not comparable with A*',
        "safe A* moves to any of the 24 cells of the 5×5 block around a cell (knight-like moves of length √5 too), so its cost can be lower than 8-connected A*'s optimum: the costs are not comparable",
      ];
    if (n === 4) return ['4-neighbourhood moves: not comparable with A*', "safe A* moves to the 4 side neighbours only, so its cost is not comparable with 8-connected A*'s"];
    return null;
  }
  if (algo === 'theta-star')
    return ['any-angle path: not comparable with A*', "Theta*'s segments run at any angle, so its cost can be lower than 8-connected A*'s optimum: the costs are not comparable"];
  if (opts.diagonal === 'never')
    return ['4-connected moves: not comparable with A*', "with diagonal moves off the moves are 4-connected, so the cost is not comparable with 8-connected A*'s"];
  return null;
}
