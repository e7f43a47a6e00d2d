import { expect, test } from '@playwright/test';

import { bifurcationStl, nodeApi, openWatched as open, screenshots, setSizeAndLayers, undoOpenedEnds, upload } from './helpers.js';

// The Prepare step: a closed surface (a bifurcation with rounded ends, as
// segmentation tools export it) gets cuts proposed at its vessel ends, made
// into openings before meshing; a cut is replaced by one clicked on the
// surface, moved and tilted; flow extensions move the caps out; smoothing
// says what it found.

test.use({ viewport: { width: 1440, height: 900 } });

let api;
test.beforeAll(async () => {
  api = await nodeApi();
});

/** A bifurcation phantom's STL (parent radius 1 along -z, branches up +z). */
const bifurcation = (options) => bifurcationStl(api, options);

/** Small and quick: a uniform size of 0.35 and one boundary layer. */
async function coarse(page) {
  await setSizeAndLayers(page, '0.35', '1');
}

/** The numbers of a '(x, y, z)' in a text. */
const coordinates = (text) => text.match(/\(([^)]*)\)/)[1].split(',').map(Number);

const frame = (page) => page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));

/**
 * With "Add a cut" on, moves the pointer over the view until the pick info
 * names a surface point that `accept`s; returns the pointer's position.
 */
async function pointAt(page, accept) {
  const box = await page.getByTestId('viewer').boundingBox();
  for (let fy = 0.5; fy < 0.97; fy += 0.015) {
    for (const fx of [0.5, 0.46, 0.54, 0.42, 0.58, 0.38, 0.62]) {
      const [x, y] = [box.x + fx * box.width, box.y + fy * box.height];
      await page.mouse.move(x, y);
      await frame(page);
      const text = await page.getByTestId('pick-info').textContent();
      if (text.startsWith('Click to cut at') && accept(coordinates(text))) return [x, y];
    }
  }
  throw new Error('no surface point found');
}

