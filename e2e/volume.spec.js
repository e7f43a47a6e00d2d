import { expect, test } from '@playwright/test';

import { exportText, loadSample, meshAndCancel, openApp, screenshots } from './helpers.js';

const num = async (page, id) => Number((await page.getByTestId(id).textContent()).replace(/,/g, ''));
const drawn = async (page) => Number(await page.getByTestId('volume-view').getAttribute('data-triangles'));

async function meshSample(page) {
  const foreign = await openApp(page);
  await page.getByTestId('load-sample').click();
  await expect(page.getByTestId('stat-openings')).toHaveText('3');
  await page.getByTestId('remesh').click();
  await expect(page.getByTestId('remesh-result')).toBeVisible({ timeout: 60_000 });
  return foreign;
}

/** gamma_k (seed section 3) of every triangle of an MSH 4.1 text. */
function mshTriangleQualities(text) {
  const lines = text.split('\n');
  const xyz = new Map();
  let i = lines.indexOf('$Nodes') + 1;
  const blocks = Number(lines[i++].split(' ')[0]);
  for (let b = 0; b < blocks; ++b) {
    const n = Number(lines[i++].split(' ')[3]);
    const tags = lines.slice(i, i + n).map(Number);
    i += n;
    tags.forEach((tag, k) => xyz.set(tag, lines[i + k].split(' ').map(Number)));
    i += n;
  }
  const out = [];
  i = lines.indexOf('$Elements') + 1;
  const eblocks = Number(lines[i++].split(' ')[0]);
  for (let b = 0; b < eblocks; ++b) {
    const [, , type, n] = lines[i++].split(' ').map(Number);
    if (type === 2) {
      for (const line of lines.slice(i, i + n)) {
        const [a, c, d] = line.split(' ').slice(1, 4).map((t) => xyz.get(Number(t)));
        const len = (p, q) => Math.hypot(p[0] - q[0], p[1] - q[1], p[2] - q[2]);
        const [l0, l1, l2] = [len(c, d), len(d, a), len(a, c)];
        const u = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
        const v = [d[0] - a[0], d[1] - a[1], d[2] - a[2]];
        const area2 = Math.hypot(u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]);
        out.push((4 * area2 * area2) / ((l0 + l1 + l2) * l0 * l1 * l2));
      }
    }
    i += n;
  }
  return out;
}

test('mesh the sample with its volume: clipped view, gamma_t histogram, groups, export', async ({ page }) => {
  const errors = [];
  page.on('pageerror', (e) => errors.push(e.message));
  const foreign = await meshSample(page);
  const view = page.getByTestId('volume-view');
  await expect(view).toBeVisible();
  await expect(page.getByTestId('show')).toHaveValue('volume');
  await expect(view).toHaveAttribute('data-triangles', /^[1-9]\d*$/);
  await expect(view).toHaveAttribute('data-cut', /^[1-9]\d*$/);

  // gamma_t (of the core: the layer's tetrahedra are apart) beside gamma_k:
  // 20 bins each, min <= mean in (0, 1].
  await expect(page.getByTestId('volume-result')).toBeVisible();
  await expect(page.locator('#tet-histogram rect')).toHaveCount(20);
  await expect(page.locator('#out-histogram rect')).toHaveCount(20);
  const min = await num(page, 'out-tet-min');
  const mean = await num(page, 'out-tet-mean');
  expect(min).toBeGreaterThan(0);
  expect(mean).toBeGreaterThanOrEqual(min);
  expect(mean).toBeLessThanOrEqual(1);
  expect(await num(page, 'out-tets')).toBeGreaterThan(1000);

  // The legend names the groups; the openings are named after their caps.
  const legend = page.getByTestId('group-legend');
  await expect(legend).toBeVisible();
  await expect(legend.locator('li')).toHaveText(['wall', 'inlet', 'outlet_1', 'outlet_2']);
  await page.getByTestId('volume-color').selectOption('group');
  await expect(legend.locator('li')).toHaveText(['wall', 'inlet', 'outlet_1', 'outlet_2', 'lumen']);
  const openings = page.getByTestId('opening-item');
  await expect(openings.nth(0)).toHaveAttribute('data-cap', 'inlet');
  await expect(openings.nth(0)).toContainText('→ inlet');

  // Moving the plane changes what is drawn, and the picture.
  const canvas = page.locator('#viewer canvas');
  const before = await drawn(page);
  const shot = await canvas.screenshot();
  await page.getByTestId('clip-position').fill('0.2');
  await expect.poll(() => drawn(page)).not.toBe(before);
  expect((await canvas.screenshot()).equals(shot)).toBe(false);
  // All kept: the boundary only (wall and caps), no cut face.
  await page.getByTestId('clip-position').fill('1');
  await expect(view).toHaveAttribute('data-cut', '0');
  const boundary = await drawn(page);
  await page.getByTestId('clip-axis').selectOption('x');
  await page.getByTestId('clip-position').fill('0.5');
  await expect.poll(() => drawn(page)).not.toBe(boundary);
  await page.getByTestId('clip-flip').check();
  await page.getByTestId('show-boundary').uncheck();
  await page.getByTestId('show-edges').uncheck();
  await expect(view).toHaveAttribute('data-cut', /^[1-9]\d*$/);

  // The other views still work, and the volume comes back.
  await page.getByTestId('show').selectOption('input');
  await expect(view).toBeHidden();
  await expect(legend).toBeHidden();
  await page.getByTestId('show').selectOption('output');
  await page.getByTestId('show').selectOption('volume');
  await expect(view).toBeVisible();

  // Export: the volume MSH of what is shown (every group, every element).
  const { name, text } = await exportText(page);
  expect(name).toBe('sample-bifurcation.msh');
  for (const group of ['2 1 "wall"', '"inlet"', '"outlet_1"', '"outlet_2"']) expect(text).toContain(group);
  expect(text).toMatch(/^3 \d+ "lumen"$/m);
  const lines = text.split('\n');
  const elements = Number(lines[lines.indexOf('$Elements') + 1].split(' ')[1]);
  expect(elements).toBe(Number(await page.getByTestId('remesh-result').getAttribute('data-elements')));

  // The surfaces' quality shown is the file's: a row a group, the layer's
  // ring at each cap apart, and the smallest shown is the file's smallest.
  const rows = page.getByTestId('surface-quality').locator('tbody tr');
  await expect(rows.locator('[data-stat=name]')).toHaveText(['wall', 'inlet', 'outlet_1', 'outlet_2']);
  const shown = [];
  for (const row of await rows.all()) {
    shown.push(Number(await row.locator('[data-stat=min]').textContent()));
    const ring = await row.locator('[data-stat=ring-min]').textContent();
    if (ring !== '–') shown.push(Number(ring.split(' ')[0]));
  }
  await expect(rows.nth(1).locator('[data-stat=ring-min]')).not.toHaveText('–');
  expect(await num(page, 'out-quality-min')).toBe(shown[0]);
  const inFile = Math.min(...mshTriangleQualities(text));
  expect(Math.abs(Math.min(...shown) - inFile)).toBeLessThanOrEqual(0.0015);
  await page.getByTestId('result-details').locator('summary').click(); // folded under the verdict
  await screenshots(page, 'surface-quality', page.getByTestId('surface-quality'));
  expect(foreign).toEqual([]);
  expect(errors).toEqual([]);
});

