// The robot page's Files menu. Open: scenario JSON (with the map files it
// refers to), a ROS map_server map (.yaml + its .pgm), a Moving AI .map —
// from the file button or dropped on the canvas; bare maps get default
// start/goal from the core. Save: the episode in force as self-contained
// scenario JSON (read from the SimHandle, so every edit is in it), the
// trace and the metrics as CSV, the canvas as PNG, the scene as SVG. Share:
// a link carrying the whole scenario in its hash, loaded on boot.
// Every failure ends in the page's error banner with the core's message.

import { MapHandle, rosImageName, scenarioForMap, type SimHandle } from '../../pkg/planlab_wasm.js';
import { decodeScenarioHash, shareLink } from '../shell/share';
import { checkSizes, rosImageFile } from '../shell/scenario-files';
import { showOpened } from '../shell/preset-select';
import { sceneSvg } from './svg';
import type { MapInfo, Scene } from '../scene/view';
import './files.css';
import { messageOf } from '../shell/dom';
import { download, onFileDrop } from '../shell/download';

/** What the page lends the Files menu. */
export interface FilesHost {
  /** The episode in force. */
  sim(): SimHandle | null;
  /** Loads scenario JSON as a fresh episode (throws the core's error). */
  load(text: string, label: string, files?: Record<string, Uint8Array>): void;
  /** What the canvas shows now. */
  scene(): Scene;
  canvas: HTMLCanvasElement;
  showError(text: string): void;
  clearError(): void;
}


const lower = (f: { name: string }) => f.name.toLowerCase();
const stem = (name: string) => name.replace(/^.*[\\/]/, '').replace(/\.[^.]*$/, '');

/** A file name made of the scenario's name: letters, digits, - and _. */
export function slug(name: string): string {
  const s = name
    .normalize('NFKD')
    .replace(/[\u0300-\u036f]/g, '')
    .replace(/[^A-Za-z0-9_-]+/g, '-')
    .replace(/^-+|-+$/g, '')
    .toLowerCase();
  return s.slice(0, 60) || 'scenario';
}


/** A bare map as a scenario (default start/goal from the core); frees `map`. */
function bareMap(map: MapHandle, label: string): { text: string; label: string; files: Record<string, Uint8Array> } {
  try {
    return { text: scenarioForMap(map, stem(label)), label, files: {} };
  } catch (e) {
    throw new Error(`${label}: ${messageOf(e)}`);
  } finally {
    map.free();
  }
}

/** The scenario JSON, label and map files a set of picked/dropped files
 *  stands for. Throws with a message saying what to open instead. */
export async function scenarioFromFiles(picked: File[]): Promise<{ text: string; label: string; files: Record<string, Uint8Array> }> {
  if (!picked.length) throw new Error('no file to open');
  checkSizes(picked);
  const bytes = async (f: File) => new Uint8Array(await f.arrayBuffer());
  const json = picked.find((f) => lower(f).endsWith('.json'));
  if (json) {
    // The map files it refers to may be among the others.
    const files: Record<string, Uint8Array> = {};
    for (const x of picked) if (x !== json) files[x.name] = await bytes(x);
    return { text: await json.text(), label: json.name, files };
  }
  const yaml = picked.find((f) => /\.ya?ml$/.test(lower(f)));
  if (yaml) {
    const text = await yaml.text();
    let image: string;
    try {
      image = rosImageName(text);
    } catch (e) {
      throw new Error(`${yaml.name}: ${messageOf(e)}`);
    }
    const pgm = rosImageFile(yaml.name, image, picked.filter((f) => lower(f).endsWith('.pgm')));
    let map: MapHandle;
    try {
      map = MapHandle.fromRos(text, await bytes(pgm));
    } catch (e) {
      throw new Error(`${yaml.name} + ${pgm.name}: ${messageOf(e)}`);
    }
    return bareMap(map, yaml.name);
  }
  const mai = picked.find((f) => lower(f).endsWith('.map'));
  if (mai) {
    let map: MapHandle;
    try {
      map = MapHandle.fromMovingAi(await mai.text());
    } catch (e) {
      throw new Error(`${mai.name}: ${messageOf(e)}`);
    }
    return bareMap(map, mai.name);
  }
  if (picked.some((f) => lower(f).endsWith('.pgm'))) {
    throw new Error('A .pgm image alone is not a map: open it together with its ROS map_server .yaml.');
  }
  throw new Error(
    `Cannot open ${picked.map((f) => f.name).join(', ')}: open a scenario .json, a ROS map (.yaml + .pgm) or a Moving AI .map.`,
  );
}

/** The Files menu: wires the open button, drop target, save and share
 *  buttons of robot.html. */
export class FilesMenu {
  private host: FilesHost;
  private name = 'scenario';
  private description = '';

  constructor(host: FilesHost) {
    this.host = host;
    const byId = <T extends HTMLElement>(id: string) => document.getElementById(id) as T | null;
    const on = (id: string, fn: () => void | Promise<void>) =>
      byId(id)?.addEventListener('click', () => void this.run(fn));
    on('save-json', () => this.saveJson());
    on('save-trace', () => this.saveTrace());
    on('save-metrics', () => this.saveMetrics());
    on('save-png', () => this.savePng());
    on('save-svg', () => this.saveSvg());
    on('save-mcap', () => this.saveMcap());
    on('share-link', () => this.copyLink());
    const input = byId<HTMLInputElement>('file-input');
    input?.addEventListener('change', () => {
      const picked = Array.from(input.files ?? []);
      input.value = '';
      if (picked.length) void this.run(() => this.open(picked));
    });
    onFileDrop(byId('canvas-wrap') ?? host.canvas, (picked) => void this.run(() => this.open(picked)));
    // A share link pasted into this tab changes only the hash.
    window.addEventListener('hashchange', () => void this.run(() => this.loadFromHash().then(() => undefined)));
  }

