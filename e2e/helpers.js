// Shared helpers of the e2e specs: open the app with every request outside
// its origin recorded, generate surface inputs in the test itself, download
// exports and take screenshots.
import AxeBuilder from '@axe-core/playwright';
import { expect } from '@playwright/test';

import { readFileSync } from 'node:fs';

import { HOST } from './port.js';
import { cappedTubeVtp as cappedTubeText } from '../wasm/test/capped-tube-vtp.js';
import { createVesselmesh } from '../wasm/src/vesselmesh.js';

/** Opens the app; returns the list of requests made to any other origin. */
export async function openApp(page, url = '/') {
  const foreign = [];
  page.on('request', (request) => {
    const url = new URL(request.url());
    if (!['http:', 'https:', 'ws:', 'wss:'].includes(url.protocol)) return; // data:, blob:
    if (url.host !== HOST) foreign.push(request.url());
  });
  await page.goto(url);
  await expect(page.locator('body')).toHaveAttribute('data-ready', 'true');
  return foreign;
}

/** Opens the app recording page errors and console errors; returns the
 * list they go into. */
export async function openWatched(page) {
  const errors = [];
  page.on('pageerror', (e) => errors.push(e.message));
  page.on('console', (m) => m.type() === 'error' && errors.push(m.text()));
  await openApp(page);
  return errors;
}

/** Opens the app and loads the bundled sample; returns the page errors and
 * the requests to other origins. */
export async function loadSample(page) {
  const errors = [];
  page.on('pageerror', (e) => errors.push(e.message));
  const foreign = await openApp(page);
  await page.getByTestId('load-sample').click();
  await expect(page.getByTestId('stat-openings')).toHaveText('3');
  return { errors, foreign };
}

/** Presses Mesh and waits for a new result (the clip info is redrawn). */
export async function meshAgain(page) {
  await page.getByTestId('clip-info').evaluate((e) => (e.textContent = ''));
  await page.getByTestId('remesh').click();
  await expect(page.getByTestId('clip-info')).not.toBeEmpty({ timeout: 60_000 });
  await expect(page.getByTestId('error')).toBeHidden();
}

/** Starts meshing the loaded sample at a size that takes a few seconds and
 * cancels it: the page says so. */
export async function meshAndCancel(page) {
  await page.getByTestId('size-value').fill('40'); // a few seconds of work
  await page.getByTestId('remesh').click();
  await expect(page.getByTestId('progress')).toBeVisible();
  await page.getByRole('button', { name: 'Cancel' }).click();
  await expect(page.getByTestId('error')).toHaveText('Cancelled.');
}

/** ASCII STL of a closed tetrahedron (4 triangles, 4 vertices, genus 0),
 * one facet inside out. */
export const TETRA_ASCII = `solid tet
${[
  [[0, 0, 0], [0, 1, 0], [1, 0, 0]],
  [[0, 0, 0], [1, 0, 0], [0, 0, 1]],
  [[0, 0, 0], [0, 0, 1], [0, 1, 0]],
  [[1, 0, 0], [0, 0, 1], [0, 1, 0]], // inside out: repaired
]
  .map((f) => `facet normal 0 0 0\nouter loop\n${f.map((v) => `vertex ${v.join(' ')}`).join('\n')}\nendloop\nendfacet`)
  .join('\n')}
endsolid tet
`;

/** Binary STL of an open box without its top: 5 squares = 10 triangles. */
export function openBoxBinary() {
  const q = (a, b, c, d) => [[a, b, c], [a, c, d]];
  const P = [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]];
  const faces = [
    ...q(0, 3, 2, 1), // bottom
    ...q(0, 1, 5, 4),
    ...q(1, 2, 6, 5),
    ...q(2, 3, 7, 6),
    ...q(3, 0, 4, 7),
  ];
  const buf = Buffer.alloc(84 + 50 * faces.length);
  buf.write('open box', 0);
  buf.writeUInt32LE(faces.length, 80);
  faces.forEach((f, t) => {
    f.forEach((v, c) => P[v].forEach((x, k) => buf.writeFloatLE(x, 84 + 50 * t + 12 + 12 * c + 4 * k)));
  });
  return buf;
}

