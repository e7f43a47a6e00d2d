// Vite build of the browser app. Everything is bundled (three.js, the worker,
// the wasm binary): the app makes no request beyond its own origin.
import { dirname, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';

import { defineConfig } from 'vite';

const here = dirname(fileURLToPath(import.meta.url));

export default defineConfig({
  root: here,
  base: './',
  build: {
    outDir: resolve(here, 'dist'),
    emptyOutDir: true,
    target: 'es2022',
    chunkSizeWarningLimit: 1024,
  },
  worker: { format: 'es' },
  server: { fs: { allow: [resolve(here, '..')] } },
  preview: { port: 4173, strictPort: true },
});
