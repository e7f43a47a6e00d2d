// The npm package installed into a fresh project (wasm/test/consumer.js):
// <vessel-mesher> on a host page that serves the installed package itself,
// with hostile CSS: two elements, each with its own worker, load (src
// attribute / load()), mesh (button / mesh()), send their events and export;
// and a Vite app bundling the package meshes the sample with the worker
// client, the API and the element. Nothing is requested outside the origin.
import { existsSync, readFileSync } from 'node:fs';
import { join } from 'node:path';

import { expect, test } from '@playwright/test';

import { buildViteApp, installedConsumer } from '../wasm/test/consumer.js';
import { createVesselmesh } from '../wasm/src/vesselmesh.js';
import { screenshots } from './helpers.js';
import { serveStatic } from './static-server.js';

const BUILT = new URL('../dist/element/vessel-mesher.js', import.meta.url).pathname;

let consumer;
test.beforeAll(() => {
  expect(existsSync(BUILT), 'dist/element is built (npm run build:web)').toBe(true);
  consumer = installedConsumer();
});
test.afterAll(() => consumer?.cleanup());

/** Records requests to any origin but the server's. */
function outsideRequests(page, server) {
  const foreign = [];
  page.on('request', (request) => {
    const url = new URL(request.url());
    if (['http:', 'https:', 'ws:', 'wss:'].includes(url.protocol) && url.host !== `127.0.0.1:${server.port}`) {
      foreign.push(request.url());
    }
  });
  return foreign;
}

const HOST_PAGE = `<!doctype html>
<html lang="en"><head><meta charset="utf-8"><title>host</title>
<style>
  /* A host page's CSS must not reach into the element. */
  button, select, progress, canvas { display: none !important; }
  * { color: #f0f !important; font-size: 40px !important; }
  vessel-mesher { height: 360px; margin: 8px; }
</style></head>
<body>
  <h1>Two meshers</h1>
  <vessel-mesher id="a" src="sample.stl" options='{"perCircumference": 12}'></vessel-mesher>
  <vessel-mesher id="b" compact options='{"perCircumference": 10, "surfaceOnly": true}'></vessel-mesher>
  <script type="module">
    import './vesselmesh/element/vessel-mesher.js';
    window.events = [];
    for (const type of ['vm-analyzed', 'vm-progress', 'vm-meshed', 'vm-error']) {
      document.addEventListener(type, (e) => window.events.push({ type, id: e.target.id, detail: type === 'vm-meshed' ? { ok: e.detail.ok } : e.detail }));
    }
  </script>
</body></html>`;

