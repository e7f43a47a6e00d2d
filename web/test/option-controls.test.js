// Node tests of the page's option controls against the core's option table
// (web/src/option-controls.js, wasm/src/option-table.json): a control of one
// option (data-option in web/index.html) has the id kebab(its JS key), the
// settings and a link's keys are those ids (old keys still read), and its
// range and default as built are the table's, in its display units; where
// it differs it says so (data-min, data-max, data-start), within the
// table's rules. A range hand-kept in index.html, or a control renamed away
// from its option, fails (the last tests prove the checks catch both).
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { describe, test } from 'node:test';

import { EXPORT_FORMATS } from '../src/files.js';
import {
  builtAttributes,
  DISPLAY_UNITS,
  fromDisplay,
  htmlControls,
  kebab,
  optionControls,
  optionSpec,
  toDisplay,
  withOptionTable,
} from '../src/option-controls.js';
import { SETTING_IDS } from '../src/settings.js';
import { byCurrentIds, decodeSettings, encodeSettings, LINK_ALIASES } from '../src/share.js';

const TABLE = JSON.parse(readFileSync(new URL('../../wasm/src/option-table.json', import.meta.url), 'utf8'));
const HTML = readFileSync(new URL('../index.html', import.meta.url), 'utf8');
const BUILT = withOptionTable(HTML, TABLE);

/** The page's own controls among the settings: compositions of options. */
const PAGE_SETTINGS = ['size-mode', 'size-value', 'layer-mode', 'wall-on', 'fidelity-on', 'decimate-on'];
/** Mesh options with a control that are not settings: a family is made by its own button. */
const NOT_SETTINGS = ['family', 'ratio', 'family-layers'];

const marked = (html) => optionControls(html).filter((c) => c.attrs.has('data-option'));
const specOf = (control, table = TABLE) => optionSpec(table, control.attrs.get('data-option'));
const byId = (html, id) => htmlControls(html).find((c) => c.id === id);

/** Whether `x` (display units) is a value of the option (its exclusive
 * bounds, wholeness), within the control's narrower range if it has one. */
function fits(spec, attrs, x) {
  const display = attrs.get('data-display');
  const min = spec.min === undefined ? undefined : toDisplay(spec.min, display);
  const max = spec.max === undefined ? undefined : toDisplay(spec.max, display);
  if (!Number.isFinite(x)) return false;
  if (min !== undefined && (spec.minExclusive ? x <= min : x < min)) return false;
  if (max !== undefined && (spec.maxExclusive ? x >= max : x > max)) return false;
  if (attrs.has('data-min') && x < Number(attrs.get('data-min'))) return false;
  if (attrs.has('data-max') && x > Number(attrs.get('data-max'))) return false;
  return spec.type !== 'integer' || Number.isInteger(x);
}

/** Checks the option controls' ids in `html`: kebab(js) of an option of the table. */
function checkIds(html) {
  for (const control of marked(html)) {
    const js = control.attrs.get('data-option');
    const spec = specOf(control);
    assert.equal(control.id, kebab(js), `data-option="${js}"`);
    if (spec.control !== undefined) assert.equal(control.id, spec.control, `the table's control id of ${js}`);
    if (control.attrs.has('data-testid')) assert.equal(control.attrs.get('data-testid'), control.id);
    assert.equal(html.split(` id="${control.id}"`).length, 2, `one element with the id ${control.id}`);
  }
  const keys = marked(html).map((c) => c.attrs.get('data-option'));
  assert.equal(new Set(keys).size, keys.length, 'one control an option');
}

/** Checks that `html` (index.html) keeps no range or default of its option controls. */
function checkSource(html) {
  for (const control of optionControls(html)) {
    const kept = control.attrs.has('data-option') ? ['min', 'max', 'value', 'checked'] : ['min', 'max'];
    for (const name of kept) assert.ok(!control.attrs.has(name), `${control.id} has ${name}="${control.attrs.get(name)}" in index.html`);
    for (const option of control.options) assert.ok(!option.attrs.has('selected'), `${control.id}: an option marked selected in index.html`);
    const display = control.attrs.get('data-display');
    if (display) assert.ok(display in DISPLAY_UNITS, `${control.id}: display unit ${display}`);
  }
}

