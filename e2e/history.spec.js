import { expect, test } from '@playwright/test';

import { bifurcationStl, nodeApi, openWatched, screenshots, upload } from './helpers.js';

// Undo and redo of the Prepare step: on a closed bifurcation, the proposed
// cuts made, the units changed, an opening renamed, the inlet chosen, a flow
// extension given and a cut removed are each undone (the Undo button,
// Ctrl+Z) and redone (Ctrl+Shift+Z, Ctrl+Y, the Redo button), the surface
// analyzed again where the analyze options differ (the openings, the view's
// surface and the proposed cuts follow); a change after an undo drops
// what was undone; a cut tilted by several key presses is one change.

test.use({ viewport: { width: 1440, height: 900 } });

let api;
test.beforeAll(async () => {
  api = await nodeApi();
});

const bifurcation = () => bifurcationStl(api, { openEnds: false });

test('every preparation change is undone and redone', async ({ page }) => {
  const errors = await openWatched(page);
  const body = page.locator('body');
  const undo = page.getByTestId('undo');
  const redo = page.getByTestId('redo');
  const cuts = page.getByTestId('cut-row');
  const openings = page.getByTestId('stat-openings');
  const names = page.getByTestId('opening-name');
  const inlet = (k) => page.getByRole('radio', { name: `Opening ${k} is the inlet` });
  const extensions = page.getByTestId('opening-extension');

  await upload(page, 'closed.stl', bifurcation());
  // 0. Its blind ends cut open on load: a step of its own, undone first.
  await expect(openings).toHaveText('3');
  await expect(body).toHaveAttribute('data-history', '2/2');
  await expect(undo).toHaveAccessibleName('Undo: cuts');
  await undo.click();
  await expect(openings).toHaveText('0');
  await expect(cuts).toHaveCount(3);
  await expect(body).toHaveAttribute('data-history', '1/2');
  await expect(undo).toBeDisabled();
  await expect(redo).toBeEnabled();
  const closedTriangles = await page.getByTestId('stat-triangles').textContent();

  // 1. The proposed cuts made into openings.
  await page.getByTestId('apply-cuts').click();
  await expect(openings).toHaveText('3');
  await expect(body).toHaveAttribute('data-history', '2/2');
  await expect(undo).toBeEnabled();
  await expect(undo).toHaveAccessibleName('Undo: cuts');
  const cutTriangles = await page.getByTestId('stat-triangles').textContent();
  expect(cutTriangles).not.toBe(closedTriangles);
  const defaultName = await names.first().inputValue();

  // 2. The units.
  await page.getByTestId('units').selectOption('cm');
  await expect(page.getByTestId('stat-units')).toContainText('cm');
  await expect(body).toHaveAttribute('data-history', '3/3');
  await expect(undo).toHaveAccessibleName('Undo: units');

  // 3. An opening's name.
  await names.first().fill('aorta');
  await names.first().press('Tab');
  await expect(body).toHaveAttribute('data-history', '4/4');
  await expect(undo).toHaveAccessibleName('Undo: opening names');

  // 4. The inlet.
  await inlet(2).check();
  await expect(body).toHaveAttribute('data-history', '5/5');
  await expect(undo).toHaveAccessibleName('Undo: inlet');

  // 5. The flow extensions.
  await page.getByTestId('flow-all').fill('3');
  await expect(body).toHaveAttribute('data-history', '6/6');
  await expect(undo).toHaveAccessibleName('Undo: flow extensions');
  for (const e of await extensions.all()) await expect(e).toHaveValue('3');

  // 6. A cut removed (not made yet).
  await page.getByTestId('cut-remove').first().click();
  await expect(cuts).toHaveCount(2);
  await expect(page.getByTestId('apply-cuts')).toBeVisible();
  await expect(body).toHaveAttribute('data-history', '7/7');
  await screenshots(page, 'history-changed', page.getByTestId('prepare'));

  // Undone one by one: the button, then Ctrl+Z (outside a text field).
  await undo.click();
  await expect(cuts).toHaveCount(3);
  await expect(page.getByTestId('apply-cuts')).toBeHidden();
  await expect(body).toHaveAttribute('data-history', '6/7');
  await expect(page.getByTestId('announce')).toHaveText('Undone: cuts');
  await expect(redo).toHaveAccessibleName('Redo: cuts');

  await undo.focus();
  await page.keyboard.press('Control+z');
  await expect(body).toHaveAttribute('data-history', '5/7');
  await expect(page.getByTestId('flow-all')).toHaveValue('0');
  for (const e of await extensions.all()) await expect(e).toHaveValue('0');

  await page.keyboard.press('Control+z');
  await expect(body).toHaveAttribute('data-history', '4/7');
  await expect(inlet(1)).toBeChecked();

  await page.keyboard.press('Control+z');
  await expect(body).toHaveAttribute('data-history', '3/7');
  await expect(names.first()).toHaveValue(defaultName);

  await page.keyboard.press('Control+z');
  await expect(body).toHaveAttribute('data-history', '2/7');
  await expect(page.getByTestId('stat-units')).toContainText('(a guess from');
  await expect(page.getByTestId('units')).toHaveValue('');
  await expect(openings).toHaveText('3');

  // Back to the closed surface: analyzed again, its proposals listed, not made.
  await page.keyboard.press('Control+z');
  await expect(body).toHaveAttribute('data-history', '1/7');
  await expect(openings).toHaveText('0');
  await expect(page.getByTestId('stat-triangles')).toHaveText(closedTriangles);
  await expect(cuts).toHaveCount(3);
  for (const row of await cuts.all()) {
    await expect(row).toHaveAttribute('data-state', 'new');
    await expect(row).toHaveAttribute('data-source', 'proposal');
  }
  await expect(page.getByTestId('apply-cuts')).toBeVisible();
  await expect(undo).toBeDisabled();
  await page.keyboard.press('Control+z'); // nothing left: nothing happens
  await expect(body).toHaveAttribute('data-history', '1/7');

  // Redone: Ctrl+Shift+Z, Ctrl+Y, then the button.
  await redo.focus();
  await page.keyboard.press('Control+Shift+Z');
  await expect(body).toHaveAttribute('data-history', '2/7');
  await expect(openings).toHaveText('3');
  await expect(page.getByTestId('stat-triangles')).toHaveText(cutTriangles);
  await page.keyboard.press('Control+y');
  await expect(body).toHaveAttribute('data-history', '3/7');
  await expect(page.getByTestId('stat-units')).toContainText('cm');
  for (const n of ['4/7', '5/7', '6/7']) {
    await redo.click();
    await expect(body).toHaveAttribute('data-history', n);
  }
  await expect(names.first()).toHaveValue('aorta');
  await expect(inlet(2)).toBeChecked();
  for (const e of await extensions.all()) await expect(e).toHaveValue('3');
  await redo.click();
  await expect(body).toHaveAttribute('data-history', '7/7');
  await expect(cuts).toHaveCount(2);
  await expect(redo).toBeDisabled();

  // A change after an undo drops what was undone.
  await undo.click();
  await expect(body).toHaveAttribute('data-history', '6/7');
  await inlet(3).check();
  await expect(body).toHaveAttribute('data-history', '7/7');
  await expect(redo).toBeDisabled();
  await expect(undo).toHaveAccessibleName('Undo: inlet');

  // Ctrl+Z in a text field is the field's own undo, not the preparation's.
  await names.nth(1).focus();
  await page.keyboard.press('Control+z');
  await expect(body).toHaveAttribute('data-history', '7/7');

  // A cut tilted with the arrow keys is one change, undone whole.
  await page.getByTestId('cut-select').first().click();
  await page.getByTestId('cut-tilt-a').focus();
  for (let i = 0; i < 4; i++) await page.keyboard.press('ArrowRight');
  await expect(page.locator('#cut-tilt-a-value')).toHaveText('4°');
  await expect(body).toHaveAttribute('data-history', '8/8');
  await expect(cuts.first()).toHaveAttribute('data-state', 'new');
  await expect(undo).toHaveAccessibleName('Undo: cuts');
  await undo.click();
  await expect(body).toHaveAttribute('data-history', '7/8');
  await expect(cuts.first()).toHaveAttribute('data-state', 'made');
  await expect(page.getByTestId('apply-cuts')).toBeHidden();
  await expect(page.getByTestId('cut-edit')).toBeHidden();
  expect(errors).toEqual([]);
});
