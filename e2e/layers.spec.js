import { expect, test } from '@playwright/test';

import { exportText, loadSample, meshAgain as mesh } from './helpers.js';

const num = async (page, id) => Number((await page.getByTestId(id).textContent()).replace(/,/g, ''));
const drawn = async (page) => Number(await page.getByTestId('volume-view').getAttribute('data-triangles'));

const elementCount = (text) => {
  const lines = text.split('\n');
  return Number(lines[lines.indexOf('$Elements') + 1].split(' ')[1]);
};

test('default boundary layer: part colors, the layer in the cut, core gamma_t, layer statistics, export', async ({
  page,
}) => {
  const { errors, foreign } = await loadSample(page);
  await expect(page.getByTestId('layers')).toHaveValue('4');
  await expect(page.getByTestId('wall-on')).not.toBeChecked();
  await mesh(page);

  // Colored by part by default: one legend entry per part, the boundary
  // layer's tetrahedra in the cut.
  const view = page.getByTestId('volume-view');
  await expect(page.getByTestId('volume-color')).toHaveValue('part');
  const parts = page.getByTestId('part-legend');
  await expect(parts).toBeVisible();
  await expect(parts.locator('li')).toHaveText(['core', 'boundary layer']);
  await expect(page.getByTestId('group-legend').locator('li')).toHaveText(['wall', 'inlet', 'outlet_1', 'outlet_2']);
  await expect(view).toHaveAttribute('data-cut-layer', /^[1-9]\d*$/);
  await expect(view).toHaveAttribute('data-cut-core', /^[1-9]\d*$/);
  await expect(view).toHaveAttribute('data-cut-wall', '0');
  await expect(page.getByTestId('clip-info')).toContainText('boundary layer');

  // The slider changes what is drawn; a cut along the vessel crosses the
  // layer along both walls.
  const before = await drawn(page);
  await page.getByTestId('clip-position').fill('0.3');
  await expect.poll(() => drawn(page)).not.toBe(before);
  await page.getByTestId('clip-axis').selectOption('y');
  await page.getByTestId('clip-position').fill('0.5');
  await expect.poll(async () => Number(await view.getAttribute('data-cut-layer'))).toBeGreaterThan(500);

  // The panel: tetrahedra per part, the core's gamma_t, the histogram of the
  // core unless asked for all, one row of layer statistics.
  await expect(page.getByTestId('out-parts')).toContainText('core');
  await expect(page.getByTestId('out-parts')).toContainText('boundary layer');
  await expect(page.getByTestId('tet-histogram-scope')).toHaveText('of the core (the flat layer elements excluded)');
  await expect(page.getByTestId('tet-histogram')).toHaveAttribute('data-scope', 'core');
  await expect(page.locator('#tet-histogram rect')).toHaveCount(20);
  const coreMin = await num(page, 'out-tet-min');
  const all = (await page.getByTestId('out-tet-all').textContent()).match(/all tetrahedra min ([\d.]+), mean ([\d.]+)/);
  expect(all).not.toBeNull();
  expect(coreMin).toBeGreaterThanOrEqual(Number(all[1]));
  expect(await num(page, 'out-tet-mean')).toBeGreaterThan(Number(all[2]));
  // The tables and histograms are folded under the verdict.
  await expect(page.getByTestId('tet-histogram')).toBeHidden();
  await page.getByTestId('result-details').locator('summary').click();
  await page.getByTestId('tet-histogram-all').check();
  await expect(page.getByTestId('tet-histogram')).toHaveAttribute('data-scope', 'all');
  await expect(page.getByTestId('tet-histogram-scope')).toHaveText('of all tetrahedra');
  const stats = page.getByTestId('layer-stats');
  await expect(stats).toBeVisible();
  await expect(stats.locator('tbody tr')).toHaveCount(1);
  const row = stats.locator('tr[data-part=boundary_layer]');
  await expect(row.locator('[data-stat=layers]')).toHaveText('4');
  await expect(row.locator('[data-stat=thickness-within-10pct]')).toHaveText(/^\d+\.\d%$/);
  await expect(row.locator('[data-stat=reduced-area]')).toHaveText(/^\d+\.\d%$/);

  // The other colorings: gamma_t (the ramp), group (the volume group lumen).
  await page.getByTestId('volume-color').selectOption('quality');
  await expect(parts).toBeHidden();
  await expect(page.locator('#legend')).toBeVisible();
  await page.getByTestId('volume-color').selectOption('group');
  await expect(page.getByTestId('group-legend').locator('li')).toHaveText([
    'wall',
    'inlet',
    'outlet_1',
    'outlet_2',
    'lumen',
  ]);

  const { text } = await exportText(page);
  expect(text).toMatch(/^3 \d+ "lumen"$/m);
  expect(text).not.toContain('"boundary_layer"');
  expect(text).not.toContain('"vessel_wall"');
  expect(elementCount(text)).toBe(Number(await page.getByTestId('remesh-result').getAttribute('data-elements')));
  expect(foreign).toEqual([]);
  expect(errors).toEqual([]);
});

