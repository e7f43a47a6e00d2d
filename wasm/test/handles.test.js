// Node tests of the handles (wasm/src/handles.js): analyze() and mesh()
// give their result's handle, the calls on an analysis or a mesh take it,
// two kept at once each answer for themselves, the API's newest is the
// default of calls given none and is freed when replaced unless kept, and
// the binding holds no state. Then the same through the worker client,
// with worker.js run in this process behind a stand-in Worker.
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { before, describe, test } from 'node:test';

import { VesselmeshClient } from '../src/client.js';
import { createVesselmesh } from '../src/vesselmesh.js';

const WASM = new URL('../dist/vesselmesh_core.wasm', import.meta.url);
let api;
let tube;
let bifurcation;
before(async () => {
  api = await createVesselmesh({ wasmBinary: readFileSync(WASM) });
  tube = api.makePhantom({ kind: 'tube' }).stl;
  bifurcation = api.makePhantom({ kind: 'bifurcation' }).stl;
});

/** Small meshes of the tube, different for each N. */
const meshTube = (perCircumference) => {
  const m = api.mesh(tube, { perCircumference, layers: 1 });
  assert.ok(m.ok, m.error);
  return m;
};
const same = (a, b) => Buffer.from(a).equals(Buffer.from(b));
/** The smallest bytes report() takes as a picture. */
const PNG = new Uint8Array([0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a]);
const images = [{ title: 'x', alt: 'x', png: PNG }];
/** A point beside the middle of an analyzed tube's axis (between its two
 * openings' centroids), where the cut across it is clean. */
const besideMiddle = (analysis) => {
  const [p, q] = analysis.openings.map((o) => o.centroid);
  return [(p[0] + q[0]) / 2 + 1, (p[1] + q[1]) / 2, (p[2] + q[2]) / 2];
};

