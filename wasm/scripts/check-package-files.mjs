// `npm pack` / `npm publish` guard (prepack): the package ships build
// outputs that are not committed; refuse to pack without them.
import { existsSync } from 'node:fs';

const root = new URL('../../', import.meta.url);
const WASM = 'build the WebAssembly modules (cmake --build build-wasm, see scripts/setup.sh)';
const needed = [
  ...['vesselmesh_core.mjs', 'vesselmesh_core.wasm', 'vesselmesh_core_mt.mjs', 'vesselmesh_core_mt.wasm', 'vesselmesh_core_mt.worker.js'].map((f) => [`wasm/dist/${f}`, WASM]),
  ['dist/element/vessel-mesher.js', 'run npm run build:web'],
];
const missing = needed.filter(([path]) => !existsSync(new URL(path, root)));
for (const [path, what] of missing) console.error(`npm pack: ${path} is missing: ${what}`);
if (missing.length) process.exit(1);
