// Helpers of the JS benchmarks: the median, and the command line of the
// wasm mesh benchmarks (wasm_mesh_bench.mjs in Node, wasm_chromium_bench.mjs
// in Chromium): the input, the runs and the mesh options by their CLI names,
// converted to the JS API's keys and types through the core's option table;
// with --serve, one run per line read from stdin (a driver such as
// bench/remesh_speed.py alternates these runs with others).
import { readFileSync } from 'node:fs';
import { createInterface } from 'node:readline';

import { createVesselmesh } from '../wasm/src/vesselmesh.js';

/** The median of an array of numbers. */
export const median = (v) => {
  const s = [...v].sort((a, b) => a - b);
  const n = s.length;
  return n % 2 ? s[(n - 1) / 2] : 0.5 * (s[n / 2 - 1] + s[n / 2]);
};

/** Exits with status 2 and a usage line. */
function usage(script, message) {
  console.error(`${message}\nusage: node bench/${script} FILE [--runs N | --serve] [vesselmesh mesh options]`);
  process.exit(2);
}

/** { file, runs, serve, options } from argv: mesh options as `vesselmesh mesh` takes them. */
export async function parseBenchArgs(argv, script) {
  const wasmBinary = readFileSync(new URL('../wasm/dist/vesselmesh_core.wasm', import.meta.url));
  const { optionTable } = await createVesselmesh({ wasmBinary });
  let runs = 5;
  let serve = false;
  let file = null;
  const options = {};
  for (let i = 0; i < argv.length; i++) {
    const a = argv[i];
    if (a === '--runs') {
      runs = Math.max(1, Number(argv[++i]));
      continue;
    }
    if (a === '--serve') {
      serve = true;
      continue;
    }
    if (!a.startsWith('--')) {
      file = a;
      continue;
    }
    const spec = optionTable.find((s) => `--${s.cli}` === a && s.commands.includes('mesh') && s.faces.includes('js'));
    if (!spec) usage(script, `unknown option ${a}`);
    if (spec.type === 'flag') options[spec.js] = !spec.defaultOn;
    else if (spec.type === 'number' || spec.type === 'integer') options[spec.js] = Number(argv[++i]);
    else options[spec.js] = argv[++i];
  }
  if (!file) usage(script, 'no input file');
  return { file, runs, serve, options };
}

/** The runs' indices: `runs` of them, or with serve one per line of stdin
 * until it closes (the caller then prints each run as a JSON line). */
export async function* runIndices(runs, serve) {
  if (!serve) {
    for (let r = 0; r < runs; r++) yield r;
    return;
  }
  let r = 0;
  for await (const _ of createInterface({ input: process.stdin })) yield r++;
}
