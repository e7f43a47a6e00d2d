import { expect, test } from '@playwright/test';

import { openApp, PNG_BYTES, screenshots, seriousViolations, STEP_NAMES, walkSteps } from './helpers.js';

// Accessibility: an axe scan of each step (load, prepare, mesh in
// progress, inspect, export, error; at desktop and phone width) fails on
// serious or critical violations, and each step's screenshots are written
// (out/step-N-STEP-{desktop,phone}.png); a file that is not a surface is
// named and the page keeps working. The keyboard-only run is
// keyboard.spec.js.

test.use({ viewport: { width: 1440, height: 900 } });

// What each step's screenshots show in sight (scrolled into view).
const FOCUS = {
  load: 'intro',
  prepare: 'cut-edit',
  mesh: 'progress',
  inspect: 'verdict',
  export: 'action-bar',
  error: 'error',
};

test('axe finds no serious or critical violation at any step, at desktop and phone width', async ({ page }) => {
  test.setTimeout(240_000);
  await openApp(page);
  let n = 0;
  await walkSteps(page, async (step) => {
    expect(await seriousViolations(page), step).toEqual([]);
    await page.setViewportSize({ width: 390, height: 844 });
    expect(await seriousViolations(page), `${step}, on a phone`).toEqual([]);
    await page.setViewportSize({ width: 1440, height: 900 });
    // Screenshots of each step: out/step-1-load-desktop.png ...
    await screenshots(page, `step-${++n}-${step}`, page.getByTestId(FOCUS[step]));
  });
  expect(n).toBe(STEP_NAMES.length);
});

test('axe: the sample with a cut being placed and smoothing by passes', async ({ page }) => {
  await openApp(page);
  await page.getByTestId('load-sample').click();
  await expect(page.getByTestId('stat-openings')).toHaveText('3');
  await page.getByTestId('smooth').selectOption('passes');
  await expect(page.getByTestId('smoothing-note')).not.toBeEmpty();
  await page.getByTestId('add-cut').click();
  await expect(page.getByTestId('add-cut')).toHaveAttribute('aria-pressed', 'true');
  expect(await seriousViolations(page), 'prepared').toEqual([]);
  await page.getByTestId('add-cut').click();
});

test('axe: a link with an invalid option (the notice), the copied link, Undo and Redo', async ({ page }) => {
  await page.goto('/#layers=abc&size-mode=size');
  await expect(page.locator('body')).toHaveAttribute('data-ready', 'true');
  await expect(page.getByTestId('link-notice')).toBeVisible();
  expect(await seriousViolations(page), 'link notice').toEqual([]);
  await page.getByTestId('load-sample').click();
  await expect(page.getByTestId('stat-openings')).toHaveText('3');
  await page.getByTestId('units').selectOption('cm');
  await expect(page.getByTestId('undo')).toBeEnabled();
  await page.getByTestId('copy-link').click();
  await expect(page.getByTestId('share-link')).toBeVisible();
  expect(await seriousViolations(page), 'copied link, undo').toEqual([]);
});

test('inlet radios are named by their opening; histogram labels are at least 11 px', async ({ page }) => {
  await openApp(page);
  await page.getByTestId('load-sample').click();
  await expect(page.getByTestId('stat-openings')).toHaveText('3');
  for (const k of [1, 2, 3]) await expect(page.getByRole('radio', { name: `Opening ${k} is the inlet` })).toHaveCount(1);
  const sizes = await page.locator('.histogram-axis').first().evaluate((el) => getComputedStyle(el).fontSize);
  expect(parseFloat(sizes)).toBeGreaterThanOrEqual(11);
});

test('a PNG is named as an image, with the formats read; the page keeps working', async ({ page }) => {
  await openApp(page);
  await page.getByTestId('file-input').setInputFiles({ name: 'scan.png', mimeType: 'image/png', buffer: PNG_BYTES });
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
