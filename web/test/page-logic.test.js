// Node tests of the page's logic without DOM: the group palette
// (web/src/palette.js, web/src/groups.js), the file sniffer
// (web/src/sniff.js) and the monotonic job progress (web/src/progress.js).
import assert from 'node:assert/strict';
import { describe, test } from 'node:test';

import { groupColors } from '../src/groups.js';
import { deltaE, PALETTE, PALETTE_SIZE } from '../src/palette.js';
import { JobProgress, duration } from '../src/progress.js';
import { describeNonSurface, sniffKind, SUPPORTED } from '../src/sniff.js';

const distance = (a, b) => Math.hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);
const minDistance = (colors) => {
  let min = Infinity;
  for (let i = 0; i < colors.length; i++) {
    for (let j = i + 1; j < colors.length; j++) min = Math.min(min, distance(colors[i], colors[j]));
  }
  return min;
};

describe('group colors', () => {
  test('the palette has 24 valid colors, far enough apart', () => {
    assert.equal(PALETTE.length, PALETTE_SIZE);
    assert.equal(PALETTE_SIZE, 24);
    for (const c of PALETTE) for (const v of c) assert.ok(v >= 0 && v <= 1);
    assert.ok(minDistance(PALETTE) > 0.1, `min distance ${minDistance(PALETTE)}`);
  });

  test('24 groups: wall, inlet and 22 outlets all differ', () => {
    const names = ['wall', 'inlet', ...Array.from({ length: 22 }, (_, i) => `outlet_${i + 1}`)];
    const colors = groupColors(names);
    assert.equal(new Set(colors.map(String)).size, 24);
    assert.ok(minDistance(colors) > 0.08, `min distance ${minDistance(colors)}`);
  });

  test('caps the user named never share a color, with each other or the outlets', () => {
    const names = ['wall', 'inlet', 'outlet_1', 'outlet_2', ...Array.from({ length: 20 }, (_, i) => `branch${i}`)];
    const colors = groupColors(names);
    assert.equal(new Set(colors.map(String)).size, names.length);
    assert.ok(minDistance(colors) > 0.08);
  });

  test('a wall ring is its cap color, paler, and the same in any list', () => {
    const [cap, ring] = groupColors(['outlet_3', 'wall_outlet_3']);
    assert.deepEqual(ring, cap.map((c) => 0.5 * c + 0.5));
    assert.deepEqual(groupColors(['wall', 'outlet_3'])[1], cap);
    const [namedRing, named] = groupColors(['wall_left', 'left']);
    assert.deepEqual(namedRing, named.map((c) => 0.5 * c + 0.5));
  });

  test('as the eye sees them: any two of 24 differ (ΔE > 25), neighbours in the list more (ΔE > 35)', () => {
    // The old palette (24 hues 15° apart) had pairs at ΔE 16: near-identical to a user.
    for (let i = 0; i < PALETTE_SIZE; i++) {
      for (let j = i + 1; j < PALETTE_SIZE; j++) {
        assert.ok(deltaE(PALETTE[i], PALETTE[j]) > 25, `colours ${i} and ${j}: ΔE ${deltaE(PALETTE[i], PALETTE[j])}`);
      }
      if (i) assert.ok(deltaE(PALETTE[i], PALETTE[i - 1]) > 35, `neighbours ${i - 1}, ${i}`);
    }
    // None looks like the wall's grey or the inlet's blue.
    const [wall, inlet] = groupColors(['wall', 'inlet']);
    for (const c of PALETTE) assert.ok(Math.min(deltaE(c, wall), deltaE(c, inlet)) > 20);
  });

  test('the first outlets have clearly different hues', () => {
    const colors = groupColors(['outlet_1', 'outlet_2', 'outlet_3', 'outlet_4']);
    assert.ok(minDistance(colors) > 0.3, `min distance ${minDistance(colors)}`);
  });
});

