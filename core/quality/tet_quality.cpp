// gamma_t = 6 sqrt(6) V / (S_sum L_max) (Marchandise et al., section 3, the
// measure of their volume meshes). With V = vol6 / 6 this is
// sqrt(6) vol6 / (S_sum L_max); for the regular tetrahedron of edge a,
// V = a^3 / (6 sqrt 2) and S_sum = sqrt(3) a^2, so gamma = 1.
// Dihedral angles: at edge (i, j) with opposite corners k, l, the interior
// angle is the angle between e x (k - i) and e x (l - i), e = j - i (both
// are the in-plane directions of the two faces, rotated by 90 degrees about
// e), evaluated with atan2 for accuracy near 0 and 180.
#include "core/quality/tet_quality.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/geom/vec3.h"
#include "core/util/parallel.h"
#include "core/util/portable_math.h"

namespace vm {
namespace {

using v3::cross;
using v3::dot;
using v3::norm;
using v3::sub;

const double* corner(const std::vector<double>& points, int32_t v) {
  return &points[3 * size_t(v)];
}

}  // namespace

std::vector<float> tet_qualities(const std::vector<double>& points,
                                 const std::vector<int32_t>& tets) {
  std::vector<float> q(tets.size() / 4);
  parallel_for(q.size(), 16384, [&](size_t begin, size_t end) {
    for (size_t t = begin; t < end; ++t) {
      const int32_t* v = &tets[4 * t];
      q[t] = float(tet_gamma(corner(points, v[0]), corner(points, v[1]), corner(points, v[2]),
                             corner(points, v[3])));
    }
  });
  return q;
}

std::vector<float> tet_qualities(const VolumeMesh& mesh) {
  return tet_qualities(mesh.points, mesh.tets);
}

DihedralRange tet_dihedral_range(const double* a, const double* b, const double* c,
                                 const double* d) {
  const double* p[4] = {a, b, c, d};
  // Edge (i, j) and its opposite corners (k, l).
  static const int kEdges[6][4] = {{0, 1, 2, 3}, {0, 2, 1, 3}, {0, 3, 1, 2},
                                   {1, 2, 0, 3}, {1, 3, 0, 2}, {2, 3, 0, 1}};
  DihedralRange r;
  for (const auto& E : kEdges) {
    double e[3], x[3], y[3], u[3], w[3], uw[3];
    sub(p[E[1]], p[E[0]], e);
    sub(p[E[2]], p[E[0]], x);
    sub(p[E[3]], p[E[0]], y);
    cross(e, x, u);
    cross(e, y, w);
    double angle;
    if (norm(u) == 0 || norm(w) == 0) {
      r.min = 0;
      r.max = 180;
      continue;
    }
    cross(u, w, uw);
    angle = pm::atan2(norm(uw), dot(u, w)) * (180.0 / std::numbers::pi);
    r.min = std::min(r.min, angle);
    r.max = std::max(r.max, angle);
  }
  return r;
}

DihedralRange dihedral_range(const std::vector<double>& points, const std::vector<int32_t>& tets) {
  DihedralRange r;
  for (size_t t = 0; 4 * t + 3 < tets.size(); ++t) {
    const int32_t* v = &tets[4 * t];
    DihedralRange one = tet_dihedral_range(corner(points, v[0]), corner(points, v[1]),
                                           corner(points, v[2]), corner(points, v[3]));
    r.min = std::min(r.min, one.min);
    r.max = std::max(r.max, one.max);
  }
  return r;
}

}  // namespace vm
