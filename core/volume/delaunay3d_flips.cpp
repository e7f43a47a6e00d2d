// Flips of Delaunay3D: 2-3, 3-2, 4-4 and edge removal (Shewchuk, "Two
// discrete optimization algorithms for the topological improvement of
// tetrahedral meshes", 2002), all through replace_tets(), which checks the
// new tetrahedra exactly (orient3d; a new ghost keeps the hull convex) and
// matches their faces with the old set's (core/volume/tet_topology.h).
// Used by boundary recovery; see delaunay3d.h.
#include <algorithm>
#include <cmath>
#include <string>

#include "core/geom/predicates.h"
#include "core/volume/delaunay3d.h"
#include "core/volume/delaunay3d_internal.h"
#include "core/volume/edge_removal.h"

namespace vm {

using delaunay3d_detail::collinear;
using delaunay3d_detail::inf_slot;

// ---------------------------------------------------------------- flips

bool Delaunay3D::new_tet_valid(const std::array<int32_t, 4>& q,
                               const std::vector<int32_t>& around) const {
  const int g = inf_slot(q.data());
  if (g < 0) return orient3d(point(q[0]), point(q[1]), point(q[2]), point(q[3])) < 0;
  // A ghost: its hull face is a proper triangle and no vertex of the
  // region is beyond it (the hull stays convex).
  const double* f[3];
  for (int s = 0, m = 0; s < 4; ++s)
    if (s != g) f[m++] = point(q[size_t(s)]);
  if (collinear(f[0], f[1], f[2])) return false;
  const double* c[4];
  for (int s = 0; s < 4; ++s) c[s] = s == g ? nullptr : point(q[size_t(s)]);
  for (int32_t w : around) {
    if (w == q[0] || w == q[1] || w == q[2] || w == q[3]) continue;
    c[g] = point(w);
    if (orient3d(c[0], c[1], c[2], c[3]) < 0) return false;
  }
  return true;
}

Result<std::vector<int32_t>> Delaunay3D::replace_tets(
    const std::vector<int32_t>& old_tets, const std::vector<std::array<int32_t, 4>>& new_tets) {
  using R = Result<std::vector<int32_t>>;
  if (old_tets.empty() || new_tets.empty()) return R::Error("replace_tets: empty set");
  for (int32_t t : old_tets)
    if (t < 0 || size_t(t) >= tet_capacity() || !is_live(t))
      return R::Error("replace_tets: an old tetrahedron is not live");
  // Phase 1: orientation of the new set (a ghost: its hull face against
  // the vertices of the old set).
  std::vector<int32_t> old_vertices;
  for (int32_t t : old_tets)
    for (int s = 0; s < 4; ++s)
      if (tet(t)[s] != kInfinite) old_vertices.push_back(tet(t)[s]);
  std::sort(old_vertices.begin(), old_vertices.end());
  old_vertices.erase(std::unique(old_vertices.begin(), old_vertices.end()), old_vertices.end());
  for (const auto& q : new_tets) {
    int infs = 0;
    for (int32_t x : q) {
      if (x == kInfinite) {
        ++infs;
        continue;
      }
      if (x < 0 || size_t(x) >= num_vertices())
        return R::Error("replace_tets: a new tetrahedron has an invalid vertex");
    }
    if (infs > 1 || !new_tet_valid(q, old_vertices))
      return R::Error("replace_tets: a new tetrahedron is not positive");
  }
  // Phase 2: face matching and commit.
  std::vector<int32_t> ids;
  switch (vm::replace_tets(topo_, old_tets.data(), int(old_tets.size()), new_tets.data(),
                           int(new_tets.size()), ids, replace_scratch_)) {
    case ReplaceError::kNone:
      break;
    case ReplaceError::kConstrainedInside:
      return R::Error("replace_tets: would remove a constrained face");
    case ReplaceError::kUnmatchedFace:
      return R::Error("replace_tets: the new set does not fill the old one");
    case ReplaceError::kUncoveredFace:
      return R::Error("replace_tets: the new set leaves a boundary face uncovered");
    case ReplaceError::kNoRoom:  // only with a slot pool
      return R::Error("replace_tets: no free slot");
  }
  seq_.last = ids[0];
  delaunay_ = false;
  ++seq_.stats.flips;
  return ids;
}

Result<std::array<int32_t, 3>> Delaunay3D::flip23(int32_t t, int k) {
  using R = Result<std::array<int32_t, 3>>;
  if (t < 0 || size_t(t) >= tet_capacity() || !is_live(t) || k < 0 || k > 3)
    return R::Error("flip23: invalid face");
  const int32_t u = neighbor(t, k) >> 2;
  if (is_ghost(t) || is_ghost(u)) return R::Error("flip23: a hull face");
  std::vector<std::array<int32_t, 4>> nt(3);
  flip23_tets(topo_, t, k, nt.data());
  auto res = replace_tets({t, u}, nt);
  if (!res.ok()) return R::Error("flip23: " + res.message());
  return std::array<int32_t, 3>{res.value()[0], res.value()[1], res.value()[2]};
}

Result<std::vector<int32_t>> Delaunay3D::remove_edge(int32_t t, int32_t a, int32_t b) {
  using R = Result<std::vector<int32_t>>;
  if (t < 0 || size_t(t) >= tet_capacity() || !is_live(t) || slot_of(tet(t), a) < 0 ||
      slot_of(tet(t), b) < 0 || a == b)
    return R::Error("remove_edge: (a, b) is not an edge of t");
  std::vector<int32_t> ring_tets, ring;
  edge_ring(t, a, b, ring_tets, ring);
  if (a == kInfinite || b == kInfinite) return R::Error("remove_edge: an edge at infinity");
  std::vector<int32_t> around = ring;
  around.insert(around.end(), {a, b});
  around.erase(std::remove(around.begin(), around.end(), kInfinite), around.end());
  const size_t n = ring.size();
  if (n < 3) return R::Error("remove_edge: fewer than 3 tetrahedra around the edge");
  // The fan from one ring vertex whose smallest tetrahedron shape (its
  // volume over its longest edge cubed; ghosts have none) is largest, every
  // new tetrahedron valid (core/volume/edge_removal.h). Ring order makes
  // (a, b, r_i, r_i+1) positive, hence (r_x, r_y, r_z, b) and
  // (r_y, r_x, r_z, a) for a triangle (x, y, z) in ring order.
  auto shape = [&](int x, int y, int z, double) {
    std::array<int32_t, 4> two[2];
    ring_triangle_tets(a, b, ring[size_t(x)], ring[size_t(y)], ring[size_t(z)], two);
    double q = 1e300;
    for (const auto& c : two) {
      if (!new_tet_valid(c, around)) return -HUGE_VAL;
      if (inf_slot(c.data()) >= 0) continue;  // ghosts: no shape
      const double* p[4] = {point(c[0]), point(c[1]), point(c[2]), point(c[3])};
      double vol = -((p[1][0] - p[0][0]) * ((p[2][1] - p[0][1]) * (p[3][2] - p[0][2]) -
                                            (p[2][2] - p[0][2]) * (p[3][1] - p[0][1])) -
                     (p[1][1] - p[0][1]) * ((p[2][0] - p[0][0]) * (p[3][2] - p[0][2]) -
                                            (p[2][2] - p[0][2]) * (p[3][0] - p[0][0])) +
                     (p[1][2] - p[0][2]) * ((p[2][0] - p[0][0]) * (p[3][1] - p[0][1]) -
                                            (p[2][1] - p[0][1]) * (p[3][0] - p[0][0])));
      double longest = 0;
      for (int i = 0; i < 4; ++i)
        for (int j = i + 1; j < 4; ++j) {
          double d2 = 0;
          for (int m = 0; m < 3; ++m) d2 += (p[i][m] - p[j][m]) * (p[i][m] - p[j][m]);
          longest = std::max(longest, d2);
        }
      q = std::min(q, std::fabs(vol) / (longest * std::sqrt(longest)));
    }
    return q;
  };
  // Any valid fan (shapes are >= 0), the best one.
  std::vector<RingTriangle> tris;
  best_ring_triangulation(int(n), RingCandidates::kFans, -1, shape, &tris);
  if (tris.empty()) return R::Error("remove_edge: no fan of the ring gives positive tetrahedra");
  std::vector<std::array<int32_t, 4>> best(2 * tris.size());
  ring_removal_tets(a, b, ring.data(), tris, best.data());
  auto res = replace_tets(ring_tets, best);
  if (!res.ok()) return R::Error("remove_edge: " + res.message());
  return res;
}

Status Delaunay3D::flip_ring(const char* name, int32_t t, int32_t a, int32_t b, size_t n,
                             std::vector<int32_t>& ring_tets, std::vector<int32_t>& ring) const {
  if (t < 0 || size_t(t) >= tet_capacity() || !is_live(t) || slot_of(tet(t), a) < 0 ||
      slot_of(tet(t), b) < 0 || a == b)
    return Status::Error(std::string(name) + ": (a, b) is not an edge of t");
  edge_ring(t, a, b, ring_tets, ring);
  if (ring.size() != n)
    return Status::Error(std::string(name) + ": the edge is not in exactly " + std::to_string(n) +
                         " tetrahedra");
  return Status::Ok();
}

Result<std::array<int32_t, 2>> Delaunay3D::flip32(int32_t t, int32_t a, int32_t b) {
  using R = Result<std::array<int32_t, 2>>;
  std::vector<int32_t> ring_tets, ring;
  if (Status st = flip_ring("flip32", t, a, b, 3, ring_tets, ring); !st.ok()) return st;
  auto res = remove_edge(t, a, b);
  if (!res.ok()) return R::Error(res.message());
  return std::array<int32_t, 2>{res.value()[0], res.value()[1]};
}

Result<std::array<int32_t, 4>> Delaunay3D::flip44(int32_t t, int32_t a, int32_t b, int32_t c) {
  using R = Result<std::array<int32_t, 4>>;
  std::vector<int32_t> ring_tets, ring;
  if (Status st = flip_ring("flip44", t, a, b, 4, ring_tets, ring); !st.ok()) return st;
  auto it = std::find(ring.begin(), ring.end(), c);
  if (it == ring.end() || c == kInfinite)
    return R::Error("flip44: c is not a finite vertex on the ring of the edge");
  const size_t s = size_t(it - ring.begin());
  std::vector<std::array<int32_t, 4>> nt;
  for (size_t i = 1; i <= 2; ++i) {
    const int32_t x = ring[s], y = ring[(s + i) % 4], z = ring[(s + i + 1) % 4];
    nt.resize(nt.size() + 2);
    ring_triangle_tets(a, b, x, y, z, &nt[nt.size() - 2]);
  }
  auto res = replace_tets(ring_tets, nt);
  if (!res.ok()) return R::Error("flip44: " + res.message());
  const auto& ids = res.value();
  return std::array<int32_t, 4>{ids[0], ids[1], ids[2], ids[3]};
}

}  // namespace vm
