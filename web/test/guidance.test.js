// Node tests of how the page leads to a mesh: core messages in the page's
// words (web/src/words.js), remedies read from failures (remedies.js), the
// verdict on a mesh (verdict.js), side effects of a preparation change
// (side-effects.js), the openings' warnings (opening-check.js), the unit
// question (units.js), the places repaired (repair-places.js), a solver
// preset's settings (solver-preset.js).
import assert from 'node:assert/strict';
import { describe, test } from 'node:test';

import { openingWarnings } from '../src/opening-check.js';
import { letter, repairPlaces, saidAsRepair } from '../src/repair-places.js';
import { crossingRemedy, fittingSize, placesIn, preparesAgain, remedyLabel, remedyOf } from '../src/remedies.js';
import { sideEffects, sideEffectText } from '../src/side-effects.js';
import { presetSettingText } from '../src/solver-preset.js';
import { unitsQuestion, withUnitGuess } from '../src/units.js';
import { inputQualityNote, LIMITS, meshVerdict, placesBelow } from '../src/verdict.js';
import { inPageWords, namesApiOption } from '../src/words.js';

// Messages as today's core phrases them for the JS API.
const FOLDED =
  'meshing a patch of 12 input triangles near (1.23456, -2.5, 3.75e-05) failed after 3 splits: no front; ' +
  'the surface is too folded there for the size: smooth it (smooth 10), give a smaller size, ' +
  'or turn crease detection off (featureAngle 180)';
const BUDGET_WALL =
  'perCircumference makes about 1.32e+04 triangles on the wall, more than the element budget (maxElements 1000) allows: ask for larger elements';
const BUDGET_TETS =
  'size makes about 7.65e+03 tetrahedra in the lumen, more than the element budget (maxElements 1000) allows: ask for larger elements';
const MEMORY =
  "size makes about 5.15e+09 tetrahedra in the lumen, more than fit in the mesher's memory (4.3 GB free: about 1.4e+07 tetrahedra at 300 bytes each): ask for larger elements (size 0.03 fits)";
const CROSSING =
  'the input crosses itself at (26.9164, 23.5701, 27.4715) mm (1 place; fix it in the segmentation, or cut that part off with clipPlanes): remeshing failed';
const LAYER = 'boundary layer: fronts collide at (1, 2, 3) (a wall too irregular for layers: remesh it, or use layers 0)';
const CLOSED =
  'the surface is closed: it has no opening to be an inlet or outlet; 3 vessel ends were found: cut them open with clip auto (or give clipPlanes or clipAt)';

describe('messages in the page’s words', () => {
  test('no API option name is left, and the controls are named instead', () => {
    for (const m of [FOLDED, BUDGET_WALL, BUDGET_TETS, CROSSING, LAYER, CLOSED]) {
      assert.ok(namesApiOption(m), `the raw message names an option: ${m}`);
      const words = inPageWords(m, { unit: 'mm', scale: 50 });
      assert.ok(!namesApiOption(words), words);
      assert.doesNotMatch(words, /\b(smooth \d|featureAngle|clipPlanes|clipAt|maxElements|clip auto|layers 0\))/);
    }
    assert.match(inPageWords(FOLDED), /Smoothing: 10 passes/);
    assert.doesNotMatch(inPageWords(FOLDED), /crease/);
    assert.match(inPageWords(BUDGET_WALL), /^N \(edges per circumference\) makes about/);
    assert.match(inPageWords(BUDGET_WALL), /\(1,000 elements\)/);
    assert.match(inPageWords(BUDGET_TETS), /^The edge length h makes/);
    assert.match(inPageWords(MEMORY, { unit: 'mm' }), /^The edge length h makes about 5\.15e\+09 tetrahedra .*: ask for larger elements \(h = 0\.03 mm fits\)$/);
    assert.match(inPageWords(MEMORY.replace('size 0.03', 'coreSize 0.03'), { unit: 'cm' }), /\(the core size = 0\.03 cm fits\)$/);
    assert.match(inPageWords(LAYER), /Layers 0 \(no boundary layer\)/);
    assert.match(inPageWords(CLOSED), /the proposed cuts \(or add your own\)/);
  });

  test('coordinates get 4 significant digits and the unit, lengths and areas their unit', () => {
    assert.match(inPageWords(FOLDED, { unit: 'mm', scale: 100 }), /near \(1\.235, -2\.5, 0\) mm failed/);
    // A unit already written is not doubled.
    assert.match(inPageWords(CROSSING, { unit: 'mm' }), /at \(26\.92, 23\.57, 27\.47\) mm \(1 place/);
    const cut = 'cut by the plane at (1, 2, 3): an opening at (4, 5, 6) of radius 1.25 (158.7 of area removed)';
    assert.equal(
      inPageWords(cut, { unit: 'cm' }),
      'cut by the plane at (1, 2, 3) cm: an opening at (4, 5, 6) cm of radius 1.25 cm (158.7 cm² of area removed)',
    );
  });
});

