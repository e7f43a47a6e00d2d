// The mesh job of the WebAssembly build under Node, for the validation's
// native-versus-wasm comparison: reads IN, meshes it through the JS API
// with the options given as JSON (default: none) and writes the file.
// usage: node validation/wasm_mesh.mjs IN OUT [OPTIONS_JSON]
import { readFileSync, writeFileSync } from 'node:fs';
import { createVesselmesh } from '../wasm/src/vesselmesh.js';

const [input, output, json] = process.argv.slice(2);
if (!output) {
  console.error('usage: node validation/wasm_mesh.mjs IN OUT [OPTIONS_JSON]');
  process.exit(2);
}
const wasmBinary = readFileSync(new URL('../wasm/dist/vesselmesh_core.wasm', import.meta.url));
const api = await createVesselmesh({ wasmBinary });
const result = api.mesh(new Uint8Array(readFileSync(input)), json ? JSON.parse(json) : {});
if (!result.ok) {
  console.error(result.error);
  process.exit(1);
}
writeFileSync(output, result.file);