/** Checks each option control's range and default in `built` (the page as built) against `table`. */
function checkBuilt(built, table = TABLE) {
  for (const control of marked(built)) {
    const spec = specOf(control, table);
    const { attrs, id } = control;
    const display = attrs.get('data-display');
    if (spec.type === 'flag') {
      assert.equal(attrs.get('type'), 'checkbox', id);
      assert.equal(attrs.has('checked'), spec.defaultOn, `${id}: checked`);
    } else if (spec.type === 'choice') {
      assert.equal(control.tag, 'select', id);
      if (id === 'format') continue; // filled from files.js (tested below)
      const values = control.options.map((o) => o.value);
      assert.deepEqual(values.filter((v) => v !== '').sort(), [...spec.choices].sort(), `${id}: every choice of ${spec.js}, and only those`);
      if (values.includes('')) assert.equal(spec.default, '', `${id}: a blank choice for an option with a default`);
      const selected = control.options.filter((o) => o.attrs.has('selected')).map((o) => o.value);
      assert.deepEqual(selected, [attrs.has('data-start') ? attrs.get('data-start') : spec.default], `${id}: the default chosen`);
    } else {
      assert.ok(['number', 'integer'].includes(spec.type), `${id}: ${spec.type}`);
      assert.equal(attrs.get('type'), 'number', id);
      const shown = (x) => (x === undefined || x === '' ? undefined : String(toDisplay(x, display)));
      // The range: the table's, or a narrower one the page says.
      for (const bound of ['min', 'max']) {
        const own = attrs.get(`data-${bound}`);
        assert.equal(attrs.get(bound), own ?? shown(spec[bound]), `${id}: ${bound}`);
        if (own !== undefined) assert.ok(fits(spec, new Map(), Number(own)), `${id}: data-${bound}="${own}" outside the table's range`);
      }
      assert.equal(attrs.get('step') === '1', spec.type === 'integer', `${id}: step 1 for an integer only`);
      // The default: the table's, or where it has none the control can show, the page's start.
      const value = attrs.get('value') ?? '';
      if (!attrs.has('data-start')) assert.equal(value, shown(spec.default) ?? '', `${id}: default`);
      else {
        const start = attrs.get('data-start');
        assert.equal(value, start, id);
        const none = spec.default === '' || !fits(spec, attrs, toDisplay(spec.default, display));
        assert.ok(none || start === '', `${id}: data-start="${start}" where the table's default ${spec.default} would do`);
        if (start === '') assert.ok(attrs.has('placeholder'), `${id}: blank for the default, and says so`);
        else assert.ok(fits(spec, attrs, Number(start)), `${id}: data-start="${start}" outside the range`);
      }
    }
  }
}

