// A static host sends no COOP/COEP headers (e2e/static-server.js here), so
// the page is not cross-origin isolated; the app's service worker adds the
// headers to what it serves (web/src/sw.js), and the page reloads once
// through it (web/src/isolation.js): then it meshes on the threaded core.
// Without service workers it works on one thread, and it never reloads
// more than once.
import { fileURLToPath } from 'node:url';

import { expect, test } from '@playwright/test';

import { screenshots } from './helpers.js';
import { serveStatic } from './static-server.js';

const DIST = fileURLToPath(new URL('../web/dist/', import.meta.url));

let server;
test.beforeAll(async () => {
  server = await serveStatic({ dirs: { '/': DIST } });
});
test.afterAll(() => server?.close());

/** A new context (with `options`) on the static server's app: its page,
 * the page's errors, the main frame's loads and every request of the
 * context (page, workers, service worker) to another origin. */
async function open(browser, options = {}) {
  const context = await browser.newContext({ ...options, baseURL: server.url });
  const page = await context.newPage();
  const watch = { errors: [], loads: 0, foreign: [] };
  page.on('pageerror', (e) => watch.errors.push(e.message));
  page.on('load', () => watch.loads++);
  context.on('request', (request) => {
    const url = new URL(request.url());
    if (['http:', 'https:', 'ws:', 'wss:'].includes(url.protocol) && url.host !== `127.0.0.1:${server.port}`) {
      watch.foreign.push(request.url());
    }
  });
  await page.goto('index.html');
  await expect(page.locator('body')).toHaveAttribute('data-ready', 'true');
  return { context, page, watch };
}

/** Loads the sample and meshes it coarsely; returns the threads the page
 * says it meshed on. */
async function meshSample(page) {
  await page.getByTestId('load-sample').click();
  await expect(page.getByTestId('stat-openings')).toHaveText('3');
  await page.getByTestId('size-value').fill('16');
  await page.getByTestId('remesh').click();
  await expect(page.getByTestId('volume-result')).toBeVisible({ timeout: 60_000 });
  await expect(page.getByTestId('error')).toBeHidden();
  return Number(await page.getByTestId('out-time').getAttribute('data-threads'));
}

/** The isolation headers of a response, by lower-case name. */
const isolationHeaders = (headers) =>
  Object.fromEntries(
    ['cross-origin-opener-policy', 'cross-origin-embedder-policy', 'cross-origin-resource-policy', 'content-type'].map((n) => [
      n,
      headers.get(n),
    ]),
  );

test('on a static host, the page reloads once through its service worker and meshes on all cores', async ({ browser }) => {
  // The server itself sends no isolation header.
  const direct = isolationHeaders((await fetch(`${server.url}index.html`)).headers);
  expect(direct['cross-origin-opener-policy']).toBeNull();
  expect(direct['cross-origin-embedder-policy']).toBeNull();

  const { context, page, watch } = await open(browser);
  expect(await page.evaluate(() => navigator.serviceWorker.controller !== null)).toBe(true);
  expect(await page.evaluate(() => crossOriginIsolated)).toBe(true);
  await expect.poll(() => watch.loads).toBe(2); // the first load and the one reload

  // Through the service worker: the precached page, and a file of the
  // origin that is not precached (from the network), keep their type and
  // get the headers.
  const served = await page.evaluate(async () =>
    Promise.all(
      ['index.html', 'manifest.webmanifest?not-precached'].map(async (u) => {
        const r = await fetch(u);
        return Object.fromEntries(r.headers);
      }),
    ),
  );
  for (const [headers, type] of [
    [served[0], 'text/html; charset=utf-8'],
    [served[1], 'application/manifest+json'],
  ]) {
    expect(headers).toMatchObject({
      'content-type': type,
      'cross-origin-opener-policy': 'same-origin',
      'cross-origin-embedder-policy': 'require-corp',
      'cross-origin-resource-policy': 'same-origin',
    });
  }

  const cores = await page.evaluate(() => Math.min(navigator.hardwareConcurrency, 8));
  expect(cores).toBeGreaterThan(1);
  expect(await meshSample(page)).toBe(cores);
  await expect(page.getByTestId('out-time')).toHaveText(new RegExp(`on ${cores} threads$`));
  await expect(page.getByTestId('out-time')).toHaveAttribute('title', '');
  await screenshots(page, 'isolated-static-host', page.getByTestId('out-time'));

  // The next visit comes through the worker at once: no reload.
  await page.reload();
  await expect(page.locator('body')).toHaveAttribute('data-ready', 'true');
  expect(await page.evaluate(() => crossOriginIsolated)).toBe(true);
  await expect.poll(() => watch.loads).toBe(3);
  expect(watch.foreign).toEqual([]);
  expect(watch.errors).toEqual([]);
  await context.close();
});

test('with service workers blocked, the page works on one thread and does not reload', async ({ browser }) => {
  const { context, page, watch } = await open(browser, { serviceWorkers: 'block' });
  expect(await page.evaluate(() => crossOriginIsolated)).toBe(false);
  expect(await meshSample(page)).toBe(1);
  await expect(page.getByTestId('out-time')).toHaveText(/on one thread$/);
  await expect(page.getByTestId('out-time')).toHaveAttribute('title', /not cross-origin isolated/);
  await screenshots(page, 'static-host-one-thread', page.getByTestId('out-time'));
  expect(watch.loads).toBe(1);
  expect(watch.foreign).toEqual([]);
  expect(watch.errors).toEqual([]);
  await context.close();
});

test('once it has reloaded in a tab, a page still not isolated stays on one thread', async ({ browser }) => {
  // As if the one reload had happened and the browser still did not
  // isolate the page: it starts, and the worker's claim does not reload it.
  const context = await browser.newContext({ baseURL: server.url });
  await context.addInitScript(() => sessionStorage.setItem('vesselmesh:isolation-reload', '1'));
  const page = await context.newPage();
  const errors = [];
  page.on('pageerror', (e) => errors.push(e.message));
  let loads = 0;
  page.on('load', () => loads++);
  await page.goto('index.html');
  await expect(page.locator('body')).toHaveAttribute('data-ready', 'true');
  await page.waitForFunction(() => navigator.serviceWorker.controller !== null);
  await page.waitForTimeout(500); // a reload would have started by now
  expect(await page.evaluate(() => crossOriginIsolated)).toBe(false);
  await expect(page.locator('body')).toHaveAttribute('data-ready', 'true');
  expect(loads).toBe(1);
  expect(errors).toEqual([]);
  await context.close();
});
