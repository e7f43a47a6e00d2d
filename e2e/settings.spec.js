import { expect, test } from '@playwright/test';

import { openApp, screenshots, setSizeAndLayers } from './helpers.js';

// The mesh and export options: each new file starts from the defaults
// unless "Keep my settings for the next file" is checked; kept, they are
// remembered in the browser (still there after a reload); Reset puts the
// defaults back, also after a reload. They are in the page's address too:
// a link (Copy link) opens with them, over what the browser remembered; a
// link's invalid options are ignored and said.

test.use({ viewport: { width: 1440, height: 900 } });

const CHANGES = [
  ['size-mode', 'select', 'size'],
  ['size-value', 'fill', '0.5'],
  ['layers', 'fill', '2'],
  ['layer-mode', 'select', 'first'],
  ['first-layer', 'fill', '0.01'],
  ['growth', 'fill', '1.2'],
  ['wall-on', 'check', true],
  ['mesher2d', 'select', 'delaunay'],
  ['format', 'select', 'vtu'],
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

test('a new file starts from the defaults, said; kept when asked, also after a reload', async ({ page }) => {
  await loaded(page);
  await expect(page.getByTestId('keep-settings')).not.toBeChecked();
  await setSizeAndLayers(page, '0.5', '0');
  // The next file: back to the defaults, and the page says so.
  await page.getByTestId('load-sample').click();
  await expect(page.getByTestId('change-notice')).toContainText('back to their defaults');
  await expect(page.getByTestId('layers')).toHaveValue('4');
  await expect(page.getByTestId('size-mode')).toHaveValue('perCircumference');
  await screenshots(page, 'settings-new-file', page.getByTestId('change-notice'));
  // Not remembered for the next visit either (the page opened anew, not
  // from the address that carries them: a reload, or a link, keeps them).
  await setSizeAndLayers(page, '0.5', '0');
  await expect.poll(() => hashOf(page)).toContain('layers=0'); // in the address before the reload
  await page.reload();
  await expect(page.locator('body')).toHaveAttribute('data-ready', 'true');
  await expect(page.getByTestId('layers')).toHaveValue('0');
  await page.goto('/');
  await expect(page.locator('body')).toHaveAttribute('data-ready', 'true');
  await expect(page.getByTestId('layers')).toHaveValue('4');
  // Kept: they stay for the next file and the next visit.
  await page.getByTestId('load-sample').click();
  await expect(page.getByTestId('stat-openings')).toHaveText('3');
  await page.getByTestId('keep-settings').check();
  await setSizeAndLayers(page, '0.5', '0');
  await page.getByTestId('load-sample').click();
  await expect(page.getByTestId('change-notice')).toBeHidden();
  await expect(page.getByTestId('layers')).toHaveValue('0');
  await page.goto('/');
  await expect(page.locator('body')).toHaveAttribute('data-ready', 'true');
  await expect(page.getByTestId('keep-settings')).toBeChecked();
  await expect(page.getByTestId('layers')).toHaveValue('0');
});

test('options survive a reload; Reset brings the defaults back', async ({ page }) => {
  await loaded(page);
  await page.getByTestId('keep-settings').check();
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

/** The hash of the page's address. */
const hashOf = (page) => new URL(page.url()).hash;

test('the options are in the address; a link sets them over the remembered ones', async ({ page, context }) => {
  await loaded(page);
  await page.getByTestId('keep-settings').check();
  expect(hashOf(page)).toBe('');
  // Remembered in this browser: a 2D mesher and 3 layers.
  await page.getByText('Advanced', { exact: true }).click();
  await page.getByTestId('mesher2d').selectOption('delaunay');
  await page.getByTestId('layers').fill('3');
  await expect.poll(() => hashOf(page)).toBe('#layers=3&mesher2d=delaunay');

  // Another tab of the same browser opens a link: the link's options win,
  // the ones it does not name get their defaults; the notice says which
  // changed. An old link's key (export-format, the control's id before it
  // became its option's, format) is still read.
  const other = await context.newPage();
  await other.goto('/#size-mode=size&size-value=0.5&layers=2&wall-on=1&export-format=vtu');
  await expect(other.locator('body')).toHaveAttribute('data-ready', 'true');
  await expect(other.locator('#link-notice-text')).toHaveText(
    'The link changed these options: “Size”, “Size N or h”, “Boundary layer: Layers”, “Grow the vessel wall outward”, “2D mesher”, “Format”.',
  );
  await other.getByTestId('load-sample').click();
  await expect(other.getByTestId('stat-openings')).toHaveText('3');
  await expect(other.getByTestId('size-mode')).toHaveValue('size');
  await expect(other.getByTestId('size-value')).toHaveValue('0.5');
  await expect(other.getByTestId('layers')).toHaveValue('2');
  await expect(other.getByTestId('wall-on')).toBeChecked();
  await expect(other.getByTestId('wall-thickness')).toBeEnabled();
  await expect(other.getByTestId('export')).toHaveText('Export VTU volume');
  await expect(other.locator('#size-label')).toContainText('h (');
  await expect(other.getByTestId('mesher2d')).toHaveValue('frontal');
  // They are now this browser's: a reload without the hash keeps them.
  await other.goto('/');
  await expect(other.locator('body')).toHaveAttribute('data-ready', 'true');
  await expect(other.getByTestId('link-notice')).toBeHidden();
  // Nor does a reload of the page's own address say anything.
  await other.reload();
  await expect(other.locator('body')).toHaveAttribute('data-ready', 'true');
  await expect(other.getByTestId('link-notice')).toBeHidden();
  await expect(other.getByTestId('layers')).toHaveValue('2');
  await expect(other.getByTestId('layers')).toHaveValue('2');
  expect(hashOf(other)).toBe('#size-mode=size&size-value=0.5&layers=2&wall-on=1&format=vtu');
  await other.close();
});

test('a link with invalid options: those are ignored and said, the valid ones set', async ({ page }) => {
  await page.goto('/#layers=2.5&size-mode=huge&growth=1.3&colour=red&output-units=m');
  await expect(page.locator('body')).toHaveAttribute('data-ready', 'true');
  const notice = page.getByTestId('link-notice');
  await expect(notice).toBeVisible();
  // Said in the page's words: the controls' names and choices, not the API's.
  await expect(notice).toContainText('“Boundary layer: Layers” set to “2.5”: must be a whole number from 0 to 100');
  await expect(notice).toContainText('“Size” set to “huge”: must be one of “Edges per circumference N (h = 2πR/N)”, “Uniform edge length h”');
  await expect(notice).toContainText('“colour”: not an option of this page');
  await expect(notice).toContainText('ignored');
  await expect(notice).toContainText('The link changed these options: “Boundary layer: Growth ratio”, “Output units”.');
  await expect(notice).not.toContainText(/perCircumference|size-mode/);
  await screenshots(page, 'settings-link-notice', notice);
  await page.getByTestId('load-sample').click();
  await expect(page.getByTestId('stat-openings')).toHaveText('3');
  await expect(page.getByTestId('layers')).toHaveValue('4');
  await expect(page.getByTestId('size-mode')).toHaveValue('perCircumference');
  await expect(page.getByTestId('growth')).toHaveValue('1.3');
  await expect(page.getByTestId('output-units')).toHaveValue('m');
  // The address keeps only what was used.
  expect(hashOf(page)).toBe('#growth=1.3&output-units=m');
  await page.getByRole('button', { name: 'Dismiss' }).click();
  await expect(notice).toBeHidden();
});

test('Copy link gives a link that opens with the same options', async ({ browser }) => {
  const context = await browser.newContext({ viewport: { width: 1440, height: 900 } });
  await context.grantPermissions(['clipboard-read', 'clipboard-write']);
  const page = await context.newPage();
  await loaded(page);
  await page.getByTestId('solver').selectOption('svfsi');
  await page.getByTestId('size-value').fill('12');
  await page.getByTestId('layer-mode').selectOption('yplus');
  await page.getByTestId('first-layer-yplus').fill('2');
  const chosen = await values(page);
  await page.getByTestId('copy-link').click();
  await expect(page.getByTestId('share-link-status')).toHaveText('Copied.');
  const link = await page.getByTestId('share-link').inputValue();
  expect(link).toContain('#solver=svfsi');
  expect(link).toContain('size-value=12');
  expect(link).toContain('first-layer-yplus=2');
  expect(await page.evaluate(() => navigator.clipboard.readText())).toBe(link);
  await expect(page.getByTestId('announce')).toHaveText('Link to these options copied');
  await screenshots(page, 'settings-copy-link', page.getByTestId('share-link'));
  await context.close();

  // Someone else (another browser, nothing remembered) opens it.
  const fresh = await browser.newContext({ viewport: { width: 1440, height: 900 } });
  const them = await fresh.newPage();
  await them.goto(link);
  await expect(them.locator('body')).toHaveAttribute('data-ready', 'true');
  await them.getByTestId('load-sample').click();
  await expect(them.getByTestId('stat-openings')).toHaveText('3');
  expect(await values(them)).toEqual(chosen);
  await expect(them.getByTestId('solver')).toHaveValue('svfsi');
  await expect(them.getByTestId('first-layer-yplus')).toHaveValue('2');
  await expect(them.getByTestId('yplus-fields')).toBeVisible();
  await expect(them.getByTestId('link-notice')).toContainText('The link changed these options: “Solver”, “Size N or h”,');
  await fresh.close();
});

const frame = (page) => page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));

/** With "Add a refinement" on, clicks the first view position on the surface. */
async function clickSurface(page) {
  const box = await page.getByTestId('viewer').boundingBox();
  for (let fy = 0.3; fy < 0.9; fy += 0.03) {
    for (const fx of [0.5, 0.45, 0.55, 0.4, 0.6]) {
      const [x, y] = [box.x + fx * box.width, box.y + fy * box.height];
      await page.mouse.move(x, y);
      await frame(page);
      if ((await page.getByTestId('pick-info').textContent()).startsWith('Click to refine around')) {
        await page.mouse.click(x, y);
        return;
      }
    }
  }
  throw new Error('no surface point found in the view');
}

/** Every control of the preparation and the view, by test id or id. */
async function prepAndView(page) {
  const ids = ['units', 'smooth', 'smooth-passes', 'repair', 'hole-fraction', 'flow-all', 'clip-axis', 'clip-position', 'volume-color'];
  const checks = ['keep-caps', 'largest-component-only', 'wireframe', 'clip-flip', 'show-boundary', 'show-edges', 'tet-histogram-all'];
  const out = {};
  for (const id of ids) out[id] = await page.locator(`#${id}`).inputValue();
  for (const id of checks) out[id] = await page.locator(`#${id}`).isChecked();
  out.names = await page.getByTestId('opening-name').evaluateAll((l) => l.map((e) => e.value));
  out.extensions = await page.getByTestId('opening-extension').evaluateAll((l) => l.map((e) => e.value));
  out.inlet = await page.locator('input[name=inlet]:checked').inputValue();
  out.refinements = await page.getByTestId('refine-row').count();
  out.units = await page.getByTestId('stat-units').textContent();
  out.triangles = await page.getByTestId('stat-triangles').textContent();
  return out;
}

test('Reset everything puts back every option, the preparation and the view; Undo brings the preparation back', async ({ page }) => {
  await openApp(page);
  const canvas = page.getByRole('application', { name: /3D view/ });
  await page.getByTestId('load-sample').click();
  await expect(page.getByTestId('stat-openings')).toHaveText('3');
  await page.mouse.move(0, 0);
  await frame(page);
  const firstView = await canvas.screenshot();
  const first = await prepAndView(page);
  const defaults = await values(page);

  // The preparation: units, smoothing, repair, an opening's name, the
  // inlet, the flow extensions.
  // Each change is waited for (the history counts it) before the next.
  const history = page.locator('body');
  await page.getByTestId('units').selectOption('cm');
  await expect(history).toHaveAttribute('data-history', '2/2');
  await page.getByTestId('smooth').selectOption('passes');
  await expect(history).toHaveAttribute('data-history', '3/3');
  await page.getByTestId('smooth-passes').fill('5');
  await page.getByTestId('smooth-passes').press('Tab');
  await expect(history).toHaveAttribute('data-history', '4/4');
  await expect(page.getByTestId('smoothing-note')).toContainText('5 passes');
  await page.getByTestId('hole-fraction').fill('0.5');
  await page.getByTestId('hole-fraction').press('Tab');
  await expect(history).toHaveAttribute('data-history', '5/5');
  await expect(page.getByTestId('stat-openings')).toHaveText('3');
  await page.getByTestId('opening-name').first().fill('aorta');
  await page.getByTestId('opening-name').first().press('Tab');
  await expect(history).toHaveAttribute('data-history', '6/6');
  await page.getByRole('radio', { name: 'Opening 2 is the inlet' }).check();
  await expect(history).toHaveAttribute('data-history', '7/7');
  // A refinement, mesh options, a mesh.
  await page.getByTestId('add-refine').click();
  await clickSurface(page);
  await expect(page.getByTestId('refine-row')).toHaveCount(1);
  await setSizeAndLayers(page, '0.35', '1');
  await page.getByTestId('remesh').click();
  await expect(page.getByTestId('volume-result')).toBeVisible({ timeout: 60_000 });
  // A flow extension (for the next mesh).
  await page.getByTestId('flow-all').fill('2');
  await expect(history).toHaveAttribute('data-history', '8/8');
  // The view: clipped otherwise, coloured by quality, no edges, turned.
  await page.getByTestId('clip-axis').selectOption('x');
  await page.getByTestId('clip-position').fill('0.3');
  await page.getByTestId('volume-color').selectOption('quality');
  await page.getByTestId('show-edges').uncheck();
  await page.getByRole('checkbox', { name: 'Wireframe' }).check();
  await canvas.focus();
  await page.keyboard.press('ArrowRight');
  await page.keyboard.press('ArrowUp');
  expect(new URL(page.url()).hash).not.toBe('');
  const changed = await prepAndView(page);
  expect(changed).not.toEqual(first);

  await page.getByTestId('reset-settings').click();
  await expect(page.getByTestId('remesh-result')).toBeHidden();
  await expect(page.locator('#steps [data-step=prepare]')).toHaveAttribute('aria-current', 'step');
  await expect(page.getByTestId('announce')).toHaveText('Everything reset to the defaults');
  expect(await values(page)).toEqual(defaults);
  expect(await prepAndView(page)).toEqual(first);
  await expect(page.getByTestId('smooth-passes')).toBeHidden();
  expect(new URL(page.url()).hash).toBe('');
  // The view: the surface as first shown, fitted the same way.
  await page.mouse.move(0, 0);
  await frame(page);
  expect((await canvas.screenshot()).equals(firstView)).toBe(true);
  await screenshots(page, 'settings-reset');

  // The preparation before the reset is one Undo away.
  await page.getByTestId('undo').click();
  await expect(page.getByTestId('stat-units')).toContainText('cm');
  await expect(page.getByTestId('opening-name').first()).toHaveValue('aorta');
  await expect(page.getByRole('radio', { name: 'Opening 2 is the inlet' })).toBeChecked();
  await expect(page.getByTestId('flow-all')).toHaveValue('2');
});
