// Node tests of the page's file names (web/src/files.js) and unit texts
// (web/src/units.js).
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { describe, test } from 'node:test';

import { ACCEPT, baseName, EXPORT_FORMATS, exportFileName } from '../src/files.js';
import { length, point, unitsQuestion, unitsText, withUnit } from '../src/units.js';

describe('file names', () => {
  test('the base name drops the surface extensions, gzip included', () => {
    for (const [name, base] of [
      ['patient.stl', 'patient'],
      ['Patient.STL', 'Patient'],
      ['model.vtp', 'model'],
      ['model.vtp.gz', 'model'],
      ['scan.vtk.GZ', 'scan'],
      ['lumen.obj', 'lumen'],
      ['lumen.ply.gz', 'lumen'],
      ['surface.gz', 'surface'],
      ['aorta.v2.stl', 'aorta.v2'],
      ['notes.txt', 'notes.txt'],
      ['.stl', 'mesh'],
    ]) {
      assert.equal(baseName(name), base, name);
    }
  });

  test('each export format has its file name', () => {
    assert.deepEqual(
      EXPORT_FORMATS.map((f) => exportFileName('model.vtp.gz', f.value)),
      [
        'model.msh',
        'model.msh',
        'model.msh',
        'model.vtu',
        'model.vtu',
        'model-boundary.vtp',
        'model-wall.stl',
        'model-mesh-complete.zip',
        'model-openfoam.zip',
        'model-openfoam.zip',
      ],
    );
    assert.deepEqual(
      EXPORT_FORMATS.filter((f) => f.volume).map((f) => f.format),
      ['vtu', 'vtu', 'mesh-complete', 'foam', 'foam'],
    );
  });

  test("the page's file input accepts every surface file", () => {
    const html = readFileSync(new URL('../index.html', import.meta.url), 'utf8');
    assert.equal(html.match(/id="file-input"[^>]*accept="([^"]*)"/)[1], ACCEPT);
  });
});

describe('units', () => {
  const guessMm = { unit: 'mm', guessed: true, certain: false, reason: 'median vessel radius 0.994' };
  const guessM = { unit: 'm', guessed: true, certain: true, reason: 'median vessel radius 0.00327' };
  const given = { unit: 'cm', guessed: false, certain: true, reason: '' };

  test('the summary says how the unit was decided', () => {
    assert.equal(unitsText(given), 'cm');
    assert.equal(unitsText(guessM), 'm (guessed from the median vessel radius 0.00327)');
    assert.equal(unitsText(guessMm), 'mm? (a guess from the median vessel radius 0.994)');
  });

  test('an unsure guess is asked about (with the other unit it could be) until said; a certain one is not', () => {
    assert.equal(
      unitsQuestion(guessMm),
      'Units: mm? The numbers could also be centimetres (median vessel radius 0.994).',
    );
    assert.equal(unitsQuestion(guessM), null);
    assert.equal(unitsQuestion(given), null);
    // The core's alternative is the one named (a cm guess that could be m).
    const guessCm = { unit: 'cm', guessed: true, certain: false, reason: 'r', alternative: 'm' };
    assert.equal(unitsQuestion(guessCm), 'Units: cm? The numbers could also be metres (r).');
    assert.match(unitsQuestion({ ...guessCm, alternative: '' }), /could also be millimetres/);
  });

  test('lengths carry their unit; rounding noise about 0 is shown as 0', () => {
    assert.equal(withUnit(6.265257227, 'mm'), '6.265 mm');
    assert.equal(withUnit(0.003272828956, 'm'), '0.003273 m');
    assert.deepEqual(
      [2500, 1000, 4, 6.25, 0.1, 123456, 1e-7, 0].map(length),
      ['2500', '1000', '4', '6.25', '0.1', '1.235e+5', '1e-7', '0'],
    );
    assert.equal(point([-8.86e-18, 1.66e-17, 4], 4.9), '(0, 0, 4)');
    assert.equal(point([0.0008449656, -0.01266689, 1e-9], 0.035), '(0.000845, -0.01267, 0)');
  });
});
