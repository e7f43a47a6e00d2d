// A blank, cross-origin isolated page (COOP/COEP) in Debian's Chromium
// (/usr/bin/chromium, driven by playwright-core), for running the JS API in
// a browser from a script: a small static server on 127.0.0.1 serves the
// repository (wasm/src, wasm/dist) under / and the blank page at /.
// Used by bench/wasm_chromium_bench.mjs and validation/chromium_mesh.mjs.
import { createReadStream, statSync } from 'node:fs';
import { createServer } from 'node:http';
import { extname, join, normalize } from 'node:path';
import { fileURLToPath } from 'node:url';

import { chromium } from 'playwright-core';

const ROOT = fileURLToPath(new URL('..', import.meta.url));
const TYPES = { '.html': 'text/html', '.js': 'text/javascript', '.mjs': 'text/javascript', '.wasm': 'application/wasm' };
const ISOLATED = { 'cross-origin-opener-policy': 'same-origin', 'cross-origin-embedder-policy': 'require-corp' };

/** Opens the page; resolves with { page, browser, close() }. */
export async function openIsolatedPage() {
  // The repository's files under / (no directory listing), and a blank page.
  const server = createServer((req, res) => {
    const path = decodeURIComponent(new URL(req.url, 'http://x').pathname);
    if (path === '/') {
      res.writeHead(200, { 'content-type': 'text/html', ...ISOLATED });
      res.end('<!doctype html><title>vesselmesh</title>');
      return;
    }
    const full = normalize(join(ROOT, path));
    if (!full.startsWith(ROOT) || !statSync(full, { throwIfNoEntry: false })?.isFile()) {
      res.writeHead(404);
      res.end();
      return;
    }
    res.writeHead(200, { 'content-type': TYPES[extname(full)] ?? 'application/octet-stream', ...ISOLATED });
    createReadStream(full).pipe(res);
  });
  await new Promise((resolve) => server.listen(0, '127.0.0.1', resolve));
  const browser = await chromium.launch({
    executablePath: process.env.CHROMIUM_PATH || '/usr/bin/chromium',
    args: ['--no-sandbox', '--disable-gpu', '--disable-background-networking', '--disable-component-update',
      '--no-first-run', '--disable-sync', '--disable-quic', '--enable-precise-memory-info'],
  });
  const page = await browser.newPage();
  await page.goto(`http://127.0.0.1:${server.address().port}/`);
  const close = async () => {
    await browser.close();
    server.close();
  };
  return { page, browser, close };
}
