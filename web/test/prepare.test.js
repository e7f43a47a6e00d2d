// Node tests of the Prepare step's smoothing note (web/src/prepare.js).
import assert from 'node:assert/strict';
import { test } from 'node:test';

import { smoothingNote } from '../src/prepare.js';

const base = { staircase: false, applied: false, passes: 0, voxel: null, max_displacement: 0, max_displacement_voxels: 0, volume_change: 0 };

test('the smoothing note says the staircase, its voxel and what smoothing did', () => {
  assert.equal(smoothingNote(base, 'mm'), '');
  assert.equal(smoothingNote(undefined, 'mm'), '');
  const stairs = { ...base, staircase: true, voxel: 0.15, applied: true, passes: 24, max_displacement_voxels: 0.4996, volume_change: -0.0012 };
  assert.equal(
    smoothingNote(stairs, 'mm'),
    'Voxel staircase detected (voxel 0.15 mm): smoothed in 24 passes, every vertex within 0.4996 voxel of where it was, volume -0.12%.',
  );
  assert.equal(
    smoothingNote({ ...stairs, volume_change: 1e-6 }, 'mm'),
    'Voxel staircase detected (voxel 0.15 mm): smoothed in 24 passes, every vertex within 0.4996 voxel of where it was.',
  );
  assert.equal(
    smoothingNote({ ...stairs, applied: false }, 'm'),
    'Voxel staircase detected (voxel 0.15 m): not smoothed (smoothing off).',
  );
  assert.equal(
    smoothingNote({ ...base, applied: true, passes: 10, max_displacement: 0.02 }, 'mm'),
    'Smoothed in 10 passes, by at most 0.02 mm.',
  );
});
