#!/usr/bin/env bash
# Installs what vesselmesh needs on Debian 12 and builds everything:
# native (core, CLI, tests, benchmarks), WebAssembly module, web app.
# Usage: scripts/setup.sh [--no-web]
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(build-essential cmake ninja-build libeigen3-dev libnanoflann-dev libgtest-dev
  libxxhash-dev zlib1g-dev
  emscripten chromium gmsh python3-gmsh nodejs npm)
missing=()
for p in "${packages[@]}"; do
  dpkg -s "$p" >/dev/null 2>&1 || missing+=("$p")
done
# nodejs/npm may come from elsewhere (the machine's own Node 20+).
if command -v node >/dev/null && command -v npm >/dev/null; then
  filtered=()
  for p in "${missing[@]}"; do [[ $p == nodejs || $p == npm ]] || filtered+=("$p"); done
  missing=("${filtered[@]}")
fi
if ((${#missing[@]})); then
  echo "== installing: ${missing[*]}"
  SUDO=""
  [[ $(id -u) -ne 0 ]] && SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq "${missing[@]}" >/dev/null
fi

echo "== npm ci"
PLAYWRIGHT_SKIP_BROWSER_DOWNLOAD=1 npm ci --no-audit --no-fund --loglevel=error

jobs=$(nproc)
echo "== native build (build/)"
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j "$jobs"

echo "== WebAssembly build (build-wasm/ -> wasm/dist/)"
export NODE_PATH=/usr/share/nodejs
emcmake cmake -S . -B build-wasm -G Ninja -DCMAKE_BUILD_TYPE=Release -DVM_BUILD_TESTS=OFF >/dev/null
cmake --build build-wasm -j "$jobs"

if [[ ${1:-} != --no-web ]]; then
  echo "== web app (web/dist/)"
  npm run --silent build:web
fi
