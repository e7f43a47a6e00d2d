// What the files of the Delaunay kernel share: delaunay3d.cpp (build,
// queries, checks), delaunay3d_insert.cpp (location, cavity, star: the
// insertion), delaunay3d_rounds.cpp (build()'s slab rounds, the partitioned
// insertion) and delaunay3d_flips.cpp (flips, edge removal). Small exact
// tests on points, and the inline members more than one of them calls. Not
// part of the API (delaunay3d.h).
#pragma once

#include <cstdint>

#include "core/geom/predicates.h"
#include "core/volume/delaunay3d.h"

namespace vm {
namespace delaunay3d_detail {

/// The slot (0..3) of kInfinite among a tetrahedron's 4 vertices v, or -1.
inline int inf_slot(const int32_t* v) {
  for (int k = 0; k < 4; ++k)
    if (v[k] == Delaunay3D::kInfinite) return k;
  return -1;
}

/// Whether points a, b, c (3 doubles each) lie on one line: exact, by the
/// three coordinate-plane projections.
inline bool collinear(const double* a, const double* b, const double* c) {
  double a2[2] = {a[2], a[0]}, b2[2] = {b[2], b[0]}, c2[2] = {c[2], c[0]};
  return orient2d(a, b, c) == 0 && orient2d(a + 1, b + 1, c + 1) == 0 && orient2d(a2, b2, c2) == 0;
}

/// Whether a and b (3 doubles each) are the same point.
inline bool same_point(const double* a, const double* b) {
  return a[0] == b[0] && a[1] == b[1] && a[2] == b[2];
}

}  // namespace delaunay3d_detail

inline bool Delaunay3D::owns(const Worker& w, int32_t t) const {
  if (w.part < 0) return true;
  const int32_t* v = tet(t);
  if ((v[0] | v[1] | v[2] | v[3]) < 0) return false;  // a ghost
  const uint8_t* part = part_.data();
  const uint8_t me = uint8_t(w.part);
  return part[v[0]] == me && part[v[1]] == me && part[v[2]] == me && part[v[3]] == me;
}

inline uint32_t Delaunay3D::visit_stamp(Worker& w) const {
  if (w.part < 0) return topo_.visit_stamp();
  w.gen += w.gen_step;
  return w.gen;
}

[[gnu::always_inline]] inline bool Delaunay3D::finite_conflict(int32_t t, const double* p,
                                                               int32_t pv) const {
  const int32_t* v = tet(t);
  // Positive tetrahedra have orient3d < 0, so "inside" is insphere < 0.
  const double s = insphere_fast(point(v[0]), point(v[1]), point(v[2]), point(v[3]), p, is_bound_);
  if (s != 0) return s < 0;
  return sos_conflict(t, p, pv);
}

[[gnu::always_inline]] inline bool Delaunay3D::conflict(int32_t t, const double* p, int32_t pv,
                                                        bool strict_hull) const {
  const int32_t* v = tet(t);
  // Live tetrahedra have no kFree vertex: negative only for kInfinite.
  if ((v[0] | v[1] | v[2] | v[3]) >= 0) return finite_conflict(t, p, pv);
  return ghost_conflict(t, p, pv, strict_hull);
}

}  // namespace vm
