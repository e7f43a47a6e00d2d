// Planar domains shared by the mesh2d tests.
#pragma once

#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

namespace vm::testing {

/// Unit circle split in `n_out` edges around a circle of radius `r_in` split
/// in `n_in` edges (a hole): points (2 doubles each) and segments.
inline void annulus(int n_out, int n_in, double r_in, std::vector<double>& pts,
                    std::vector<int32_t>& seg) {
  for (int i = 0; i < n_out; ++i) {
    double a = 2 * std::numbers::pi * i / n_out;
    pts.insert(pts.end(), {std::cos(a), std::sin(a)});
    seg.insert(seg.end(), {i, (i + 1) % n_out});
  }
  for (int i = 0; i < n_in; ++i) {
    double a = 2 * std::numbers::pi * i / n_in;
    pts.insert(pts.end(), {r_in * std::cos(a), r_in * std::sin(a)});
    seg.insert(seg.end(), {n_out + i, n_out + (i + 1) % n_in});
  }
}

}  // namespace vm::testing
