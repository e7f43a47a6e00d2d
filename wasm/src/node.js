// The package's entry in Node ('vesselmesh'): createVesselmesh() reads the
// wasm shipped in the package (wasm/dist/) unless given wasmBinary, and runs
// the threaded core with its pool on worker_threads (node-threads.js).
// VesselmeshClient needs a Web Worker: browsers only.
import { readFile } from 'node:fs/promises';

import { createThreadedCore, defaultThreads, singleThreadReason } from './node-threads.js';
import { createVesselmeshIn } from './vesselmesh.js';

export { VesselmeshClient } from './client.js';

const NODE = {
  loadWasmBinary: () => readFile(new URL('../dist/vesselmesh_core.wasm', import.meta.url)),
  singleThreadReason,
  defaultThreads,
  createThreadedCore,
};

/** Loads the WebAssembly module and returns the API, as in the browser:
 * jobs run on up to `threads` threads (0, the default: the machine's cores,
 * os.availableParallelism(); at most 8) on the threaded core, whose pool
 * threads do not keep the process alive; threads: 1, a given wasmBinary or
 * a threaded core that does not start: the single-threaded core, and
 * threadsNote says why.
 * @param {{ wasmBinary?: ArrayBuffer|Uint8Array, threads?: number }} [options] */
export async function createVesselmesh(options = {}) {
  return createVesselmeshIn(NODE, options);
}
