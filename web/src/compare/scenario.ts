// The scenario the compare page runs every planner on: its JSON, map files
// and the `set=path=value` edits from the URL (as `planlab run --set`),
// checked by building it once, and its card (description, seed, edits).

import { SimHandle, editScenario } from '../../pkg/planlab_wasm.js';
import { recipeJson } from '../shell/runlink';
import { el, messageOf } from '../shell/dom';
import type { MapFiles } from '../shell/scenario-files';

export class ComparedScenario {
  text = '';
  /** The preset's file name ('' for a picked file). */
  file = '';
  files: MapFiles = {};
  /** Edits applied for every planner; dropped when another scenario opens. */
  edits: [string, string][] = [];
  private readonly ui = { description: el('scenario-description'), seed: el('seed'), edits: el('edits') };

  /** Takes a scenario with `newEdits` applied: checked by building it with
   *  its own planner first, so a broken file is reported as such (thrown);
   *  edits that break it are dropped, and the returned problems say so. */
  set(text: string, file: string, label: string, files: MapFiles, newEdits: [string, string][] = []): string[] {
    const problems: string[] = [];
    let kept = newEdits;
    if (kept.length) {
      try {
        SimHandle.fromScenario(editScenario(text, recipeJson(null, kept)), files).free();
      } catch (e) {
        problems.push(`edits ${kept.map(([p, v]) => `${p}=${v}`).join(', ')} not applied: ${messageOf(e)}`);
        kept = [];
      }
    }
    if (!kept.length) SimHandle.fromScenario(text, files).free();
    this.text = text;
    this.file = file;
    this.files = files;
    this.edits = kept;
    const ui = this.ui;
    ui.edits.textContent = kept.length ? kept.map(([p, v]) => `${p}=${v}`).join(', ') : '—';
    ui.edits.title = ui.edits.textContent;
    try {
      const s = JSON.parse(text) as { name?: string; description?: string; seed?: number };
      ui.description.textContent = s.description || s.name || label;
      ui.description.title = s.description ?? '';
      ui.seed.textContent = String(s.seed ?? 0);
    } catch {
      ui.description.textContent = label;
    }
    return problems;
  }

  /** The scenario's own planner (null when it names none or is not JSON). */
  ownPlanner(): string | null {
    try {
      const n = (JSON.parse(this.text) as { local_planner?: { name?: unknown } }).local_planner?.name;
      return typeof n === 'string' ? n : null;
    } catch {
      return null;
    }
  }

  /** A SimHandle of the scenario with `planner` swapped in and the edits
   *  applied (the CLI's `--planner NAME`, then every `--set`). */
  build(planner: string): SimHandle {
    return SimHandle.fromScenario(editScenario(this.text, recipeJson(planner, this.edits)), this.files);
  }
}
