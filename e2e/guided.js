// Helpers of the specs that take a hard model from load to an exported MSH
// with the page's controls only (hard-files.spec.js, verdict.spec.js): axe
// at both widths, the openings' labels as a user sees them, the way past a
// refusal (its remedy's button), the verdict, the export checked.
import { expect } from '@playwright/test';

import { exportText, screenshots, seriousViolations, setSizeAndLayers } from './helpers.js';
import { readMsh } from './msh.js';

/** No serious or critical axe violation at desktop nor at phone width. */
export async function expectAccessible(page, step) {
  expect(await seriousViolations(page), step).toEqual([]);
  await page.setViewportSize({ width: 390, height: 844 });
  expect(await seriousViolations(page), `${step}, on a phone`).toEqual([]);
  await page.setViewportSize({ width: 1440, height: 900 });
}

/** Axe at both widths, then the screenshots (out/NAME-{desktop,phone}.png)
 * with `focus` in sight. */
export async function lookAt(page, name, focus = null) {
  await expectAccessible(page, name);
  await screenshots(page, name, focus);
}

/** Confirms the unit in the units question (shown while it is a guess). */
export async function confirmUnit(page, unit) {
  const prompt = page.getByTestId('units-prompt');
  await expect(prompt).toBeVisible();
  await prompt.getByRole('button', { name: unit, exact: true }).click();
  await expect(prompt).toBeHidden();
  await expect(page.getByTestId('stat-units')).toHaveText(unit);
}

/** The openings' labels in the view: [{k, name, color, box}] (box: on the
 * page, null when hidden), in the order of the openings. */
export async function openingLabels(page) {
  return page.getByTestId('opening-label').evaluateAll((nodes) =>
    nodes.map((n) => {
      const r = n.getBoundingClientRect();
      return {
        k: Number(n.dataset.k),
        name: n.dataset.name,
        color: getComputedStyle(n).backgroundColor,
        box: n.hidden ? null : { x: r.x, y: r.y, w: r.width, h: r.height },
      };
    }),
  );
}

/** The openings' list rows: [{name, swatch}] (swatch: its colour). */
export async function openingRows(page) {
  return page.getByTestId('opening-item').evaluateAll((rows) =>
    rows.map((row) => ({
      name: row.querySelector('.opening-name').value,
      swatch: getComputedStyle(row.querySelector('.swatch')).backgroundColor,
    })),
  );
}

/** Expects every opening told apart: one label each, numbered as its row,
 * in its row's colour, all colours different, inside the view, no two
 * labels over each other. */
export async function expectOpeningsToldApart(page, count) {
  await expect(page.getByTestId('opening-label')).toHaveCount(count);
  const labels = await openingLabels(page);
  const rows = await openingRows(page);
  const view = await page.getByTestId('viewer').boundingBox();
  expect(labels.map((l) => l.k)).toEqual(rows.map((_, i) => i + 1));
  expect(labels.map((l) => l.name)).toEqual(rows.map((r) => r.name));
  expect(labels.map((l) => l.color)).toEqual(rows.map((r) => r.swatch));
  expect(new Set(labels.map((l) => l.color)).size).toBe(count);
  for (const { k, box } of labels) {
    expect(box, `label ${k} shown`).not.toBeNull();
    expect(box.x >= view.x - 1 && box.x + box.w <= view.x + view.width + 1, `label ${k} inside the view`).toBe(true);
    expect(box.y >= view.y - 1 && box.y + box.h <= view.y + view.height + 1, `label ${k} inside the view`).toBe(true);
  }
  for (let i = 0; i < labels.length; i++) {
    for (let j = i + 1; j < labels.length; j++) {
      const [a, b] = [labels[i].box, labels[j].box];
      const apart = a.x + a.w <= b.x + 0.5 || b.x + b.w <= a.x + 0.5 || a.y + a.h <= b.y + 0.5 || b.y + b.h <= a.y + 0.5;
      expect(apart, `labels ${i + 1} and ${j + 1} apart`).toBe(true);
    }
  }
}

/** The verdict or the error, whichever is shown (after a Mesh press). */
export const verdictOrError = (page) => page.locator('[data-testid=verdict]:visible, [data-testid=error]:visible').first();

/**
 * Presses Mesh and waits for the verdict (scrolled into sight, focused) or
 * a refusal; a refusal's remedy button is pressed (at most `remedies`
 * times), as a user would. The error text never names an API option.
 * Returns the remedies pressed (their button labels).
 */
export async function meshThroughRemedies(page, { remedies = 2, timeout = 120_000 } = {}) {
  const pressed = [];
  await page.getByTestId('remesh').click();
  for (;;) {
    const verdict = page.getByTestId('verdict');
    const error = page.getByTestId('error');
    await expect(verdictOrError(page)).toBeVisible({ timeout });
    if (await verdict.isVisible()) break;
    const text = await error.textContent();
    expect(text).not.toMatch(/\b(clipPlanes|clipAt|featureAngle|maxElements|perCircumference|keepCaps|smooth \d+)\b/);
    const remedy = page.getByTestId('error-actions').locator('button[data-testid^="remedy-"]');
    expect(pressed.length < remedies && (await remedy.count()) > 0, `a way forward from: ${text}`).toBe(true);
    pressed.push(await remedy.first().textContent());
    await remedy.first().click();
    await expect(page.locator('body')).toHaveAttribute('data-remedy', 'done', { timeout });
    // A cut made ends in Prepare: the user meshes again.
    if (!(await verdict.isVisible()) && !(await error.isVisible())) await page.getByTestId('remesh').click();
  }
  await expect(page.getByTestId('verdict')).toBeFocused();
  await expect(page.getByTestId('verdict')).toBeInViewport();
  return pressed;
}

/** Exports the mesh as MSH 4.1 and checks the file: no problem, the wall,
 * the lumen, the inlet and `outlets` outlets. Returns the file's reading. */
export async function exportValidMsh(page, { name, outlets }) {
  const { name: file, text } = await exportText(page);
  expect(file).toBe(name);
  const msh = readMsh(text);
  expect(msh.problems).toEqual([]);
  const names = msh.groups.map((g) => g.name);
  expect(names).toEqual(expect.arrayContaining(['wall', 'lumen', 'inlet']));
  expect(names.filter((n) => /^outlet_\d+$/.test(n))).toHaveLength(outlets);
  expect(msh.elements[4]).toBeGreaterThan(1000); // tetrahedra
  return msh;
}

/** The end of a hard model's way: meshed at edge length `size` with
 * `layers` layers (through any refusal's remedy), the verdict looked at
 * (out/NAME-inspect-*), exported as FILE and checked. */
export async function meshLookExport(page, name, { size, layers, file, outlets }) {
  await setSizeAndLayers(page, size, layers);
  await meshThroughRemedies(page);
  await lookAt(page, `${name}-inspect`, page.getByTestId('verdict'));
  return exportValidMsh(page, { name: file, outlets });
}
