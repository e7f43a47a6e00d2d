// Vite build of the browser app. Everything is bundled (three.js, the worker,
// the wasm binary): the app makes no request beyond its own origin.
//
// `vite build --mode singlefile` builds the one-file app instead:
// dist/vesselmesh.html with the JS, the CSS, the worker and the wasm inlined,
// which works opened from disk (file://) with no network. `--mode element`
// builds the <vessel-mesher> custom element into dist/element/.
import { readFileSync } from 'node:fs';
import { dirname, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';

import { defineConfig } from 'vite';
import { VitePWA } from 'vite-plugin-pwa';
import { viteSingleFile } from 'vite-plugin-singlefile';

// Cross-origin isolation, for the threaded core (the app works without it,
// on one thread): the dev and preview servers send these headers; on a
// static host, which does not, the service worker adds them (src/sw.js).
import { ISOLATION_HEADERS } from './src/isolation-headers.js';
import { withOptionTable } from './src/option-controls.js';

const here = dirname(fileURLToPath(import.meta.url));

/** Renames the one-file build's index.html to vesselmesh.html. */
const renameHtml = (name) => ({
  name: 'vm-rename-html',
  enforce: 'post',
  generateBundle(_options, bundle) {
    const html = bundle['index.html'];
    if (html) html.fileName = name;
  },
});

/** The option controls' ranges and defaults (min, max, value, checked,
 * selected) filled in from the core's option table (option-controls.js),
 * in the page's HTML: the controls show them before the wasm is loaded. */
export const optionTable = () => ({
  name: 'vm-option-table',
  transformIndexHtml: {
    order: 'pre',
    handler: (html) => withOptionTable(html, JSON.parse(readFileSync(resolve(here, '../wasm/src/option-table.json'), 'utf8'))),
  },
});

/** The Emscripten module's own `new URL('vesselmesh_core.wasm', import.meta.url)`
 * is never fetched (vesselmesh.js always passes wasmBinary); inlined, it
 * would be a second copy of the wasm in the file. */
const dropCoreWasmUrl = () => ({
  name: 'vm-drop-core-wasm-url',
  transform(code, id) {
    if (!id.endsWith('vesselmesh_core.mjs')) return null;
    return code.replace(/new URL\((["'])vesselmesh_core\.wasm\1,\s*import\.meta\.url\)/g, '"vesselmesh_core.wasm"');
  },
});

/** The client's default worker (a separate file) is never started in the
 * one-file app (worker-inline.js is): drop the file Vite emits for it. */
const dropWorkerFiles = () => ({
  name: 'vm-drop-worker-files',
  enforce: 'post',
  generateBundle(_options, bundle) {
    for (const name of Object.keys(bundle)) if (/^(assets\/)?worker-.*\.js$/.test(name)) delete bundle[name];
  },
});

/** The installable app: a web app manifest and a service worker
 * (src/sw.js) precaching every file of the build (page, bundle, CSS, the
 * worker script, the wasm), so that after one visit the app reloads and
 * restarts its worker (Cancel) with no server, and adding the COOP/COEP
 * headers to what it serves. The page registers it (src/isolation.js, told
 * its URL here) and, served without the headers, reloads once through it. */
const installable = () => [
  VitePWA({
    strategies: 'injectManifest',
    srcDir: 'src',
    filename: 'sw.js',
    injectRegister: false,
    includeAssets: ['icon.svg'],
    manifest: {
      name: 'vesselmesh',
      short_name: 'vesselmesh',
      description: 'Quality meshes for cardiovascular flow simulation, in the browser',
      start_url: './',
      scope: './',
      display: 'standalone',
      background_color: '#f4f6f8',
      theme_color: '#17212b',
      icons: [{ src: 'icon.svg', sizes: 'any', type: 'image/svg+xml', purpose: 'any' }],
    },
    injectManifest: {
      globPatterns: ['**/*.{html,js,mjs,css,wasm,svg,webmanifest}'],
      maximumFileSizeToCacheInBytes: 16 * 2 ** 20,
      rollupFormat: 'iife',
    },
  }),
  {
    name: 'vm-service-worker-url',
    apply: 'build', // the dev server has no service worker
    config: () => ({ define: { __VM_SERVICE_WORKER__: JSON.stringify('./sw.js') } }),
  },
];

/** The one-file app has no icon file beside it: the page's icon link
 * carries the icon itself (a data: URL), so nothing is asked for. */
const inlineIcon = () => ({
  name: 'vm-inline-icon',
  transformIndexHtml(html) {
    const svg = readFileSync(resolve(here, 'public/icon.svg'), 'utf8');
    return html.replace('href="./icon.svg"', `href="data:image/svg+xml,${encodeURIComponent(svg.trim())}"`);
  },
});

function singleFileConfig() {
  return {
    root: here,
    base: './',
    publicDir: false, // the icon is for the installable app
    resolve: {
      alias: [
        { find: /^\.\/worker-source\.js$/, replacement: resolve(here, 'src/worker-inline.js') },
        { find: /^\.\/threaded-core\.js$/, replacement: resolve(here, 'src/threaded-core-none.js') },
      ],
    },
    build: {
      outDir: resolve(here, '../dist'),
      emptyOutDir: false,
      target: 'es2022',
      chunkSizeWarningLimit: 8192,
      assetsInlineLimit: () => true,
    },
    // A classic worker: Chromium refuses module workers from blob: URLs in a
    // file:// page.
    worker: { format: 'iife', plugins: () => [dropCoreWasmUrl()] },
    plugins: [
      optionTable(),
      dropCoreWasmUrl(),
      inlineIcon(),
      viteSingleFile({ removeViteModuleLoader: true }),
      renameHtml('vesselmesh.html'),
      dropWorkerFiles(),
    ],
  };
}

/** The <vessel-mesher> element as a module a page loads with a plain
 * <script type="module"> (three.js bundled in): dist/element/vessel-mesher.js,
 * its worker and the wasm beside it in dist/element/assets/. */
function elementConfig() {
  return {
    root: here,
    base: './',
    publicDir: false,
    build: {
      outDir: resolve(here, '../dist/element'),
      emptyOutDir: true,
      target: 'es2022',
      chunkSizeWarningLimit: 1024,
      modulePreload: false,
      rollupOptions: {
        input: resolve(here, 'src/element/vessel-mesher.js'),
        preserveEntrySignatures: 'exports-only',
        output: {
          entryFileNames: 'vessel-mesher.js',
          chunkFileNames: 'assets/[name]-[hash].js',
          assetFileNames: 'assets/[name]-[hash][extname]',
        },
      },
    },
    worker: { format: 'es' },
  };
}

export default defineConfig(({ mode }) =>
  mode === 'singlefile'
    ? singleFileConfig()
    : mode === 'element'
    ? elementConfig()
    : {
        root: here,
        base: './',
        build: {
          outDir: resolve(here, 'dist'),
          emptyOutDir: true,
          target: 'es2022',
          chunkSizeWarningLimit: 1024,
        },
        worker: { format: 'es' },
        plugins: [optionTable(), installable()],
        server: { fs: { allow: [resolve(here, '..')] }, headers: ISOLATION_HEADERS },
        preview: { port: 4173, strictPort: true, headers: ISOLATION_HEADERS },
      },
);
