import AxeBuilder from '@axe-core/playwright';
import { expect, test } from '@playwright/test';

import { loadSample, nodeApi, screenshots, setSizeAndLayers, surfacePoint } from './helpers.js';

// The size field before meshing and measurements on the surface (issue 19):
// "Colour by" the vessel radius R or the asked edge size h, with a legend
// in the model's unit whose numbers are the core's (the same sample and
// sizeField() here, in Node); a refinement sphere's size is the legend's
// smallest; the measure tool's radius is the core's at the nearest vertex
// and its distance the points'. Keyboard: the tool starts from its button,
// measures at the view's centre, Escape stops it. Axe and the phone width.

test.use({ viewport: { width: 1440, height: 900 } });

/** The core, in Node, with the page's sample analyzed (the sample is
 * generated deterministically: the same surface as in the page). */
async function coreWithSample() {
  const api = await nodeApi();
  const { stl } = api.makePhantom({ kind: 'bifurcation', voxel: 0.08, noise: 0.3 });
  const analyzed = api.analyze(stl);
  expect(analyzed.ok).toBe(true);
  return { api, analyzed };
}

const minMax = (a) => [Math.min(...a), Math.max(...a)];
const legendRange = async (page) => {
  const legend = page.getByTestId('size-legend');
  return [Number(await legend.getAttribute('data-min')), Number(await legend.getAttribute('data-max'))];
};
const close = (x, y, rel = 1e-6) => Math.abs(x - y) <= rel * Math.max(Math.abs(x), Math.abs(y));

/** Serious and critical axe violations, as readable lines. */
async function seriousViolations(page) {
  const { violations } = await new AxeBuilder({ page }).analyze();
  return violations
    .filter((v) => v.impact === 'serious' || v.impact === 'critical')
    .map((v) => `${v.impact} ${v.id}: ${v.help} (${v.nodes.map((n) => n.target.join(' ')).join('; ')})`);
}

async function noSideScroll(page, when) {
  await page.setViewportSize({ width: 390, height: 844 });
  const width = await page.evaluate(() => document.scrollingElement.scrollWidth);
  expect(width, `${when}: page scroll width at 390 px`).toBeLessThanOrEqual(390);
  await page.setViewportSize({ width: 1440, height: 900 });
}

