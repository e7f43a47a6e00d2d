// Pinning the remeshed surface to far input vertices (see pin_to_input.h).
// Phases: (1) the far input vertices, largest relative gap first; (2) for
// each, its closest output triangle gets a vertex there: the nearest free
// corner moved onto it when close, else a split of the nearest edge or of
// the triangle, each under a fold guard.
#include "core/surface/pin_to_input.h"

#include <algorithm>
#include <array>

#include "core/geom/vec3.h"
#include "core/mesh/star_visibility.h"
#include "core/mesh/surface_distance.h"
#include "core/quality/triangle_quality.h"
#include "core/surface/optimize_surface.h"

namespace vm {
namespace {

/// A changed triangle may turn by less than 60 degrees.
constexpr double kCosMaxTurn = 0.5;
/// Moved triangles keep gamma_k >= kMoveGamma; split ones >= kSplitGamma.
constexpr double kMoveGamma = 0.3;
constexpr double kSplitGamma = 0.1;
/// A corner closer than this times h moves; a closest point with a
/// barycentric coordinate below kEdgeBary splits the opposite edge.
constexpr double kMoveDistance = 0.35;
constexpr double kEdgeBary = 0.2;
/// A pin is freed when a vertex of its triangles has a star no direction
/// sees within about 75 degrees (a needle: layers could not grow there).
constexpr double kCosMaxFold = 0.25;

void normal(const double* a, const double* b, const double* c, double* n) {
  double u[3], w[3];
  v3::sub(b, a, u);
  v3::sub(c, a, w);
  v3::cross(u, w, n);
}

/// Triangle (a, b, c) keeps the side of `before` (turns less than the
/// guard) and gamma_k >= min_gamma.
bool acceptable(const double* a, const double* b, const double* c, const double* before,
                double min_gamma) {
  double n[3];
  normal(a, b, c, n);
  return v3::dot(before, n) > kCosMaxTurn * v3::norm(before) * v3::norm(n) &&
         triangle_gamma(a, b, c) >= min_gamma;
}

class Pinner {
 public:
  Pinner(SurfaceMesh& m, std::vector<int32_t>& home, std::vector<uint8_t>& fixed,
         std::vector<int32_t>& pin_of)
      : m_(m),
        home_(home),
        fixed_(fixed),
        pin_of_(pin_of),
        star_(m.num_vertices()),
        touched_(m.num_triangles(), 0) {
    for (size_t t = 0; t < m.num_triangles(); ++t)
      for (int c = 0; c < 3; ++c)
        star_[size_t(m.triangles[3 * t + size_t(c)])].push_back(int32_t(t));
  }

  bool touched(int32_t t) const { return touched_[size_t(t)] != 0; }

  /// Moves free vertex o onto input vertex v at x (home triangle `home`)
  /// if its triangles pass the guard.
  bool move(int32_t o, int32_t v, const double* x, int32_t home) {
    if (fixed_[size_t(o)] != kFree) return false;
    for (int32_t t : star_[size_t(o)]) {
      const int32_t* T = tri(t);
      double before[3];
      normal(p(T[0]), p(T[1]), p(T[2]), before);
      std::array<const double*, 3> q{p(T[0]), p(T[1]), p(T[2])};
      for (int c = 0; c < 3; ++c)
        if (T[c] == o) q[size_t(c)] = x;
      if (!acceptable(q[0], q[1], q[2], before, kMoveGamma)) return false;
    }
    std::copy_n(x, 3, p(o));
    home_[size_t(o)] = home;
    fixed_[size_t(o)] = kPinned;
    pin_of_[size_t(o)] = v;
    for (int32_t t : star_[size_t(o)]) touched_[size_t(t)] = 1;
    return true;
  }

  /// Splits triangle t = (a, b, c) into three at input vertex v (at x).
  bool split_triangle(int32_t t, int32_t v, const double* x, int32_t home) {
    const std::array<int32_t, 3> T{tri(t)[0], tri(t)[1], tri(t)[2]};
    double before[3];
    normal(p(T[0]), p(T[1]), p(T[2]), before);
    for (int k = 0; k < 3; ++k)
      if (!acceptable(p(T[size_t(k)]), p(T[size_t(k + 1) % 3]), x, before, kSplitGamma))
        return false;
    const int32_t n = add_vertex(v, x, home);
    set(t, {T[0], T[1], n});
    add({T[1], T[2], n});
    add({T[2], T[0], n});
    return true;
  }

