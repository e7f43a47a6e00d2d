// Vertex moves of the volume optimizer (optimize_volume.h): smart
// smoothing of the free vertices (Freitag and Ollivier-Gooch, "Tetrahedral
// mesh improvement using swapping and smoothing", IJNME 40, 1997: smart
// Laplacian with a quality guard) toward an ODT-like position (Chen and
// Xu 2004; Alliez, Cohen-Steiner, Yvinec and Desbrun 2005), a move kept
// when the sum of 1 / gamma_t over the vertex's star decreases and its
// smallest quality does not fall below min(before, smooth_floor); and the
// sliver phase's climb of the smallest quality of a star (gradient of the
// worst tetrahedron, then deterministic random perturbations). A star's
// qualities are evaluated from what does not change while its vertex moves
// (prepare_star(), eval_star()), every accepted move checked with the exact
// orient3d. A smoothing pass runs on kParts slabs of vertices at the same
// time (on the threads): smooth_pass() says why no slab reads what another
// writes.
#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "core/geom/predicates.h"
#include "core/geom/vec3.h"
#include "core/quality/tet_quality.h"
#include "core/util/parallel.h"
#include "core/volume/optimize_volume_internal.h"

namespace vm {
namespace optimize_volume_detail {
namespace {

// Smallest quality a smoothing move may create (below it the exact
// orientation test decides anyway; this keeps the search off flat shapes).
constexpr double kGuard = 1e-3;

using v3::cross;
using v3::dot;
using v3::sub;

// Circumcenter of a tetrahedron and its signed volume times 6 (> 0:
// positive); false when (nearly) flat.
inline bool circumcenter(const double* a, const double* b, const double* c, const double* d,
                         double* o, double* vol6) {
  double u[3], v[3], w[3];
  sub(b, a, u), sub(c, a, v), sub(d, a, w);
  double vw[3], wu[3], uv[3];
  cross(v, w, vw), cross(w, u, wu), cross(u, v, uv);
  *vol6 = dot(u, vw);
  if (*vol6 == 0) return false;
  const double inv = 0.5 / *vol6;
  const double uu = dot(u, u), vv = dot(v, v), ww = dot(w, w);
  for (int k = 0; k < 3; ++k) o[k] = a[k] + (uu * vw[k] + vv * wu[k] + ww * uv[k]) * inv;
  return std::isfinite(o[0]) && std::isfinite(o[1]) && std::isfinite(o[2]);
}

// The Opposite of each tetrahedron of the star S of v, for eval_star().
void prepare_star(Optimizer& op, int32_t v, Span S, StarScratch& w) {
  w.opp.resize(S.size());
  size_t i = 0;
  for (int32_t t : S) {
    const int32_t* tv = op.m.tet(t);
    int s = 0;
    while (tv[s] != v) ++s;
    const int* f = kFaceOut[s];  // (v, f) is an even permutation of (0, 1, 2, 3)
    Opposite& o = w.opp[i++];
    const double* px = op.m.point(tv[f[0]]);
    const double* py = op.m.point(tv[f[1]]);
    const double* pz = op.m.point(tv[f[2]]);
    double u[3], w[3], e[3];
    for (int k = 0; k < 3; ++k) o.x[k] = px[k], o.y[k] = py[k], o.z[k] = pz[k];
    sub(py, px, u), sub(pz, px, w), sub(pz, py, e);
    cross(u, w, o.n);
    o.area2 = std::sqrt(dot(o.n, o.n));
    o.len2 = std::max({dot(u, u), dot(w, w), dot(e, e)});
    o.hsum = op.h[size_t(tv[f[0]])] + op.h[size_t(tv[f[1]])] + op.h[size_t(tv[f[2]])];
  }
}

// Min and sum of 1/q over the star S of v with v at p; false if a
// tetrahedron falls below kGuard (or min_required). Precondition:
// prepare_star(v, S, w) (v may have moved since). The qualities go to
// w.q (for move()).
bool eval_star(Span S, const double* p, double min_required, double* qmin, double* inv_sum,
               StarScratch& w) {
  double mn = 1e300, sum = 0;
  w.q.resize(S.size());
  for (size_t i = 0; i < S.size(); ++i) {
    const Opposite& o = w.opp[i];
    double dx[3], dy[3], dz[3], c1[3], c2[3], c3[3];
    sub(o.x, p, dx), sub(o.y, p, dy), sub(o.z, p, dz);
    cross(dx, dy, c1), cross(dy, dz, c2), cross(dz, dx, c3);
    // vol6 = (x - p) . ((y - p) x (z - p)) = (x - p) . n.
    const double vol6 = dot(dx, o.n);
    const double faces =
        0.5 * (o.area2 + std::sqrt(dot(c1, c1)) + std::sqrt(dot(c2, c2)) + std::sqrt(dot(c3, c3)));
    const double l2 = std::max({o.len2, dot(dx, dx), dot(dy, dy), dot(dz, dz)});
    const double den = faces * std::sqrt(l2);
    const double q = den > 0 ? 2.449489742783178 * vol6 / den : 0;
    if (q < kGuard || q < min_required) return false;
    w.q[i] = q;
    mn = std::min(mn, q);
    sum += 1 / q;
  }
  *qmin = mn;
  *inv_sum = sum;
  return true;
}

bool exact_star_ok(Optimizer& op, int32_t v, Span S, const double* p) {
  for (int32_t t : S) {
    const int32_t* tv = op.m.tet(t);
    const double* c[4];
    for (int k = 0; k < 4; ++k) c[k] = tv[k] == v ? p : op.m.point(tv[k]);
    if (orient3d(c[0], c[1], c[2], c[3]) >= 0) return false;
  }
  return true;
}

// Moves v to p, the star's qualities from the eval_star() that accepted
// p; marks the star unless `mark_later` (the caller does).
void move_vertex(Optimizer& op, int32_t v, Span S, const double* p, const StarScratch& w,
                 bool mark_later = false) {
  op.m.set_point(v, p);
  size_t i = 0;
  for (int32_t t : S) {
    op.q[size_t(t)] = w.q[i++];
    if (!mark_later) op.mark(t);
  }
}

// Reads and writes only v, its star's tetrahedra and their vertices'
// positions (and w); marks nothing when `mark_later`.
bool smooth_vertex(Optimizer& op, int32_t v, Span star, StarScratch& w, bool mark_later) {
  if (op.m.is_fixed(v) || star.size() == 0) return false;
  double old_min = 1e300, old_sum = 0;
  for (int32_t t : star) {
    old_min = std::min(old_min, op.cached(t));
    old_sum += 1 / std::max(op.cached(t), 1e-12);
  }
  if (old_min >= op.options.smooth_below) return false;
  prepare_star(op, v, star, w);
  const double* x = op.m.point(v);
  double odt[3] = {0, 0, 0}, wsum = 0, lap[3] = {0, 0, 0};
  int nlap = 0;
  // (v, x, y, z) is positive: the circumcenter from v's corner.
  for (size_t i = 0; i < star.size(); ++i) {
    const Opposite& o = w.opp[i];
    double cc[3], vol;
    if (circumcenter(x, o.x, o.y, o.z, cc, &vol) && vol > 0) {
      const double ht = 0.25 * (op.h[size_t(v)] + o.hsum);
      const double w = vol / (ht * ht * ht);
      for (int k = 0; k < 3; ++k) odt[k] += w * cc[k];
      wsum += w;
    }
    for (int k = 0; k < 3; ++k) lap[k] += o.x[k] + o.y[k] + o.z[k];
    nlap += 3;
  }
  const double floor = std::min(old_min, op.options.smooth_floor);
  double targets[2][3];
  int nt = 0;
  if (wsum > 0) {
    for (int k = 0; k < 3; ++k) targets[nt][k] = odt[k] / wsum;
    ++nt;
  }
  if (nlap > 0) {
    for (int k = 0; k < 3; ++k) targets[nt][k] = lap[k] / nlap;
    ++nt;
  }
  for (int i = 0; i < nt; ++i) {
    double step = 1.0;
    for (int attempt = 0; attempt < 3; ++attempt, step *= 0.5) {
      const double p[3] = {x[0] + step * (targets[i][0] - x[0]),
                           x[1] + step * (targets[i][1] - x[1]),
                           x[2] + step * (targets[i][2] - x[2])};
      double mn, sum;
      if (!eval_star(star, p, floor, &mn, &sum, w)) continue;
      if (sum < old_sum * (1 - 1e-6) && exact_star_ok(op, v, star, p)) {
        move_vertex(op, v, star, p, w, mark_later);
        ++w.moves;
        return true;
      }
    }
  }
  return false;
}

}  // namespace

// Smart smoothing of v toward its ODT-like position (circumcenters of the
// star weighted by volume / h^3), falling back to the centroid of its
// neighbors; halved steps. Returns whether v moved.
bool smooth_vertex(Optimizer& op, int32_t v) {
  if (op.m.is_fixed(v)) return false;
  op.m.star(v, op.star);
  const bool moved = smooth_vertex(op, v, Span(op.star), op.seq, false);
  op.stats.smoothing_moves += std::exchange(op.seq.moves, 0);
  return moved;
}

// One smoothing sweep. The topology does not change during the sweep, so
// the stars come from one vertex-to-tetrahedra incidence table (CSR)
// instead of a search each. The vertices are cut into kParts slabs
// of equal count along the longest axis of their box; a vertex whose
// star's vertices are all in its own slab is interior: smoothing it reads
// and writes nothing another slab's interior vertices do, so the slabs
// smooth their interior vertices (each in index order) at the same time;
// then the others the same way in kParts + 1 slabs cut halfway between
// the first cuts; then what is left, in index order. The slabs do not
// depend on the thread count, so neither does the mesh.
void smooth_pass(Optimizer& op) {
  const size_t nv = op.m.num_vertices();
  op.inc_off.assign(nv + 1, 0);
  for (int32_t t = 0; t < int32_t(op.m.capacity()); ++t)
    if (op.m.is_live(t))
      for (int k = 0; k < 4; ++k) ++op.inc_off[size_t(op.m.tet(t)[k]) + 1];
  for (size_t v = 0; v < nv; ++v) op.inc_off[v + 1] += op.inc_off[v];
  op.inc.resize(size_t(op.inc_off[nv]));
  op.fill.assign(op.inc_off.begin(), op.inc_off.end() - 1);
  for (int32_t t = 0; t < int32_t(op.m.capacity()); ++t)
    if (op.m.is_live(t))
      for (int k = 0; k < 4; ++k) op.inc[size_t(op.fill[size_t(op.m.tet(t)[k])]++)] = t;
  auto star_of = [&](int32_t v) {
    return Span(op.inc.data() + op.inc_off[size_t(v)],
                size_t(op.inc_off[size_t(v) + 1] - op.inc_off[size_t(v)]));
  };
  // Slab j of `part` smooths the vertices of lists[j] whose star lies in
  // it, in index order, at the same time as the other slabs; the others
  // are returned, in index order.
  auto by_slabs = [&](const std::vector<uint8_t>& part,
                      const std::vector<std::vector<int32_t>>& lists) {
    const size_t n = lists.size();
    std::vector<std::vector<int32_t>> later(n), moved(n);
    std::vector<StarScratch> scratch(n);
    parallel_for(n, 1, [&](size_t begin, size_t end) {
      for (size_t j = begin; j < end; ++j)
        for (int32_t v : lists[j]) {
          const Span star = star_of(v);
          bool interior = true;
          for (int32_t t : star)
            for (int k = 0; k < 4; ++k) interior = interior && part[size_t(op.m.tet(t)[k])] == j;
          if (!interior)
            later[j].push_back(v);
          else if (smooth_vertex(op, v, star, scratch[j], true))
            moved[j].push_back(v);
        }
    });
    std::vector<int32_t> rest;
    for (size_t j = 0; j < n; ++j) {
      op.stats.smoothing_moves += scratch[j].moves;
      for (int32_t v : moved[j])
        for (int32_t t : star_of(v)) op.mark(t);
      rest.insert(rest.end(), later[j].begin(), later[j].end());
    }
    std::sort(rest.begin(), rest.end());
    return rest;
  };
  const std::vector<uint8_t> part = vertex_slabs(op, kParts);
  std::vector<std::vector<int32_t>> mine(kParts);
  for (int32_t v = 0; v < int32_t(nv); ++v) mine[part[size_t(v)]].push_back(v);
  const std::vector<int32_t> near_cuts = by_slabs(part, mine);
  // The vertices near a cut, again by slabs, whose cuts now fall halfway
  // between the first ones (so each first cut is inside one).
  const std::vector<uint8_t> part2 = vertex_slabs(op, kParts, true);
  std::vector<std::vector<int32_t>> mine2(kParts + 1);
  for (int32_t v : near_cuts) mine2[part2[size_t(v)]].push_back(v);
  const std::vector<int32_t> rest = by_slabs(part2, mine2);
  for (int32_t v : rest) smooth_vertex(op, v, star_of(v), op.seq, false);
  op.stats.smoothing_moves += std::exchange(op.seq.moves, 0);
}

// Raises the smallest quality of v's star: gradient of the worst
// tetrahedron's quality, then deterministic random perturbations.
bool climb_vertex(Optimizer& op, int32_t v) {
  if (op.m.is_fixed(v)) return false;
  op.m.star(v, op.star);
  if (op.star.empty()) return false;
  prepare_star(op, v, Span(op.star), op.seq);
  double old_min = 1e300;
  int32_t worst = -1;
  for (int32_t t : op.star)
    if (op.cached(t) < old_min) old_min = op.cached(t), worst = t;
  const double* x = op.m.point(v);
  // The scale of the moves: the mean distance from v to the worst
  // tetrahedron's other corners (the geometry's, whatever h says).
  double hv = 0;
  for (int s = 0; s < 4; ++s) {
    const int32_t w = op.m.tet(worst)[s];
    if (w == v) continue;
    double d[3];
    sub(op.m.point(w), x, d);
    hv += std::sqrt(dot(d, d)) / 3;
  }
  bool moved = false;
  // A move to p is kept when the star's smallest quality rises and every
  // tetrahedron stays positive (exact).
  auto try_move = [&](const double* p) {
    double mn, sum;
    if (!eval_star(Span(op.star), p, old_min * (1 + 1e-6) + 1e-9, &mn, &sum, op.seq) ||
        !exact_star_ok(op, v, Span(op.star), p))
      return false;
    move_vertex(op, v, Span(op.star), p, op.seq);
    old_min = mn;
    moved = true;
    ++op.stats.sliver_moves;
    return true;
  };
  // Gradient of the worst quality by central differences.
  {
    const int32_t* tv = op.m.tet(worst);
    double grad[3];
    const double eps = 1e-4 * hv;
    for (int k = 0; k < 3; ++k) {
      double pp[3] = {x[0], x[1], x[2]}, pm[3] = {x[0], x[1], x[2]};
      pp[k] += eps, pm[k] -= eps;
      const double* c1[4];
      const double* c2[4];
      for (int s = 0; s < 4; ++s) {
        c1[s] = tv[s] == v ? pp : op.m.point(tv[s]);
        c2[s] = tv[s] == v ? pm : op.m.point(tv[s]);
      }
      grad[k] = (tet_gamma(c1[0], c1[1], c1[2], c1[3]) - tet_gamma(c2[0], c2[1], c2[2], c2[3])) /
                (2 * eps);
    }
    const double gn = std::sqrt(dot(grad, grad));
    if (gn > 0) {
      for (double step = 0.2 * hv; step > 0.005 * hv; step *= 0.5) {
        const double p[3] = {x[0] + step * grad[0] / gn, x[1] + step * grad[1] / gn,
                             x[2] + step * grad[2] / gn};
        if (try_move(p)) break;
      }
    }
  }
  // Random perturbations.
  for (int attempt = 0; attempt < 12; ++attempt) {
    const double mag = hv * (attempt < 6 ? 0.1 : 0.03);
    double d[3];
    for (double& c : d) c = 2 * op.uniform() - 1;
    const double* xv = op.m.point(v);
    const double p[3] = {xv[0] + mag * d[0], xv[1] + mag * d[1], xv[2] + mag * d[2]};
    try_move(p);
  }
  return moved;
}

}  // namespace optimize_volume_detail
}  // namespace vm
