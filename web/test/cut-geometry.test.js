// Node tests of the Prepare step's cut geometry (web/src/cut-geometry.js).
import assert from 'node:assert/strict';
import { describe, test } from 'node:test';

import { alongVessel, cutPlane, keepSide, normalize, tiltAxes, tilted } from '../src/cut-geometry.js';

const dot = (a, b) => a.reduce((s, x, i) => s + x * b[i], 0);
const close = (a, b, tol = 1e-12) => a.every((x, i) => Math.abs(x - b[i]) <= tol);

describe('cut geometry', () => {
  test('the tilt axes are unit, perpendicular to the normal and to each other', () => {
    for (const n of [[0, 0, 1], [1, 0, 0], normalize([1, 2, -3]), normalize([-0.2, 0.1, 0.97])]) {
      const [u, v] = tiltAxes(n);
      for (const [a, b] of [[u, n], [v, n], [u, v]]) assert.ok(Math.abs(dot(a, b)) < 1e-12);
      assert.ok(Math.abs(Math.hypot(...u) - 1) < 1e-12 && Math.abs(Math.hypot(...v) - 1) < 1e-12);
    }
  });

  test('a tilt turns the normal by its angle; none leaves it (normalized)', () => {
    const n = normalize([0.3, -0.2, 0.9]);
    assert.ok(close(tilted([0, 0, 2]), [0, 0, 1]));
    for (const [a, b] of [[10, 0], [0, -25], [30, 40]]) {
      const t = tilted(n, [a, b]);
      const expected = Math.cos((a * Math.PI) / 180) * Math.cos((b * Math.PI) / 180);
      assert.ok(Math.abs(dot(t, n) - expected) < 1e-12, `${a}, ${b}`);
      assert.ok(Math.abs(Math.hypot(...t) - 1) < 1e-12);
    }
  });

  test('the plane is the point and the tilted normal', () => {
    assert.deepEqual(cutPlane({ point: [1, 2, 3], normal: [0, 0, 2], tilt: [0, 0] }), [1, 2, 3, 0, 0, 1]);
    const p = cutPlane({ point: [0, 0, 0], normal: [0, 0, 1], tilt: [90, 0] });
    assert.ok(Math.abs(p[5]) < 1e-12);
  });

  test('a move goes along the normal by radii; the found cut keeps the old side', () => {
    assert.deepEqual(alongVessel({ point: [1, 0, 0], normal: [0, 0, 2], radius: 2 }, 0.5), [1, 0, 1]);
    const old = { normal: [0, 0, 1] };
    assert.deepEqual(keepSide({ point: [0, 0, 0], normal: [0, 0.1, -1], radius: 1 }, old).normal, [-0, -0.1, 1]);
    const same = { point: [0, 0, 0], normal: [0, 0.1, 1], radius: 1 };
    assert.equal(keepSide(same, old), same);
  });
});
