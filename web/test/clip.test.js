// Node tests of the clipped volume view (web/src/clip.js) on a generated
// tetrahedral grid (its adjacency from the page's old face matcher,
// face-matcher.js) and on the volume the WebAssembly module makes of the
// bifurcation phantom, whose adjacency (volume.across) the core gives
// (wasm/dist must be built).
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { before, describe, test } from 'node:test';

import { createVesselmesh } from '../../wasm/src/vesselmesh.js';
import { ClipBuffers, clipBoundary, tetCentroids, UNKNOWN_TAG } from '../src/clip.js';
import { withPrismsSplit } from '../src/prisms.js';
import { faceAdjacency } from './face-matcher.js';
import { facesByVertices, kuhnGrid } from './kuhn-grid.js';

const TAG_COLORS = new Uint8Array([10, 0, 0, 20, 0, 0, 30, 0, 0, 40, 0, 0, 50, 0, 0, 60, 0, 0, 70, 0, 0]);
const CUT = [1, 2, 3];

function clip(mesh, across, axis, value, extra = {}) {
  const centroid = tetCentroids(mesh.positions, mesh.tets, axis);
  const out = new ClipBuffers(16);
  return clipBoundary(mesh, across, centroid, { value, tagColors: TAG_COLORS, cutColor: CUT, ...extra }, out);
}

/** Brute-force checks of a clipped boundary: closed and oriented (every
 * directed edge has its reverse as often), and encloses the kept tets. */
function checkClosed(mesh, out, keep) {
  const P = out.positions;
  const edges = new Map();
  const key = (a, b) => `${a[0]},${a[1]},${a[2]}|${b[0]},${b[1]},${b[2]}`;
  let enclosed = 0;
  for (let t = 0; t < out.count; t++) {
    const c = [0, 1, 2].map((k) => Array.from(P.subarray(9 * t + 3 * k, 9 * t + 3 * k + 3)));
    for (let k = 0; k < 3; k++) {
      const e = key(c[k], c[(k + 1) % 3]);
      edges.set(e, (edges.get(e) ?? 0) + 1);
    }
    const [a, b, d] = c;
    enclosed += (a[0] * (b[1] * d[2] - b[2] * d[1]) - a[1] * (b[0] * d[2] - b[2] * d[0]) + a[2] * (b[0] * d[1] - b[1] * d[0])) / 6;
  }
  for (const [e, n] of edges) {
    const [a, b] = e.split('|');
    assert.equal(edges.get(`${b}|${a}`), n, `edge ${e}`);
  }
  let volume = 0;
  const { positions: X, tets: T } = mesh;
  for (let t = 0; t < T.length / 4; t++) {
    if (!keep(t)) continue;
    const [a, b, c, d] = [0, 1, 2, 3].map((k) => [0, 1, 2].map((x) => X[3 * T[4 * t + k] + x]));
    const u = b.map((x, i) => x - a[i]);
    const v = c.map((x, i) => x - a[i]);
    const w = d.map((x, i) => x - a[i]);
    volume += (w[0] * (u[1] * v[2] - u[2] * v[1]) + w[1] * (u[2] * v[0] - u[0] * v[2]) + w[2] * (u[0] * v[1] - u[1] * v[0])) / 6;
  }
  assert.ok(Math.abs(enclosed - volume) <= 1e-6 * Math.max(1, volume), `enclosed ${enclosed}, tets ${volume}`);
}

