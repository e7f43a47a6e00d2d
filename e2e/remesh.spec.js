import { expect, test } from '@playwright/test';

import { exportText, nodeApi, openApp, screenshots, upload } from './helpers.js';

const num = async (page, id) => Number((await page.getByTestId(id).textContent()).replace(/,/g, ''));

test('remesh the sample: quality shown beside the input, the views, export', async ({ page }) => {
  const foreign = await openApp(page);
  await page.getByTestId('load-sample').click();
  await expect(page.getByTestId('stat-openings')).toHaveText('3');
  const inputMin = await num(page, 'quality-min');
  const inputMean = await num(page, 'quality-mean');

  // Uniform size, Floater map and Delaunay refinement from the advanced options.
  await page.getByTestId('size-mode').selectOption('size');
  await page.getByTestId('size-value').fill('0.2');
  await page.locator('details summary', { hasText: 'Advanced' }).click();
  await page.getByTestId('param').selectOption('floater');
  await page.getByTestId('mesher2d').selectOption('delaunay');
  await page.getByTestId('remesh').click();
  await expect(page.getByTestId('remesh-result')).toBeVisible();
  const min = await num(page, 'out-quality-min');
  const mean = await num(page, 'out-quality-mean');
  expect(min).toBeGreaterThan(inputMin);
  expect(mean).toBeGreaterThan(inputMean);
  expect(mean).toBeGreaterThan(0.9);
  expect(await num(page, 'out-triangles')).toBeGreaterThan(500);
  await expect(page.locator('#out-histogram rect')).toHaveCount(20);
  // The input histogram is still there, and the view switches between both.
  await expect(page.locator('#histogram rect')).toHaveCount(20);
  await page.getByTestId('show').selectOption('input');
  await page.getByTestId('show').selectOption('output');

  // Export reuses the meshed result: the same elements in the file (the
  // remeshed wall, the caps and the tetrahedra).
  const { text } = await exportText(page);
  const lines = text.split('\n');
  const elements = Number(lines[lines.indexOf('$Elements') + 1].split(' ')[1]);
  expect(elements).toBe(Number(await page.getByTestId('remesh-result').getAttribute('data-elements')));
  expect(elements).toBeGreaterThan(await num(page, 'out-triangles'));
  expect(foreign).toEqual([]);
});

test('a bad size gives a readable error and the page keeps working', async ({ page }) => {
  await openApp(page);
  await page.getByTestId('load-sample').click();
  await expect(page.getByTestId('stat-openings')).toHaveText('3');
  await page.getByTestId('size-value').fill('1');
  await page.getByTestId('remesh').click();
  await expect(page.getByTestId('error')).toContainText('N (edges per circumference) needs');
  await expect(page.getByTestId('error')).not.toContainText('perCircumference');
  await page.getByTestId('size-value').fill('16');
  await page.getByTestId('remesh').click();
  await expect(page.getByTestId('remesh-result')).toBeVisible();
  await expect(page.getByTestId('error')).toBeHidden();
  expect(await num(page, 'out-quality-min')).toBeGreaterThan(0.3);
});

/** Opens the app with a phantom (`makePhantom` options) of `openings`
 * openings, set to mesh its wall alone at h = 0.3. */
async function openPhantomForWall(page, phantom, openings) {
  const api = await nodeApi();
  await openApp(page);
  await upload(page, `${phantom.kind}.stl`, Buffer.from(api.makePhantom(phantom).stl));
  await expect(page.getByTestId('stat-openings')).toHaveText(String(openings));
  await page.getByTestId('size-mode').selectOption('size');
  await page.getByTestId('size-value').fill('0.3');
  await page.getByTestId('surface-only').check();
}

test('pinning to far input vertices: on by default, off from the advanced options', async ({ page }) => {
  // A mildly noisy phantom whose bumps a 0.3 wall partly misses.
  await openPhantomForWall(page, { kind: 'bifurcation', voxel: 0.1, noise: 0.1 }, 3);
  await page.getByTestId('remesh').click();
  await expect(page.getByTestId('out-fidelity')).toBeVisible();
  const pinned = await num(page, 'out-pinned');
  const far = await num(page, 'out-far');
  expect(pinned).toBeGreaterThan(0);

  await page.locator('details summary', { hasText: 'Advanced' }).click();
  await page.getByTestId('fidelity-on').uncheck();
  await page.getByTestId('remesh').click();
  await expect(page.getByTestId('out-pinned')).toHaveText('0');
  expect(await num(page, 'out-far')).toBeGreaterThan(far);
});

test('an oversampled surface is decimated before remeshing: said in the result, off from the advanced options', async ({ page }) => {
  await openPhantomForWall(page, { kind: 'tube', voxel: 0.03 }, 2); // about 218,000 triangles
  await page.locator('details summary', { hasText: 'Advanced' }).click();
  await expect(page.getByTestId('decimate-on')).toBeChecked();
  await page.getByTestId('remesh').click();
  await expect(page.getByTestId('out-decimated')).toBeVisible();
  const kept = await num(page, 'out-decimated-triangles');
  expect(kept).toBeGreaterThan(0);
  expect(kept).toBeLessThan(218000 / 8);
  expect(await num(page, 'out-quality-min')).toBeGreaterThan(0.55);
  await screenshots(page, 'remesh-decimated', page.getByTestId('remesh-result'));

  await page.getByTestId('decimate-on').uncheck();
  await page.getByTestId('out-triangles').evaluate((e) => (e.textContent = ''));
  await page.getByTestId('remesh').click();
  await expect(page.getByTestId('out-triangles')).not.toBeEmpty({ timeout: 60_000 });
  await expect(page.getByTestId('out-decimated')).toBeHidden();
  await expect(page.getByTestId('error')).toBeHidden();
});
