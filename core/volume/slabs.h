// Slabs of equal point count along one axis: how the partitioned rounds of
// the kernel's build, the refinement and the volume optimizer cut their
// work (docs/ARCHITECTURE.md, "Threads"). The cuts depend on the values
// alone, never on the thread count.
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

namespace vm {

struct Slabs {
  int axis = 0;
  std::vector<double> cuts;  // ascending
  /// The slab of point p (3 doubles): the number of cuts <= p[axis], so
  /// ties go to the same slab.
  int of(const double* p) const {
    return int(std::upper_bound(cuts.begin(), cuts.end(), p[axis]) - cuts.begin());
  }
};

/// `parts` slabs of about equal count of the values xs (the points'
/// coordinates along `axis`; reordered): cuts at the values of ranks
/// n j / parts, j = 1 .. parts - 1; halfway: parts + 1 slabs, cut halfway
/// between those (ranks n (2 j - 1) / (2 parts), j = 1 .. parts). No cut
/// when xs is empty.
inline Slabs equal_count_slabs(std::vector<double>& xs, int axis, size_t parts,
                               bool halfway = false) {
  Slabs s;
  s.axis = axis;
  const size_t n = xs.size();
  for (size_t j = 1; j < parts + halfway && n > 0; ++j) {
    auto at = xs.begin() + ptrdiff_t(halfway ? n * (2 * j - 1) / (2 * parts) : n * j / parts);
    std::nth_element(xs.begin(), at, xs.end());
    s.cuts.push_back(*at);
  }
  return s;
}

}  // namespace vm