describe('remedies', () => {
  test('the core’s remedy wins; an unknown action is not offered', () => {
    const given = { action: 'trim_end', places: [[1, 2, 3]], value: 0 };
    assert.deepEqual(remedyOf({ error: FOLDED, remedy: given }), given);
    assert.equal(remedyOf({ error: 'something', remedy: { action: 'dance', places: [], value: 0 } }), null);
  });

  test('read from the messages the core gives no remedy for: smoothing, a crossing left, closed', () => {
    assert.deepEqual(remedyOf({ error: FOLDED }), { action: 'smooth', places: [[1.23456, -2.5, 3.75e-5]], value: 10 });
    assert.deepEqual(remedyOf({ error: CROSSING }), { action: 'cut_here', places: [[26.9164, 23.5701, 27.4715]], value: 0 });
    const ends = [[0, 0, 1], [0, 0, 9]];
    assert.deepEqual(remedyOf({ error: CLOSED }, { proposals: ends }), { action: 'cut_here', places: ends, value: 0 });
    assert.equal(remedyOf({ error: CLOSED }), null, 'closed, nothing proposed: no cut to offer');
    assert.equal(remedyOf({ error: 'Opening 2: names cannot be wall' }), null);
    assert.equal(remedyOf({ error: 'x', cancelled: true }), null);
  });

  test('the refusals the core gives a remedy for are not read from their message', () => {
    // Layers, repairs and pieces: the core's remedy only (none: no button).
    assert.equal(remedyOf({ error: LAYER }), null);
    const nonManifold = 'cannot mesh: the surface has 4 non-manifold edges (…), e.g. near (1, 2, 3); split them into manifold sheets with repair auto';
    assert.equal(remedyOf({ error: nonManifold }), null);
    assert.equal(remedyOf({ error: 'cannot mesh: the surface has 2 connected components' }), null);
    const layer = { error: LAYER, remedy: { action: 'no_layers', places: [[1, 2, 3]], value: 0 } };
    assert.deepEqual(remedyOf(layer), layer.remedy);
    // A crossing with repair off: the core says to repair, not to cut.
    const repair = { action: 'repair', places: [[26.9164, 23.5701, 27.4715]], value: 0 };
    assert.deepEqual(remedyOf({ error: CROSSING, remedy: repair }), repair);
    assert.equal(remedyLabel(repair), 'Repair the surface');
  });

  test('a self-crossing by an opening is a damaged end: one trim an end', () => {
    const openings = [{ centroid: [0, 0, 6], radius: 1 }, { centroid: [0, 0, -6], radius: 1 }];
    const near = [[0.1, 0, 5.6], [-0.1, 0.2, 5.5]];
    assert.deepEqual(remedyOf({ error: CROSSING.replace('(26.9164, 23.5701, 27.4715)', '(0.1, 0, 5.6)') }, { openings }), {
      action: 'trim_end',
      places: [[0.1, 0, 5.6]],
      value: 0,
    });
    assert.equal(remedyLabel(crossingRemedy(near, openings)), 'Trim the damaged end');
    assert.deepEqual(crossingRemedy([[0.1, 0, 5.6], [0, 0, -5.8]], openings).places.length, 2);
    assert.equal(crossingRemedy([[0, 0, 0]], openings).action, 'cut_here', 'in the middle of a vessel: cut there');
    const defect = [...openings, { centroid: [0, 0, 0.1], radius: 1e-9 }];
    assert.equal(crossingRemedy([[0, 0, 0]], defect).action, 'cut_here', 'a tiny defect loop is no vessel end');
  });

  test('a coarser size that fits the budget: N as the square root, h by the element kind', () => {
    const n = fittingSize(BUDGET_WALL, { mode: 'perCircumference', value: 40 });
    assert.equal(n.mode, 'perCircumference');
    // 1.32e4 triangles at N = 40 for a budget of 900: N <= 40 / sqrt(14.67) = 10.4.
    assert.equal(n.value, 10);
    const h = fittingSize(BUDGET_TETS, { mode: 'size', value: 0.35 });
    // 7.65e3 tetrahedra for 900: h x (8.5)^(1/3) = 0.71.
    assert.equal(h.value, 0.71);
    assert.equal(fittingSize('something else', { mode: 'size', value: 1 }), null);
    const remedy = remedyOf({ error: BUDGET_TETS, option: 'size' }, { size: { mode: 'size', value: 0.35 } });
    assert.equal(remedy.action, 'coarser');
    assert.equal(remedyLabel(remedy, { unit: 'mm' }), 'Use a coarser size (h = 0.71 mm)');
  });

  test('labels in the page’s words; which remedies prepare again', () => {
    assert.equal(remedyLabel({ action: 'trim_end', places: [[0, 0, 0]] }), 'Trim the damaged end');
    assert.equal(remedyLabel({ action: 'cut_here', places: [[0, 0, 0], [1, 1, 1]] }), 'Cut at these 2 places');
    assert.equal(remedyLabel({ action: 'no_layers' }), 'Mesh without layers here');
    assert.equal(remedyLabel({ action: 'smooth', value: 10 }), 'Smooth the surface (10 passes)');
    assert.equal(remedyLabel({ action: 'coarser', value: 12, mode: 'perCircumference' }), 'Use a coarser size (N = 12)');
    assert.equal(preparesAgain({ action: 'trim_end' }), true);
    assert.equal(preparesAgain({ action: 'coarser' }), false);
    assert.deepEqual(placesIn('at (1, 2, 3) and (-4.5, 5e-3, 6)'), [[1, 2, 3], [-4.5, 0.005, 6]]);
  });
});

