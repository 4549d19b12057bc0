// What hovering a cell says about the search at the player's current step:
// its state, g, h, f, parent and the steps at which it was opened and
// expanded.

import type { CellInfo } from '../scene/search-player';

const num = (v: number) => (Number.isFinite(v) ? v.toFixed(3) : '—');

export function describeSearch(i: CellInfo | null): string {
  if (!i || (i.state === 'unseen' && i.openedAt === null && i.closedAt === null)) return i ? 'not reached yet' : '';
  const parts = [i.state === 'closed' ? 'expanded' : i.state === 'open' ? 'open' : 'unseen'];
  if (Number.isFinite(i.g)) parts.push(`g ${num(i.g)} h ${num(i.h)} f ${num(i.f)}`);
  if (i.parent) parts.push(`parent (${i.parent[0]}, ${i.parent[1]})`);
  if (i.openedAt !== null) parts.push(`opened at step ${i.openedAt}`);
  if (i.closedAt !== null) parts.push(`expanded at step ${i.closedAt}`);
  return parts.join(' · ');
}
