// Prism to three tetrahedra by the smallest-index diagonals (Dompierre et
// al., IMR 1999): rotate the prism so its smallest vertex id is local vertex
// 0, then choose the diagonal of the quad opposite it by comparing the
// smallest ids of its two diagonals.
#include "core/mesh/prism_split.h"

#include <algorithm>

namespace vm {

std::array<std::array<int32_t, 4>, 3> split_prism(const int32_t v[6]) {
  // The orientation-preserving relabelings that bring each vertex to 0.
  static constexpr int kRotation[6][6] = {{0, 1, 2, 3, 4, 5}, {1, 2, 0, 4, 5, 3},
                                          {2, 0, 1, 5, 3, 4}, {3, 5, 4, 0, 2, 1},
                                          {4, 3, 5, 1, 0, 2}, {5, 4, 3, 2, 1, 0}};
  const int first = int(std::min_element(v, v + 6) - v);
  int32_t r[6];
  for (int k = 0; k < 6; ++k) r[k] = v[kRotation[first][k]];
  if (std::min(r[1], r[5]) < std::min(r[2], r[4]))
    return {{{r[0], r[1], r[2], r[5]}, {r[0], r[1], r[5], r[4]}, {r[0], r[4], r[5], r[3]}}};
  return {{{r[0], r[1], r[2], r[4]}, {r[0], r[4], r[2], r[5]}, {r[0], r[4], r[5], r[3]}}};
}

std::array<std::array<int32_t, 3>, 2> split_quad(const int32_t q[4]) {
  const int32_t m = std::min({q[0], q[1], q[2], q[3]});
  if (m == q[0] || m == q[2]) return {{{q[0], q[1], q[2]}, {q[0], q[2], q[3]}}};
  return {{{q[1], q[2], q[3]}, {q[1], q[3], q[0]}}};
}

}  // namespace vm
