#include "core/mesh/surface_mesh.h"

#include <algorithm>
#include <cmath>

namespace vm {

double BoundingBox::diagonal() const {
  double s = 0;
  for (int k = 0; k < 3; ++k) s += (max[k] - min[k]) * (max[k] - min[k]);
  return std::sqrt(s);
}

BoundingBox bounding_box(const std::vector<double>& points) {
  BoundingBox box;
  if (points.empty()) return box;
  for (int k = 0; k < 3; ++k) box.min[k] = box.max[k] = points[k];
  for (size_t i = 0; i < points.size(); i += 3) {
    for (int k = 0; k < 3; ++k) {
      box.min[k] = std::min(box.min[k], points[i + k]);
      box.max[k] = std::max(box.max[k], points[i + k]);
    }
  }
  return box;
}

}  // namespace vm
