import AxeBuilder from '@axe-core/playwright';
import { expect, test } from '@playwright/test';

import { openApp, screenshots, TETRA_ASCII } from './helpers.js';

// Accessibility: an axe scan of each step (loaded, prepared, meshed) fails
// on serious or critical violations; the whole workflow, from opening a
// file to the export, by keyboard only; the 3D view orbits by keyboard; a
// file that is not a surface is named and the page keeps working.

test.use({ viewport: { width: 1440, height: 900 } });

/** Serious and critical axe violations of the page, as readable lines. */
async function seriousViolations(page) {
  const { violations } = await new AxeBuilder({ page }).analyze();
  return violations
    .filter((v) => v.impact === 'serious' || v.impact === 'critical')
    .map((v) => `${v.impact} ${v.id}: ${v.help} (${v.nodes.map((n) => n.target.join(' ')).join('; ')})`);
}

/** Small and quick meshing options. */
async function coarse(page) {
  await page.getByTestId('size-mode').selectOption('size');
  await page.getByTestId('size-value').fill('0.35');
  await page.getByTestId('layers').fill('1');
}

/** Presses Tab until `locator` has the focus (at most `max` presses). */
async function tabTo(page, locator, max = 200) {
  for (let i = 0; i < max; i++) {
    if (await locator.evaluate((el) => el === document.activeElement)) return;
    await page.keyboard.press('Tab');
  }
  throw new Error(`not reached by Tab: ${locator}`);
}

test('axe finds no serious or critical violation at any step', async ({ page }) => {
  await openApp(page);
  expect(await seriousViolations(page), 'empty page').toEqual([]);

  await page.getByTestId('load-sample').click();
  await expect(page.getByTestId('stat-openings')).toHaveText('3');
  await expect(page.getByTestId('next-step')).toContainText('press Mesh');
  expect(await seriousViolations(page), 'loaded').toEqual([]);
  await screenshots(page, 'a11y-loaded');

  // Prepared: smoothed by passes, a cut being placed.
  await page.getByTestId('smooth').selectOption('passes');
  await expect(page.getByTestId('smoothing-note')).not.toBeEmpty();
  await page.getByTestId('add-cut').click();
  await expect(page.getByTestId('add-cut')).toHaveAttribute('aria-pressed', 'true');
  expect(await seriousViolations(page), 'prepared').toEqual([]);
  await page.getByTestId('add-cut').click();

  await coarse(page);
  await page.getByTestId('remesh').click();
  await expect(page.getByTestId('volume-result')).toBeVisible({ timeout: 60_000 });
  await expect(page.getByTestId('next-step')).toContainText('press Export');
  expect(await seriousViolations(page), 'meshed').toEqual([]);
  await page.setViewportSize({ width: 390, height: 844 });
  expect(await seriousViolations(page), 'meshed, on a phone').toEqual([]);
  await page.setViewportSize({ width: 1440, height: 900 });
  await screenshots(page, 'a11y-meshed', page.getByTestId('volume-result'));
});

test('inlet radios are named by their opening; histogram labels are at least 11 px', async ({ page }) => {
  await openApp(page);
  await page.getByTestId('load-sample').click();
  await expect(page.getByTestId('stat-openings')).toHaveText('3');
  for (const k of [1, 2, 3]) await expect(page.getByRole('radio', { name: `Opening ${k} is the inlet` })).toHaveCount(1);
  const sizes = await page.locator('.histogram-axis').first().evaluate((el) => getComputedStyle(el).fontSize);
  expect(parseFloat(sizes)).toBeGreaterThanOrEqual(11);
});

test('keyboard only: open a file, orbit the view, mesh and export', async ({ page }) => {
  await openApp(page);
  // The file button opens the picker (listened for before the key press,
  // so the browser's dialog is surely intercepted), and a file is opened.
  const chooser = page.waitForEvent('filechooser');
  await tabTo(page, page.getByTestId('open-file'));
  await page.keyboard.press('Enter');
  await (await chooser).setFiles({ name: 'tetra.stl', mimeType: 'model/stl', buffer: Buffer.from(TETRA_ASCII) });
  await expect(page.getByTestId('stat-triangles')).toHaveText('4');
  // Then the sample (a vessel to mesh), by keyboard.
  await tabTo(page, page.getByTestId('load-sample'));
  await page.keyboard.press('Enter');
  await expect(page.getByTestId('stat-openings')).toHaveText('3');
  await expect(page.locator('#steps [data-step=prepare]')).toHaveAttribute('aria-current', 'step');

  // The view: focusable, named; the arrows turn it, + zooms.
  const canvas = page.getByRole('application', { name: /3D view/ });
  await tabTo(page, canvas);
  const before = await canvas.screenshot();
  await page.keyboard.press('ArrowRight');
  await page.keyboard.press('ArrowRight');
  await page.keyboard.press('ArrowUp');
  const turned = await canvas.screenshot();
  expect(turned.equals(before)).toBe(false);
  await page.keyboard.press('+');
  expect((await canvas.screenshot()).equals(turned)).toBe(false);
  await page.keyboard.press('0');

  // The options by keyboard: a uniform size, one layer.
  await tabTo(page, page.getByTestId('size-mode'));
  await page.keyboard.press('ArrowDown'); // Uniform edge length h
  await expect(page.getByTestId('size-mode')).toHaveValue('size');
  await page.keyboard.press('Tab');
  await expect(page.getByTestId('size-value')).toBeFocused();
  await page.keyboard.press('Control+A');
  await page.keyboard.type('0.35');
  await tabTo(page, page.getByTestId('layers'));
  await page.keyboard.press('Control+A');
  await page.keyboard.type('1');

  await tabTo(page, page.getByTestId('remesh'));
  await page.keyboard.press('Enter');
  await expect(page.getByTestId('volume-result')).toBeVisible({ timeout: 60_000 });
  await expect(page.locator('#steps [data-step=inspect]')).toHaveAttribute('aria-current', 'step');

  await tabTo(page, page.getByTestId('export'));
  const [download] = await Promise.all([page.waitForEvent('download'), page.keyboard.press('Enter')]);
  expect(download.suggestedFilename()).toBe('sample-bifurcation.msh');
  await expect(page.locator('#steps [data-step=export]')).toHaveAttribute('aria-current', 'step');
  await expect(page.getByTestId('announce')).toContainText('Exported sample-bifurcation.msh');
});

test('a PNG is named as an image, with the formats read; the page keeps working', async ({ page }) => {
  await openApp(page);
  const png = Buffer.concat([Buffer.from([0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a]), Buffer.alloc(200)]);
  await page.getByTestId('file-input').setInputFiles({ name: 'scan.png', mimeType: 'image/png', buffer: png });
  const error = page.getByTestId('error');
  await expect(error).toContainText('scan.png: this seems to be a PNG image, not a surface');
  await expect(error).toContainText('STL, VTP, VTK, OBJ or PLY');
  await expect(page.getByTestId('next-step')).toContainText('Open another file');
  await expect(page.getByTestId('announce')).toContainText('PNG image');
  await screenshots(page, 'a11y-wrong-file', error);
  await page.getByTestId('load-sample').click();
  await expect(page.getByTestId('stat-openings')).toHaveText('3');
  await expect(error).toBeHidden();
});
