import { execFileSync } from 'node:child_process';
import { mkdtempSync, readFileSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';

import { expect, test } from '@playwright/test';

import { exportDownload, meshAgain, openApp, setSizeAndLayers, upload } from './helpers.js';

// A clinician gets the same mesh from the page as from the CLI: the MSH the
// page downloads equals, byte for byte but for the options it records, what
// the native CLI writes for the same file with the options the MSH's
// provenance line lists.

const native = process.env.VM_NATIVE ?? fileURLToPath(new URL('../build/vesselmesh', import.meta.url));
const cli = (...args) => execFileSync(native, args, { encoding: 'utf8', stdio: ['ignore', 'pipe', 'pipe'] });

/** CLI arguments for the provenance line's "id=value" pairs. */
function cliArguments(provenance) {
  const table = new Map(JSON.parse(cli('options', '--json')).map((o) => [o.id, o]));
  const args = [];
  for (const pair of provenance.split(' ').filter(Boolean)) {
    const [id, value] = pair.split('=');
    const o = table.get(id);
    expect(o, `option ${id} in the provenance line`).toBeTruthy();
    if (o.type === 'flag') {
      // A default-on flag's CLI name is its "off" form (--no-remesh).
      if ((value === 'true') !== o.defaultOn) args.push(`--${o.cli}`);
    } else {
      args.push(`--${o.cli}`, value);
    }
  }
  return args;
}

/** Meshes a bifurcation phantom in the page (after `setUp(page)`) and with
 * the CLI at the options the page's file records; expects the same bytes. */
async function expectSameBytes(page, setUp) {
  const dir = mkdtempSync(join(tmpdir(), 'vm-e2e-same-'));
  try {
    const stl = join(dir, 'bifurcation.stl');
    cli('phantom', stl, '--kind', 'bifurcation', '--voxel', '0.1', '--noise', '0.2');
    await openApp(page);
    await upload(page, 'bifurcation.stl', readFileSync(stl));
    await expect(page.getByTestId('stat-openings')).toHaveText('3');
    await page.getByTestId('export-format').selectOption('msh-4.1');
    await setUp(page);
    await meshAgain(page);
    const { bytes } = await exportDownload(page);
    const text = bytes.toString('latin1');
    const provenance = text.split('\n').find((l) => l.startsWith('vesselmesh '));
    const options = provenance.split('; options: ')[1] ?? '';
    const out = join(dir, 'cli.msh');
    cli('mesh', stl, '-o', out, '--quiet', ...cliArguments(options));
    const theirs = readFileSync(out).toString('latin1');
    expect(theirs.length).toBeGreaterThan(1000);
    expect(text.includes('$Elements')).toBe(true);
    // The provenance line records the options as each side gave them (the
    // page also lists values equal to the defaults, which the CLI has no
    // flag for, e.g. surface_only=false); the input's hash must agree, and
    // every other byte.
    const [pageLine, cliLine] = [text, theirs].map((t) => t.split('\n').find((l) => l.startsWith('vesselmesh ')));
    expect(pageLine.split('; options:')[0]).toBe(cliLine.split('; options:')[0]);
    expect(text.replace(pageLine, '') === theirs.replace(cliLine, ''), `page options: ${options}`).toBe(true);
  } finally {
    rmSync(dir, { recursive: true, force: true });
  }
}

test('the page and the CLI write the same MSH bytes', async ({ page }) => {
  test.setTimeout(120_000);
  await expectSameBytes(page, async () => {});
});

test('the same bytes with a fine core, which the CLI refines in slabs on its threads', async ({ page }) => {
  test.setTimeout(120_000);
  // Uniform h = 0.13 without layers: over 8192 queued vertices, so the
  // native refinement runs its slab rounds (on 2 threads here).
  await expectSameBytes(page, (p) => setSizeAndLayers(p, '0.13', '0'));
});
