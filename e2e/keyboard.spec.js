import { expect, test } from '@playwright/test';

import { closedBifurcation, openWatched, screenshots } from './helpers.js';

// The whole workflow by keyboard only (Tab, Enter, Space, the arrow keys,
// typing a number, Ctrl+Z): the file chooser opened from the Open button,
// the units chosen and undone, the proposed cuts made, the inlet moved,
// the 3D view orbited and zoomed, the mesh options set, a refinement
// placed at the view's centre, meshed, the clipping plane moved, a format
// chosen and the mesh exported.

test.use({ viewport: { width: 1440, height: 900 } });

/** Presses Tab until `locator` has the focus (at most `max` presses). */
async function tabTo(page, locator, max = 300) {
  for (let i = 0; i < max; i++) {
    if (await locator.evaluate((el) => el === document.activeElement)) return;
    await page.keyboard.press('Tab');
  }
  throw new Error(`not reached by Tab: ${locator}`);
}

test('keyboard only: open a file, prepare, orbit the view, mesh, inspect and export', async ({ page }) => {
  test.setTimeout(180_000);
  const errors = await openWatched(page);
  const step = (name) => expect(page.locator(`#steps [data-step=${name}]`)).toHaveAttribute('aria-current', 'step');
  await step('load');

  // Load: the Open button opens the file chooser (listened for before the
  // key press, so the browser's dialog is surely intercepted).
  const chooser = page.waitForEvent('filechooser');
  await tabTo(page, page.getByTestId('open-file'));
  await page.keyboard.press('Enter');
  await (await chooser).setFiles({ name: 'closed.stl', mimeType: 'model/stl', buffer: await closedBifurcation() });
  // Its blind ends cut open on load; Ctrl+Z takes the cuts back.
  await expect(page.getByTestId('stat-openings')).toHaveText('3');
  await step('prepare');
  await expect(page.locator('body')).toHaveAttribute('data-history', '2/2');
  await page.keyboard.press('Control+z');
  await expect(page.getByTestId('stat-closed')).toHaveText('yes');
  await expect(page.locator('body')).toHaveAttribute('data-history', '1/2');

  // Prepare: the units (arrow keys on the select), undone with Ctrl+Z.
  await tabTo(page, page.getByTestId('units'));
  await page.keyboard.press('ArrowDown'); // mm
  await expect(page.getByTestId('units')).toHaveValue('mm');
  await expect(page.locator('body')).toHaveAttribute('data-history', '2/2');
  await page.keyboard.press('Control+z');
  await expect(page.locator('body')).toHaveAttribute('data-history', '1/2');
  await expect(page.getByTestId('units')).toHaveValue('');
  // The proposed cuts made (Enter on the button).
  await tabTo(page, page.getByTestId('apply-cuts'));
  await page.keyboard.press('Enter');
  await expect(page.getByTestId('stat-openings')).toHaveText('3');
  // The inlet: the arrow keys move it within the radio group.
  await tabTo(page, page.getByRole('radio', { name: 'Opening 1 is the inlet' }));
  await page.keyboard.press('ArrowDown');
  await expect(page.getByRole('radio', { name: 'Opening 2 is the inlet' })).toBeChecked();
  await expect(page.getByRole('radio', { name: 'Opening 2 is the inlet' })).toBeFocused();

  // The view: focusable, named; the arrows turn it, + zooms, 0 fits.
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

  // Mesh: a uniform size (arrow on the select, a number typed), one layer
  // (the arrow keys on the number), its own group (Space on the checkbox).
  await tabTo(page, page.getByTestId('size-mode'));
  await page.keyboard.press('ArrowDown'); // Uniform edge length h
  await expect(page.getByTestId('size-mode')).toHaveValue('size');
  await page.keyboard.press('Tab');
  await expect(page.getByTestId('size-value')).toBeFocused();
  await page.keyboard.press('Control+A');
  await page.keyboard.type('0.35');
  await tabTo(page, page.getByTestId('layers'));
  for (let i = 0; i < 3; i++) await page.keyboard.press('ArrowDown');
  await expect(page.getByTestId('layers')).toHaveValue('1');
  await tabTo(page, page.getByTestId('tag-layer'));
  await page.keyboard.press('Space');
  await expect(page.getByTestId('tag-layer')).toBeChecked();
  // A local refinement placed at the view's centre (the view turned by
  // the arrow keys until the surface is there), its size typed.
  await tabTo(page, page.getByTestId('add-refine'));
  await page.keyboard.press('Enter');
  await expect(page.getByTestId('add-refine')).toHaveAttribute('aria-pressed', 'true');
  for (let turn = 0; (await page.getByTestId('refine-row').count()) === 0; turn++) {
    expect(turn, 'turns of the view before the surface is at its centre').toBeLessThan(24);
    if (turn > 0) {
      await tabTo(page, canvas);
      await page.keyboard.press('ArrowUp');
    }
    await tabTo(page, page.getByTestId('refine-center'));
    await page.keyboard.press('Enter');
  }
  await expect(page.getByTestId('refine-radius')).toBeFocused();
  await tabTo(page, page.getByTestId('refine-size'));
  await page.keyboard.press('Control+A');
  await page.keyboard.type('0.2');
  await tabTo(page, page.getByTestId('remesh'));
  await page.keyboard.press('Enter');
  await expect(page.getByTestId('volume-result')).toBeVisible({ timeout: 60_000 });
  await step('inspect');
  await expect(page.getByTestId('undo')).toBeEnabled();

  // Inspect: the clipping plane moved with the arrow keys.
  const info = await page.getByTestId('clip-info').textContent();
  await tabTo(page, page.getByTestId('clip-position'));
  for (let i = 0; i < 100; i++) await page.keyboard.press('ArrowLeft');
  expect(Number(await page.getByTestId('clip-position').inputValue())).toBeLessThan(0.5);
  await expect(page.getByTestId('clip-info')).not.toHaveText(info);

  // Export: MSH 2.2 chosen with the arrows, Space on the button.
  await tabTo(page, page.getByTestId('format'));
  await page.keyboard.press('ArrowDown');
  await expect(page.getByTestId('format')).toHaveValue('msh-2.2');
  await tabTo(page, page.getByTestId('export'));
  await expect(page.getByTestId('export')).toHaveText('Export MSH 2.2');
  const [download] = await Promise.all([page.waitForEvent('download'), page.keyboard.press('Space')]);
  expect(download.suggestedFilename()).toBe('closed.msh');
  await step('export');
  await expect(page.getByTestId('announce')).toContainText('Exported closed.msh');
  const chunks = [];
  for await (const chunk of await download.createReadStream()) chunks.push(chunk);
  expect(Buffer.concat(chunks).toString('latin1', 0, 16)).toMatch(/^\$MeshFormat\n2\.2/);
  await screenshots(page, 'keyboard-exported', page.getByTestId('export'));
  expect(errors).toEqual([]);
});
