import { expect, test } from '@playwright/test';

import { openApp } from './helpers.js';

// The mesh and export options are remembered in the browser: changed,
// still there after a reload; Reset puts the defaults back, also after a
// reload.

const CHANGES = [
  ['size-mode', 'select', 'size'],
  ['size-value', 'fill', '0.5'],
  ['layers', 'fill', '2'],
  ['layer-mode', 'select', 'first'],
  ['first-layer', 'fill', '0.01'],
  ['growth', 'fill', '1.2'],
  ['wall-on', 'check', true],
  ['mesher2d', 'select', 'delaunay'],
  ['export-format', 'select', 'vtu'],
  ['output-units', 'select', 'm'],
];

async function loaded(page) {
  await openApp(page);
  await page.getByTestId('load-sample').click();
  await expect(page.getByTestId('stat-openings')).toHaveText('3');
}

async function values(page) {
  const out = {};
  for (const [id, kind] of CHANGES) {
    const field = page.getByTestId(id);
    out[id] = kind === 'check' ? await field.isChecked() : await field.inputValue();
  }
  return out;
}

test('options survive a reload; Reset brings the defaults back', async ({ page }) => {
  await loaded(page);
  const defaults = await values(page);
  await page.getByText('Advanced', { exact: true }).click(); // the 2D mesher is in there
  for (const [id, kind, value] of CHANGES) {
    const field = page.getByTestId(id);
    if (kind === 'select') await field.selectOption(value);
    else if (kind === 'check') await field.check();
    else await field.fill(value);
  }
  const changed = await values(page);
  expect(changed).toEqual(Object.fromEntries(CHANGES.map(([id, , v]) => [id, v])));

  await page.reload();
  await expect(page.locator('body')).toHaveAttribute('data-ready', 'true');
  await page.getByTestId('load-sample').click();
  await expect(page.getByTestId('stat-openings')).toHaveText('3');
  expect(await values(page)).toEqual(changed);
  // What depends on them follows: the size's label, the first-layer field,
  // the wall's fields, the Export button.
  await expect(page.locator('#size-label')).toContainText('h (');
  await expect(page.getByTestId('first-layer')).toBeVisible();
  await expect(page.getByTestId('wall-thickness')).toBeEnabled();
  await expect(page.getByTestId('export')).toHaveText('Export VTU volume');

  await page.getByTestId('reset-settings').click();
  expect(await values(page)).toEqual(defaults);
  await expect(page.locator('#size-label')).toHaveText('N');
  await expect(page.getByTestId('first-layer')).toBeHidden();
  await expect(page.getByTestId('wall-thickness')).toBeDisabled();
  await expect(page.getByTestId('export')).toHaveText('Export MSH 4.1');
  await page.reload();
  await expect(page.locator('body')).toHaveAttribute('data-ready', 'true');
  expect(await values(page)).toEqual(defaults);
});
