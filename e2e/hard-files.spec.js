import { expect, test } from '@playwright/test';

import {
  confirmUnit,
  expectOpeningsToldApart,
  exportValidMsh,
  lookAt,
  meshLookExport,
  meshThroughRemedies,
  verdictOrError,
} from './guided.js';
import { centimetreBifurcation, damagedEndTube, domedCapsTube, shortTrunkClosed, twentyOpenings } from './hard-inputs.js';
import { openApp, setSizeAndLayers, upload } from './helpers.js';

// Hard models from load to a valid exported MSH with the page's controls
// only (issue 45), each looked at (axe, screenshots out/hard-*-{desktop,
// phone}.png) at its steps: a 20-opening tree whose openings are told apart
// by their labels; a closed model whose widest end is a short trunk; a
// model with domed caps; a model with a damaged, self-crossing end; a model
// in centimetres. The inputs are generated (hard-inputs.js).

test.use({ viewport: { width: 1440, height: 900 } });

test('20 openings: each told apart by its label, before and after meshing; exported', async ({ page }) => {
  test.setTimeout(240_000);
  await openApp(page);
  const { stl, ends } = twentyOpenings();
  expect(ends).toBe(20);
  await upload(page, 'tree-20.stl', stl);
  await expect(page.getByTestId('stat-openings')).toHaveText('20');
  await confirmUnit(page, 'mm');
  await expect(page.getByTestId('openings-check')).toBeHidden(); // the openings look right

  // Labels: one per opening, numbered and coloured as its row, apart.
  await expectOpeningsToldApart(page, 20);
  await page.setViewportSize({ width: 390, height: 844 });
  await expectOpeningsToldApart(page, 20);
  await page.setViewportSize({ width: 1440, height: 900 });
  // A click on a label selects its row; hovering a row marks its label and rim.
  await page.getByTestId('opening-label').nth(6).click();
  await expect(page.getByTestId('opening-item').nth(6)).toBeFocused();
  await expect(page.getByTestId('opening-item').nth(6)).toHaveClass(/active/);
  await expect(page.getByTestId('opening-label').nth(6)).toHaveClass(/active/);
  await page.getByTestId('opening-item').nth(2).hover();
  await expect(page.getByTestId('opening-label').nth(2)).toHaveClass(/active/);
  await lookAt(page, 'hard-tree20-prepare', page.locator('#openings'));

  await setSizeAndLayers(page, '0.3', '1');
  expect(await meshThroughRemedies(page)).toEqual([]);
  await expect(page.getByTestId('verdict-title')).toHaveText('Ready for CFD');
  // After meshing: the labels stay at the caps; the legend of 21 groups is
  // folded (it would cover the model).
  await expectOpeningsToldApart(page, 20);
  const fold = page.getByTestId('group-legend-fold');
  await expect(fold).toBeVisible();
  await expect(fold.locator('summary')).toHaveText('Groups (21)');
  await expect(fold).not.toHaveAttribute('open', '');
  await page.setViewportSize({ width: 390, height: 844 });
  const view = await page.getByTestId('viewer').boundingBox();
  const legend = await fold.boundingBox();
  expect(legend.height * legend.width, 'the folded legend covers little of the view').toBeLessThan(0.1 * view.width * view.height);
  await page.setViewportSize({ width: 1440, height: 900 });
  await lookAt(page, 'hard-tree20-inspect', page.getByTestId('verdict'));

  await exportValidMsh(page, { name: 'tree-20.msh', outlets: 19 });
});

test('a closed model whose widest end is a short trunk: the trunk is cut open and is the inlet', async ({ page }) => {
  test.setTimeout(180_000);
  await openApp(page);
  const { stl, trunkTip } = shortTrunkClosed();
  await upload(page, 'short-trunk.stl', stl);
  await expect(page.getByTestId('stat-closed')).toHaveText('yes');
  await lookAt(page, 'hard-trunk-load', page.getByTestId('prepare'));
  // The proposed cuts; a vessel end they miss is warned about, with its cut.
  await page.getByTestId('apply-cuts').click();
  await expect(page.getByTestId('openings-title')).toBeFocused();
  const missed = page.getByTestId('warning-cut_here');
  if (await missed.isVisible()) {
    await missed.click();
    await expect(page.locator('body')).toHaveAttribute('data-remedy', 'done');
  }
  await expect(page.getByTestId('stat-openings')).toHaveText('3');
  await expect(page.getByTestId('openings-check')).toBeHidden();
  // The inlet: the largest opening, the trunk's (nearest its tip).
  const inlet = page.getByTestId('opening-item').first();
  await expect(inlet.getByTestId('inlet-choice')).toBeChecked();
  const centre = (await inlet.getByTestId('opening-source').locator('..').textContent()).match(/at \(([^)]*)\)/)[1].split(', ').map(Number);
  expect(Math.hypot(...centre.map((x, k) => x - trunkTip[k]))).toBeLessThan(1.5);
  await lookAt(page, 'hard-trunk-prepare', page.locator('#openings'));

  await meshLookExport(page, 'hard-trunk', { size: '0.25', layers: '2', file: 'short-trunk.msh', outlets: 2 });
});

