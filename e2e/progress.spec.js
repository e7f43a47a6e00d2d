import { expect, test } from '@playwright/test';

import { openWatched, screenshots, setSizeAndLayers, upload } from './helpers.js';
import { treeStl } from './tree.js';

// The progress of a mesh on a generated 10-branch vessel tree (tree.js):
// the bar never goes back, names each stage as it comes, with the elapsed
// time; everything it showed is recorded as it is drawn.

test.use({ viewport: { width: 1440, height: 900 } });

test('meshing a 10-branch tree: the progress only moves forward, stage by stage', async ({ page }) => {
  test.setTimeout(180_000);
  const errors = await openWatched(page);
  const { stl, ends } = treeStl();
  await upload(page, 'tree.stl', stl);
  await expect(page.getByTestId('stat-openings')).toHaveText(String(ends));
  await setSizeAndLayers(page, '0.2', '2');

  // Every value and stage the bar shows, and every time text.
  await page.evaluate(() => {
    window.shown_ = [];
    const bar = document.getElementById('progress-bar');
    const stage = document.getElementById('progress-stage');
    const time = document.getElementById('progress-time');
    const record = () => {
      if (!bar.dataset.fraction) return;
      window.shown_.push({ fraction: Number(bar.dataset.fraction), stage: stage.textContent, time: time.textContent });
    };
    new MutationObserver(record).observe(bar, { attributes: true, attributeFilter: ['data-fraction'] });
    new MutationObserver(record).observe(stage, { childList: true, characterData: true, subtree: true });
  });
  await page.getByTestId('remesh').click();
  await expect(page.getByTestId('progress')).toBeVisible();
  await expect(page.getByTestId('volume-result')).toBeVisible({ timeout: 150_000 });
  await expect(page.getByTestId('progress')).toBeHidden();
  expect(errors).toEqual([]);

  const shown = (await page.evaluate(() => window.shown_)).filter((s) => s.stage.startsWith('mesh'));
  expect(shown.length).toBeGreaterThan(5);
  for (let i = 1; i < shown.length; i++) {
    expect(shown[i].fraction, `report ${i} (${shown[i].stage}) after ${shown[i - 1].fraction}`).toBeGreaterThanOrEqual(shown[i - 1].fraction);
  }
  // Stages by name ('mesh: remesh', 'mesh: refine volume' ...), in sight as they come.
  const stages = [...new Set(shown.map((s) => s.stage))];
  expect(stages.length, stages.join(', ')).toBeGreaterThan(2);
  expect(stages.filter((s) => s.startsWith('mesh: ')).length).toBeGreaterThan(1);
  expect(shown.every((s) => /elapsed/.test(s.time))).toBe(true);
  // The volume has the tree's 10 openings capped.
  await expect(page.locator('#out-caps')).toHaveText(/^inlet(, outlet_\d+){9}$/);
  await screenshots(page, 'progress-tree', page.getByTestId('volume-result'));
});
