#!/usr/bin/env bash
# Fuzzing: the libFuzzer targets of tests/fuzz/, built by clang in the
# sanitized build (build-asan/: AddressSanitizer and UBSan, halting on the
# first report; scripts/test.sh builds it for the suite first), each run for
# FUZZ_SECONDS (default 60) from generated seeds: every surface reader
# (fuzz_read_surface) and the option table's parsing (fuzz_options). Any
# crash, sanitizer report, timeout or memory blow-up fails the run; the
# input that caused it is left in out/fuzz/ (add it to
# tests/fuzz/regressions/readers/ once fixed: the GoogleTest suite replays
# them). Usage: bash scripts/fuzz.sh [SECONDS]
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-${FUZZ_SECONDS:-60}}
CC=clang CXX=clang++ cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=Debug -DVM_SANITIZE=ON >/dev/null
cmake --build build-asan -j "$(nproc)" --target fuzz_read_surface fuzz_options
export UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
python3 tests/fuzz/make_seeds.py "$work/readers" "$work/options"
cp tests/fuzz/regressions/readers/* "$work/readers/" 2>/dev/null || true
mkdir -p out/fuzz
common=(-max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -malloc_limit_mb=1024 -artifact_prefix=out/fuzz/ -print_final_stats=1)
# The two targets side by side (each runs on one core), their logs
# printed in turn.
run() {  # run NAME ARGS...: the target's exit status in $work/NAME.status
  local name=$1; shift
  set +e
  build-asan/"$name" "$@" "${common[@]}" > "$work/$name.log" 2>&1
  echo $? > "$work/$name.status"
}
run fuzz_read_surface "$work/readers" -dict=tests/fuzz/readers.dict -max_len=65536 &
run fuzz_options "$work/options" -max_len=256 &
wait
status=0
for name in fuzz_read_surface fuzz_options; do
  echo "== $name ($seconds s)"
  grep -E '^(Done|stat::number_of_executed_units|==[0-9]+==ERROR|SUMMARY)|runtime error|artifact|read back' "$work/$name.log" || true
  [[ $(cat "$work/$name.status") -eq 0 ]] || status=1
done
if [[ $status -ne 0 ]]; then
  echo "fuzzing found a failure: the input is in out/fuzz/" >&2
  exit 1
fi
echo "fuzzing: no failure"
