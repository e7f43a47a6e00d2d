// Node tests of the settings' link (web/src/share.js): the hash holds the
// settings that differ from the defaults, and reading it back gives them;
// values no control accepts are refused with what they must be.
import assert from 'node:assert/strict';
import { describe, test } from 'node:test';

import { decodeSettings, encodeSettings, ignoredNotice, linkNotice, parseValue } from '../src/share.js';

const SPECS = [
  {
    id: 'size-mode',
    name: 'Size',
    kind: 'select',
    options: ['perCircumference', 'size'],
    labels: ['Edges per circumference N (h = 2πR/N)', 'Uniform edge length h'],
  },
  { id: 'size-value', name: 'Size N or h', kind: 'number', min: 0, max: undefined, integer: false, empty: false },
  { id: 'layers', name: 'Boundary layer: Layers', kind: 'number', min: 0, max: 100, integer: true, empty: false },
  { id: 'first-layer', name: 'Boundary layer: First-layer height', kind: 'number', min: 0, max: undefined, integer: false, empty: true },
  { id: 'wall-on', name: 'Vessel wall: Grow the vessel wall outward', kind: 'checkbox' },
  { id: 'output-units', name: 'Output units', kind: 'select', options: ['', 'mm', 'cm', 'm'], labels: ['same as input', 'mm', 'cm', 'm'] },
];
const IDS = SPECS.map((s) => s.id);
const DEFAULTS = { 'size-mode': 'perCircumference', 'size-value': '20', layers: '4', 'first-layer': '', 'wall-on': false, 'output-units': '' };

describe('settings link', () => {
  test('the defaults make no hash', () => {
    assert.equal(encodeSettings(IDS, DEFAULTS, DEFAULTS), '');
    assert.equal(encodeSettings(IDS, new Map(Object.entries(DEFAULTS)), new Map(Object.entries(DEFAULTS))), '');
  });

  test('changed settings round-trip through the hash, in the controls order', () => {
    const values = { ...DEFAULTS, 'wall-on': true, 'size-value': '0.35', 'size-mode': 'size', 'output-units': 'm', 'first-layer': '0.01' };
    const hash = encodeSettings(IDS, values, DEFAULTS);
    assert.equal(hash, '#size-mode=size&size-value=0.35&first-layer=0.01&wall-on=1&output-units=m');
    const back = decodeSettings(hash, SPECS);
    assert.deepEqual(back.problems, []);
    assert.equal(back.given, true);
    assert.deepEqual(back.values, { 'size-mode': 'size', 'size-value': '0.35', 'first-layer': '0.01', 'wall-on': true, 'output-units': 'm' });
  });

  test('a value set back to a blank default is written empty and read back', () => {
    const hash = encodeSettings(IDS, { ...DEFAULTS, 'output-units': 'cm' }, { ...DEFAULTS, 'output-units': 'mm' });
    assert.equal(hash, '#output-units=cm');
    assert.deepEqual(decodeSettings('#first-layer=', SPECS).values, { 'first-layer': '' });
  });

  test('no hash: nothing given', () => {
    assert.deepEqual(decodeSettings('', SPECS), { values: {}, problems: [], given: false });
    assert.deepEqual(decodeSettings('#', SPECS), { values: {}, problems: [], given: false });
  });

  test('invalid values and unknown names are refused with what they must be; the others are kept', () => {
    const { values, problems, given } = decodeSettings(
      '#size-mode=huge&layers=2.5&size-value=abc&wall-on=maybe&colour=red&output-units=cm&size-value=-1&first-layer=&layers=200',
      SPECS,
    );
    assert.equal(given, true);
    assert.deepEqual(values, { 'output-units': 'cm', 'first-layer': '' });
    // Named as the page names the controls and their choices, not by the API's names.
    assert.deepEqual(problems, [
      '“Size” set to “huge”: must be one of “Edges per circumference N (h = 2πR/N)”, “Uniform edge length h”',
      '“Boundary layer: Layers” set to “2.5”: must be a whole number from 0 to 100',
      '“Size N or h” set to “abc”: must be a number of at least 0',
      '“Vessel wall: Grow the vessel wall outward” set to “maybe”: must be on or off (1 or 0)',
      '“colour”: not an option of this page',
      '“Size N or h” set to “-1”: must be a number of at least 0',
      '“Boundary layer: Layers” set to “200”: must be a whole number from 0 to 100',
    ]);
    assert.ok(problems.every((p) => !/perCircumference|size-mode/.test(p)));
    assert.match(ignoredNotice(problems), /^The link's 7 settings “Size” set to “huge”: .* ignored \(their defaults are used\)\.$/);
    assert.equal(ignoredNotice([]), '');
  });

  test('a blank is refused where the default is not blank', () => {
    assert.deepEqual(parseValue(SPECS[1], ''), { problem: 'a number of at least 0' });
    assert.deepEqual(parseValue(SPECS[2], ' 3 '), { value: '3' });
    assert.deepEqual(parseValue(SPECS[4], 'true'), { value: true });
    assert.deepEqual(parseValue(SPECS[4], '0'), { value: false });
  });

  test('the notice of an opened link names what it changed and what it ignored', () => {
    assert.equal(linkNotice(['Boundary layer: Layers', 'Output units'], []), 'The link changed these options: “Boundary layer: Layers”, “Output units”.');
    assert.equal(
      linkNotice(['Boundary layer: Layers'], ['“Size” set to “huge”: must be one of “Edges per circumference N (h = 2πR/N)”, “Uniform edge length h”']),
      'The link changed these options: “Boundary layer: Layers”. The link\'s setting “Size” set to “huge”: must be one of ' +
        '“Edges per circumference N (h = 2πR/N)”, “Uniform edge length h” — ignored (its default is used).',
    );
    assert.match(linkNotice([], ['“x”: not an option of this page']), /^The link's setting “x”: /);
    assert.equal(linkNotice([], []), '');
  });

  test('escaped characters survive', () => {
    const specs = [{ id: 'name', kind: 'text' }];
    const hash = encodeSettings(['name'], { name: 'a b&c=d' }, { name: '' });
    assert.deepEqual(decodeSettings(hash, specs).values, { name: 'a b&c=d' });
  });
});
