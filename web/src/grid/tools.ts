// The grid page's editing tools and the hint each shows.

export type Tool = 'start' | 'goal' | 'wall' | 'erase';

export const TOOL_HINTS: Record<Tool, string> = {
  start: 'Click a free cell to place the start.',
  goal: 'Click a free cell to place the goal.',
  wall: 'Drag on the map to paint walls.',
  erase: 'Drag on the map to erase walls.',
};
