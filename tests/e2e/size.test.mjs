// First load of every built page (wasm + JS + CSS, decoded, with an empty
// cache) stays within the budget (FIRST_LOAD_LIMIT in firstload.mjs), and
// travels compressed (the build's .br/.gz twins, sent by `planlab serve`).
// Deterministic: the bytes depend on the build only, not on the machine.

import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { startSession } from './harness.mjs';
import { FIRST_LOAD_LIMIT, FIRST_LOAD_SENT_LIMIT, kB, measureFirstLoad, sitePages } from './firstload.mjs';

let session;
before(async () => {
  session = await startSession();
});
after(async () => {
  await session?.close();
});

test('first load of every page is within its budgets, sent and decoded (wasm + JS + CSS)', async () => {
  const pages = sitePages();
  // The site's own pages at least; pages added later are measured too.
  for (const p of ['index.html', 'robot.html', 'apf.html', 'arm.html', 'barn.html']) assert.ok(pages.includes(p), `${p} built`);
  for (const p of pages) {
    const m = await measureFirstLoad(session, p);
    console.log(`${p}: first load ${kB(m.firstLoad)} (wasm ${kB(m.wasm)}, js ${kB(m.js)}, css ${kB(m.css)}), ${kB(m.sentFirstLoad)} sent compressed`);
    // Every page that plans loads the wasm module; a page that fetched
    // nothing would pass the bar vacuously.
    assert.ok(m.js > 0, `${p}: loaded no JS`);
    assert.ok(m.sentFirstLoad <= FIRST_LOAD_SENT_LIMIT, `${p}: ${m.sentFirstLoad} bytes sent > ${FIRST_LOAD_SENT_LIMIT}: ${JSON.stringify(m.files.slice(0, 5))}`);
    assert.ok(m.firstLoad <= FIRST_LOAD_LIMIT, `${p}: ${m.firstLoad} bytes > ${FIRST_LOAD_LIMIT}: ${JSON.stringify(m.files.slice(0, 5))}`);
  }
});

test('the server sends the build\'s compressed twins: every page\'s wasm, JS and CSS travel compressed', async () => {
  for (const p of sitePages()) {
    const m = await measureFirstLoad(session, p);
    for (const f of m.files) {
      if (!['wasm', 'js', 'css', 'html'].includes(f.kind) || f.bytes < 1024) continue;
      assert.ok(['br', 'gzip'].includes(f.encoding), `${p}: ${f.url} (${f.bytes} B) sent with content-encoding ${f.encoding}`);
      assert.ok(f.sent < f.bytes, `${p}: ${f.url} sent ${f.sent} B of ${f.bytes}`);
    }
    // wasm and minified JS compress to well under half.
    assert.ok(m.sentFirstLoad < 0.5 * m.firstLoad, `${p}: ${m.sentFirstLoad} B sent of ${m.firstLoad}`);
  }
});
