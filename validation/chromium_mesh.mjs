// The mesh job of the WebAssembly build in Chromium, for the validation's
// same-bytes check: meshes IN through the JS API in a cross-origin isolated
// page (bench/chromium_page.mjs) on T threads (the threaded core; T = 1 the
// single-threaded one) with the options given as JSON (default: none), and
// prints one JSON line { ok, threads, bytes, sha256 } of the written file
// (its hash, not its bytes, crosses back from the page).
// usage: node validation/chromium_mesh.mjs IN THREADS [OPTIONS_JSON]
import { readFileSync } from 'node:fs';

import { openIsolatedPage } from '../bench/chromium_page.mjs';

const [input, threads, json] = process.argv.slice(2);
if (!threads) {
  console.error('usage: node validation/chromium_mesh.mjs IN THREADS [OPTIONS_JSON]');
  process.exit(2);
}
const { page, close } = await openIsolatedPage();
let result;
try {
  result = await page.evaluate(
    async ({ bytes, threads, options }) => {
      const { createVesselmesh } = await import('/wasm/src/vesselmesh.js');
      const api = await createVesselmesh({ threads });
      const r = api.mesh(new Uint8Array(bytes), options);
      if (!r.ok) return { ok: false, error: r.error, threads: api.threads };
      const digest = new Uint8Array(await crypto.subtle.digest('SHA-256', r.file));
      const sha256 = Array.from(digest, (b) => b.toString(16).padStart(2, '0')).join('');
      return { ok: true, threads: api.threads, threadsNote: api.threadsNote, bytes: r.file.length, sha256 };
    },
    { bytes: Array.from(readFileSync(input)), threads: Number(threads), options: json ? JSON.parse(json) : {} },
  );
} finally {
  await close();
}
console.log(JSON.stringify(result));
process.exit(result.ok ? 0 : 1);
