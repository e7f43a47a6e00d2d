// Node tests of the built module: a mesh-independence family (mesh() with
// `family`) and the methods report (report()).
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { before, describe, test } from 'node:test';
import { crc32, deflateSync } from 'node:zlib';

import { createVesselmesh } from '../src/vesselmesh.js';
import { unzip } from './unzip.js';

let api, stl;
before(async () => {
  const wasmBinary = readFileSync(new URL('../dist/vesselmesh_core.wasm', import.meta.url));
  api = await createVesselmesh({ wasmBinary });
  const phantom = api.makePhantom({ kind: 'bifurcation', voxel: 0.1, noise: 0.3 });
  assert.ok(phantom.ok, phantom.error);
  stl = phantom.stl;
});

const text = (bytes) => new TextDecoder().decode(bytes);

/** A 1 x 1 grey PNG file. */
function onePixelPng() {
  const chunk = (type, data) => {
    const body = Buffer.concat([Buffer.from(type, 'latin1'), data]);
    const out = Buffer.alloc(12 + data.length);
    out.writeUInt32BE(data.length, 0);
    body.copy(out, 4);
    out.writeUInt32BE(crc32(body), 8 + data.length);
    return out;
  };
  const ihdr = Buffer.from([0, 0, 0, 1, 0, 0, 0, 1, 8, 2, 0, 0, 0]);
  const idat = deflateSync(Buffer.from([0, 128, 128, 128]));
  const signature = Buffer.from([137, 80, 78, 71, 13, 10, 26, 10]);
  return new Uint8Array(Buffer.concat([signature, chunk('IHDR', ihdr), chunk('IDAT', idat), chunk('IEND', Buffer.alloc(0))]));
}

/** The physical group names of an MSH 4.1 text. */
const physicalNames = (msh) => {
  const block = msh.split('$PhysicalNames\n')[1].split('$EndPhysicalNames')[0].trim().split('\n');
  return block.slice(1).map((line) => line.split('"')[1]);
};

describe('mesh family', () => {
  test('three meshes of one surface, refined by the ratio, in one zip with the table', () => {
    const stages = [];
    const r = api.mesh(stl, {
      perCircumference: 10,
      layers: 2,
      family: 3,
      ratio: 1.4,
      onProgress: (f, stage) => {
        stages.push(stage);
        return true;
      },
    });
    assert.ok(r.ok, r.error);
    assert.equal(r.fileName, 'mesh-family.zip');
    const files = unzip(r.file);
    assert.deepEqual(Object.keys(files).sort(), ['family.csv', 'family.json', 'mesh_0.msh', 'mesh_1.msh', 'mesh_2.msh']);
    const names = ['mesh_0.msh', 'mesh_1.msh', 'mesh_2.msh'].map((f) => physicalNames(files[f]));
    assert.deepEqual(names[1], names[0]);
    assert.deepEqual(names[2], names[0]);
    assert.ok(names[0].includes('inlet') && names[0].includes('lumen'), names[0].join());
    assert.match(files['mesh_2.msh'], /family_member=2/);
    // The table: in the result, the zip's JSON and CSV alike.
    assert.equal(r.family.members, 3);
    assert.equal(r.family.layers, 'refine');
    assert.deepEqual(JSON.parse(files['family.json']), r.family);
    assert.equal(files['family.csv'], r.familyCsv);
    assert.equal(r.familyCsv.trim().split('\n').length, 4);
    const rows = r.family.rows;
    assert.deepEqual(
      rows.map((row) => row.file),
      ['mesh_0.msh', 'mesh_1.msh', 'mesh_2.msh'],
    );
    assert.deepEqual(
      rows.map((row) => row.layers),
      [2, 3, 4],
    );
    for (const row of rows.slice(1)) assert.ok(Math.abs(row.ratio - 1.4) < 0.14, `ratio ${row.ratio}`);
    for (const row of rows) assert.ok(row.core_gamma_t_min >= 0.25, `core quality ${row.core_gamma_t_min}`);
    assert.ok(rows[2].cells > 5 * rows[0].cells);
    // The result shown is the first member, the mesh as asked.
    assert.equal(r.volume.tets.length / 4, rows[0].tetrahedra);
    assert.equal(r.report.output.volume?.tetrahedra ?? rows[0].tetrahedra, rows[0].tetrahedra);
    // Progress says which member runs.
    assert.ok(stages.some((s) => s.startsWith('member 3 of 3')));
  });

  test('bad family options are refused by name', () => {
    for (const [options, message] of [
      [{ family: 9 }, /family needs a number of meshes from 1 \(one mesh\) to 6/],
      [{ family: 2, ratio: 5 }, /ratio needs a refinement ratio from 1.1 to 2/],
      [{ family: 2, familyLayers: 'more' }, /familyLayers needs refine or fixed/],
      [{ family: 2, surfaceOnly: true }, /family makes volume meshes/],
    ]) {
      const r = api.mesh(stl, { perCircumference: 8, ...options });
      assert.equal(r.ok, false);
      assert.match(r.error, message);
    }
  });
});

describe('methods report', () => {
  test('the report of a mesh: offline HTML with the core rendered views, or the given ones', () => {
    const m = api.mesh(stl, { perCircumference: 10, layers: 2 });
    assert.ok(m.ok, m.error);
    const r = api.report({ inputName: 'bif<1>.stl' });
    assert.ok(r.ok, r.error);
    assert.equal(r.fileName, 'vesselmesh-report.html');
    const html = text(r.file);
    assert.match(html, /^<!DOCTYPE html>|^<!doctype html>/i);
    assert.match(html, /<html lang="en"/);
    assert.doesNotMatch(html, /<script|https?:\/\//);
    assert.ok(html.includes('bif&lt;1&gt;.stl'));
    assert.equal((html.match(/data:image\/png;base64,/g) ?? []).length, 3);
    for (const group of ['wall', 'inlet', 'outlet_1', 'outlet_2', 'lumen']) assert.ok(html.includes(group), group);
    const tets = (m.volume.tets.length / 4).toLocaleString('en-US');
    assert.ok(html.includes(tets), `the tetrahedra count ${tets}`);
    // The page's own pictures instead.
    const given = api.report({ images: [{ title: 'Wall', alt: 'the wall', png: onePixelPng() }] });
    assert.ok(given.ok, given.error);
    assert.equal((text(given.file).match(/data:image\/png;base64,/g) ?? []).length, 1);
    const bad = api.report({ images: [{ title: 'x', alt: 'x', png: new Uint8Array([1, 2, 3]) }] });
    assert.equal(bad.ok, false);
    assert.match(bad.error, /image 1 \('x', 3 bytes\) is not a PNG file: give PNG bytes/);
  });

  test('the report after a family has its table', () => {
    const m = api.mesh(stl, { perCircumference: 10, layers: 1, family: 2 });
    assert.ok(m.ok, m.error);
    const html = text(api.report().file);
    assert.ok(html.includes('mesh_1.msh'));
  });
});
