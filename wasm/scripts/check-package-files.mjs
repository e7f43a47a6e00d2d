// `npm pack` / `npm publish` guard (prepack): the package ships build
// outputs that are not committed; refuse to pack without them.
import { existsSync } from 'node:fs';

const root = new URL('../../', import.meta.url);
const needed = [
  ['wasm/dist/vesselmesh_core.mjs', 'build the WebAssembly module (cmake --build build-wasm, see scripts/setup.sh)'],
  ['wasm/dist/vesselmesh_core.wasm', 'build the WebAssembly module (cmake --build build-wasm, see scripts/setup.sh)'],
  ['dist/element/vessel-mesher.js', 'run npm run build:web'],
];
const missing = needed.filter(([path]) => !existsSync(new URL(path, root)));
for (const [path, what] of missing) console.error(`npm pack: ${path} is missing: ${what}`);
if (missing.length) process.exit(1);
