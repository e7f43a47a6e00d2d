// The weighted percentile of a sample: the value below which a given share
// of the total weight lies.
#pragma once

#include <algorithm>
#include <utility>
#include <vector>

namespace vm {

/// The smallest value v of `values_weights` (value, weight >= 0 pairs, not
/// empty, weights not all 0) such that the weights of the values up to v
/// reach `fraction` (0 to 1) of the total. Sorts its copy of the sample.
inline double weighted_percentile(std::vector<std::pair<double, double>> values_weights,
                                  double fraction) {
  std::sort(values_weights.begin(), values_weights.end());
  double total = 0;
  for (const auto& vw : values_weights) total += vw.second;
  double below = 0;
  for (const auto& [value, weight] : values_weights)
    if ((below += weight) >= fraction * total) return value;
  return values_weights.back().first;
}

}  // namespace vm
