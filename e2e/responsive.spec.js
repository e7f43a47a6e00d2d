import { expect, test } from '@playwright/test';

import { openApp, screenshots, setSizeAndLayers, STEP_NAMES, upload, walkSteps } from './helpers.js';

// A large surface generated in the worker, analyzed while the main thread
// keeps painting frames and answering clicks; then a job is cancelled.
test('the page stays responsive during a long analysis, and cancel works', async ({ page }) => {
  await openApp(page);
  // Build a large binary STL (a fine tube) in the test and upload it.
  const n = 600;
  const m = 600;
  const tris = 2 * n * m;
  const buf = Buffer.alloc(84 + 50 * tris);
  buf.writeUInt32LE(tris, 80);
  const p = (i, j) => [Math.cos((2 * Math.PI * i) / n), Math.sin((2 * Math.PI * i) / n), (4 * j) / m];
  let t = 0;
  const put = (a, b, c) => {
    [a, b, c].forEach((v, k) => v.forEach((x, d) => buf.writeFloatLE(x, 84 + 50 * t + 12 + 12 * k + 4 * d)));
    t++;
  };
  for (let j = 0; j < m; j++) {
    for (let i = 0; i < n; i++) {
      put(p(i, j), p(i + 1, j), p(i + 1, j + 1));
      put(p(i, j), p(i + 1, j + 1), p(i, j + 1));
    }
  }
  await page.evaluate(() => {
    window.frames_ = 0;
    const tick = () => {
      window.frames_++;
      requestAnimationFrame(tick);
    };
    requestAnimationFrame(tick);
  });
  // Every value the progress bar shows, to check it never goes back.
  await page.evaluate(() => {
    window.fractions_ = [];
    const bar = document.getElementById('progress-bar');
    new MutationObserver(() => bar.dataset.fraction && window.fractions_.push(Number(bar.dataset.fraction))).observe(bar, {
      attributes: true,
      attributeFilter: ['data-fraction'],
    });
  });
  await upload(page, 'tube.stl', buf);
  await expect(page.getByTestId('progress')).toBeVisible();
  await expect(page.getByTestId('progress-stage')).toContainText('read');
  await expect(page.getByTestId('progress-time')).toContainText('elapsed');
  await expect(page.getByRole('button', { name: 'Cancel' })).toBeVisible();
  await screenshots(page, 'responsive-progress', page.getByTestId('progress'));
  const before = await page.evaluate(() => window.frames_);
  // The main thread answers while the worker computes.
  await page.getByRole('checkbox', { name: 'Wireframe' }).click();
  await page.waitForTimeout(300);
  const after = await page.evaluate(() => window.frames_);
  expect(after).toBeGreaterThan(before);
  await expect(page.getByTestId('stat-triangles')).toHaveText(tris.toLocaleString('en-US'), { timeout: 60_000 });
  const fractions = await page.evaluate(() => window.fractions_);
  expect(fractions.length).toBeGreaterThan(1);
  for (let i = 1; i < fractions.length; i++) expect(fractions[i]).toBeGreaterThanOrEqual(fractions[i - 1]);

  // Cancel a running job: the page reports it and keeps working.
  await upload(page, 'tube-again.stl', buf);
  await expect(page.getByTestId('progress')).toBeVisible();
  await page.getByRole('button', { name: 'Cancel' }).click();
  await expect(page.getByTestId('error')).toHaveText('Cancelled.');
  await page.getByTestId('load-sample').click();
  await expect(page.getByTestId('stat-openings')).toHaveText('3');
});

