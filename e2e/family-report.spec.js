import { mkdirSync, writeFileSync } from 'node:fs';
import { pathToFileURL } from 'node:url';

import AxeBuilder from '@axe-core/playwright';
import { expect, test } from '@playwright/test';

import { exportDownload, loadSample, meshAgain, nodeApi, seriousViolations, setSizeAndLayers } from './helpers.js';
import { readMsh } from './msh.js';
import { serveStatic } from './static-server.js';
import { readZip } from './zip.js';

// The export area's mesh-independence family and methods report: Mesh
// family downloads one zip of N meshes and their table (the same groups in
// each), tabled in the page with the ratios achieved; Download report gives
// one HTML page with the page's own pictures that works from disk with no
// network, names what the page shows, has the family's table and passes axe.
// The element's `report` attribute and report() do the same.

test.use({ viewport: { width: 1440, height: 900 } });

const OUT = new URL('../out/', import.meta.url).pathname;

/** Clicks `button` and waits for the download: its suggested name and bytes. */
async function downloadOf(page, button, timeout = 120_000) {
  const [download] = await Promise.all([page.waitForEvent('download', { timeout }), button.click()]);
  const chunks = [];
  for await (const chunk of await download.createReadStream()) chunks.push(chunk);
  return { name: download.suggestedFilename(), bytes: Buffer.concat(chunks) };
}

/** Opens an HTML file from disk in a new context that can reach nothing
 * else (every request but file: is aborted); returns the page and the
 * requests that were refused. */
async function openOffline(browser, path) {
  const context = await browser.newContext();
  const refused = [];
  await context.route('**', (route) => {
    if (route.request().url().startsWith('file:')) return route.continue();
    refused.push(route.request().url());
    return route.abort();
  });
  const page = await context.newPage();
  await page.goto(pathToFileURL(path).href);
  return { page, context, refused };
}

/** What an opened report shows: its pictures (loaded, with their alt texts),
 * histograms, text and axe violations. */
async function readReport(page) {
  await page.waitForLoadState('load');
  const images = await page
    .locator('img')
    .evaluateAll((imgs) =>
      imgs.map((i) => ({ complete: i.complete, width: i.naturalWidth, alt: i.alt, src: i.src.slice(0, 21) })),
    );
  const svgs = await page.locator('svg').count();
  const text = await page.locator('body').innerText();
  const { violations } = await new AxeBuilder({ page }).analyze();
  return { images, svgs, text, violations: violations.map((v) => `${v.impact} ${v.id}: ${v.help}`) };
}

