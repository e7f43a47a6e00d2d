// Node tests of the size view's and the measure tool's logic without DOM:
// the legend's range and round ticks (web/src/scalar-legend.js), the length
// colormap (web/src/colormap.js), the nearest vertex the radius is read at
// (web/src/size-view.js) and the measured distance (web/src/measure.js).
import assert from 'node:assert/strict';
import { describe, test } from 'node:test';

import { scalarColor } from '../src/colormap.js';
import { distance } from '../src/measure.js';
import { niceTicks, rampPosition, valueRange } from '../src/scalar-legend.js';
import { nearestVertex } from '../src/size-view.js';

describe('length legend', () => {
  test('the range skips values that are not numbers', () => {
    assert.deepEqual(valueRange(new Float32Array([0.5, 2, NaN, 0.25, Infinity])), [0.25, 2]);
    assert.equal(valueRange([]), null);
  });

  test('ticks are round, ascending and within the range', () => {
    for (const [lo, hi] of [
      [0.502, 6.74],
      [0.08, 0.326],
      [0.03, 0.031],
      [120, 4500],
      [1e-4, 3e-4],
    ]) {
      const ticks = niceTicks(lo, hi, 4);
      assert.ok(ticks.length >= 2 && ticks.length <= 9, `${lo}..${hi}: ${ticks}`);
      for (const [i, t] of ticks.entries()) {
        assert.ok(t >= lo && t <= hi, `${t} in ${lo}..${hi}`);
        if (i) assert.ok(t > ticks[i - 1]);
        // A multiple of 1, 2 or 5 times a power of ten: few digits.
        assert.equal(Number(t.toPrecision(3)), t, `round: ${t}`);
      }
    }
    assert.deepEqual(niceTicks(0.08, 0.326), [0.1, 0.2, 0.3]);
    assert.deepEqual(niceTicks(2, 2), [2]);
  });

  test('ramp positions are clamped to 0..1', () => {
    assert.equal(rampPosition(1, 0, 4), 0.25);
    assert.equal(rampPosition(-1, 0, 4), 0);
    assert.equal(rampPosition(9, 0, 4), 1);
    assert.equal(rampPosition(3, 3, 3), 0.5);
  });

  test('the colormap grows lighter with the value', () => {
    const luminance = (t) => {
      const c = new Float32Array(3);
      scalarColor(t, c);
      return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
    };
    for (let t = 0; t < 1; t += 0.05) assert.ok(luminance(t + 0.05) > luminance(t), `at ${t}`);
  });
});

describe('measurements', () => {
  test('the nearest vertex and the distance', () => {
    const positions = new Float32Array([0, 0, 0, 1, 0, 0, 0, 2, 0, 5, 5, 5]);
    assert.equal(nearestVertex(positions, [0.9, 0.2, 0]), 1);
    assert.equal(nearestVertex(positions, [4, 4, 4]), 3);
    assert.equal(distance([0, 0, 0], [3, 4, 12]), 13);
  });
});