test('colour by the vessel radius and the asked size, legends in mm with the core numbers', async ({ page }) => {
  const { api, analyzed } = await coreWithSample();
  const { errors } = await loadSample(page);
  await expect(page.getByTestId('size-legend')).toBeHidden();

  // R: the legend's ends are the core's smallest and largest radius.
  await page.getByTestId('colour-by').selectOption('radius');
  const legend = page.getByTestId('size-legend');
  await expect(legend).toBeVisible();
  await expect(legend).toHaveAttribute('data-mode', 'radius');
  await expect(legend).toContainText('Vessel radius R (mm)');
  await expect(page.locator('#legend')).toBeHidden(); // the γ ramp gives way
  const field = api.sizeField({});
  const [r0, r1] = minMax(field.radius);
  const [l0, l1] = await legendRange(page);
  expect(close(l0, r0) && close(l1, r1), `legend ${l0}..${l1}, core ${r0}..${r1}`).toBe(true);
  // The phantom's parent vessel has radius 1: inside the range, and the
  // smallest is a branch's (the outlets' radii).
  expect(l0).toBeLessThan(1);
  expect(l1).toBeGreaterThan(1);
  const smallestOpening = Math.min(...analyzed.analysis.openings.map((o) => o.radius));
  expect(l0).toBeGreaterThan(0.6 * smallestOpening);
  const ticks = (await legend.getAttribute('data-ticks')).split(' ').map(Number);
  expect(ticks.length).toBeGreaterThan(0);
  for (const t of ticks) expect(t > l0 && t < l1).toBe(true);
  await expect(legend.locator('[data-end=min]')).toHaveText(String(Number(l0.toPrecision(4))));
  await screenshots(page, 'sizeview-radius');

  // h with N = 20 (the default): 2 pi R / 20 graded, the core's numbers.
  await page.getByTestId('colour-by').selectOption('size');
  await expect(legend).toHaveAttribute('data-mode', 'size');
  await expect(legend).toContainText('Edge size h (mm)');
  let [h0, h1] = minMax(api.sizeField({ perCircumference: 20 }).size);
  await expect.poll(async () => (await legendRange(page))[1]).toBeCloseTo(h1, 5);
  expect((await legendRange(page))[0]).toBeCloseTo(h0, 5);

  // The colours follow the options: N = 10 doubles the sizes.
  await page.getByTestId('size-value').fill('10');
  [h0, h1] = minMax(api.sizeField({ perCircumference: 10 }).size);
  await expect.poll(async () => (await legendRange(page))[1]).toBeCloseTo(h1, 5);
  await page.getByTestId('size-value').fill('20');

  // A refinement sphere: its size H is the smallest on the legend.
  await page.getByTestId('add-refine').click();
  const [x, y] = await surfacePoint(page, 'Click to refine around');
  await page.mouse.click(x, y);
  await expect(page.getByTestId('refine-row')).toHaveCount(1);
  await page.getByTestId('refine-radius').fill('1.5');
  await page.getByTestId('refine-size').fill('0.04');
  await expect.poll(async () => (await legendRange(page))[0]).toBeCloseTo(0.04, 6);
  await expect(legend.locator('[data-end=min]')).toHaveText('0.04');
  await page.getByTestId('refine-size').fill('0.06');
  await expect.poll(async () => (await legendRange(page))[0]).toBeCloseTo(0.06, 6);
  await expect(page.getByTestId('colour-status')).toHaveText('');

  // A bad size is said, not coloured.
  await page.getByTestId('size-value').fill('2');
  await expect(page.getByTestId('colour-status')).toContainText('perCircumference');
  await page.getByTestId('size-value').fill('20');
  await expect(page.getByTestId('colour-status')).toHaveText('');

  expect(await seriousViolations(page), 'coloured by size').toEqual([]);
  await page.getByTestId('refine-options').scrollIntoViewIfNeeded();
  await screenshots(page, 'sizeview-size', page.getByTestId('colour-by'));
  await noSideScroll(page, 'coloured');

  // Meshed, the volume is shown: nothing coloured, the status says where
  // the colours are; the input surface shown again, they are back.
  await page.getByTestId('colour-by').selectOption('radius');
  await expect(legend).toHaveAttribute('data-mode', 'radius');
  await setSizeAndLayers(page, '0.35', '1');
  await page.getByTestId('refine-remove').click();
  await page.getByTestId('remesh').click();
  await expect(page.getByTestId('volume-result')).toBeVisible({ timeout: 60_000 });
  await expect(legend).toBeHidden();
  await expect(page.getByTestId('part-legend')).toBeVisible();
  await expect(page.getByTestId('colour-status')).toContainText('Drawn on the input surface');
  await page.getByTestId('show').selectOption('input');
  await expect(legend).toBeVisible();
  expect(close((await legendRange(page))[0], r0)).toBe(true);
  await expect(page.getByTestId('colour-status')).toHaveText('');

  // Back to quality: the γ legend again.
  await page.getByTestId('colour-by').selectOption('none');
  await expect(legend).toBeHidden();
  await expect(page.locator('#legend')).toBeVisible();
  expect(errors).toEqual([]);
});

