// The page and the CLI give a user the same mesh: the WebAssembly build,
// through the JS API, must write the same bytes as the native CLI (built by
// scripts/setup.sh at build/vesselmesh, or VM_NATIVE) for the same input and
// options. Inputs are generated phantoms (their STL bytes compared first),
// meshed with the default options and with a coarse uniform size.
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { existsSync, mkdtempSync, readFileSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { after, before, describe, test } from 'node:test';
import { fileURLToPath } from 'node:url';

import { createVesselmesh } from '../src/vesselmesh.js';

const native = process.env.VM_NATIVE ?? fileURLToPath(new URL('../../build/vesselmesh', import.meta.url));
let api;
let dir;
before(async () => {
  assert.ok(existsSync(native), `the native CLI ${native} is missing: build it first (scripts/setup.sh)`);
  const wasmBinary = readFileSync(new URL('../dist/vesselmesh_core.wasm', import.meta.url));
  api = await createVesselmesh({ wasmBinary });
  dir = mkdtempSync(join(tmpdir(), 'vm-determinism-'));
});
after(() => rmSync(dir, { recursive: true, force: true }));

const cli = (...args) => execFileSync(native, args, { encoding: 'utf8', stdio: ['ignore', 'pipe', 'pipe'] });

/** The first differing line of two texts, for the failure message. */
const firstDifference = (a, b) => {
  const x = Buffer.from(a).toString('latin1').split('\n');
  const y = Buffer.from(b).toString('latin1').split('\n');
  const i = x.findIndex((line, k) => line !== y[k]);
  return i < 0 ? `lengths ${x.length} vs ${y.length} lines` : `line ${i + 1}: ${x[i]} | ${y[i]}`;
};

const cases = [
  { name: 'noisy voxel bifurcation', phantom: { kind: 'bifurcation', voxel: 0.12, noise: 0.3 },
    cliPhantom: ['--kind', 'bifurcation', '--voxel', '0.12', '--noise', '0.3'] },
  { name: 'dirty aneurysm (repaired)', phantom: { kind: 'aneurysm', voxel: 0.12, dirty: true },
    cliPhantom: ['--kind', 'aneurysm', '--voxel', '0.12', '--dirty'] },
  { name: '17-branch tree', phantom: { kind: 'tree' }, cliPhantom: ['--kind', 'tree'],
    options: { size: 0.3, layers: 2 }, cliOptions: ['--size', '0.3', '--layers', '2'] },
  // A core large enough (over 8192 queued vertices) for the refinement's
  // slab rounds, which the CLI runs on its threads.
  { name: 'bifurcation with a fine core (slab rounds)', phantom: { kind: 'bifurcation', voxel: 0.12, noise: 0.3 },
    cliPhantom: ['--kind', 'bifurcation', '--voxel', '0.12', '--noise', '0.3'],
    options: { size: 0.13, layers: 0 }, cliOptions: ['--size', '0.13', '--layers', '0', '--threads', '2'] },
];

describe('WebAssembly and native CLI write the same bytes', () => {
  for (const c of cases) {
    test(c.name, () => {
      const stl = api.makePhantom(c.phantom);
      assert.ok(stl.ok, stl.error);
      const stlPath = join(dir, `${c.name}.stl`);
      cli('phantom', stlPath, ...c.cliPhantom);
      assert.ok(Buffer.from(stl.stl).equals(readFileSync(stlPath)), 'the phantom STL differs');

      const m = api.mesh(stl.stl, c.options ?? {});
      assert.ok(m.ok, m.error);
      assert.ok(m.volume.tets.length > 0);
      const mshPath = join(dir, `${c.name}.msh`);
      cli('mesh', stlPath, '-o', mshPath, '--quiet', ...(c.cliOptions ?? []));
      const ours = Buffer.from(m.file);
      const theirs = readFileSync(mshPath);
      assert.ok(ours.equals(theirs), `MSH differs at ${firstDifference(ours, theirs)}`);
    });
  }
});