test('a closed bifurcation: proposed cuts made into openings, one replaced by a clicked cut, meshed', async ({
  page,
}) => {
  const errors = await open(page);
  await upload(page, 'closed-bifurcation.stl', bifurcation({ openEnds: false }));
  // The three blind vessel ends are cut open by default, listed as made
  // cuts; Undo (in the notice) takes them back to proposals.
  const cuts = page.getByTestId('cut-row');
  await expect(page.getByTestId('stat-closed')).toHaveText('no');
  await expect(page.getByTestId('opening-source')).toHaveText(['cut', 'cut', 'cut']);
  for (const row of await cuts.all()) await expect(row).toHaveAttribute('data-state', 'made');
  await screenshots(page, 'prepare-opened', page.getByTestId('prepare'));
  await undoOpenedEnds(page);

  // The three vessel ends are proposed, not yet made.
  await expect(cuts).toHaveCount(3);
  for (const row of await cuts.all()) {
    await expect(row).toHaveAttribute('data-state', 'new');
    await expect(row).toHaveAttribute('data-source', 'proposal');
  }
  await expect(page.getByTestId('cuts-hint')).toContainText('closed');
  await expect(page.getByTestId('cuts-hint')).toContainText('3 cuts proposed');
  await screenshots(page, 'prepare-proposals', page.getByTestId('prepare'));

  // Cut these open: an opening a cut, shown before meshing.
  await page.getByTestId('apply-cuts').click();
  await expect(page.getByTestId('stat-openings')).toHaveText('3');
  await expect(page.getByTestId('stat-closed')).toHaveText('no');
  await expect(page.getByTestId('opening-source')).toHaveText(['cut', 'cut', 'cut']);
  for (const row of await cuts.all()) await expect(row).toHaveAttribute('data-state', 'made');
  await expect(page.getByTestId('apply-cuts')).toBeHidden();
  const tipZ = coordinates(await page.getByTestId('opening-item').first().textContent())[2];
  expect(tipZ).toBeLessThan(-5.5); // the parent's end (the inlet, the largest)

  // The parent vessel's cut (the lowest) is removed, by its labelled button.
  const zs = [];
  for (const row of await cuts.all()) zs.push(coordinates(await row.locator('td').nth(1).textContent())[2]);
  const lowest = zs.indexOf(Math.min(...zs)) + 1;
  await page.getByRole('button', { name: `Remove cut ${lowest}` }).click();
  await expect(cuts).toHaveCount(2);
  await expect(page.getByTestId('apply-cuts')).toBeVisible();
  // The action bar says what to do about it.
  await expect(page.getByTestId('next-step')).toContainText('Cut these open');

  // A cut clicked on the parent vessel, halfway down.
  await page.getByTestId('add-cut').click();
  await expect(page.getByTestId('add-cut')).toHaveAttribute('aria-pressed', 'true');
  const [x, y] = await pointAt(page, ([, , z]) => z > -3.8 && z < -2.2);
  await page.mouse.click(x, y);
  await expect(cuts).toHaveCount(3);
  const added = cuts.nth(2);
  await expect(added).toHaveAttribute('data-source', 'added');
  await expect(added).toHaveAttribute('data-state', 'new');
  await expect(page.getByTestId('add-cut')).toHaveAttribute('aria-pressed', 'false');
  await expect(page.getByTestId('cut-edit')).toBeVisible();
  await expect(added.getByTestId('cut-select')).toHaveAttribute('aria-pressed', 'true');
  const radius = Number(await added.locator('td').nth(2).textContent());
  expect(radius).toBeGreaterThan(0.7);
  expect(radius).toBeLessThan(1.3);

  // Moved along the vessel by the keyboard (a quarter radius), and tilted.
  const centre = added.locator('td').nth(1);
  const beforeText = await centre.textContent();
  const before = coordinates(beforeText);
  await page.getByRole('slider', { name: 'Along the vessel (local radii)' }).focus();
  await page.keyboard.press('ArrowRight');
  await expect(page.locator('#cut-move-value')).toHaveText('+0.25 R');
  await expect(centre).not.toHaveText(beforeText);
  const after = coordinates(await centre.textContent());
  const moved = Math.hypot(...after.map((v, i) => v - before[i]));
  expect(moved).toBeGreaterThan(0.05);
  expect(moved).toBeLessThan(1);
  await page.getByRole('slider', { name: 'Tilt about the first axis (°)' }).fill('10');
  await expect(page.locator('#cut-tilt-a-value')).toHaveText('10°');
  await screenshots(page, 'prepare-added-cut', page.getByTestId('prepare'));

  // Meshing now would not use the listed cuts: refused, said beside them.
  await page.getByTestId('remesh').click();
  await expect(page.getByTestId('prepare-error')).toContainText('not made yet');
  await expect(page.getByTestId('apply-cuts')).toBeFocused();
  expect(await page.locator('body').getAttribute('data-mesh-jobs')).toBe('0');

  await page.getByTestId('apply-cuts').click();
  await expect(cuts.nth(2)).toHaveAttribute('data-state', 'made');
  await expect(page.getByTestId('prepare-error')).toBeHidden();
  await expect(page.getByTestId('stat-openings')).toHaveText('3');
  const inletZ = coordinates(await page.getByTestId('opening-item').first().textContent())[2];
  expect(inletZ).toBeGreaterThan(-4);
  expect(inletZ).toBeLessThan(-2);

  // Meshed with the same cuts: an inlet and two outlets.
  await coarse(page);
  await page.getByTestId('remesh').click();
  await expect(page.getByTestId('remesh-result')).toBeVisible({ timeout: 90_000 });
  await expect(page.locator('#out-caps')).toHaveText('inlet, outlet_1, outlet_2');
  await expect(page.getByTestId('group-legend').locator('li')).toHaveText(['wall', 'inlet', 'outlet_1', 'outlet_2']);
  await expect(page.getByTestId('opening-item').first()).toHaveAttribute('data-cap', 'inlet');
  await screenshots(page, 'prepare-meshed', page.getByTestId('remesh-result'));
  expect(errors).toEqual([]);
});

