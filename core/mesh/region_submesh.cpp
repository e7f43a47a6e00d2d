// The part of a volume mesh made of some of its regions (see
// region_submesh.h).
#include "core/mesh/region_submesh.h"

#include <algorithm>
#include <array>
#include <map>

namespace vm {
namespace {

using Key = std::array<int32_t, 4>;

/// A face's vertices, sorted, a triangle's fourth -1.
Key face_key(const int32_t* v, int n) {
  Key k{v[0], v[1], v[2], n == 4 ? v[3] : -1};
  if (n == 4)
    std::sort(k.begin(), k.end());
  else
    std::sort(k.begin(), k.begin() + 3);
  return k;
}

// The faces of a tetrahedron and of a prism (MSH node order), as local
// vertex lists (-1: a triangle).
constexpr int kTetFaces[4][4] = {{1, 2, 3, -1}, {0, 3, 2, -1}, {0, 1, 3, -1}, {0, 2, 1, -1}};
constexpr int kPrismFaces[5][4] = {
    {0, 2, 1, -1}, {3, 4, 5, -1}, {0, 1, 4, 3}, {1, 2, 5, 4}, {2, 0, 3, 5}};

}  // namespace

VolumeMesh region_submesh(const VolumeMesh& mesh, const std::vector<int32_t>& regions) {
  const auto kept = [&](int32_t region) {
    return std::find(regions.begin(), regions.end(), region) != regions.end();
  };
  VolumeMesh out;
  // Phase 1: the kept cells, and each of their faces with the cell's
  // centroid (a face is oriented out of its cell when the centroid is
  // behind it).
  std::map<Key, std::array<double, 3>> centroid_of_face;
  const auto add_cell = [&](const int32_t* v, int n, const auto& faces, int nfaces) {
    std::array<double, 3> c{};
    for (int i = 0; i < n; ++i)
      for (int k = 0; k < 3; ++k) c[size_t(k)] += mesh.points[3 * size_t(v[i]) + size_t(k)] / n;
    for (int f = 0; f < nfaces; ++f) {
      int32_t fv[4];
      const int m = faces[f][3] < 0 ? 3 : 4;
      for (int i = 0; i < m; ++i) fv[i] = v[faces[f][i]];
      centroid_of_face[face_key(fv, m)] = c;
    }
  };
  for (size_t t = 0; t < mesh.num_tets(); ++t) {
    if (!kept(mesh.tet_region[t])) continue;
    out.tets.insert(out.tets.end(), &mesh.tets[4 * t], &mesh.tets[4 * t] + 4);
    out.tet_region.push_back(mesh.tet_region[t]);
    add_cell(&mesh.tets[4 * t], 4, kTetFaces, 4);
  }
  for (size_t q = 0; q < mesh.num_prisms(); ++q) {
    if (!kept(mesh.prism_region[q])) continue;
    out.prisms.insert(out.prisms.end(), &mesh.prisms[6 * q], &mesh.prisms[6 * q] + 6);
    out.prism_region.push_back(mesh.prism_region[q]);
    add_cell(&mesh.prisms[6 * q], 6, kPrismFaces, 5);
  }
  // Phase 2: the faces bounding a kept cell, pointing out of it.
  const auto keep_faces = [&](const std::vector<int32_t>& faces, const std::vector<int32_t>& tags,
                              int n, std::vector<int32_t>& out_faces,
                              std::vector<int32_t>& out_tags) {
    for (size_t f = 0; f < tags.size(); ++f) {
      const int32_t* v = &faces[size_t(n) * f];
      const auto it = centroid_of_face.find(face_key(v, n));
      if (it == centroid_of_face.end()) continue;
      const double* a = &mesh.points[3 * size_t(v[0])];
      const double* b = &mesh.points[3 * size_t(v[1])];
      const double* c = &mesh.points[3 * size_t(v[2])];
      const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
      const double w[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
      const double normal[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2],
                                u[0] * w[1] - u[1] * w[0]};
      double side = 0;
      for (int k = 0; k < 3; ++k) side += normal[k] * (it->second[size_t(k)] - a[k]);
      std::vector<int32_t> face(v, v + n);
      if (side > 0) std::reverse(face.begin(), face.end());  // it pointed into the cell
      out_faces.insert(out_faces.end(), face.begin(), face.end());
      out_tags.push_back(tags[f]);
    }
  };
  keep_faces(mesh.triangles, mesh.triangle_tag, 3, out.triangles, out.triangle_tag);
  keep_faces(mesh.quads, mesh.quad_tag, 4, out.quads, out.quad_tag);
  // Phase 3: only the points used, in their original order.
  std::vector<int32_t> index(mesh.num_vertices(), -1);
  for (const std::vector<int32_t>* cells : {&out.tets, &out.prisms, &out.triangles, &out.quads})
    for (int32_t v : *cells) index[size_t(v)] = 0;
  int32_t next = 0;
  for (size_t v = 0; v < index.size(); ++v) {
    if (index[v] < 0) continue;
    index[v] = next++;
    out.points.insert(out.points.end(), &mesh.points[3 * v], &mesh.points[3 * v] + 3);
  }
  for (std::vector<int32_t>* cells : {&out.tets, &out.prisms, &out.triangles, &out.quads})
    for (int32_t& v : *cells) v = index[size_t(v)];
  return out;
}

}  // namespace vm
