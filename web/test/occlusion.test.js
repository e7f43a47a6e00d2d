// Node tests of the hidden-behind test of the view's labels
// (web/src/occlusion.js): against a brute-force test of every triangle, on
// a sphere and an open tube, and the point's own surface not counted.
import assert from 'node:assert/strict';
import { describe, test } from 'node:test';

import { Occluder } from '../src/occlusion.js';

/** A UV sphere of radius r at c: {positions, triangles}. */
function sphere(r = 1, c = [0, 0, 0], n = 24, m = 12) {
  const positions = [];
  const triangles = [];
  for (let j = 0; j <= m; j++) {
    for (let i = 0; i < n; i++) {
      const [t, p] = [(Math.PI * j) / m, (2 * Math.PI * i) / n];
      positions.push(c[0] + r * Math.sin(t) * Math.cos(p), c[1] + r * Math.sin(t) * Math.sin(p), c[2] + r * Math.cos(t));
    }
  }
  for (let j = 0; j < m; j++) {
    for (let i = 0; i < n; i++) {
      const [a, b] = [j * n + i, j * n + ((i + 1) % n)];
      triangles.push(a, b, b + n, a, b + n, a + n);
    }
  }
  return { positions: new Float32Array(positions), triangles: new Uint32Array(triangles) };
}

/** Whether the segment from-to meets any triangle before its last 1e-4 (brute force). */
function bruteBlocked({ positions: P, triangles: T }, from, to) {
  const d = to.map((x, a) => x - from[a]);
  const sub = (u, v) => u.map((x, a) => x - v[a]);
  const cross = (u, v) => [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]];
  const dot = (u, v) => u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
  const p = (v) => [P[3 * v], P[3 * v + 1], P[3 * v + 2]];
  for (let t = 0; t < T.length; t += 3) {
    const [a, b, c] = [p(T[t]), p(T[t + 1]), p(T[t + 2])];
    const [e1, e2] = [sub(b, a), sub(c, a)];
    const q = cross(d, e2);
    const det = dot(e1, q);
    if (det === 0) continue;
    const s = sub(from, a);
    const u = dot(s, q) / det;
    const r = cross(s, e1);
    const v = dot(d, r) / det;
    const at = dot(e2, r) / det;
    if (u >= 0 && v >= 0 && u + v <= 1 && at >= 0 && at < 1 - 1e-4) return true;
  }
  return false;
}

describe('hidden behind the surface', () => {
  test('a point behind a sphere is hidden, one in front or beside it is not', () => {
    const s = sphere();
    const o = new Occluder(s.positions, s.triangles);
    const camera = [0, 0, 10];
    assert.equal(o.blocked(camera, [0, 0, -2]), true);
    assert.equal(o.blocked(camera, [0, 0, 2]), false);
    assert.equal(o.blocked(camera, [3, 0, -2]), false);
    // The point's own surface (the near pole) does not hide it; the far pole is hidden.
    assert.equal(o.blocked(camera, [0, 0, 1]), false);
    assert.equal(o.blocked(camera, [0, 0, -1]), true);
    // From inside the box (the camera zoomed in), too.
    assert.equal(o.blocked([0.5, 0.5, 1.5], [0, 0, -2]), true);
  });

  test('the grid agrees with every triangle tried, from random cameras to random points', () => {
    const s = sphere(1.3, [0.2, -0.1, 0.4], 40, 20);
    const o = new Occluder(s.positions, s.triangles);
    let seed = 7;
    const random = () => ((seed = (seed * 1103515245 + 12345) % 2 ** 31) / 2 ** 31) * 2 - 1;
    let hidden = 0;
    for (let i = 0; i < 400; i++) {
      const camera = [6 * random(), 6 * random(), 6 * random()];
      const point = [2 * random(), 2 * random(), 2 * random()];
      const expected = bruteBlocked(s, camera, point);
      assert.equal(o.blocked(camera, point), expected, `camera ${camera} point ${point}`);
      hidden += expected;
    }
    assert.ok(hidden > 50 && hidden < 350, `both cases tried (${hidden} hidden)`);
  });

  test('a flat surface (one triangle) has a grid too', () => {
    const o = new Occluder(new Float32Array([0, 0, 0, 1, 0, 0, 0, 1, 0]), new Uint32Array([0, 1, 2]));
    assert.equal(o.blocked([0.2, 0.2, 1], [0.2, 0.2, -1]), true);
    assert.equal(o.blocked([0.8, 0.8, 1], [0.8, 0.8, -1]), false);
  });
});
