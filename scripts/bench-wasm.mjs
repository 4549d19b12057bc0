#!/usr/bin/env node
// wasm-vs-native A* benchmark on Moving AI maps.
//
// Both sides run the same Rust code, planlab_wasm::batch::Batch::solve_all
// (every query of a .scen planned once, the planner and passability grid
// built beforehand): natively through `examples/bench_native.rs` timed with
// Instant, and in headless Chromium through the bench page (web/bench.html)
// timed with performance.now() around one wasm call per repetition, so the
// boundary cost is negligible. Prints one JSON line per map:
//   {"map","rows","native_astar_ms","wasm_astar_ms","ratio"}
// with the median milliseconds per query over all timed blocks of each side
// (native and wasm rounds alternate), ratio = wasm / native, and the same
// ratio from the fastest blocks as min_ratio. The
// 512×512 maps use every k-th .scen row (k fixed by --sample, default ≤ 250
// rows), the same rows on both sides.
//
// Needs a built site (npm --prefix web run build:wasm && npm --prefix web run build).
// Usage: node scripts/bench-wasm.mjs [--sample N] [--quick]

import { spawnSync } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { REPO, SHARED, startSession } from '../tests/e2e/harness.mjs';

const args = process.argv.slice(2);
const quick = args.includes('--quick');
const sampleArg = args.indexOf('--sample');
const SAMPLE = sampleArg >= 0 ? Number(args[sampleArg + 1]) : 250;
const ROUNDS = quick ? 1 : 3;

const MAPS = [
  // inner = whole-scenario passes per timed block (≥ ~50 ms per block).
  { name: 'dao/arena', reps: quick ? 3 : 5, inner: 30 },
  { name: 'maze/maze512-1-0', reps: quick ? 2 : 3, inner: 1 },
  { name: 'random/random512-10-0', reps: quick ? 2 : 3, inner: 1 },
];

const median = (xs) => {
  const s = [...xs].sort((a, b) => a - b);
  const m = s.length >> 1;
  return s.length % 2 ? s[m] : (s[m - 1] + s[m]) / 2;
};

/** Every k-th row so that at most `n` remain (deterministic, spans all buckets). */
function sampleScen(text, n) {
  const lines = text.split('\n');
  const header = lines[0].startsWith('version') ? [lines[0]] : [];
  const rows = lines.slice(header.length).filter((l) => l.trim());
  const k = Math.max(1, Math.ceil(rows.length / n));
  return [...header, ...rows.filter((_, i) => i % k === 0)].join('\n') + '\n';
}

function cargo(argv) {
  const r = spawnSync('cargo', argv, { cwd: REPO, stdio: ['ignore', 'inherit', 'inherit'] });
  if (r.status !== 0) throw new Error(`cargo ${argv.join(' ')} failed`);
}

function native(mapFile, scenFile, reps, inner) {
  const exe = path.join(REPO, 'target/release/examples/bench_native');
  const r = spawnSync(exe, [mapFile, scenFile, String(reps), 'astar', String(inner)], { encoding: 'utf8' });
  if (r.status !== 0) throw new Error(`bench_native failed: ${r.stderr}`);
  return JSON.parse(r.stdout.trim().split('\n').pop());
}

async function main() {
  process.stderr.write('building the native bench (cargo --release)…\n');
  cargo(['build', '--release', '-p', 'planlab-wasm', '--example', 'bench_native']);
  const tmp = fs.mkdtempSync(path.join(os.tmpdir(), 'planlab-bench-'));
  const session = await startSession();
  const results = [];
  try {
    const page = await session.context.newPage();
    page.on('pageerror', (e) => process.stderr.write(`pageerror: ${e.message}\n`));
    await page.goto(session.base + 'bench.html');
    await page.waitForFunction(() => document.body.dataset.state !== 'loading', null, { timeout: 30_000 });
    if ((await page.getAttribute('body', 'data-state')) !== 'ready') {
      throw new Error(`bench page failed: ${await page.textContent('#out')}`);
    }
    for (const m of MAPS) {
      const mapFile = path.join(SHARED, 'data/movingai', `${m.name}.map`);
      const mapText = fs.readFileSync(mapFile, 'utf8');
      const scenText = sampleScen(fs.readFileSync(`${mapFile}.scen`, 'utf8'), SAMPLE);
      const scenFile = path.join(tmp, `${path.basename(m.name)}.scen`);
      fs.writeFileSync(scenFile, scenText);

      // Alternate native and wasm rounds so load from other processes on
      // this small machine hits both sides alike; medians over all blocks.
      const natTimes = [];
      const webTimes = [];
      let nat;
      let web;
      for (let round = 0; round < ROUNDS; round++) {
        nat = native(mapFile, scenFile, m.reps, m.inner);
        web = await page.evaluate(([mt, st, reps, inner]) => window.planlabBench(mt, st, reps, inner), [
          mapText,
          scenText,
          m.reps,
          m.inner,
        ]);
        natTimes.push(...nat.times_ms);
        webTimes.push(...web.timesMs);
      }
      if (web.rows !== nat.rows) throw new Error(`${m.name}: row counts differ`);
      // Same code, same answers: totals agree and match the scenario optimum.
      if (Math.abs(web.totalCost - nat.total_cost) > 1e-6) {
        throw new Error(`${m.name}: wasm total ${web.totalCost} != native ${nat.total_cost}`);
      }
      if (Math.abs(web.totalCost - web.optimalSum) > 1e-3 * web.rows) {
        throw new Error(`${m.name}: total ${web.totalCost} != optimal sum ${web.optimalSum}`);
      }
      const nativeMs = median(natTimes) / (nat.rows * nat.inner);
      const wasmMs = median(webTimes) / (web.rows * web.inner);
      const nativeMinMs = Math.min(...natTimes) / (nat.rows * nat.inner);
      const wasmMinMs = Math.min(...webTimes) / (web.rows * web.inner);
      const line = {
        map: path.basename(m.name),
        rows: web.rows,
        native_astar_ms: Number(nativeMs.toFixed(5)),
        wasm_astar_ms: Number(wasmMs.toFixed(5)),
        ratio: Number((wasmMs / nativeMs).toFixed(3)),
        min_ratio: Number((wasmMinMs / nativeMinMs).toFixed(3)),
      };
      results.push(line);
      console.log(JSON.stringify(line));
    }
  } finally {
    await session.close();
    fs.rmSync(tmp, { recursive: true, force: true });
  }
  const worst = Math.max(...results.map((r) => r.ratio));
  process.stderr.write(`worst wasm/native ratio ${worst.toFixed(3)} (target ≤ 1.5)\n`);
}

main().catch((e) => {
  console.error(e.message ?? e);
  process.exit(1);
});
