import { expect, test } from '@playwright/test';

import { openApp, screenshots, surfacePoint } from './helpers.js';

// Local refinement in the Mesh step: a sphere placed by clicking on the
// surface, its radius and size edited, meshes finer there (the core's
// refine option); a bad size is marked and said; removing it meshes as
// before.

test.use({ viewport: { width: 1440, height: 900 } });

const count = async (page, id) => Number((await page.getByTestId(id).textContent()).replace(/,/g, ''));

test('a refinement sphere placed on the surface meshes finer there; removed, the mesh is as before', async ({ page }) => {
  const errors = [];
  page.on('pageerror', (e) => errors.push(e.message));
  const foreign = await openApp(page);
  await page.getByTestId('load-sample').click();
  await expect(page.getByTestId('stat-openings')).toHaveText('3');
  await expect(page.getByTestId('refine-hint')).toContainText('None');
  await page.getByTestId('layers').fill('0');
  await page.getByTestId('remesh').click();
  await expect(page.getByTestId('remesh-result')).toBeVisible({ timeout: 60_000 });
  const plain = await count(page, 'out-triangles');

  // Place one: the view shows the surface to click on.
  await page.getByTestId('add-refine').click();
  await expect(page.getByTestId('add-refine')).toHaveAttribute('aria-pressed', 'true');
  await expect(page.getByTestId('show')).toHaveValue('input');
  const [x, y] = await surfacePoint(page, 'Click to refine around');
  await page.mouse.click(x, y);
  const rows = page.getByTestId('refine-row');
  await expect(rows).toHaveCount(1);
  await expect(page.getByTestId('add-refine')).toHaveAttribute('aria-pressed', 'false');
  await page.getByTestId('refine-radius').fill('1.5');

  // A size of 0 is refused where the user looks, and nothing is meshed.
  await page.getByTestId('refine-size').fill('0');
  await page.getByTestId('remesh').click();
  await expect(page.getByTestId('error')).toContainText('Local refinement 1: the size must be a length > 0');
  await expect(page.getByTestId('refine-size')).toHaveAttribute('aria-invalid', 'true');

  await page.getByTestId('refine-size').fill('0.06');
  await page.getByTestId('remesh').click();
  await expect.poll(() => count(page, 'out-triangles'), { timeout: 60_000 }).toBeGreaterThan(1.2 * plain);
  await expect(page.getByTestId('error')).toBeHidden();
  await page.getByTestId('show').selectOption('output');
  await screenshots(page, 'refine', page.getByTestId('refine-options'));

  // Removed: the same mesh as without it.
  await page.getByTestId('refine-remove').click();
  await expect(rows).toHaveCount(0);
  await page.getByTestId('remesh').click();
  await expect.poll(() => count(page, 'out-triangles'), { timeout: 60_000 }).toBe(plain);
  expect(foreign).toEqual([]);
  expect(errors).toEqual([]);
});
