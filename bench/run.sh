#!/usr/bin/env bash
# Runs the benchmarks (native and wasm) on the reference surfaces when present
# and on a generated ~2M-triangle phantom. Build first (scripts/setup.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
data=../shared/data/vascular
files=()
[[ -d $data ]] && files=("$data"/*.stl)
echo "== native: read + weld + repair + analysis"
./build/read_analyze_bench "${files[@]}"
echo
echo "== wasm (node): read + weld + repair + analysis"
node bench/wasm_bench.mjs "${files[@]}"
