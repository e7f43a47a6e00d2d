import { execFileSync } from 'node:child_process';
import { mkdtempSync, readFileSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';

import { expect, test } from '@playwright/test';

import { exportDownload, meshAgain, openApp, screenshots, setSizeAndLayers, upload } from './helpers.js';
import { serveStatic } from './static-server.js';

// A clinician gets the same mesh from the page as from the CLI: the MSH the
// page downloads equals, byte for byte but for the options it records, what
// the native CLI writes for the same file with the options the MSH's
// provenance line lists. The app served by vite preview is cross-origin
// isolated and meshes with the threaded core on all the browser's cores;
// served without the COOP/COEP headers, and without the service worker
// that would add them, it falls back to the single-threaded core; both
// must write the CLI's bytes.

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

/** Meshes a bifurcation phantom in the page at `url` (after `setUp(page)`)
 * and with the CLI at the options the page's file records; expects the same
 * bytes. Returns the number of threads the page says it meshed on. */
async function expectSameBytes(page, setUp, url = '/') {
  const dir = mkdtempSync(join(tmpdir(), 'vm-e2e-same-'));
  try {
    const stl = join(dir, 'bifurcation.stl');
    cli('phantom', stl, '--kind', 'bifurcation', '--voxel', '0.1', '--noise', '0.2');
    await openApp(page, url);
    await upload(page, 'bifurcation.stl', readFileSync(stl));
    await expect(page.getByTestId('stat-openings')).toHaveText('3');
    await page.getByTestId('format').selectOption('msh-4.1');
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
    await expect(page.getByTestId('out-time')).toHaveText(/^Meshed in \d+\.\d s on (one thread|\d+ threads)$/);
    return Number(await page.getByTestId('out-time').getAttribute('data-threads'));
  } finally {
    rmSync(dir, { recursive: true, force: true });
  }
}

/** The threads the threaded core runs on in this browser. */
const browserThreads = (page) => page.evaluate(() => Math.min(navigator.hardwareConcurrency, 8));

test('the page and the CLI write the same MSH bytes', async ({ page }) => {
  test.setTimeout(120_000);
  const threads = await expectSameBytes(page, async () => {});
  expect(await page.evaluate(() => crossOriginIsolated)).toBe(true);
  expect(threads).toBe(await browserThreads(page));
  await screenshots(page, 'meshed-threads', page.getByTestId('out-time'));
});

test.describe('without a service worker', () => {
  // The app's service worker would add the headers (e2e/isolation.spec.js).
  test.use({ serviceWorkers: 'block' });

  test('served without COOP/COEP, the page meshes on one thread and writes the same bytes', async ({ page }) => {
    test.setTimeout(120_000);
    const dist = fileURLToPath(new URL('../web/dist/', import.meta.url));
    const server = await serveStatic({ dirs: { '/': dist } });
    try {
      const threads = await expectSameBytes(page, async () => {}, `${server.url}index.html`);
      expect(await page.evaluate(() => crossOriginIsolated)).toBe(false);
      expect(threads).toBe(1);
      await expect(page.getByTestId('out-time')).toHaveAttribute('title', /not cross-origin isolated/);
    } finally {
      await server.close();
    }
  });
});

test('the same bytes with a fine core, which the CLI refines in slabs on its threads', async ({ page }) => {
  test.setTimeout(120_000);
  // Uniform h = 0.13 without layers: over 8192 queued vertices, so the
  // native refinement runs its slab rounds (on 2 threads here).
  const threads = await expectSameBytes(page, (p) => setSizeAndLayers(p, '0.13', '0'));
  expect(threads).toBe(await browserThreads(page));
});
