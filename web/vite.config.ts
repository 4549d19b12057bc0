import { defineConfig, type Plugin } from 'vite';
import { copyFileSync, existsSync, mkdirSync, readdirSync, readFileSync, renameSync, statSync, writeFileSync } from 'node:fs';
import { extname, resolve } from 'node:path';
import { brotliCompressSync, constants as zlibConstants, gzipSync } from 'node:zlib';
import { fileURLToPath } from 'node:url';

const here = fileURLToPath(new URL('.', import.meta.url));
const scenarios = resolve(here, '../assets/scenarios');

/**
 * `virtual:robot-presets`: the scenarios in assets/scenarios that have a
 * `local_planner` section (file, name, description, planner), read at build
 * time, since a static page cannot list a directory. The robot page fetches
 * the chosen file from ./scenarios/ like any other asset.
 */
function robotPresets(): Plugin {
  const id = 'virtual:robot-presets';
  const resolved = '\0' + id;
  return {
    name: 'planlab-robot-presets',
    resolveId: (source) => (source === id ? resolved : null),
    load(source) {
      if (source !== resolved) return null;
      const out: { file: string; name: string; description: string; planner: string }[] = [];
      for (const f of readdirSync(scenarios).filter((f) => f.endsWith('.json')).sort()) {
        const path = resolve(scenarios, f);
        this.addWatchFile(path);
        let s: Record<string, unknown>;
        try {
          s = JSON.parse(readFileSync(path, 'utf8'));
        } catch (e) {
          this.warn(`assets/scenarios/${f}: not JSON (${(e as Error).message}); left out of the robot presets`);
          continue;
        }
        const lp = s.local_planner as { name?: unknown } | undefined;
        if (!lp || typeof lp.name !== 'string') continue;
        out.push({
          file: f,
          name: typeof s.name === 'string' && s.name ? s.name : f,
          description: typeof s.description === 'string' ? s.description : '',
          planner: lp.name,
        });
      }
      // The demo first: it is what the page opens with.
      out.sort((a, b) => Number(b.file === 'dwa-demo.json') - Number(a.file === 'dwa-demo.json'));
      return `export default ${JSON.stringify(out)};`;
    },
  };
}

/**
 * `virtual:gallery`: assets/gallery.json's experiments (one per
 * `planlab reproduce` id; crates/planlab-core/tests/gallery.rs keeps it equal
 * to the reproduce registry), read at build time.
 */
function gallery(): Plugin {
  const id = 'virtual:gallery';
  const resolved = '\0' + id;
  const file = resolve(here, '../assets/gallery.json');
  return {
    name: 'planlab-gallery',
    resolveId: (source) => (source === id ? resolved : null),
    load(source) {
      if (source !== resolved) return null;
      this.addWatchFile(file);
      const g = JSON.parse(readFileSync(file, 'utf8')) as { experiments: unknown[] };
      return `export default ${JSON.stringify(g.experiments)};`;
    },
  };
}

/**
 * `virtual:reproduce-results`: assets/reproduce-results.jsonl (the family
 * results of `planlab reproduce --variants 30 --seed 0 --json`, written by
 * scripts/reproduce-results.sh; crates/planlab-core/tests/gallery.rs keeps
 * it equal to the registry), read at build time, keyed by id, without the
 * per-variant rows (trace hashes) that no card shows. A missing file gives
 * no results: the cards say so.
 */
function reproduceResults(): Plugin {
  const id = 'virtual:reproduce-results';
  const resolved = '\0' + id;
  const file = resolve(here, '../assets/reproduce-results.jsonl');
  return {
    name: 'planlab-reproduce-results',
    resolveId: (source) => (source === id ? resolved : null),
    load(source) {
      if (source !== resolved) return null;
      this.addWatchFile(file);
      const out: Record<string, unknown> = {};
      if (!existsSync(file)) {
        this.warn('assets/reproduce-results.jsonl is missing (scripts/reproduce-results.sh): the gallery shows no results');
        return 'export default {};';
      }
      readFileSync(file, 'utf8')
        .split('\n')
        .filter((l) => l.trim())
        .forEach((l, i) => {
          let r: Record<string, unknown>;
          try {
            r = JSON.parse(l);
          } catch (e) {
            this.error(`assets/reproduce-results.jsonl line ${i + 1}: ${(e as Error).message}`);
          }
          delete r.rows;
          out[String(r.id)] = r;
        });
      return `export default ${JSON.stringify(out)};`;
    },
  };
}

