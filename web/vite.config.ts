import { defineConfig } from 'vite';
import { resolve } from 'node:path';
import { fileURLToPath } from 'node:url';

const here = fileURLToPath(new URL('.', import.meta.url));

// The served site is web/dist and nothing outside it, so the preset maps in
// ../assets are copied in as the public dir (served at ./maps/...), and the
// wasm module from ./pkg is bundled by Vite through its `new URL(...)` import.
export default defineConfig({
  base: './',
  publicDir: resolve(here, '../assets'),
  build: {
    outDir: 'dist',
    emptyOutDir: true,
    target: 'es2022',
    rollupOptions: {
      input: {
        main: resolve(here, 'index.html'),
        bench: resolve(here, 'bench.html'),
      },
    },
  },
  server: { fs: { allow: ['..'] } },
});
