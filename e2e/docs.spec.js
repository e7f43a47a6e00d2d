// The documentation site (docs/dist/, npm run build:docs): its live
// <vessel-mesher> examples mesh the bundled sample in place, the options
// page lists every option of the table with its unit, every documentation
// page is on it with its links resolved, and nothing is requested outside
// the site's origin.
import { existsSync } from 'node:fs';

import { expect, test } from '@playwright/test';

import { createVesselmesh } from '../wasm/src/node.js';
import { screenshots } from './helpers.js';
import { freePort, startPreview } from './preview.js';
import { serveStatic } from './static-server.js';

const DOCS = new URL('../docs/dist/', import.meta.url).pathname;

let server;
test.beforeAll(async () => {
  expect(existsSync(`${DOCS}index.html`), 'docs/dist is built (npm run build:docs)').toBe(true);
  server = await serveStatic({ dirs: { '/': DOCS } });
});
test.afterAll(() => server?.close());

function watch(page) {
  const foreign = [];
  const errors = [];
  page.on('request', (request) => {
    const url = new URL(request.url());
    if (['http:', 'https:', 'ws:', 'wss:'].includes(url.protocol) && url.host !== `127.0.0.1:${server.port}`) {
      foreign.push(request.url());
    }
  });
  page.on('pageerror', (e) => errors.push(e.message));
  return { foreign, errors };
}

test('the getting-started page meshes the sample in place', async ({ page }) => {
  const { foreign, errors } = watch(page);
  await page.goto(`${server.url}index.html`);
  const el = page.locator('#start');
  await expect(el.getByRole('status')).toContainText('3 openings', { timeout: 60_000 });
  await el.getByRole('button', { name: 'Mesh' }).click();
  await expect(el.getByRole('status')).toContainText('tetrahedra', { timeout: 60_000 });
  await screenshots(page, 'docs-start', el);
  expect(foreign).toEqual([]);
  expect(errors).toEqual([]);
});

test('the element page: a scripted example meshes and logs its events', async ({ page }) => {
  const { foreign, errors } = watch(page);
  await page.goto(`${server.url}element.html`);
  await expect(page.locator('body')).toHaveAttribute('data-scripted', 'meshed', { timeout: 60_000 });
  const log = page.locator('#log');
  await expect(log).toContainText('vm-analyzed: 3 openings');
  await expect(log).toContainText('vm-progress');
  await expect(log).toContainText(/vm-meshed: \d+ tetrahedra/);
  await expect(page.locator('#full').getByRole('status')).toContainText('3 openings');
  await screenshots(page, 'docs-element', page.locator('#scripted'));
  expect(foreign).toEqual([]);
  expect(errors).toEqual([]);
});

test('the family page: its live element meshes a family of three and downloads the report', async ({ page }) => {
  const { foreign, errors } = watch(page);
  await page.goto(`${server.url}family.html`);
  const el = page.locator('#family');
  await expect(el.getByRole('status')).toContainText('3 openings', { timeout: 60_000 });
  const meshed = page.evaluate(
    () => new Promise((resolve) => document.getElementById('family').addEventListener('vm-meshed', (e) => resolve(e.detail.family), { once: true })),
  );
  await el.getByRole('button', { name: 'Mesh' }).click();
  const family = await meshed;
  expect(family.rows.map((r) => r.file)).toEqual(['mesh_0.msh', 'mesh_1.msh', 'mesh_2.msh']);
  for (const row of family.rows.slice(1)) expect(Math.abs(row.ratio - 1.4)).toBeLessThan(0.14);
  const download = page.waitForEvent('download');
  await el.getByRole('button', { name: 'Download report' }).click();
  expect((await download).suggestedFilename()).toMatch(/report\.html$/);
  expect(foreign).toEqual([]);
  expect(errors).toEqual([]);
});

test('the options page lists every option of the table with its unit; every page is linked and its links resolve', async ({ page }) => {
  const { optionTable } = await createVesselmesh();
  const { foreign } = watch(page);
  await page.goto(`${server.url}options.html`);
  for (const command of ['info', 'mesh', 'phantom']) {
    const expected = optionTable.filter((o) => o.commands.includes(command));
    const rows = page.locator(`table[data-command="${command}"] tbody tr`);
    await expect(rows).toHaveCount(expected.length);
    for (const o of expected.filter((o) => o.unit === 'length')) {
      await expect(page.locator(`[id="${command}-${o.id}"] .unit`)).toContainText("model's unit");
    }
  }
  const links = await page.locator('header nav a').evaluateAll((as) => as.map((a) => a.getAttribute('href')));
  expect(links).toEqual([
    'index.html', 'cli.html', 'options.html', 'outputs.html', 'js-api.html', 'element.html',
    'family.html', 'app.html', 'method.html', 'benchmarks.html', 'limits.html', 'architecture.html', 'decisions.html',
  ]);
  const broken = [];
  for (const href of links) {
    const response = await page.goto(`${server.url}${href}`);
    expect(response.status()).toBe(200);
    await expect(page.locator('main h1, main h2').first()).toBeVisible();
    // The links in the text: to a page of the site, and to a heading there.
    const targets = await page.locator('main a[href]').evaluateAll((as) => as.map((a) => a.getAttribute('href')));
    for (const target of targets.filter((t) => !/^https?:/.test(t))) {
      const [file, fragment] = target.split('#');
      if (file && !links.includes(file)) broken.push(`${href}: ${target}`);
      else if (fragment) {
        if (file && file !== href) await page.goto(`${server.url}${file}`);
        if ((await page.locator(`[id="${decodeURIComponent(fragment)}"]`).count()) !== 1) broken.push(`${href}: ${target}`);
        if (file && file !== href) await page.goto(`${server.url}${href}`);
      }
    }
  }
  expect(broken).toEqual([]);
  await page.goto(`${server.url}cli.html`);
  await expect(page.locator('main')).toContainText('damaged_ends');
  await screenshots(page, 'docs-cli');
  await page.goto(`${server.url}method.html`);
  await expect(page.locator('main')).toContainText('γ');
  await screenshots(page, 'docs-method');
  expect(foreign).toEqual([]);
});

test('served by npm run preview:docs, the docs are cross-origin isolated and the live example still meshes', async ({ page }) => {
  const preview = await startPreview(await freePort(), 'web/vite.config.js', ['--outDir', '../docs/dist']);
  try {
    const errors = [];
    page.on('pageerror', (e) => errors.push(e.message));
    await page.goto(`${preview.url}index.html`);
    expect(await page.evaluate(() => self.crossOriginIsolated)).toBe(true);
    const el = page.locator('#start');
    await expect(el.getByRole('status')).toContainText('3 openings', { timeout: 60_000 });
    await el.getByRole('button', { name: 'Mesh' }).click();
    await expect(el.getByRole('status')).toContainText('tetrahedra', { timeout: 60_000 });
    expect(errors).toEqual([]);
  } finally {
    await preview.stop();
  }
});
