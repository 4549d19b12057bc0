// The Run card's layer checkboxes (fan, global path, trail, LiDAR, fog of
// war): each switches its layer of the view; the fan's also stops the
// SimHandle recording rollouts, which makes stepping faster.

import type { SimHandle } from '../../pkg/planlab_wasm.js';
import type { Scene } from '../scene/view';
import { el, type ErrorBanner } from '../shell/dom';

const BOXES = [
  ['show-fan', 'fan'],
  ['show-path', 'path'],
  ['show-trail', 'trail'],
  ['show-lidar', 'lidar'],
  ['show-fog', 'fog'],
] as const;

export interface ToggleHost {
  sim(): SimHandle | null;
  scene(): Scene;
  /** Pull and repaint after a switch. */
  refresh(): void;
  guard: ErrorBanner['guard'];
}

export function installToggles(host: ToggleHost): void {
  for (const [id, key] of BOXES) {
    const box = el<HTMLInputElement>(id);
    box.addEventListener(
      'change',
      host.guard(() => {
        host.scene().show[key] = box.checked;
        if (key === 'fan') host.sim()?.setRecordRollouts(box.checked);
        host.refresh();
      }),
    );
  }
}
