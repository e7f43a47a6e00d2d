import { gzipSync } from 'node:zlib';

import { expect, test } from '@playwright/test';

import { expectStats, openApp, openBoxBinary, screenshots, TETRA_ASCII, upload } from './helpers.js';

const num = async (page, id) => Number((await page.getByTestId(id).textContent()).replace(/,/g, ''));

test('the sample loads, is analyzed and shown', async ({ page }) => {
  const foreign = await openApp(page);
  await page.getByTestId('load-sample').click();
  await expect(page.getByTestId('stat-openings')).toHaveText('3');
  expect(await num(page, 'stat-triangles')).toBeGreaterThan(1000);
  await expect(page.getByTestId('stat-genus')).toHaveText('0');
  await expect(page.getByTestId('stat-components')).toHaveText('1');
  const min = await num(page, 'quality-min');
  const mean = await num(page, 'quality-mean');
  expect(min).toBeGreaterThanOrEqual(0);
  expect(mean).toBeGreaterThan(min);
  expect(mean).toBeLessThanOrEqual(1);
  await expect(page.locator('#viewer canvas')).toBeVisible();
  await expect(page.locator('#histogram rect')).toHaveCount(20);
  // Hovering an opening highlights it (its list item becomes active).
  const first = page.getByTestId('opening-item').first();
  await expect(page.getByTestId('opening-item')).toHaveCount(3);
  await first.hover();
  await expect(first).toHaveClass(/active/);
  expect(foreign).toEqual([]);
});

test('an ASCII STL picked with the file input', async ({ page }) => {
  await openApp(page);
  await upload(page, 'tetra.stl', Buffer.from(TETRA_ASCII));
  await expectStats(page, { triangles: '4', vertices: '4', openings: '0', closed: 'yes', genus: '0', format: 'ASCII STL' });
  await expect(page.getByTestId('warnings')).toContainText('re-oriented');
});

test('a binary STL of an open box', async ({ page }) => {
  await openApp(page);
  await upload(page, 'box.stl', openBoxBinary());
  await expectStats(page, { triangles: '10', vertices: '8', openings: '1', closed: 'no', format: 'binary STL' });
  await expect(page.getByTestId('opening-item')).toContainText('perimeter 4');
});

for (const version of ['4.1', '2.2']) {
  test(`export MSH ${version}`, async ({ page }) => {
    await openApp(page);
    await upload(page, 'tetra.stl', Buffer.from(TETRA_ASCII));
    await expect(page.getByTestId('stat-triangles')).toHaveText('4');
    await page.getByTestId('format').selectOption(`msh-${version}`);
    // Closed, without an opening: the page says so before meshing; the user goes on.
    await page.getByTestId('export').click();
    await expect(page.getByTestId('error')).toContainText('The surface is closed');
    const [download] = await Promise.all([page.waitForEvent('download'), page.getByTestId('mesh-anyway').click()]);
    expect(download.suggestedFilename()).toBe('tetra.msh');
    const chunks = [];
    for await (const chunk of await download.createReadStream()) chunks.push(chunk);
    const text = Buffer.concat(chunks).toString();
    expect(text.startsWith(`$MeshFormat\n${version} 0 8\n`)).toBe(true);
    expect(text).toContain('"wall"');
    expect(text.trimEnd().endsWith('$EndElements')).toBe(true);
  });
}

test('bad inputs give readable errors and the page keeps working', async ({ page }) => {
  await openApp(page);
  const error = page.getByTestId('error');
  await upload(page, 'empty.stl', Buffer.alloc(0));
  await expect(error).toBeVisible();
  await expect(error).toContainText('empty.stl: empty file');

  await upload(page, 'garbage.stl', Buffer.from('this is not a mesh\n'));
  await expect(error).toContainText('garbage.stl: not a surface file this tool reads');

  // 256 MiB of zeros, gzipped (256 members of 1 MiB): refused from its
  // first inflated bytes, the rest never inflated.
  const member = gzipSync(Buffer.alloc(1 << 20), { level: 9 });
  await upload(page, 'zeros.stl.gz', Buffer.concat(Array(256).fill(member)));
  await expect(error).toContainText('zeros.stl.gz: gzip-compressed file: its first 65536 decompressed bytes are not');
  await expect(error).toContainText('they are all zero bytes; the rest was not decompressed. Open the surface file itself');
  await screenshots(page, 'refused-gzip', error);

  const truncated = openBoxBinary().subarray(0, 300);
  await upload(page, 'truncated.stl', truncated);
  await expect(error).toContainText('truncated binary STL');

  await page.getByTestId('load-sample').click();
  await expect(page.getByTestId('stat-openings')).toHaveText('3');
  await expect(error).toBeHidden();
});

test('several components: export refused, then allowed with the largest only', async ({ page }) => {
  await openApp(page);
  // The open box plus a far tetrahedron as one ASCII file.
  const box = openBoxBinary();
  let facets = '';
  for (let t = 0; t < 10; t++) {
    facets += 'facet normal 0 0 0\nouter loop\n';
    for (let c = 0; c < 3; c++) {
      const at = 84 + 50 * t + 12 + 12 * c;
      facets += `vertex ${box.readFloatLE(at)} ${box.readFloatLE(at + 4)} ${box.readFloatLE(at + 8)}\n`;
    }
    facets += 'endloop\nendfacet\n';
  }
  const tetra = TETRA_ASCII.replace('solid tet\n', '').replace('endsolid tet\n', '').replace(/vertex (\S+)/g, (_, x) => `vertex ${Number(x) + 10}`);
  await upload(page, 'two.stl', Buffer.from(`solid two\n${facets}${tetra}endsolid two\n`));
  await expect(page.getByTestId('stat-components')).toHaveText('2');
  await page.getByTestId('export').click();
  await expect(page.getByTestId('error')).toContainText('2 connected components');
  await page.getByTestId('largest-component-only').check();
  // One opening: the page warns (no outlet) before meshing; the user goes on.
  await page.getByTestId('export').click();
  await expect(page.getByTestId('error')).toContainText('no outlet');
  const [download] = await Promise.all([page.waitForEvent('download'), page.getByTestId('mesh-anyway').click()]);
  expect(download.suggestedFilename()).toBe('two.msh');
});
