// The Speed select of the simulation pages: its value is the clock's
// simulated seconds per real second, echoed in its output. Whatever sets
// the select (the user, a URL parameter, a gallery link) goes through its
// input event, so the clock and the echo never disagree.

import type { SimClock } from './sim-clock';

/** Wires `select` to `clock`; returns a setter for the pages' own uses. */
export function bindSpeed(select: HTMLSelectElement, out: HTMLOutputElement, clock: SimClock): (x: number) => void {
  select.addEventListener('input', () => {
    clock.speed = Number(select.value) || 1;
    out.textContent = `${clock.speed}×`;
  });
  return (x) => {
    select.value = String(x);
    select.dispatchEvent(new Event('input'));
  };
}
