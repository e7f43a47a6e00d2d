// Incremental 3D Delaunay triangulation (Bowyer 1981, Watson 1981) with
// BRIO/Hilbert order (Amenta, Choi, Rote 2003), exact predicates with
// symbolic perturbation (Shewchuk 1997; Edelsbrunner, Muecke 1990) and flips
// (Shewchuk 2002). See delaunay3d.h for the data layout. This file: build()
// (its phases: the first tetrahedron, the insertions, the input numbering
// restored), the topology queries and the invariant checks. The insertion
// kernel (location, cavity, star) is delaunay3d_insert.cpp, build()'s slab
// rounds and the partitioned insertion delaunay3d_rounds.cpp, the flips
// delaunay3d_flips.cpp.
#include "core/volume/delaunay3d.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/geom/predicates.h"
#include "core/volume/delaunay3d_internal.h"

namespace vm {

using delaunay3d_detail::collinear;
using delaunay3d_detail::same_point;

// ---------------------------------------------------------------- building

Result<Delaunay3D> Delaunay3D::build(std::vector<double> points, const BuildOptions& options) {
  if (!(options.parts >= 1 && options.parts <= 64) || !(options.min_part_points >= 1) ||
      !(options.retry_rounds >= 0))
    return Result<Delaunay3D>::Error(
        "Delaunay build: parts = " + std::to_string(options.parts) +
        ", min_part_points = " + std::to_string(options.min_part_points) +
        ", retry_rounds = " + std::to_string(options.retry_rounds) +
        "; options need 1 <= parts <= 64, min_part_points >= 1, retry_rounds >= 0");
  if (points.size() % 3 != 0) return Result<Delaunay3D>::Error("points: size not a multiple of 3");
  for (double x : points)
    if (!std::isfinite(x)) return Result<Delaunay3D>::Error("points: non-finite coordinate");
  const int64_t n = int64_t(points.size() / 3);
  if (n > int64_t(INT32_MAX / 8))
    return Result<Delaunay3D>::Error("points: too many for 32-bit tetrahedron ids");
  Delaunay3D d;
  // Vertices are numbered in insertion order while building, so that
  // consecutive insertions touch nearby memory (the input order is
  // arbitrary); Phase 3 restores the input numbering. Ties are broken by
  // input index throughout (sos_id_), so the result does not depend on it.
  std::vector<int32_t> order = brio_hilbert_order(points, options.sort);
  d.pts_.resize(points.size());
  for (int64_t i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k)
      d.pts_[3 * size_t(i) + k] = points[3 * size_t(order[size_t(i)]) + k];
  d.sos_id_ = order;
  d.dup_.assign(size_t(n), -1);
  for (int64_t i = 0; i < n; ++i) d.grow_box(d.point(int32_t(i)));
  d.topo_.vertex_tet.assign(size_t(n), -1);

  // Phase 1: the first tetrahedron from the first 4 affinely independent
  // points of the order.
  int32_t ib = -1, ic = -1, id = -1;
  for (int32_t i = 1; i < n && ib < 0; ++i)
    if (!same_point(d.point(0), d.point(i))) ib = i;
  for (int32_t i = ib + 1; ib > 0 && i < n && ic < 0; ++i)
    if (!collinear(d.point(0), d.point(ib), d.point(i))) ic = i;
  for (int32_t i = ic + 1; ic > 0 && i < n && id < 0; ++i)
    if (orient3d(d.point(0), d.point(ib), d.point(ic), d.point(i)) != 0) id = i;
  if (id < 0)
    return Result<Delaunay3D>::Error(
        "points: fewer than 4 affinely independent points (all coplanar, collinear or equal)");
  // About 6.7 tetrahedra a vertex (build_insertions() adds the room its
  // rounds leave unused).
  d.topo_.reserve(size_t(n) * 7 + 16);
  d.init_first_tet(0, ib, ic, id);

  // Phase 2: the other points in order.
  d.building_ = true;
  const int32_t first[4] = {0, ib, ic, id};
  d.build_insertions(options, first);
  d.building_ = false;

  // Phase 3: back to input numbering, and vertex_tet, which the stars
  // above left to this pass.
  std::vector<int32_t> vtet(static_cast<size_t>(n), -1), dup(static_cast<size_t>(n));
  for (int32_t t = 0; t < int32_t(d.topo_.capacity()); ++t) {
    int32_t* v = d.topo_.tets[size_t(t)].v;
    if (v[0] == kFree) continue;
    for (int k = 0; k < 4; ++k)
      if (v[k] >= 0) vtet[size_t(v[k] = order[size_t(v[k])])] = t;
  }
  for (int64_t i = 0; i < n; ++i) {
    const int32_t o = d.dup_[size_t(i)];
    dup[size_t(order[size_t(i)])] = o >= 0 ? order[size_t(o)] : -1;
  }
  d.topo_.vertex_tet.swap(vtet);
  d.dup_.swap(dup);
  d.pts_.swap(points);
  d.sos_id_.clear();
  return d;
}

void Delaunay3D::init_first_tet(int32_t a, int32_t b, int32_t c, int32_t d) {
  if (orient3d(point(a), point(b), point(c), point(d)) > 0) std::swap(a, b);
  const int32_t base[4] = {a, b, c, d};
  int32_t ids[5];
  for (int32_t& t : ids) t = topo_.new_slot();
  std::copy(base, base + 4, topo_.tets[size_t(ids[0])].v);
  for (int k = 0; k < 4; ++k) {
    int32_t* g = topo_.tets[size_t(ids[k + 1])].v;
    std::copy(base, base + 4, g);
    g[k] = kInfinite;
    // Replacing a vertex by a point on the other side of its face flips
    // the orientation: swap two finite slots to restore it.
    int i = (k + 1) % 4, j = (k + 2) % 4;
    std::swap(g[i], g[j]);
  }
  // Link every pair of faces with the same vertex set.
  for (int x = 0; x < 5; ++x)
    for (int kx = 0; kx < 4; ++kx) {
      const int32_t* vx = topo_.tets[size_t(ids[x])].v;
      for (int y = x + 1; y < 5; ++y)
        for (int ky = 0; ky < 4; ++ky) {
          const int32_t* vy = topo_.tets[size_t(ids[y])].v;
          int shared = 0;
          for (int s = 0; s < 4; ++s)
            if (s != kx && slot_of(vy, vx[s]) >= 0 && slot_of(vy, vx[s]) != ky) ++shared;
          if (shared == 3) {
            topo_.tets[size_t(ids[x])].n[kx] = 4 * ids[y] + ky;
            topo_.tets[size_t(ids[y])].n[ky] = 4 * ids[x] + kx;
          }
        }
    }
  for (int32_t v : base) topo_.vertex_tet[size_t(v)] = ids[0];
  seq_.last = ids[0];
}

// ---------------------------------------------------------------- queries

template <class Stop>
int32_t Delaunay3D::around_until(int32_t v, AroundScratch& s, Stop&& stop) const {
  // The breadth-first search of tets_around_vertex(), deduplicated by the
  // scratch's own set; a list longer than half the set is scanned instead.
  if (++s.gen == 0) {
    std::fill(s.stamp.begin(), s.stamp.end(), 0u);
    s.gen = 1;
  }
  const uint32_t gen = s.gen;
  std::vector<int32_t>& out = s.tets;
  auto first_visit = [&](int32_t t) {
    if (out.size() >= kAroundSlots / 2) return std::find(out.begin(), out.end(), t) == out.end();
    for (uint32_t h = (uint32_t(t) * 0x9e3779b1u) >> 22;; h = (h + 1) & (kAroundSlots - 1)) {
      if (s.stamp[h] != gen) {
        s.stamp[h] = gen;
        s.key[h] = t;
        return true;
      }
      if (s.key[h] == t) return false;
    }
  };
  out.clear();
  const int32_t t0 = topo_.vertex_tet[size_t(v)];
  if (t0 < 0) return -1;
  first_visit(t0);
  out.push_back(t0);
  for (size_t i = 0; i < out.size(); ++i) {
    const TetTopology::Rec& r = topo_.tets[size_t(out[i])];
    // The neighbors across the faces through v (the others' links may be
    // relinked by another part's star meanwhile, so they are never read)
    // are fetched while this one is tested (memory bound, as
    // tets_around_vertex()).
    const int sv = slot_of(r.v, v);
    for (int j = 0; j < 4; ++j)
      if (j != sv && r.n[j] >= 0) __builtin_prefetch(&topo_.tets[size_t(r.n[j] >> 2)]);
    if (stop(out[i])) return out[i];
    for (int j = 0; j < 4; ++j) {
      if (j == sv || r.n[j] < 0) continue;
      const int32_t n = r.n[j] >> 2;
      if (first_visit(n)) out.push_back(n);
    }
  }
  return -1;
}

void Delaunay3D::tets_around_vertex_in(int part, int32_t v, std::vector<int32_t>& out) const {
  if (part < 0) return tets_around_vertex(v, out);
  AroundScratch& s = parts_[size_t(part)].around;
  around_until(v, s, [](int32_t) { return false; });
  out.swap(s.tets);
}

int32_t Delaunay3D::find_edge(int32_t a, int32_t b, AroundScratch& s) const {
  if (a < 0 || size_t(a) >= num_vertices()) return -1;
  return around_until(a, s, [&](int32_t t) { return slot_of(tet(t), b) >= 0; });
}

int32_t Delaunay3D::find_face(int32_t a, int32_t b, int32_t c, int* k, AroundScratch& s) const {
  if (a < 0 || size_t(a) >= num_vertices()) return -1;
  const int32_t t = around_until(a, s, [&](int32_t u) {
    const int32_t* v = tet(u);
    return slot_of(v, b) >= 0 && slot_of(v, c) >= 0;
  });
  if (t >= 0 && k) {
    const int32_t* v = tet(t);
    for (int j = 0; j < 4; ++j)
      if (v[j] != a && v[j] != b && v[j] != c) *k = j;
  }
  return t;
}

size_t Delaunay3D::num_finite_tets() const {
  size_t n = 0;
  for_each_finite_tet([&](int32_t) { ++n; });
  return n;
}

std::vector<int32_t> Delaunay3D::finite_tets() const {
  std::vector<int32_t> out;
  out.reserve(4 * num_finite_tets());
  for_each_finite_tet([&](int32_t t) { out.insert(out.end(), tet(t), tet(t) + 4); });
  return out;
}

void Delaunay3D::set_constrained(int32_t t, int k, bool on) {
  const int32_t e = neighbor(t, k);
  const int32_t u = e >> 2, j = e & 3;
  if (on) {
    topo_.constrained[size_t(t)] |= uint8_t(1u << k);
    topo_.constrained[size_t(u)] |= uint8_t(1u << j);
  } else {
    topo_.constrained[size_t(t)] &= uint8_t(~(1u << k));
    topo_.constrained[size_t(u)] &= uint8_t(~(1u << j));
  }
}

int32_t Delaunay3D::find_edge(int32_t a, int32_t b) const { return find_edge(a, b, seq_.around); }

int32_t Delaunay3D::find_face(int32_t a, int32_t b, int32_t c, int* k) const {
  return find_face(a, b, c, k, seq_.around);
}

void Delaunay3D::edge_ring(int32_t t, int32_t a, int32_t b, std::vector<int32_t>& ring_tets,
                           std::vector<int32_t>& ring_verts) const {
  vm::edge_ring(topo_, t, a, b, ring_tets, ring_verts, {false, tet_capacity() + 1});
}

// ---------------------------------------------------------------- checks

Status Delaunay3D::check(bool delaunay) const {
  if (Status s = check_topology(topo_, num_vertices(), true, false); !s.ok()) return s;
  auto fail = [](const std::string& what, int32_t t) {
    return Status::Error(what + " (tetrahedron " + std::to_string(t) + ")");
  };
  for (int32_t t = 0; t < int32_t(tet_capacity()); ++t) {
    if (!is_live(t)) continue;
    const int32_t* v = tet(t);
    int infs = 0;
    for (int k = 0; k < 4; ++k) {
      if (v[k] == kInfinite) {
        ++infs;
        continue;
      }
      if (dup_[size_t(v[k])] >= 0) return fail("a duplicate point is a vertex", t);
    }
    if (infs == 0 && orient3d(point(v[0]), point(v[1]), point(v[2]), point(v[3])) >= 0)
      return fail("finite tetrahedron not positive", t);
    for (int k = 0; k < 4; ++k) {
      const int32_t e = neighbor(t, k);
      const int32_t u = e >> 2, j = e & 3;
      const int32_t* w = tet(u);
      if (v[k] == w[j]) return fail("two tetrahedra with the same vertices", t);
      if (infs == 1 && v[k] == kInfinite) {
        // The finite neighbor's apex is on the inner side of the hull face.
        int32_t q[4];
        std::copy(v, v + 4, q);
        q[k] = w[j];
        if (orient3d(point(q[0]), point(q[1]), point(q[2]), point(q[3])) <= 0)
          return fail("ghost tetrahedron wrongly oriented", t);
      }
      if (delaunay && infs == 0 && w[j] != kInfinite && !is_constrained(t, k) &&
          finite_conflict(t, point(w[j]), w[j]))
        return fail("face not locally Delaunay", t);
      if (delaunay && infs == 1 && v[k] != kInfinite && w[j] != kInfinite &&
          conflict(t, point(w[j]), w[j], true))
        return fail("convex hull not convex", t);
    }
  }
  return Status::Ok();
}

}  // namespace vm
