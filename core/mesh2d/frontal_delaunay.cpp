// Frontal-Delaunay (Rebay 1993), as used by the seed paper's "Frontal"
// mesher. Phases: constrained triangulation of the boundary, classification
// of triangles (accepted / active / waiting), then the frontal loop: the
// worst active triangle gets its optimal point, triangles changed by the
// insertion are classified again.
#include "core/mesh2d/frontal_delaunay.h"

#include <cmath>
#include <queue>

#include "core/mesh2d/triangulation2d.h"
#include "core/util/portable_math.h"

namespace vm {
namespace {

using detail::Circle;
using detail::Triangulation;

constexpr double kSqrt3 = 1.7320508075688772;

struct State {
  double ratio = 0;  // circumradius / (h / sqrt 3)
  uint32_t version = 0;
  uint8_t accepted = 0;
};

}  // namespace

Result<Mesh2D> frontal_delaunay(const std::vector<double>& points,
                                const std::vector<int32_t>& segments, const SizeField2D& size,
                                const RefinementOptions& options) {
  using R = Result<Mesh2D>;
  if (points.size() / 2 < 3) return R::Error("meshing needs at least 3 points");
  Triangulation tr(points);
  std::vector<int32_t> alias;
  Status st = detail::build_constrained(points, segments, tr, alias);
  if (!st.ok()) return st;

  std::vector<State> state;
  using Entry = std::tuple<double, int32_t, uint32_t>;
  std::priority_queue<Entry> heap;
  bool bad_size = false;
  auto usable = [&](int32_t t) { return t >= 0 && tr.tri(t).in && !tr.has_super_vertex(t); };
  auto classify = [&](int32_t t) {
    if (size_t(t) >= state.size()) state.resize(tr.num_triangles());
    State& S = state[size_t(t)];
    ++S.version;
    S.accepted = 1;
    if (!usable(t)) return;
    const auto& T = tr.tri(t);
    const double *a = tr.pt(T.v[0]), *b = tr.pt(T.v[1]), *c = tr.pt(T.v[2]);
    const double h = size((a[0] + b[0] + c[0]) / 3, (a[1] + b[1] + c[1]) / 3);
    if (!(h > 0)) bad_size = true;
    const Circle cc = detail::circumcircle(a, b, c);
    S.ratio = std::isfinite(cc.r2) ? std::sqrt(cc.r2) * kSqrt3 / h : 1e300;
    S.accepted = S.ratio <= options.frontal_radius_tolerance;
  };
  // Active: not accepted, with an edge on the boundary or on an accepted
  // triangle (the front). Returns that edge, or -1.
  auto front_edge = [&](int32_t t) {
    if (!usable(t) || state[size_t(t)].accepted) return -1;
    const auto& T = tr.tri(t);
    for (int k = 0; k < 3; ++k)
      if (T.c[k] || (usable(T.n[k]) && state[size_t(T.n[k])].accepted)) return k;
    return -1;
  };
  auto push_if_active = [&](int32_t t) {
    if (t >= 0 && front_edge(t) >= 0)
      heap.push({state[size_t(t)].ratio, t, state[size_t(t)].version});
  };

  state.resize(tr.num_triangles());
  for (int32_t t = 0; t < int32_t(tr.num_triangles()); ++t) classify(t);
  for (int32_t t = 0; t < int32_t(tr.num_triangles()); ++t) push_if_active(t);
  if (bad_size) return R::Error("the size field must be positive");

  std::vector<int32_t> touched;
  size_t inserted = 0;
  while (!heap.empty()) {
    auto [ratio, t, version] = heap.top();
    (void)ratio;
    heap.pop();
    if (state[size_t(t)].version != version) continue;
    const int k = front_edge(t);
    if (k < 0) continue;
    // Rebay's point on the perpendicular bisector of the front edge (a, b).
    const auto& T = tr.tri(t);
    const double *a = tr.pt(T.v[(k + 1) % 3]), *b = tr.pt(T.v[(k + 2) % 3]), *c = tr.pt(T.v[k]);
    const double m[2] = {0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])};
    const double ex = b[0] - a[0], ey = b[1] - a[1];
    const double len = pm::hypot(ex, ey), p = 0.5 * len;
    double n[2] = {-ey / len, ex / len};  // left of a -> b: into t (ccw)
    const double h = size(m[0], m[1]);
    if (!(h > 0)) return R::Error("the size field must be positive");
    const Circle cc = detail::circumcircle(a, b, c);
    const double q = (cc.cx - m[0]) * n[0] + (cc.cy - m[1]) * n[1];  // signed
    const double rho_m = h / kSqrt3;
    double rho = std::max(rho_m, p);
    if (q > 0) rho = std::min(rho, (p * p + q * q) / (2 * q));
    const double d = rho + std::sqrt(std::max(rho * rho - p * p, 0.0));
    double x[2] = {m[0] + d * n[0], m[1] + d * n[1]};
    // Accept the triangle as it is if the point leaves the domain, enters
    // a boundary edge's diametral circle or comes too close to a vertex.
    int32_t s = tr.find_triangle(x);
    bool ok = tr.tri(s).in && !tr.has_super_vertex(s) && !detail::encroaches(tr, s, x);
    for (int j = 0; j < 3 && ok; ++j) {
      const double* v = tr.pt(tr.tri(s).v[j]);
      ok = pm::hypot(v[0] - x[0], v[1] - x[1]) > 0.3 * std::min(h, len);
    }
    if (!ok) {
      state[size_t(t)].accepted = 1;
      ++state[size_t(t)].version;
      for (int j = 0; j < 3; ++j) push_if_active(T.n[j]);
      continue;
    }
    touched.clear();
    tr.set_touched_log(&touched);
    tr.insert(tr.add_point(x[0], x[1]));
    tr.set_touched_log(nullptr);
    if (++inserted > options.max_inserted)
      return R::Error("meshing stopped: more than " + std::to_string(options.max_inserted) +
                      " points inserted");
    for (int32_t u : touched) classify(u);
    if (bad_size) return R::Error("the size field must be positive");
    for (int32_t u : touched) {
      push_if_active(u);
      const auto& U = tr.tri(u);
      for (int j = 0; j < 3; ++j) push_if_active(U.n[j]);
    }
  }
  return detail::extract_mesh(tr, points);
}

}  // namespace vm