  /** Remembers the loaded scenario's name and description (for saving). */
  noteLoaded(text: string, label: string): void {
    try {
      const s = JSON.parse(text) as { name?: unknown; description?: unknown };
      this.name = typeof s.name === 'string' && s.name ? s.name : stem(label);
      this.description = typeof s.description === 'string' ? s.description : '';
    } catch {
      this.name = stem(label);
      this.description = '';
    }
  }

  private async run(fn: () => void | Promise<void>): Promise<void> {
    try {
      await fn();
    } catch (e) {
      this.host.showError(messageOf(e));
    }
  }

  private sim(): SimHandle {
    const s = this.host.sim();
    if (!s) throw new Error('no scenario loaded');
    return s;
  }

  /** Opens picked or dropped files. */
  async open(picked: File[]): Promise<void> {
    const { text, label, files } = await scenarioFromFiles(picked);
    try {
      this.host.load(text, label, files);
    } catch (e) {
      throw new Error(`${label}: ${messageOf(e)}`);
    }
    this.noteLoaded(text, label);
    showOpened(document.getElementById('preset') as HTMLSelectElement | null, label);
    document.body.dataset.opened = label;
  }

  /** The episode in force as scenario JSON (what Save and Share use). */
  scenarioJson(): string {
    const sim = this.sim();
    const json = sim.scenarioJson(this.name, this.description);
    this.noteLiveEdits(sim.liveEdits);
    return json;
  }

  /** A new run (load, reset, edit restart): the last save's note is stale. */
  static forgetNote(): void {
    const note = document.getElementById('files-note');
    if (note) note.hidden = true;
  }

  /** A scenario file has no clock for edits: it holds the goal, movers and
   *  planner as they are now, from t = 0. Says so when this run was edited
   *  while it went on, since the file's run then differs from it. */
  private noteLiveEdits(n: number): void {
    const note = document.getElementById('files-note');
    if (!note) return;
    note.hidden = n === 0;
    note.textContent = n
      ? `${n} edit${n === 1 ? '' : 's'} made while this run went on (t > 0) ${n === 1 ? 'is' : 'are'} saved as in force from t = 0, so the saved scenario's run differs from this one (edits made before Play reproduce it exactly).`
      : '';
    document.body.dataset.liveEdits = String(n);
  }

  private file(ext: string): string {
    return `${slug(this.name)}${ext}`;
  }

  saveJson(): void {
    download(this.file('.json'), this.scenarioJson(), 'application/json');
    this.host.clearError();
  }

  saveTrace(): void {
    download(this.file('-trace.csv'), this.sim().traceCsv(), 'text/csv');
  }

  saveMetrics(): void {
    download(this.file('-metrics.csv'), this.sim().metricsCsv(), 'text/csv');
  }

  async savePng(): Promise<void> {
    const blob = await new Promise<Blob | null>((res) => this.host.canvas.toBlob(res, 'image/png'));
    if (!blob) throw new Error('the canvas could not be encoded as PNG');
    download(this.file('.png'), blob);
  }

  saveSvg(): void {
    const sim = this.sim();
    const map = sim.map();
    let info: MapInfo;
    try {
      const o = map.origin();
      info = { width: map.width, height: map.height, resolution: map.resolution, originX: o[0], originY: o[1], cells: map.cells() };
    } finally {
      map.free();
    }
    download(this.file('.svg'), sceneSvg(info, this.host.scene(), this.name, sim.time), 'image/svg+xml');
  }

  /** The scenario in force, run from its start to its end, as an MCAP file
   *  (the on-demand module's writer: it is not in the page's first load). */
  async saveMcap(): Promise<void> {
    const text = this.scenarioJson();
    const m = await import('../../pkg-reproduce/planlab_wasm_reproduce.js');
    await m.default();
    const bytes = m.scenarioMcap(text);
    // A copy backed by a plain ArrayBuffer, as Blob's type asks.
    download(this.file('.mcap'), new Blob([new Uint8Array(bytes)], { type: 'application/octet-stream' }));
    this.host.clearError();
  }

  /** Puts the share link in the page (and on the clipboard when allowed). */
  async copyLink(): Promise<void> {
    const out = document.getElementById('share-url') as HTMLInputElement | null;
    let link: string;
    try {
      link = await shareLink(this.scenarioJson());
    } catch (e) {
      if (out) {
        out.value = '';
        out.hidden = true;
      }
      throw e;
    }
    if (out) {
      out.value = link;
      out.hidden = false;
      out.select();
    }
    let copied = false;
    try {
      await navigator.clipboard?.writeText(link);
      copied = !!navigator.clipboard;
    } catch {
      // No permission (or no clipboard): the link is in the field to copy.
    }
    const hint = document.getElementById('hint');
    if (hint) {
      hint.textContent = copied
        ? `Share link copied (${(link.length / 1024).toFixed(1)} KB): it reproduces this scenario.`
        : 'Share link ready below the Files buttons: copy it from there.';
    }
    document.body.dataset.shareLength = String(link.length);
    this.host.clearError();
  }

  /** Loads the scenario in the location hash, if any; true when it did. */
  async loadFromHash(): Promise<boolean> {
    const text = await decodeScenarioHash(location.hash);
    if (text === null) return false;
    this.host.load(text, 'shared link');
    this.noteLoaded(text, 'shared link');
    showOpened(document.getElementById('preset') as HTMLSelectElement | null, 'a shared link');
    document.body.dataset.opened = 'shared link';
    return true;
  }
}