  /// Splits the edge of t opposite corner k, and the triangle across it,
  /// at input vertex v (at x). Refused on an opening or a crease (both
  /// ends kept).
  bool split_edge(int32_t t, int k, int32_t v, const double* x, int32_t home) {
    const int32_t c = tri(t)[k], a = tri(t)[(k + 1) % 3], b = tri(t)[(k + 2) % 3];
    auto kept = [&](int32_t v) {
      return fixed_[size_t(v)] == kOnOpening || fixed_[size_t(v)] == kOnFeature;
    };
    if (kept(a) && kept(b)) return false;
    int32_t u = -1, d = -1;  // u = (b, a, d)
    for (int32_t s : star_[size_t(a)]) {
      if (s == t) continue;
      const int32_t* S = tri(s);
      for (int j = 0; j < 3; ++j)
        if (S[j] == b && S[(j + 1) % 3] == a) u = s, d = S[(j + 2) % 3];
    }
    if (u < 0 || touched(u)) return false;
    double nt[3], nu[3];
    normal(p(a), p(b), p(c), nt);
    normal(p(b), p(a), p(d), nu);
    if (!acceptable(p(a), x, p(c), nt, kSplitGamma) ||
        !acceptable(x, p(b), p(c), nt, kSplitGamma) ||
        !acceptable(p(b), x, p(d), nu, kSplitGamma) || !acceptable(x, p(a), p(d), nu, kSplitGamma))
      return false;
    const int32_t n = add_vertex(v, x, home);
    set(t, {a, n, c});
    add({n, b, c});
    set(u, {b, n, d});
    add({n, a, d});
    return true;
  }

  double* p(int32_t v) { return &m_.points[3 * size_t(v)]; }
  int32_t* tri(int32_t t) { return &m_.triangles[3 * size_t(t)]; }

 private:
  int32_t add_vertex(int32_t v, const double* x, int32_t home) {
    m_.points.insert(m_.points.end(), x, x + 3);
    home_.push_back(home);
    fixed_.push_back(kPinned);
    pin_of_.push_back(v);
    star_.emplace_back();
    return int32_t(home_.size() - 1);
  }
  void unlink(int32_t t) {
    for (int c = 0; c < 3; ++c) {
      auto& s = star_[size_t(tri(t)[c])];
      s.erase(std::find(s.begin(), s.end(), t));
    }
  }
  void link(int32_t t) {
    for (int c = 0; c < 3; ++c) star_[size_t(tri(t)[c])].push_back(t);
    touched_[size_t(t)] = 1;
  }
  void set(int32_t t, std::array<int32_t, 3> v) {
    unlink(t);
    std::copy(v.begin(), v.end(), tri(t));
    link(t);
  }
  void add(std::array<int32_t, 3> v) {
    m_.triangles.insert(m_.triangles.end(), v.begin(), v.end());
    touched_.push_back(0);
    link(int32_t(touched_.size() - 1));
  }