test('the vessel wall and a separate boundary_layer group', async ({ page }) => {
  const { errors } = await loadSample(page);
  await expect(page.getByTestId('wall-thickness')).toBeDisabled();
  await page.getByTestId('wall-on').check();
  await expect(page.getByTestId('wall-thickness')).toBeEnabled();
  await expect(page.getByTestId('wall-thickness')).toHaveValue('0.1');
  await page.getByTestId('tag-layer').check();
  await mesh(page);

  const view = page.getByTestId('volume-view');
  await expect(page.getByTestId('part-legend').locator('li')).toHaveText(['core', 'boundary layer', 'vessel wall']);
  await expect(view).toHaveAttribute('data-cut-wall', /^[1-9]\d*$/);
  await expect(page.getByTestId('layer-stats').locator('tbody tr')).toHaveCount(2);
  await expect(page.locator('#layer-stats tr[data-part=vessel_wall] [data-stat=layers]')).toHaveText('4');
  await page.getByTestId('volume-color').selectOption('group');
  const legend = page.getByTestId('group-legend').locator('li');
  await expect(legend).toHaveText([
    'wall',
    'inlet',
    'outlet_1',
    'outlet_2',
    'outer_wall',
    'wall_inlet',
    'wall_outlet_1',
    'wall_outlet_2',
    'lumen',
    'boundary_layer',
    'vessel_wall',
  ]);

  const { text } = await exportText(page);
  const groups = ['lumen', 'boundary_layer', 'vessel_wall', 'outer_wall', 'wall_inlet', 'wall_outlet_1'];
  for (const group of groups) expect(text).toContain(`"${group}"`);
  expect(elementCount(text)).toBe(Number(await page.getByTestId('remesh-result').getAttribute('data-elements')));
  expect(errors).toEqual([]);
});

test('layers 0: no layer part; bad layer and wall input give readable errors and the page keeps working', async ({
  page,
}) => {
  const { errors } = await loadSample(page);
  const error = page.getByTestId('error');

  await page.getByTestId('layers').fill('1.5');
  await page.getByTestId('remesh').click();
  await expect(error).toContainText('Boundary layer: the number of layers must be a number of layers from 0 (none) to 100.');
  await expect(page.getByTestId('layers')).toHaveAttribute('aria-invalid', 'true');
  await expect(page.getByTestId('remesh-result')).toBeHidden();

  // No layer: the layer's fields are off, the volume is all core.
  await page.getByTestId('layers').fill('0');
  await expect(page.getByTestId('layer-thickness')).toBeDisabled();
  await expect(page.getByTestId('layers')).toHaveAttribute('aria-invalid', 'false');
  await mesh(page);
  const view = page.getByTestId('volume-view');
  await expect(page.getByTestId('part-legend').locator('li')).toHaveText(['core']);
  await expect(view).toHaveAttribute('data-cut-layer', '0');
  await expect(view).toHaveAttribute('data-cut-core', /^[1-9]\d*$/);
  await expect(page.getByTestId('layer-stats')).toBeHidden();
  await expect(page.getByTestId('tet-histogram-all')).toBeHidden();
  await expect(page.getByTestId('out-parts')).toHaveText('');

  // A bad wall thickness is refused; fixed, the wall grows on the bare lumen.
  await page.getByTestId('wall-on').check();
  await page.getByTestId('wall-thickness').fill('1.5');
  await page.getByTestId('remesh').click();
  await expect(error).toContainText(
    'Vessel wall: the thickness must be a fraction of the local vessel radius in (0, 1)',
  );
  await expect(page.getByTestId('wall-thickness')).toHaveAttribute('aria-invalid', 'true');
  await page.getByTestId('wall-thickness').fill('0.1');
  await mesh(page);
  await expect(page.getByTestId('part-legend').locator('li')).toHaveText(['core', 'vessel wall']);

  // First-layer height mode: a height is proposed; a bad growth is refused.
  await page.getByTestId('wall-on').uncheck();
  await page.getByTestId('layers').fill('5');
  await page.getByTestId('layer-mode').selectOption('first');
  await expect(page.getByTestId('layer-thickness')).toBeHidden();
  await expect(page.getByTestId('first-layer')).toHaveValue(/^0\.\d+$/);
  await page.getByTestId('growth').fill('5');
  await page.getByTestId('remesh').click();
  await expect(error).toContainText('Boundary layer: the growth must be a growth ratio from 1 to 3.');
  await page.getByTestId('growth').fill('1.2');
  await mesh(page);
  await expect(page.getByTestId('part-legend').locator('li')).toHaveText(['core', 'boundary layer']);
  await expect(page.locator('#layer-stats tr[data-part=boundary_layer] [data-stat=layers]')).toHaveText('5');
  expect(errors).toEqual([]);
});

test('kept prisms: shown split in the cut, written as prisms and quads', async ({ page }) => {
  const { errors } = await loadSample(page);
  await page.getByTestId('prisms').check();
  await mesh(page);
  const view = page.getByTestId('volume-view');
  await expect(page.getByTestId('part-legend').locator('li')).toHaveText(['core', 'boundary layer']);
  await expect(view).toHaveAttribute('data-cut-layer', /^[1-9]\d*$/);
  // The file: element blocks of prisms (type 6) and quads (type 3).
  const { text } = await exportText(page);
  const lines = text.split('\n');
  const first = lines.indexOf('$Elements') + 2;
  const types = new Set();
  for (let i = first; i < lines.length && lines[i] !== '$EndElements'; ) {
    const [, , type, count] = lines[i].split(' ').map(Number);
    types.add(type);
    i += count + 1;
  }
  expect([...types].sort()).toEqual([2, 3, 4, 6]);
  expect(errors).toEqual([]);
});