test('a model with domed caps (fans around a lifted apex): opened at its ends and meshed', async ({ page }) => {
  test.setTimeout(180_000);
  await openApp(page);
  await upload(page, 'domed.stl', await domedCapsTube());
  // The caps are recognised (their rims openings), or the ends proposed as cuts.
  const openings = page.getByTestId('stat-openings');
  await expect(openings).not.toBeEmpty();
  if ((await openings.textContent()) === '0') {
    await expect(page.getByTestId('cut-row')).toHaveCount(2);
    await lookAt(page, 'hard-domed-load', page.getByTestId('prepare'));
    await page.getByTestId('apply-cuts').click();
  }
  await expect(openings).toHaveText('2');
  await lookAt(page, 'hard-domed-prepare', page.locator('#openings'));
  await meshLookExport(page, 'hard-domed', { size: '0.25', layers: '2', file: 'domed.msh', outlets: 1 });
});

test('a model with a damaged, self-crossing end: marked, trimmed from the page, meshed', async ({ page }) => {
  test.setTimeout(180_000);
  await openApp(page);
  await upload(page, 'damaged.stl', await damagedEndTube());
  await expect(page.getByTestId('stat-openings')).toHaveText('2');
  // Where the surface crosses itself: said in the page's words, marked in
  // the view (a mark zooms there), with the trim as a button.
  const warning = page.locator('[data-testid=opening-warning][data-warning=self-crossing]');
  const crossing = await warning.isVisible();
  if (crossing) {
    await expect(warning).toContainText('damaged vessel end');
    await expect(page.getByTestId('place-mark').first()).toBeVisible();
    await page.getByTestId('place-mark').first().click();
    await lookAt(page, 'hard-damaged-load', warning);
  }
  await setSizeAndLayers(page, '0.3', '1');
  // Meshing refuses the crossing (today's core) with the trim as its remedy,
  // or repairs it itself (issue 44); either way the page leads to a mesh.
  await page.getByTestId('remesh').click();
  const error = page.getByTestId('error');
  await expect(verdictOrError(page)).toBeVisible({ timeout: 120_000 });
  if (await error.isVisible()) {
    await expect(page.getByTestId('remedy-trim_end')).toHaveText('Trim the damaged end');
    await expect(page.getByTestId('remedy-trim_end')).toBeFocused();
    await lookAt(page, 'hard-damaged-refused', error);
    await page.getByTestId('remedy-trim_end').click();
    await expect(page.locator('body')).toHaveAttribute('data-remedy', 'done');
    await expect(page.getByTestId('cut-row')).toHaveCount(1);
    await expect(page.getByTestId('stat-openings')).toHaveText('2');
    await meshThroughRemedies(page);
  }
  await lookAt(page, 'hard-damaged-inspect', page.getByTestId('verdict'));
  await exportValidMsh(page, { name: 'damaged.msh', outlets: 1 });
});

test('a model in cm: one guess, asked until confirmed, never changed silently; cuts and spheres stay', async ({ page }) => {
  test.setTimeout(180_000);
  await openApp(page);
  await upload(page, 'bifurcation-cm.stl', await centimetreBifurcation());
  await expect(page.getByTestId('stat-openings')).toHaveText('3');
  const units = page.getByTestId('stat-units');
  const prompt = page.getByTestId('units-prompt');
  await expect(prompt).toBeVisible();
  const guess = await units.textContent();
  // Smoothing changes the radii the guess was made from: the guess stays.
  await page.getByTestId('smooth').selectOption('passes');
  await expect(page.getByTestId('smoothing-note')).toContainText('10 passes');
  await expect(units).toHaveText(guess);
  await expect(prompt).toBeVisible();
  // A refinement sphere and a cut where the user put them, before the unit.
  await page.getByTestId('add-refine').click();
  await page.getByTestId('refine-center').click();
  await expect(page.getByTestId('refine-row')).toHaveCount(1);
  const sphere = await page.getByTestId('refine-row').locator('td').nth(1).textContent();
  await lookAt(page, 'hard-cm-guess', prompt);
  await confirmUnit(page, 'cm');
  await expect(page.getByTestId('stat-bbox')).toContainText(' cm, diagonal');
  await expect(page.getByTestId('refine-row').locator('td').nth(1)).toHaveText(sphere);
  await expect(page.locator('#size-label')).toHaveText('N');
  // The unit stays cm through another preparation change.
  await page.getByTestId('smooth').selectOption('off');
  await expect(page.getByTestId('smoothing-note')).toBeEmpty();
  await expect(units).toHaveText('cm');
  await lookAt(page, 'hard-cm-prepare', page.getByTestId('stat-units'));
  await meshLookExport(page, 'hard-cm', { size: '0.035', layers: '1', file: 'bifurcation-cm.msh', outlets: 2 });
});
