import { expect, test } from '@playwright/test';

import { openApp, TETRA_ASCII, upload } from './helpers.js';

test('no request leaves the origin, and the app works offline once loaded', async ({ page, context }) => {
  const foreign = await openApp(page);
  await context.setOffline(true);
  await upload(page, 'tetra.stl', Buffer.from(TETRA_ASCII));
  await expect(page.getByTestId('stat-triangles')).toHaveText('4');
  const [download] = await Promise.all([
    page.waitForEvent('download'),
    page.getByTestId('export').click(),
  ]);
  expect(download.suggestedFilename()).toBe('tetra.msh');
  await page.getByTestId('load-sample').click();
  await expect(page.getByTestId('stat-openings')).toHaveText('3');
  expect(foreign).toEqual([]);
});
