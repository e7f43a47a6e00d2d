// Node tests of the built WebAssembly module: solver presets (`solver`),
// physical tags unique across dimensions, the first layer from a target y+
// (issue 23).
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { before, describe, test } from 'node:test';

import { createVesselmesh } from '../src/vesselmesh.js';

let api;
let tube;
before(async () => {
  const wasmBinary = readFileSync(new URL('../dist/vesselmesh_core.wasm', import.meta.url));
  api = await createVesselmesh({ wasmBinary });
  tube = api.makePhantom({ kind: 'tube', voxel: 0.15, noise: 0.3 }).stl;
});

const text = (bytes) => new TextDecoder().decode(bytes);

/** What an MSH file (4.1 or 2.2) holds: its version, [dim, tag, name] of
 * each physical group, the element types, the largest |coordinate|. */
function readMsh(msh) {
  const lines = text(msh).split('\n');
  const version = lines[lines.indexOf('$MeshFormat') + 1].split(' ')[0];
  const p = lines.indexOf('$PhysicalNames');
  const groups = lines.slice(p + 2, p + 2 + Number(lines[p + 1])).map((l) => {
    const [dim, tag, name] = l.split(' ');
    return [Number(dim), Number(tag), name.slice(1, -1)];
  });
  const types = new Set();
  let e = lines.indexOf('$Elements') + 1;
  if (version === '2.2') {
    for (const l of lines.slice(e + 1, e + 1 + Number(lines[e]))) types.add(Number(l.split(' ')[1]));
  } else {
    const blocks = Number(lines[e].split(' ')[0]);
    e++;
    for (let b = 0; b < blocks; b++) {
      const [, , type, n] = lines[e].split(' ').map(Number);
      types.add(type);
      e += n + 1;
    }
  }
  let largest = 0;
  const n = lines.indexOf('$Nodes');
  const end = lines.indexOf('$EndNodes');
  for (const l of lines.slice(n + 1, end)) {
    const xyz = l.split(' ').map(Number);
    if (xyz.length === 3 || (version === '2.2' && xyz.length === 4)) {
      for (const x of xyz.slice(-3)) largest = Math.max(largest, Math.abs(x));
    }
  }
  return { version, groups, types: [...types].sort((a, b) => a - b), largest };
}

const setting = (m, option) => m.report.preset.settings.find((s) => s.option === option);

describe('solver presets', () => {
  test('solverPresets lists the choices of the solver option', () => {
    const spec = api.optionTable.find((s) => s.js === 'solver');
    assert.deepEqual(api.solverPresets.map((p) => p.name), spec.choices);
    const foam = api.solverPresets.find((p) => p.name === 'openfoam');
    assert.deepEqual([foam.prisms, foam.format, foam.mshVersion, foam.outputUnits], [true, 'foam', '2.2', 'm']);
  });

  test("solver 'fenics': tetrahedra only in the MSH, the preset in the report", () => {
    const m = api.mesh(tube, { layers: 2, solver: 'fenics' });
    assert.equal(m.ok, true, m.error);
    assert.equal(m.format, 'msh');
    const msh = readMsh(m.msh);
    assert.equal(msh.version, '4.1');
    assert.deepEqual(msh.types, [2, 4]);
    assert.equal(m.volume.prisms, undefined);
    assert.equal(m.report.preset.solver, 'fenics');
    assert.deepEqual(setting(m, 'prisms'), { option: 'prisms', value: 'false', from: 'preset' });
  });

  test("solver 'openfoam': the native case by default; as MSH: prisms, 2.2, metres; an explicit option wins", () => {
    const c = api.mesh(tube, { layers: 2, solver: 'openfoam', units: 'mm' });
    assert.equal(c.ok, true, c.error);
    assert.deepEqual([c.format, c.fileName], ['foam', 'openfoam-case.zip']);
    assert.deepEqual([c.file[0], c.file[1]], [0x50, 0x4b]); // PK
    assert.deepEqual(setting(c, 'format'), { option: 'format', value: 'foam', from: 'preset' });
    const m = api.mesh(tube, { layers: 2, solver: 'openfoam', units: 'mm', format: 'msh' });
    assert.equal(m.ok, true, m.error);
    const msh = readMsh(m.msh);
    assert.equal(msh.version, '2.2');
    assert.deepEqual(msh.types, [2, 3, 4, 6]);
    assert.ok(m.volume.prisms.length > 0);
    // The model is in mm (coordinates of a few units); the file in metres.
    let model = 0;
    for (const x of m.volume.positions) model = Math.max(model, Math.abs(x));
    assert.ok(Math.abs(msh.largest - model / 1000) < 1e-6 * model, `${msh.largest} vs ${model} mm`);
    assert.deepEqual(setting(m, 'outputUnits'), { option: 'outputUnits', value: 'm', from: 'preset' });
    assert.match(m.report.preset.note, /wall is a wall patch/);
    // Export without meshing again: still the preset's version and unit.
    const again = api.export('msh');
    assert.equal(again.ok, true, again.error);
    assert.equal(readMsh(again.file).version, '2.2');
    assert.ok(Math.abs(readMsh(again.file).largest - msh.largest) < 1e-12);
    // Explicit options win over the preset.
    const mine = api.mesh(tube, { layers: 2, solver: 'openfoam', prisms: false, mshVersion: '4.1', format: 'msh' });
    assert.equal(mine.ok, true, mine.error);
    assert.deepEqual(readMsh(mine.msh).types, [2, 4]);
    assert.equal(readMsh(mine.msh).version, '4.1');
    assert.deepEqual(setting(mine, 'prisms'), { option: 'prisms', value: 'false', from: 'user' });
  });

  test("solver 'svfsi': a mesh-complete zip by default, format wins", () => {
    const m = api.mesh(tube, { layers: 2, solver: 'svfsi' });
    assert.equal(m.ok, true, m.error);
    assert.equal(m.format, 'mesh-complete');
    assert.equal(m.fileName, 'mesh-complete.zip');
    assert.deepEqual([m.file[0], m.file[1]], [0x50, 0x4b]); // PK
    assert.deepEqual(setting(m, 'format'), { option: 'format', value: 'mesh-complete', from: 'preset' });
    const msh = api.mesh(tube, { layers: 2, solver: 'svfsi', format: 'msh' });
    assert.equal(msh.format, 'msh');
    assert.deepEqual(setting(msh, 'format'), { option: 'format', value: 'msh', from: 'user' });
  });

  test("solver 'svfsi' with a vessel wall: fluid/ and solid/ mesh-complete folders in the zip", () => {
    const m = api.mesh(tube, { layers: 2, solver: 'svfsi', wallThickness: 0.1 });
    assert.equal(m.ok, true, m.error);
    const names = Buffer.from(m.file).toString('latin1');
    for (const path of ['fluid/mesh-complete.mesh.vtu', 'fluid/mesh-surfaces/wall.vtp', 'solid/mesh-complete.mesh.vtu', 'solid/mesh-surfaces/wall.vtp', 'solid/mesh-surfaces/outer_wall.vtp']) {
      assert.ok(names.includes(path), path);
    }
    assert.ok(!names.includes('fluid/mesh-surfaces/outer_wall.vtp'));
  });

  test('a bad solver is refused with the JS option name', () => {
    const m = api.mesh(tube, { solver: 'ansys' });
    assert.equal(m.ok, false);
    assert.equal(m.option, 'solver');
    assert.match(m.error, /^solver needs gmsh, openfoam, fenics or svfsi/);
  });
});