test('the inlet chosen in the openings list is capped as the inlet', async ({ page }) => {
  await meshSample(page);
  const openings = page.getByTestId('opening-item');
  await expect(openings.nth(0)).toHaveAttribute('data-cap', 'inlet');
  await expect(openings.nth(1)).toHaveAttribute('data-cap', /^outlet_\d$/);
  await page.getByTestId('inlet-choice').nth(1).check();
  await page.getByTestId('remesh').click();
  await expect(openings.nth(1)).toHaveAttribute('data-cap', 'inlet', { timeout: 60_000 });
  await expect(openings.nth(0)).toHaveAttribute('data-cap', /^outlet_\d$/);
  await expect(page.getByTestId('group-legend').locator('li')).toHaveText(['wall', 'inlet', 'outlet_1', 'outlet_2']);
  const { text } = await exportText(page);
  expect(text).toContain('"inlet"');
});

test('surface only: no volume view; a bad core size is refused and the page keeps working', async ({ page }) => {
  await openApp(page);
  await page.getByTestId('load-sample').click();
  await expect(page.getByTestId('stat-openings')).toHaveText('3');
  await page.getByTestId('surface-only').check();
  // No volume: the layer and wall settings do not apply.
  await expect(page.getByTestId('layers')).toBeDisabled();
  await expect(page.getByTestId('wall-on')).toBeDisabled();
  await page.getByTestId('remesh').click();
  await expect(page.getByTestId('remesh-result')).toBeVisible({ timeout: 60_000 });
  await expect(page.getByTestId('show')).toHaveValue('output');
  await expect(page.locator('#show option[value=volume]')).toHaveCount(0);
  await expect(page.getByTestId('volume-view')).toBeHidden();
  await expect(page.getByTestId('volume-result')).toBeHidden();
  await expect(page.getByTestId('group-legend')).toBeHidden();
  await expect(page.getByTestId('opening-item').nth(0)).toHaveAttribute('data-cap', '');
  const surface = await exportText(page);
  expect(surface.text).toContain('"wall"');
  expect(surface.text).not.toContain('"lumen"');

  await page.getByTestId('surface-only').uncheck();
  await expect(page.getByTestId('layers')).toBeEnabled();
  await page.getByTestId('core-size').fill('-1');
  await page.getByTestId('remesh').click();
  const error = page.getByTestId('error');
  await expect(error).toContainText('Core size must be a length ≥ 0');
  await expect(page.getByTestId('core-size')).toHaveAttribute('aria-invalid', 'true');
  await page.getByTestId('core-size').fill('0.5');
  await page.getByTestId('remesh').click();
  await expect(page.getByTestId('volume-view')).toBeVisible({ timeout: 60_000 });
  await expect(error).toBeHidden();
  await expect(page.getByTestId('core-size')).toHaveAttribute('aria-invalid', 'false');
});

test('a volume mesh can be cancelled; the next one works', async ({ page }) => {
  const { errors } = await loadSample(page);
  await meshAndCancel(page);
  await expect(page.getByTestId('remesh-result')).toBeHidden();
  await page.getByTestId('size-value').fill('16');
  await page.getByTestId('remesh').click();
  await expect(page.getByTestId('volume-view')).toHaveAttribute('data-triangles', /^[1-9]\d*$/, { timeout: 60_000 });
  await expect(page.getByTestId('error')).toBeHidden();
  expect(errors).toEqual([]);
});
