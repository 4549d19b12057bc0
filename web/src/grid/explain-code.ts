// Short pseudo-code of each grid planner for the explain panel, one entry
// per line with the role of the search event it belongs to: `start` (the
// first cell enters the open list), `expand` (a cell is taken off it),
// `open` (a neighbour is opened or improved), `line` (a straight-line
// check), `post` (key points / Bottom-Up after the search). The panel
// highlights the line of the current event's role.

export type Role = 'start' | 'expand' | 'open' | 'line' | 'post';
export type CodeLine = [text: string, role?: Role];

const ASTAR: CodeLine[] = [
  ['open ← {start};  g(start) ← 0', 'start'],
  ['while open is not empty:'],
  ['  n ← take the open cell with the lowest f = g + w·h', 'expand'],
  ['  if n = goal: return the path back through the parents'],
  ['  for each neighbour m of n (not expanded):'],
  ['    if g(n) + cost(n, m) < g(m):'],
  ['      g(m) ← g(n) + cost(n, m);  parent(m) ← n', 'open'],
  ['      put m in open with f(m) = g(m) + w·h(m)', 'open'],
  ['return "no path"'],
];

const CODE: Record<string, CodeLine[]> = {
  astar: ASTAR,
  dijkstra: [
    ['open ← {start};  g(start) ← 0', 'start'],
    ['while open is not empty:'],
    ['  n ← take the open cell with the lowest g (no h: f = g)', 'expand'],
    ['  if n = goal: return the path back through the parents'],
    ['  for each neighbour m of n (not expanded):'],
    ['    if g(n) + cost(n, m) < g(m):'],
    ['      g(m) ← g(n) + cost(n, m);  parent(m) ← n', 'open'],
    ['      put m in open', 'open'],
    ['return "no path"'],
  ],
  bfs: [
    ['queue ← [start];  mark start as reached', 'start'],
    ['while the queue is not empty:'],
    ['  n ← take the FIRST cell of the queue (no f, no h)', 'expand'],
    ['  if n = goal: return the path back through the parents'],
    ['  for each neighbour m of n not reached yet:'],
    ['    mark m reached;  parent(m) ← n', 'open'],
    ['    append m to the END of the queue', 'open'],
    ['return "no path"'],
  ],
  greedy: [
    ['open ← {start}', 'start'],
    ['while open is not empty:'],
    ['  n ← take the open cell with the lowest h (g is ignored)', 'expand'],
    ['  if n = goal: return the path back through the parents'],
    ['  for each neighbour m of n not reached yet:'],
    ['    parent(m) ← n', 'open'],
    ['    put m in open with key h(m)', 'open'],
    ['return "no path"'],
  ],
  'bidirectional-astar': [
    ['open_f ← {start};  open_b ← {goal};  μ ← ∞', 'start'],
    ['p(m) ← (h(m, goal) − h(m, start)) / 2;  key_f = g_f + p,  key_b = g_b − p'],
    ['while min key_f + min key_b < μ  (both lists non-empty):'],
    ['  side ← the list with the smaller least key'],
    ['  n ← take its open cell with the lowest key;  μ ← min(μ, g_f(n) + g_b(n))', 'expand'],
    ['  for each neighbour m of n (not expanded on this side):'],
    ['    if g(n) + cost(n, m) < g_side(m):'],
    ['      g_side(m) ← g(n) + cost(n, m);  put m in that list', 'open'],
    ['      μ ← min(μ, g_f(m) + g_b(m))', 'open'],
    ['return the path through the best meeting cell'],
  ],
  'ida-star': [
    ['bound ← h(start)'],
    ['loop:'],
    ['  path ← [start]  (a new round, from scratch)', 'start'],
    ['  depth-first: expand n, the last cell of the path', 'expand'],
    ['    for each neighbour m of n:'],
    ['      if g(m) + h(m) > bound: remember the smallest such f; skip it'],
    ['      if m was reached this round at no higher g: skip it'],
    ['      push m on the path', 'open'],
    ['      if m = goal: return the path'],
    ['    when n has no neighbour left: pop it (backtrack)'],
    ['  bound ← the smallest f seen above the bound'],
  ],
  jps: [
    ['open ← {start};  g(start) ← 0', 'start'],
    ['while open is not empty:'],
    ['  n ← take the open cell with the lowest f = g + h', 'expand'],
    ['  if n = goal: return the jump points joined by straight runs'],
    ['  for each direction d the move into n leaves open (pruned):'],
    ['    scan from n along d to a wall or a jump point j', 'line'],
    ['    if j found and g(n) + |n j| < g(j):'],
    ['      g(j) ← g(n) + |n j|;  parent(j) ← n;  put j in open', 'open'],
    ['return "no path"'],
  ],
  'jps-plus': [
    ['table ← every cell\'s jump distance in each of the 8 directions (once per map)', 'start'],
    ['open ← {start};  g(start) ← 0', 'start'],
    ['while open is not empty:'],
    ['  n ← take the open cell with the lowest f = g + h', 'expand'],
    ['  if n = goal: return the jump points joined by straight runs'],
    ['  for each direction d the move into n leaves open (pruned):'],
    ['    j ← the cell table(n, d) steps away (or the goal, if nearer)', 'line'],
    ['    if j is a jump point and g(n) + |n j| < g(j):'],
    ['      g(j) ← g(n) + |n j|;  parent(j) ← n;  put j in open', 'open'],
    ['return "no path"'],
  ],
  'theta-star': [
    ['open ← {start};  g(start) ← 0', 'start'],
    ['while open is not empty:'],
    ['  n ← take the open cell with the lowest f = g + h (Euclidean)', 'expand'],
    ['  if n = goal: return the path back through the parents'],
    ['  for each neighbour m of n (not expanded):'],
    ['    if parent(n) sees m (line of sight):', 'line'],
    ['      candidate: parent(n) → m,  g = g(parent(n)) + |parent(n) m|'],
    ['    else candidate: n → m,  g = g(n) + cost(n, m)'],
    ['    if the candidate g < g(m): take it; put m in open', 'open'],
    ['return "no path"'],
  ],
  'dstar-lite': [
    ['rhs(goal) ← 0;  U ← {goal}  (it searches from the goal)', 'start'],
    ['while key(top of U) < key(start) or start is inconsistent:'],
    ['  u ← take from U the lowest key [min(g, rhs) + h + k_m, min(g, rhs)]', 'expand'],
    ['  if g(u) > rhs(u): g(u) ← rhs(u)  (settle it)'],
    ['  else: g(u) ← ∞  (and update u itself)'],
    ['  for each neighbour s of u:'],
    ['    rhs(s) ← min over its neighbours s′ of cost(s, s′) + g(s′)'],
    ['    if g(s) ≠ rhs(s): put s in U with its key (shown: rhs, h)', 'open'],
    ['    else: take s out of U (not recorded)'],
    ['after an edit: k_m += h(old start, new start); update the changed cells'],
  ],
  'safe-astar': [
    ['open ← {start};  g(start) ← 0', 'start'],
    ['while open is not empty:'],
    ['  n ← take the open cell with the lowest f = g + h + ε·L(n)', 'expand'],
    ['      (admissible variant: f = g + h, the ε·L is in g)'],
    ['  if n = goal: return the path back through the parents'],
    ['  for each move n → m of the 5×5 block over free cells only:'],
    ['    if g(n) + |n m| (+ ε·L(m), admissible) < g(m):'],
    ['      g(m) ← that;  parent(m) ← n;  put m in open', 'open'],
    ['return "no path"'],
  ],
};

/** After the search: the key points / Bottom-Up segment checks. */
const POST: CodeLine = ['after the search: key points / Bottom-Up check straight segments of the path', 'post'];

/** The pseudo-code of `algorithm`, with the post-processing line when
 *  key points or Bottom-Up run. */
export function pseudoCode(algorithm: string, post: boolean): CodeLine[] {
  const code = CODE[algorithm] ?? ASTAR;
  return post ? [...code, POST] : code;
}

/** Every algorithm with its own pseudo-code (the tests check the menu's). */
export const CODED = Object.keys(CODE);
