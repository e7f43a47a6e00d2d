#!/usr/bin/env bash
# README command 1: set up, build, mesh the bundled sample with the CLI, then
# serve the app on localhost.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh

echo "== meshing the bundled sample"
mkdir -p out
./build/vesselmesh phantom out/sample.stl --kind bifurcation --voxel 0.08 --noise 0.3
./build/vesselmesh info out/sample.stl
./build/vesselmesh mesh out/sample.stl -o out/sample.msh
echo
echo "== vesselmesh app: http://127.0.0.1:${PORT:-4173}/  (Ctrl-C to stop)"
exec npx vite preview --config web/vite.config.js --host 127.0.0.1 --port "${PORT:-4173}" --strictPort