/** A mesh() result of `tets` (list of [quality, part, centroid]) and a wall
 * of triangles (list of [quality, centroid]), as the page gets it. */
function fakeResult({ tets = [], triangles = [], layer = null, volumeChange = -0.01, warnings = [] }) {
  const positions = [];
  const tetIndex = [];
  for (const [, , c] of tets) {
    const v = positions.length / 3;
    for (let k = 0; k < 4; k++) positions.push(...c);
    tetIndex.push(v, v + 1, v + 2, v + 3);
  }
  const wall = [];
  const triIndex = [];
  for (const [, c] of triangles) {
    const v = wall.length / 3;
    for (let k = 0; k < 3; k++) wall.push(...c);
    triIndex.push(v, v + 1, v + 2);
  }
  return {
    report: {
      warnings,
      output: {
        triangles: triangles.length,
        groups: [{ name: 'wall', elements: triangles.length }, { name: 'lumen', elements: tets.length }],
        remesh: { fidelity: { volume_change: volumeChange } },
        volume: { tetrahedra: tets.length, ...(layer && { boundary_layer: layer }) },
      },
    },
    volume: {
      positions: new Float32Array(positions),
      tets: new Uint32Array(tetIndex),
      tetQuality: new Float32Array(tets.map(([q]) => q)),
      tetPart: new Uint8Array(tets.map(([, p]) => p)),
    },
    surface: { positions: new Float32Array(wall), triangles: new Uint32Array(triIndex), quality: new Float32Array(triangles.map(([q]) => q)) },
  };
}