describe('mesh handles', () => {
  test('two meshes kept at once: each exports its own bytes, the calls without one the newest', () => {
    // What export() gave while each was the only mesh (its provenance
    // names export's own options: not mesh()'s file).
    const a = meshTube(10);
    assert.equal(typeof a.handle.delete, 'function');
    const aloneA = api.export('msh').file;
    assert.deepEqual(api.keep(a.handle), { ok: true });
    const b = meshTube(12);
    const aloneB = api.export('msh').file;
    assert.ok(!a.handle.isDeleted(), 'kept: a newer mesh does not free it');
    assert.ok(!same(a.file, b.file), 'the two meshes differ');

    const exportA = api.export('msh', { mesh: a.handle });
    const exportB = api.export('msh', { mesh: b.handle });
    assert.ok(exportA.ok && exportB.ok, exportA.error ?? exportB.error);
    assert.ok(same(exportA.file, aloneA), "export A gives A's bytes");
    assert.ok(same(exportB.file, aloneB), "export B gives B's bytes");
    assert.ok(same(api.export('msh').file, aloneB), 'no handle: the newest');
    // mesh()'s file but for the provenance line, which adds export's format.
    const lines = (bytes) => new TextDecoder().decode(bytes).split('\n');
    const [meshed, exported] = [lines(a.file), lines(exportA.file)];
    assert.equal(meshed.length, exported.length);
    const differ = meshed.filter((line, i) => line !== exported[i]);
    assert.equal(differ.length, 1);
    assert.match(differ[0], /^vesselmesh .*options: per_circumference=10 layers=1$/);
    // Another format, with export's options, of the older one.
    const vtuA = api.export('vtu', { mesh: a.handle, outputUnits: 'm' });
    assert.equal(vtuA.fileName, 'mesh.vtu');
    assert.ok(!same(vtuA.file, api.export('vtu', { mesh: b.handle, outputUnits: 'm' }).file));
    // report() of each: the same options, other counts.
    const reportA = new TextDecoder().decode(api.report({ mesh: a.handle, images }).file);
    const reportB = new TextDecoder().decode(api.report({ images }).file);
    assert.match(reportA, /^<!DOCTYPE html>/i);
    assert.notEqual(reportA, reportB);
    assert.deepEqual(api.release(a.handle), { ok: true });
    assert.ok(a.handle.isDeleted());
  });

  test('a newest replaced without keep() is freed; using it is refused, not thrown', () => {
    const a = meshTube(10);
    const b = meshTube(12);
    const aloneB = api.export('msh').file;
    assert.ok(a.handle.isDeleted(), 'a newer mesh freed it');
    const refused = api.export('msh', { mesh: a.handle });
    assert.equal(refused.ok, false);
    assert.equal(refused.kind, 'bad_input');
    assert.match(refused.error, /^export: this mesh was released .*: mesh again$/);
    assert.match(api.report({ mesh: a.handle }).error, /^report: this mesh was released/);
    assert.ok(same(api.export('msh', { mesh: b.handle }).file, aloneB));
  });

  test('release(): frees now; the calls without a handle then have no newest', () => {
    const m = meshTube(10);
    assert.deepEqual(api.release(m.handle), { ok: true });
    assert.ok(m.handle.isDeleted());
    assert.deepEqual(api.release(m.handle), { ok: true }, 'again: nothing');
    assert.deepEqual(api.export('msh'), { ok: false, error: 'nothing to export: mesh a surface first', kind: 'bad_input' });
    assert.deepEqual(api.report(), { ok: false, error: 'no report yet: mesh a surface first', kind: 'bad_input' });
    assert.match(api.keep(m.handle).error, /^keep: this mesh was released/);
    for (const bad of [undefined, null, 7, 'mesh', {}, { kind: 'mesh', id: 1 }]) {
      const r = api.release(bad);
      assert.equal(r.ok, false);
      assert.match(r.error, /^release: give the `handle` of an analyze\(\) or mesh\(\) result of this API/);
      assert.equal(api.keep(bad).ok, false);
    }
    // A handle deleted by its own delete() is refused as released too.
    const n = meshTube(10);
    n.handle.delete();
    assert.match(api.export('msh').error, /^export: this mesh was released/);
  });

  test('a mesh family: the handle is its first member, with the table', () => {
    const family = api.mesh(tube, { perCircumference: 10, layers: 1, family: 2 });
    assert.ok(family.ok, family.error);
    api.keep(family.handle);
    meshTube(10);
    const withTable = new TextDecoder().decode(api.report({ mesh: family.handle, images }).file);
    const without = new TextDecoder().decode(api.report({ images }).file);
    assert.match(withTable, /mesh_1\.msh/);
    assert.doesNotMatch(without, /mesh_1\.msh/);
    // Its export is the first member's mesh alone.
    const first = api.export('msh', { mesh: family.handle });
    assert.ok(first.ok, first.error);
    assert.match(new TextDecoder().decode(first.file.subarray(0, 200)), /^\$MeshFormat/);
    api.release(family.handle);
  });
});