test('Mesh family: a zip of 3 meshes with the same groups, tabled; the report from disk has its pictures and the family', async ({
  page,
  browser,
}) => {
  test.setTimeout(300_000);
  const { errors, foreign } = await loadSample(page);
  // The fields' ranges and defaults are the option table's.
  const members = page.getByTestId('family');
  const ratio = page.getByTestId('ratio');
  await expect(members).toHaveValue('3');
  await expect(members).toHaveAttribute('min', '2');
  await expect(members).toHaveAttribute('max', '6');
  await expect(ratio).toHaveValue('1.4');
  await expect(ratio).toHaveAttribute('min', '1.1');
  await expect(ratio).toHaveAttribute('max', '2');
  await expect(page.getByTestId('family-layers')).toHaveValue('refine');
  await expect(page.getByRole('spinbutton', { name: 'Meshes N' })).toHaveCount(1);
  await expect(page.getByRole('combobox', { name: 'Boundary layer' })).toHaveValue('refine');
  await expect(page.getByTestId('download-report')).toBeHidden(); // no mesh yet

  await setSizeAndLayers(page, '0.4', '2');
  await meshAgain(page);
  await expect(page.getByTestId('download-report')).toBeVisible();
  // The report of a single mesh: the page's three pictures, no family.
  const single = (await downloadOf(page, page.getByTestId('download-report'))).bytes.toString();
  expect(single.match(/<img [^>]*src="data:image\/png;base64,/g)).toHaveLength(3);
  expect(single).not.toContain('<h2>Mesh family</h2>');

  // A ratio out of range is said where the user looks; the field is marked.
  await ratio.fill('3');
  await page.getByTestId('mesh-family').click();
  await expect(page.getByTestId('error')).toContainText('Mesh family: the ratio must be from 1.1 to 2');
  await expect(ratio).toHaveAttribute('aria-invalid', 'true');
  await expect(ratio).toBeFocused();
  await ratio.fill('1.4');
  await expect(ratio).toHaveAttribute('aria-invalid', 'false');

  const zip = await downloadOf(page, page.getByTestId('mesh-family'));
  expect(zip.name).toBe('sample-bifurcation-mesh-family.zip');
  const entries = readZip(zip.bytes);
  expect([...entries.keys()].sort()).toEqual(['family.csv', 'family.json', 'mesh_0.msh', 'mesh_1.msh', 'mesh_2.msh']);
  const family = JSON.parse(entries.get('family.json').toString());
  expect(family.members).toBe(3);
  expect(entries.get('family.csv').toString().split('\n').filter(Boolean)).toHaveLength(4); // a header and 3 rows
  // Every member has the same physical groups (the solver's boundary
  // conditions apply to each), and is a sound mesh.
  const meshes = ['mesh_0.msh', 'mesh_1.msh', 'mesh_2.msh'].map((f) => readMsh(entries.get(f).toString()));
  const names = meshes.map((m) => m.groups.map((g) => `${g.dim} ${g.name}`).sort());
  expect(names[0]).toEqual(expect.arrayContaining(['2 wall', '2 inlet', '2 outlet_1', '2 outlet_2', '3 lumen']));
  expect(names[1]).toEqual(names[0]);
  expect(names[2]).toEqual(names[0]);
  for (const [k, m] of meshes.entries()) expect(m.problems, `mesh_${k}.msh`).toEqual([]);
  expect(meshes[1].elements[4]).toBeGreaterThan(meshes[0].elements[4]);
  expect(meshes[2].elements[4]).toBeGreaterThan(meshes[1].elements[4]);

  // The table in the page: a column per mesh, the ratios achieved near 1.4.
  const table = page.getByTestId('family-table');
  await expect(table).toBeVisible();
  await expect(table.locator('caption')).toHaveText('Mesh family: 3 meshes, ratio 1.4');
  await expect(page.getByTestId('family-note')).toContainText('boundary layer refined with the family');
  await expect(page.getByTestId('family-note')).toContainText('Downloaded as sample-bifurcation-mesh-family.zip');
  await expect(table.locator('thead th[scope=col]')).toHaveText(['Mesh 0', 'Mesh 1', 'Mesh 2']);
  await expect(table.locator('tbody th[scope=row]')).toHaveText([
    'Cells',
    'h (mm)',
    'Ratio achieved',
    'γt min',
    'γt mean',
    'Layers',
    'First layer (mm)',
    'Time (s)',
  ]);
  const cell = (stat, k) => table.locator(`tr[data-stat=${stat}] td[data-member="${k}"]`);
  for (const k of [1, 2]) {
    const achieved = Number(await cell('ratio', k).textContent());
    expect(Math.abs(achieved - 1.4) / 1.4, `ratio of mesh ${k}`).toBeLessThan(0.1);
  }
  for (const k of [0, 1, 2]) await expect(cell('cells', k)).toHaveText(family.rows[k].cells.toLocaleString('en'));
  await expect(cell('layers', 2)).toHaveText(String(family.rows[2].layers));
  // The view and the result show the first mesh: the mesh as asked.
  await expect(page.getByTestId('out-tets')).toHaveText(family.rows[0].tetrahedra.toLocaleString('en'));
  await expect(page.getByTestId('family-table').locator('..')).toBeFocused();
  expect(await seriousViolations(page), 'the page with the family table').toEqual([]);
  // Export writes that first mesh again, without meshing: it is the mesh of the panel's options.
  const jobs = await page.locator('body').getAttribute('data-mesh-jobs');
  const msh = await exportDownload(page);
  expect(msh.name).toBe('sample-bifurcation.msh');
  expect(readMsh(msh.bytes.toString()).elements[4]).toBe(meshes[0].elements[4]);
  await expect(page.locator('body')).toHaveAttribute('data-mesh-jobs', jobs);

  // The report of that mesh and its family, with the page's own pictures.
  const tets = await page.getByTestId('out-tets').textContent();
  const groups = [...(await page.locator('#out-caps').textContent()).split(', '), 'wall'];
  const viewBefore = await page.evaluate(() => document.querySelector('#viewer canvas').width);
  const report = await downloadOf(page, page.getByTestId('download-report'));
  expect(report.name).toBe('sample-bifurcation-report.html');
  await expect(page.getByTestId('next-step')).toContainText('Downloaded sample-bifurcation-report.html');
  await expect(page.locator('body')).toHaveAttribute('data-mesh-jobs', jobs); // the worker still held the mesh
  // The view is put back as it was (its size, the volume shown).
  expect(await page.evaluate(() => document.querySelector('#viewer canvas').width)).toBe(viewBefore);
  await expect(page.getByTestId('volume-view')).toBeVisible();
  await expect(page.getByTestId('clip-info')).toContainText('triangles drawn');

  mkdirSync(OUT, { recursive: true });
  // Pictures of the export area: the report button at the top of the
  // panel (out/family-report-{desktop,phone}.png), then the family's table
  // on a phone (out/family-table-phone.png).
  const top = (id) => page.getByTestId(id).evaluate((el) => el.scrollIntoView({ block: 'start', behavior: 'instant' }));
  for (const [size, width, height] of [
    ['desktop', 1440, 900],
    ['phone', 390, 844],
  ]) {
    await page.setViewportSize({ width, height });
    await page.locator('[data-report-box]').evaluate((el) => el.scrollIntoView({ block: 'start' }));
    await page.screenshot({ path: `${OUT}family-report-${size}.png` });
  }
  await top('family-table');
  await page.screenshot({ path: `${OUT}family-table-phone.png` });
  const width = await page.evaluate(() => document.scrollingElement.scrollWidth);
  expect(width, 'page scroll width on a phone').toBeLessThanOrEqual(390);
  const [scroll, client] = await page.locator('#panel-body').evaluate((el) => [el.scrollWidth, el.clientWidth]);
  expect(scroll, 'panel scroll width on a phone').toBeLessThanOrEqual(client);
  for (const id of ['mesh-family', 'download-report', 'family', 'ratio', 'family-layers']) {
    const box = await page.getByTestId(id).boundingBox();
    expect(box.x + box.width, `${id} within the phone's width`).toBeLessThanOrEqual(390);
  }
  await page.setViewportSize({ width: 1440, height: 900 });

  const path = `${OUT}family-report.html`;
  writeFileSync(path, report.bytes);
  const offline = await openOffline(browser, path);
  try {
    const seen = await readReport(offline.page);
    expect(seen.images).toHaveLength(3);
    for (const image of seen.images) {
      expect(image.complete && image.width > 0, image.alt).toBe(true);
      expect(image.src).toBe('data:image/png;base64');
    }
    // The pictures are the page's (its alt texts), with numbers.
    expect(seen.images.map((i) => i.alt.split(',')[0])).toEqual([
      'Wall mesh',
      expect.stringMatching(/^The volume mesh cut by the plane/),
      expect.stringMatching(/^Close-up of the cut/),
    ]);
    expect(seen.images[0].alt).toContain(`${await page.getByTestId('out-triangles').textContent()} triangles`);
    expect(seen.svgs).toBeGreaterThanOrEqual(2); // the histograms
    expect(seen.text).toContain(tets);
    for (const name of groups) expect(seen.text, name).toContain(name);
    expect(seen.text).toContain('Mesh family');
    for (const file of ['mesh_0.msh', 'mesh_1.msh', 'mesh_2.msh']) expect(seen.text).toContain(file);
    expect(seen.violations).toEqual([]);
    expect(offline.refused).toEqual([]);
    await offline.page.screenshot({ path: `${OUT}family-report-html.png`, fullPage: false });
  } finally {
    await offline.context.close();
  }
  expect(foreign).toEqual([]);
  expect(errors).toEqual([]);
});

const BUILT = new URL('../dist/element/', import.meta.url).pathname;

test('<vessel-mesher report>: the button once meshed, report() a Blob of HTML; a family in its options exports a zip', async ({
  page,
}) => {
  test.setTimeout(240_000);
  const api = await nodeApi();
  const sample = api.makePhantom({ kind: 'bifurcation', voxel: 0.08, noise: 0.3 });
  const host = `<!doctype html>
<html lang="en"><head><meta charset="utf-8"><title>host</title>
<style>vessel-mesher { height: 360px; margin: 8px; }</style></head>
<body>
  <vessel-mesher id="m" report src="sample.stl" options='{"units": "mm", "size": 0.45, "layers": 1}'></vessel-mesher>
  <vessel-mesher id="plain" compact></vessel-mesher>
  <script type="module" src="./vesselmesh/element/vessel-mesher.js"></script>
</body></html>`;
  const server = await serveStatic({
    files: { '/': host, '/sample.stl': Buffer.from(sample.stl) },
    dirs: { '/vesselmesh/element/': BUILT },
  });
  try {
    const errors = [];
    page.on('pageerror', (e) => errors.push(e.message));
    await page.goto(server.url);
    const m = page.locator('#m');
    await expect(m.getByRole('status')).toContainText('3 openings', { timeout: 60_000 });
    const button = m.getByRole('button', { name: 'Download report' });
    await expect(button).toBeHidden();
    await expect(page.locator('#plain').getByRole('button', { name: 'Download report' })).toBeHidden();
    await m.getByRole('button', { name: 'Mesh' }).click();
    await expect(m.getByRole('status')).toContainText('tetrahedra', { timeout: 120_000 });
    await expect(button).toBeVisible();

    const made = await page.evaluate(async () => {
      const blob = await document.getElementById('m').report();
      const text = await blob.text();
      return {
        type: blob.type,
        head: text.slice(0, 200),
        images: (text.match(/<img [^>]*src="data:image\/png;base64,/g) ?? []).length,
        alts: [...text.matchAll(/alt="([^"]*)"/g)].map((x) => x[1].split(',')[0]),
      };
    });
    expect(made.type).toBe('text/html');
    expect(made.head).toContain('<html lang="en"');
    expect(made.images).toBe(3);
    expect(made.alts[0]).toBe('Wall mesh'); // the element's view drew them

    const download = await downloadOf(page, button);
    expect(download.name).toBe('sample-report.html');
    expect(download.bytes.toString()).toContain('<html lang="en"');

    // A family from the options: export() gives its zip.
    const family = await page.evaluate(async () => {
      const el = document.getElementById('m');
      el.setAttribute('options', JSON.stringify({ ...el.meshOptions, family: 2, ratio: 1.5 }));
      const result = await el.mesh();
      const blob = await el.export();
      const bytes = [...new Uint8Array(await blob.arrayBuffer())];
      return { ok: result.ok, members: result.family?.members, type: blob.type, bytes };
    });
    expect(family.ok).toBe(true);
    expect(family.members).toBe(2);
    expect(family.type).toBe('application/zip');
    const entries = [...readZip(Buffer.from(family.bytes)).keys()].sort();
    expect(entries).toEqual(['family.csv', 'family.json', 'mesh_0.msh', 'mesh_1.msh']);
    expect(errors).toEqual([]);
  } finally {
    await server.close();
  }
});
