import { expect, test } from '@playwright/test';

import { dentedTubeStl } from '../wasm/test/dented-tube.js';
import { meshThroughRemedies } from './guided.js';
import { bifurcationStl, nodeApi, openWatched as open, screenshots, setSizeAndLayers, upload } from './helpers.js';

// Repairs in the Prepare step: a dirty segmentation (small holes, a fin,
// touching holes, duplicates, a flipped patch: makePhantom's dirty) is
// repaired with the defaults, its holes listed with where they are and
// closed; with repair off or no hole size, the holes become openings and
// meshing the non-manifold surface is refused, said where the user looks.
// A surface that crosses itself is re-surfaced there by default (listed
// and marked where), and refused with Repair off, the repair its remedy.
// The largest volume change (Advanced) refuses a wall too coarse for the
// vessel and lets the user accept it.

test.use({ viewport: { width: 1440, height: 900 } });

let api;
test.beforeAll(async () => {
  api = await nodeApi();
});

const phantom = (options) => bifurcationStl(api, options);

/** The numbers of the first '(x, y, z)' in a text. */
const coordinates = (text) => text.match(/\(([^)]*)\)/)[1].split(',').map(Number);

test('a dirty surface is repaired, its holes listed and closed; repair off leaves them openings', async ({ page }) => {
  const errors = await open(page);
  const dirty = phantom({ dirty: true });
  const analysis = api.analyze(dirty);
  expect(analysis.ok).toBe(true);
  const closedHoles = analysis.analysis.holes.filter((h) => h.closed);
  expect(closedHoles.length).toBeGreaterThan(3);

  await upload(page, 'dirty.stl', dirty);
  await expect(page.getByTestId('stat-openings')).toHaveText('3');
  await expect(page.getByTestId('repair-note')).toContainText('Repaired:');
  await expect(page.getByTestId('repair-note')).toContainText(`${closedHoles.length} holes closed`);
  await expect(page.getByTestId('repair-note')).toContainText('fin removed');
  const rows = page.getByTestId('hole-row');
  await expect(rows).toHaveCount(analysis.analysis.holes.length);
  // Each row says where its hole is (the core's centroid) and that it was closed.
  for (const [i, hole] of analysis.analysis.holes.entries()) {
    const text = await rows.nth(i).textContent();
    coordinates(text).forEach((x, k) => expect(Math.abs(x - hole.centroid[k])).toBeLessThan(1e-3 * Math.max(1, Math.abs(x))));
    await expect(rows.nth(i)).toHaveAttribute('data-state', hole.closed ? 'closed' : 'open');
  }
  await expect(page.getByTestId('holes-hint')).toContainText('marked in orange');
  await rows.first().hover();
  await screenshots(page, 'repair-holes', page.getByTestId('prepare'));

  // Repair off: the holes are openings, nothing is closed, and meshing the
  // non-manifold surface is refused with a message in view. The fin's free
  // edges are a slit (2 vertices), never an opening; the two holes touching
  // at a vertex are one loop until the auto repair splits that vertex.
  const off = api.analyze(dirty, { repair: 'off' });
  expect(off.ok).toBe(true);
  expect(off.analysis.slits.length).toBe(1);
  expect(off.analysis.openings.every((o) => o.vertices.length >= 3 && o.radius > 0)).toBe(true);
  expect(off.analysis.openings.length).toBeGreaterThanOrEqual(3 + closedHoles.length - 1);
  await page.getByTestId('repair').selectOption('off');
  await expect(page.getByTestId('holes-hint')).toContainText('Repair is off');
  await expect(page.getByTestId('holes')).toBeHidden();
  await expect(page.getByTestId('stat-openings')).toHaveText(String(off.analysis.openings.length));
  await page.getByTestId('remesh').click();
  await expect(page.getByTestId('error')).toContainText(/non-manifold/i);
  await expect(page.getByTestId('error')).toBeInViewport();
  await screenshots(page, 'repair-off-refused', page.getByTestId('error'));

  // A hole size of 0 closes no hole: every loop is an opening.
  await page.getByTestId('repair').selectOption('auto');
  await expect(page.getByTestId('stat-openings')).toHaveText('3');
  await page.getByTestId('hole-fraction').fill('0');
  await page.getByTestId('hole-fraction').press('Enter');
  await expect(page.getByTestId('holes-hint')).toHaveText('No holes found.');
  // (The loops around the split non-manifold vertex count differently with repair on.)
  await expect.poll(async () => Number(await page.getByTestId('stat-openings').textContent())).toBeGreaterThan(3 + closedHoles.length - 2);

  // A size out of range is marked and said, and nothing is analyzed.
  await page.getByTestId('hole-fraction').fill('2');
  await page.getByTestId('hole-fraction').press('Enter');
  await expect(page.getByTestId('hole-fraction')).toHaveAttribute('aria-invalid', 'true');
  await expect(page.getByTestId('prepare-error')).toContainText('from 0 to 1');

  // Back to the default: repaired and meshed, with an inlet and two outlets.
  await page.getByTestId('hole-fraction').fill('0.25');
  await page.getByTestId('hole-fraction').press('Enter');
  await expect(page.getByTestId('stat-openings')).toHaveText('3');
  await expect(page.getByTestId('hole-row')).toHaveCount(analysis.analysis.holes.length);
  await setSizeAndLayers(page, '0.35', '1');
  await page.getByTestId('remesh').click();
  await expect(page.getByTestId('remesh-result')).toBeVisible({ timeout: 90_000 });
  await expect(page.locator('#out-caps')).toHaveText('inlet, outlet_1, outlet_2');
  expect(errors).toEqual([]);
});

