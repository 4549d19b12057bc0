// Loading scenario JSON and the map files it refers to, for any page that
// builds a SimHandle: a preset from the site's ./scenarios/ (its map file,
// and a ROS yaml's image, fetched relative to it), or the files a person
// picked (the .json plus the map files among them). Map files are keyed by
// base name, as SimHandle.fromScenario looks them up. The ROS yaml's image
// name comes from the caller's wasm module (`rosImageName`): the grid page
// loads another module than the robot page, and this file imports neither.

/** The core's reader of a ROS yaml's `image:` (each page's wasm module). */
export type ImageNameOf = (yaml: string) => string;

export type MapFiles = Record<string, Uint8Array>;

/** Largest file the pages read (a browser tab holds it whole, then the
 *  core parses it): far above any real map (a 4000×4000 ROS image is
 *  16 MB), far below what would stall the tab. The CLI reads larger. */
export const MAX_OPEN_BYTES = 64 * 1024 * 1024;

/** Throws a one-line message when any picked file is over
 *  [`MAX_OPEN_BYTES`], before anything is read. */
export function checkSizes(picked: File[]): void {
  for (const f of picked) {
    if (f.size > MAX_OPEN_BYTES) {
      const mb = (n: number) => `${Math.round(n / (1024 * 1024))} MB`;
      throw new Error(`${f.name} is ${mb(f.size)}: the page opens files up to ${mb(MAX_OPEN_BYTES)} (the planlab CLI reads larger ones).`);
    }
  }
}

/** The .pgm among `pgms` that a ROS yaml named `yamlName` refers to as
 *  `image` (by base name); a one-line error when it is missing or when the
 *  only one opened has another name (it may be another map's image). */
export function rosImageFile(yamlName: string, image: string, pgms: File[]): File {
  const base = image.split(/[\\/]/).pop() ?? image;
  const pgm = pgms.find((f) => f.name === base);
  if (pgm) return pgm;
  if (pgms.length) {
    const names = pgms.map((f) => f.name).join(', ');
    throw new Error(`${yamlName} names the image "${base}", but the .pgm opened is ${names}: open the image it names (or rename the file to ${base} if it is that image).`);
  }
  throw new Error(`${yamlName} needs its image "${base}": open the .yaml together with its .pgm (select both, or drop both).`);
}

export async function fetchText(url: URL): Promise<string> {
  const r = await fetch(url);
  if (!r.ok) throw new Error(`cannot load ${url.pathname}: HTTP ${r.status}`);
  return r.text();
}

export async function fetchBytes(url: URL): Promise<Uint8Array> {
  const r = await fetch(url);
  if (!r.ok) throw new Error(`cannot load ${url.pathname}: HTTP ${r.status}`);
  return new Uint8Array(await r.arrayBuffer());
}

export const baseName = (p: string): string => p.split(/[\\/]/).pop() ?? p;

/** The map files scenario `text` refers to, fetched relative to its URL
 *  (none for an inline map; JSON errors are left to SimHandle, which
 *  reports them with their position). */
export async function mapFilesOf(text: string, scenarioUrl: URL, rosImageName: ImageNameOf): Promise<MapFiles> {
  let ref: unknown;
  try {
    ref = (JSON.parse(text) as { map?: { file?: unknown } }).map?.file;
  } catch {
    return {};
  }
  if (typeof ref !== 'string') return {};
  const files: MapFiles = {};
  const url = new URL(ref, scenarioUrl);
  files[baseName(ref)] = await fetchBytes(url);
  if (/\.ya?ml$/i.test(ref)) {
    const image = rosImageName(new TextDecoder().decode(files[baseName(ref)]));
    files[baseName(image)] = await fetchBytes(new URL(image, url));
  }
  return files;
}

/** A preset of the site (`scenarios/FILE`) with its map files. */
export async function loadPresetFiles(file: string, rosImageName: ImageNameOf): Promise<{ text: string; files: MapFiles }> {
  const url = new URL(`scenarios/${file}`, document.baseURI);
  const text = await fetchText(url);
  return { text, files: await mapFilesOf(text, url, rosImageName) };
}

/** Picked files: the scenario .json and the others as map files; null when
 *  nothing was picked. Throws when no .json is among them. */
export async function readPicked(picked: File[]): Promise<{ name: string; text: string; files: MapFiles } | null> {
  checkSizes(picked);
  const f = picked.find((x) => x.name.toLowerCase().endsWith('.json'));
  if (!f) {
    if (picked.length) throw new Error(`Open a scenario .json (with the map files it refers to), not ${picked.map((x) => x.name).join(', ')}.`);
    return null;
  }
  const files: MapFiles = {};
  for (const x of picked) if (x !== f) files[x.name] = new Uint8Array(await x.arrayBuffer());
  return { name: f.name, text: await f.text(), files };
}
