// The grid page's editing tools and the hint each shows.

export type Tool = 'start' | 'goal' | 'wall' | 'erase' | 'cost';

export const TOOL_HINTS: Record<Tool, string> = {
  start: 'Click a free cell to place the start.',
  goal: 'Click a free cell to place the goal.',
  wall: 'Drag on the map to paint walls.',
  erase: 'Drag on the map to erase walls and weights.',
  cost: 'Drag on the map to paint cells of the chosen weight (a move into one costs its length × the weight; 1 erases).',
};
