// The npm package as a user gets it: packed, installed into a fresh project,
// then used there: the JS API in Node (the wasm found without
// configuration), its TypeScript declarations checked by tsc on a typed
// consumer file (and a wrong option refused), and a Vite app bundling the
// API, the worker client and the element (e2e/element.spec.js runs it).
import assert from 'node:assert/strict';
import { execFileSync, spawnSync } from 'node:child_process';
import { existsSync, readdirSync, readFileSync, writeFileSync } from 'node:fs';
import { availableParallelism } from 'node:os';
import { join } from 'node:path';
import { after, before, describe, test } from 'node:test';

import { buildViteApp, installedConsumer, REPO } from './consumer.js';

const built = existsSync(join(REPO, 'wasm/dist/vesselmesh_core.wasm')) && existsSync(join(REPO, 'dist/element/vessel-mesher.js'));

const NODE_CONSUMER = `import { createVesselmesh } from 'vesselmesh';
const api = await createVesselmesh();
const sample = api.makePhantom({ kind: 'bifurcation', voxel: 0.08, noise: 0.3 });
const result = api.mesh(sample.stl, { perCircumference: 10 });
if (!result.ok) throw new Error(result.error);
const head = new TextDecoder().decode(result.msh.subarray(0, 20));
console.log(JSON.stringify({ version: api.version, threads: api.threads, threadsNote: api.threadsNote, tets: result.volume.tets.length / 4, head }));
`;

const TYPED_CONSUMER = `import { createVesselmesh, VesselmeshClient, type MeshOptions, type MeshResult } from 'vesselmesh';
import { VesselMesher } from 'vesselmesh/element';

export async function meshIt(bytes: Uint8Array): Promise<number> {
  const api = await createVesselmesh();
  const options: MeshOptions = { perCircumference: 12, layers: 3, format: 'vtu', mshVersion: '2.2' };
  const result: MeshResult = api.mesh(bytes, options);
  if (!result.ok) throw new Error(result.error + (result.option ?? ''));
  const exported = api.export('msh', { mshVersion: '4.1', mesh: result.handle });
  api.release(result.handle);
  return result.file.length + (exported.ok ? exported.file.length : 0) + api.optionTable.length;
}

export async function inBrowser(bytes: Uint8Array): Promise<string> {
  const client = new VesselmeshClient();
  const version: string = await client.ready;
  const analyzed = await client.analyze(bytes, { onProgress: (fraction: number, stage: string) => void [fraction, stage] });
  if (analyzed.ok) void (await client.sizeField({ analysis: analyzed.handle, perCircumference: 12 })).ok;
  client.cancel();
  const el = document.createElement('vessel-mesher');
  const typed: VesselMesher = el;
  el.addEventListener('vm-progress', (e) => void e.detail.fraction.toFixed(2));
  el.addEventListener('vm-error', (e) => void e.detail.message.length);
  await typed.load(bytes);
  const meshed = await typed.mesh({ perCircumference: 8 });
  const blob: Blob = await typed.export('stl');
  return version + String(meshed.ok) + blob.size;
}
`;

const WRONG_CONSUMER = `import { createVesselmesh } from 'vesselmesh';
const api = await createVesselmesh();
api.mesh(new Uint8Array(0), { perCircumference: 'twelve' });
`;

const TSCONFIG = {
  compilerOptions: {
    target: 'es2022',
    module: 'nodenext',
    moduleResolution: 'nodenext',
    lib: ['es2022', 'dom'],
    strict: true,
    noEmit: true,
    skipLibCheck: false,
    types: [],
  },
};

