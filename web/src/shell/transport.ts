// The Run / Step / Reset / Run-to-end buttons of the lock-step pages
// (compare, BARN): their labels and the body flags the e2e tests wait on,
// their clicks and their keys (Space, `.`, R, E), wired the same way.

import { installKeys } from './keys';

export interface TransportButtons {
  play: HTMLButtonElement;
  step: HTMLButtonElement;
  reset: HTMLButtonElement;
  instant: HTMLButtonElement;
}

/** The Run button and `body[data-playing]` (and `data-state=running` once
 *  it plays) for `playing`. */
export function showPlaying(play: HTMLButtonElement, body: HTMLElement, playing: boolean): void {
  play.textContent = playing ? '❚❚ Pause' : '▶ Run';
  play.dataset.playing = String(playing);
  body.dataset.playing = String(playing);
  if (playing) body.dataset.state = 'running';
}

/** The flags of a run that has ended: not playing, `data-state=done`,
 *  `data-done`. */
export function showDone(play: HTMLButtonElement, body: HTMLElement): void {
  showPlaying(play, body, false);
  body.dataset.state = 'done';
  body.dataset.done = 'true';
}

/** What the buttons do; `guard` shows what they throw. */
export interface TransportActions {
  toggle(): void;
  /** One control step, paused. */
  step(): void;
  reset(): void;
  instant(): void | Promise<void>;
}

export function wireTransport(b: TransportButtons, a: TransportActions, guard: (f: () => void | Promise<void>) => () => void): void {
  b.play.addEventListener('click', guard(a.toggle));
  b.step.addEventListener('click', guard(a.step));
  b.reset.addEventListener('click', guard(a.reset));
  b.instant.addEventListener('click', guard(a.instant));
  installKeys({
    ' ': () => {
      if (!b.play.disabled) b.play.click();
    },
    '.': () => b.step.click(),
    r: () => b.reset.click(),
    e: () => b.instant.click(),
  });
}
