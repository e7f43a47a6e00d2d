// The package's entry in Node ('vesselmesh'): createVesselmesh() reads the
// wasm shipped in the package (wasm/dist/vesselmesh_core.wasm) unless given
// wasmBinary. VesselmeshClient needs a Web Worker: browsers only.
import { readFile } from 'node:fs/promises';

import { createVesselmesh as createWithBinary } from './vesselmesh.js';

export { VesselmeshClient } from './client.js';

/** In Node the core runs on one thread: Emscripten 3.1.6's threaded
 * module cannot start its Workers in an ES module there (the vesselmesh CLI
 * has threads and writes the same mesh).
 * @param {{ wasmBinary?: ArrayBuffer|Uint8Array }} [options] */
export async function createVesselmesh(options = {}) {
  const wasmBinary = options.wasmBinary ?? (await readFile(new URL('../dist/vesselmesh_core.wasm', import.meta.url)));
  const api = await createWithBinary({ ...options, wasmBinary });
  return { ...api, threadsNote: 'Node: the WebAssembly core runs on one thread here (the CLI has threads)' };
}