test('measure: the radius at a point, the distance between two, by mouse and by keyboard', async ({ page }) => {
  const { api, analyzed } = await coreWithSample();
  const { radius } = api.sizeField({});
  const positions = analyzed.surface.positions;
  const nearestRadius = (p) => {
    let best = -1;
    let bestD = Infinity;
    for (let v = 0; v < positions.length / 3; v++) {
      const d = Math.hypot(positions[3 * v] - p[0], positions[3 * v + 1] - p[1], positions[3 * v + 2] - p[2]);
      if (d < bestD) [best, bestD] = [v, d];
    }
    return radius[best];
  };
  const { errors } = await loadSample(page);
  const info = page.getByTestId('measure-info');
  await expect(info).toBeHidden();

  await page.getByTestId('measure').click();
  await expect(page.getByTestId('measure')).toHaveAttribute('aria-pressed', 'true');
  const a = await surfacePoint(page, 'Click to measure at');
  await page.mouse.click(...a);
  await expect(info).toContainText('vessel radius R');
  await expect(info).toHaveAttribute('data-radius', /\d/);
  const [p] = JSON.parse(await info.getAttribute('data-points'));
  expect(Number(await info.getAttribute('data-radius'))).toBeCloseTo(nearestRadius(p), 6);

  const b = await surfacePoint(page, 'Click to measure at', a);
  await page.mouse.click(...b);
  await expect(info).toContainText('Distance');
  const points = JSON.parse(await info.getAttribute('data-points'));
  expect(points).toHaveLength(2);
  const d = Math.hypot(points[1][0] - points[0][0], points[1][1] - points[0][1], points[1][2] - points[0][2]);
  expect(d).toBeGreaterThan(0);
  expect(Number(await info.getAttribute('data-distance'))).toBeCloseTo(d, 9);
  await expect(info).toContainText(`Distance ${Number(d.toPrecision(4))} mm`);
  await expect(info).not.toContainText('R …'); // both radii arrived
  expect(await seriousViolations(page), 'measuring').toEqual([]);
  await screenshots(page, 'measure');
  await noSideScroll(page, 'measuring');

  // Escape stops and clears.
  await page.keyboard.press('Escape');
  await expect(page.getByTestId('measure')).toHaveAttribute('aria-pressed', 'false');
  await expect(info).toBeHidden();
  await expect(page.getByTestId('measure-center')).toBeHidden();

  // By keyboard: the button, then the view's centre (orbited by the arrow
  // keys until the surface is there).
  await page.getByTestId('measure').focus();
  await page.keyboard.press('Enter');
  await expect(page.getByTestId('measure')).toHaveAttribute('aria-pressed', 'true');
  const canvas = page.getByTestId('view-canvas');
  for (let i = 0; i < 24; i++) {
    await page.getByTestId('measure-center').focus();
    await page.keyboard.press('Enter');
    if (await info.isVisible()) break;
    await canvas.focus();
    await page.keyboard.press('ArrowLeft');
  }
  await expect(info).toContainText('vessel radius R');
  const [c] = JSON.parse(await info.getAttribute('data-points'));
  await expect.poll(async () => Number(await info.getAttribute('data-radius'))).toBeCloseTo(nearestRadius(c), 6);
  await page.keyboard.press('Escape');
  await expect(info).toBeHidden();

  // Inspect: meshed, the volume is shown; measuring shows the remeshed
  // surface to click on, and R is still the input's nearest vertex's.
  await setSizeAndLayers(page, '0.35', '1');
  await page.getByTestId('remesh').click();
  await expect(page.getByTestId('volume-result')).toBeVisible({ timeout: 60_000 });
  await expect(page.getByTestId('show')).toHaveValue('volume');
  await page.getByTestId('measure').click();
  await expect(page.getByTestId('show')).toHaveValue('output');
  await page.mouse.click(...(await surfacePoint(page, 'Click to measure at')));
  await expect(info).toHaveAttribute('data-radius', /\d/);
  const [o] = JSON.parse(await info.getAttribute('data-points'));
  expect(Number(await info.getAttribute('data-radius'))).toBeCloseTo(nearestRadius(o), 6);
  await page.keyboard.press('Escape');
  expect(errors).toEqual([]);
});