describe('clip: a 4x4x4 Kuhn grid', () => {
  const n = 4;
  const mesh = kuhnGrid(n);
  const across = faceAdjacency(mesh.tets, mesh.vertexCount, mesh.triangles, mesh.triangleTag);

  test('adjacency: symmetric, boundary faces tagged by side', () => {
    const nt = mesh.tets.length / 4;
    assert.equal(nt, 6 * n ** 3);
    let boundary = 0;
    const perTag = new Array(6).fill(0);
    for (let f = 0; f < across.length; f++) {
      const u = across[f];
      if (u < 0) {
        boundary++;
        perTag[-1 - u]++;
        continue;
      }
      const t = f >> 2;
      assert.ok(u !== t);
      let back = 0;
      for (let g = 0; g < 4; g++) if (across[4 * u + g] === t) back++;
      assert.equal(back, 1, `face ${f}`);
    }
    assert.equal(boundary, 12 * n * n);
    assert.deepEqual(perTag, new Array(6).fill(2 * n * n));
    // Without boundary triangles the tags are unknown.
    const bare = faceAdjacency(mesh.tets, mesh.vertexCount);
    assert.ok(bare.every((u, f) => (u >= 0 ? u === across[f] : u === -1 - UNKNOWN_TAG)));
  });

  test('keeping everything draws the boundary; keeping nothing draws nothing', () => {
    const all = clip(mesh, across, 2, n + 1);
    assert.equal(all.count, 12 * n * n);
    assert.equal(all.cut, 0);
    checkClosed(mesh, all, () => true);
    assert.equal(clip(mesh, across, 2, -1).count, 0);
    assert.equal(clip(mesh, across, 2, -1, { flip: true }).count, 12 * n * n);
  });

  test('every cut is closed, oriented outward and encloses the kept tets', () => {
    for (const axis of [0, 1, 2]) {
      const centroid = tetCentroids(mesh.positions, mesh.tets, axis);
      for (const value of [0.3, 1.5, 2, 2.6, 3.7]) {
        for (const flip of [false, true]) {
          const out = clip(mesh, across, axis, value, { flip });
          assert.ok(out.cut > 0);
          checkClosed(mesh, out, (t) => (flip ? centroid[t] >= value : centroid[t] <= value));
        }
      }
    }
  });

  test('colors: tags and cut faces, or one color per tet', () => {
    const out = clip(mesh, across, 0, 2);
    const seen = new Set();
    for (let t = 0; t < out.count; t++) seen.add(out.colors[9 * t] + 256 * out.colors[9 * t + 2]);
    // Sides x = 0 (tag 0), y, z (tags 2-5) and the cut; not x = n (tag 1).
    assert.deepEqual([...seen].sort((a, b) => a - b), [10, 30, 40, 50, 60, 1 + 256 * 3]);
    const tetColors = new Uint8Array(mesh.tets.length / 4 * 3).fill(99);
    const q = clip(mesh, across, 0, 2, { tetColors });
    assert.equal(q.count, out.count);
    assert.ok(q.colors.subarray(0, 9 * q.count).every((c) => c === 99));
  });

  test('cut faces: the color of their tet, and counted per part', () => {
    const nt = mesh.tets.length / 4;
    const tetPart = Uint8Array.from({ length: nt }, (_, t) => t % 3);
    const cutTetColors = Uint8Array.from({ length: 3 * nt }, (_, i) => 100 + tetPart[Math.floor(i / 3)]);
    const out = clip(mesh, across, 0, 2, { cutTetColors, tetPart });
    const centroid = tetCentroids(mesh.positions, mesh.tets, 0);
    const expected = [0, 0, 0];
    for (let t = 0; t < nt; t++) {
      if (!(centroid[t] <= 2)) continue;
      for (let f = 0; f < 4; f++) {
        const u = across[4 * t + f];
        if (u >= 0 && !(centroid[u] <= 2)) expected[tetPart[t]]++;
      }
    }
    assert.deepEqual(out.cutByPart, expected);
    assert.equal(expected[0] + expected[1] + expected[2], out.cut);
    const colored = [0, 0, 0];
    for (let t = 0; t < out.count; t++) if (out.colors[9 * t] >= 100) colored[out.colors[9 * t] - 100]++;
    assert.deepEqual(colored, expected); // the boundary keeps its tag colors
    assert.deepEqual(clip(mesh, across, 0, 2).cutByPart, [0, 0, 0]); // no tetPart: not counted
  });

  test('buffers grow and are reused', () => {
    const centroid = tetCentroids(mesh.positions, mesh.tets, 1);
    const out = new ClipBuffers(1);
    const options = { value: 2, tagColors: TAG_COLORS, cutColor: CUT };
    clipBoundary(mesh, across, centroid, options, out);
    assert.ok(out.grown && out.capacity >= out.count);
    const { positions } = out;
    const count = out.count;
    clipBoundary(mesh, across, centroid, { ...options, value: 1 }, out);
    assert.ok(!out.grown && out.positions === positions && out.count < count);
  });
});