describe('option controls', () => {
  test('kebab-case of a JS key', () => {
    assert.equal(kebab('coreSize'), 'core-size');
    assert.equal(kebab('firstLayerYplus'), 'first-layer-yplus');
    assert.equal(kebab('mesher2d'), 'mesher2d');
    assert.equal(kebab('prisms'), 'prisms');
  });

  test('index.html marks its option controls, not the compositions of options', () => {
    const ids = marked(HTML).map((c) => c.id);
    for (const id of ['layers', 'core-size', 'prisms', 'format', 'max-volume-change', 'solver', 'output-units', 'units']) {
      assert.ok(ids.includes(id), id);
    }
    for (const id of PAGE_SETTINGS) assert.ok(!ids.includes(id), id);
  });

  test("every control with data-option has the id kebab(its option's JS key), of an option of the table", () => {
    checkIds(HTML);
  });

  test('no range or default is kept in index.html: the build fills them in', () => {
    checkSource(HTML);
  });

  test("each control's range and default as built are the table's, in its display units", () => {
    checkBuilt(BUILT);
  });

  test('a control of an option\'s range (data-range-of) has its range', () => {
    const flow = byId(BUILT, 'flow-all');
    const spec = optionSpec(TABLE, flow.attrs.get('data-range-of'));
    assert.equal(flow.attrs.get('min'), String(spec.min));
    assert.equal(flow.attrs.get('max'), String(spec.max));
  });

  test('the format select offers every format of the table; its first is the default (MSH in its default version)', () => {
    const format = optionSpec(TABLE, 'format');
    const version = optionSpec(TABLE, 'mshVersion');
    assert.deepEqual([...new Set(EXPORT_FORMATS.map((f) => f.format))].sort(), [...format.choices].sort());
    for (const f of EXPORT_FORMATS) if (f.mshVersion) assert.ok(version.choices.includes(f.mshVersion), f.value);
    // Binary MSH is the table's flag, with version 4.1 (the core refuses 2.2).
    assert.equal(optionSpec(TABLE, 'mshBinary').type, 'flag');
    for (const f of EXPORT_FORMATS) if (f.mshBinary) assert.deepEqual([f.format, f.mshVersion, f.mime], ['msh', '4.1', 'application/octet-stream'], f.value);
    // Compressed VTU and binary OpenFOAM: the table's flags, on their formats.
    assert.deepEqual([optionSpec(TABLE, 'vtkCompress').type, optionSpec(TABLE, 'foamBinary').type], ['flag', 'flag']);
    assert.deepEqual(EXPORT_FORMATS.filter((f) => f.vtkCompress).map((f) => f.format), ['vtu']);
    assert.deepEqual(EXPORT_FORMATS.filter((f) => f.foamBinary).map((f) => f.format), ['foam']);
    assert.deepEqual([EXPORT_FORMATS[0].format, EXPORT_FORMATS[0].mshVersion], ['msh', version.default]);
    assert.equal(byId(HTML, 'format').options.length, 0, 'filled from files.js');
  });

  test('percent is a display unit: the control shows the fraction in percent, one default', () => {
    const control = byId(BUILT, 'max-volume-change');
    const spec = specOf(control);
    assert.equal(control.attrs.get('data-display'), 'percent');
    assert.equal(Number(control.attrs.get('value')), Number(spec.default) * 100);
    assert.equal(fromDisplay(Number(control.attrs.get('value')), 'percent'), Number(spec.default));
    assert.equal(Number(control.attrs.get('max')), spec.max * 100);
    assert.equal(toDisplay(0.05, 'percent'), 5);
    assert.equal(toDisplay(0.07, 'percent'), 7);
  });

  test('builtAttributes: what each kind of control gets', () => {
    const [layers] = optionControls('<input id="layers" data-option="layers" type="number" />');
    assert.deepEqual(builtAttributes(TABLE, layers), { min: '0', max: '100', value: '4', step: '1' });
    const [prisms] = optionControls('<input type="checkbox" id="prisms" data-option="prisms" />');
    assert.deepEqual(builtAttributes(TABLE, prisms), { checked: false });
    const [percent] = optionControls('<input id="max-volume-change" data-option="maxVolumeChange" data-display="percent" type="number" />');
    assert.deepEqual(builtAttributes(TABLE, percent), { min: '0', max: '100', value: '5' });
    assert.throws(() => builtAttributes(TABLE, optionControls('<input id="x" data-option="noSuchOption" type="number" />')[0]), /noSuchOption/);
  });

  test('the checks catch a range or default kept by hand, an id renamed, a start or a narrower range that does not fit', () => {
    const edit = (from, to) => {
      assert.ok(HTML.includes(from), from);
      return HTML.replace(from, to);
    };
    assert.throws(() => checkSource(edit('data-option="layers" type="number"', 'data-option="layers" type="number" max="50"')), /layers has max/);
    assert.throws(() => checkSource(edit('data-option="growth" type="number" step="any"', 'data-option="growth" type="number" step="any" value="1.2"')), /growth has value/);
    assert.throws(() => checkIds(edit('id="prisms" data-testid="prisms"', 'id="keep-prisms" data-testid="keep-prisms"')), /data-option="prisms"/);
    assert.throws(() => checkIds(edit('id="core-size" data-testid="core-size"', 'id="core" data-testid="core"')), /data-option="coreSize"/);
    // As built: a narrower range outside the table's, a start where the table's default fits.
    assert.throws(() => checkBuilt(withOptionTable(edit('data-min="1"', 'data-min="-1"'), TABLE)), /wall-layers: data-min/);
    assert.throws(() => checkBuilt(withOptionTable(edit('data-option="layers"', 'data-option="layers" data-start="3"'), TABLE)), /layers: data-start/);
    // A page built from another table (a range or a default changed since).
    const growth = TABLE.map((s) => (s.js === 'growth' ? { ...s, max: 4 } : s));
    assert.throws(() => checkBuilt(BUILT, growth), /growth: max/);
    const viscosity = TABLE.map((s) => (s.js === 'viscosity' ? { ...s, default: '0.004' } : s));
    assert.throws(() => checkBuilt(BUILT, viscosity), /viscosity: default/);
    checkBuilt(withOptionTable(HTML, growth), growth);
  });
});

