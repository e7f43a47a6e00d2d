// Node tests of the built module: the files pipelines exchange. Surface
// formats in (a VTP with face labels), capped models opened, units, named
// openings, and every output format, written again without meshing.
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { before, describe, test } from 'node:test';
import { inflateSync } from 'node:zlib';

import { readZip } from '../../e2e/zip.js';
import { transferables } from '../src/transfer.js';
import { createVesselmesh } from '../src/vesselmesh.js';
import { cappedTubeVtp as cappedTubeText } from './capped-tube-vtp.js';
import { unzip } from './unzip.js';

let api;
before(async () => {
  const wasmBinary = readFileSync(new URL('../dist/vesselmesh_core.wasm', import.meta.url));
  api = await createVesselmesh({ wasmBinary });
});

const text = (bytes) => new TextDecoder().decode(bytes);

/** The capped tube VTP (capped-tube-vtp.js) as file bytes. */
const cappedTubeVtp = (n, m) => new TextEncoder().encode(cappedTubeText(n, m));

/** An ASCII STL of the phantom tube's triangles moved by (offset, offset,
 * offset), as text; every number exact (JavaScript's shortest round trip). */
function asciiStl(stl, offset = 0) {
  const view = new DataView(stl.buffer, stl.byteOffset, stl.byteLength);
  const n = view.getUint32(80, true);
  const lines = ['solid tube'];
  for (let t = 0; t < n; ++t) {
    lines.push('facet normal 0 0 0', 'outer loop');
    for (let c = 0; c < 3; ++c) {
      const at = 84 + 50 * t + 12 + 12 * c;
      lines.push(`vertex ${[0, 4, 8].map((k) => view.getFloat32(at + k, true) + offset).join(' ')}`);
    }
    lines.push('endloop', 'endfacet');
  }
  return `${lines.join('\n')}\nendsolid tube\n`;
}

