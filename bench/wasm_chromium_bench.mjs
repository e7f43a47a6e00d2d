// Benchmark: the mesh job of the WebAssembly build in Chromium (Debian's
// /usr/bin/chromium driven by playwright-core), through the JS API on the
// page's main thread, as bench/wasm_mesh_bench.mjs does under Node. A small
// static server on 127.0.0.1 serves the repository (wasm/src, wasm/dist) and
// a blank page; the STL is handed to the page as bytes. Prints one JSON
// object: per-run wall seconds (performance.now() in the page), median, the
// output's counts and quality, the page's peak JS heap, the browser version.
// With --serve it runs once per line read from stdin, prints each run as a
// JSON line {run, seconds}, and the object above when stdin closes.
//
// usage: node bench/wasm_chromium_bench.mjs FILE.stl [--size H | --per-circumference N]
//          [--runs N | --serve] [--surface-only] [--layers N] [--core-size H]
import { createReadStream, readFileSync, statSync } from 'node:fs';
import { createServer } from 'node:http';
import { basename, extname, join, normalize } from 'node:path';
import { fileURLToPath } from 'node:url';

import { chromium } from 'playwright-core';
import { median, parseBenchArgs, runIndices } from './benchutil.mjs';

const ROOT = fileURLToPath(new URL('..', import.meta.url));
const TYPES = { '.html': 'text/html', '.js': 'text/javascript', '.mjs': 'text/javascript', '.wasm': 'application/wasm' };

const { file, runs, serve, options } = await parseBenchArgs(process.argv.slice(2), 'wasm_chromium_bench.mjs');

// The repository's files under / (no directory listing), and a blank page.
const server = createServer((req, res) => {
  const path = decodeURIComponent(new URL(req.url, 'http://x').pathname);
  if (path === '/') {
    res.writeHead(200, { 'content-type': 'text/html' });
    res.end('<!doctype html><title>vesselmesh bench</title>');
    return;
  }
  const full = normalize(join(ROOT, path));
  if (!full.startsWith(ROOT) || !statSync(full, { throwIfNoEntry: false })?.isFile()) {
    res.writeHead(404);
    res.end();
    return;
  }
  res.writeHead(200, { 'content-type': TYPES[extname(full)] ?? 'application/octet-stream' });
  createReadStream(full).pipe(res);
});
await new Promise((resolve) => server.listen(0, '127.0.0.1', resolve));
const origin = `http://127.0.0.1:${server.address().port}`;

const browser = await chromium.launch({
  executablePath: process.env.CHROMIUM_PATH || '/usr/bin/chromium',
  args: ['--no-sandbox', '--disable-gpu', '--disable-background-networking', '--disable-component-update',
    '--no-first-run', '--disable-sync', '--disable-quic', '--enable-precise-memory-info'],
});
let result;
try {
  const page = await browser.newPage();
  await page.goto(`${origin}/`);
  // The module and the input stay in the page between runs (one evaluate per
  // run, so that runs can be driven one at a time from stdin).
  await page.evaluate(
    async ({ bytes }) => {
      const { createVesselmesh } = await import('/wasm/src/vesselmesh.js');
      window.bench = { api: await createVesselmesh(), input: new Uint8Array(bytes), last: null, heap: 0 };
    },
    { bytes: Array.from(readFileSync(file)) },
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
      };
    });
    result.seconds = seconds;
  }
  result.browser = `Chromium ${browser.version()}`;
} finally {
  await browser.close();
  server.close();
}
if (result.ok) result.median_seconds = median(result.seconds);
console.log(JSON.stringify({ file: basename(file), options, runs: result.seconds?.length ?? 0, ...result }));
process.exit(result.ok ? 0 : 1);
