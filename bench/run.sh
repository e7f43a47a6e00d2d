#!/usr/bin/env bash
# Runs the benchmarks (native and wasm) on the reference surfaces when present
# (read + analysis throughput, the 3D Delaunay kernel on random points, then
# the remeshing speed of bench/remesh_speed.py)
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
echo
echo "== native: 3D Delaunay kernel, random points (points/s)"
./build/delaunay_bench --runs 3 --sizes 100000,1000000 --kinds cube,cylinder
echo "-- on 2 threads (the build's slab rounds)"
./build/delaunay_bench --runs 3 --sizes 1000000 --kinds cube --threads 2

if [[ -f $data/aortic-arch.stl ]]; then
  echo
  echo "== remesh speed: aortic-arch.stl at h = 0.06 (native, wasm, Gmsh when installed)"
  py=python3
  [[ -x /usr/bin/python3 ]] && py=/usr/bin/python3
  "$py" bench/remesh_speed.py --data "$data" --json out/speed/surface.json
fi

echo
echo "== every real file with default options (native and wasm, median of 3)"
py=python3
[[ -x /usr/bin/python3 ]] && py=/usr/bin/python3
"$py" bench/default_runs.py --runs 3 --json out/speed/default_runs.json || true