test('the largest volume change refuses a wall too coarse for the vessel, and the user can accept it', async ({ page }) => {
  const errors = await open(page);
  await upload(page, 'bifurcation.stl', phantom());
  await expect(page.getByTestId('stat-openings')).toHaveText('3');
  await setSizeAndLayers(page, '3', '0');
  await page.getByTestId('remesh').click();
  const error = page.getByTestId('error');
  await expect(error).toContainText(/less volume/);
  await expect(error).toBeInViewport();
  const lost = Number(/([\d.]+)% less volume/.exec(await error.textContent())[1]);
  expect(lost).toBeGreaterThan(5);

  // Accepting more than was lost meshes it.
  await page.locator('details summary', { hasText: 'Advanced' }).click();
  await page.getByTestId('max-volume-change').fill('-1');
  await page.getByTestId('remesh').click();
  await expect(page.getByTestId('max-volume-change')).toHaveAttribute('aria-invalid', 'true');
  await expect(error).toContainText('percentage from 0 to 100');
  await page.getByTestId('max-volume-change').fill(String(Math.ceil(lost) + 1));
  await page.getByTestId('remesh').click();
  await expect(page.getByTestId('remesh-result')).toBeVisible({ timeout: 90_000 });
  await expect(error).toBeHidden();
  expect(errors).toEqual([]);
});

test('a surface that crosses itself: re-surfaced by default, said and marked where, meshed; with Repair off, refused with the repair as its remedy', async ({ page }) => {
  test.setTimeout(150_000);
  const errors = await open(page);
  await upload(page, 'dented-tube.stl', Buffer.from(dentedTubeStl()));
  // Re-surfaced by default: said in the repairs in the page's words, with
  // its place, lettered as its mark in the view; nothing is left crossing.
  await expect(page.getByTestId('repair-note')).toContainText('1 place re-surfaced where the surface crossed itself');
  const place = page.getByTestId('repair-place');
  await expect(place).toHaveCount(1);
  await expect(place).toHaveAttribute('data-kind', 'resurfaced');
  await expect(place).toContainText(
    /Re-surfaced where the surface crossed itself, at \(-0\.8\d+, 0\.0\d+, 4\.2\d+\) cm: 58 pairs of crossing triangles, 1,416 triangles replaced by 1,112\./,
  );
  const mark = page.getByTestId('repair-mark');
  await expect(mark).toHaveCount(1);
  await expect(mark).toHaveText('A');
  await expect(mark).toBeVisible();
  await expect(mark).toHaveAccessibleName(/^Repair A: re-surfaced where the surface crossed itself/);
  await place.hover();
  await expect(mark).toHaveClass(/active/);
  // The core's long account is not said twice; nothing is asked before meshing.
  await expect(page.getByTestId('warnings')).not.toContainText('crossed itself');
  await expect(page.getByTestId('openings-check')).toBeHidden();
  await screenshots(page, 'repair-resurfaced', page.getByTestId('repair-places'));
  await setSizeAndLayers(page, '0.3', '1');
  expect(await meshThroughRemedies(page)).toEqual([]);
  await expect(page.locator('#out-caps')).toHaveText('inlet, outlet_1');

  // Repair off: the crossing stays, said before meshing with the repair as
  // its fix; meshing refuses, saying where, with the same remedy, which
  // re-surfaces it and meshes.
  await page.getByTestId('repair').selectOption('off');
  await expect(place).toHaveCount(0);
  await expect(mark).toHaveCount(0);
  await expect(page.getByTestId('warnings')).toContainText(/the surface crosses itself at 1 place \(\d+ pairs of triangles\), at \(-?[\d.]+, -?[\d.e-]+, [\d.]+\) cm/);
  const warning = page.locator('[data-testid=opening-warning][data-warning=self-crossing]');
  await expect(warning).toContainText('Repair is off');
  await expect(warning.getByTestId('warning-repair')).toHaveText('Repair the surface');
  await page.getByTestId('remesh').click();
  const error = page.getByTestId('error');
  await expect(error).toContainText(/the input crosses itself at \(-?[\d.]+, -?[\d.e-]+, [\d.]+\) cm \(1 place; fix it in the segmentation/);
  await expect(error).not.toContainText(/clipPlanes|repair off/);
  await expect(error).toBeInViewport();
  const remedy = page.getByTestId('remedy-repair');
  await expect(remedy).toHaveText('Repair the surface');
  await expect(remedy).toBeFocused();
  await expect(page.getByTestId('place-mark').first()).toBeVisible();
  await screenshots(page, 'self-crossing-refused', error);
  await remedy.click();
  await expect(page.locator('body')).toHaveAttribute('data-remedy', 'done', { timeout: 120_000 });
  await expect(page.getByTestId('repair')).toHaveValue('auto');
  await expect(place).toHaveCount(1);
  await expect(page.getByTestId('verdict')).toBeVisible();
  await expect(error).toBeHidden();
  expect(errors).toEqual([]);
});