describe('the verdict on a mesh', () => {
  const goodLayer = { layers: 4, thickness_within_10pct: 0.97, reduced_area_fraction: 0.02 };

  test('a good mesh is ready for CFD, its worst elements placed', () => {
    const result = fakeResult({
      tets: [[0.5, 0, [0, 0, 0]], [0.3, 0, [5, 5, 5]], [0.01, 1, [9, 9, 9]]], // a flat layer element does not count
      triangles: [[0.9, [0, 0, 0]], [0.6, [1, 1, 1]]],
      layer: goodLayer,
    });
    const v = meshVerdict(result, { unit: 'mm', scale: 10 });
    assert.equal(v.ready, true);
    assert.equal(v.title, 'Ready for CFD');
    assert.deepEqual(v.items.map((i) => i.level), ['ok', 'ok', 'ok', 'ok', 'ok']);
    const tets = v.items.find((i) => i.id === 'tets');
    assert.match(tets.text, /γt 0\.30/);
    assert.deepEqual(tets.places[0].point, [5, 5, 5]);
    assert.match(v.items.find((i) => i.id === 'layer').text, /full thickness on 97\.0% of the wall/);
  });

  test('a mesh with slivers, a thinned layer and a volume loss: each is a check, with places', () => {
    const tets = [[0.02, 0, [1, 1, 1]], [0.05, 0, [1.1, 1, 1]], [0.03, 0, [8, 8, 8]], [0.7, 0, [4, 4, 4]]];
    const result = fakeResult({
      tets,
      triangles: [[0.9, [0, 0, 0]]],
      layer: { layers: 4, thickness_within_10pct: 0.6, reduced_area_fraction: 0.35 },
      volumeChange: -0.08,
      warnings: ['the mesh is written in m from a guessed unit, mm (unconfirmed: x); say units if it is not'],
    });
    const v = meshVerdict(result, { unit: 'mm', scale: 10 });
    assert.equal(v.ready, false);
    const levels = Object.fromEntries(v.items.map((i) => [i.id, i.level]));
    assert.deepEqual(levels, { elements: 'ok', tets: 'check', triangles: 'ok', layer: 'check', volume: 'check', 'warning-1': 'check' });
    assert.equal(v.title, 'Check these 4 things before CFD');
    const slivers = v.items.find((i) => i.id === 'tets');
    assert.match(slivers.text, /^3 tetrahedra below γt 0\.1 \(worst 0\.02\), most in 2 places/);
    // The most crowded place first: two slivers near (1, 1, 1).
    assert.equal(slivers.places[0].point[0].toFixed(2), '1.05');
    assert.match(v.items.find((i) => i.id === 'volume').text, /−8\.0%/);
    assert.doesNotMatch(v.items.find((i) => i.id === 'warning-1').text, /say units/);
  });

  test('a warning of the meshing that names places has them: the layer grown after the wall was relaxed', () => {
    const warning =
      'the boundary layer could not grow at (1, 2, 3) and 2 more places (a needle-like spike or fold the wall follows ' +
      'from the input): the wall was smoothed there (14 vertices, moved at most 0.02)';
    const v = meshVerdict(fakeResult({ tets: [[0.5, 0, [0, 0, 0]]], triangles: [[0.9, [0, 0, 0]]], warnings: [warning] }), { unit: 'mm', scale: 10 });
    const item = v.items.find((i) => i.id === 'warning-1');
    assert.equal(item.level, 'check');
    assert.deepEqual(item.places.map((p) => p.point), [[1, 2, 3]]);
    assert.match(item.text, /could not grow at \(1, 2, 3\) mm/);
  });

  test('no layer is a note, not a check; surface only has no volume items', () => {
    const v = meshVerdict(fakeResult({ tets: [[0.5, 0, [0, 0, 0]]], triangles: [[0.9, [0, 0, 0]]] }));
    assert.equal(v.items.find((i) => i.id === 'layer').level, 'note');
    assert.equal(v.ready, true);
    const surfaceOnly = fakeResult({ triangles: [[0.9, [0, 0, 0]]] });
    delete surfaceOnly.report.output.volume;
    delete surfaceOnly.volume;
    assert.deepEqual(meshVerdict(surfaceOnly).items.map((i) => i.id), ['elements', 'triangles', 'volume']);
  });

  test('places group the elements below the limit by cells', () => {
    const positions = new Float32Array([0, 0, 0, 0.1, 0, 0, 5, 5, 5]);
    const found = placesBelow({ positions, elements: new Uint32Array([0, 1, 2]), size: 1, quality: new Float32Array([0.01, 0.02, 0.05]), limit: LIMITS.tet, cell: 1 });
    assert.equal(found.below, 3);
    assert.deepEqual(found.places.map((p) => p.count), [2, 1]);
    assert.equal(found.worst.quality.toFixed(2), '0.01');
  });

  test('needles in the input are said to go with remeshing', () => {
    assert.match(inputQualityNote({ min: 0.00007 }), /remeshing removes them/);
    assert.equal(inputQualityNote({ min: 0.3 }), '');
  });
});

describe('side effects of a preparation change', () => {
  const analysis = (openings, caps = 0, unit = 'mm') => ({
    openings: openings.map(([c, r]) => ({ centroid: c, radius: r })),
    caps_removed: caps,
    units: { unit },
    bounding_box: { diagonal: 10 },
  });

  test('openings, caps, the inlet and the unit are said; nothing when the same', () => {
    const before = analysis([[[0, 0, 0], 1]], 1);
    const after = analysis([[[0, 0, 9], 0.2]], 0);
    const effects = sideEffects(before, after);
    assert.deepEqual(effects, ['caps found 1 → 0', 'the inlet moved to (0, 0, 9) mm']);
    assert.equal(sideEffectText('smoothing', effects), 'Changing the smoothing also changed: caps found 1 → 0, the inlet moved to (0, 0, 9) mm.');
    assert.deepEqual(sideEffects(before, analysis([], 0)), ['openings 1 → 0', 'caps found 1 → 0']);
    assert.deepEqual(sideEffects(before, analysis([[[0, 0, 0.5], 1]], 1)), []);
    assert.equal(sideEffectText('smoothing', []), '');
  });
});

