import { inflateSync } from 'node:zlib';

import { expect, test } from '@playwright/test';

import { cappedTubeVtp, exportDownload, nodeApi, openApp, screenshots, setSizeAndLayers, upload } from './helpers.js';
import { readZip } from './zip.js';

// The files a vascular pipeline exchanges: a capped SimVascular-like VTP
// whose caps become named openings, every export format written from one
// mesh, names checked by the core as they are typed, and the model's unit.

test.use({ viewport: { width: 1440, height: 900 } });

/** Opens the app and records page errors and console errors. */
async function open(page) {
  const errors = [];
  page.on('pageerror', (e) => errors.push(e.message));
  page.on('console', (m) => m.type() === 'error' && errors.push(m.text()));
  const foreign = await openApp(page);
  return { errors, foreign };
}

async function pickVtp(page) {
  await page.getByTestId('file-input').setInputFiles({
    name: 'model.vtp',
    mimeType: 'application/xml',
    buffer: cappedTubeVtp(),
  });
  await expect(page.getByTestId('stat-openings')).toHaveText('2');
}

/** Small and quick: a uniform size of 0.4 and one boundary layer. */
async function coarse(page) {
  await setSizeAndLayers(page, '0.4', '1');
}

const meshJobs = (page) => page.locator('body').getAttribute('data-mesh-jobs');

/** The largest z of the MSH 4.1 file's volume entity (its bounding box). */
function mshMaxZ(text) {
  const lines = text.split('\n');
  const counts = lines[lines.indexOf('$Entities') + 1].split(' ').map(Number);
  const surfaces = counts[2];
  const volume = lines[lines.indexOf('$Entities') + 2 + surfaces].split(' ').map(Number);
  return volume[6];
}

