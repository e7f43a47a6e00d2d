// The threaded core in Node (wasm/src/node-threads.js): the package's Node
// entry loads it with its pool on worker_threads when asked for more than
// one thread, writes the same bytes as the single-threaded core, leaves no
// global behind, and a script using it exits by itself.
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import { readFileSync } from 'node:fs';
import { before, describe, test } from 'node:test';

import { createVesselmesh } from '../src/node.js';
import { createVesselmeshIn } from '../src/vesselmesh.js';

const NODE_ENTRY = new URL('../src/node.js', import.meta.url).href;

let one;
let two;
let globalsBefore;
before(async () => {
  globalsBefore = { Worker: globalThis.Worker, navigator: globalThis.navigator };
  one = await createVesselmesh({ threads: 1 });
  two = await createVesselmesh({ threads: 2 });
});

describe('the threaded core in Node', () => {
  test('threads: 2 loads the threaded core on 2 threads; threads: 1 the single-threaded core', () => {
    assert.equal(two.threads, 2);
    assert.equal(two.threadsNote, '');
    assert.equal(one.threads, 1);
    assert.match(one.threadsNote, /threads: 1 was asked/);
    assert.equal(two.version, one.version);
  });

  const cases = [
    { name: 'noisy bifurcation', phantom: { kind: 'bifurcation', voxel: 0.08, noise: 0.3 }, options: { perCircumference: 10 } },
    { name: 'dirty aneurysm, default options (boundary layer)', phantom: { kind: 'aneurysm', voxel: 0.12, dirty: true } },
  ];
  for (const c of cases) {
    test(`a volume mesh on 2 threads is the same bytes as on 1: ${c.name}`, () => {
      const stl = one.makePhantom(c.phantom);
      assert.ok(stl.ok, stl.error);
      const a = one.mesh(stl.stl, c.options);
      const b = two.mesh(stl.stl, c.options);
      assert.ok(a.ok, a.error);
      assert.ok(b.ok, b.error);
      assert.ok(b.volume.tets.length > 4000, `${b.volume.tets.length / 4} tetrahedra`);
      assert.ok(Buffer.from(a.msh).equals(Buffer.from(b.msh)), 'the MSH files differ');
    });
  }

  test('no global is left behind (Worker, navigator)', () => {
    assert.equal(globalThis.Worker, globalsBefore.Worker);
    assert.equal(globalThis.navigator, globalsBefore.navigator);
  });

  test('a script that meshes on 2 threads exits by itself', () => {
    const script = `import { createVesselmesh } from ${JSON.stringify(NODE_ENTRY)};
const api = await createVesselmesh({ threads: 2 });
const stl = api.makePhantom({ kind: 'bifurcation', voxel: 0.12 }).stl;
const result = api.mesh(stl, { perCircumference: 20 });
console.log(JSON.stringify({ threads: api.threads, note: api.threadsNote, ok: result.ok, error: result.error }));`;
    const run = spawnSync(process.execPath, ['--input-type=module', '-e', script], { encoding: 'utf8', timeout: 90_000 });
    assert.equal(run.signal, null, `killed after 90 s (hangs?): ${run.stderr}`);
    assert.equal(run.status, 0, run.stderr);
    assert.deepEqual(JSON.parse(run.stdout), { threads: 2, note: '', ok: true });
    assert.equal(run.stderr, '');
  });

  test('a threaded core that does not start: the single-threaded core, and threadsNote says why', async () => {
    const wasm = () => readFileSync(new URL('../dist/vesselmesh_core.wasm', import.meta.url));
    const host = {
      loadWasmBinary: wasm,
      singleThreadReason: () => '',
      defaultThreads: () => 2,
      createThreadedCore: async () => {
        throw new Error('no pool');
      },
    };
    const api = await createVesselmeshIn(host, {});
    assert.equal(api.threads, 1);
    assert.equal(api.threadsNote, 'the threaded core did not start (no pool)');
    assert.equal(api.makePhantom({}).ok, true);
  });
});
