// The package's entry in Node ('vesselmesh'): createVesselmesh() reads the
// wasm shipped in the package (wasm/dist/vesselmesh_core.wasm) unless given
// wasmBinary. VesselmeshClient needs a Web Worker: browsers only.
import { readFile } from 'node:fs/promises';

import { createVesselmesh as createWithBinary } from './vesselmesh.js';

export { VesselmeshClient } from './client.js';

/** @param {{ wasmBinary?: ArrayBuffer|Uint8Array }} [options] */
export async function createVesselmesh(options = {}) {
  const wasmBinary = options.wasmBinary ?? (await readFile(new URL('../dist/vesselmesh_core.wasm', import.meta.url)));
  return createWithBinary({ ...options, wasmBinary });
}
