// Mutable region mesh for local reconnection and smoothing (Shewchuk 2002;
// Klingner and Shewchuk 2007); see tet_mesh.h for the layout.
#include "core/volume/tet_mesh.h"

#include <algorithm>
#include <string>

#include "core/geom/predicates.h"
#include "core/mesh/tet_face_adjacency.h"
#include "core/volume/delaunay3d.h"

namespace vm {
Result<TetMesh> TetMesh::from_kernel(const Delaunay3D& kernel, int32_t tag,
                                     const std::vector<int32_t>& vertex_map, int32_t num_vertices,
                                     std::vector<uint8_t> fixed) {
  using R = Result<TetMesh>;
  if (vertex_map.size() != kernel.num_vertices())
    return R::Error("tet mesh: one vertex_map entry per kernel vertex expected");
  if (num_vertices < 0 || fixed.size() != size_t(num_vertices))
    return R::Error("tet mesh: one fixed flag per vertex expected");
  TetMesh m;
  m.pts_.assign(3 * size_t(num_vertices), 0.0);
  std::vector<uint8_t> seen(size_t(num_vertices), 0);
  for (size_t v = 0; v < vertex_map.size(); ++v) {
    const int32_t w = vertex_map[v];
    if (w < 0) continue;
    if (w >= num_vertices) return R::Error("tet mesh: vertex_map entry out of range");
    for (int k = 0; k < 3; ++k) m.pts_[3 * size_t(w) + size_t(k)] = kernel.point(int32_t(v))[k];
    seen[size_t(w)] = 1;
  }
  m.fixed_ = std::move(fixed);
  TetTopology& tp = m.topo_;
  tp.vertex_tet.assign(size_t(num_vertices), -1);
  // Phase 1: ids of the region's tetrahedra, ordered by their smallest
  // mesh vertex (a counting sort: with vertices numbered along a curve,
  // neighbors get nearby ids, which keeps the optimizer's memory accesses
  // local); ties in kernel id order.
  const int32_t cap = int32_t(kernel.tet_capacity());
  std::vector<int32_t> id(size_t(cap), -1);
  std::vector<int32_t> first(size_t(num_vertices) + 1, 0);
  for (int32_t t = 0; t < cap; ++t) {
    if (!kernel.is_live(t) || kernel.is_ghost(t) || kernel.tag(t) != tag) continue;
    int32_t lo = INT32_MAX;
    for (int k = 0; k < 4; ++k) {
      const int32_t w = vertex_map[size_t(kernel.tet(t)[k])];
      if (w < 0) return R::Error("tet mesh: a region vertex is not mapped");
      lo = std::min(lo, w);
    }
    id[size_t(t)] = lo;
    ++first[size_t(lo) + 1];
  }
  for (size_t v = 0; v < size_t(num_vertices); ++v) first[v + 1] += first[v];
  const int32_t n = first[size_t(num_vertices)];
  for (int32_t t = 0; t < cap; ++t)
    if (id[size_t(t)] >= 0) id[size_t(t)] = first[size_t(id[size_t(t)])]++;
  tp.tets.resize(size_t(n));
  tp.constrained.assign(size_t(n), 0);
  tp.tagged = false;
  // Phase 2: vertices, neighbors and constraints (slots kept, so the
  // kernel's face indices stay valid).
  for (int32_t t = 0; t < cap; ++t) {
    const int32_t i = id[size_t(t)];
    if (i < 0) continue;
    for (int k = 0; k < 4; ++k) {
      const int32_t w = vertex_map[size_t(kernel.tet(t)[k])];
      tp.tets[size_t(i)].v[k] = w;
      tp.vertex_tet[size_t(w)] = i;
      const int32_t e = kernel.neighbor(t, k);
      const int32_t u = id[size_t(e >> 2)];
      tp.tets[size_t(i)].n[k] = u >= 0 ? 4 * u + (e & 3) : kBoundary;
      if (u >= 0 && kernel.is_constrained(t, k)) tp.constrained[size_t(i)] |= uint8_t(1u << k);
    }
  }
  tp.stamp.assign(size_t(n), 0);
  return m;
}

Result<TetMesh> TetMesh::from_arrays(std::vector<double> points, const std::vector<int32_t>& tets,
                                     std::vector<uint8_t> fixed) {
  using R = Result<TetMesh>;
  if (points.size() % 3 != 0 || tets.size() % 4 != 0)
    return R::Error("tet mesh: array sizes not multiples of 3 / 4");
  const size_t nv = points.size() / 3;
  if (fixed.size() != nv) return R::Error("tet mesh: one fixed flag per vertex expected");
  for (int32_t v : tets)
    if (v < 0 || size_t(v) >= nv) return R::Error("tet mesh: vertex index out of range");
  TetMesh m;
  m.pts_ = std::move(points);
  m.fixed_ = std::move(fixed);
  TetTopology& tp = m.topo_;
  const size_t nt = tets.size() / 4;
  tp.vertex_tet.assign(nv, -1);
  tp.tets.resize(nt);
  for (size_t t = 0; t < nt; ++t)
    for (int k = 0; k < 4; ++k) {
      tp.tets[t].v[k] = tets[4 * t + size_t(k)];
      tp.tets[t].n[k] = kBoundary;
    }
  tp.constrained.assign(nt, 0);
  tp.tagged = false;
  tp.stamp.assign(nt, 0);
  for (size_t i = 0; i < tets.size(); ++i) tp.vertex_tet[size_t(tets[i])] = int32_t(i / 4);
  // Faces matched by the one tetrahedron face adjacency (its boundary entry
  // is kBoundary).
  static_assert(kBoundary == kNoTetAcross);
  auto across = tet_face_adjacency(tets.data(), nt, nv);
  if (!across.ok()) return R::Error("tet mesh: a face shared by more than two tetrahedra");
  for (size_t i = 0; i < tets.size(); ++i) tp.link(int32_t(i)) = across.value()[i];
  return m;
}

int32_t TetMesh::add_vertex(const double* p) {
  pts_.insert(pts_.end(), {p[0], p[1], p[2]});
  fixed_.push_back(0);
  topo_.vertex_tet.push_back(-1);
  return int32_t(topo_.vertex_tet.size() - 1);
}

std::vector<int32_t> TetMesh::tets() const {
  std::vector<int32_t> out;
  out.reserve(4 * num_tets());
  for (int32_t t = 0; t < int32_t(capacity()); ++t)
    if (is_live(t)) out.insert(out.end(), tet(t), tet(t) + 4);
  return out;
}

Status TetMesh::check() const {
  if (Status s = check_topology(topo_, num_vertices(), false, true); !s.ok())
    return Status::Error("tet mesh: " + s.message());
  for (int32_t t = 0; t < int32_t(capacity()); ++t) {
    if (!is_live(t)) continue;
    const int32_t* v = tet(t);
    if (orient3d(point(v[0]), point(v[1]), point(v[2]), point(v[3])) >= 0)
      return Status::Error("tet mesh: tetrahedron not positive (tetrahedron " + std::to_string(t) +
                           ")");
  }
  return Status::Ok();
}

}  // namespace vm