describe('analysis handles', () => {
  test('two analyses kept at once: sizeField, openingNames and cutAt each on its own', () => {
    const t = api.analyze(tube);
    const b = api.analyze(bifurcation);
    assert.ok(t.ok && b.ok);
    assert.ok(t.handle.isDeleted(), 'not kept: freed by the newer analysis');
    const t2 = api.analyze(tube);
    api.keep(t2.handle);
    const b2 = api.analyze(bifurcation);

    const sizeT = api.sizeField({ analysis: t2.handle, perCircumference: 12 });
    const sizeB = api.sizeField({ perCircumference: 12 });
    assert.ok(sizeT.ok && sizeB.ok, sizeT.error ?? sizeB.error);
    assert.deepEqual(sizeT.positions, t2.surface.positions);
    assert.deepEqual(sizeB.positions, b2.surface.positions, 'no handle: the newest');
    // Its radius, kept on the analysis, does not leak into the other's.
    assert.deepEqual(api.sizeField({ analysis: t2.handle, perCircumference: 12 }).radius, sizeT.radius);

    assert.deepEqual(api.openingNames({ analysis: t2.handle }).names, ['inlet', 'outlet_1']);
    assert.deepEqual(api.openingNames({ analysis: b2.handle, inlet: 2 }).names, ['outlet_1', 'inlet', 'outlet_2']);
    assert.equal(api.openingNames().names.length, 3);

    // Halfway along the tube: the cut there, across the tube (not the
    // bifurcation, the newest).
    const mid = besideMiddle(t2.analysis);
    const cut = api.cutAt(mid, { analysis: t2.handle });
    assert.ok(cut.ok, cut.error);
    assert.ok(cut.radius > 0.5 && cut.radius < 1.5, `radius ${cut.radius}`);
    assert.notDeepEqual(api.cutAt(mid), cut);
    api.release(t2.handle);
    assert.match(api.cutAt(mid, { analysis: t2.handle }).error, /^cutAt: this analysis was released .*: analyze the surface again$/);
  });

  test('a handle of the wrong kind, or of another API object, is refused by the option it was given as', async () => {
    const a = api.analyze(tube);
    const m = meshTube(10);
    const wrong = api.export('msh', { mesh: a.handle });
    assert.equal(wrong.ok, false);
    assert.equal(wrong.kind, 'bad_option');
    assert.equal(wrong.option, 'mesh');
    assert.match(wrong.error, /^export: mesh must be the handle of a mesh of this API/);
    assert.equal(api.sizeField({ analysis: m.handle }).option, 'analysis');
    assert.equal(api.openingNames({ analysis: 3 }).option, 'analysis');
    assert.equal(api.report({ mesh: { kind: 'mesh', id: 1 } }).option, 'mesh');
    const other = await createVesselmesh({ wasmBinary: readFileSync(WASM) });
    assert.equal(other.export('msh', { mesh: m.handle }).option, 'mesh');
    assert.equal(other.release(m.handle).ok, false);
  });

  test('a failed job leaves no newest (as before handles); a kept one stays usable', () => {
    const a = api.analyze(tube);
    api.keep(a.handle);
    const bad = api.analyze(new TextEncoder().encode('solid nothing\nendsolid nothing\n'));
    assert.equal(bad.ok, false);
    assert.deepEqual(api.sizeField(), { ok: false, error: 'nothing analyzed yet: analyze a surface first', kind: 'bad_input' });
    assert.deepEqual(api.openingNames({ analysis: a.handle }).names, ['inlet', 'outlet_1']);
    // Not bytes: refused before the job, the newest stays.
    const b = api.analyze(tube);
    assert.equal(api.analyze('not bytes').ok, false);
    assert.ok(!b.handle.isDeleted());
    assert.equal(api.openingNames().names.length, 2);
    api.release(a.handle);
  });
});