export async function upload(page, name, buffer) {
  await page.getByTestId('file-input').setInputFiles({ name, mimeType: 'model/stl', buffer });
}

/** The capped tube VTP (wasm/test/capped-tube-vtp.js) as file bytes. */
export const cappedTubeVtp = (n, m) => Buffer.from(cappedTubeText(n, m));

/** Clicks Export and waits for the download: its suggested name and bytes. */
export async function exportDownload(page) {
  const [download] = await Promise.all([page.waitForEvent('download'), page.getByTestId('export').click()]);
  const chunks = [];
  for await (const chunk of await download.createReadStream()) chunks.push(chunk);
  return { name: download.suggestedFilename(), bytes: Buffer.concat(chunks) };
}

/** The same with the file as text. */
export async function exportText(page) {
  const { name, bytes } = await exportDownload(page);
  return { name, text: bytes.toString() };
}

let api = null;
/** The JS API on the built WebAssembly module, in Node (the specs' own
 * inputs and reference results), loaded once. */
export async function nodeApi() {
  api ??= await createVesselmesh({ wasmBinary: readFileSync(new URL('../wasm/dist/vesselmesh_core.wasm', import.meta.url)) });
  return api;
}

/** A bifurcation phantom's STL (parent radius 1 along -z, branches up +z),
 * voxel 0.15, with `options` of makePhantom. */
export const bifurcationStl = (vm, options = {}) => Buffer.from(vm.makePhantom({ kind: 'bifurcation', voxel: 0.15, ...options }).stl);

/**
 * A closed model's blind vessel ends are cut open on load (the page's
 * default, as the core's clip auto), said with Undo; Undo there takes the
 * `n` cuts back, leaving them proposed (not made) on the closed surface.
 */
export async function undoOpenedEnds(page, n = 3) {
  await expect(page.getByTestId('change-notice')).toContainText(`The ${n} blind vessel ends were cut open`);
  await expect(page.getByTestId('cut-row')).toHaveCount(n);
  await expect(page.getByTestId('stat-openings')).toHaveText(String(n));
  await page.getByTestId('change-undo').click();
  await expect(page.getByTestId('stat-closed')).toHaveText('yes');
  await expect(page.getByTestId('stat-openings')).toHaveText('0');
  for (const row of await page.getByTestId('cut-row').all()) await expect(row).toHaveAttribute('data-state', 'new');
}

/** A closed bifurcation phantom's STL (rounded vessel ends, as segmentation
 * tools export it: its cuts are proposed), made by the JS API here. */
export async function closedBifurcation() {
  return bifurcationStl(await nodeApi(), { openEnds: false });
}

/** A PNG's first bytes: a file that is not a surface. */
export const PNG_BYTES = Buffer.concat([Buffer.from([0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a]), Buffer.alloc(200)]);

/** Sets the mesh options most specs mesh with: a uniform edge size h (a
 * string, as typed) and the number of boundary layers. */
export async function setSizeAndLayers(page, size, layers) {
  await page.getByTestId('size-mode').selectOption('size');
  await page.getByTestId('size-value').fill(size);
  await page.getByTestId('layers').fill(layers);
}

/** Expects the analysis summary to show these texts, in this order: keys are
 * the statistics' names (`triangles` for stat-triangles, ...). */
export async function expectStats(page, stats) {
  for (const [name, text] of Object.entries(stats)) await expect(page.getByTestId(`stat-${name}`)).toHaveText(text);
}

/** The workflow's steps, in order, as walkSteps() stops at them. */
export const STEP_NAMES = ['load', 'prepare', 'mesh', 'inspect', 'export', 'error'];

/**
 * Walks the page through every step of the workflow and calls `at(step)`
 * (awaited) at each, the page showing it: 'load' (the empty page),
 * 'prepare' (a closed bifurcation, its proposed cuts listed, one selected
 * to move and tilt), 'mesh' (a fine mesh in progress, cancelled after),
 * 'inspect' (a coarse mesh's volume), 'export' (downloaded), 'error' (a PNG
 * opened). The app must be open and empty.
 */
