// The one-file app (dist/vesselmesh.html, `npm run build:web`): opened from
// disk with the network off, it loads the sample, meshes it and exports an
// MSH that Gmsh reads; it requests nothing but itself (file:, data:, blob:).
import { execFileSync } from 'node:child_process';
import { existsSync, mkdtempSync, rmSync, statSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { pathToFileURL } from 'node:url';

import { expect, test } from '@playwright/test';

import { exportDownload, screenshots } from './helpers.js';

const FILE = new URL('../dist/vesselmesh.html', import.meta.url).pathname;

/** Gmsh's view of an MSH file: its element and node counts (Debian's
 * python3-gmsh; GMSH_PYTHON names another interpreter). */
function gmshCounts(bytes) {
  const dir = mkdtempSync(join(tmpdir(), 'vm-msh-'));
  try {
    const path = join(dir, 'mesh.msh');
    writeFileSync(path, bytes);
    const script = [
      'import gmsh, json, sys',
      'gmsh.initialize()',
      'gmsh.option.setNumber("General.Verbosity", 0)',
      'gmsh.open(sys.argv[1])',
      'types, tags, _ = gmsh.model.mesh.getElements()',
      'nodes, _, _ = gmsh.model.mesh.getNodes()',
      'print(json.dumps({"types": [int(t) for t in types], "elements": sum(len(t) for t in tags), "nodes": len(nodes)}))',
      'gmsh.finalize()',
    ].join('\n');
    const python = process.env.GMSH_PYTHON || '/usr/bin/python3';
    const out = execFileSync(python, ['-c', script, path], { encoding: 'utf8' });
    return JSON.parse(out.trim().split('\n').at(-1));
  } finally {
    rmSync(dir, { recursive: true, force: true });
  }
}

test('the one-file app works from file:// with the network off', async ({ page, context }) => {
  expect(existsSync(FILE), 'dist/vesselmesh.html is built (npm run build:web)').toBe(true);
  const outside = [];
  page.on('request', (request) => {
    const { protocol } = new URL(request.url());
    if (!['file:', 'data:', 'blob:'].includes(protocol)) outside.push(request.url());
  });
  const errors = [];
  page.on('pageerror', (e) => errors.push(e.message));
  await context.setOffline(true);
  await page.goto(pathToFileURL(FILE).href);
  await expect(page.locator('body')).toHaveAttribute('data-ready', 'true');
  await page.getByTestId('load-sample').click();
  await expect(page.getByTestId('stat-openings')).toHaveText('3');
  await page.getByTestId('remesh').click();
  await expect(page.getByTestId('remesh-result')).toBeVisible({ timeout: 60_000 });
  await page.getByTestId('format').selectOption('msh-4.1');
  const { name, bytes } = await exportDownload(page);
  expect(name).toMatch(/\.msh$/);
  const counts = gmshCounts(bytes);
  expect(counts.types).toContain(4); // tetrahedra
  expect(counts.elements).toBeGreaterThan(1000);
  expect(counts.nodes).toBeGreaterThan(100);
  await screenshots(page, 'singlefile');
  expect(statSync(FILE).size).toBeLessThan(8 * 2 ** 20);
  expect(outside).toEqual([]);
  expect(errors).toEqual([]);
});