describe('settings and links', () => {
  test('the settings are option controls (by their ids) or the listed compositions of the page', () => {
    const options = new Map(marked(HTML).map((c) => [c.id, c]));
    for (const id of SETTING_IDS) {
      assert.ok(options.has(id) || PAGE_SETTINGS.includes(id), `${id}: neither an option control nor a page composition`);
      assert.ok(byId(HTML, id), `${id}: no such control in index.html`);
    }
    for (const id of PAGE_SETTINGS) assert.ok(SETTING_IDS.includes(id), id);
    // Every mesh option with a control is a setting; the per-file ones (info and mesh) are not.
    for (const [id, control] of options) {
      const spec = specOf(control);
      if (spec.commands.includes('info')) assert.ok(!SETTING_IDS.includes(id), `${id}: per file, not a setting`);
      else if (!NOT_SETTINGS.includes(id)) assert.ok(SETTING_IDS.includes(id), `${id}: a mesh option not remembered`);
    }
  });

  /** The settings' specs as the page makes them (share.js controlSpec) from the controls as built. */
  function settingSpecs() {
    return SETTING_IDS.map((id) => {
      const { tag, attrs, options } = byId(BUILT, id);
      if (attrs.get('type') === 'checkbox') return { id, kind: 'checkbox' };
      if (tag === 'select') return { id, kind: 'select', options: id === 'format' ? EXPORT_FORMATS.map((f) => f.value) : options.map((o) => o.value) };
      const bound = (s) => (s === undefined || s === '' ? undefined : Number(s));
      return { id, kind: 'number', min: bound(attrs.get('min')), max: bound(attrs.get('max')), integer: attrs.get('step') === '1', empty: !attrs.get('value') };
    });
  }

  test("a link's keys are the controls' ids; its values are checked against the table's ranges", () => {
    const specs = settingSpecs();
    const defaults = Object.fromEntries(specs.map((s) => [s.id, s.kind === 'checkbox' ? false : 'x']));
    const values = Object.fromEntries(specs.map((s) => [s.id, s.kind === 'checkbox' ? true : 'y']));
    const keys = [...new URLSearchParams(encodeSettings(SETTING_IDS, values, defaults).slice(1)).keys()];
    assert.deepEqual(keys, SETTING_IDS);
    for (const id of ['prisms', 'format', 'core-size', 'max-volume-change']) assert.ok(keys.includes(id), id);
    // The end of the table's range is accepted, one past it refused (in display units).
    const layers = optionSpec(TABLE, 'layers');
    assert.deepEqual(decodeSettings(`#layers=${layers.max}`, specs).values, { layers: String(layers.max) });
    assert.match(decodeSettings(`#layers=${layers.max + 1}`, specs).problems[0], new RegExp(`from ${layers.min} to ${layers.max}`));
    assert.deepEqual(decodeSettings('#max-volume-change=100', specs).problems, []);
    assert.equal(decodeSettings('#max-volume-change=101', specs).problems.length, 1);
    assert.deepEqual(decodeSettings('#core-size=', specs).values, { 'core-size': '' });
  });

  test("an old link's keys are still read: keep-prisms is prisms, export-format is format", () => {
    const specs = settingSpecs();
    assert.deepEqual(LINK_ALIASES, { 'keep-prisms': 'prisms', 'export-format': 'format' });
    const link = decodeSettings('#keep-prisms=1&export-format=vtu&layers=2', specs);
    assert.deepEqual(link.problems, []);
    assert.equal(link.given, true);
    assert.deepEqual(link.values, { prisms: true, format: 'vtu', layers: '2' });
    assert.match(decodeSettings('#export-format=doc', specs).problems[0], /^“format” set to “doc”: must be one of/);
    // So are this browser's remembered settings (the new key wins when both are there).
    assert.deepEqual(byCurrentIds({ 'keep-prisms': true, 'export-format': 'vtu', layers: '2' }), {
      prisms: true,
      format: 'vtu',
      layers: '2',
      'keep-prisms': true,
      'export-format': 'vtu',
    });
    assert.equal(byCurrentIds({ 'export-format': 'vtu', format: 'stl' }).format, 'stl');
    // The aliases name renamed controls only.
    for (const [old, id] of Object.entries(LINK_ALIASES)) {
      assert.ok(SETTING_IDS.includes(id), id);
      assert.ok(!SETTING_IDS.includes(old), old);
      assert.ok(!byId(HTML, old), old);
    }
  });
});

describe('the build', () => {
  test("the page's builds (app, one file) fill the controls in from wasm/src/option-table.json", async () => {
    const { default: config } = await import('../vite.config.js');
    for (const mode of ['production', 'singlefile']) {
      const plugins = config({ mode, command: 'build' }).plugins.flat(Infinity);
      const plugin = plugins.find((p) => p?.name === 'vm-option-table');
      assert.ok(plugin, `${mode}: no vm-option-table plugin`);
      assert.equal(plugin.transformIndexHtml.handler(HTML), BUILT, mode);
    }
  });
});
