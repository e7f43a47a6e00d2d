// Node tests of sizeField(): the size field of the last analyzed surface
// before meshing, through the built WebAssembly module (wasm/dist must be
// built: scripts/setup.sh).
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { before, describe, test } from 'node:test';

import { transferables } from '../src/transfer.js';
import { createVesselmesh } from '../src/vesselmesh.js';

let api;
let analyzed;
before(async () => {
  const wasmBinary = readFileSync(new URL('../dist/vesselmesh_core.wasm', import.meta.url));
  api = await createVesselmesh({ wasmBinary });
  const { stl } = api.makePhantom({ kind: 'bifurcation', voxel: 0.08, noise: 0.3 });
  analyzed = api.analyze(stl);
  assert.ok(analyzed.ok, analyzed.error);
});

const median = (values) => [...values].sort((a, b) => a - b)[Math.floor(values.length / 2)];

describe('sizeField', () => {
  test('the analyzed surface with R and h = 2 pi R / N at each vertex', () => {
    const f = api.sizeField({ perCircumference: 16, gradation: 0 });
    assert.ok(f.ok, f.error);
    const { positions, triangles } = analyzed.surface;
    assert.deepEqual(f.positions, positions);
    assert.deepEqual(f.triangles, triangles);
    assert.ok(f.radius instanceof Float32Array && f.size instanceof Float32Array);
    assert.equal(f.radius.length, positions.length / 3);
    assert.equal(f.size.length, positions.length / 3);
    assert.equal(f.unit, analyzed.analysis.units.unit);
    for (let v = 0; v < f.size.length; v++) {
      const want = (2 * Math.PI * f.radius[v]) / 16;
      assert.ok(Math.abs(f.size[v] - want) <= 1e-6 * want, `vertex ${v}: ${f.size[v]} vs ${want}`);
    }
    // Near each opening (within one and a half of its radii of its
    // centroid) R is the opening's radius, within 15%.
    for (const o of analyzed.analysis.openings) {
      const near = [];
      for (let v = 0; v < f.radius.length; v++) {
        const d = Math.hypot(
          positions[3 * v] - o.centroid[0],
          positions[3 * v + 1] - o.centroid[1],
          positions[3 * v + 2] - o.centroid[2],
        );
        if (d < 1.5 * o.radius) near.push(f.radius[v]);
      }
      assert.ok(near.length > 20);
      assert.ok(Math.abs(median(near) - o.radius) < 0.15 * o.radius, `${median(near)} vs ${o.radius}`);
    }
    // Its arrays cross from the worker moved, not copied.
    const buffers = transferables(f);
    for (const key of ['positions', 'triangles', 'radius', 'size']) assert.ok(buffers.includes(f[key].buffer));
  });

  test('a refinement sphere bounds h inside it; sizeMax above', () => {
    const c = analyzed.analysis.openings[0].centroid;
    const f = api.sizeField({ refine: [[...c, 1.5, 0.03]], sizeMax: 0.25 });
    assert.ok(f.ok, f.error);
    let inside = 0;
    for (let v = 0; v < f.size.length; v++) {
      const p = f.positions.subarray(3 * v, 3 * v + 3);
      if (Math.hypot(p[0] - c[0], p[1] - c[1], p[2] - c[2]) <= 1.5) {
        inside++;
        assert.ok(f.size[v] <= 0.03 * (1 + 1e-6), `${f.size[v]}`);
      }
      assert.ok(f.size[v] <= 0.25 * (1 + 1e-6));
    }
    assert.ok(inside > 10);
    assert.ok(Math.abs(Math.min(...f.size) - 0.03) < 1e-6);
  });

  test('refuses what mesh() refuses, by the JS names', () => {
    const bad = api.sizeField({ perCircumference: 2 });
    assert.equal(bad.ok, false);
    assert.equal(bad.option, 'perCircumference');
    const tiny = api.sizeField({ refine: [0, 0, 0, 1, 1e-9] });
    assert.equal(tiny.option, 'refine');
    assert.match(tiny.error, /below 1e-4 of the model's size/);
    assert.match(api.sizeField({ bogus: 1 }).error, /unknown option 'bogus'/);
  });
});
