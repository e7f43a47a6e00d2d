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

namespace vm {
namespace {

inline void sub(const double* a, const double* b, double* out) {
  for (int k = 0; k < 3; ++k) out[k] = a[k] - b[k];
}
inline void cross(const double* u, const double* v, double* out) {
  out[0] = u[1] * v[2] - u[2] * v[1];
  out[1] = u[2] * v[0] - u[0] * v[2];
  out[2] = u[0] * v[1] - u[1] * v[0];
}
inline double dot(const double* u, const double* v) {
  return u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
}
inline double norm(const double* u) { return std::sqrt(dot(u, u)); }

// Twice the area of triangle a, b, c.
double area2(const double* a, const double* b, const double* c) {
  double u[3], v[3], n[3];
  sub(b, a, u);
  sub(c, a, v);
  cross(u, v, n);
  return norm(n);
}

const double* corner(const std::vector<double>& points, int32_t v) {
  return &points[3 * size_t(v)];
}

}  // namespace

double tet_gamma(const double* a, const double* b, const double* c, const double* d) {
  const double vol6 = tet_volume6(a, b, c, d);
  const double faces = 0.5 * (area2(a, b, c) + area2(a, b, d) + area2(a, c, d) + area2(b, c, d));
  const double* p[4] = {a, b, c, d};
  double longest2 = 0;
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) {
      double e[3];
      sub(p[j], p[i], e);
      longest2 = std::max(longest2, dot(e, e));
    }
  const double den = faces * std::sqrt(longest2);
  if (!(den > 0)) return 0.0;
  return std::clamp(std::sqrt(6.0) * vol6 / den, -1.0, 1.0);
}

std::vector<float> tet_qualities(const std::vector<double>& points,
                                 const std::vector<int32_t>& tets) {
  std::vector<float> q(tets.size() / 4);
  for (size_t t = 0; t < q.size(); ++t) {
    const int32_t* v = &tets[4 * t];
    q[t] = float(tet_gamma(corner(points, v[0]), corner(points, v[1]), corner(points, v[2]),
                           corner(points, v[3])));
  }
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
    angle = std::atan2(norm(uw), dot(u, w)) * (180.0 / std::numbers::pi);
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
