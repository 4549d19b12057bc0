// The race page's help: how lanes advance and what the table compares.

import type { HelpContent } from '../shell/help';
import { gridPlannerHelp, type CorePlanner } from '../shell/help-content';

export function raceHelp(core: CorePlanner[] = []): HelpContent {
  return {
    page: 'race',
    intro:
      'The race plans one query on one map with 2–4 grid planners and plays their searches side by side. Lanes advance in step: every frame each lane plays the same number of search events (opens, expansions, line checks), so the lane that needs fewer events to find its path finishes first. The table compares expanded cells, the open set left at the end, events, path cost and path cells; the winners are the fewest expanded cells and the lowest cost (an optimal planner always ties on cost).',
    planners: gridPlannerHelp(core),
    params: [
      { name: 'Events per frame', unit: 'events', default: 16, doc: 'The budget every lane plays per animation frame.' },
      { name: 'Diagonal moves', unit: '', default: 'no corner cutting', doc: 'The move rule of every lane; a planner that refuses it says so in its lane.' },
    ],
    shortcuts: [
      { keys: 'Space', action: 'race (from the start)' },
      { keys: 'F', action: 'finish: every lane played to its end' },
      { keys: 'click', action: 'move the start (every lane replans)' },
      { keys: 'Shift + click', action: 'move the goal' },
      { keys: 'wheel / right drag', action: 'zoom / pan every lane' },
    ],
  };
}
