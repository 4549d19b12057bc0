// First-load size of the built pages: what a browser actually transfers when
// it opens a page with an empty cache, from Playwright's network events.
// Shared by tests/e2e/size.test.mjs (the bar) and scripts/bench-browser.mjs
// (the report). `bytes` are the decoded bodies (what the page sees), `sent`
// what travelled on the wire: `planlab serve` sends the build's .br/.gz
// twins to a browser that accepts them.

import fs from 'node:fs';
import path from 'node:path';
import { DIST } from './harness.mjs';

/** A page's first-load budget on the wire: wasm + JS + CSS as sent
 *  compressed, bytes. This is what a class on a slow network waits for. */
export const FIRST_LOAD_SENT_LIMIT = 600_000;

/** The same files decoded, bytes: what the browser compiles and parses. */
// 1.5 MB was the aim; the robot module (web/pkg) has since grown with the ROS
// baselines and critic catalogue (1242 -> 1415 kB of wasm) and the BARN
// engine (scan costmap, Jackal, worlds: -> 1570 kB), so robot.html decodes
// to 1.80 MB (516 kB sent). Moving the BARN and ROS planners into a lazily
// loaded module, as the reproduce variants are, would bring it back under
// 1.5 MB; until then this bound stops further growth. Raised from 1.90 MB
// (robot.html then 1,899,829 B) to 1.925 MB for JPS+ (its jump table and
// scans, +11 kB: the robot episode's global planner can be any grid
// planner), the bidirectional search's frontier rule and the DWA screen's
// chunked walk and braking headings (+8 kB): robot.html 1,918,859 B. Back
// to 1.90 MB once JPS and bidirectional A* stopped compiling a copy of
// their search for the zero estimate (−41 kB), which paid for the bucket
// ring's occupancy bits and the 8-byte JPS+ table: robot.html 1,889.5 kB.
export const FIRST_LOAD_LIMIT = 1_900_000;

/** Every page of the built site: the .html files at the top of web/dist. */
export function sitePages() {
  return fs
    .readdirSync(DIST)
    .filter((f) => f.endsWith('.html'))
    .sort();
}

function kindOf(url, contentType) {
  const p = new URL(url).pathname;
  if (p.endsWith('.wasm') || contentType.includes('application/wasm')) return 'wasm';
  if (/\.m?js$/.test(p) || contentType.includes('javascript')) return 'js';
  if (p.endsWith('.css') || contentType.includes('text/css')) return 'css';
  if (p.endsWith('.html') || p.endsWith('/') || contentType.includes('text/html')) return 'html';
  return 'other';
}

/**
 * Opens `page` (a file name under web/dist) in a fresh browser page with the
 * cache disabled, waits until the network is idle, and sums the bodies of
 * every response by kind. Returns
 * `{ page, wasm, js, css, html, other, firstLoad, sentFirstLoad, files:
 * [{url, kind, bytes, sent, encoding}] }` where `firstLoad = wasm + js +
 * css` (decoded bytes) and `sentFirstLoad` the same files' wire bytes.
 */
export async function measureFirstLoad(session, page) {
  const tab = await session.context.newPage();
  const cdp = await session.context.newCDPSession(tab);
  await cdp.send('Network.setCacheDisabled', { cacheDisabled: true });
  const pending = [];
  const files = [];
  tab.on('response', (r) => {
    pending.push(
      (async () => {
        const url = r.url();
        if (!url.startsWith(session.base)) return;
        const kind = kindOf(url, r.headers()['content-type'] ?? '');
        let bytes;
        try {
          bytes = (await r.body()).length;
        } catch {
          // A body Chromium already dropped: the file it came from.
          const rel = decodeURIComponent(new URL(url).pathname).replace(/^\/+/, '') || 'index.html';
          bytes = fs.statSync(path.join(DIST, rel)).size;
        }
        const encoding = r.headers()['content-encoding'] ?? null;
        // Wire size of the body (compressed when it travelled so). Chromium
        // reports 0 for a body another tab already fetched; that body is
        // the file's twin for its encoding, so its size is read on disk.
        const twin = () => {
          const rel = decodeURIComponent(new URL(url).pathname).replace(/^\/+/, '') || 'index.html';
          const ext = { br: '.br', gzip: '.gz' }[encoding] ?? '';
          return fs.statSync(path.join(DIST, rel + ext)).size;
        };
        const reported = await r
          .request()
          .sizes()
          .then((z) => z.responseBodySize)
          .catch(() => 0);
        const sent = reported > 0 ? reported : twin();
        files.push({ url: url.slice(session.base.length), kind, bytes, sent, encoding });
      })(),
    );
  });
  await tab.goto(session.base + page, { waitUntil: 'networkidle' });
  await Promise.all(pending);
  await cdp.detach().catch(() => {});
  await tab.close();
  const sum = (k) => files.filter((f) => f.kind === k).reduce((a, f) => a + f.bytes, 0);
  const out = { page, wasm: sum('wasm'), js: sum('js'), css: sum('css'), html: sum('html'), other: sum('other') };
  out.firstLoad = out.wasm + out.js + out.css;
  out.sentFirstLoad = files.filter((f) => ['wasm', 'js', 'css'].includes(f.kind)).reduce((a, f) => a + f.sent, 0);
  out.files = files.sort((a, b) => b.bytes - a.bytes);
  return out;
}

export const kB = (n) => `${(n / 1000).toFixed(1)} kB`;
