// Benchmark: the mesh job (read, repair, analyze, remesh, write MSH) of the
// WebAssembly build under Node through the JS API, as a page would call it
// (api.mesh(bytes, options), including the copies out of the wasm heap).
// The module is loaded by the package's Node entry (wasm/src/node.js): with
// --threads T (T > 1; 0: all cores) the threaded core on T threads (its pool
// on worker_threads), with --threads 1 or none the single-threaded core.
// Prints one JSON object: per-run wall and CPU seconds (CPU includes the
// pool's threads and Node's own helper threads, e.g. the JIT compiler),
// medians, the threads the core ran on, the output's counts and quality,
// and the process's peak RSS (process.resourceUsage().maxRSS, which
// includes Node itself: baseline_rss_mb is the RSS before the module loads).
// With --serve it runs once per line read from stdin, prints each run as a
// JSON line {run, seconds, cpu_seconds}, and the object above when stdin closes.
//
// usage: node bench/wasm_mesh_bench.mjs FILE.stl [--size H | --per-circumference N]
//          [--param lscm|harmonic|floater] [--mesher2d frontal|delaunay|adapt] [--runs N | --serve]
//          [--surface-only] [--layers N] [--core-size H] [--threads T]
import { readFileSync } from 'node:fs';
import { basename } from 'node:path';
import { performance } from 'node:perf_hooks';
import { median, parseBenchArgs, runIndices } from './benchutil.mjs';

const baselineRss = process.memoryUsage().rss;
const { createVesselmesh } = await import('../wasm/src/node.js');

const { file, runs, serve, options } = await parseBenchArgs(process.argv.slice(2), 'wasm_mesh_bench.mjs');

const t0 = performance.now();
const threads = options.threads ?? 1;
const api = await createVesselmesh({ threads: threads || undefined });
const instantiateSeconds = (performance.now() - t0) / 1000;
const bytes = new Uint8Array(readFileSync(file));

const seconds = [];
const cpuSeconds = [];
let last = null;
for await (const r of runIndices(runs, serve)) {
  const c = process.cpuUsage();
  const t = performance.now();
  const res = api.mesh(bytes, options);
  const dt = (performance.now() - t) / 1000;
  const cu = process.cpuUsage(c);
  cpuSeconds.push((cu.user + cu.system) / 1e6);
  if (!res.ok) {
    console.log(JSON.stringify({ ok: false, file: basename(file), options, error: res.error }));
    process.exit(1);
  }
  seconds.push(dt);
  last = res;
  if (serve) console.log(JSON.stringify({ run: r + 1, seconds: dt, cpu_seconds: cpuSeconds[r] }));
}
if (!last) {
  console.log(JSON.stringify({ ok: false, file: basename(file), options, error: 'no run' }));
  process.exit(1);
}
const out = last.report.output;
console.log(
  JSON.stringify({
    ok: true,
    file: basename(file),
    options,
    runs: seconds.length,
    seconds,
    median_seconds: median(seconds),
    cpu_seconds: cpuSeconds,
    median_cpu_seconds: median(cpuSeconds),
    core_seconds: last.report.seconds,
    stage_seconds: out.remesh?.seconds ?? null,
    instantiate_seconds: instantiateSeconds,
    triangles: out.triangles,
    tets: out.volume?.tetrahedra ?? 0,
    vertices: out.vertices,
    quality: { min: out.quality.min, mean: out.quality.mean },
    msh_bytes: last.msh.length,
    threads: api.threads,
    threads_note: api.threadsNote,
    peak_rss_mb: process.resourceUsage().maxRSS / 1024,
    baseline_rss_mb: baselineRss / 2 ** 20,
    node: process.version,
  }),
);
