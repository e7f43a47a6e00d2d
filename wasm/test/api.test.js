// Node tests of the built WebAssembly module through the JS API
// (wasm/dist must be built: scripts/setup.sh).
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { availableParallelism } from 'node:os';
import { before, describe, test } from 'node:test';

import { transferables } from '../src/transfer.js';
import { createVesselmesh } from '../src/vesselmesh.js';
import { dentedTubeStl } from './dented-tube.js';

let api;
before(async () => {
  const wasmBinary = readFileSync(new URL('../dist/vesselmesh_core.wasm', import.meta.url));
  api = await createVesselmesh({ wasmBinary });
});

const text = (bytes) => new TextDecoder().decode(bytes);
const ascii = (s) => new TextEncoder().encode(s);

const point = (p, i) => [p[3 * i], p[3 * i + 1], p[3 * i + 2]];
const sub = (a, b) => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
const distance = (a, b) => Math.hypot(...sub(a, b));

/** Sorted vertex triple of a face, as a Map key. */
const faceKey = (f) => Array.from(f).sort((p, q) => p - q).join(' ');
const byFace = new WeakMap();
/** face key -> the tetrahedra having that face (one or two). */
const tetsByFace = (v) => {
  if (byFace.has(v)) return byFace.get(v);
  const faces = new Map();
  for (let t = 0; t < v.tets.length / 4; t++) {
    const [a, b, c, d] = v.tets.subarray(4 * t, 4 * t + 4);
    for (const f of [[a, b, c], [a, b, d], [a, c, d], [b, c, d]]) {
      const k = faceKey(f);
      const list = faces.get(k);
      if (list) list.push(t);
      else faces.set(k, [t]);
    }
  }
  byFace.set(v, faces);
  return faces;
};
/** Tetrahedra per part: [core, viscous layer, vessel wall]. */
const partCounts = (v) => {
  const n = [0, 0, 0];
  for (const p of v.tetPart) n[p]++;
  return n;
};
/** Edges of a triangle surface used by one triangle (the openings' rims). */
const rimEdges = (triangles) => {
  const uses = new Map();
  for (let i = 0; i < triangles.length; i += 3) {
    for (let c = 0; c < 3; c++) {
      const k = faceKey([triangles[i + c], triangles[i + ((c + 1) % 3)]]);
      uses.set(k, (uses.get(k) ?? 0) + 1);
    }
  }
  return [...uses.values()].filter((n) => n === 1).length;
};
/**
 * Invariants of any volume result: every tetrahedron positive
 * (((b-a)x(c-a)).(d-a) > 0); each face bounds one or two tetrahedra; the
 * faces of one tetrahedron are exactly the tagged triangles that are not
 * interfaces (`wall` between the layer and the vessel wall), and enclose
 * the tets' volume outward (divergence theorem); per tag, as many
 * triangles as the report's group.
 */
const checkVolume = (v, report) => {
  const nv = v.positions.length / 3;
  const nt = v.tets.length / 4;
  let volume = 0;
  for (let t = 0; t < nt; t++) {
    const [a, b, c, d] = [0, 1, 2, 3].map((k) => point(v.positions, v.tets[4 * t + k]));
    const six = dot(cross(sub(b, a), sub(c, a)), sub(d, a));
    assert.ok(six > 0, `tetrahedron ${t}: signed volume ${six / 6}`);
    volume += six / 6;
  }
  const nb = v.triangleTag.length;
  assert.equal(v.triangles.length, 3 * nb);
  assert.equal(nb, report.output.volume.boundary_triangles);
  assert.ok(v.triangles.every((i) => i < nv));
  const faces = tetsByFace(v);
  const tagged = new Set();
  const counts = new Map();
  let enclosed = 0;
  for (let t = 0; t < nb; t++) {
    const tri = v.triangles.subarray(3 * t, 3 * t + 3);
    const around = faces.get(faceKey(tri));
    assert.ok(around, `boundary triangle ${t} is no tetrahedron's face`);
    tagged.add(faceKey(tri));
    const name = v.surfaceNames[v.triangleTag[t]];
    assert.ok(name !== undefined, `boundary triangle ${t}: tag ${v.triangleTag[t]}`);
    counts.set(name, (counts.get(name) ?? 0) + 1);
    if (around.length === 2) {
      assert.equal(name, 'wall', `triangle ${t} between two tetrahedra`);
      continue;
    }
    const [a, b, c] = [0, 1, 2].map((k) => point(v.positions, tri[k]));
    enclosed += dot(a, cross(b, c)) / 6;
  }
  for (const [k, around] of faces) {
    assert.ok(around.length <= 2, `face ${k} of ${around.length} tetrahedra`);
    if (around.length === 1) assert.ok(tagged.has(k), `untagged boundary face ${k}`);
  }
  assert.ok(Math.abs(enclosed / volume - 1) < 1e-4, `tets ${volume}, boundary ${enclosed}`);
  const surfaces = report.output.groups.filter((g) => g.dim === 2);
  assert.deepEqual(v.surfaceNames, surfaces.map((g) => g.name));
  for (const g of surfaces) assert.equal(counts.get(g.name), g.elements, g.name);
};

/** Every group of the report is named in the MSH file, and the file has
 * as many elements as the groups together. */
function checkGroupsInMsh(m) {
  const t = text(m.msh);
  for (const g of m.report.output.groups) assert.match(t, new RegExp(`^${g.dim} \\d+ "${g.name}"$`, 'm'));
  const lines = t.split('\n');
  const total = m.report.output.groups.reduce((n, g) => n + g.elements, 0);
  assert.equal(Number(lines[lines.indexOf('$Elements') + 1].split(' ')[1]), total);
}

// Closed tetrahedron as ASCII STL, one facet inside out.
const TETRA = `solid tet
facet normal 0 0 0
outer loop
vertex 0 0 0
vertex 0 1 0
vertex 1 0 0
endloop
endfacet
facet normal 0 0 0
outer loop
vertex 0 0 0
vertex 1 0 0
vertex 0 0 1
endloop
endfacet
facet normal 0 0 0
outer loop
vertex 0 0 0
vertex 0 0 1
vertex 0 1 0
endloop
endfacet
facet normal 0 0 0
outer loop
vertex 1 0 0
vertex 0 0 1
vertex 0 1 0
endloop
endfacet
endsolid tet
`;

describe('threads', () => {
  test('with a wasmBinary the single-threaded core loads, on one thread, and says why', () => {
    assert.equal(api.threads, 1);
    assert.match(api.threadsNote, /wasmBinary/);
  });

  test('the Node entry runs the threaded core on the machine\'s cores (at most 8)', async () => {
    const { createVesselmesh: createInNode } = await import('../src/node.js');
    const nodeApi = await createInNode();
    const cores = availableParallelism();
    assert.equal(nodeApi.threads, cores < 2 ? 1 : Math.min(cores, 8));
    assert.equal(nodeApi.threadsNote, cores < 2 ? 'Node reports one core' : '');
    assert.equal(nodeApi.makePhantom({}).ok, true);
  });

  test('threads takes the job option\'s range: 0 (all cores) to 256; anything else is refused', async () => {
    for (const threads of [-2, 1.5, 257, 'two']) {
      await assert.rejects(createVesselmesh({ threads }), /createVesselmesh: threads must be an integer from 0 \(all cores\) to 256, not /);
    }
    const wasmBinary = readFileSync(new URL('../dist/vesselmesh_core.wasm', import.meta.url));
    for (const threads of [0, 1, 256]) assert.equal((await createVesselmesh({ wasmBinary, threads })).threads, 1);
  });
});

