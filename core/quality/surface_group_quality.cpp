// gamma_k of the written surfaces, per group (see surface_group_quality.h).
#include "core/quality/surface_group_quality.h"

namespace vm {

std::vector<SurfaceGroupQuality> surface_group_quality(const VolumeMesh& mesh,
                                                       const std::vector<std::string>& names,
                                                       size_t ring_first, size_t ring_end,
                                                       int bins) {
  std::vector<std::vector<float>> plain(names.size()), ring(names.size());
  for (size_t t = 0; t < mesh.num_triangles(); ++t) {
    const int32_t* v = &mesh.triangles[3 * t];
    const auto p = [&](int k) { return &mesh.points[3 * size_t(v[k])]; };
    const float g = float(triangle_gamma(p(0), p(1), p(2)));
    const size_t tag = size_t(mesh.triangle_tag[t]);
    (t >= ring_first && t < ring_end ? ring : plain)[tag].push_back(g);
  }
  std::vector<SurfaceGroupQuality> out;
  for (size_t tag = 0; tag < names.size(); ++tag) {
    if (names[tag].empty() || (plain[tag].empty() && ring[tag].empty())) continue;
    SurfaceGroupQuality g;
    g.name = names[tag];
    g.tag = int32_t(tag);
    g.quality = quality_stats(plain[tag], bins);
    if (!ring[tag].empty()) g.ring = quality_stats(ring[tag], bins);
    out.push_back(std::move(g));
  }
  return out;
}

}  // namespace vm
