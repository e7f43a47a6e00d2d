// Benchmark: the mesh job of the WebAssembly build in Chromium (Debian's
// /usr/bin/chromium driven by playwright-core), through the JS API on the
// main thread of a blank page (bench/chromium_page.mjs), as
// bench/wasm_mesh_bench.mjs does under Node. The page is cross-origin
// isolated (COOP/COEP), so that with --threads T
// (T > 1; 0: the browser's cores) the API loads its threaded core on T
// threads; --threads 1 or none: the single-threaded core. The STL is handed
// to the page as bytes. Prints one JSON object: per-run wall seconds
// (performance.now() in the page), median, the threads the core ran on, the
// output's counts and quality, the page's peak JS heap, the browser version.
// With --serve it runs once per line read from stdin, prints each run as a
// JSON line {run, seconds}, and the object above when stdin closes.
//
// usage: node bench/wasm_chromium_bench.mjs FILE.stl [--size H | --per-circumference N]
//          [--runs N | --serve] [--surface-only] [--layers N] [--core-size H] [--threads T]
import { readFileSync } from 'node:fs';
import { basename } from 'node:path';

import { median, parseBenchArgs, runIndices } from './benchutil.mjs';
import { openIsolatedPage } from './chromium_page.mjs';

const { file, runs, serve, options } = await parseBenchArgs(process.argv.slice(2), 'wasm_chromium_bench.mjs');

const { page, browser, close } = await openIsolatedPage();
let result;
try {
  // The module and the input stay in the page between runs (one evaluate per
  // run, so that runs can be driven one at a time from stdin).
  await page.evaluate(
    async ({ bytes, threads }) => {
      const { createVesselmesh } = await import('/wasm/src/vesselmesh.js');
      const api = await createVesselmesh({ threads: threads || undefined });
      window.bench = { api, input: new Uint8Array(bytes), last: null, heap: 0 };
    },
    { bytes: Array.from(readFileSync(file)), threads: options.threads ?? 1 },
  );
  const seconds = [];
  for await (const r of runIndices(runs, serve)) {
    const run = await page.evaluate((options) => {
      const b = window.bench;
      const t = performance.now();
      b.last = b.api.mesh(b.input, options);
      const dt = (performance.now() - t) / 1000;
      b.heap = Math.max(b.heap, performance.memory?.usedJSHeapSize ?? 0);
      return b.last.ok ? { ok: true, seconds: dt } : { ok: false, error: b.last.error };
    }, options);
    if (!run.ok) {
      result = run;
      break;
    }
    seconds.push(run.seconds);
    if (serve) console.log(JSON.stringify({ run: r + 1, seconds: run.seconds }));
  }
  if (!result && !seconds.length) result = { ok: false, error: 'no run' };
  if (!result) {
    result = await page.evaluate(() => {
      const out = window.bench.last.report.output;
      return {
        ok: true,
        triangles: out.triangles,
        tets: out.volume?.tetrahedra ?? 0,
        quality: { min: out.quality.min, mean: out.quality.mean },
        peak_js_heap_mb: window.bench.heap / 2 ** 20,
        threads: window.bench.api.threads,
        threads_note: window.bench.api.threadsNote,
      };
    });
    result.seconds = seconds;
  }
  result.browser = `Chromium ${browser.version()}`;
} finally {
  await close();
}
if (result.ok) result.median_seconds = median(result.seconds);
console.log(JSON.stringify({ file: basename(file), options, runs: result.seconds?.length ?? 0, ...result }));
process.exit(result.ok ? 0 : 1);