test('two <vessel-mesher> elements on a host page mesh independently and send their events', async ({ page }) => {
  const api = await createVesselmesh({ wasmBinary: readFileSync(new URL('../wasm/dist/vesselmesh_core.wasm', import.meta.url)) });
  const sample = api.makePhantom({ kind: 'bifurcation', voxel: 0.08, noise: 0.3 });
  expect(sample.ok).toBe(true);
  const server = await serveStatic({
    files: { '/': HOST_PAGE, '/sample.stl': Buffer.from(sample.stl) },
    dirs: { '/vesselmesh/element/': join(consumer.pkg, 'dist/element/') },
  });
  try {
    const foreign = outsideRequests(page, server);
    const errors = [];
    page.on('pageerror', (e) => errors.push(e.message));
    await page.goto(server.url);

    // a: loads its src; meshed with its own Mesh button.
    const a = page.locator('#a');
    await expect(a.getByRole('status')).toContainText('3 openings', { timeout: 60_000 });
    await expect(a.getByRole('button', { name: 'Mesh' })).toBeVisible(); // host CSS hides buttons
    await expect(a.getByRole('button', { name: 'Open…' })).toBeVisible();
    await a.getByRole('button', { name: 'Mesh' }).click();
    await expect(a.getByRole('status')).toContainText('tetrahedra', { timeout: 60_000 });

    // b (compact): load() with bytes, mesh() with an override, export().
    const b = page.locator('#b');
    await expect(b.getByRole('button', { name: 'Open…' })).toBeHidden();
    const analysis = await page.evaluate(async () => {
      const bytes = new Uint8Array(await (await fetch('sample.stl')).arrayBuffer());
      const analysis = await document.getElementById('b').load(bytes);
      return { openings: analysis.openings.length };
    });
    expect(analysis.openings).toBe(3);
    const meshed = await page.evaluate(async () => {
      const el = document.getElementById('b');
      const result = await el.mesh({ mshVersion: '2.2' });
      const msh = await (await el.export('msh')).text();
      const vtp = await el.export('vtp');
      const mshType = (await el.export('msh')).type;
      await el.mesh({ mshBinary: true });
      const binaryType = (await el.export('msh')).type;
      return {
        mshType,
        binaryType,
        ok: result.ok,
        hasVolume: Boolean(result.volume),
        triangles: result.report.output.triangles,
        head: msh.slice(0, 20),
        vtpType: vtp.type,
        vtpHead: (await vtp.text()).slice(0, 400),
      };
    });
    expect(meshed.ok).toBe(true);
    expect([meshed.mshType, meshed.binaryType]).toEqual(['text/plain', 'application/octet-stream']);
    expect(meshed.hasVolume).toBe(false); // surfaceOnly from its options attribute
    expect(meshed.triangles).toBeGreaterThan(100);
    expect(meshed.head).toBe('$MeshFormat\n2.2 0 8\n');
    expect(meshed.vtpHead).toContain('<VTKFile type="PolyData"');

    // A bad option: vm-error with the API's message; the result is the failure.
    const bad = await page.evaluate(() => document.getElementById('b').mesh({ perCircumference: -1 }));
    expect(bad.ok).toBe(false);

    const events = await page.evaluate(() => window.events);
    const of = (id, type) => events.filter((e) => e.id === id && e.type === type);
    for (const id of ['a', 'b']) {
      expect(of(id, 'vm-analyzed')).toHaveLength(1);
      expect(of(id, 'vm-meshed').length).toBeGreaterThanOrEqual(1);
      expect(of(id, 'vm-meshed')[0].detail.ok).toBe(true);
      const progress = of(id, 'vm-progress');
      expect(progress.length).toBeGreaterThan(1);
      for (const { detail } of progress) {
        expect(detail.fraction).toBeGreaterThanOrEqual(0);
        expect(detail.fraction).toBeLessThanOrEqual(1);
        expect(typeof detail.stage).toBe('string');
      }
    }
    expect(of('a', 'vm-error')).toEqual([]);
    expect(of('b', 'vm-error')).toHaveLength(1);
    expect(of('b', 'vm-error')[0].detail.message).toMatch(/\S/);

    // Each element has its own worker, started from the page's origin.
    const workers = page.workers().map((w) => new URL(w.url()));
    expect(workers.length).toBeGreaterThanOrEqual(2);
    for (const url of workers) expect(url.host).toBe(`127.0.0.1:${server.port}`);

    await screenshots(page, 'element', page.locator('#b'));
    expect(foreign).toEqual([]);
    expect(errors).toEqual([]);
  } finally {
    await server.close();
  }
});

test('a Vite app that installed the package meshes the sample with the client, the API and the element', async ({ page }) => {
  // Packs, installs and builds an app first: minutes when the other worker
  // meshes a large tree on a 2-core machine.
  test.setTimeout(300_000);
  const server = await serveStatic({ dirs: { '/': buildViteApp(consumer) }, files: {} });
  try {
    const foreign = outsideRequests(page, server);
    const errors = [];
    page.on('pageerror', (e) => errors.push(e.message));
    await page.goto(`${server.url}index.html`);
    await expect(page.locator('#out')).toHaveAttribute('data-result', /./, { timeout: 60_000 });
    const result = JSON.parse(await page.locator('#out').getAttribute('data-result'));
    expect(result.error).toBeUndefined();
    expect(result.worker).toBeGreaterThan(1000);
    expect(result.direct).toBeGreaterThan(100);
    expect(result.element).toBe(result.worker); // the same options, the same mesh
    expect(foreign).toEqual([]);
    expect(errors).toEqual([]);
  } finally {
    await server.close();
  }
});