describe('the openings before meshing', () => {
  const base = { units: { unit: 'mm' }, bounding_box: { diagonal: 50 }, clip_proposals: [] };
  const opening = (c, r) => ({ centroid: c, radius: r });

  test('a vessel end first proposed and left closed, wider than every opening: likely the inlet', () => {
    const a = { ...base, openings: [opening([0, 0, 10], 1), opening([5, 0, 10], 0.8)] };
    const proposals = [{ point: [0, 0, 10.5], radius: 1 }, { point: [5, 0, 10.2], radius: 0.8 }, { point: [0, 0, -10], radius: 2 }];
    const [w] = openingWarnings(a, { proposals });
    assert.equal(w.id, 'closed-end');
    assert.match(w.text, /still closed at \(0, 0, -10\) mm \(radius 2 mm\): it is wider than every opening/);
    assert.deepEqual(w.remedy, { action: 'cut_here', places: [[0, 0, -10]], value: 0, ends: true });
    assert.deepEqual(openingWarnings(a, { proposals: proposals.slice(0, 2) }), []);
  });

  test('a crossing left: with the repairs off, the remedy is to repair; with them on, trim or cut', () => {
    const a = { ...base, openings: [opening([0, 0, 6], 1), opening([0, 0, -6], 1)], self_crossings: { places: [[0.1, 0, 5.6]] } };
    const [on] = openingWarnings(a);
    assert.equal(on.id, 'self-crossing');
    assert.equal(on.remedy.action, 'trim_end');
    assert.match(on.text, /at a damaged vessel end: meshing may fail there\.$/);
    const [off] = openingWarnings(a, { prep: { repair: 'off' } });
    assert.deepEqual(off.remedy, { action: 'repair', places: [[0.1, 0, 5.6]], value: 0 });
    assert.match(off.text, /Repair is off: with it on, such places are re-surfaced or trimmed\)\.$/);
  });

  test('one opening: no outlet; tiny loops: defect loops, not vessel ends', () => {
    assert.deepEqual(openingWarnings({ ...base, openings: [opening([0, 0, 0], 1)] }).map((w) => w.id), ['no-outlet']);
    const a = { ...base, openings: [opening([0, 0, 0], 1), opening([3, 0, 0], 0.6), opening([1, 1, 1], 0.003), opening([2, 2, 2], 0)] };
    const [w] = openingWarnings(a);
    assert.equal(w.id, 'tiny-openings');
    assert.match(w.text, /^Openings 3, 4 are tiny \(radius down to 0 mm/);
    assert.equal(w.places.length, 2);
    // Closed: said, with the proposed ends as the cuts.
    const [closed] = openingWarnings({ ...base, openings: [], clip_proposals: [{ point: [0, 0, 5], radius: 1 }] });
    assert.equal(closed.id, 'no-opening');
    assert.deepEqual(closed.remedy, { action: 'cut_here', places: [[0, 0, 5]], value: 0, ends: true });
    assert.equal(remedyLabel(closed.remedy), 'Cut the vessel end open');
    assert.equal(openingWarnings({ ...base, openings: [] })[0].remedy, undefined);
    // The file's first proposals are the analysis' own again: each end is cut once.
    const ends = [{ point: [0, 0, 5], radius: 1 }, { point: [0, 0, -5], radius: 1 }];
    const [again] = openingWarnings({ ...base, openings: [], clip_proposals: ends }, { proposals: ends });
    assert.deepEqual(again.remedy.places, [[0, 0, 5], [0, 0, -5]]);
  });
});

describe('the unit', () => {
  test('asked while it is a guess, sure or not; the first guess is kept', () => {
    assert.equal(unitsQuestion({ unit: 'm', guessed: true, certain: true, reason: 'median vessel radius 0.00327' }), null);
    assert.match(unitsQuestion({ unit: 'mm', guessed: true, certain: false, reason: 'r' }), /could also be centimetres/);
    assert.equal(unitsQuestion({ unit: 'cm', guessed: false }), null);
    assert.deepEqual(withUnitGuess({ smooth: 'off' }, { unit: 'cm' }), { smooth: 'off', units: 'cm' });
    assert.deepEqual(withUnitGuess({ units: 'mm' }, { unit: 'cm' }), { units: 'mm' });
    assert.deepEqual(withUnitGuess({}, null), {});
  });
});