// The served site is web/dist and nothing outside it, so the preset maps in
// ../assets are copied in as the public dir (served at ./maps/...), and the
// wasm module from ./pkg is bundled by Vite through its `new URL(...)` import.
/**
 * Copies docs/algorithms.md into the site as `docs/algorithms.md`: the
 * pages' help cites it (the core's planner descriptions name its
 * sections) and links there, so the citation is not a 404 on the site.
 */
function algorithmNotes(): Plugin {
  let outDir = '';
  const src = resolve(here, '../docs/algorithms.md');
  return {
    name: 'planlab-algorithm-notes',
    apply: 'build',
    configResolved(config) {
      outDir = resolve(config.root, config.build.outDir);
    },
    closeBundle() {
      mkdirSync(resolve(outDir, 'docs'), { recursive: true });
      copyFileSync(src, resolve(outDir, 'docs/algorithms.md'));
    },
  };
}

/** File types worth compressing (text and wasm; images are compressed already). */
const COMPRESSIBLE = new Set(['.html', '.js', '.mjs', '.css', '.json', '.jsonl', '.wasm', '.svg', '.map', '.scen', '.pgm', '.yaml', '.yml', '.txt', '.md', '.world', '.csv']);

/**
 * Precompresses the built site: beside every compressible file of at least
 * 1 KiB, `NAME.br` (brotli, quality 11) and `NAME.gz` (gzip, level 9) when
 * they are smaller than the file. `planlab serve` sends them to browsers
 * that accept them (tower-http's precompressed ServeFile), so a page's
 * first load travels compressed with no work per request. Node's own zlib
 * does the compressing: no extra dependency.
 */
function precompress(): Plugin {
  let outDir = '';
  return {
    name: 'planlab-precompress',
    apply: 'build',
    configResolved(config) {
      outDir = resolve(config.root, config.build.outDir);
    },
    closeBundle() {
      const walk = (dir: string): string[] =>
        readdirSync(dir, { withFileTypes: true }).flatMap((e) => {
          const p = resolve(dir, e.name);
          return e.isDirectory() ? walk(p) : e.isFile() ? [p] : [];
        });
      let before = 0;
      let after = 0;
      for (const file of walk(outDir)) {
        if (!COMPRESSIBLE.has(extname(file).toLowerCase()) || statSync(file).size < 1024) continue;
        const body = readFileSync(file);
        const br = brotliCompressSync(body, {
          params: {
            [zlibConstants.BROTLI_PARAM_QUALITY]: 11,
            [zlibConstants.BROTLI_PARAM_SIZE_HINT]: body.length,
          },
        });
        const gz = gzipSync(body, { level: 9 });
        for (const [ext, packed] of [['.br', br], ['.gz', gz]] as const) {
          if (packed.length >= body.length) continue;
          // Written whole, then renamed: a server never sends half a file.
          writeFileSync(file + ext + '.tmp', packed);
          renameSync(file + ext + '.tmp', file + ext);
        }
        before += body.length;
        after += Math.min(body.length, br.length);
      }
      console.log(`precompressed ${(before / 1e6).toFixed(2)} MB to ${(after / 1e6).toFixed(2)} MB (brotli)`);
    },
  };
}

export default defineConfig({
  base: './',
  publicDir: resolve(here, '../assets'),
  plugins: [robotPresets(), gallery(), reproduceResults(), algorithmNotes(), precompress()],
  build: {
    outDir: 'dist',
    emptyOutDir: true,
    target: 'es2022',
    rollupOptions: {
      input: {
        grid: resolve(here, 'index.html'),
        gallery: resolve(here, 'gallery.html'),
        robot: resolve(here, 'robot.html'),
        compare: resolve(here, 'compare.html'),
        race: resolve(here, 'race.html'),
        barn: resolve(here, 'barn.html'),
        arm: resolve(here, 'arm.html'),
        apf: resolve(here, 'apf.html'),
        bench: resolve(here, 'bench.html'),
      },
    },
  },
  server: { fs: { allow: ['..'] } },
});