describe('clip: the volume of the bifurcation phantom', () => {
  let volume; // with the boundary layer (the default)
  let walled; // and the vessel wall: `wall` triangles between two tets
  let prismatic; // prisms kept, as the page shows them (withPrismsSplit)
  before(async () => {
    const wasmBinary = readFileSync(new URL('../../wasm/dist/vesselmesh_core.wasm', import.meta.url));
    const api = await createVesselmesh({ wasmBinary });
    const stl = api.makePhantom({ noise: 0.3, kind: 'bifurcation', voxel: 0.12 }).stl;
    const r = api.mesh(stl, { size: 0.3 });
    assert.equal(r.ok, true, r.error);
    volume = r.volume;
    const w = api.mesh(stl, { size: 0.3, wallThickness: 0.1 });
    assert.equal(w.ok, true, w.error);
    walled = w.volume;
    const p = api.mesh(stl, { size: 0.3, prisms: true, wallThickness: 0.1 });
    assert.equal(p.ok, true, p.error);
    assert.ok(p.volume.prisms.length > 0);
    prismatic = withPrismsSplit(p.volume);
  });

  test("the core's adjacency equals the page's old face matcher's", () => {
    for (const v of [volume, walled, prismatic]) {
      const { tets, triangles, triangleTag, positions, across } = v;
      assert.ok(across instanceof Int32Array);
      assert.equal(across.length, tets.length);
      assert.deepEqual(across, faceAdjacency(tets, positions.length / 3, triangles, triangleTag));
    }
  });

  test('adjacency agrees with a brute-force face map; boundary = tagged triangles', () => {
    const { tets, triangles, triangleTag, across } = volume;
    const faces = facesByVertices(tets);
    const tags = new Map();
    triangleTag.forEach((g, b) => tags.set(Array.from(triangles.subarray(3 * b, 3 * b + 3)).sort((x, y) => x - y).join(), g));
    for (const [key, list] of faces) {
      if (list.length === 2) {
        assert.equal(across[list[0]], list[1] >> 2);
        assert.equal(across[list[1]], list[0] >> 2);
      } else {
        assert.equal(list.length, 1);
        assert.equal(across[list[0]], -1 - tags.get(key), key);
      }
    }
  });

  test('clips along each axis are closed and enclose the kept tets', () => {
    const { tets, triangleTag, positions, across } = volume;
    const all = clip(volume, across, 0, Infinity);
    assert.equal(all.count, triangleTag.length);
    for (const axis of [0, 1, 2]) {
      const centroid = tetCentroids(positions, tets, axis);
      const sorted = Float32Array.from(centroid).sort();
      const value = sorted[sorted.length >> 1];
      const out = clip(volume, across, axis, value);
      assert.ok(out.cut > 0 && out.count > out.cut);
      checkClosed(volume, out, (t) => centroid[t] <= value);
    }
  });

  test('with the vessel wall the interface is inside: the outer boundary is drawn, cuts are closed', () => {
    const { tets, triangleTag, positions, surfaceNames, tetPart, across } = walled;
    const wall = surfaceNames.indexOf('wall');
    const interfaces = triangleTag.filter((g) => g === wall).length;
    assert.ok(interfaces > 0);
    const all = clip(walled, across, 0, Infinity, { tetPart });
    assert.equal(all.count, triangleTag.length - interfaces);
    assert.equal(all.cut, 0);
    for (const axis of [0, 1, 2]) {
      const centroid = tetCentroids(positions, tets, axis);
      const sorted = Float32Array.from(centroid).sort();
      const value = sorted[sorted.length >> 1];
      const out = clip(walled, across, axis, value, { tetPart });
      assert.ok(out.cutByPart.every((n) => n > 0), `axis ${axis}: ${out.cutByPart}`);
      checkClosed(walled, out, (t) => centroid[t] <= value);
    }
  });
});
