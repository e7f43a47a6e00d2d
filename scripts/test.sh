#!/usr/bin/env bash
# README command 2: set up, build, check that core's includes keep to the
# module table, run every test: GoogleTest + CLI (ctest),
# the same suite under AddressSanitizer/UBSan, the hostile-input corpus, a
# short libFuzzer run of the readers and the option table, the Node test of
# the built
# WebAssembly module, and the Playwright specs in Chromium.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/stage.sh
stage "setup (scripts/setup.sh)"
bash scripts/setup.sh
jobs=$(nproc)

stage "module floors (scripts/check_layers.py: core's includes against docs/ARCHITECTURE.md)"
/usr/bin/python3 scripts/check_layers.py --self-test
/usr/bin/python3 scripts/check_layers.py

stage "ctest (native, Release)"
ctest --test-dir build --output-on-failure -j "$jobs"

stage "ctest (Debug at -O1, -fsanitize=address,undefined; clang, with the fuzzers)"
# One instrumented build for the suite and the fuzzers (scripts/fuzz.sh).
CC=clang CXX=clang++ cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=Debug -DVM_SANITIZE=ON >/dev/null
cmake --build build-asan -j "$jobs" --target vm_tests fuzz_read_surface fuzz_options
# The CLI script (tests/cli) runs in the Release build above only: under the
# sanitizers it took 5-6 of the stage's minutes, for code the suite and the
# fuzzers already cover there.
UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1 ctest --test-dir build-asan --output-on-failure -j "$jobs" -E '^cli_tests$'

stage "hostile-input corpus (CLI under a 4 GiB memory cap)"
/usr/bin/python3 -W ignore tests/hostile/run_corpus.py build/vesselmesh

stage "fuzzing (libFuzzer, 30 s a target, side by side)"
bash scripts/fuzz.sh 30

stage "node --test (WebAssembly module)"
npm run --silent test:wasm

stage "playwright (Chromium)"
npm run --silent test:e2e
stage_summary "scripts/test.sh"