test('a capped VTP: caps become openings, one named, the mesh exported as VTU then MSH without meshing again', async ({
  page,
}) => {
  const { errors, foreign } = await open(page);
  await pickVtp(page);
  await expect(page.getByTestId('stat-format')).toHaveText('VTK XML PolyData (ascii)');
  await expect(page.getByTestId('stat-caps')).toHaveText('2 removed (faces labelled by ModelFaceID)');
  const rows = page.getByTestId('opening-item');
  await expect(rows).toHaveCount(2);
  await expect(rows.getByTestId('opening-source')).toHaveText(['cap, ModelFaceID 2', 'cap, ModelFaceID 3']);
  // Face labels hint at cm (SimVascular's unit); this one is in mm.
  await expect(page.getByTestId('stat-units')).toContainText('cm?');
  await page.getByTestId('units').selectOption('mm');
  await expect(page.getByTestId('stat-units')).toHaveText('mm');
  await expect(rows.nth(0)).toContainText('radius 0.9943 mm');
  await expect(page.getByTestId('warnings')).toContainText('2 planar caps were recognised and removed');
  await expect(page.getByTestId('warnings')).toContainText('(keep them with “Keep flat caps as wall”)');
  const names = page.getByTestId('opening-name');
  await expect(names.nth(0)).toHaveValue('inlet');
  await expect(names.nth(1)).toHaveValue('outlet_1');
  await expect(names.nth(0)).toHaveAccessibleName('Group name of opening 1');

  // Hovering a row still highlights its rim; naming opening 2.
  await rows.nth(1).hover();
  await expect(rows.nth(1)).toHaveClass(/active/);
  await names.nth(1).fill('distal');
  await expect(names.nth(1)).toHaveAttribute('aria-invalid', 'false');
  await coarse(page);
  await page.getByTestId('remesh').click();
  await expect(page.getByTestId('remesh-result')).toBeVisible({ timeout: 60_000 });
  expect(await meshJobs(page)).toBe('1');
  await expect(rows.nth(1)).toHaveAttribute('data-cap', 'distal');
  await expect(rows.nth(0)).toHaveAttribute('data-cap', 'inlet');
  await expect(page.getByTestId('group-legend').locator('li')).toHaveText(['wall', 'inlet', 'distal']);
  await expect(page.locator('#out-caps')).toHaveText('inlet, distal');

  // Export: the VTU, then the MSH, both written from the mesh shown.
  await page.getByTestId('format').selectOption('vtu');
  const vtu = await exportDownload(page);
  expect(vtu.name).toBe('model.vtu');
  expect(vtu.bytes.toString()).toContain('<VTKFile type="UnstructuredGrid"');
  // Compressed: the same cells, their types in VTK's zlib blocks (the block
  // header, then each block inflated).
  await page.getByTestId('format').selectOption('vtu-compressed');
  await expect(page.getByTestId('export')).toHaveText('Export VTU volume, zlib-compressed');
  await screenshots(page, 'formats-vtu-compressed', page.getByTestId('format'));
  const vtuz = await exportDownload(page);
  expect(vtuz.name).toBe('model.vtu');
  const vtuzText = vtuz.bytes.toString('latin1');
  expect(vtuzText).toContain('header_type="UInt64" compressor="vtkZLibDataCompressor"');
  expect(vtuz.bytes.length).toBeLessThan(vtu.bytes.length / 2);
  const cells = Number(vtu.bytes.toString().match(/NumberOfCells="(\d+)"/)[1]);
  expect(vtuzText).toContain(`NumberOfCells="${cells}"`);
  const data = vtuzText.indexOf('_', vtuzText.indexOf('<AppendedData')) + 1;
  const at = data + Number(vtuzText.match(/Name="types" format="appended" offset="(\d+)"/)[1]);
  const blocks = Number(vtuz.bytes.readBigUInt64LE(at));
  let from = at + 24 + 8 * blocks;
  const types = [];
  for (let b = 0; b < blocks; ++b) {
    const size = Number(vtuz.bytes.readBigUInt64LE(at + 24 + 8 * b));
    types.push(...inflateSync(vtuz.bytes.subarray(from, from + size)));
    from += size;
  }
  expect(types.length).toBe(cells);
  expect(types.every((t) => t === 10)).toBe(true);
  await page.getByTestId('format').selectOption('msh-4.1');
  const msh = await exportDownload(page);
  expect(msh.name).toBe('model.msh');
  const text = msh.bytes.toString();
  expect(text.startsWith('$MeshFormat\n4.1 0 8\n')).toBe(true);
  expect(text).toContain('"distal"');
  expect(mshMaxZ(text)).toBeCloseTo(4, 6);
  // In centimetres, the boundary faces, the wall, the SimVascular folder.
  await page.getByTestId('output-units').selectOption('cm');
  expect(mshMaxZ((await exportDownload(page)).bytes.toString())).toBeCloseTo(0.4, 6);
  // MSH 4.1 binary: the downloaded bytes as written (the int 1 after the
  // header, little-endian), the names in text, as many nodes as the text file.
  await page.getByTestId('format').selectOption('msh-4.1-binary');
  await expect(page.getByTestId('export')).toHaveText('Export MSH 4.1 binary');
  await screenshots(page, 'formats-msh-binary', page.getByTestId('format'));
  const binary = await exportDownload(page);
  expect(binary.name).toBe('model.msh');
  const head = Buffer.from('$MeshFormat\n4.1 1 8\n\x01\x00\x00\x00\n$EndMeshFormat\n', 'latin1');
  expect(binary.bytes.subarray(0, head.length).equals(head)).toBe(true);
  expect(binary.bytes.toString('latin1')).toContain('"distal"');
  const nodesAt = binary.bytes.indexOf('\n$Nodes\n') + 8;
  const textNodes = text.split('$Nodes\n')[1].split('\n');
  const nodes = Number(textNodes[0].split(' ')[1]);
  expect(Number(binary.bytes.readBigUInt64LE(nodesAt + 8))).toBe(nodes);
  // The first node's doubles (after the counts, the block's header and the
  // tags) are the text file's, in cm: bytes no text decoding would keep.
  const firstAt = nodesAt + 32 + 20 + 8 * nodes;
  const first = textNodes[2 + nodes].split(' ').map(Number);
  [0, 1, 2].forEach((k) => expect(binary.bytes.readDoubleLE(firstAt + 8 * k)).toBeCloseTo(first[k] / 10, 12));
  expect(binary.bytes.subarray(-14).toString()).toBe('\n$EndElements\n');
  await page.getByTestId('format').selectOption('vtp');
  const vtp = await exportDownload(page);
  expect(vtp.name).toBe('model-boundary.vtp');
  expect(vtp.bytes.toString()).toContain('<VTKFile type="PolyData"');
  await page.getByTestId('format').selectOption('stl');
  expect((await exportDownload(page)).name).toBe('model-wall.stl');
  await page.getByTestId('format').selectOption('mesh-complete');
  const zip = await exportDownload(page);
  expect(zip.name).toBe('model-mesh-complete.zip');
  expect([...zip.bytes.subarray(0, 4)]).toEqual([0x50, 0x4b, 0x03, 0x04]);
  expect(zip.bytes.toString('latin1')).toContain('mesh-surfaces/distal.vtp');
  // The OpenFOAM case, zipped: constant/polyMesh with its boundary file.
  await page.getByTestId('format').selectOption('foam');
  const foam = await exportDownload(page);
  expect(foam.name).toBe('model-openfoam.zip');
  expect([...foam.bytes.subarray(0, 4)]).toEqual([0x50, 0x4b, 0x03, 0x04]);
  const foamText = foam.bytes.toString('latin1');
  for (const name of ['constant/polyMesh/boundary', 'constant/polyMesh/faces', 'constant/polyMesh/owner']) {
    expect(foamText).toContain(name);
  }
  // Binary: the same case, its faces a faceCompactList of raw labels.
  await page.getByTestId('format').selectOption('foam-binary');
  await expect(page.getByTestId('export')).toHaveText('Export OpenFOAM case, binary polyMesh');
  const foamBinary = readZip((await exportDownload(page)).bytes);
  const faces = foamBinary.get('constant/polyMesh/faces').toString('latin1');
  expect(faces).toMatch(/format {6}binary;\n {4}class {7}faceCompactList;/);
  const textFaces = readZip(foam.bytes).get('constant/polyMesh/faces').toString();
  const nFaces = Number(textFaces.split('\n}\n')[1].trim().split('\n')[0]);
  expect(faces.split('\n}\n')[1].trim().split('\n')[0]).toBe(String(nFaces + 1));  // the offsets
  expect(await meshJobs(page)).toBe('1');
  await screenshots(page, 'formats', rows.nth(1));

  // Another name: the shown mesh no longer matches, so Export meshes first.
  await names.nth(1).fill('iliac');
  await page.getByTestId('format').selectOption('msh-2.2');
  const renamed = await exportDownload(page);
  expect(renamed.bytes.toString().startsWith('$MeshFormat\n2.2 0 8\n')).toBe(true);
  expect(renamed.bytes.toString()).toContain('"iliac"');
  expect(await meshJobs(page)).toBe('2');
  await expect(rows.nth(1)).toHaveAttribute('data-cap', 'iliac');
  expect(errors).toEqual([]);
  expect(foreign).toEqual([]);
});

