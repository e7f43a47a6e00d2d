// The property the reader fuzz target and its regression test check: any
// bytes read as a surface give a value or an error, and a value is well
// formed. Aborts (a fuzzer finding) when it is not.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <span>

#include "core/io/read_surface.h"

namespace vm::fuzz {

/// Limits small enough that a fuzzer's claims of huge counts or sizes are
/// refused quickly: 1M triangles, 64 MiB decompressed.
inline SurfaceReadOptions fuzz_limits() {
  SurfaceReadOptions o;
  o.max_triangles = 1'000'000;
  o.max_decompressed_bytes = size_t(64) << 20;
  return o;
}

[[noreturn]] inline void broken(const char* what) {
  std::fprintf(stderr, "read_surface returned a malformed surface: %s\n", what);
  std::abort();
}

/// Reads `bytes`; returns whether it was read (an error is fine).
inline bool read_and_check(std::span<const uint8_t> bytes) {
  Result<SurfaceFile> r = read_surface(bytes, fuzz_limits());
  if (!r.ok()) {
    if (r.message().empty()) broken("an error without a message");
    return false;
  }
  const SurfaceFile& f = r.value();
  if (f.soup.coords.empty()) {
    if (f.points.size() % 3 != 0 || f.triangles.size() % 3 != 0) broken("array sizes");
    const size_t n = f.points.size() / 3;
    for (int32_t v : f.triangles)
      if (v < 0 || size_t(v) >= n) broken("a corner index outside the points");
    for (double x : f.points)
      if (!std::isfinite(x)) broken("a non-finite coordinate");
  } else {
    if (f.soup.coords.size() % 9 != 0) broken("soup size");
    for (float x : f.soup.coords)
      if (!std::isfinite(x)) broken("a non-finite coordinate");
  }
  if (!f.face_labels.empty() && f.face_labels.size() != f.num_triangles())
    broken("labels and triangles differ in number");
  if (f.num_triangles() > fuzz_limits().max_triangles) broken("more triangles than the limit");
  return true;
}

}  // namespace vm::fuzz
