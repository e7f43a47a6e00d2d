// Command line of the wasm mesh benchmarks (wasm_mesh_bench.mjs in Node,
// wasm_chromium_bench.mjs in Chromium): the input, the runs and the mesh
// options, named as the CLI names them. Exits with status 2 on bad usage.
export function parseBenchArgs(argv, script) {
  let runs = 5;
  let file = null;
  const options = {};
  for (let i = 0; i < argv.length; i++) {
    const a = argv[i];
    if (a === '--runs') runs = Math.max(1, Number(argv[++i]));
    else if (a === '--size') options.size = Number(argv[++i]);
    else if (a === '--per-circumference') options.perCircumference = Number(argv[++i]);
    else if (a === '--param') options.param = argv[++i];
    else if (a === '--mesher2d') options.mesher2d = argv[++i];
    else if (a === '--surface-only') options.surfaceOnly = true;
    else if (a === '--layers') options.layers = Number(argv[++i]);
    else if (a === '--core-size') options.coreSize = Number(argv[++i]);
    else if (a.startsWith('--')) {
      console.error(`unknown option ${a}`);
      process.exit(2);
    } else file = a;
  }
  if (!file) {
    console.error(`usage: node bench/${script} FILE.stl [--size H] [--runs N]`);
    process.exit(2);
  }
  return { file, runs, options };
}
