// Benchmark: read + weld + repair + analysis throughput of the WebAssembly
// build under Node (api.analyze, including the copy of the result arrays out
// of the wasm heap). Median of several runs per input.
//
// usage: node bench/wasm_bench.mjs [--runs N] [--generated-voxel V] [FILES.stl...]
import { readFileSync } from 'node:fs';
import { basename } from 'node:path';
import { performance } from 'node:perf_hooks';

import { createVesselmesh } from '../wasm/src/vesselmesh.js';
import { median } from './benchutil.mjs';

const args = process.argv.slice(2);
let runs = 7;
let voxel = 0.0115;
const files = [];
for (let i = 0; i < args.length; i++) {
  if (args[i] === '--runs') runs = Math.max(1, Number(args[++i]));
  else if (args[i] === '--generated-voxel') voxel = Number(args[++i]);
  else files.push(args[i]);
}

const wasmBinary = readFileSync(new URL('../wasm/dist/vesselmesh_core.wasm', import.meta.url));
const api = await createVesselmesh({ wasmBinary });

const inputs = files.map((f) => ({ name: basename(f), bytes: new Uint8Array(readFileSync(f)) }));
if (voxel > 0) {
  const p = api.makePhantom({ kind: 'bifurcation', voxel, noise: 0.3 });
  if (!p.ok) throw new Error(p.error);
  inputs.push({ name: `generated-bifurcation (voxel ${voxel})`, bytes: p.stl });
}


console.log(`${'input'.padEnd(44)} ${'triangles'.padStart(10)} ${'median s'.padStart(10)} ${'Mtri/s'.padStart(12)}`);
for (const input of inputs) {
  const times = [];
  let triangles = 0;
  for (let r = 0; r < runs; r++) {
    const t0 = performance.now();
    const res = api.analyze(input.bytes);
    const dt = (performance.now() - t0) / 1000;
    if (!res.ok) throw new Error(`${input.name}: ${res.error}`);
    triangles = res.analysis.input_triangles;
    times.push(dt);
  }
  const m = median(times);
  console.log(
    `${input.name.padEnd(44)} ${String(triangles).padStart(10)} ${m.toFixed(4).padStart(10)} ${(triangles / m / 1e6).toFixed(2).padStart(12)}`,
  );
}
const mem = process.memoryUsage();
console.log(`peak-ish memory: rss ${(mem.rss / 2 ** 20).toFixed(0)} MB (runs: ${runs})`);
