// The part of a volume mesh made of some of its regions (see
// region_submesh.h).
#include "core/mesh/region_submesh.h"

#include <algorithm>
#include <array>

#include "core/mesh/face_groups.h"

namespace vm {

VolumeMesh region_submesh(const VolumeMesh& mesh, const std::vector<int32_t>& regions) {
  const auto kept = [&](int32_t region) {
    return std::find(regions.begin(), regions.end(), region) != regions.end();
  };
  const size_t nt = mesh.num_tets(), np = mesh.num_prisms();
  VolumeMesh out;
  // Phase 1: the kept cells.
  std::vector<uint8_t> cell_kept(nt + np, 0);
  for (size_t t = 0; t < nt; ++t) {
    if (!kept(mesh.tet_region[t])) continue;
    cell_kept[t] = 1;
    out.tets.insert(out.tets.end(), &mesh.tets[4 * t], &mesh.tets[4 * t] + 4);
    out.tet_region.push_back(mesh.tet_region[t]);
  }
  for (size_t q = 0; q < np; ++q) {
    if (!kept(mesh.prism_region[q])) continue;
    cell_kept[nt + q] = 1;
    out.prisms.insert(out.prisms.end(), &mesh.prisms[6 * q], &mesh.prisms[6 * q] + 6);
    out.prism_region.push_back(mesh.prism_region[q]);
  }
  // Phase 2: each face of the mesh (triangles, then quads) on a kept cell:
  // the last such cell in the element order (tetrahedra, then prisms).
  const std::vector<int32_t> faces = volume_mesh_faces(mesh);
  const size_t cell_faces = 4 * nt + 5 * np;
  const FaceGroups groups = group_faces(faces.data(), faces.size() / 4, mesh.num_vertices());
  std::vector<int64_t> cell_of(faces.size() / 4 - cell_faces, -1);
  for (size_t g = 0; g < groups.num_groups(); ++g) {
    int64_t cell = -1;
    for (size_t k = 0; k < groups.size(g); ++k) {
      const size_t i = groups.face(g, k);
      if (i < cell_faces) {
        if (cell_kept[face_element(i, nt)]) cell = int64_t(face_element(i, nt));
      } else {
        cell_of[i - cell_faces] = cell;
      }
    }
  }
  // Phase 3: those faces, pointing out of their cell (its centroid behind
  // them).
  const auto centroid = [&](int64_t cell) {
    const bool tet = size_t(cell) < nt;
    const int n = tet ? 4 : 6;
    const int32_t* v = tet ? &mesh.tets[4 * size_t(cell)] : &mesh.prisms[6 * (size_t(cell) - nt)];
    std::array<double, 3> c{};
    for (int i = 0; i < n; ++i)
      for (int k = 0; k < 3; ++k) c[size_t(k)] += mesh.points[3 * size_t(v[i]) + size_t(k)] / n;
    return c;
  };
  const auto keep_faces = [&](const std::vector<int32_t>& faces, const std::vector<int32_t>& tags,
                              int n, size_t first, std::vector<int32_t>& out_faces,
                              std::vector<int32_t>& out_tags) {
    for (size_t f = 0; f < tags.size(); ++f) {
      const int64_t cell = cell_of[first + f];
      if (cell < 0) continue;
      const std::array<double, 3> c = centroid(cell);
      const int32_t* v = &faces[size_t(n) * f];
      const double* a = &mesh.points[3 * size_t(v[0])];
      const double* b = &mesh.points[3 * size_t(v[1])];
      const double* d = &mesh.points[3 * size_t(v[2])];
      const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
      const double w[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
      const double normal[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2],
                                u[0] * w[1] - u[1] * w[0]};
      double side = 0;
      for (int k = 0; k < 3; ++k) side += normal[k] * (c[size_t(k)] - a[k]);
      std::vector<int32_t> face(v, v + n);
      if (side > 0) std::reverse(face.begin(), face.end());  // it pointed into the cell
      out_faces.insert(out_faces.end(), face.begin(), face.end());
      out_tags.push_back(tags[f]);
    }
  };
  keep_faces(mesh.triangles, mesh.triangle_tag, 3, 0, out.triangles, out.triangle_tag);
  keep_faces(mesh.quads, mesh.quad_tag, 4, mesh.num_triangles(), out.quads, out.quad_tag);
  // Phase 4: only the points used, in their original order.
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