describe('file sniffing', () => {
  const bytes = (list, size = 512) => {
    const b = new Uint8Array(size);
    b.set(list);
    return b;
  };
  const text = (s, at = 0, size = 512) => {
    const b = new Uint8Array(size);
    b.set(new TextEncoder().encode(s), at);
    return b;
  };
  test('images, documents, archives and scans are recognised', () => {
    assert.equal(sniffKind(bytes([0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a])), 'a PNG image');
    assert.equal(sniffKind(bytes([0xff, 0xd8, 0xff, 0xe0])), 'a JPEG image');
    assert.equal(sniffKind(text('%PDF-1.7')), 'a PDF document');
    assert.equal(sniffKind(bytes([0x50, 0x4b, 0x03, 0x04])), 'a ZIP archive');
    assert.match(sniffKind(text('DICM', 128)), /^a DICOM image/);
  });
  test('surfaces and unknown files pass (the core decides)', () => {
    assert.equal(sniffKind(text('solid tet\nfacet normal 0 0 0')), null);
    assert.equal(sniffKind(text('<?xml version="1.0"?><VTKFile')), null);
    assert.equal(sniffKind(text('ply\nformat ascii 1.0')), null);
    assert.equal(sniffKind(bytes([0x1f, 0x8b, 0x08])), null); // gzip
    assert.equal(sniffKind(text('binary stl header', 0, 84)), null);
    assert.equal(sniffKind(new Uint8Array(0)), null);
    assert.equal(sniffKind(text('DICM', 128).subarray(0, 131)), null); // too short to hold it
  });
  test('the message says what it seems to be and what is read', () => {
    const m = describeNonSurface(bytes([0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a]));
    assert.match(m, /PNG image/);
    assert.ok(m.includes(SUPPORTED));
    assert.equal(describeNonSurface(text('solid x')), null);
  });
});

describe('job progress', () => {
  test('never goes backwards, whatever the worker reports', () => {
    const p = new JobProgress('mesh', 0);
    const shown = [];
    for (const [f, stage, t] of [
      [0, 'read', 100],
      [0.3, 'repair', 200],
      [0.2, 'repair', 300], // a nested stage restarts
      [0.9, 'quality', 400],
      [0.0, 'boundary layers', 500], // a stage reporting its own 0..1
      [0.5, 'boundary layers', 600],
      [0.92, 'tetrahedra', 700],
      [0.95, 'tetrahedra', 800],
      [1, 'done', 900],
    ]) {
      p.report(f, stage, t);
      shown.push(p.fraction);
    }
    for (let i = 1; i < shown.length; i++) assert.ok(shown[i] >= shown[i - 1], shown.join(' '));
    assert.equal(shown.at(-1), 1);
    assert.ok(shown[5] > shown[4], 'a restarting stage still moves the bar');
  });
  test('stage changes are told; elapsed and time left', () => {
    const p = new JobProgress('read', 0);
    assert.equal(p.report(0.1, 'read', 100), false);
    assert.equal(p.report(0.25, 'repair', 2000), true);
    assert.equal(p.elapsed(), 2);
    assert.equal(p.remaining(), 6); // 2 s for a quarter: 6 s for the rest
    assert.equal(p.text(), 'repair · 2 s elapsed · about 6 s left');
    const early = new JobProgress('read', 0);
    early.report(0.01, 'read', 500);
    assert.equal(early.remaining(), null);
    assert.equal(early.timeText(), '1 s elapsed');
    // Under a second and a half left by the rate: finishing, not "about 0 s".
    const late = new JobProgress('mesh', 0);
    late.report(0.9, 'tetrahedra', 10_000);
    assert.equal(late.timeText(), '10 s elapsed · finishing');
  });
  test('durations', () => {
    assert.equal(duration(0.4), '0 s');
    assert.equal(duration(59), '59 s');
    assert.equal(duration(65), '1 min 05 s');
  });
});