test('a click off the surface is said next to the cuts, one on a rounded vessel end cuts there; the page keeps working', async ({ page }) => {
  const errors = await open(page);
  await upload(page, 'closed-bifurcation.stl', bifurcation({ openEnds: false }));
  await undoOpenedEnds(page);
  await page.getByTestId('add-cut').click();
  const box = await page.getByTestId('viewer').boundingBox();
  await page.mouse.move(box.x + box.width - 10, box.y + box.height / 2);
  await expect(page.getByTestId('pick-info')).toHaveText('Not on the surface');
  await page.mouse.click(box.x + box.width - 10, box.y + box.height / 2);
  await expect(page.getByTestId('prepare-error')).toContainText('No surface there');
  await expect(page.getByTestId('cut-row')).toHaveCount(3);
  await expect(page.getByTestId('add-cut')).toHaveAttribute('aria-pressed', 'true');
  await screenshots(page, 'prepare-error', page.getByTestId('prepare'));
  // On the rounded tip of a vessel end: a cut there all the same (across
  // the end, below its dome), the error gone; removed again.
  const [x, y] = await pointAt(page, ([, , z]) => z < -6 && z > -6.5);
  await page.mouse.click(x, y);
  await expect(page.getByTestId('cut-row')).toHaveCount(4);
  await expect(page.getByTestId('cut-row').nth(3)).toHaveAttribute('data-source', 'added');
  await expect(page.getByTestId('prepare-error')).toBeHidden();
  await page.getByRole('button', { name: 'Remove cut 4' }).click();
  await expect(page.getByTestId('cut-row')).toHaveCount(3);
  await page.getByTestId('add-cut').click();
  await expect(page.getByTestId('add-cut')).toHaveAttribute('aria-pressed', 'true');
  // Escape stops adding; the cuts are still made.
  await page.keyboard.press('Escape');
  await expect(page.getByTestId('add-cut')).toHaveAttribute('aria-pressed', 'false');
  await page.getByTestId('apply-cuts').click();
  await expect(page.getByTestId('stat-openings')).toHaveText('3');
  await expect(page.getByTestId('prepare-error')).toBeHidden();
  await screenshots(page, 'prepare-error-cleared', page.getByTestId('prepare'));
  expect(errors).toEqual([]);
});

test('smoothing says what it found; flow extensions of 3 radii move every cap out', async ({ page }) => {
  const errors = await open(page);
  await upload(page, 'bifurcation-mask.stl', bifurcation({ binary: true }));
  await expect(page.getByTestId('stat-openings')).toHaveText('3');
  const note = page.getByTestId('smoothing-note');
  await expect(note).toContainText('Voxel staircase detected (voxel 0.15 cm)');
  await expect(note).toContainText('smoothed in');
  await page.getByRole('combobox', { name: 'Smoothing' }).selectOption('off');
  await expect(note).toContainText('not smoothed');
  await page.getByRole('combobox', { name: 'Smoothing' }).selectOption('passes');
  await expect(note).toContainText('smoothed in 10 passes');
  await page.getByRole('spinbutton', { name: 'Passes' }).fill('5');
  await page.getByRole('spinbutton', { name: 'Passes' }).blur();
  await expect(note).toContainText('smoothed in 5 passes');
  await page.getByRole('combobox', { name: 'Smoothing' }).selectOption('auto');
  await expect(note).toContainText('smoothed in 24 passes');
  await expect(page.getByTestId('cut-row')).toHaveCount(0);

  const rows = page.getByTestId('opening-item');
  await page.getByRole('spinbutton', { name: 'Flow extension, all openings' }).fill('3');
  for (const row of await rows.all()) await expect(row.getByTestId('opening-extension')).toHaveValue('3');
  await expect(page.getByRole('spinbutton', { name: 'Flow extension of opening 2, in local radii (0: none)' })).toHaveValue(
    '3',
  );
  await coarse(page);
  await page.getByTestId('remesh').click();
  await expect(page.getByTestId('remesh-result')).toBeVisible({ timeout: 90_000 });
  await expect(page.locator('#out-caps')).toHaveText('inlet, outlet_1, outlet_2');
  for (const row of await rows.all()) {
    const radius = Number((await row.textContent()).match(/radius ([\d.]+) cm/)[1]);
    const shift = Number(await row.getAttribute('data-cap-shift'));
    expect(shift).toBeGreaterThan(2 * radius);
    expect(shift).toBeLessThan(4 * radius);
    await expect(row.getByTestId('opening-shift')).toContainText('its cap');
  }
  await screenshots(page, 'prepare-flow-extensions', rows.first());

  // Per opening: none at opening 2, the others still 3 radii ({1: 3, 3: 3}).
  await page.getByRole('spinbutton', { name: 'Flow extension of opening 2, in local radii (0: none)' }).fill('0');
  await page.getByTestId('remesh').click();
  await expect(page.locator('body')).toHaveAttribute('data-mesh-jobs', '2');
  await expect(page.getByTestId('progress')).toBeHidden({ timeout: 90_000 });
  await expect(rows.nth(1).getByTestId('opening-shift')).toHaveText('');
  expect(Number(await rows.nth(1).getAttribute('data-cap-shift'))).toBeLessThan(0.1);
  expect(Number(await rows.nth(0).getAttribute('data-cap-shift'))).toBeGreaterThan(2);
  await expect(rows.nth(2).getByTestId('opening-shift')).toContainText('its cap');
  expect(errors).toEqual([]);
});
