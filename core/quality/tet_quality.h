// Tetrahedron quality gamma_t of the seed paper (Marchandise et al., section
// 3): gamma = 6 sqrt(6) V / (sum of the 4 face areas * longest edge), 1 for
// the regular tetrahedron, 0 for a sliver or any flat one; plus dihedral
// angles, the usual companion measure of volume meshes.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/geom/vec3.h"
#include "core/mesh/volume_mesh.h"

namespace vm {

/// gamma_t of the tetrahedron a, b, c, d (3 doubles each), with the signed
/// volume V = tet_volume6(a, b, c, d) / 6 (positive for vesselmesh's
/// orientation, see volume_mesh.h). In (0, 1] for a valid tetrahedron, 1
/// only for the regular one; 0 for a flat one (coplanar corners) or one with
/// coincident corners; negative for an inverted one (-gamma of its mirror
/// image), so a single `min >= 0` check also catches inversions. Invariant
/// under translation, rotation and uniform scaling. Inline: the volume
/// optimizer evaluates it in its hot loops.
inline double tet_gamma(const double* a, const double* b, const double* c, const double* d) {
  using v3::cross, v3::dot, v3::sub;
  double ab[3], ac[3], ad[3], bc[3], bd[3], cd[3];
  sub(b, a, ab), sub(c, a, ac), sub(d, a, ad), sub(c, b, bc), sub(d, b, bd), sub(d, c, cd);
  double n1[3], n2[3], n3[3], n4[3];  // twice the face areas' vectors
  cross(ab, ac, n1), cross(ab, ad, n2), cross(ac, ad, n3), cross(bc, bd, n4);
  const double vol6 = dot(n1, ad);  // tet_volume6(a, b, c, d)
  const double faces = 0.5 * (std::sqrt(dot(n1, n1)) + std::sqrt(dot(n2, n2)) +
                              std::sqrt(dot(n3, n3)) + std::sqrt(dot(n4, n4)));
  const double longest2 =
      std::max({dot(ab, ab), dot(ac, ac), dot(ad, ad), dot(bc, bc), dot(bd, bd), dot(cd, cd)});
  const double den = faces * std::sqrt(longest2);
  if (!(den > 0)) return 0.0;
  return std::clamp(2.449489742783178 * vol6 / den, -1.0, 1.0);  // sqrt(6)
}

/// gamma_t of every tetrahedron of `points` (3 doubles per vertex) and `tets`
/// (4 indices each): tets.size() / 4 values. Summarize with quality_stats
/// (quality/triangle_quality.h; negative values fall in the first bin and
/// show in `min`). Precondition: indices in range.
std::vector<float> tet_qualities(const std::vector<double>& points,
                                 const std::vector<int32_t>& tets);

/// Same for the tetrahedra of `mesh` (prisms are not measured).
std::vector<float> tet_qualities(const VolumeMesh& mesh);

/// Smallest and largest interior dihedral angle, in degrees.
struct DihedralRange {
  double min = 180;
  double max = 0;
};

/// The six interior dihedral angles of the tetrahedron a, b, c, d (the angle
/// between the two faces at each edge, inside the solid), in degrees; 70.53
/// for all six of the regular tetrahedron. Orientation-independent: an
/// inverted tetrahedron has the angles of its mirror image. A flat one has
/// angles of 0 and 180; faces of zero area count as 0 and 180 too.
DihedralRange tet_dihedral_range(const double* a, const double* b, const double* c,
                                 const double* d);

/// Over all tetrahedra of `points` / `tets` (as tet_qualities); {180, 0}
/// when there is none.
DihedralRange dihedral_range(const std::vector<double>& points, const std::vector<int32_t>& tets);

}  // namespace vm