describe('physical tags', () => {
  test('unique across dimensions in MSH 4.1 and 2.2, the report has the same', () => {
    for (const mshVersion of ['4.1', '2.2']) {
      const m = api.mesh(tube, { layers: 2, tagLayer: true, wallThickness: 0.1, wallLayers: 2, mshVersion });
      assert.equal(m.ok, true, m.error);
      const { groups } = readMsh(m.msh);
      const tags = groups.map(([, tag]) => tag);
      assert.equal(new Set(tags).size, tags.length, JSON.stringify(groups));
      assert.deepEqual(
        groups,
        m.report.output.groups.map((g) => [g.dim, g.tag, g.name]),
      );
      const surfaces = groups.filter(([dim]) => dim === 2).map(([, tag]) => tag);
      const volumes = groups.filter(([dim]) => dim === 3).map(([, tag]) => tag);
      assert.ok(Math.max(...surfaces) < Math.min(...volumes), JSON.stringify(groups));
      assert.deepEqual(
        groups.filter(([dim]) => dim === 3).map(([, , name]) => name),
        ['lumen', 'boundary_layer', 'vessel_wall'],
      );
    }
  });
});

describe('first layer from y+', () => {
  test('firstLayerYplus with inletVelocity sets the first height, reported', () => {
    const m = api.mesh(tube, { layers: 3, growth: 1.2, firstLayerYplus: 1, inletVelocity: 0.4, units: 'mm' });
    assert.equal(m.ok, true, m.error);
    const y = m.report.first_layer_yplus;
    assert.equal(y.yplus, 1);
    assert.equal(y.inlet, 'inlet');
    assert.deepEqual([y.density, y.viscosity], [1060, 0.0035]);
    // The formula, by hand, from the reported inlet diameter (mm).
    const d = y.inlet_diameter / 1000;
    const re = (1060 * 0.4 * d) / 0.0035;
    const tau = 0.5 * 0.026 * re ** (-1 / 7) * 1060 * 0.4 ** 2;
    const height = (0.0035 / 1060) / Math.sqrt(tau / 1060);
    assert.ok(Math.abs(y.height_m - height) < 1e-12 * 1e3, `${y.height_m} vs ${height}`);
    assert.ok(Math.abs(y.height - 1000 * height) < 1e-9);
  });

  test('conflicts and missing flow values are refused with the JS option names', () => {
    const both = api.mesh(tube, { firstLayerYplus: 1, inletVelocity: 0.4, firstLayer: 0.01 });
    assert.equal(both.ok, false);
    assert.equal(both.option, 'firstLayerYplus');
    assert.match(both.error, /firstLayerYplus and firstLayer both set the first layer's height/);
    const noVelocity = api.mesh(tube, { firstLayerYplus: 1 });
    assert.equal(noVelocity.option, 'firstLayerYplus');
    assert.match(noVelocity.error, /inletVelocity/);
    const alone = api.mesh(tube, { viscosity: 0.004 });
    assert.equal(alone.option, 'viscosity');
  });
});
