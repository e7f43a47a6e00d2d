// A k-d tree over a flat array of 3D points (nanoflann, Debian's
// libnanoflann-dev): the nearest-vertex and radius searches of the vessel
// radius, the layers' gap and the volume size field.
#pragma once

#include <cstddef>
#include <cstdint>
#include <nanoflann.hpp>
#include <vector>

namespace vm {

/// nanoflann's view of `pts` (3 doubles per point, kept alive by the caller).
struct PointCloud {
  const std::vector<double>& pts;
  size_t kdtree_get_point_count() const { return pts.size() / 3; }
  double kdtree_get_pt(size_t i, size_t d) const { return pts[3 * i + d]; }
  template <class Box>
  bool kdtree_get_bbox(Box&) const {
    return false;
  }
};

/// The tree: point ids are uint32_t, distances squared Euclidean.
using PointKdTree =
    nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, PointCloud>,
                                        PointCloud, 3, uint32_t>;

}  // namespace vm
