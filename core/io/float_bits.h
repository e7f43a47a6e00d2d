// Floats from their IEEE-754 bit patterns (std::bit_cast is missing from
// the libc++ of Emscripten 3.1.6), and little-endian loads of binary files.
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

/// The little-endian uint32 / float32 at p (4 readable bytes).
inline uint32_t load_u32le(const uint8_t* p) {
  return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
}
inline float load_f32le(const uint8_t* p) { return float_from_bits(load_u32le(p)); }

}  // namespace vm
