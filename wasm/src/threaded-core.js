// The threaded WebAssembly core (wasm/dist/vesselmesh_core_mt.*): the same
// Embind API as the single-threaded module, with the core's loops on a pool
// of Web Workers sharing the module's memory. It needs SharedArrayBuffer,
// which browsers give only to cross-origin isolated pages (served with
// Cross-Origin-Opener-Policy: same-origin and Cross-Origin-Embedder-Policy:
// require-corp, by the server or, for the app on a static host, by its
// service worker: web/src/sw.js); elsewhere createVesselmesh() uses the
// single-threaded core.
// The mesh is the same on any number of threads (docs/ARCHITECTURE.md,
// "Determinism").
//
// The module file is loaded by URL, not bundled: each pool Worker
// (vesselmesh_core_mt.worker.js) imports that same file.

/** The most threads the threaded core starts, the calling one included. */
export const MAX_THREADS = 8;

/** Why the single-threaded core is used here, or '' when the threaded one
 * can run. */
export function singleThreadReason() {
  if (typeof Worker !== 'function') return 'Web Workers are not available here';
  if (typeof SharedArrayBuffer !== 'function' || globalThis.crossOriginIsolated !== true) {
    return 'the page is not cross-origin isolated (its server sends no COOP/COEP headers)';
  }
  if ((globalThis.navigator?.hardwareConcurrency ?? 1) < 2) return 'the browser reports one core';
  return '';
}

/** The browser's cores, at most MAX_THREADS. */
export const defaultThreads = () => Math.min(globalThis.navigator?.hardwareConcurrency ?? 1, MAX_THREADS);

/** Fetches `url` (or fails saying which file). */
async function fetchOk(url) {
  const response = await fetch(url);
  if (!response.ok) throw new Error(`cannot load ${url}: HTTP ${response.status}`);
  return response;
}

/** Rejects after `ms` unless `promise` settles first: a pool Worker that
 * fails to load leaves Emscripten's module waiting for ever. */
export function within(promise, ms, what) {
  let timer;
  const late = new Promise((_, reject) => {
    timer = setTimeout(() => reject(new Error(`${what} did not start within ${ms / 1000} s`)), ms);
  });
  return Promise.race([promise, late]).finally(() => clearTimeout(timer));
}

/**
 * Loads the threaded core with a pool of `threads` - 1 Workers; the core's
 * jobs then use at most `threads` threads (2..MAX_THREADS).
 * @returns {Promise<object>} the Embind module
 */
export async function createThreadedCore(threads) {
  const script = new URL('../dist/vesselmesh_core_mt.mjs', import.meta.url).href;
  const worker = new URL('../dist/vesselmesh_core_mt.worker.js', import.meta.url).href;
  const wasm = new URL('../dist/vesselmesh_core_mt.wasm', import.meta.url).href;
  const [{ default: create }, workerSource, wasmBinary] = await Promise.all([
    import(/* @vite-ignore */ script),
    fetchOk(worker).then((r) => r.blob()),
    fetchOk(wasm).then((r) => r.arrayBuffer()),
  ]);
  // The pool Workers start from a blob: URL of the worker script, which is
  // same-origin wherever a bundler put the script (or inlined it as data:).
  const workerUrl = URL.createObjectURL(new Blob([workerSource], { type: 'text/javascript' }));
  const core = await within(
    create({
      wasmBinary,
      vmPoolSize: threads - 1, // read by the module (PTHREAD_POOL_SIZE, wasm/CMakeLists.txt)
      mainScriptUrlOrBlob: script,
      locateFile: (name) => (name.endsWith('.worker.js') ? workerUrl : name),
    }),
    20_000,
    'the threaded core',
  );
  core.setThreadLimit(threads);
  return core;
}
