// The grid page's maps: the presets (a Moving AI map, the TurtleBot3 ROS
// map, a scenario, an empty grid of large cells to draw on), a scenario with its map and endpoints, and picked files
// (one `.map`, a ROS `.yaml` + `.pgm`, an ASCII `.txt` or a scenario
// `.json` with the map files it refers to). The wasm readers parse them;
// errors name the file.

import { MapHandle, ScenarioHandle, rosImageName } from '../../pkg-grid/planlab_wasm.js';
import { checkSizes, fetchBytes, fetchText, rosImageFile } from '../shell/scenario-files';
import { messageOf } from '../shell/dom';
import type { Cell } from './cells';

interface Preset {
  name: string;
  kind: 'movingai' | 'ros' | 'scenario' | 'empty';
  files: string[];
  /** Endpoints to place (a scenario brings its own). */
  start?: Cell;
  goal?: Cell;
}

const PRESETS: Record<string, Preset> = {
  // Few cells, so each is large on screen (a class draws walls on it).
  empty: {
    name: 'empty 30×18',
    kind: 'empty',
    files: [],
    start: [3, 9],
    goal: [26, 9],
  },
  arena: {
    name: 'arena.map',
    kind: 'movingai',
    files: ['maps/arena.map'],
    start: [1, 45],
    goal: [47, 9],
  },
  turtlebot3: {
    name: 'turtlebot3.yaml',
    kind: 'ros',
    files: ['maps/turtlebot3.yaml', 'maps/turtlebot3.pgm'],
    start: [152, 182],
    goal: [235, 215],
  },
  'grid-demo': {
    name: 'grid-demo.json',
    kind: 'scenario',
    files: ['scenarios/grid-demo.json'],
  },
};

export interface MapHost {
  /** Shows map `m` with endpoints (null: to be placed). */
  install(m: MapHandle, name: string, start: Cell | null, goal: Cell | null): void;
  /** Sets the planner controls from options. */
  applyOptions(o: Record<string, unknown>): void;
  /** The core's default options. */
  defaults(): Record<string, unknown>;
}

const site = (path: string) => new URL(path, document.baseURI);

export async function loadPreset(host: MapHost, key: string): Promise<void> {
  const p = PRESETS[key];
  if (!p) throw new Error(`unknown preset ${key}`);
  if (p.kind === 'scenario') {
    installScenario(host, ScenarioHandle.fromJson(await fetchText(site(p.files[0]))), p.name, {});
    return;
  }
  let m: MapHandle;
  if (p.kind === 'empty') {
    m = MapHandle.empty(30, 18);
  } else if (p.kind === 'movingai') {
    m = MapHandle.fromMovingAi(await fetchText(site(p.files[0])));
  } else {
    const [yaml, pgm] = await Promise.all([fetchText(site(p.files[0])), fetchBytes(site(p.files[1]))]);
    m = MapHandle.fromRos(yaml, pgm);
  }
  host.install(m, p.name, p.start ?? null, p.goal ?? null);
}

/**
 * Installs a scenario: its map (inline, or a referenced file looked up in
 * `files` by name), endpoints and planner options (`extra` over its own).
 */
export function installScenario(
  host: MapHost,
  sc: ScenarioHandle,
  name: string,
  files: Record<string, Uint8Array>,
  extra: Record<string, unknown> = {},
): void {
  try {
    const m = sc.loadMap(files);
    host.applyOptions({ ...host.defaults(), ...(sc.plannerOptions() as Record<string, unknown>), ...extra });
    const s = sc.start();
    const g = sc.goal();
    host.install(m, sc.name ? `${sc.name} (${name})` : name, [s[0], s[1]], [g[0], g[1]]);
  } finally {
    sc.free();
  }
}

const ext = (f: File) => f.name.toLowerCase().split('.').pop() ?? '';

/** Reads picked files: one `.map`, a ROS `.yaml` + `.pgm`, a `.txt` or a
 *  scenario `.json` (+ its map files); false when nothing was picked. */
export async function loadFiles(host: MapHost, list: FileList | File[] | null): Promise<boolean> {
  const files = Array.from(list ?? []);
  if (!files.length) return false;
  checkSizes(files);
  const yaml = files.find((f) => ext(f) === 'yaml' || ext(f) === 'yml');
  const pgms = files.filter((f) => ext(f) === 'pgm');
  const movingai = files.find((f) => ext(f) === 'map');
  const ascii = files.find((f) => ext(f) === 'txt');
  const json = files.find((f) => ext(f) === 'json');
  const named = async <T>(name: string, f: () => T | Promise<T>): Promise<T> => {
    try {
      return await f();
    } catch (e) {
      throw new Error(`${name}: ${messageOf(e)}`);
    }
  };
  if (json) {
    // A scenario; the map files it references may be among the others.
    const bytes: Record<string, Uint8Array> = {};
    for (const f of files) if (f !== json) bytes[f.name] = new Uint8Array(await f.arrayBuffer());
    const text = await json.text();
    await named(json.name, () => installScenario(host, ScenarioHandle.fromJson(text), json.name, bytes));
    return true;
  }
  let m: MapHandle;
  let name: string;
  if (yaml) {
    name = yaml.name;
    const yamlText = await yaml.text();
    const image = await named(yaml.name, () => rosImageName(yamlText));
    const pgm = rosImageFile(yaml.name, image, pgms);
    const bytes = new Uint8Array(await pgm.arrayBuffer());
    m = await named(`${yaml.name} + ${pgm.name}`, () => MapHandle.fromRos(yamlText, bytes));
  } else if (movingai) {
    name = movingai.name;
    const text = await movingai.text();
    m = await named(movingai.name, () => MapHandle.fromMovingAi(text));
  } else if (ascii) {
    name = ascii.name;
    const text = await ascii.text();
    m = await named(ascii.name, () => MapHandle.fromAscii(text));
  } else if (pgms.length) {
    throw new Error(`${pgms[0].name} is only the image of a ROS map: select it together with its .yaml (resolution, origin, thresholds).`);
  } else {
    throw new Error(
      `Cannot open ${files.map((f) => f.name).join(', ')}: expected a Moving AI .map, a ROS .yaml with its .pgm, or a planlab scenario .json.`,
    );
  }
  host.install(m, name, null, null);
  return true;
}