test('names the core refuses are marked at their input and nothing is meshed', async ({ page }) => {
  const { errors } = await open(page);
  await pickVtp(page);
  const names = page.getByTestId('opening-name');
  const refusals = page.getByTestId('opening-name-error');

  // The inlet choice renames the openings left to their default.
  await page.getByTestId('inlet-choice').nth(1).check();
  await expect(names.nth(0)).toHaveValue('outlet_1');
  await expect(names.nth(1)).toHaveValue('inlet');
  await page.getByTestId('inlet-choice').nth(0).check();
  await expect(names.nth(0)).toHaveValue('inlet');

  await names.nth(1).fill('wall');
  await expect(names.nth(1)).toHaveAttribute('aria-invalid', 'true');
  await expect(refusals.nth(1)).toHaveText(
    "A name cannot be 'wall': wall, lumen, outer_wall, boundary_layer, vessel_wall and wall_* name other groups",
  );
  await expect(refusals.nth(0)).toBeHidden();
  await page.getByTestId('remesh').click();
  await expect(page.getByTestId('error')).toContainText("Opening 2: A name cannot be 'wall'");
  await page.getByTestId('export').click();
  await expect(page.getByTestId('error')).toContainText("Opening 2: A name cannot be 'wall'");
  await screenshots(page, 'formats-names', names.nth(1));

  await names.nth(1).fill('9x');
  await expect(refusals.nth(1)).toHaveText(
    'A name needs 1-64 letters, digits, _ or -, starting with a letter',
  );
  // Each name once: the second of two equal names is refused.
  await names.nth(1).fill('distal');
  await expect(names.nth(1)).toHaveAttribute('aria-invalid', 'false');
  await names.nth(0).fill('distal');
  await expect(refusals.nth(1)).toHaveText("The names give 'distal' to openings 1 and 2: each name once");
  await page.getByTestId('remesh').click();
  await expect(page.getByTestId('error')).toContainText('Opening 2: The names give');
  expect(await meshJobs(page)).toBe('0');
  await expect(page.getByTestId('remesh-result')).toBeHidden();

  // Cleared, a name takes its default back once the input is left.
  await names.nth(0).fill('');
  await names.nth(0).blur();
  await expect(names.nth(0)).toHaveValue('inlet');
  await expect(names.nth(1)).toHaveAttribute('aria-invalid', 'false');
  await expect(refusals).toHaveText(['', '']);
  expect(errors).toEqual([]);
});

