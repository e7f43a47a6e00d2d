import { expect, test } from '@playwright/test';

import { meshAndCancel, openApp, screenshots, TETRA_ASCII, upload } from './helpers.js';
import { freePort, startPreview } from './preview.js';

test('no request leaves the origin, and the app works offline once loaded', async ({ page, context }) => {
  const foreign = await openApp(page);
  await context.setOffline(true);
  await upload(page, 'tetra.stl', Buffer.from(TETRA_ASCII));
  await expect(page.getByTestId('stat-triangles')).toHaveText('4');
  // Closed, without an opening: said before meshing; the user goes on.
  await page.getByTestId('export').click();
  const [download] = await Promise.all([page.waitForEvent('download'), page.getByTestId('mesh-anyway').click()]);
  expect(download.suggestedFilename()).toBe('tetra.msh');
  await page.getByTestId('load-sample').click();
  await expect(page.getByTestId('stat-openings')).toHaveText('3');
  expect(foreign).toEqual([]);
});

test('installed: after one visit the app reloads and meshes with its server stopped, Cancel included', async ({ browser }) => {
  const port = await freePort();
  const server = await startPreview(port);
  const context = await browser.newContext({ baseURL: `http://127.0.0.1:${port}/` });
  const page = await context.newPage();
  const errors = [];
  page.on('pageerror', (e) => errors.push(e.message));
  const foreign = [];
  page.on('request', (request) => {
    const url = new URL(request.url());
    if (['http:', 'https:', 'ws:', 'wss:'].includes(url.protocol) && url.host !== `127.0.0.1:${port}`) {
      foreign.push(request.url());
    }
  });
  try {
    await page.goto('/');
    await expect(page.locator('body')).toHaveAttribute('data-ready', 'true');
    expect(await page.evaluate(() => crossOriginIsolated)).toBe(true);
    const manifest = await page.locator('link[rel="manifest"]').getAttribute('href');
    expect(manifest).toMatch(/manifest\.webmanifest$/);
    // The service worker is active and controls the page once it has
    // precached everything.
    await page.evaluate(() => navigator.serviceWorker.ready);
    await page.waitForFunction(() => navigator.serviceWorker.controller !== null);
    const cached = await page.evaluate(async () => {
      const names = [];
      for (const key of await caches.keys()) {
        for (const request of await (await caches.open(key)).keys()) names.push(new URL(request.url).pathname);
      }
      return names;
    });
    expect(cached.some((n) => /\/assets\/worker-.*\.js$/.test(n))).toBe(true);
    expect(cached.some((n) => /\.wasm$/.test(n))).toBe(true);
    expect(cached.some((n) => /index\.html$/.test(n))).toBe(true);
  } finally {
    await server.stop();
  }
  // No server now: a fetch that misses the cache fails.
  await expect(page.evaluate((u) => fetch(u).then(() => 'answered', () => 'failed'), `http://127.0.0.1:${port}/not-cached`)).resolves.toBe('failed');
  await page.reload();
  await expect(page.locator('body')).toHaveAttribute('data-ready', 'true');
  expect(await page.evaluate(() => crossOriginIsolated)).toBe(true); // the cached headers
  await page.getByTestId('load-sample').click();
  await expect(page.getByTestId('stat-openings')).toHaveText('3');
  await meshAndCancel(page);
  // The restarted worker's script and wasm come from the cache.
  await page.getByTestId('size-value').fill('16');
  await page.getByTestId('remesh').click();
  await expect(page.getByTestId('volume-view')).toHaveAttribute('data-triangles', /^[1-9]\d*$/, { timeout: 60_000 });
  await expect(page.getByTestId('error')).toBeHidden();
  // The threaded core is precached too: offline, the app keeps its threads.
  expect(Number(await page.getByTestId('out-time').getAttribute('data-threads'))).toBe(
    Math.min(await page.evaluate(() => navigator.hardwareConcurrency), 8),
  );
  await screenshots(page, 'installed-offline');
  expect(foreign).toEqual([]);
  expect(errors).toEqual([]);
  await context.close();
});
