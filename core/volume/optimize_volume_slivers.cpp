// The sliver phase of the volume optimizer (optimize_volume.h): the
// tetrahedra still below sliver_threshold, worst first, get a flip
// (optimize_volume_flips.cpp), else their vertices climb the smallest
// quality of their stars (optimize_volume_smooth.cpp), else a vertex is
// inserted near them when the star of the new vertex over a star-shaped
// cavity raises the smallest quality there (the insertion of Klingner and
// Shewchuk, "Aggressive tetrahedral mesh improvement", IMR 2007), in rounds
// alternated with flip passes, within a work bound.
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "core/geom/predicates.h"
#include "core/geom/vec3.h"
#include "core/quality/tet_quality.h"
#include "core/volume/optimize_volume_internal.h"

namespace vm {
namespace optimize_volume_detail {
namespace {

using v3::cross;
using v3::dot;
using v3::sub;

// Grows cav (seeded with t) until every boundary face sees p (the
// tetrahedron of the face and p positive); false if that needs crossing
// a constrained face or more than kMaxCavity tetrahedra.
bool grow_cavity(Optimizer& op, int32_t t, const double* p, std::vector<int32_t>& cav) {
  // Each tetrahedron's faces are checked once, when it joins: a face
  // found visible stays visible, and one hidden brings its neighbor in.
  cav.assign(1, t);
  for (size_t i = 0; i < cav.size(); ++i) {
    const int32_t c = cav[i];
    const int32_t* tv = op.m.tet(c);
    for (int k = 0; k < 4; ++k) {
      const int32_t e = op.m.neighbor(c, k);
      if (e >= 0 && std::find(cav.begin(), cav.end(), e >> 2) != cav.end()) continue;
      const double* q[4] = {op.m.point(tv[0]), op.m.point(tv[1]), op.m.point(tv[2]),
                            op.m.point(tv[3])};
      q[k] = p;
      if (orient3d(q[0], q[1], q[2], q[3]) < 0) continue;  // visible
      if (op.m.is_constrained(c, k) || int(cav.size()) >= kMaxCavity) return false;
      cav.push_back(e >> 2);
    }
  }
  return true;
}

// New tetrahedra of the star of p (vertex id pv) over the boundary of cav
// and their smallest quality.
double star_tets(Optimizer& op, const std::vector<int32_t>& cav, const double* p, int32_t pv,
                 std::vector<std::array<int32_t, 4>>& nt) {
  nt.clear();
  double mn = 1e300;
  for (int32_t c : cav)
    for (int k = 0; k < 4; ++k) {
      const int32_t e = op.m.neighbor(c, k);
      if (e >= 0 && std::find(cav.begin(), cav.end(), e >> 2) != cav.end()) continue;
      const int32_t* tv = op.m.tet(c);
      std::array<int32_t, 4> q = {tv[0], tv[1], tv[2], tv[3]};
      const double* x[4] = {op.m.point(tv[0]), op.m.point(tv[1]), op.m.point(tv[2]),
                            op.m.point(tv[3])};
      x[k] = p;
      q[size_t(k)] = pv;
      mn = std::min(mn, tet_gamma(x[0], x[1], x[2], x[3]));
      nt.push_back(q);
    }
  return mn;
}

// Inserts a vertex near tetrahedron t (its centroid, off its constrained
// faces, or off its largest face on either side) when the star of the
// new vertex over a star-shaped cavity raises the smallest quality there.
bool insert_near(Optimizer& op, int32_t t) {
  const int32_t* tv = op.m.tet(t);
  const double* x[4] = {op.m.point(tv[0]), op.m.point(tv[1]), op.m.point(tv[2]), op.m.point(tv[3])};
  // Scale: the mean edge length of t (the geometry's, whatever h says);
  // the new vertex's size: the mean of its corners'.
  double ht = 0, hnew = 0, cen[3] = {0, 0, 0};
  for (int s = 0; s < 4; ++s) {
    hnew += 0.25 * op.h[size_t(tv[s])];
    for (int k = 0; k < 3; ++k) cen[k] += 0.25 * x[s][k];
  }
  for (const auto& e : kTetEdges) {
    double d[3];
    sub(x[e[0]], x[e[1]], d);
    ht += std::sqrt(dot(d, d)) / 6;
  }
  // Candidates: the centroid, and for constrained faces points inward
  // from the face centroid (for two, from their common edge) at depths
  // 0.4, 0.6 and 0.8 h.
  std::vector<std::array<double, 3>> cand = {{cen[0], cen[1], cen[2]}};
  double dir[3] = {0, 0, 0}, base[3] = {0, 0, 0};
  int ncons = 0;
  const double depths[3] = {0.4, 0.6, 0.8};
  for (int k = 0; k < 4; ++k) {
    if (!op.m.is_constrained(t, k)) continue;
    const int* f = kFaceOut[k];
    double u[3], w[3], n[3];
    sub(x[f[1]], x[f[0]], u), sub(x[f[2]], x[f[0]], w), cross(u, w, n);
    const double len = std::sqrt(dot(n, n));
    if (!(len > 0)) continue;
    // kFaceOut is counterclockwise seen from outside: n points out of t.
    double fc[3];
    for (int c = 0; c < 3; ++c) {
      fc[c] = (x[f[0]][c] + x[f[1]][c] + x[f[2]][c]) / 3;
      dir[c] -= n[c] / len;
      base[c] += fc[c];
    }
    ++ncons;
    for (double dep : depths)
      cand.push_back({fc[0] - dep * ht * n[0] / len, fc[1] - dep * ht * n[1] / len,
                      fc[2] - dep * ht * n[2] / len});
  }
  if (ncons >= 2) {
    const double len = std::sqrt(dot(dir, dir));
    if (len > 0)
      for (double dep : depths)
        cand.push_back({base[0] / ncons + dep * ht * dir[0] / len,
                        base[1] / ncons + dep * ht * dir[1] / len,
                        base[2] / ncons + dep * ht * dir[2] / len});
  }
  // The best candidate (smallest quality of its star), then a random
  // search around it with a shrinking radius.
  const int32_t pv = int32_t(op.m.num_vertices());
  double best_q = -1e300;
  std::array<double, 3> best_p{};
  auto try_point = [&](const std::array<double, 3>& p) {
    if (!grow_cavity(op, t, p.data(), op.cav)) return;
    const double nm = star_tets(op, op.cav, p.data(), pv, op.nt);
    if (nm > best_q) {
      best_q = nm;
      best_p = p;
    }
  };
  for (const auto& p : cand) try_point(p);
  // Points off t on both sides, along the normal of its largest face: a
  // flat tetrahedron (four nearly coplanar corners, as among the first
  // layer's points over a planar cap) has no good point in its plane,
  // and flips among coplanar points leave flat ones.
  {
    double n_best[3] = {0, 0, 0}, area2 = 0;
    for (int k = 0; k < 4; ++k) {
      const int* f = kFaceOut[k];
      double u[3], w[3], n[3];
      sub(x[f[1]], x[f[0]], u), sub(x[f[2]], x[f[0]], w), cross(u, w, n);
      if (dot(n, n) > area2) area2 = dot(n, n), std::copy(n, n + 3, n_best);
    }
    const double len = std::sqrt(area2);
    if (len > 0)
      for (double side : {1.0, -1.0})
        for (double dep : depths)
          try_point({cen[0] + side * dep * ht * n_best[0] / len,
                     cen[1] + side * dep * ht * n_best[1] / len,
                     cen[2] + side * dep * ht * n_best[2] / len});
  }
  if (best_q <= -1e300) return false;
  for (int it = 0; it < 24; ++it) {
    const double r = 0.25 * ht * (1 - it / 24.0);
    std::array<double, 3> p = best_p;
    for (double& c : p) c += r * (2 * op.uniform() - 1);
    try_point(p);
  }
  if (!grow_cavity(op, t, best_p.data(), op.cav)) return false;
  double old_min = 1e300;
  for (int32_t c : op.cav) old_min = std::min(old_min, op.cached(c));
  if (!(best_q > old_min + 1e-9)) return false;
  const std::vector<int32_t> best_cav = op.cav;
  const double* cand_best = best_p.data();
  const int32_t v = op.m.add_vertex(cand_best);
  op.h.push_back(hnew);
  star_tets(op, best_cav, cand_best, v, op.nt);
  op.fseq.created.clear();
  if (commit(op, op.fseq, best_cav.data(), int(best_cav.size()), op.nt.data(), int(op.nt.size())) !=
      Flip::kDone) {
    // Not expected (the cavity is star-shaped): the vertex stays unused.
    return false;
  }
  ++op.stats.insertions;
  smooth_vertex(op, v);
  climb_vertex(op, v);
  return true;
}

}  // namespace

void sliver_phase(Optimizer& op) {
  // Work bound: tetrahedra treated, over all rounds, at most 4 times the
  // first round's count (plus a constant), whatever the rounds create.
  // The bad tetrahedra of a round after the first: those of the round
  // before and those it created or moved, still below the threshold
  // (no scan of the whole mesh).
  int64_t budget = -1;
  std::vector<int32_t> bad, log;
  for (int32_t t = 0; t < int32_t(op.m.capacity()); ++t)
    if (op.m.is_live(t) && op.cached(t) < op.options.sliver_threshold) bad.push_back(t);
  op.log = &log;
  for (int round = 0; round < op.options.sliver_rounds; ++round) {
    if (round > 0) {
      log.insert(log.end(), bad.begin(), bad.end());
      std::sort(log.begin(), log.end());
      log.erase(std::unique(log.begin(), log.end()), log.end());
      bad.clear();
      for (int32_t t : log)
        if (op.m.is_live(t) && op.cached(t) < op.options.sliver_threshold) bad.push_back(t);
      log.clear();
    }
    if (bad.empty()) break;
    if (budget < 0) budget = 4 * int64_t(bad.size()) + 256;
    std::sort(bad.begin(), bad.end(), [&](int32_t a, int32_t b) {
      return op.cached(a) < op.cached(b) || (op.cached(a) == op.cached(b) && a < b);
    });
    bool changed = false, spent = false;
    for (int32_t t : bad) {
      if (!op.m.is_live(t) || op.cached(t) >= op.options.sliver_threshold) continue;
      if (--budget < 0) {
        spent = true;
        break;
      }
      op.fseq.created.clear();
      if (improve_topology(op, t, op.fseq) == Flip::kDone) {
        changed = true;
        continue;
      }
      const int32_t tv[4] = {op.m.tet(t)[0], op.m.tet(t)[1], op.m.tet(t)[2], op.m.tet(t)[3]};
      for (int32_t v : tv) changed = climb_vertex(op, v) || changed;
      if (op.m.is_live(t) && op.cached(t) < op.options.sliver_threshold && insert_near(op, t))
        changed = true;
    }
    flip_pass(op, op.options.sliver_threshold, true);
    if (!changed || spent) break;
  }
  op.log = nullptr;
}

}  // namespace optimize_volume_detail
}  // namespace vm
