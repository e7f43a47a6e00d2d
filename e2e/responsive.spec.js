import { expect, test } from '@playwright/test';

import { openApp, upload } from './helpers.js';

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
  await upload(page, 'tube.stl', buf);
  await expect(page.getByTestId('progress')).toBeVisible();
  const before = await page.evaluate(() => window.frames_);
  // The main thread answers while the worker computes.
  await page.getByRole('checkbox', { name: 'Wireframe' }).click();
  await page.waitForTimeout(300);
  const after = await page.evaluate(() => window.frames_);
  expect(after).toBeGreaterThan(before);
  await expect(page.getByTestId('stat-triangles')).toHaveText(tris.toLocaleString('en-US'), { timeout: 60_000 });

  // Cancel a running job: the page reports it and keeps working.
  await upload(page, 'tube-again.stl', buf);
  await expect(page.getByTestId('progress')).toBeVisible();
  await page.getByRole('button', { name: 'Cancel' }).click();
  await expect(page.getByTestId('error')).toHaveText('Cancelled.');
  await page.getByTestId('load-sample').click();
  await expect(page.getByTestId('stat-openings')).toHaveText('3');
});
