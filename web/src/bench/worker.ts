// The bench page's worker: runs planlab (its own instance of the grid wasm
// module) and PathFinding.js on one thread, off the page's, and posts
// progress and rows back. PathFinding.js (CommonJS) is bundled here only:
// in the page's graph its interop helpers would become a chunk that every
// other page loads too.

import init from '../../pkg-grid/planlab_wasm.js';
import { runVersus } from './versus';
import type { RunRequest, WorkerMessage } from './shared';

const post = (m: WorkerMessage) => self.postMessage(m);

self.onmessage = async (e: MessageEvent<RunRequest>) => {
  try {
    await init();
    const rows = await runVersus(
      e.data.cases,
      e.data.reps,
      (message) => post({ type: 'progress', message }),
      (row) => post({ type: 'row', row }),
    );
    post({ type: 'done', rows });
  } catch (err) {
    post({ type: 'error', message: err instanceof Error ? err.message : String(err) });
  }
};