test('units: metres guessed plainly and not asked, an unsure guess asked and changed; caps kept as wall', async ({ page }) => {
  const api = await nodeApi();
  const phantom = (scale) => Buffer.from(api.makePhantom({ kind: 'tube', voxel: 0.12, flatCaps: true, scale }).stl);
  const { errors } = await open(page);
  const units = page.getByTestId('stat-units');
  const prompt = page.getByTestId('units-prompt');

  // A model in metres: the core is certain, so nothing is asked; the
  // summary says how it was guessed; every length in m.
  await upload(page, 'metres.stl', phantom(0.003));
  await expect(units).toContainText('m (guessed from the vessel radius 0.00354 largest');
  await expect(units).toContainText('only m gives human vessel sizes');
  await expect(prompt).toBeHidden();
  await expect(page.getByTestId('stat-bbox')).toContainText(' m, diagonal 0.03497 m');
  await expect(page.getByTestId('opening-item').first()).toContainText('radius 0.003273 m');
  await expect(page.getByTestId('warnings')).toContainText('the model is in metres');
  await page.getByTestId('size-mode').selectOption('size');
  await expect(page.locator('#size-label')).toHaveText('h (m)');

  // The same shape in millimetres or centimetres: the page asks.
  await upload(page, 'unsure.stl', phantom(1));
  await expect(prompt).toBeVisible();
  await expect(prompt).toContainText('Units: cm? The numbers could also be millimetres (vessel radius 1.18 largest');
  await expect(units).toContainText('cm? (a guess from the vessel radius 1.18 largest');
  await expect(page.getByTestId('units')).toHaveValue('');
  await screenshots(page, 'formats-units', prompt);
  await prompt.getByRole('button', { name: 'cm', exact: true }).click();
  await expect(units).toHaveText('cm');
  await expect(prompt).toBeHidden();
  await expect(page.getByTestId('units')).toHaveValue('cm');
  await expect(page.getByTestId('opening-item').first()).toContainText('radius 1.091 cm');
  await expect(page.getByRole('combobox', { name: 'Output units' })).toContainText('same as input (cm)');
  // Back to the guess: asked again; confirmed as mm, the question goes.
  await page.getByTestId('units').selectOption('');
  await expect(prompt).toBeVisible();
  await prompt.getByRole('button', { name: 'mm', exact: true }).click();
  await expect(units).toHaveText('mm');
  await expect(prompt).toBeHidden();

  // The flat caps kept as wall: a closed surface, no opening.
  await expect(page.getByTestId('stat-caps')).toHaveText('2 removed');
  await page.getByTestId('keep-caps').check();
  await expect(page.getByTestId('stat-openings')).toHaveText('0');
  await expect(page.getByTestId('stat-caps')).toHaveText('kept as wall');
  await expect(page.getByTestId('stat-closed')).toHaveText('yes');
  await expect(units).toHaveText('mm');
  expect(errors).toEqual([]);
});

test('a UTF-16 ASCII STL is read, and the page says it was UTF-16', async ({ page }) => {
  const { errors, foreign } = await open(page);
  const facet = 'facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\n';
  const text = `solid t\n${facet}endsolid t\n`;
  await upload(page, 'utf16.stl', Buffer.concat([Buffer.from([0xff, 0xfe]), Buffer.from(text, 'utf16le')]));
  await expect(page.getByTestId('stat-format')).toHaveText('ASCII STL');
  await expect(page.getByTestId('stat-input-triangles')).toHaveText('1');
  await expect(page.getByTestId('warnings')).toContainText('UTF-16');
  expect(errors).toEqual([]);
  expect(foreign).toEqual([]);
});