describe('files in', () => {
  test('ASCII STL as segmentation tools write it: a byte order mark, NUL in the name, CR line ends, UTF-16', () => {
    const stl = api.makePhantom({ kind: 'tube', voxel: 0.3 }).stl;
    const want = api.analyze(stl);
    assert.equal(want.ok, true, want.error);
    const body = asciiStl(stl);
    const utf16 = new Uint8Array(2 + 2 * body.length);
    utf16.set([0xff, 0xfe]);
    for (let i = 0; i < body.length; ++i) utf16[2 + 2 * i] = body.charCodeAt(i);
    const cases = {
      bom: new TextEncoder().encode(`\ufeff${body}`),
      name: new TextEncoder().encode(body.replace('solid tube', 'solid a\fb\0c')),
      cr: new TextEncoder().encode(body.replaceAll('\n', '\r')),
      utf16,
    };
    for (const [name, bytes] of Object.entries(cases)) {
      const got = api.analyze(bytes);
      assert.equal(got.ok, true, `${name}: ${got.error}`);
      assert.equal(got.analysis.format, 'ASCII STL', name);
      assert.equal(got.analysis.triangles, want.analysis.triangles, name);
      assert.equal(got.analysis.openings.length, want.analysis.openings.length, name);
    }
    assert.ok(api.analyze(utf16).analysis.warnings.some((w) => /UTF-16/.test(w)));
    const bad = api.analyze(new TextEncoder().encode(`${'not a mesh '.repeat(20)}\n`));
    assert.equal(bad.ok, false);
    assert.match(bad.error, /not a surface file this tool reads/);
  });

  test('ASCII STL 1e5 from the origin: every digit kept, meshed as at the origin', () => {
    // A tube of radius 0.01: float32 corners (spacing 2^-7 at 1e5) would
    // collapse it.
    const stl = api.makePhantom({ kind: 'tube', voxel: 0.3, scale: 0.01 }).stl;
    const want = api.analyze(stl);
    assert.equal(want.ok, true, want.error);
    const far = new TextEncoder().encode(asciiStl(stl, 1e5));
    const got = api.analyze(far);
    assert.equal(got.ok, true, got.error);
    assert.equal(got.analysis.format, 'ASCII STL');
    assert.equal(got.analysis.vertices, want.analysis.vertices);
    assert.equal(got.analysis.openings.length, 2);
    const meshed = api.mesh(far);
    assert.equal(meshed.ok, true, meshed.error);
    assert.ok(meshed.report.output.volume.tetrahedra > 0);
  });

  test('a labelled VTP: its caps become openings, the unit is given or guessed', () => {
    const vtp = cappedTubeVtp();
    const a = api.analyze(vtp);
    assert.equal(a.ok, true, a.error);
    assert.match(a.analysis.format, /^VTK XML PolyData/);
    assert.equal(a.analysis.label_array, 'ModelFaceID');
    assert.equal(a.analysis.caps_removed, 2);
    assert.equal(a.analysis.closed, false);
    assert.deepEqual(a.analysis.openings.map((o) => o.source), ['cap', 'cap']);
    assert.deepEqual(a.analysis.openings.map((o) => o.label).sort(), [2, 3]);
    assert.deepEqual(a.analysis.openings.map((o) => o.name), ['inlet', 'outlet_1']);
    // A tube of radius 1 and length 4 with labelled caps: a 10 mm vessel in
    // cm (SimVascular's unit, which the labels hint at), or in mm a 1 mm
    // vessel 4 mm long (unusual): cm, likely, mm the alternative.
    const { unit, guessed, certain, confidence, alternative, reason, measures } = a.analysis.units;
    assert.deepEqual([unit, guessed, certain, confidence, alternative], ['cm', true, false, 'likely', 'mm']);
    // Measured across the lumen: 1 on the wall, along the tube from the caps
    // (up to its half length, 2) on their share of the area.
    assert.ok(measures.largest_radius >= 0.99 && measures.largest_radius <= 2, reason);
    assert.ok(Math.abs(measures.median_radius - 1) < 0.01, reason);
    assert.equal(measures.label_array, 'ModelFaceID');
    assert.match(reason, /^vessel radius [\d.]+ largest, 1 median, /);
    // Caps kept and the flat ends not clipped (clip auto would cut them as
    // blind ends): a closed wall.
    const kept = api.analyze(vtp, { keepCaps: true, clip: 'off', units: 'cm' });
    assert.equal(kept.ok, true, kept.error);
    assert.equal(kept.analysis.openings.length, 0);
    assert.equal(kept.analysis.closed, true);
    assert.equal(kept.analysis.units.unit, 'cm');
    assert.equal(kept.analysis.units.guessed, false);
  });

  test('a SimVascular-like model with 186 labelled faces and tiny 6-triangle caps meshes at default options', () => {
    // makePhantom({kind: 'outlets'}): a capped tube with 20 tiny capped
    // branches, also as a labelled VTP. Every cap becomes an opening; the
    // mesh has a wall, an inlet and 21 outlets.
    const p = api.makePhantom({ kind: 'outlets' });
    assert.equal(p.ok, true, p.error);
    assert.ok(p.vtp instanceof Uint8Array && p.stl instanceof Uint8Array);
    assert.deepEqual(transferables(p), [p.stl.buffer, p.vtp.buffer]); // the worker moves both
    assert.match(text(p.vtp.subarray(0, 400)), /<VTKFile type="PolyData"/);
    const a = api.analyze(p.vtp);
    assert.equal(a.ok, true, a.error);
    assert.equal(a.analysis.label_array, 'ModelFaceID');
    assert.equal(a.analysis.caps_removed, 22);
    assert.equal(a.analysis.openings.length, 22);
    assert.ok(a.analysis.openings.every((o) => o.source === 'cap'));
    assert.equal(a.analysis.openings.filter((o) => o.vertices.length === 6).length, 20);
    const m = api.mesh(p.vtp);
    assert.equal(m.ok, true, m.error);
    const names = m.report.output.groups.map((g) => g.name);
    const outlets = Array.from({ length: 21 }, (_, k) => `outlet_${k + 1}`);
    assert.deepEqual(names, ['wall', 'inlet', ...outlets, 'lumen']);
    assert.ok(m.report.output.groups.every((g) => g.elements > 0));
    assert.ok(m.report.output.volume.tetrahedra > 0);
    assert.ok(m.report.output.volume.quality.min > 0);
    assert.ok(Array.isArray(m.report.output.remesh.fallback_patches));
    // An unlabelled kind has no VTP.
    assert.equal(api.makePhantom({ kind: 'tube', voxel: 0.3 }).vtp, undefined);
  });

  test('units from anatomy: a carotid in cm or in mm, and what the page asks', () => {
    // The bifurcation's parent has radius 1: at scale 0.35 a 3.5 mm carotid
    // written in cm, at 3.5 the same in mm.
    const inCm = api.analyze(api.makePhantom({ kind: 'bifurcation', voxel: 0.15, scale: 0.35 }).stl);
    assert.equal(inCm.ok, true, inCm.error);
    const cm = inCm.analysis.units;
    assert.deepEqual([cm.unit, cm.guessed, cm.certain, cm.confidence, cm.alternative], ['cm', true, false, 'likely', 'mm']);
    assert.match(cm.reason, /^vessel radius 0\.3\d* largest, .*: cm gives typical human vessel sizes, mm unusual ones \(/);
    assert.ok(cm.measures.largest_radius < cm.measures.diagonal);
    const inMm = api.analyze(api.makePhantom({ kind: 'bifurcation', voxel: 0.15, scale: 3.5 }).stl);
    assert.deepEqual([inMm.analysis.units.unit, inMm.analysis.units.alternative], ['mm', 'cm']);
    // Whatever is done to the surface, the guess stays.
    const closed = api.makePhantom({ kind: 'bifurcation', voxel: 0.15, scale: 0.35, openEnds: false }).stl;
    const before = api.analyze(closed).analysis.units;
    const after = api.analyze(closed, { clip: 'auto', flowExtension: 3, smooth: 5 }).analysis.units;
    assert.deepEqual(after, before);
  });

  test('a flat-capped phantom in metres: 3 openings from caps, metres guessed', () => {
    const p = api.makePhantom({ kind: 'bifurcation', voxel: 0.12, noise: 0.3, flatCaps: true, scale: 0.003 });
    assert.equal(p.ok, true, p.error);
    const a = api.analyze(p.stl);
    assert.equal(a.ok, true, a.error);
    assert.equal(a.analysis.openings.length, 3);
    assert.equal(a.analysis.units.unit, 'm');
    assert.equal(a.analysis.units.certain, true);
    assert.match(a.analysis.warnings.join('\n'), /planar caps were recognised.*keepCaps/);
    assert.match(a.analysis.warnings.join('\n'), /in metres.*say otherwise with units/);
  });

  test('what is not a surface is refused with the formats it could be', () => {
    const png = new Uint8Array([0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0, 0, 0, 13, 0x49, 0x48, 0x44, 0x52]);
    const r = api.analyze(png);
    assert.equal(r.ok, false);
    assert.equal(r.kind, 'bad_input');
    assert.match(r.error, /not a surface file this tool reads \(binary or ASCII STL, VTK XML PolyData/);
    assert.match(r.error, /PNG/);
  });
});

describe('flow extensions', () => {
  test('each opening moved out along its normal, in local radii; per opening with {K: L}', () => {
    const stl = api.makePhantom({ kind: 'bifurcation', voxel: 0.12, noise: 0.3 }).stl;
    const plain = api.analyze(stl).analysis.openings;
    const ext = api.analyze(stl, { flowExtension: { 2: 3 } });
    assert.equal(ext.ok, true, ext.error);
    const [a, b] = [plain[1], ext.analysis.openings[1]];
    const moved = [0, 1, 2].map((k) => b.centroid[k] - a.centroid[k]);
    const want = [0, 1, 2].map((k) => 3 * a.radius * a.normal[k]);
    assert.ok(Math.hypot(...moved.map((m, k) => m - want[k])) < 1e-6, JSON.stringify({ moved, want }));
    assert.ok(Math.abs(b.extension - 3 * a.radius) < 1e-9);
    assert.equal(ext.analysis.openings[0].extension, 0);
    const m = api.mesh(stl, { flowExtension: 2, size: 0.3, layers: 1 });
    assert.equal(m.ok, true, m.error);
    assert.match(api.analyze(stl, { flowExtension: -1 }).error, /^flowExtension needs a length in local radii/);
  });
});

describe('names and files out', () => {
  let tube;
  before(() => {
    tube = cappedTubeVtp();
  });

  test('named openings become the groups; bad names are refused in JS words', () => {
    const m = api.mesh(tube, { size: 0.4, layers: 1, names: { 2: 'distal', 1: 'proximal' } });
    assert.equal(m.ok, true, m.error);
    assert.deepEqual(m.volume.surfaceNames, ['wall', 'proximal', 'distal']);
    assert.deepEqual(
      m.report.output.groups.map((g) => g.name),
      ['wall', 'proximal', 'distal', 'lumen'],
    );
    for (const [names, pattern] of [
      [{ 1: 'lumen' }, /^names cannot be 'lumen'/],
      [{ 3: 'x' }, /^names names opening 3, but there are 2 openings$/],
      [{ 1: '9x' }, /^names needs K=NAME with NAME 1-64 letters/],
      [{ 1: 'a', 2: 'a' }, /^names gives 'a' to openings 1 and 2: each name once$/],
      [{ 0: 'a' }, /^names keys must be opening numbers >= 1/],
      ['a', /^names needs K=VALUE with K an opening number >= 1$/],
    ]) {
      const r = api.mesh(tube, { size: 0.4, names });
      assert.equal(r.ok, false, JSON.stringify(names));
      assert.match(r.error, pattern);
      assert.equal(r.kind, 'bad_option');
    }
  });

  test('openingNames() previews the names mesh() will give, or its refusal', () => {
    assert.equal(api.analyze(tube).ok, true);
    assert.deepEqual(api.openingNames().names, ['inlet', 'outlet_1']);
    assert.deepEqual(api.openingNames({ inlet: 2 }).names, ['outlet_1', 'inlet']);
    assert.deepEqual(api.openingNames({ names: { 1: 'aorta' } }).names, ['aorta', 'outlet_1']);
    const bad = api.openingNames({ names: { 1: 'wall' } });
    assert.equal(bad.ok, false);
    assert.equal(bad.option, 'names');
  });

  test('every format, from mesh() and again from export() without meshing', () => {
    const m = api.mesh(tube, { size: 0.4, layers: 1, format: 'vtu' });
    assert.equal(m.ok, true, m.error);
    assert.equal(m.format, 'vtu');
    assert.equal(m.fileName, 'mesh.vtu');
    assert.equal(m.msh, undefined);
    assert.match(text(m.file.subarray(0, 300)), /<!-- vesselmesh [\d.]+; input xxh128:[0-9a-f]{32}; options: size=0.4 layers=1 format=vtu -->/);
    assert.match(text(m.file.subarray(0, 400)), /<VTKFile type="UnstructuredGrid"/);
    const tets = m.volume.tets.length / 4;
    assert.match(text(m.file.subarray(0, 600)), new RegExp(`NumberOfCells="${tets}"`));
    const msh = api.export('msh', { mshVersion: '2.2', outputUnits: 'm' });
    assert.equal(msh.ok, true, msh.error);
    assert.equal(msh.fileName, 'mesh.msh');
    assert.ok(text(msh.file).startsWith('$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Comments\nvesselmesh'));
    const vtp = api.export('vtp');
    assert.match(text(vtp.file.subarray(0, 400)), /<VTKFile type="PolyData"/);
    const stl = api.export('stl');
    assert.equal(stl.file.length, 84 + 50 * m.surface.triangles.length / 3);
    const zip = api.export('mesh-complete');
    assert.equal(zip.ok, true, zip.error);
    assert.equal(zip.fileName, 'mesh-complete.zip');
    assert.deepEqual([...zip.file.subarray(0, 4)], [0x50, 0x4b, 0x03, 0x04]);
    for (const name of ['mesh-complete.mesh.vtu', 'mesh-complete.exterior.vtp', 'mesh-surfaces/inlet.vtp']) {
      assert.ok(text(zip.file).includes(name), name);
    }
    assert.match(api.export('obj').error, /^format needs msh, vtu, vtp, stl, mesh-complete or foam$/);
    assert.match(api.export('msh', { size: 1 }).error, /unknown export option 'size'/);
  });

  test('foam: a zip of the OpenFOAM case, prisms kept, in metres', () => {
    const m = api.mesh(tube, { size: 0.4, layers: 2, prisms: true, format: 'foam', outputUnits: 'm', units: 'mm' });
    assert.equal(m.ok, true, m.error);
    assert.equal(m.format, 'foam');
    assert.equal(m.fileName, 'openfoam-case.zip');
    const files = unzip(m.file);
    assert.deepEqual(Object.keys(files).sort(), [
      'case.foam',
      'constant/polyMesh/boundary',
      'constant/polyMesh/cellZones',
      'constant/polyMesh/faces',
      'constant/polyMesh/neighbour',
      'constant/polyMesh/owner',
      'constant/polyMesh/points',
      'system/controlDict',
      'system/fvSchemes',
      'system/fvSolution',
    ]);
    const body = (name) => files[`constant/polyMesh/${name}`].split('\n}\n')[1];
    // The volume's points and cells, every cell face once.
    const v = m.volume;
    const nPoints = v.positions.length / 3;
    const [nTets, nPrisms] = [v.tets.length / 4, v.prisms.length / 6];
    assert.ok(nPrisms > 0);
    assert.equal(Number(body('points').trim().split('\n')[0]), nPoints);
    const note = files['constant/polyMesh/owner'].match(
      /note\s+"nPoints:(\d+)\s+nCells:(\d+)\s+nFaces:(\d+)\s+nInternalFaces:(\d+)"/,
    );
    const [, points, cells, nFaces, nInternal] = note.map(Number);
    assert.deepEqual([points, cells], [nPoints, nTets + nPrisms]);
    assert.equal(body('faces').match(/^[34]\(/gm).length, nFaces);
    // Internal faces twice, boundary faces (the tagged triangles and quads) once.
    assert.equal(nFaces - nInternal, v.triangles.length / 3 + v.quads.length / 4);
    assert.equal(2 * nInternal + (nFaces - nInternal), 4 * nTets + 5 * nPrisms);
    // Patches: the wall a wall, the openings patches; the lumen a cell zone.
    const boundary = body('boundary');
    assert.match(boundary, /wall\n\s+\{\n\s+type\s+wall;/);
    assert.match(boundary, /inlet\n\s+\{\n\s+type\s+patch;/);
    assert.match(boundary, /outlet_1\n\s+\{\n\s+type\s+patch;/);
    assert.match(body('cellZones'), /^lumen$/m);
    // Metres: the points are the volume's (in mm) over 1000.
    const z = [...body('points').matchAll(/\(\S+ \S+ (\S+)\)/g)].map((p) => Number(p[1]));
    const zMm = v.positions.filter((_, i) => i % 3 === 2);
    assert.ok(Math.abs(Math.max(...z) - Math.max(...zMm) / 1000) < 1e-6, `max z ${Math.max(...z)}`);
    assert.equal(api.export('foam').fileName, 'openfoam-case.zip');
  });

  test('a surface-only result has no volume format', () => {
    const m = api.mesh(tube, { size: 0.4, surfaceOnly: true, format: 'stl' });
    assert.equal(m.ok, true, m.error);
    assert.equal(m.fileName, 'mesh.stl');
    const vtu = api.export('vtu');
    assert.equal(vtu.ok, false);
    assert.equal(vtu.error, 'format cannot be vtu: it holds a volume mesh, and this one is surface only (surfaceOnly); use msh, vtp or stl');
    // Asked before meshing, it is refused before meshing (nothing runs).
    let calls = 0;
    const early = api.mesh(tube, { surfaceOnly: true, format: 'mesh-complete', onProgress: () => ++calls });
    assert.equal(early.kind, 'bad_option');
    assert.equal(early.option, 'format');
    assert.equal(calls, 0);
  });

  test('MSH 4.1 binary: bytes in Gmsh\'s layout, the same nodes and elements as the text file; 2.2 refused', () => {
    const m = api.mesh(tube, { size: 0.4, layers: 1, mshBinary: true });
    assert.equal(m.ok, true, m.error);
    assert.ok(m.file instanceof Uint8Array && m.msh === m.file);
    assert.ok(transferables(m).includes(m.file.buffer), 'moved from the worker, not copied');
    const head = '$MeshFormat\n4.1 1 8\n';
    assert.equal(text(m.file.subarray(0, head.length)), head);
    assert.deepEqual([...m.file.subarray(head.length, head.length + 5)], [1, 0, 0, 0, 10], 'the int 1, little-endian');
    // One character a byte (windows-1252), so that offsets in the text are offsets in the bytes.
    const bytewise = (bytes) => new TextDecoder('latin1').decode(bytes);
    // The 4 size_t after "$Nodes\n" and "$Elements\n": blocks, count, min and max tag.
    const counts = (bytes, section) => {
      const at = bytewise(bytes).indexOf(`\n$${section}\n`) + section.length + 3;
      const view = new DataView(bytes.buffer, bytes.byteOffset + at, 32);
      return [0, 8, 16, 24].map((k) => Number(view.getBigUint64(k, true)));
    };
    const ascii = api.export('msh', { mesh: m.handle });
    const line = (section) => text(ascii.file).split(`$${section}\n`)[1].split('\n')[0].split(' ').map(Number);
    assert.deepEqual(counts(m.file, 'Nodes'), line('Nodes'));
    assert.deepEqual(counts(m.file, 'Elements'), line('Elements'));
    assert.equal(counts(m.file, 'Nodes')[1], m.volume.positions.length / 3);
    const again = api.export('msh', { mshBinary: true, mesh: m.handle });
    assert.ok(again.file instanceof Uint8Array);
    const body = (bytes) => bytes.subarray(bytewise(bytes).indexOf('$EndComments\n'));
    assert.deepEqual(body(again.file), body(m.file));
    const refused = api.mesh(tube, { mshBinary: true, mshVersion: '2.2' });
    assert.equal(refused.option, 'mshBinary');
    assert.match(refused.error, /^mshBinary writes MSH 4\.1 only.*give mshVersion 4\.1, or drop mshBinary$/);
  });

  test('vtkCompress: VTK\'s zlib blocks, inflating to the raw VTU\'s arrays; foamBinary: raw lists of the same mesh', () => {
    const m = api.mesh(tube, { size: 0.4, layers: 1, format: 'vtu', vtkCompress: true });
    assert.equal(m.ok, true, m.error);
    assert.match(text(m.file.subarray(0, 400)), /byte_order="LittleEndian" header_type="UInt64" compressor="vtkZLibDataCompressor">/);
    const raw = api.export('vtu', { mesh: m.handle });
    assert.ok(m.file.length < raw.file.length / 2, `${m.file.length} bytes, raw ${raw.file.length}`);
    // Each DataArray's values: at its offset after the '_', a UInt64 byte
    // count then the bytes (raw), or VTK's block header (count, block
    // size, last partial size, each block's size) then zlib blocks.
    const arrays = (bytes, zlib) => {
      const latin1 = new TextDecoder('latin1').decode(bytes);
      const data = latin1.indexOf('_', latin1.indexOf('<AppendedData encoding="raw">')) + 1;
      const view = new DataView(bytes.buffer, bytes.byteOffset);
      const u64 = (at) => Number(view.getBigUint64(data + at, true));
      const out = {};
      for (const [, name, offset] of latin1.slice(0, data).matchAll(/<DataArray type="\w+"(?: Name="(\w+)")?.*? offset="(\d+)"/g)) {
        const at = Number(offset);
        if (!zlib) {
          out[name ?? 'Points'] = bytes.subarray(data + at + 8, data + at + 8 + u64(at));
          continue;
        }
        const [blocks, size, last] = [u64(at), u64(at + 8), u64(at + 16)];
        const parts = [];
        let from = data + at + 24 + 8 * blocks;
        for (let b = 0; b < blocks; ++b) {
          const part = inflateSync(bytes.subarray(from, from + u64(at + 24 + 8 * b)));
          assert.equal(part.length, b + 1 === blocks && last ? last : size);
          parts.push(part);
          from += u64(at + 24 + 8 * b);
        }
        out[name ?? 'Points'] = new Uint8Array(Buffer.concat(parts));
      }
      return out;
    };
    const [packed, plain] = [arrays(m.file, true), arrays(raw.file, false)];
    assert.deepEqual(Object.keys(packed).sort(), ['GlobalElementID', 'GlobalNodeID', 'ModelRegionID', 'Points', 'connectivity', 'offsets', 'types']);
    for (const name of Object.keys(plain)) assert.deepEqual(packed[name], plain[name], name);
    const u32 = (u8) => new Uint32Array(u8.buffer.slice(u8.byteOffset, u8.byteOffset + u8.length));
    assert.deepEqual(u32(packed.connectivity), m.volume.tets);
    assert.equal(packed.types.length, m.volume.tets.length / 4);
    assert.ok(packed.types.every((t) => t === 10));
    // export() compresses as mesh() did.
    const again = api.export('vtu', { mesh: m.handle, vtkCompress: true });
    const body = (bytes) => bytes.subarray(text(bytes.subarray(0, 400)).indexOf('<VTKFile'));
    assert.deepEqual(body(again.file), body(m.file));

    // foamBinary: points as doubles (the volume's, shown as floats), owner
    // as int32 labels.
    const foam = readZip(api.export('foam', { mesh: m.handle, foamBinary: true }).file);
    const list = (name, width) => {
      const bytes = foam.get(`constant/polyMesh/${name}`);
      const latin1 = new TextDecoder('latin1').decode(bytes);
      assert.match(latin1, /\n {4}format {6}binary;\n {4}class {7}\w+;\n {4}arch {8}"LSB;label=32;scalar=64";/);
      const at = latin1.indexOf('\n}\n') + 3;
      const [, n] = latin1.slice(at).match(/^\n*(\d+)\n\(/);
      const start = latin1.indexOf('(', at) + 1;
      assert.equal(latin1.slice(start + Number(n) * width, start + Number(n) * width + 2), ')\n');
      return new Uint8Array(bytes.subarray(start, start + Number(n) * width)).buffer;  // a copy, aligned
    };
    assert.deepEqual(Float32Array.from(new Float64Array(list('points', 24))), m.volume.positions);
    const note = new TextDecoder().decode(foam.get('constant/polyMesh/owner')).match(/nCells:(\d+)\s+nFaces:(\d+)\s+nInternalFaces:(\d+)/);
    const [cells, faces, internal] = note.slice(1).map(Number);
    assert.equal(cells, m.volume.tets.length / 4);
    const owner = new Int32Array(list('owner', 4));
    assert.equal(owner.length, faces);
    assert.ok(owner.every((c) => c >= 0 && c < cells));
    // Internal faces in upper-triangular order: owners never decrease.
    assert.ok(owner.subarray(0, internal).every((c, i, a) => i === 0 || a[i - 1] <= c));
    assert.equal(new Int32Array(list('neighbour', 4)).length, internal);
  });

  test('export() records its own options in the provenance', () => {
    assert.equal(api.mesh(tube, { size: 0.4, layers: 0 }).ok, true);
    const msh = api.export('msh', { outputUnits: 'cm' });
    const comment = text(msh.file.subarray(0, 300)).split('\n')[4];
    assert.match(comment, /options: size=0\.4 layers=0 .*output_units=cm/);
    assert.match(comment, / format=msh/);
  });
});
