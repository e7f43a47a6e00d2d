// libFuzzer target: any bytes through read_surface (every reader, gzip,
// UTF-16). A reader must return a value or an error, never crash, hang or
// allocate beyond its limits; a surface it returns is well formed: corner
// indices within the points, finite coordinates, as many labels as
// triangles. Built by scripts/fuzz.sh (clang, -fsanitize=fuzzer,address,
// undefined); inputs it found are kept in tests/fuzz/regressions/ and
// replayed by the GoogleTest suite (fuzz_regressions_test.cpp).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>

#include "tests/fuzz/check_surface.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  vm::fuzz::read_and_check(std::span<const uint8_t>(data, size));
  return 0;
}