// A phone (390x844): no horizontal scroll, the view above the panel and at
// least 300 px wide, the action bar's buttons in sight, every control of the
// panel reachable within the screen's width; the same once meshed.
test('on a phone the page fits its width and every action is reachable', async ({ page }) => {
  await page.setViewportSize({ width: 390, height: 844 });
  await openApp(page);
  const fits = async (when) => {
    const width = await page.evaluate(() => document.scrollingElement.scrollWidth);
    expect(width, `${when}: page scroll width`).toBeLessThanOrEqual(390);
    const body = await page.locator('#panel-body').evaluate((el) => [el.scrollWidth, el.clientWidth]);
    expect(body[0], `${when}: panel scroll width`).toBeLessThanOrEqual(body[1]);
    const view = await page.getByTestId('viewer').boundingBox();
    const panel = await page.locator('#panel-body').boundingBox();
    expect(view.width).toBeGreaterThanOrEqual(300);
    expect(view.y + view.height).toBeLessThanOrEqual(panel.y + 1); // stacked: the view on top
    for (const id of ['remesh', 'export']) {
      const box = await page.getByTestId(id).boundingBox();
      expect(box.y + box.height, `${when}: ${id} in sight`).toBeLessThanOrEqual(844);
      expect(box.x + box.width).toBeLessThanOrEqual(390);
    }
    // Every visible control of the panel can be scrolled to, within the width.
    const controls = page.locator('#panel-body :is(button, select, input:not([type=hidden]), summary)');
    for (let i = 0, n = await controls.count(); i < n; i++) {
      const control = controls.nth(i);
      if (!(await control.isVisible())) continue;
      await control.scrollIntoViewIfNeeded();
      const box = await control.boundingBox();
      expect(box.x, `${when}: control ${i}`).toBeGreaterThanOrEqual(0);
      expect(box.x + box.width, `${when}: control ${i}`).toBeLessThanOrEqual(390);
      expect(box.y + box.height, `${when}: control ${i}`).toBeLessThanOrEqual(844);
    }
  };
  await page.getByTestId('load-sample').click();
  await expect(page.getByTestId('stat-openings')).toHaveText('3');
  await fits('loaded');
  await setSizeAndLayers(page, '0.35', '1');
  await page.getByTestId('remesh').click();
  await expect(page.getByTestId('volume-result')).toBeVisible({ timeout: 60_000 });
  await fits('meshed');
  await screenshots(page, 'responsive-phone-meshed', page.getByTestId('volume-view'));
});

// Every step of the workflow on a phone (390x844): no horizontal scroll of
// the page nor of the panel, the action bar's buttons (Mesh, Export, Undo,
// Redo, Cancel while a job runs) within the screen.
test('on a phone no step scrolls sideways and the actions stay in sight', async ({ page }) => {
  test.setTimeout(240_000);
  await page.setViewportSize({ width: 390, height: 844 });
  await openApp(page);
  const seen = [];
  await walkSteps(page, async (step) => {
    seen.push(step);
    const width = await page.evaluate(() => document.scrollingElement.scrollWidth);
    expect(width, `${step}: page scroll width`).toBeLessThanOrEqual(390);
    const [scroll, client] = await page.locator('#panel-body').evaluate((el) => [el.scrollWidth, el.clientWidth]);
    expect(scroll, `${step}: panel scroll width`).toBeLessThanOrEqual(client);
    const bar = page.getByTestId('action-bar');
    const [barScroll, barClient] = await bar.evaluate((el) => [el.scrollWidth, el.clientWidth]);
    expect(barScroll, `${step}: action bar scroll width`).toBeLessThanOrEqual(barClient);
    const buttons = bar.getByRole('button');
    for (let i = 0, n = await buttons.count(); i < n; i++) {
      const button = buttons.nth(i);
      if (!(await button.isVisible())) continue;
      const box = await button.boundingBox();
      const name = await button.textContent();
      expect(box.x, `${step}: ${name}`).toBeGreaterThanOrEqual(0);
      expect(box.x + box.width, `${step}: ${name}`).toBeLessThanOrEqual(390);
      expect(box.y + box.height, `${step}: ${name}`).toBeLessThanOrEqual(844);
    }
    if (step === 'mesh') await expect(page.getByRole('button', { name: 'Cancel' })).toBeInViewport();
    if (['prepare', 'inspect', 'export'].includes(step)) {
      for (const id of ['remesh', 'export', 'undo', 'redo']) await expect(page.getByTestId(id)).toBeInViewport();
    }
  });
  expect(seen).toEqual(STEP_NAMES);
});
