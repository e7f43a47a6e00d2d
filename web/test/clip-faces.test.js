// The clipped view's face table (web/src/clip.js) is a copy of the core's
// (kFaceOut in core/mesh/volume_mesh.h): both must list the same faces in
// the same order and orientation.
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { test } from 'node:test';

import { TET_FACES } from '../src/clip.js';

test('TET_FACES equals the core face table kFaceOut', () => {
  const header = readFileSync(new URL('../../core/mesh/volume_mesh.h', import.meta.url), 'utf8');
  const m = header.match(/kFaceOut\[4\]\[3\]\s*=\s*\{([^;]*)\};/);
  assert.ok(m, 'kFaceOut not found in core/mesh/volume_mesh.h');
  const rows = [...m[1].matchAll(/\{\s*(\d+)\s*,\s*(\d+)\s*,\s*(\d+)\s*\}/g)].map((r) => r.slice(1, 4).map(Number));
  assert.deepEqual(rows, TET_FACES);
});
