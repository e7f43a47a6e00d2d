import { expect, test } from '@playwright/test';

import { exportDownload, loadSample, meshAgain as mesh, screenshots } from './helpers.js';

// "Which solver?": asked once in the Mesh step, remembered; the preset sets
// the element types, export format and units; the result says what it set.
// The first layer from a target y+ is reachable there too.

/** The MSH text's version, physical groups [dim, tag, name] and element types. */
function readMsh(text) {
  const lines = text.split('\n');
  const version = lines[lines.indexOf('$MeshFormat') + 1].split(' ')[0];
  const p = lines.indexOf('$PhysicalNames');
  const groups = lines.slice(p + 2, p + 2 + Number(lines[p + 1])).map((l) => {
    const [dim, tag, name] = l.split(' ');
    return [Number(dim), Number(tag), name.slice(1, -1)];
  });
  let e = lines.indexOf('$Elements') + 1;
  const types = new Set();
  if (version === '2.2') {
    for (const l of lines.slice(e + 1, e + 1 + Number(lines[e]))) types.add(Number(l.split(' ')[1]));
  } else {
    const blocks = Number(lines[e++].split(' ')[0]);
    for (let b = 0; b < blocks; b++) {
      const [, , type, n] = lines[e].split(' ').map(Number);
      types.add(type);
      e += n + 1;
    }
  }
  return { version, groups, types: [...types].sort((a, b) => a - b) };
}

test('OpenFOAM: the native case by default; as MSH 2.2: prisms in metres, tags unique; remembered after a reload', async ({ page }) => {
  const { errors, foreign } = await loadSample(page);
  await expect(page.getByTestId('solver')).toHaveValue('');
  await expect(page.getByTestId('solver-hint')).toBeHidden();
  await page.getByTestId('solver').selectOption('openfoam');
  // The preset sets the controls it decides; the user may change them after.
  await expect(page.getByTestId('prisms')).toBeChecked();
  await expect(page.getByTestId('format')).toHaveValue('foam');
  await expect(page.getByTestId('output-units')).toHaveValue('m');
  await expect(page.getByTestId('solver-hint')).toContainText('layer prisms kept, OpenFOAM case');
  await expect(page.getByTestId('solver-hint')).toContainText('written in m');
  await expect(page.getByTestId('solver-hint')).toContainText('wall is a wall patch');
  // The user may still want gmshToFoam's input: MSH 2.2, chosen after.
  await page.getByTestId('format').selectOption('msh-2.2');
  await page.getByTestId('layers').fill('2');
  await mesh(page);
  await expect(page.getByTestId('out-preset')).toBeVisible();
  // In the page's words, not the API's option names.
  await expect(page.getByTestId('out-preset')).toContainText('Preset for OpenFOAM (polyMesh case): MSH 2.2, written in m');
  await expect(page.getByTestId('out-preset')).toContainText('yours: layer prisms kept'); // the checkbox says so
  await expect(page.getByTestId('out-preset')).not.toContainText(/mshVersion|outputUnits|prisms true/);
  await screenshots(page, 'solver-openfoam', page.getByTestId('solver'));

  const { name, bytes } = await exportDownload(page);
  expect(name).toMatch(/\.msh$/);
  const msh = readMsh(bytes.toString());
  expect(msh.version).toBe('2.2');
  expect(msh.types).toEqual([2, 3, 4, 6]);
  const tags = msh.groups.map(([, tag]) => tag);
  expect(new Set(tags).size).toBe(tags.length);
  expect(msh.groups).toEqual([
    [2, 1, 'wall'],
    [2, 2, 'inlet'],
    [2, 3, 'outlet_1'],
    [2, 4, 'outlet_2'],
    [3, 5, 'lumen'],
  ]);

  // Asked once: remembered with the other options.
  await page.reload();
  await expect(page.locator('body')).toHaveAttribute('data-ready', 'true');
  await expect(page.getByTestId('solver')).toHaveValue('openfoam');
  await expect(page.getByTestId('solver-hint')).toContainText('OpenFOAM');
  expect(foreign).toEqual([]);
  expect(errors).toEqual([]);
});

test('FEniCS: tetrahedra only; a target y+ sizes the first layer, shown in the result', async ({ page }) => {
  const { errors } = await loadSample(page);
  await page.getByTestId('prisms').check();
  await page.getByTestId('solver').selectOption('fenics');
  await expect(page.getByTestId('prisms')).not.toBeChecked();
  await expect(page.getByTestId('format')).toHaveValue('msh-4.1');
  await expect(page.getByTestId('output-units')).toHaveValue('');
  await page.getByTestId('layers').fill('3');
  await page.getByTestId('layer-mode').selectOption('yplus');
  await expect(page.getByTestId('yplus-fields')).toBeVisible();
  await expect(page.getByTestId('density')).toHaveValue('1060');
  await expect(page.getByTestId('viscosity')).toHaveValue('0.0035');
  await page.getByTestId('first-layer-yplus').fill('2');
  await page.getByTestId('inlet-velocity').fill('0.4');
  await mesh(page);
  await expect(page.getByTestId('out-preset')).toContainText('Preset for FEniCS (dolfinx):');
  const yplus = page.getByTestId('out-yplus');
  await expect(yplus).toBeVisible();
  await expect(yplus).toContainText(/^First layer [\d.e-]+ mm for y\+ 2 at inlet \(diameter [\d.]+ mm, 0\.4 m\/s: Re \d+/);
  await screenshots(page, 'solver-fenics-yplus', yplus);
  const msh = readMsh((await exportDownload(page)).bytes.toString());
  expect(msh.version).toBe('4.1');
  expect(msh.types).toEqual([2, 4]);
  expect(errors).toEqual([]);

  // A bad velocity is said next to its field, before the core is asked.
  await page.getByTestId('inlet-velocity').fill('-1');
  await page.getByTestId('remesh').click();
  await expect(page.getByTestId('error')).toContainText('the inlet velocity must be a positive velocity in m/s');
  await expect(page.getByTestId('inlet-velocity')).toHaveAttribute('aria-invalid', 'true');
});

test('svFSI with a vessel wall: the download holds fluid/ and solid/ mesh-complete folders', async ({ page }) => {
  const { errors, foreign } = await loadSample(page);
  await page.getByTestId('solver').selectOption('svfsi');
  await expect(page.getByTestId('format')).toHaveValue('mesh-complete');
  await page.getByTestId('layers').fill('1');
  await page.getByTestId('wall-on').check();
  await mesh(page);
  const { name, bytes } = await exportDownload(page);
  expect(name).toMatch(/\.zip$/);
  // A zip's central directory names its entries in plain text.
  const names = bytes.toString('latin1');
  for (const path of ['fluid/mesh-complete.mesh.vtu', 'fluid/mesh-surfaces/wall.vtp', 'solid/mesh-complete.mesh.vtu', 'solid/mesh-surfaces/wall.vtp', 'solid/mesh-surfaces/outer_wall.vtp']) {
    expect(names).toContain(path);
  }
  expect(foreign).toEqual([]);
  expect(errors).toEqual([]);
});