describe('npm package', () => {
  let consumer;
  before(() => {
    assert.ok(built, 'the wasm (wasm/dist/) and the element (dist/element/, npm run build:web) are built');
    consumer = installedConsumer();
  });
  after(() => consumer?.cleanup());

  test('the tarball holds the API, its types, the wasm and the element, and no sources beyond them', () => {
    const files = execFileSync('tar', ['-tzf', consumer.tarball], { encoding: 'utf8' }).split('\n').filter(Boolean);
    for (const f of ['wasm/src/index.js', 'wasm/src/node.js', 'wasm/src/threaded-core.js', 'wasm/src/node-threads.js', 'wasm/src/node-pthread.js', 'wasm/src/vesselmesh.d.ts', 'wasm/src/element.d.ts', 'wasm/dist/vesselmesh_core.wasm', 'wasm/dist/vesselmesh_core_mt.mjs', 'wasm/dist/vesselmesh_core_mt.wasm', 'wasm/dist/vesselmesh_core_mt.worker.js', 'dist/element/vessel-mesher.js']) {
      assert.ok(files.includes(`package/${f}`), `${f} is in the tarball`);
    }
    assert.ok(files.some((f) => /^package\/dist\/element\/assets\/worker-.*\.js$/.test(f)));
    // The README (the front door) and the pages it links to.
    for (const f of ['README.md', 'docs/cli.md', 'docs/options.md', 'docs/javascript.md', 'docs/element.md']) {
      assert.ok(files.includes(`package/${f}`), `${f} is in the tarball`);
    }
    assert.ok(!files.some((f) => /^package\/(core|cli|web|e2e|tests)\//.test(f)));
    const pkg = JSON.parse(readFileSync(join(consumer.pkg, 'package.json'), 'utf8'));
    assert.equal(pkg.private, undefined);
    assert.deepEqual(pkg.dependencies ?? {}, {});
  });

  test('Node: import { createVesselmesh } from "vesselmesh" meshes the sample with no configuration, on all cores', () => {
    writeFileSync(join(consumer.dir, 'mesh.mjs'), NODE_CONSUMER);
    const out = JSON.parse(execFileSync(process.execPath, ['mesh.mjs'], { cwd: consumer.dir, encoding: 'utf8', timeout: 120_000 }));
    assert.match(out.version, /\d+\.\d+/);
    const cores = availableParallelism();
    assert.equal(out.threads, cores < 2 ? 1 : Math.min(cores, 8), out.threadsNote);
    assert.ok(out.tets > 1000, `${out.tets} tetrahedra`);
    assert.equal(out.head, '$MeshFormat\n4.1 0 8\n');
  });

  test('tsc checks a typed consumer against the declarations, and refuses a wrong option type', () => {
    const tsc = join(REPO, 'node_modules/typescript/bin/tsc');
    writeFileSync(join(consumer.dir, 'tsconfig.json'), JSON.stringify({ ...TSCONFIG, files: ['consumer.ts'] }));
    writeFileSync(join(consumer.dir, 'consumer.ts'), TYPED_CONSUMER);
    const good = spawnSync(process.execPath, [tsc, '-p', 'tsconfig.json'], { cwd: consumer.dir, encoding: 'utf8' });
    assert.equal(good.status, 0, good.stdout + good.stderr);
    writeFileSync(join(consumer.dir, 'tsconfig.wrong.json'), JSON.stringify({ ...TSCONFIG, files: ['wrong.ts'] }));
    writeFileSync(join(consumer.dir, 'wrong.ts'), WRONG_CONSUMER);
    const wrong = spawnSync(process.execPath, [tsc, '-p', 'tsconfig.wrong.json'], { cwd: consumer.dir, encoding: 'utf8' });
    assert.notEqual(wrong.status, 0);
    assert.match(wrong.stdout + wrong.stderr, /perCircumference|not assignable/);
  });

  test('a Vite app bundles the API, the worker client and the element, the wasm and worker as files', () => {
    const dist = buildViteApp(consumer);
    const assets = readdirSync(join(dist, 'assets'));
    assert.ok(assets.some((f) => f.endsWith('.wasm')), assets.join(' '));
    assert.ok(assets.filter((f) => /^worker-.*\.js$/.test(f)).length >= 1, assets.join(' '));
  });
});
