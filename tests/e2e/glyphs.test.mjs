// Every symbol the pages write (U+2000 and above: arrows, player and
// check marks, Greek letters…) has a glyph in a font of this machine, the
// Debian machine the e2e tests run on: "⏸" once showed as an empty box.
// Reads the pages' sources; asks fontconfig (`fc-list :charset=HEX`, from
// Chromium's dependencies) which fonts cover each character.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { WEB } from './harness.mjs';

function sources(dir) {
  return fs.readdirSync(dir, { withFileTypes: true }).flatMap((e) => {
    const p = path.join(dir, e.name);
    if (e.isDirectory()) return sources(p);
    return /\.(ts|html|css)$/.test(e.name) ? [p] : [];
  });
}

test('every symbol on the pages has a glyph in an installed font', () => {
  const files = [...sources(path.join(WEB, 'src')), ...fs.readdirSync(WEB).filter((f) => f.endsWith('.html')).map((f) => path.join(WEB, f))];
  const where = new Map();
  for (const f of files) {
    for (const ch of fs.readFileSync(f, 'utf8')) {
      if (ch.codePointAt(0) >= 0x2000 && !where.has(ch)) where.set(ch, path.relative(WEB, f));
    }
  }
  assert.ok(where.size > 10, `found ${where.size} symbols: the scan reads the sources`);
  const missing = [];
  for (const [ch, file] of where) {
    const hex = ch.codePointAt(0).toString(16);
    const r = spawnSync('fc-list', [`:charset=${hex}`], { encoding: 'utf8' });
    assert.equal(r.status, 0, `fc-list failed: ${r.stderr}`);
    if (!r.stdout.trim()) missing.push(`${ch} (U+${hex.toUpperCase()}, ${file})`);
  }
  assert.deepEqual(missing, [], 'symbols with no glyph in any installed font');
});