describe('analyze', () => {
  test('a stray triangle far away is removed as a speck, not welded into the vessel', () => {
    const stl = api.makePhantom({ kind: 'bifurcation', voxel: 0.12 }).stl;
    const n = new DataView(stl.buffer, stl.byteOffset).getUint32(80, true);
    const bytes = new Uint8Array(stl.length + 50);
    bytes.set(stl);
    const view = new DataView(bytes.buffer);
    view.setUint32(80, n + 1, true);
    [0, 0, 1, 1e6, 0, 0, 1e6 + 1, 0, 0, 1e6, 1, 0].forEach((x, i) => view.setFloat32(stl.length + 4 * i, x, true));
    const clean = api.analyze(stl).analysis;
    const r = api.analyze(bytes);
    assert.equal(r.ok, true, r.error);
    assert.equal(r.analysis.specks_removed, 1);
    assert.equal(r.analysis.components, 1);
    assert.equal(r.analysis.vertices, clean.vertices);
    assert.equal(r.analysis.openings.length, 3);
    assert.match(r.analysis.warnings.join('\n'), /removed a small separate piece \(1 triangle, under 1% of the surface\) at \(1e\+06, 0, 0\)/);
  });

  test('a closed surface: with clip off the vessel ends proposed as cuts, cutAt and clipPlanes/clipAt open it', () => {
    const p = api.makePhantom({ kind: 'bifurcation', voxel: 0.12, noise: 0.3, openEnds: false });
    const r = api.analyze(p.stl, { clip: 'off' });
    assert.equal(r.ok, true, r.error);
    assert.equal(r.analysis.closed, true);
    assert.equal(r.analysis.openings.length, 0);
    const proposals = r.analysis.clip_proposals;
    assert.equal(proposals.length, 3);
    assert.match(r.analysis.warnings.join('\n'), /3 vessel ends were found: cut them open with clip auto \(or give clipPlanes or clipAt\)/);
    // A click 2 radii in from the first proposal, beside the vessel: the
    // cut is across the same vessel, parallel to the proposal, facing its end.
    const e = proposals[0];
    const click = e.point.map((x, k) => x - 2 * e.radius * e.normal[k] + 1.5 * e.radius * (k === 0 ? 1 : 0));
    const c = api.cutAt(click);
    assert.equal(c.ok, true, c.error);
    assert.ok(dot(c.normal, e.normal) > Math.cos((10 * Math.PI) / 180), `${c.normal} vs ${e.normal}`);
    assert.ok(Math.abs(c.radius - e.radius) < 0.15 * e.radius, `${c.radius} vs ${e.radius}`);
    assert.ok(c.areaRemoved > 0);
    // The plane as clipPlanes: one opening from a clip there; clipAt the same.
    for (const options of [{ clipPlanes: [...c.point, ...c.normal] }, { clipAt: [click] }]) {
      const cut = api.analyze(p.stl, { ...options, clip: 'off' });
      assert.equal(cut.ok, true, cut.error);
      assert.equal(cut.analysis.openings.length, 1);
      assert.equal(cut.analysis.openings[0].source, 'clip');
      assert.ok(distance(cut.analysis.openings[0].centroid, c.point) < 0.1 * c.radius);
      // The two other ends are still proposed.
      assert.equal(cut.analysis.clip_proposals.length, 2);
    }
    // By default (clip auto) every end is cut: the cut given, then the others.
    const opened = api.analyze(p.stl, { clipPlanes: [...c.point, ...c.normal] });
    assert.equal(opened.ok, true, opened.error);
    assert.deepEqual(opened.analysis.openings.map((o) => o.shape).sort(), ['blind_end', 'blind_end', 'plane']);
    assert.deepEqual(opened.analysis.clip_proposals, []);
    const bad = api.cutAt([1, 2]);
    assert.equal(bad.ok, false);
    assert.match(bad.error, /cutAt needs a point \[x, y, z\]/);
  });

  test('default options open a closed tree at every blind end; its short, wide root is the inlet', () => {
    const p = api.makePhantom({ kind: 'root', voxel: 0.15, noise: 0.3, openEnds: false });
    assert.equal(p.ok, true, p.error);
    const r = api.analyze(p.stl);
    assert.equal(r.ok, true, r.error);
    const o = r.analysis.openings;
    assert.equal(o.length, 5);
    assert.ok(o.every((x) => x.source === 'clip' && x.shape === 'blind_end'));
    assert.equal(o[0].name, 'inlet');
    assert.ok(Math.abs(o[0].radius - 1.7) < 0.17, `${o[0].radius}`);
    assert.ok(o.slice(1).every((x) => x.radius < 0.6 * o[0].radius));
    assert.match(r.analysis.warnings.join('\n'), /cut 5 vessel ends open \(clip auto.*\(a short, wide root\)/);
    // clip off: the blind ends kept and proposed, the root among them.
    const off = api.analyze(p.stl, { clip: 'off' });
    assert.equal(off.analysis.openings.length, 0);
    assert.equal(off.analysis.clip_proposals.length, 5);
    assert.equal(off.analysis.clip_proposals.filter((x) => x.short_root).length, 1);
    // A click on the root's end gives its cut, never "not a tube".
    const tip = [0, 0, -3.1];
    const c = api.cutAt(tip);
    assert.equal(c.ok, true, c.error);
    assert.ok(Math.abs(Math.abs(c.normal[2]) - 1) < 0.05, `${c.normal}`);
    assert.ok(Math.abs(c.radius - 1.7) < 0.25, `${c.radius}`);
  });

  test('fan and dome caps become openings at their rims, their shape said', () => {
    for (const [caps, noise, voxel] of [['fan', 0.3, 0.15], ['dome', 0.1, 0.1]]) {
      const p = api.makePhantom({ kind: 'bifurcation', voxel, noise, caps });
      assert.equal(p.ok, true, p.error);
      const r = api.analyze(p.stl);
      assert.equal(r.ok, true, r.error);
      assert.deepEqual(r.analysis.openings.map((o) => [o.source, o.shape]), [['cap', caps], ['cap', caps], ['cap', caps]], caps);
      assert.equal(r.analysis.caps_removed, 3);
      assert.match(r.analysis.warnings.join('\n'), /3 caps were recognised and removed/);
      // Caps kept as wall and clip off: a click on a cap cuts at its rim,
      // the plane of the opening the default makes.
      const kept = api.analyze(p.stl, { keepCaps: true, clip: 'off' });
      assert.equal(kept.analysis.openings.length, 0);
      const inlet = r.analysis.openings[0];
      const onCap = inlet.centroid.map((x, k) => x + 0.05 * inlet.radius * inlet.normal[k]);
      const c = api.cutAt(onCap);
      assert.equal(c.ok, true, c.error);
      assert.ok(Math.abs(dot(sub(c.point, inlet.centroid), inlet.normal)) < 0.05 * inlet.radius, caps);
      assert.ok(Math.abs(dot(c.normal, inlet.normal)) > Math.cos((5 * Math.PI) / 180), caps);
    }
  });

  test('a generated bifurcation: counts, openings, arrays consistent', () => {
    const p = api.makePhantom({ noise: 0.3, kind: 'bifurcation', voxel: 0.12 });
    assert.equal(p.ok, true);
    const r = api.analyze(p.stl);
    assert.equal(r.ok, true, r.error);
    const { analysis: a, surface: s } = r;
    assert.equal(a.format, 'binary STL');
    assert.equal(a.openings.length, 3);
    assert.equal(a.genus, 0);
    assert.equal(a.components, 1);
    assert.equal(a.closed, false);
    assert.equal(s.positions.length, 3 * a.vertices);
    assert.equal(s.triangles.length, 3 * a.triangles);
    assert.equal(s.quality.length, a.triangles);
    assert.ok(s.triangles.every((v) => v < a.vertices));
    assert.ok(s.quality.every((q) => q >= 0 && q <= 1));
    assert.ok(a.quality.min <= a.quality.mean && a.quality.mean <= 1);
    assert.equal(a.quality.histogram.reduce((x, y) => x + y, 0), a.triangles);
    // The openings' loops index real vertices and are listed largest first.
    for (const o of a.openings) assert.ok(o.vertices.every((v) => v < a.vertices));
    assert.ok(a.openings[0].radius >= a.openings[1].radius);
  });

  test('a dirty phantom: holes closed and listed apart from the openings; repair off keeps them', () => {
    const p = api.makePhantom({ kind: 'aneurysm', voxel: 0.12, dirty: true });
    assert.equal(p.ok, true);
    const r = api.analyze(p.stl);
    assert.equal(r.ok, true, r.error);
    const a = r.analysis;
    assert.equal(a.openings.length, 3);
    assert.ok(a.holes.length >= 5, `${a.holes.length} holes`);
    assert.ok(a.holes.every((h) => h.closed && h.perimeter > 0 && h.radius < 0.25 * h.vessel_radius));
    assert.equal(a.nonmanifold_edges, 0);
    assert.equal(a.nonmanifold_vertices, 0);
    const closed = /holes smaller than 0.25 of the local vessel radius \(holeFraction\) were closed/;
    assert.ok(a.warnings.some((w) => closed.test(w)));
    const off = api.analyze(p.stl, { repair: 'off' });
    assert.equal(off.ok, true, off.error);
    assert.ok(off.analysis.nonmanifold_edges > 0);
    assert.ok(off.analysis.holes.every((h) => !h.closed));
    // The fin's free edges (2 vertices) are a slit with its place, never an opening.
    assert.equal(off.analysis.slits.length, 1);
    assert.equal(off.analysis.slits[0].centroid.length, 3);
    assert.ok(off.analysis.openings.every((o) => o.vertices.length >= 3 && o.radius > 0));
  });

  test('a tube with a dent pushed through the opposite wall: re-surfaced by default, saying where', () => {
    const stl = dentedTubeStl();
    const r = api.analyze(ascii(stl));
    assert.equal(r.ok, true, r.error);
    assert.equal(r.analysis.self_crossings.pairs, 0);
    const [place] = r.analysis.repairs.crossings_resurfaced;
    assert.equal(place.resolved, true);
    assert.ok(distance(place.where, [-1, 0, 4]) < 0.7, `${place.where}`);
    assert.match(r.analysis.warnings.join('\n'), /the surface crossed itself at \(-?[\d.]+, .*re-surfaced there/);
    const meshed = api.mesh(ascii(stl), { layers: 0 });
    assert.equal(meshed.ok, true, meshed.error);
  });

  test('two vessels passing into each other, and damaged ends: meshed with the defaults', () => {
    for (const options of [{ kind: 'crossing', voxel: 0.15 }, { damagedEnds: true, voxel: 0.12 }]) {
      const { stl } = api.makePhantom(options);
      const r = api.mesh(stl);
      assert.equal(r.ok, true, `${JSON.stringify(options)}: ${r.error}`);
      const names = r.report.output.groups.filter((g) => g.dim === 2).map((g) => g.name);
      assert.ok(names.includes('wall') && names.includes('inlet') && names.includes('outlet_1'), `${names}`);
      const repairs = r.report.input.repairs;
      if (options.kind) assert.ok(repairs.crossings_resurfaced.every((p) => p.resolved));
      else assert.equal(repairs.damaged_ends.filter((e) => e.trimmed).length, 3);
      // Without the repair: refused, saying where.
      const off = api.mesh(stl, { repair: 'off' });
      assert.equal(off.ok, false);
      assert.match(off.error, /crosses itself at \(/);
    }
  });

  test('a tube with a dent pushed through the opposite wall, repair off: where it crosses itself, and mesh() says so', () => {
    const stl = dentedTubeStl();
    const r = api.analyze(ascii(stl), { repair: 'off' });
    assert.equal(r.ok, true, r.error);
    const c = r.analysis.self_crossings;
    assert.equal(c.checked, true);
    assert.ok(c.pairs > 0);
    assert.equal(c.place_count, 1);
    assert.ok(distance(c.places[0], [-1, 0, 4]) < 0.7, `${c.places[0]}`);
    assert.match(r.analysis.warnings.join('\n'), /the surface crosses itself at 1 place \(\d+ pairs of triangles\), at \(-?[\d.]+, /);
    const failed = api.mesh(ascii(stl), { repair: 'off' });
    assert.equal(failed.ok, false);
    const unit = r.analysis.units.unit;
    assert.match(failed.error, new RegExp(`^the input crosses itself at \\(-?[\\d.]+, -?[\\d.e-]+, [\\d.]+\\) ${unit} \\(1 place; fix it in the segmentation, or cut that part off with clipPlanes\\): `));
    // A clean surface: checked, none.
    const clean = api.analyze(api.makePhantom({ kind: 'bifurcation', voxel: 0.12 }).stl).analysis.self_crossings;
    assert.deepEqual(clean, { checked: true, pairs: 0, place_count: 0, places: [] });
  });

  test('ASCII STL of a closed tetrahedron, re-oriented outward', () => {
    const r = api.analyze(ascii(TETRA));
    assert.equal(r.ok, true, r.error);
    assert.equal(r.analysis.format, 'ASCII STL');
    assert.equal(r.analysis.vertices, 4);
    assert.equal(r.analysis.triangles, 4);
    assert.equal(r.analysis.closed, true);
    assert.equal(r.analysis.genus, 0);
    assert.equal(r.analysis.openings.length, 0);
    assert.ok(r.analysis.repairs.flipped >= 1);
  });

  test('accepts an ArrayBuffer', () => {
    const r = api.analyze(ascii(TETRA).buffer);
    assert.equal(r.ok, true, r.error);
  });

  test('bad inputs give specific errors', () => {
    const cases = [
      [new Uint8Array(0), /empty file/],
      [ascii('hello, not a mesh\n'), /not a surface file this tool reads/],
      [ascii('solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex nan 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid x\n'), /NaN/],
    ];
    const p = api.makePhantom({ noise: 0.3, voxel: 0.2 });
    cases.push([p.stl.subarray(0, 2000), /truncated binary STL/]);
    for (const [bytes, pattern] of cases) {
      const r = api.analyze(bytes);
      assert.equal(r.ok, false);
      assert.match(r.error, pattern);
    }
    assert.match(api.analyze('not bytes').error, /Uint8Array/);
    assert.match(api.analyze(ascii(TETRA), { onProgress: 3 }).error, /onProgress/);
  });

  test('progress increases to 1; returning false cancels', () => {
    const stl = api.makePhantom({ noise: 0.3, voxel: 0.15 }).stl;
    const seen = [];
    const r = api.analyze(stl, { onProgress: (f, stage) => { seen.push([f, stage]); } });
    assert.equal(r.ok, true);
    assert.ok(seen.length >= 4);
    for (let i = 1; i < seen.length; i++) assert.ok(seen[i][0] >= seen[i - 1][0]);
    assert.equal(seen.at(-1)[0], 1);
    assert.ok(seen.some(([, stage]) => stage === 'repair'));
    let calls = 0;
    const c = api.analyze(stl, { onProgress: () => ++calls < 2 });
    assert.deepEqual([c.ok, c.cancelled, c.error], [false, true, 'cancelled']);
  });
});

describe('mesh', () => {
  test('an oversampled surface is decimated before remeshing, unless decimate is off', () => {
    const fine = api.makePhantom({ kind: 'tube', voxel: 0.03 }).stl;  // about 218,000 triangles
    const r = api.mesh(fine, { size: 0.3, surfaceOnly: true });
    assert.equal(r.ok, true, r.error);
    const remesh = r.report.output.remesh;
    assert.ok(remesh.decimated_triangles > 0 && remesh.decimated_triangles < r.report.input.triangles / 8);
    // Still on the input, and as good as the seed's frontal row.
    assert.ok(remesh.fidelity.max_vertex_offset < 1e-9);
    assert.ok(r.report.output.quality.min > 0.55);
    const off = api.mesh(fine, { size: 0.3, surfaceOnly: true, decimate: 'off' });
    assert.equal(off.ok, true, off.error);
    assert.equal(off.report.output.remesh.decimated_triangles, 0);
    const bad = api.mesh(fine, { size: 0.3, decimate: true });
    assert.equal(bad.ok, false);
    assert.match(bad.error, /decimate/);
  });

  test('threads is accepted (one thread in this build), changes nothing, and is checked', () => {
    const stl = api.makePhantom({ noise: 0.3, voxel: 0.15 }).stl;
    const plain = api.mesh(stl, { surfaceOnly: true });
    const two = api.mesh(stl, { surfaceOnly: true, threads: 2 });
    assert.equal(two.ok, true, two.error);
    assert.deepEqual(two.msh, plain.msh);
    assert.equal(api.analyze(stl, { threads: 4 }).ok, true);
    const bad = api.mesh(stl, { threads: -1 });
    assert.equal(bad.ok, false);
    assert.match(bad.error, /threads needs an integer from 0 \(all cores\) to 256/);
  });

  const countElements = (msh) => {
    const lines = text(msh).split('\n');
    const i = lines.indexOf('$Elements');
    return lines[i + 1].split(' ');
  };

  const groupNames = (r) => r.report.output.groups.map((g) => `${g.dim} ${g.name}`);
  const groupTotal = (r) => r.report.output.groups.reduce((n, g) => n + g.elements, 0);

  test('MSH 4.1 by default: wall, caps and lumen groups, every element', () => {
    const stl = api.makePhantom({ noise: 0.3, kind: 'tube', voxel: 0.15 }).stl;
    const r = api.mesh(stl);
    assert.equal(r.ok, true, r.error);
    const t = text(r.msh);
    assert.ok(t.startsWith('$MeshFormat\n4.1 0 8\n'));
    assert.ok(t.includes('2 1 "wall"'));
    assert.deepEqual(groupNames(r), ['2 wall', '2 inlet', '2 outlet_1', '3 lumen']);
    const triangles = r.report.output.triangles;
    assert.equal(r.report.output.groups[0].elements, triangles);
    assert.equal(Number(countElements(r.msh)[1]), groupTotal(r));
    assert.equal(r.surface.triangles.length, 3 * triangles);
  });

  test('MSH 2.2 on request; bad version refused', () => {
    const stl = ascii(TETRA);
    const r = api.mesh(stl, { mshVersion: '2.2', remesh: false });
    assert.equal(r.ok, true, r.error);
    assert.ok(text(r.msh).startsWith('$MeshFormat\n2.2 0 8\n'));
    // A closed surface has no caps: the 4 wall triangles and the lumen.
    assert.deepEqual(groupNames(r), ['2 wall', '3 lumen']);
    assert.equal(countElements(r.msh)[0], String(groupTotal(r)));
    assert.equal(r.volume.tets.length / 4, r.report.output.volume.tetrahedra);
    assert.equal(api.mesh(stl, { mshVersion: '3' }).error, 'mshVersion needs 4.1 or 2.2');
  });

  test('several components refused unless the largest is kept; small pieces removed as specks', () => {
    const a = api.makePhantom({ noise: 0.3, kind: 'tube', voxel: 0.2 }).stl;
    const b = api.makePhantom({ noise: 0.3, kind: 'tube', voxel: 0.25, scale: 0.8 }).stl;
    const tet = api.analyze(ascii(TETRA));
    assert.equal(tet.ok, true);
    const count = (stl) => new DataView(stl.buffer, stl.byteOffset).getUint32(80, true);
    /** The binary STL of a's triangles, then `extra` [x0 y0 z0 ...] triangles moved by 50. */
    const append = (extra) => {
      const n = count(a);
      const out = new Uint8Array(a.length + (extra.length / 9) * 50);
      out.set(a);
      const view = new DataView(out.buffer);
      view.setUint32(80, n + extra.length / 9, true);
      for (let t = 0; t < extra.length / 9; t++)
        for (let i = 0; i < 9; i++) view.setFloat32(a.length + 50 * t + 12 + 4 * i, extra[9 * t + i] + 50, true);
      return out;
    };
    // A second vessel: refused, or only the largest kept.
    const other = [];
    for (let t = 0; t < count(b); t++)
      for (let i = 0; i < 9; i++) other.push(new DataView(b.buffer, b.byteOffset).getFloat32(84 + 50 * t + 12 + 4 * i, true));
    const both = append(other);
    const refused = api.mesh(both);
    assert.equal(refused.ok, false);
    assert.match(refused.error, /2 connected components/);
    const kept = api.mesh(both, { largestComponentOnly: true, remesh: false });
    assert.equal(kept.ok, true, kept.error);
    assert.equal(kept.report.output.triangles, count(a));
    // A tetrahedron beside it: a speck, removed with a warning.
    const { positions, triangles } = tet.surface;
    const speck = [];
    for (const v of triangles) speck.push(positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]);
    const withSpeck = api.mesh(append(speck), { remesh: false, surfaceOnly: true });
    assert.equal(withSpeck.ok, true, withSpeck.error);
    assert.equal(withSpeck.report.output.triangles, count(a));
    assert.match(withSpeck.report.warnings.join('\n'), /removed a small separate piece \(4 triangles/);
  });
});

describe('mesh: surface remeshing', () => {
  const stl = () => api.makePhantom({ kind: 'bifurcation', voxel: 0.1, noise: 0.3 }).stl;

  test('uniform size keeps the topology and gives quality triangles of size h', () => {
    const r = api.mesh(stl(), { size: 0.15 });
    assert.equal(r.ok, true, r.error);
    const out = r.report.output;
    assert.ok(out.remesh.patches > 1);
    assert.equal(out.genus, 0);
    assert.equal(out.openings, 3);
    assert.ok(out.quality.min > 0.3, `min ${out.quality.min}`);
    assert.ok(out.quality.mean > 0.9, `mean ${out.quality.mean}`);
    // Median edge length within 10% of h.
    const { positions: p, triangles: t } = r.surface;
    const lengths = [];
    for (let i = 0; i < t.length; i += 3) {
      for (let c = 0; c < 3; c++) {
        const a = 3 * t[i + c], b = 3 * t[i + ((c + 1) % 3)];
        lengths.push(Math.hypot(p[a] - p[b], p[a + 1] - p[b + 1], p[a + 2] - p[b + 2]));
      }
    }
    lengths.sort((x, y) => x - y);
    const median = lengths[lengths.length >> 1];
    assert.ok(Math.abs(median / 0.15 - 1) < 0.1, `median edge ${median}`);
  });

  test('every parametrization and 2D mesher works; radius-adaptive is the default', () => {
    // The surface alone: harmonic and Floater maps (for comparison) can leave
    // folds that the boundary layer refuses (see 'mesh: boundary layers').
    for (const param of ['lscm', 'harmonic', 'floater']) {
      for (const mesher2d of ['frontal', 'delaunay', 'adapt']) {
        const r = api.mesh(stl(), { size: 0.2, param, mesher2d, surfaceOnly: true });
        assert.equal(r.ok, true, `${param}/${mesher2d}: ${r.error}`);
        assert.equal(r.report.output.openings, 3);
      }
    }
    const adaptive = api.mesh(stl(), { perCircumference: 20, surfaceOnly: true });
    assert.equal(adaptive.ok, true, adaptive.error);
    assert.ok(adaptive.report.output.remesh.size.max > adaptive.report.output.remesh.size.min);
  });

  test('fidelity: far input vertices pinned by default, none with 0; bad values refused', () => {
    const bumpy = api.makePhantom({ kind: 'bifurcation', voxel: 0.1, noise: 0.1 }).stl;
    const on = api.mesh(bumpy, { size: 0.3, surfaceOnly: true });
    const off = api.mesh(bumpy, { size: 0.3, surfaceOnly: true, fidelity: 0 });
    assert.equal(on.ok, true, on.error);
    assert.equal(off.ok, true, off.error);
    const a = on.report.output.remesh.fidelity;
    const b = off.report.output.remesh.fidelity;
    assert.ok(a.pinned_vertices > 0, JSON.stringify(a));
    assert.equal(b.pinned_vertices, 0);
    assert.ok(a.input_gap_vertices < b.input_gap_vertices, `${a.input_gap_vertices} vs ${b.input_gap_vertices}`);
    assert.equal(on.report.output.openings, 3);
    assert.match(api.mesh(bumpy, { fidelity: 2 }).error, /^fidelity needs a fraction of h in \[0, 1\]/);
  });

  test('bad options are refused with the JS option name', () => {
    assert.match(api.mesh(stl(), { size: -1 }).error, /^size needs a positive length/);
    assert.match(api.mesh(stl(), { perCircumference: 2 }).error, /^perCircumference needs/);
    assert.match(api.mesh(stl(), { mesher2d: 'quad' }).error, /mesher2d needs frontal, delaunay or adapt/);
    assert.match(api.mesh(stl(), { param: 'x' }).error, /param needs lscm, harmonic or floater/);
    assert.match(api.mesh(stl(), { foo: 1 }).error, /unknown option 'foo'/);
    assert.match(api.mesh(stl(), { size: NaN }).error, /^size needs a positive length/);
    assert.match(api.mesh(stl(), { size: '0.1' }).error, /^size must be a number$/);
    assert.match(api.mesh(stl(), { remesh: 'yes' }).error, /remesh must be true or false/);
  });
});

describe('mesh: volume', () => {
  let stl;
  let openings;
  let r; // the default mesh of the bifurcation phantom
  before(() => {
    stl = api.makePhantom({ kind: 'bifurcation', voxel: 0.1, noise: 0.3 }).stl;
    openings = api.analyze(stl).analysis.openings;
    r = api.mesh(stl);
  });

  /** Centroid of the boundary triangles tagged `name`. */
  const tagCentroid = (v, name) => {
    const tag = v.surfaceNames.indexOf(name);
    const c = [0, 0, 0];
    let n = 0;
    v.triangleTag.forEach((g, t) => {
      if (g !== tag) return;
      for (let k = 0; k < 3; k++) point(v.positions, v.triangles[3 * t + k]).forEach((x, d) => (c[d] += x / 3));
      n++;
    });
    return c.map((x) => x / n);
  };

  test('default: groups wall, inlet, outlet_1, outlet_2, lumen in the report and the MSH', () => {
    assert.equal(r.ok, true, r.error);
    const out = r.report.output;
    assert.deepEqual(
      out.groups.map((g) => [g.dim, g.name]),
      [[2, 'wall'], [2, 'inlet'], [2, 'outlet_1'], [2, 'outlet_2'], [3, 'lumen']],
    );
    assert.deepEqual(out.caps.map((c) => c.name), ['inlet', 'outlet_1', 'outlet_2']);
    // Each opening's group is its cap and the layer's ring in the cap plane:
    // 2 triangles per rim edge and layer (4 layers by default).
    let ring = 0;
    for (const c of out.caps) {
      const group = out.groups.find((g) => g.name === c.name).elements;
      assert.ok(group > c.triangles, c.name);
      assert.equal((group - c.triangles) % 8, 0, c.name);
      ring += group - c.triangles;
    }
    assert.equal(ring, 2 * 4 * rimEdges(r.surface.triangles));
    assert.equal(out.groups.at(-1).elements, out.volume.tetrahedra);
    checkGroupsInMsh(r);
    // The wall surface is still returned, and is the wall group.
    assert.equal(r.surface.triangles.length, 3 * out.groups[0].elements);
  });

  test('capped and closed models mesh with the default options: wall, inlet, outlets, lumen, valid', () => {
    for (const [options, openings] of [
      [{ kind: 'bifurcation', voxel: 0.15, noise: 0.1, caps: 'dome' }, 3],
      [{ kind: 'bifurcation', voxel: 0.15, noise: 0.3, caps: 'fan' }, 3],
      [{ kind: 'root', voxel: 0.15, noise: 0.3, openEnds: false }, 5],
    ]) {
      const p = api.makePhantom(options);
      assert.equal(p.ok, true, p.error);
      const m = api.mesh(p.stl);
      assert.equal(m.ok, true, m.error);
      const names = m.report.output.groups.map((g) => g.name);
      const outlets = Array.from({ length: openings - 1 }, (_, k) => `outlet_${k + 1}`);
      assert.deepEqual(names, ['wall', 'inlet', ...outlets, 'lumen'], JSON.stringify(options));
      checkVolume(m.volume, m.report);
      checkGroupsInMsh(m);
    }
  });

  test('default: volume arrays consistent, every tetrahedron positive', () => {
    const v = r.volume;
    const out = r.report.output.volume;
    const nv = v.positions.length / 3;
    const nt = v.tets.length / 4;
    assert.ok(v.positions instanceof Float32Array && v.tets instanceof Uint32Array);
    assert.equal(nv, out.vertices);
    assert.equal(nt, out.tetrahedra);
    assert.ok(nt > 1000);
    assert.ok(v.tets.every((i) => i < nv));
    assert.equal(v.tetQuality.length, nt);
    assert.ok(v.tetQuality.every((q) => q > 0 && q <= 1));
    assert.equal(v.tetRegion.length, nt);
    assert.deepEqual(v.regionNames, ['lumen', '', '']);
    assert.ok(v.tetRegion.every((g) => g === 0));
    assert.ok(out.quality.min > 0 && out.quality.min <= out.quality.mean);
    assert.equal(out.quality.histogram.length, 20);
    assert.equal(out.quality.histogram.reduce((x, y) => x + y, 0), nt);
    checkVolume(v, r.report);
    // The default inlet is the largest opening.
    const caps = r.report.output.caps;
    assert.ok(distance(caps[0].centroid, openings[0].centroid) < 0.5 * openings[0].radius);
    assert.ok(distance(tagCentroid(v, 'inlet'), openings[0].centroid) < 0.5 * openings[0].radius);
  });

  test('default: 4 boundary layers (tetPart 1) on the wall, the core apart', () => {
    const v = r.volume;
    const out = r.report.output.volume;
    const nt = v.tets.length / 4;
    const wallTriangles = r.report.output.triangles;
    assert.ok(v.tetPart instanceof Uint8Array);
    assert.equal(v.tetPart.length, nt);
    const parts = partCounts(v);
    // Every layer is one prism per wall triangle, split into 3 tetrahedra.
    assert.deepEqual(parts, [nt - 3 * 4 * wallTriangles, 3 * 4 * wallTriangles, 0]);
    assert.ok(parts[0] > 0);
    // Each wall triangle is the face of one layer tetrahedron (the first layer).
    const tag = v.surfaceNames.indexOf('wall');
    const faces = tetsByFace(v);
    v.triangleTag.forEach((g, b) => {
      if (g !== tag) return;
      const around = faces.get(faceKey(v.triangles.subarray(3 * b, 3 * b + 3)));
      assert.deepEqual(around.map((t) => v.tetPart[t]), [1], `wall triangle ${b}`);
    });
    // The core's gamma_t apart (the layer's tetrahedra are flat by design).
    const core = out.core_quality;
    assert.equal(core.count, parts[0]);
    assert.equal(core.histogram.reduce((x, y) => x + y, 0), parts[0]);
    assert.ok(core.min >= out.quality.min && core.mean > out.quality.mean);
    let min = 1;
    v.tetPart.forEach((p, t) => p === 0 && (min = Math.min(min, v.tetQuality[t])));
    assert.ok(Math.abs(min - core.min) < 1e-6, `core min ${core.min}, tets ${min}`);
    const layer = out.boundary_layer;
    assert.equal(layer.layers, 4);
    for (const key of ['reduced_area_fraction', 'thickness_within_10pct', 'min_factor', 'mean_factor']) {
      assert.ok(layer[key] >= 0 && layer[key] <= 1, `${key} ${layer[key]}`);
    }
    assert.ok(layer.front_quality_min > 0);
    assert.equal(out.vessel_wall, undefined);
    assert.ok(out.seconds.layers > 0);
  });

  test('surfaceOnly: the wall alone, no volume', () => {
    const s = api.mesh(stl, { surfaceOnly: true });
    assert.equal(s.ok, true, s.error);
    assert.equal(s.volume, undefined);
    assert.deepEqual(s.report.output.groups, [
      { dim: 2, tag: 1, name: 'wall', elements: s.report.output.triangles },
    ]);
    assert.ok(!s.report.output.caps?.length);
    assert.ok(!s.report.output.volume);
    const t = text(s.msh);
    assert.ok(t.includes('"wall"'));
    assert.ok(!t.includes('"inlet"') && !t.includes('"lumen"'));
  });

  test('inlet: 2 caps the second opening as the inlet', () => {
    const m = api.mesh(stl, { inlet: 2, coreSize: 0.5 });
    assert.equal(m.ok, true, m.error);
    const caps = m.report.output.caps;
    assert.equal(caps[0].name, 'inlet');
    assert.ok(distance(caps[0].centroid, openings[1].centroid) < 0.5 * openings[1].radius);
    assert.ok(distance(tagCentroid(m.volume, 'inlet'), openings[1].centroid) < 0.5 * openings[1].radius);
    // The default inlet (the largest opening) is now an outlet.
    const was = caps.find((c) => distance(c.centroid, openings[0].centroid) < 0.5 * openings[0].radius);
    assert.match(was.name, /^outlet_\d$/);
    assert.deepEqual(m.report.output.groups.map((g) => g.name), ['wall', 'inlet', 'outlet_1', 'outlet_2', 'lumen']);
  });

  test('progress goes through the volume stages; returning false there cancels', () => {
    const small = api.makePhantom({ noise: 0.3, kind: 'tube', voxel: 0.2 }).stl;
    const stages = [];
    const m = api.mesh(small, { onProgress: (f, stage) => void stages.push(stage) });
    assert.equal(m.ok, true, m.error);
    assert.ok(stages.includes('caps') && stages.includes('tetrahedra'), stages.join(','));
    assert.equal(stages.at(-1), 'done');
    const c = api.mesh(small, { onProgress: (f, stage) => stage !== 'tetrahedra' });
    assert.deepEqual([c.ok, c.cancelled], [false, true]);
  });

  test('the worker moves every typed array of the result, each buffer once', () => {
    const m = api.mesh(stl, { size: 0.3 });
    assert.equal(m.ok, true, m.error);
    const list = transferables(m);
    const arrays = [m.msh, ...Object.values(m.surface), ...Object.values(m.volume)].filter((a) =>
      ArrayBuffer.isView(a),
    );
    // msh; surface positions, triangles, quality; volume positions, tets,
    // tetQuality, tetRegion, tetPart, triangles, triangleTag, across.
    assert.equal(arrays.length, 12);
    assert.ok(list.includes(m.volume.tetPart.buffer));
    assert.equal(new Set(list).size, list.length);
    for (const a of arrays) assert.ok(list.includes(a.buffer));
    const tets = m.volume.tets.length;
    const moved = structuredClone(m, { transfer: list });
    assert.ok(arrays.every((a) => a.length === 0)); // detached: moved, not copied
    assert.deepEqual(moved.volume.surfaceNames, ['wall', 'inlet', 'outlet_1', 'outlet_2']);
    assert.equal(moved.volume.tets.length, tets);
    assert.deepEqual(transferables({ ok: false, error: 'x' }), []);
  });

  test('a size whose tetrahedra do not fit the module\'s memory is refused before meshing, with the size that fits', () => {
    // 4 GB hold about 14M tetrahedra at 300 bytes each; h = 0.005 on the
    // bifurcation is about 2.6e9, beyond any element budget given.
    const started = performance.now();
    let stages = 0;
    const m = api.mesh(stl, { size: 0.005, maxElements: 1e9, onProgress: (f, stage) => void (stages += /remesh|meshing|volume|tetra/.test(stage)) });
    assert.ok(performance.now() - started < 10_000, 'refused before meshing');
    assert.equal(stages, 0);
    assert.equal(m.ok, false);
    assert.equal(m.kind, 'bad_option');
    assert.equal(m.option, 'size');
    assert.match(m.error, /^size makes about [\d.]+e\+09 tetrahedra in the lumen, more than fit in the mesher's memory \(4\.\d GB free: about 1\.4e\+07 tetrahedra at 300 bytes each\): ask for larger elements \(size 0\.0\d+ fits\)$/);
    assert.doesNotMatch(m.error, /maxElements|--|vesselmesh/);
    assert.equal(m.remedy.action, 'coarser');
    assert.ok(m.remedy.value > 0.005 && m.error.includes(`(size ${Number(m.remedy.value.toPrecision(3))} fits)`), m.error);
  });

  test('a core call that throws stops this API object, said as out of memory for a memory error; a new one meshes', async () => {
    // A RangeError thrown through the core's frames, as a failed memory
    // growth throws it (a real one: Emscripten's "Aborted(OOM)", which a
    // 4 GB module reaches only after minutes).
    const own = await createVesselmesh({ wasmBinary: readFileSync(new URL('../dist/vesselmesh_core.wasm', import.meta.url)) });
    const m = own.mesh(stl, {
      onProgress: () => {
        throw new RangeError('WebAssembly.Memory.grow(): Maximum memory size exceeded');
      },
    });
    assert.equal(m.ok, false);
    assert.equal(m.kind, 'out_of_memory');
    assert.equal(m.restart, true);
    assert.match(m.error, /^out of memory while meshing: the mesher's memory \(\d+ MB in use, at most 4096 MB\) ran out; try a coarser size \(a larger size or a smaller perCircumference\)$/);
    const after = own.makePhantom({ kind: 'tube' });
    assert.equal(after.ok, false);
    assert.equal(after.restart, true);
    assert.match(after.error, /^the mesher stopped after an earlier failure \(out of memory while meshing: .*\): create a new one \(createVesselmesh\(\)\)$/);
    // Another error is no memory's: internal.
    const other = await createVesselmesh({ wasmBinary: readFileSync(new URL('../dist/vesselmesh_core.wasm', import.meta.url)) });
    const o = other.analyze(stl, { onProgress: () => { throw new Error('a callback failed'); } });
    assert.equal(o.kind, 'internal');
    assert.match(o.error, /^internal error: the mesher stopped in analyze\(\) \(a callback failed\); please report it$/);
    // The API object the other tests use meshes on.
    assert.equal(api.makePhantom({ kind: 'tube' }).ok, true);
  });

  test('bad volume options are refused with the JS option name', () => {
    const cases = [
      [{ inlet: 0 }, /^inlet needs an opening number from 1 to 1000000 \(as the analysis lists them\)$/],
      [{ inlet: 1.5 }, /^inlet needs an opening number from 1/],
      [{ inlet: 9 }, /^inlet must be between 1 and the number of openings \(3\)$/],
      [{ coreSize: -1 }, /^coreSize needs a length >= 0/],
      [{ coreSize: 'big' }, /^coreSize must be a number$/],
      [{ surfaceOnly: 'yes' }, /^surfaceOnly must be true or false$/],
    ];
    for (const [options, pattern] of cases) {
      const m = api.mesh(stl, options);
      assert.equal(m.ok, false, JSON.stringify(options));
      assert.match(m.error, pattern);
      assert.doesNotMatch(m.error, /--|vesselmesh/);
    }
  });
});

describe('mesh: boundary layers and vessel wall', () => {
  let bifurcation;
  let tube;
  before(() => {
    bifurcation = api.makePhantom({ kind: 'bifurcation', voxel: 0.1, noise: 0.3 }).stl;
    tube = api.makePhantom({ noise: 0.3, kind: 'tube', voxel: 0.15 }).stl;
  });
  const groupsOf = (m) => m.report.output.groups.map((g) => `${g.dim} ${g.name}`);
  const group = (m, name) => m.report.output.groups.find((g) => g.name === name)?.elements;
  test('wallThickness: the vessel wall outward (tetPart 2), its groups, `wall` an interface', () => {
    const m = api.mesh(bifurcation, { wallThickness: 0.1 });
    assert.equal(m.ok, true, m.error);
    const out = m.report.output;
    assert.deepEqual(groupsOf(m), [
      '2 wall', '2 inlet', '2 outlet_1', '2 outlet_2',
      '2 outer_wall', '2 wall_inlet', '2 wall_outlet_1', '2 wall_outlet_2',
      '3 lumen', '3 vessel_wall',
    ]);
    const v = m.volume;
    const nt = v.tets.length / 4;
    const wall = out.triangles;
    // 4 layers each way, 3 tetrahedra per prism.
    assert.deepEqual(partCounts(v), [nt - 24 * wall, 12 * wall, 12 * wall]);
    assert.deepEqual(v.regionNames, ['lumen', '', 'vessel_wall']);
    v.tetPart.forEach((p, t) => assert.equal(v.tetRegion[t], p === 2 ? 2 : 0, `tet ${t}`));
    assert.equal(group(m, 'lumen'), nt - 12 * wall);
    assert.equal(group(m, 'vessel_wall'), 12 * wall);
    assert.equal(group(m, 'outer_wall'), wall);
    // The wall ring of each opening matches the layer's ring there.
    for (const c of out.caps) assert.equal(group(m, `wall_${c.name}`), group(m, c.name) - c.triangles, c.name);
    // `wall` is the interface: every wall triangle between a layer
    // tetrahedron and a vessel wall one.
    checkVolume(v, m.report);
    const faces = tetsByFace(v);
    const tag = v.surfaceNames.indexOf('wall');
    let interfaces = 0;
    v.triangleTag.forEach((g, b) => {
      if (g !== tag) return;
      const around = faces.get(faceKey(v.triangles.subarray(3 * b, 3 * b + 3)));
      assert.deepEqual(around.map((t) => v.tetPart[t]).sort(), [1, 2], `wall triangle ${b}`);
      interfaces++;
    });
    assert.equal(interfaces, wall);
    checkGroupsInMsh(m);
    for (const name of ['"vessel_wall"', '"outer_wall"', '"wall_inlet"']) assert.ok(text(m.msh).includes(name));
    const stats = out.volume.vessel_wall;
    assert.equal(stats.layers, 4);
    assert.ok(stats.thickness_within_10pct >= 0 && stats.thickness_within_10pct <= 1);
    assert.equal(out.volume.boundary_layer.layers, 4);
    assert.equal(out.volume.core_quality.count, nt - 24 * wall);
  });

  test('tagLayer: the viscous layer is its own volume group boundary_layer', () => {
    const m = api.mesh(tube, { tagLayer: true, layers: 3 });
    assert.equal(m.ok, true, m.error);
    const v = m.volume;
    const nt = v.tets.length / 4;
    const wall = m.report.output.triangles;
    assert.deepEqual(groupsOf(m), ['2 wall', '2 inlet', '2 outlet_1', '3 lumen', '3 boundary_layer']);
    assert.deepEqual(v.regionNames, ['lumen', 'boundary_layer', '']);
    assert.deepEqual(partCounts(v), [nt - 9 * wall, 9 * wall, 0]);
    v.tetPart.forEach((p, t) => assert.equal(v.tetRegion[t], p, `tet ${t}`));
    assert.equal(group(m, 'lumen'), nt - 9 * wall);
    assert.equal(group(m, 'boundary_layer'), 9 * wall);
    assert.equal(m.report.output.volume.boundary_layer.layers, 3);
    checkGroupsInMsh(m);
  });

  test('prisms: kept prisms (positive by their split) and quads at the openings, shown split', async () => {
    const m = api.mesh(tube, { prisms: true, wallThickness: 0.1, wallLayers: 2 });
    assert.equal(m.ok, true, m.error);
    const v = m.volume;
    const wall = m.report.output.triangles;
    assert.equal(v.prisms.length / 6, (4 + 2) * wall);
    assert.equal(v.prismRegion.length, v.prisms.length / 6);
    assert.ok(v.tetPart.every((p) => p === 0)); // the tets are the core's
    assert.equal(v.quadTag.length, v.quads.length / 4);
    const names = new Set(Array.from(v.quadTag, (t) => v.surfaceNames[t]));
    assert.deepEqual([...names].sort(), ['inlet', 'outlet_1', 'wall_inlet', 'wall_outlet_1']);
    // Shown as tetrahedra: every one positive, the boundary closed by the
    // triangles and the split quads.
    const { withPrismsSplit } = await import('../../web/src/prisms.js');
    const shown = withPrismsSplit(v);
    assert.equal(shown.tets.length / 4, v.tets.length / 4 + 3 * (v.prisms.length / 6));
    assert.equal(shown.triangles.length / 3, v.triangles.length / 3 + 2 * (v.quads.length / 4));
    for (let t = 0; t < shown.tets.length / 4; t++) {
      const [a, b, c, d] = [0, 1, 2, 3].map((k) => point(shown.positions, shown.tets[4 * t + k]));
      assert.ok(dot(cross(sub(b, a), sub(c, a)), sub(d, a)) > 0, `shown tetrahedron ${t}`);
    }
    const tagged = new Set();
    for (let b = 0; b < shown.triangleTag.length; b++) tagged.add(faceKey(shown.triangles.subarray(3 * b, 3 * b + 3)));
    for (const [k, around] of tetsByFace(shown)) {
      assert.ok(around.length <= 2, `face ${k} of ${around.length} tetrahedra`);
      if (around.length === 1) assert.ok(tagged.has(k), `untagged boundary face ${k}`);
    }
    assert.ok(text(m.msh).includes('"vessel_wall"'));
    assert.match(api.mesh(tube, { prisms: 'yes' }).error, /^prisms must be true or false$/);
  });

  test('sizes beyond the element budget or the memory are refused as values, never thrown', () => {
    const stl = api.makePhantom({ kind: 'tube', voxel: 0.3 }).stl;
    for (const [options, option] of [
      [{ size: 1e-30 }, 'size'],
      [{ size: 1e-10, surfaceOnly: true }, 'size'],
      [{ sizeMax: 1e-300, size: 1e-300 }, 'size'],
      [{ perCircumference: 1e6 }, 'perCircumference'],
      [{ coreSize: 1e-5 }, 'coreSize'],
    ]) {
      const r = api.mesh(stl, options);
      assert.equal(r.ok, false, JSON.stringify(options));
      assert.equal(r.kind, 'bad_option');
      assert.equal(r.option, option);
      // Tetrahedra: the memory is the limit (about 14M in 4 GB); triangles: the budget.
      assert.match(r.error, /triangles on the wall, more than the element budget \(maxElements 15000000\)|tetrahedra in the lumen, more than fit in the mesher's memory/);
    }
  });

  test('the default size is coarsened to the budget and says so; a size given is refused with one that fits', () => {
    const stl = api.makePhantom({ kind: 'bifurcation', voxel: 0.15 }).stl;
    const m = api.mesh(stl, { maxElements: 15000 });
    assert.equal(m.ok, true, m.error);
    const b = m.report.element_budget;
    assert.deepEqual([b.max_elements, b.coarsened, b.asked_per_circumference], [15000, true, 20]);
    assert.ok(b.per_circumference >= 13 && b.per_circumference < 20, `${b.per_circumference}`);
    assert.ok(b.elements <= 15000 && b.asked_elements > 15000, JSON.stringify(b));
    assert.match(
      m.report.warnings.join('\n'),
      new RegExp(`the default size \\(perCircumference 20\\) would make about .* coarsened to perCircumference ${b.per_circumference} .* ask for the finer mesh with perCircumference 20 and maxElements ${b.enough}`),
    );
    const given = api.mesh(stl, { maxElements: 15000, perCircumference: 20 });
    assert.equal(given.ok, false);
    assert.equal(given.option, 'perCircumference');
    assert.equal(given.remedy.action, 'coarser');
    assert.ok(given.remedy.value < 20);
    assert.match(given.error, new RegExp(`\\(perCircumference ${given.remedy.value} fits\\)`));
  });

  test('a surface that encloses no volume is refused as such', () => {
    // A flat disk of radius 10: a fan of 24 triangles.
    let text = 'solid disk\n';
    for (let i = 0; i < 24; i++) {
      const [a, b] = [i, i + 1].map((k) => [10 * Math.cos((k * Math.PI) / 12), 10 * Math.sin((k * Math.PI) / 12), 0]);
      text += `facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex ${a.join(' ')}\nvertex ${b.join(' ')}\nendloop\nendfacet\n`;
    }
    const disk = ascii(`${text}endsolid disk\n`);
    const a = api.analyze(disk);
    assert.equal(a.ok, true, a.error);
    assert.ok(a.analysis.enclosed_share < 0.5);
    assert.match(a.analysis.warnings.join('\n'), /the surface encloses no volume: it is a single sheet/);
    const m = api.mesh(disk);
    assert.equal(m.ok, false);
    assert.match(m.error, /^cannot mesh: the surface encloses no volume: .* e\.g\. at \(0, 0, 0\) (mm|cm|m); /);
  });

  test('a size too coarse for the vessels is refused naming the size to use', () => {
    const stl = api.makePhantom({ kind: 'bifurcation', voxel: 0.12 }).stl;
    const r = api.mesh(stl, { size: 5, layers: 0 });
    assert.equal(r.ok, false);
    assert.equal(r.kind, 'bad_option');
    assert.equal(r.option, 'size');
    assert.match(r.error, /^size 5 makes a wall that encloses [\d.]+% less volume than the input .*use size [\d.]+ or smaller \(or accept the change with maxVolumeChange [\d.]+\)$/);
    const ok = api.mesh(stl, { surfaceOnly: true });
    const f = ok.report.output.remesh.fidelity;
    assert.ok(f.volume_change < 0 && f.volume_change > -0.05, `${f.volume_change}`);
    assert.ok(Math.abs(f.output_volume / f.input_volume - 1 - f.volume_change) < 1e-9);
  });

  test('layerFractions: the cumulative heights the core grows layers by', () => {
    assert.deepEqual([...api.layerFractions({ layers: 4 }).fractions], [0, 0.25, 0.5, 0.75, 1]);
    const f = api.layerFractions({ layers: 3, growth: 2 }).fractions;
    assert.deepEqual([...f].map((x) => Number(x.toFixed(12))), [0, 1 / 7, 3 / 7, 1].map((x) => Number(x.toFixed(12))));
    assert.equal(api.layerFractions({ growth: 9 }).option, 'growth');
  });

  test('refine: a sphere bounds the size on the wall and in the volume; several are taken', () => {
    const plain = api.mesh(tube, { layers: 0 });
    const one = api.mesh(tube, { layers: 0, refine: [0, 0, 0, 1.5, 0.1] });
    assert.equal(one.ok, true, one.error);
    assert.ok(Math.abs(one.report.output.remesh.size.min - 0.1) < 1e-9);
    assert.ok(one.report.output.triangles > plain.report.output.triangles);
    assert.ok(one.report.output.volume.tetrahedra > plain.report.output.volume.tetrahedra);
    const two = api.mesh(tube, { layers: 0, refine: [[0, 0, 0, 1.5, 0.1], [0, 0, 4, 1.5, 0.1]] });
    assert.ok(two.report.output.triangles > one.report.output.triangles);
    const bad = api.mesh(tube, { refine: [0, 0, 0, -1, 0.05] });
    assert.equal(bad.ok, false);
    assert.equal(bad.option, 'refine');
    assert.match(bad.error, /^refine needs 5 numbers/);
  });

  test('layers: 0 gives no layer part; firstLayer + growth sets the heights', () => {
    const m = api.mesh(tube, { layers: 0 });
    assert.equal(m.ok, true, m.error);
    assert.ok(m.volume.tetPart.every((p) => p === 0));
    assert.deepEqual(m.volume.regionNames, ['lumen', '', '']);
    assert.equal(m.report.output.volume.boundary_layer, undefined);
    // No ring: each opening's group is its cap alone.
    for (const c of m.report.output.caps) assert.equal(group(m, c.name), c.triangles, c.name);
    assert.equal(m.report.output.volume.core_quality.count, m.volume.tets.length / 4);
    // The surfaces as written, a group each: no ring without layers.
    const surfaces = m.report.output.volume.surfaces;
    assert.deepEqual(surfaces.map((s) => s.name), ['wall', ...m.report.output.caps.map((c) => c.name)]);
    for (const s of surfaces) assert.equal(s.quality.count, group(m, s.name), s.name);
    assert.ok(surfaces.every((s) => s.ring_quality === undefined));

    const f = api.mesh(tube, { firstLayer: 0.005, growth: 1.3, layers: 5 });
    assert.equal(f.ok, true, f.error);
    assert.equal(partCounts(f.volume)[1], 15 * f.report.output.triangles);
    assert.equal(f.report.output.volume.boundary_layer.layers, 5);
    // With layers, each cap's group is its disc plus the layer's flat ring.
    for (const s of f.report.output.volume.surfaces.slice(1)) {
      assert.equal(s.quality.count + s.ring_quality.count, group(f, s.name), s.name);
      assert.ok(s.ring_quality.min < s.quality.min, s.name);
    }
    // The first layer's height: the wall's vertices to their layer-1 copies.
    // (The tets of a wall triangle's first prism have the wall vertices and
    // the first layer's.)
    const { positions: p, tets, tetPart } = f.volume;
    const wallVertices = new Set(f.volume.triangles.filter((_, i) => f.volume.triangleTag[Math.floor(i / 3)] === 0));
    let shortest = Infinity;
    for (let t = 0; t < tets.length / 4; t++) {
      if (tetPart[t] !== 1) continue;
      const q = tets.subarray(4 * t, 4 * t + 4);
      for (const a of q) {
        if (!wallVertices.has(a)) continue;
        for (const b of q) {
          if (b === a || wallVertices.has(b)) continue;
          shortest = Math.min(shortest, Math.hypot(p[3 * a] - p[3 * b], p[3 * a + 1] - p[3 * b + 1], p[3 * a + 2] - p[3 * b + 2]));
        }
      }
    }
    assert.ok(shortest <= 0.005 * 1.001 && shortest > 0.001, `first layer ${shortest}`);
  });

  test('bad layer options are refused with the JS option name', () => {
    const cases = [
      [{ layers: -1 }, /^layers needs a number of layers from 0 \(none\) to 100$/],
      [{ layers: 1.5 }, /^layers needs a number of layers from 0 \(none\) to 100$/],
      [{ layers: 101 }, /^layers needs a number of layers/],
      [{ layerThickness: 1 }, /^layerThickness needs a fraction of the local vessel radius in \(0, 1\)$/],
      [{ layerThickness: 0 }, /^layerThickness needs a fraction/],
      [{ firstLayer: 0 }, /^firstLayer needs a positive height/],
      [{ growth: 0.5 }, /^growth needs a growth ratio from 1 to 3$/],
      [{ growth: 4 }, /^growth needs a growth ratio from 1 to 3$/],
      [{ wallThickness: 0 }, /^wallThickness needs a fraction of the local vessel radius in \(0, 1\)$/],
      [{ wallLayers: 2.5 }, /^wallLayers needs a number of layers from 0 \(none\) to 100$/],
      [{ tagLayer: 1 }, /^tagLayer must be true or false$/],
    ];
    for (const [options, pattern] of cases) {
      const m = api.mesh(tube, options);
      assert.equal(m.ok, false, JSON.stringify(options));
      assert.match(m.error, pattern);
      assert.doesNotMatch(m.error, /--|vesselmesh|wall-|layer-/);
    }
  });

  test('a wall too irregular for layers: relaxed where the layer could not grow, said with the places', () => {
    // The phantom's staircase surface as it is (not remeshed) folds: the
    // wall is smoothed there and the layer grown.
    const m = api.mesh(bifurcation, { remesh: false });
    assert.equal(m.ok, true, m.error);
    const said = m.report.warnings.filter((w) => /could not grow at \(/.test(w));
    assert.equal(said.length, 1, m.report.warnings.join('\n'));
    assert.match(said[0], /the wall was smoothed there \(\d+ vertices, moved at most [\d.e-]+\)$/);
    assert.ok(m.report.output.groups.some((g) => g.name === 'lumen' && g.elements > 0));
  });
});

describe('makePhantom', () => {
  test('each kind has its openings and genus', () => {
    const expected = { tube: [2, 0], bifurcation: [3, 0], aneurysm: [3, 0], torus: [0, 1], tree: [11, 0], root: [5, 0] };
    for (const [kind, [openings, genus]] of Object.entries(expected)) {
      const p = api.makePhantom({ noise: 0.3, kind, voxel: 0.15 });
      assert.equal(p.ok, true, p.error);
      const r = api.analyze(p.stl);
      assert.equal(r.analysis.openings.length, openings, kind);
      assert.equal(r.analysis.genus, genus, kind);
    }
  });

  test('deterministic for a seed; bad options refused', () => {
    const a = api.makePhantom({ noise: 0.3, voxel: 0.2, seed: 7 });
    const b = api.makePhantom({ noise: 0.3, voxel: 0.2, seed: 7 });
    assert.deepEqual(a.stl, b.stl);
    assert.equal(api.makePhantom({ kind: 'blob' }).error, 'kind needs bifurcation, tube, aneurysm, torus, tree, crossing, outlets or root');
    assert.equal(api.makePhantom({ caps: 'cone' }).error, 'caps needs flat, fan or dome');
    assert.equal(api.makePhantom({ voxel: 0 }).error, 'voxel needs a positive voxel size');
    assert.match(api.makePhantom({ voxel: 1e-4 }).error, /too large/);
    assert.match(api.makePhantom({ seed: -1 }).error, /seed/);
  });
});
