#!/usr/bin/env bash
# Installs what vesselmesh needs on Debian 12 and builds everything:
# native (core, CLI, tests, benchmarks), WebAssembly module, web app.
# Usage: scripts/setup.sh [--no-web | --deps-only]
#   --deps-only: install the packages and fetch zlib's source, build nothing.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/stage.sh

# openfoam and python3-dolfinx: the solvers validation/solver_check.py runs the
# meshes in (CI's real-data step).
packages=(build-essential cmake ninja-build libeigen3-dev libnanoflann-dev libfast-float-dev libgtest-dev
  libxxhash-dev libfmt-dev zlib1g-dev dpkg-dev emscripten chromium gmsh python3-gmsh python3-vtk9
  python3-meshio clang libclang-rt-14-dev openfoam python3-dolfinx nodejs npm)
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
  stage "installing: ${missing[*]}"
  SUDO=""
  [[ $(id -u) -ne 0 ]] && SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq "${missing[@]}" >/dev/null
fi

# zlib for the WebAssembly build: Emscripten's own zlib port downloads from
# outside the Debian and npm registries, which is not possible here, so
# CMakeLists.txt compiles Debian's zlib source from build-deps/zlib
# (gitignored). It comes from `apt-get source zlib`, which needs a deb-src
# entry: one is added next to the existing deb entries (same URIs, suites,
# components and key), never by editing them.
fetch_zlib_source() {
  [[ -f build-deps/zlib/inflate.c ]] && return 0
  stage "zlib source (apt-get source zlib -> build-deps/zlib)"
  local SUDO=""
  [[ $(id -u) -ne 0 ]] && SUDO="sudo"
  local list=/etc/apt/sources.list.d/vesselmesh-deb-src.sources
  if ! grep -qsE '^(Types:.*deb-src|deb-src )' /etc/apt/sources.list /etc/apt/sources.list.d/*.list \
    /etc/apt/sources.list.d/*.sources; then
    local entries=""
    if [[ -f /etc/apt/sources.list.d/debian.sources ]]; then
      # Each "Types: deb" stanza again with "Types: deb-src".
      entries=$(awk 'BEGIN { RS = ""; FS = "\n" }
        { types = ""; rest = ""
          for (i = 1; i <= NF; i++) {
            if ($i ~ /^Types:/) types = $i
            else if ($i ~ /^(URIs|Suites|Components|Signed-By):/) rest = rest $i "\n"
          }
          if (types ~ /[ \t]deb([ \t]|$)/ && rest != "") printf "Types: deb-src\n%s\n", rest }' \
        /etc/apt/sources.list.d/debian.sources)
    elif [[ -f /etc/apt/sources.list ]]; then
      list=/etc/apt/sources.list.d/vesselmesh-deb-src.list
      entries=$(sed -n 's/^deb \(.*\)/deb-src \1/p' /etc/apt/sources.list)
    fi
    if [[ -z $entries ]]; then
      echo "setup: no Debian deb entry found to derive a deb-src entry from" >&2
      return 1
    fi
    printf '%s\n' "$entries" | $SUDO tee "$list" >/dev/null
    $SUDO apt-get update -qq
  fi
  if ! dpkg -s dpkg-dev >/dev/null 2>&1; then
    DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq dpkg-dev >/dev/null
  fi
  local tmp
  tmp=$(mktemp -d)
  chmod 755 "$tmp"  # apt's _apt user writes the download there
  if ! (cd "$tmp" && apt-get source -qq zlib >/dev/null 2>&1); then
    # The newest version may be missing from a mirror (the security archive's
    # pool, here): try each version apt knows, newest first.
    local v fetched=""
    for v in $(apt-cache showsrc zlib | sed -n 's/^Version: //p' | sort -rVu); do
      rm -rf "${tmp:?}"/*
      if (cd "$tmp" && apt-get source -qq "zlib=$v" >/dev/null 2>&1); then
        fetched=$v
        break
      fi
    done
    if [[ -z $fetched ]]; then
      echo "setup: apt-get source zlib failed (is a deb-src entry reachable?)" >&2
      rm -rf "$tmp"
      return 1
    fi
  fi
  local src
  src=$(find "$tmp" -mindepth 1 -maxdepth 1 -type d -name 'zlib-*' | head -n 1)
  if [[ -z $src || ! -f $src/inflate.c ]]; then
    echo "setup: apt-get source zlib gave no zlib source tree" >&2
    rm -rf "$tmp"
    return 1
  fi
  mkdir -p build-deps
  rm -rf build-deps/zlib
  mv "$src" build-deps/zlib
  rm -rf "$tmp"
}
fetch_zlib_source

if [[ ${1:-} == --deps-only ]]; then
  exit 0
fi

stage "npm ci"
PLAYWRIGHT_SKIP_BROWSER_DOWNLOAD=1 npm ci --no-audit --no-fund --loglevel=error

jobs=$(nproc)
stage "native build (build/)"
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j "$jobs"

stage "WebAssembly build (build-wasm/ -> wasm/dist/)"
export NODE_PATH=/usr/share/nodejs
emcmake cmake -S . -B build-wasm -G Ninja -DCMAKE_BUILD_TYPE=Release -DVM_BUILD_TESTS=OFF >/dev/null
cmake --build build-wasm -j "$jobs"

if [[ ${1:-} != --no-web ]]; then
  stage "web app (web/dist/, dist/vesselmesh.html, dist/element/) and docs (docs/dist/)"
  npm run --silent build:web
  npm run --silent build:docs
fi
stage_summary "scripts/setup.sh"