export async function walkSteps(page, at) {
  await expect(page.locator('body')).toHaveAttribute('data-step', 'load');
  await at('load');

  await upload(page, 'closed-bifurcation.stl', await closedBifurcation());
  await undoOpenedEnds(page);
  await page.getByTestId('cut-select').first().click();
  await expect(page.getByTestId('cut-edit')).toBeVisible();
  await expect(page.locator('body')).toHaveAttribute('data-step', 'prepare');
  await at('prepare');

  await page.getByTestId('apply-cuts').click();
  await expect(page.getByTestId('stat-openings')).toHaveText('3');
  // Fine enough to be still running while `at` looks at it.
  await setSizeAndLayers(page, '0.06', '4');
  await page.getByTestId('remesh').click();
  await expect(page.getByTestId('progress')).toBeVisible();
  await expect(page.getByTestId('progress-stage')).toContainText('mesh');
  await expect(page.locator('body')).toHaveAttribute('data-step', 'mesh');
  await at('mesh');
  await expect(page.getByTestId('progress'), 'the mesh still runs after the mesh step was looked at').toBeVisible();
  await page.getByRole('button', { name: 'Cancel' }).click();
  await expect(page.getByTestId('error')).toHaveText('Cancelled.');

  await page.getByTestId('size-value').fill('0.35');
  await page.getByTestId('layers').fill('1');
  await page.getByTestId('remesh').click();
  await expect(page.getByTestId('volume-result')).toBeVisible({ timeout: 60_000 });
  await expect(page.locator('body')).toHaveAttribute('data-step', 'inspect');
  await at('inspect');

  const download = await exportDownload(page);
  expect(download.name).toBe('closed-bifurcation.msh');
  await expect(page.locator('body')).toHaveAttribute('data-step', 'export');
  await at('export');

  await page.getByTestId('file-input').setInputFiles({ name: 'scan.png', mimeType: 'image/png', buffer: PNG_BYTES });
  await expect(page.getByTestId('error')).toContainText('scan.png: this seems to be a PNG image');
  await at('error');
}

/** Screenshots of the page at desktop (1440x900) and phone (390x844) width,
 * `focus` (a locator) scrolled into view: out/NAME-desktop.png,
 * out/NAME-phone.png; the desktop size is restored. */
export async function screenshots(page, name, focus = null) {
  const out = new URL('../out/', import.meta.url).pathname;
  for (const [size, width, height] of [
    ['desktop', 1440, 900],
    ['phone', 390, 844],
  ]) {
    await page.setViewportSize({ width, height });
    if (focus) await focus.scrollIntoViewIfNeeded();
    await page.screenshot({ path: `${out}${name}-${size}.png` });
  }
  await page.setViewportSize({ width: 1440, height: 900 });
}

const frame = (page) => page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));

/** With a click mode on (a cut, a refinement, a measurement), the first
 * view position whose pick info starts with `prefix` (it names a surface
 * point there), scanning from the view's middle; `after`: a position to
 * skip within 40 px of. */
export async function surfacePoint(page, prefix, after = null) {
  const box = await page.getByTestId('viewer').boundingBox();
  for (let fy = 0.3; fy < 0.9; fy += 0.03) {
    for (const fx of [0.5, 0.45, 0.55, 0.4, 0.6]) {
      const [x, y] = [box.x + fx * box.width, box.y + fy * box.height];
      if (after && Math.hypot(x - after[0], y - after[1]) < 40) continue;
      await page.mouse.move(x, y);
      await frame(page);
      if ((await page.getByTestId('pick-info').textContent()).startsWith(prefix)) return [x, y];
    }
  }
  throw new Error('no surface point found in the view');
}

/** Serious and critical axe violations of the page, as readable lines. */
export async function seriousViolations(page) {
  const { violations } = await new AxeBuilder({ page }).analyze();
  return violations
    .filter((v) => v.impact === 'serious' || v.impact === 'critical')
    .map((v) => `${v.impact} ${v.id}: ${v.help} (${v.nodes.map((n) => n.target.join(' ')).join('; ')})`);
}