// The worker (worker.js) run in this process: its `self` is a stand-in
// whose postMessage answers the client through a stand-in Worker; each
// Worker imports its own instance of the module (as a new worker would).
describe('worker client handles', () => {
  let instances = 0;
  let current = null;
  let failGrowth = false;
  class StandInWorker {
    constructor() {
      this.onmessage = null;
      this.onerror = null;
      this.waiting = [];
      current = this;
      import(`../src/worker.js?instance=${++instances}`).then(() => {
        this.handler = globalThis.self.onmessage;
        for (const data of this.waiting) this.handler({ data });
      });
    }
    postMessage(message) {
      const data = structuredClone(message);
      if (this.handler) this.handler({ data });
      else this.waiting.push(data);
    }
    answer(message, transfer) {
      if (this.terminated) return;
      // A failed memory growth while the core runs (the progress callback
      // is called from inside it).
      if (failGrowth && message.type === 'progress') throw new RangeError('WebAssembly.Memory.grow(): Maximum memory size exceeded');
      const data = structuredClone(message, { transfer });
      setImmediate(() => this.onmessage?.({ data }));
    }
    terminate() {
      this.terminated = true;
    }
  }
  let client;
  before(async () => {
    // The worker's API fetches its wasm next to it: a file here.
    const realFetch = globalThis.fetch;
    globalThis.fetch = async (url) =>
      String(url).startsWith('file:') ? new Response(readFileSync(new URL(url))) : realFetch(url);
    globalThis.self = { postMessage: (message, transfer) => current.answer(message, transfer) };
    client = new VesselmeshClient({ createWorker: () => new StandInWorker() });
    assert.equal(await client.ready, api.version);
  });

  test("mesh A (kept), mesh B: export A gives A's bytes, export B B's; B's replacement frees B", async () => {
    const a = await client.mesh(tube, { perCircumference: 10, layers: 1 });
    assert.ok(a.ok, a.error);
    assert.equal(a.handle.kind, 'mesh');
    assert.equal(typeof a.handle.id, 'number');
    const aloneA = (await client.export('msh')).file;
    assert.deepEqual(await client.keep(a.handle), { ok: true });
    const b = await client.mesh(tube, { perCircumference: 12, layers: 1 });
    assert.ok(b.ok, b.error);
    const aloneB = (await client.export('msh')).file;
    assert.notEqual(b.handle.id, a.handle.id);
    assert.ok(!same(aloneA, aloneB));
    assert.ok(same((await client.export('msh', { mesh: a.handle })).file, aloneA), "export A gives A's bytes");
    assert.ok(same((await client.export('msh', { mesh: b.handle })).file, aloneB), "export B gives B's bytes");
    assert.ok(same((await client.export('msh')).file, aloneB), 'no handle: the newest');

    const wrong = await client.export('msh', { mesh: { kind: 'analysis', id: a.handle.id, worker: a.handle.worker } });
    assert.equal(wrong.option, 'mesh');
    assert.equal((await client.report({ mesh: 'a' })).option, 'mesh');

    const c = await client.mesh(tube, { perCircumference: 10, layers: 1 });
    assert.ok(c.ok);
    assert.match((await client.export('msh', { mesh: b.handle })).error, /^export: this mesh was released/);
    assert.ok(same((await client.export('msh', { mesh: a.handle })).file, aloneA), 'kept: still there');
    assert.deepEqual(await client.release(a.handle), { ok: true });
    assert.deepEqual(await client.release(a.handle), { ok: true }, 'again: nothing');
    assert.match((await client.export('msh', { mesh: a.handle })).error, /^export: this mesh was released/);
    assert.equal((await client.release(7)).ok, false);
  });

  test('analyses by handle; after cancel() the old handles are refused as a restarted worker\'s', async () => {
    const t = await client.analyze(tube);
    await client.keep(t.handle);
    const b = await client.analyze(bifurcation);
    assert.ok(t.ok && b.ok);
    assert.equal(t.handle.kind, 'analysis');
    assert.deepEqual((await client.openingNames({ analysis: t.handle })).names, ['inlet', 'outlet_1']);
    assert.equal((await client.openingNames()).names.length, 3);
    const size = await client.sizeField({ analysis: t.handle, perCircumference: 12 });
    assert.deepEqual(size.positions, t.surface.positions);
    const mid = besideMiddle(t.analysis);
    assert.deepEqual(await client.cutAt(mid, { analysis: t.handle }), api.cutAt(mid, { analysis: api.analyze(tube).handle }));

    client.cancel();
    await client.ready;
    const gone = await client.sizeField({ analysis: t.handle });
    assert.match(gone.error, /^sizeField: this analysis was made by a mesher worker since restarted \(cancel\(\)\)/);
    assert.deepEqual(await client.openingNames(), { ok: false, error: 'nothing analyzed yet: analyze a surface first', kind: 'bad_input' });
    assert.deepEqual(await client.release(t.handle), { ok: true }, 'nothing to free');
    assert.match((await client.keep(t.handle)).error, /restarted/);
  });

  test('a worker whose module runs out of memory is replaced: the failure says so, the next job runs', async () => {
    const a = await client.mesh(tube, { perCircumference: 10, layers: 1 });
    assert.ok(a.ok, a.error);
    const before = instances;
    let restarted = null;
    client.onRestart = (failure) => (restarted = failure);
    failGrowth = true;
    const m = await client.mesh(tube, { perCircumference: 12, layers: 1 });
    failGrowth = false;
    assert.equal(m.ok, false);
    assert.equal(m.kind, 'out_of_memory');
    assert.match(m.error, /^out of memory while meshing: the mesher's memory \(\d+ MB in use, at most 4096 MB\) ran out; try a coarser size \(a larger size or a smaller perCircumference\); the mesher was restarted$/);
    assert.equal(restarted?.kind, 'out_of_memory');
    assert.equal(instances, before + 1, 'a new worker');
    await client.ready;
    assert.match((await client.export('msh', { mesh: a.handle })).error, /was made by a mesher worker since restarted/);
    const again = await client.mesh(tube, { perCircumference: 12, layers: 1 });
    assert.ok(again.ok, again.error);
    client.onRestart = null;
  });
});
