// Node test of the built module: hostile input through the JS API never
// throws. Broken bytes (truncations, bit flips, lying headers, non-finite
// coordinates, text, gzip of nothing) and every numeric option at hostile
// values (the option table's bounds and past them, 0, -1, 1e-30, 1e300, NaN,
// Infinity, strings) give {ok: false, error} with a message, or a result;
// nothing escapes as an exception, and the module keeps working after.
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { gzipSync } from 'node:zlib';
import { before, test } from 'node:test';

import { createVesselmesh } from '../src/vesselmesh.js';

let api;
let tube;
before(async () => {
  const wasmBinary = readFileSync(new URL('../dist/vesselmesh_core.wasm', import.meta.url));
  api = await createVesselmesh({ wasmBinary });
  tube = api.makePhantom({ kind: 'tube', voxel: 0.3 }).stl;
});

/** Calls `fn`; fails the test when it throws or gives no {ok} answer. */
function settles(what, fn) {
  let r;
  assert.doesNotThrow(() => {
    r = fn();
  }, what);
  assert.equal(typeof r?.ok, 'boolean', what);
  if (!r.ok) assert.ok(typeof r.error === 'string' && r.error.length > 0, `${what}: an error without a message`);
  return r;
}

/** A deterministic generator of numbers in [0, 1). */
function random(seed) {
  let s = seed >>> 0;
  return () => {
    s = (Math.imul(s, 1664525) + 1013904223) >>> 0;
    return s / 2 ** 32;
  };
}

test('broken bytes are refused with a message, never thrown', () => {
  const rnd = random(7);
  const cases = [];
  for (const cut of [0, 1, 83, 84, 100, 134, tube.length >> 1, tube.length - 1]) cases.push([`cut ${cut}`, tube.slice(0, cut)]);
  for (let k = 0; k < 30; ++k) {
    const b = tube.slice();
    for (let i = 0; i <= k % 4; ++i) b[84 + Math.floor(rnd() * (b.length - 84))] ^= 1 << Math.floor(rnd() * 8);
    cases.push([`bit flip ${k}`, b]);
  }
  for (const count of [0, 1, 2 ** 31, 2 ** 32 - 1]) {
    const b = tube.slice();
    new DataView(b.buffer).setUint32(80, count, true);
    cases.push([`header count ${count}`, b]);
  }
  for (const [k, bad] of [NaN, Infinity, -Infinity, 3.4e38].entries()) {
    const b = tube.slice();
    new DataView(b.buffer).setFloat32(84 + 50 * (3 * k) + 12 + 4 * k, bad, true);
    cases.push([`coordinate ${bad}`, b]);
  }
  cases.push(['text', new TextEncoder().encode('this is not a mesh, only words long enough to be read as a header\n'.repeat(3))]);
  cases.push(['gzip of nothing', gzipSync(new Uint8Array(0))]);
  cases.push(['gzip truncated', gzipSync(tube).slice(0, 300)]);
  cases.push(['empty', new Uint8Array(0)]);
  let refused = 0;
  for (const [what, bytes] of cases) {
    if (!settles(`analyze: ${what}`, () => api.analyze(bytes)).ok) ++refused;
    settles(`mesh: ${what}`, () => api.mesh(bytes, { size: 0.5, layers: 0 }));
  }
  assert.ok(refused >= 12, `only ${refused} of ${cases.length} broken inputs were refused`);
  assert.equal(api.analyze(tube).ok, true, 'the module works after');
});

test('a gzip of no surface is refused from its first inflated bytes, not inflated whole', () => {
  // 512 members of 1 MiB of zeros each: 512 MiB inflated, about 0.5 MB given.
  const member = gzipSync(new Uint8Array(1 << 20), { level: 9 });
  const bomb = new Uint8Array(member.length * 512);
  for (let k = 0; k < 512; ++k) bomb.set(member, k * member.length);
  const r = settles('analyze: gzip of 512 MiB of zeros', () => api.analyze(bomb));
  assert.equal(r.ok, false);
  assert.match(r.error, /^gzip-compressed file: its first 65536 decompressed bytes are not the start of a surface file/);
  assert.match(r.error, /they are all zero bytes; the rest was not decompressed\. Open the surface file itself/);
  const meshed = settles('mesh: gzip of 512 MiB of zeros', () => api.mesh(bomb, { size: 0.5, layers: 0 }));
  assert.equal(meshed.ok, false);
  assert.match(meshed.error, /the rest was not decompressed/);
  // A gzipped surface still reads as itself.
  const plain = api.analyze(tube);
  const zipped = api.analyze(gzipSync(tube));
  assert.equal(zipped.ok, true, zipped.error);
  assert.equal(zipped.analysis.input_triangles, plain.analysis.input_triangles);
  assert.equal(zipped.analysis.format, `gzip, ${plain.analysis.format}`);
});

test('every numeric option at hostile values is refused or meshes, never thrown', () => {
  const values = (s) => {
    const v = [0, -1, 1e-30, 1e300, NaN, Infinity, -Infinity, 'abc', '', 1.5, 2 ** 31];
    if (s.min !== undefined) v.push(s.min, s.min - 1e-9 - Math.abs(s.min) * 1e-9);
    if (s.max !== undefined && s.max < 1e30) v.push(s.max, s.max * (1 + 1e-9) + 1e-9);
    return v;
  };
  let cases = 0;
  for (const spec of api.optionTable) {
    if (!spec.faces.includes('js') || !['number', 'integer'].includes(spec.type)) continue;
    for (const value of values(spec)) {
      const v = spec.perOpening === 'required' ? { 1: value } : value;
      if (spec.commands.includes('mesh')) {
        const r = settles(`mesh ${spec.js}: ${value}`, () => api.mesh(tube, { size: 0.6, layers: 1, [spec.js]: v }));
        if (r.ok) assert.ok(r.msh?.length > 0, `${spec.js}: ${value}: ok without a file`);
      } else if (spec.commands.includes('info')) {
        settles(`analyze ${spec.js}: ${value}`, () => api.analyze(tube, { [spec.js]: v }));
      } else {
        settles(`makePhantom ${spec.js}: ${value}`, () => api.makePhantom({ voxel: 0.4, [spec.js]: v }));
      }
      ++cases;
    }
  }
  assert.ok(cases > 200, `${cases} cases`);
  assert.equal(api.mesh(tube, { size: 0.6, layers: 1 }).ok, true, 'the module works after');
});
