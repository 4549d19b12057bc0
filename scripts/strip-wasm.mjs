#!/usr/bin/env node
// Drops the custom sections of built wasm modules (the `name` section of
// function names, ~200 kB in the playground module, and `producers`): the
// browser needs none of them, they only serve stack traces with names, and
// binaryen's wasm-opt (which would strip them) cannot be downloaded here.
// Rewrites each file in place and prints the bytes saved.
//
// Usage: node scripts/strip-wasm.mjs FILE.wasm [...]

import fs from 'node:fs';

function leb(buf, pos) {
  let value = 0;
  let shift = 0;
  let byte;
  do {
    byte = buf[pos++];
    value += (byte & 0x7f) * 2 ** shift;
    shift += 7;
  } while (byte & 0x80);
  return [value, pos];
}

export function stripCustomSections(buf) {
  if (buf.length < 8 || buf.readUInt32LE(0) !== 0x6d736100) throw new Error('not a wasm module');
  const keep = [buf.subarray(0, 8)];
  const dropped = [];
  let pos = 8;
  while (pos < buf.length) {
    const start = pos;
    const id = buf[pos++];
    const [size, body] = leb(buf, pos);
    const end = body + size;
    if (end > buf.length) throw new Error('truncated wasm section');
    if (id === 0) {
      const [len, name] = leb(buf, body);
      dropped.push(`${buf.subarray(name, name + len).toString('utf8')} (${end - start} B)`);
    } else {
      keep.push(buf.subarray(start, end));
    }
    pos = end;
  }
  return { out: Buffer.concat(keep), dropped };
}

const files = process.argv.slice(2);
if (!files.length) {
  console.error('usage: node scripts/strip-wasm.mjs FILE.wasm [...]');
  process.exit(2);
}
for (const f of files) {
  const buf = fs.readFileSync(f);
  const { out, dropped } = stripCustomSections(buf);
  fs.writeFileSync(f, out);
  console.log(`${f}: ${buf.length} -> ${out.length} bytes (dropped ${dropped.join(', ') || 'nothing'})`);
}
