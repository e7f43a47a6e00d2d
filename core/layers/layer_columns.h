// The geometry of the boundary layer's columns (Marchandise et al., section
// 2.2: the layer nodes are placed along each surface node's direction): the
// point of layer k above a wall vertex for a thickness factor, rim columns
// in their cap plane's coordinates so they stay in the plane to rounding.
#pragma once

#include <cstdint>
#include <vector>

#include "core/layers/layer_geometry.h"
#include "core/layers/layer_mesh.h"
#include "core/mesh/surface_mesh.h"
#include "core/surface/cap_openings.h"

namespace vm {

/// Point k of wall vertex v: wall[v] + fraction[k] * factor * requested[v] *
/// direction[v]; for a rim vertex of opening o the same in the plane
/// coordinates of planes[o] (the plane's own arithmetic, OpeningPlane::at).
/// All references must outlive the object; `opening_of` gives each wall
/// vertex's opening or -1, `openings` their rims (indices into planes).
class LayerColumns {
 public:
  LayerColumns(const SurfaceMesh& wall, const std::vector<double>& dir,
               const std::vector<double>& requested, const std::vector<double>& fraction,
               const std::vector<OpeningPlane>& planes, const std::vector<LayerOpening>& openings,
               const std::vector<int32_t>& opening_of)
      : wall_(wall), dir_(dir), requested_(requested), fraction_(fraction), planes_(planes) {
    rim_index_.assign(wall.num_vertices(), -1);
    opening_of_ = &opening_of;
    for (const LayerOpening& op : openings)
      for (size_t i = 0; i < op.rim.size(); ++i) rim_index_[size_t(op.rim[i])] = int32_t(i);
  }

  layers::Vec3 point(int32_t v, size_t k, double factor) const {
    using namespace layers;  // NOLINT: the layer stage's own vector helpers
    const double h = fraction_[k] * factor * requested_[size_t(v)];
    const Vec3 d = at(dir_, v);
    const int32_t o = (*opening_of_)[size_t(v)];
    if (o < 0) return at(wall_.points, v) + h * d;
    const OpeningPlane& pl = planes_[size_t(o)];
    const size_t i = size_t(rim_index_[size_t(v)]);
    if (k == 0) return pl.at(pl.uv[2 * i], pl.uv[2 * i + 1]);
    return pl.at(pl.uv[2 * i] + h * dot(d, pl.e1), pl.uv[2 * i + 1] + h * dot(d, pl.e2));
  }

 private:
  const SurfaceMesh& wall_;
  const std::vector<double>& dir_;
  const std::vector<double>& requested_;
  const std::vector<double>& fraction_;
  const std::vector<OpeningPlane>& planes_;
  const std::vector<int32_t>* opening_of_;
  std::vector<int32_t> rim_index_;
};

}  // namespace vm
