// How the robot page opens a scenario: a preset of the site, and at start
// the link it was opened with (a share link `#s=…`, a variant link of the
// reproduce registry, a gallery run link with its planner and `--set`
// edits and `run=1`) or else the first preset.

import presets from 'virtual:robot-presets';
import { recipeJson, runParams, variantParams } from '../shell/runlink';
import { loadVariant } from '../shell/variant';
import { editScenario, rosImageName } from '../../pkg/planlab_wasm.js';
import { loadPresetFiles, mapFilesOf, type MapFiles } from '../shell/scenario-files';
import { messageOf } from '../shell/dom';

export interface OpenHost {
  /** Loads scenario JSON as a fresh episode (throws the core's error). */
  load(text: string, label: string, files: MapFiles): void;
  /** A share link in the URL hash, loaded; false when there is none. */
  loadFromHash(): Promise<boolean>;
  preset: HTMLSelectElement;
  /** Starts play. */
  play(): void;
  showError(text: string): void;
}

/** Preset `file` of the site, its text passed through `edit`. */
export async function loadPreset(host: OpenHost, file: string, edit: (text: string) => string = (t) => t): Promise<void> {
  try {
    const { text, files } = await loadPresetFiles(file, rosImageName);
    host.load(edit(text), file, files);
  } catch (e) {
    throw new Error(`${file}: ${messageOf(e)}`);
  }
}

/** Opens what the page's URL asks for (see the file comment). */
export async function openFirst(host: OpenHost): Promise<void> {
  // A gallery link: preset, planner and `--set` edits of a reproduce run, and `run=1`.
  const link = runParams();
  const q = link.scenario;
  const first = q && presets.some((p) => p.file === q) ? q : presets[0]?.file;
  if (!first) throw new Error('no robot presets (assets/scenarios/*.json with a local_planner)');
  host.preset.value = first;
  // A share link (#s=…) opens its scenario instead of the first preset.
  let shared: unknown = null;
  try {
    if (await host.loadFromHash()) return;
  } catch (e) {
    shared = e;
  }
  // A variant link: the registry's tree of that run on that variant (its
  // planner and edits included), instead of the preset; a bad one (unknown
  // id or run, k too large) shows the core's message over the preset.
  let variantError: unknown = null;
  try {
    const variant = variantParams();
    if (variant) {
      const v = await loadVariant(variant);
      const label = `${variant.exp} variant ${variant.k} (${variant.as})`;
      host.load(v.text, label, await mapFilesOf(v.text, new URL(`scenarios/${first}`, document.baseURI), rosImageName));
      document.body.dataset.variant = String(variant.k);
      if (link.run) host.play();
      return;
    }
  } catch (e) {
    variantError = e;
  }
  await loadPreset(host, first, first === q ? (t) => editScenario(t, recipeJson(link.planner, link.set)) : undefined);
  if (variantError !== null) host.showError(`Could not open the variant: ${messageOf(variantError)}`);
  else if (first === q && link.run) host.play();
  if (shared !== null) host.showError(`Could not open the shared link: ${messageOf(shared)}`);
}
