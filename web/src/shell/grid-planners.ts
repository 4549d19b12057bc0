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
  { name: 'theta-star', label: 'Theta* (any-angle)' },
  { name: 'dstar-lite', label: 'D* Lite (incremental)' },
  { name: 'safe-astar', label: 'Safe A* (Ge & Li)' },
];

export const GRID_PLANNER_NAMES = GRID_PLANNERS.map((p) => p.name);

export const plannerLabel = (name: string): string => GRID_PLANNERS.find((p) => p.name === name)?.label ?? name;
