// The option table is the one source of every option: the JS API, its type
// declarations (vesselmesh.d.ts), the CLI (`vesselmesh options --json`) and
// the option list of docs/options.md must agree with it.
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { existsSync, readFileSync } from 'node:fs';
import { before, describe, test } from 'node:test';

import { ELEMENT_TYPES_PATH, elementTypes, TABLE_PATH, tableJson, TYPES_PATH, typesFor } from '../scripts/gen-types.mjs';
import { createVesselmesh } from '../src/vesselmesh.js';

const root = new URL('../../', import.meta.url);
const cli = new URL('build/vesselmesh', root);

let api;
before(async () => {
  const wasmBinary = readFileSync(new URL('../dist/vesselmesh_core.wasm', import.meta.url));
  api = await createVesselmesh({ wasmBinary });
});

/** A valid JS value of an option, for a type check. */
function validValue(spec) {
  const low = spec.min ?? 0;
  const number = spec.type === 'integer' ? Math.ceil(low + (spec.minExclusive ? 1 : 0)) : low + (spec.minExclusive ? 0.5 : 0);
  const value = {
    number: Math.min(number, spec.max ?? Infinity),
    integer: Math.min(number, spec.max ?? Infinity),
    flag: !spec.defaultOn,
    choice: spec.choices[0],
    text: spec.default || 'a',
    numbers: Array(spec.listSize).fill(Math.max(low, 0) + 1),
  }[spec.type];
  return spec.perOpening === 'required' ? { 1: value } : value;
}

/** A JS value of the wrong type for an option. */
const wrongType = (spec) => (spec.type === 'flag' ? 'yes' : spec.type === 'number' || spec.type === 'integer' ? '1' : true);

describe('option table', () => {
  test('the committed vesselmesh.d.ts is generated from the table (node wasm/scripts/gen-types.mjs)', () => {
    assert.equal(readFileSync(TYPES_PATH, 'utf8'), typesFor(api.optionTable));
    assert.equal(readFileSync(ELEMENT_TYPES_PATH, 'utf8'), elementTypes());
  });

  test('the committed option-table.json (the page builds its controls from it) is the table (node wasm/scripts/gen-types.mjs)', () => {
    assert.equal(readFileSync(TABLE_PATH, 'utf8'), tableJson(api.optionTable));
    assert.deepEqual(JSON.parse(readFileSync(TABLE_PATH, 'utf8')), api.optionTable);
  });

  test('every JS option of the table is declared in vesselmesh.d.ts with its JS key', () => {
    const dts = readFileSync(TYPES_PATH, 'utf8');
    for (const spec of api.optionTable.filter((s) => s.faces.includes('js'))) {
      assert.match(dts, new RegExp(`^  ${spec.js}\\?: `, 'm'), spec.id);
    }
  });

  test('ids, CLI names and JS keys are unique per command', () => {
    for (const command of ['info', 'mesh', 'phantom']) {
      const specs = api.optionTable.filter((s) => s.commands.includes(command));
      for (const key of ['id', 'cli', 'js']) {
        const names = specs.map((s) => s[key]).filter(Boolean);
        assert.equal(new Set(names).size, names.length, `${command} ${key}`);
      }
    }
  });

  test('the CLI prints the same table as the WebAssembly module', { skip: !existsSync(cli) && 'no native build' }, () => {
    const fromCli = JSON.parse(execFileSync(cli.pathname, ['options', '--json'], { encoding: 'utf8' }));
    assert.deepEqual(fromCli, api.optionTable);
  });

  test("docs/options.md's option list is the CLI's `options --markdown`", { skip: !existsSync(cli) && 'no native build' }, () => {
    const page = readFileSync(new URL('docs/options.md', root), 'utf8');
    const block = page.match(/<!-- options:begin[^>]*-->\n([\s\S]*?)<!-- options:end -->/);
    assert.ok(block, 'docs/options.md has no <!-- options:begin --> ... <!-- options:end --> block');
    const generated = execFileSync(cli.pathname, ['options', '--markdown'], { encoding: 'utf8' });
    assert.equal(block[1], generated, 'regenerate it: build/vesselmesh options --markdown');
  });

  test('every CLI option of the table appears in --help', { skip: !existsSync(cli) && 'no native build' }, () => {
    const help = execFileSync(cli.pathname, ['--help'], { encoding: 'utf8' });
    for (const spec of api.optionTable.filter((s) => s.faces.includes('cli'))) {
      assert.ok(help.includes(`--${spec.cli}`), spec.id);
    }
  });

  test('every JS option is reachable: a wrong type is refused naming the JS key, not a CLI flag', () => {
    const stl = api.makePhantom({ kind: 'tube', voxel: 0.4 }).stl;
    for (const spec of api.optionTable.filter((s) => s.faces.includes('js'))) {
      const call = spec.commands.includes('mesh') ? 'mesh' : spec.commands.includes('info') ? 'analyze' : 'makePhantom';
      const args = call === 'makePhantom' ? [{ [spec.js]: wrongType(spec) }] : [stl, { [spec.js]: wrongType(spec) }];
      const r = api[call](...args);
      assert.equal(r.ok, false, spec.id);
      assert.equal(r.kind, 'bad_option', `${spec.id}: ${r.error}`);
      assert.equal(r.option, spec.js);
      assert.ok(r.error.startsWith(`${spec.js} `), r.error);
      assert.doesNotMatch(r.error, /--/);
    }
  });

  test('a value in range is accepted by the option check (it is not refused as an option)', () => {
    const stl = api.makePhantom({ kind: 'tube', voxel: 0.4 }).stl;
    for (const spec of api.optionTable.filter((s) => s.faces.includes('js') && s.commands.includes('info'))) {
      const r = api.analyze(stl, { [spec.js]: validValue(spec) });
      assert.notEqual(r.kind, 'bad_option', `${spec.id}: ${r.error}`);
    }
  });

  test('out of range values are refused with what the option needs', () => {
    const stl = api.makePhantom({ kind: 'tube', voxel: 0.4 }).stl;
    for (const spec of api.optionTable.filter((s) => s.faces.includes('js') && s.max !== undefined && s.type !== 'numbers')) {
      const call = spec.commands.includes('mesh') ? 'mesh' : spec.commands.includes('info') ? 'analyze' : 'makePhantom';
      const bad = spec.max * (1 + 1e-9) + 1; // past the maximum, also for 1e30
      const r = call === 'makePhantom' ? api.makePhantom({ [spec.js]: bad }) : api[call](stl, { [spec.js]: bad });
      assert.equal(r.kind, 'bad_option', spec.id);
      assert.equal(r.error, `${spec.js} needs ${spec.needs}`);
    }
  });

  test('unknown keys are refused', () => {
    const r = api.makePhantom({ bogus: 1 });
    assert.equal(r.ok, false);
    assert.match(r.error, /unknown option 'bogus'/);
  });
});
