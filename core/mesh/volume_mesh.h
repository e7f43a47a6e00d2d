// Indexed volume mesh: the mesh type the cap, layer and volume stages write
// and the MSH writer reads (Marchandise et al., sections 2.2 and 3).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace vm {

/// Signed volume times 6 of the tetrahedron a, b, c, d (3 doubles each):
/// ((b - a) x (c - a)) . (d - a). Positive for the orientation every
/// vesselmesh tetrahedron has (Gmsh's convention), i.e. orient3d(a, b, c, d)
/// < 0 in the predicates' sign convention.
inline double tet_volume6(const double* a, const double* b, const double* c, const double* d) {
  const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  const double w[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
  return (u[1] * v[2] - u[2] * v[1]) * w[0] + (u[2] * v[0] - u[0] * v[2]) * w[1] +
         (u[0] * v[1] - u[1] * v[0]) * w[2];
}

/// Face k of a positive tetrahedron (the face opposite vertex k), as slots
/// ordered counterclockwise seen from outside: its normal points out of the
/// tetrahedron, and orient3d(face, q) < 0 iff q is strictly outside face k.
/// The one face table of the C++ code; web/src/clip.js keeps a copy
/// (TET_FACES), compared with this one by web/test/clip-faces.test.js.
inline constexpr int kFaceOut[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};

/// A volume mesh with its boundary, as flat arrays.
/// - points: 3 doubles per vertex.
/// - tets: 4 vertex indices per tetrahedron, tet_volume6 > 0.
/// - prisms: 6 per prism, nodes 0-1-2 the bottom triangle, 3-4-5 the top,
///   node 3 above 0 (MSH type 6, Gmsh's reference prism): the bottom is
///   counterclockwise seen from the top, so tet_volume6(0, 1, 2, 3) > 0 and
///   every sub-tetrahedron of a valid prism is positive.
/// - tet_region / prism_region: one region tag per element (>= 0): the
///   physical volume the element belongs to.
/// - triangles: 3 per boundary or interface triangle, oriented outward of the
///   region they bound; triangle_tag: one surface tag per triangle (>= 0).
/// - quads: 4 per boundary or interface quadrilateral (the side faces of
///   kept prisms), a cycle oriented like the triangles; quad_tag likewise.
struct VolumeMesh {
  std::vector<double> points;
  std::vector<int32_t> tets;
  std::vector<int32_t> tet_region;
  std::vector<int32_t> prisms;
  std::vector<int32_t> prism_region;
  std::vector<int32_t> triangles;
  std::vector<int32_t> triangle_tag;
  std::vector<int32_t> quads;
  std::vector<int32_t> quad_tag;

  size_t num_vertices() const { return points.size() / 3; }
  size_t num_tets() const { return tets.size() / 4; }
  size_t num_prisms() const { return prisms.size() / 6; }
  size_t num_triangles() const { return triangles.size() / 3; }
  size_t num_quads() const { return quads.size() / 4; }
};

}  // namespace vm
