// Share links: a whole scenario JSON in the URL hash, so a link reproduces
// the scenario (and, the simulation being deterministic, its trace).
//
//   #s=<base64url(deflate-raw(JSON))>   when the browser has CompressionStream
//   #j=<base64url(UTF-8 JSON)>          fallback without it
//
// Nothing leaves the browser: the hash is not sent to the server.

/** Longest link we hand out, characters. Browsers accept more, but chat
 *  programs, mail clients and servers' logs truncate long URLs. */
export const MAX_LINK_CHARS = 64 * 1024;

export function toBase64Url(bytes: Uint8Array): string {
  let s = '';
  const CHUNK = 0x8000;
  for (let i = 0; i < bytes.length; i += CHUNK) s += String.fromCharCode(...bytes.subarray(i, i + CHUNK));
  return btoa(s).replace(/\+/g, '-').replace(/\//g, '_').replace(/=+$/, '');
}

export function fromBase64Url(text: string): Uint8Array {
  if (!/^[A-Za-z0-9_-]*$/.test(text)) throw new Error('the link is damaged: it has characters base64url does not use');
  const b64 = text.replace(/-/g, '+').replace(/_/g, '/') + '='.repeat((4 - (text.length % 4)) % 4);
  let bin: string;
  try {
    bin = atob(b64);
  } catch {
    throw new Error('the link is damaged: its data is not base64url');
  }
  const out = new Uint8Array(bin.length);
  for (let i = 0; i < bin.length; i++) out[i] = bin.charCodeAt(i);
  return out;
}

const hasStreams = () => typeof CompressionStream === 'function' && typeof DecompressionStream === 'function';

async function pipe(bytes: Uint8Array, stream: CompressionStream | DecompressionStream): Promise<Uint8Array> {
  const body = new Blob([bytes as BlobPart]).stream().pipeThrough(stream);
  return new Uint8Array(await new Response(body).arrayBuffer());
}

/** The hash (with its `#`) that carries `json`. */
export async function encodeScenarioHash(json: string): Promise<string> {
  const raw = new TextEncoder().encode(json);
  if (hasStreams()) {
    try {
      return `#s=${toBase64Url(await pipe(raw, new CompressionStream('deflate-raw')))}`;
    } catch {
      // Some browsers know CompressionStream but not deflate-raw.
    }
  }
  return `#j=${toBase64Url(raw)}`;
}

/** The scenario JSON in a location hash, `null` when it carries none;
 *  throws with a readable message when the link is damaged. */
export async function decodeScenarioHash(hash: string): Promise<string | null> {
  const m = /^#?([sj])=(.*)$/s.exec(hash);
  if (!m) return null;
  const bytes = fromBase64Url(m[2]);
  if (m[1] === 'j') return new TextDecoder('utf-8', { fatal: true }).decode(bytes);
  if (!hasStreams()) throw new Error('this browser cannot decompress the shared link (no DecompressionStream)');
  let raw: Uint8Array;
  try {
    raw = await pipe(bytes, new DecompressionStream('deflate-raw'));
  } catch {
    throw new Error('the link is damaged: its data does not decompress (was it cut short?)');
  }
  return new TextDecoder().decode(raw);
}

/** A full link to `page` (this location without its hash) carrying `json`;
 *  throws when it would be longer than MAX_LINK_CHARS. */
export async function shareLink(json: string, page: string = location.href): Promise<string> {
  const base = page.replace(/#.*$/, '');
  const link = base + (await encodeScenarioHash(json));
  if (link.length > MAX_LINK_CHARS) {
    const kb = (link.length / 1024).toFixed(0);
    throw new Error(
      `This scenario is too large for a share link (${kb} KB; at most ${MAX_LINK_CHARS / 1024} KB): ` +
        'save it as scenario JSON and share the file instead.',
    );
  }
  return link;
}