  SurfaceMesh& m_;
  std::vector<int32_t>& home_;
  std::vector<uint8_t>& fixed_;
  std::vector<int32_t>& pin_of_;
  std::vector<std::vector<int32_t>> star_;
  std::vector<uint8_t> touched_;
};

/// Barycentric coordinates of x (in the plane of a, b, c, which must not
/// be degenerate).
std::array<double, 3> barycentric(const double* x, const double* a, const double* b,
                                  const double* c) {
  double n[3], na[3], nb[3];
  normal(a, b, c, n);
  normal(x, b, c, na);
  normal(a, x, c, nb);
  const double area2 = v3::dot(n, n);
  if (!(area2 > 0)) return {1.0 / 3, 1.0 / 3, 1.0 / 3};
  const double l0 = v3::dot(na, n) / area2, l1 = v3::dot(nb, n) / area2;
  return {l0, l1, 1 - l0 - l1};
}

}  // namespace

PinStats pin_to_input(SurfaceMesh& output, WallVertices& wall, const SurfaceMesh& input,
                      const std::vector<double>& h, const std::vector<double>& gaps, double limit,
                      const std::vector<uint8_t>& skip, const TriangleBvh* bvh) {
  PinStats st;
  // Phase 1: the far input vertices.
  std::vector<std::pair<double, int32_t>> far;
  for (size_t v = 0; v < gaps.size(); ++v) {
    const double rel = gaps[v] / h[v];
    if (rel > limit && (skip.empty() || !skip[v])) far.push_back({-rel, int32_t(v)});
  }
  st.far = far.size();
  if (far.empty()) return st;
  std::sort(far.begin(), far.end());

  // Phase 2: a vertex of the output onto each.
  std::vector<int32_t> input_tri(input.num_vertices(), -1);  // a triangle of each input vertex
  for (size_t t = 0; t < input.num_triangles(); ++t)
    for (int c = 0; c < 3; ++c) input_tri[size_t(input.triangles[3 * t + size_t(c)])] = int32_t(t);
  // Built before any change: triangles split later are touched and skipped.
  const TriangleBvh built = bvh ? TriangleBvh{} : build_triangle_bvh(output);
  const TriangleBvh& tree = bvh ? *bvh : built;
  Pinner pin(output, wall.home, wall.fixed, wall.pin_of);
  for (const auto& [neg_rel, v] : far) {
    const double* x = &input.points[3 * size_t(v)];
    const int32_t t = closest_surface_point(output, tree, x).triangle;
    if (t < 0 || pin.touched(t)) continue;
    const std::array<int32_t, 3> T{pin.tri(t)[0], pin.tri(t)[1], pin.tri(t)[2]};
    // The nearest corner moves if it is close.
    int nearest = 0;
    double best = 1e300;
    for (int k = 0; k < 3; ++k) {
      double d[3];
      v3::sub(pin.p(T[size_t(k)]), x, d);
      if (v3::dot(d, d) < best) best = v3::dot(d, d), nearest = k;
    }
    const double hv = h[size_t(v)];
    const int32_t home_v = input_tri[size_t(v)];
    bool done = best < kMoveDistance * kMoveDistance * hv * hv &&
                pin.move(T[size_t(nearest)], v, x, home_v);
    if (!done) {
      const auto l = barycentric(x, pin.p(T[0]), pin.p(T[1]), pin.p(T[2]));
      const int k = int(std::min_element(l.begin(), l.end()) - l.begin());
      done = (l[size_t(k)] < kEdgeBary && pin.split_edge(t, k, v, x, home_v)) ||
             pin.split_triangle(t, v, x, home_v);
    }
    st.pinned += done;
  }
  return st;
}

size_t unpin_poor(const SurfaceMesh& output, WallVertices& wall, double min_gamma,
                  std::vector<uint8_t>& skip) {
  std::vector<uint8_t>& fixed = wall.fixed;
  std::vector<int32_t>& pin_of = wall.pin_of;
  const std::vector<double> seen = star_visibility(output);
  const size_t nt = output.num_triangles();
  size_t freed = 0;
  for (size_t t = 0; t < nt; ++t) {
    const int32_t* T = &output.triangles[3 * t];
    if (fixed[size_t(T[0])] != kPinned && fixed[size_t(T[1])] != kPinned &&
        fixed[size_t(T[2])] != kPinned)
      continue;
    const bool folded = seen[size_t(T[0])] < kCosMaxFold || seen[size_t(T[1])] < kCosMaxFold ||
                        seen[size_t(T[2])] < kCosMaxFold;
    if (!folded &&
        triangle_gamma(&output.points[3 * size_t(T[0])], &output.points[3 * size_t(T[1])],
                       &output.points[3 * size_t(T[2])]) >= min_gamma)
      continue;
    for (int c = 0; c < 3; ++c) {
      const size_t o = size_t(T[c]);
      if (fixed[o] != kPinned) continue;
      fixed[o] = kFree;
      skip[size_t(pin_of[o])] = 1;
      pin_of[o] = -1;
      ++freed;
    }
  }
  return freed;
}

}  // namespace vm
