// Floats from their IEEE-754 bit patterns (std::bit_cast is missing from
// the libc++ of Emscripten 3.1.6).
#pragma once

#include <cstdint>
#include <cstring>

namespace vm {

inline float float_from_bits(uint32_t u) {
  float f;
  std::memcpy(&f, &u, 4);
  return f;
}

inline double double_from_bits(uint64_t u) {
  double d;
  std::memcpy(&d, &u, 8);
  return d;
}

}  // namespace vm