describe('the places the preparation repaired', () => {
  const analysis = {
    units: { unit: 'mm' },
    bounding_box: { diagonal: 20 },
    repairs: {
      crossings_resurfaced: [
        { where: [1, 2, 3], pairs: 58, resolved: true, box_min: [0, 0, 0], box_max: [2, 2, 1], triangles_removed: 1416, triangles_added: 1112 },
        { where: [0, 0, 9], pairs: 4, resolved: false, box_min: [0, 0, 8], box_max: [1, 1, 10], triangles_removed: 0, triangles_added: 0, why: 'at an opening' },
      ],
      damaged_ends: [
        { where: [0, 0, 9.5], radius: 1, trimmed: true, depth: 0.95, point: [0, 0, 8.6], normal: [0, 0, 1], triangles_removed: 526, crossing: 5, misoriented: 2, nonmanifold: 0, tiny_loops: 14 },
        { where: [0, 0, -9.5], radius: 0.5, trimmed: false, depth: 0, point: [0, 0, 0], normal: [0, 0, -1], triangles_removed: 0, crossing: 3, misoriented: 0, nonmanifold: 0, tiny_loops: 0 },
      ],
    },
  };

  test('each re-surfaced crossing and damaged end, lettered, in the page’s words, where it is', () => {
    const places = repairPlaces(analysis);
    assert.deepEqual(places.map((p) => [p.id, p.kind]), [['A', 'resurfaced'], ['B', 'trimmed'], ['C', 'damaged']]);
    assert.equal(
      places[0].text,
      'Re-surfaced where the surface crossed itself, at (1, 2, 3) mm: 58 pairs of crossing triangles, 1,416 triangles replaced by 1,112.',
    );
    assert.equal(
      places[1].text,
      'Trimmed back 0.95 radii to a clean cross-section: the damaged vessel end at (0, 0, 9.5) mm ' +
        '(radius 1 mm; triangles 5 crossing, 2 folded or twisted, 14 around tiny loops).',
    );
    assert.deepEqual(places[1].point, [0, 0, 8.6], 'the mark is at the clean cut');
    const one = repairPlaces({ ...analysis, repairs: { damaged_ends: [{ ...analysis.repairs.damaged_ends[0], depth: 1 }] } });
    assert.match(one[0].text, /^Trimmed back 1 radius to/);
    assert.match(places[2].text, /^Not trimmed: the damaged vessel end at \(0, 0, -9\.5\) mm \(radius 0\.5 mm; triangles 3 crossing\), the damage/);
    for (const p of places) assert.ok(!namesApiOption(p.text), p.text);
    assert.deepEqual(repairPlaces({ units: { unit: 'mm' }, bounding_box: { diagonal: 1 } }), []);
    assert.equal(letter(0), 'A');
    assert.equal(letter(26), 'AA');
  });

  test('the warnings they say already are not said again', () => {
    assert.equal(saidAsRepair('the surface crossed itself at (1, 2, 3) (58 pairs of triangles: overlapping or intersecting sheets): re-surfaced there as the boundary'), true);
    assert.equal(saidAsRepair('the vessel end at (1, 2, 3) (radius 1) is damaged (triangles 5 crossing): trimmed back'), true);
    assert.equal(saidAsRepair('the surface crosses itself at (1, 2, 3) (4 pairs of triangles) and could not be re-surfaced there (too big)'), false);
  });
});

describe('the preset said in the result', () => {
  test('each setting in the page’s words, never the API’s option names', () => {
    const said = [
      ['prisms', 'true'],
      ['prisms', 'false'],
      ['mshVersion', '2.2'],
      ['outputUnits', 'm'],
      ['outputUnits', ''],
      ['format', 'foam'],
      ['format', 'msh'],
      ['format', 'mesh-complete'],
      ['layerThickness', '0.3'],
      ['someOption', '2'],
    ].map(([option, value]) => presetSettingText({ option, value }));
    assert.deepEqual(said, [
      'layer prisms kept',
      'tetrahedra only',
      'MSH 2.2',
      'written in m',
      "in the input's unit",
      'OpenFOAM case',
      'MSH',
      'SimVascular mesh-complete',
      'the layers’ total thickness 0.3',
      'some option 2',
    ]);
  });
});
