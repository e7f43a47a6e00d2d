// h(x) = min(H, min_i (h_i + g |x - x_i|)) by branch and bound over a k-d
// tree (Friedman, Bentley and Finkel, "An algorithm for finding best matches
// in logarithmic expected time", ACM TOMS 3, 1977) whose nodes carry the
// smallest h_i below them; see size_field3d.h.
//
// Phases of build: (1) validation, (2) a balanced implicit tree by median
// splits along the longest box axis (leaves of at most kLeaf points),
// (3) node boxes (rounded outward to float) and exact minimum sizes, so that
// the lower bound min_h + g dist(x, box) never exceeds the true one and a
// node that can at best tie the current value is skipped.
#include "core/volume/size_field3d.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

namespace vm {
namespace {

constexpr int32_t kLeaf = 8;

float round_down(double x) {
  float f = float(x);
  return double(f) > x ? std::nextafter(f, -INFINITY) : f;
}
float round_up(double x) {
  float f = float(x);
  return double(f) < x ? std::nextafter(f, INFINITY) : f;
}

}  // namespace

Result<VolumeSizeField> VolumeSizeField::build(const std::vector<double>& points,
                                               const std::vector<double>& sizes,
                                               const VolumeSizeOptions& options) {
  using R = Result<VolumeSizeField>;
  // Phase 1: validation.
  if (points.size() % 3 != 0) return R::Error("size field: points not a multiple of 3");
  const size_t n = points.size() / 3;
  if (n == 0) return R::Error("size field: no boundary point");
  if (sizes.size() != n) return R::Error("size field: one size per point expected");
  if (n > size_t(INT32_MAX) / 4) return R::Error("size field: too many points");
  for (double x : points)
    if (!std::isfinite(x)) return R::Error("size field: non-finite coordinate");
  for (double h : sizes)
    if (!(h > 0) || !std::isfinite(h)) return R::Error("size field: sizes must be finite and > 0");
  if (!(options.core_size >= 0) || !std::isfinite(options.core_size))
    return R::Error("size field: core size must be finite and >= 0");
  if (!(options.gradation >= 0) || !std::isfinite(options.gradation))
    return R::Error("size field: gradation must be finite and >= 0");

  VolumeSizeField f;
  f.core_ = options.core_size;
  f.g_ = options.gradation;
  f.min_size_ = *std::min_element(sizes.begin(), sizes.end());
  if (f.core_ > 0) f.min_size_ = std::min(f.min_size_, f.core_);
  f.spheres_ = options.spheres;
  for (const RefineSphere& s : f.spheres_) f.min_size_ = std::min(f.min_size_, s.size);

  // Phase 2: tree order. Depth d with ceil(n / 2^d) <= kLeaf.
  int depth = 0;
  while ((int64_t(n) + (int64_t(1) << depth) - 1) / (int64_t(1) << depth) > kLeaf) ++depth;
  f.nodes_.resize((size_t(1) << (depth + 1)) - 1);
  std::vector<int32_t> order(n);
  std::iota(order.begin(), order.end(), 0);
  // Median splits, breadth-first over the implicit tree.
  struct Range {
    int32_t node, begin, end;
  };
  std::vector<Range> stack = {{0, 0, int32_t(n)}};
  const int32_t first_leaf = int32_t((size_t(1) << depth) - 1);
  while (!stack.empty()) {
    const Range r = stack.back();
    stack.pop_back();
    f.nodes_[size_t(r.node)].begin = r.begin;
    f.nodes_[size_t(r.node)].end = r.end;
    if (r.node >= first_leaf) continue;
    double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
    for (int32_t i = r.begin; i < r.end; ++i)
      for (int k = 0; k < 3; ++k) {
        const double x = points[3 * size_t(order[size_t(i)]) + size_t(k)];
        lo[k] = std::min(lo[k], x);
        hi[k] = std::max(hi[k], x);
      }
    int axis = 0;
    for (int k = 1; k < 3; ++k)
      if (hi[k] - lo[k] > hi[axis] - lo[axis]) axis = k;
    const int32_t mid = r.begin + (r.end - r.begin) / 2;
    // Ties by index keep the order (hence the tree) deterministic.
    std::nth_element(order.begin() + r.begin, order.begin() + mid, order.begin() + r.end,
                     [&](int32_t a, int32_t b) {
                       const double xa = points[3 * size_t(a) + size_t(axis)];
                       const double xb = points[3 * size_t(b) + size_t(axis)];
                       return xa < xb || (xa == xb && a < b);
                     });
    stack.push_back({2 * r.node + 1, r.begin, mid});
    stack.push_back({2 * r.node + 2, mid, r.end});
  }
  f.pts_.resize(3 * n);
  f.size_.resize(n);
  for (size_t i = 0; i < n; ++i) {
    for (int k = 0; k < 3; ++k)
      f.pts_[3 * i + size_t(k)] = points[3 * size_t(order[i]) + size_t(k)];
    f.size_[i] = sizes[size_t(order[i])];
  }

  // Phase 3: boxes and minimum sizes, leaves up.
  for (int32_t node = int32_t(f.nodes_.size()) - 1; node >= 0; --node) {
    Node& nd = f.nodes_[size_t(node)];
    if (node >= first_leaf) {
      double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300}, mh = 1e300;
      for (int32_t i = nd.begin; i < nd.end; ++i) {
        for (int k = 0; k < 3; ++k) {
          lo[k] = std::min(lo[k], f.pts_[3 * size_t(i) + size_t(k)]);
          hi[k] = std::max(hi[k], f.pts_[3 * size_t(i) + size_t(k)]);
        }
        mh = std::min(mh, f.size_[size_t(i)]);
      }
      for (int k = 0; k < 3; ++k) {
        nd.lo[k] = nd.begin < nd.end ? round_down(lo[k]) : 0;
        nd.hi[k] = nd.begin < nd.end ? round_up(hi[k]) : 0;
      }
      nd.min_h = nd.begin < nd.end ? mh : INFINITY;
    } else {
      const Node& a = f.nodes_[2 * size_t(node) + 1];
      const Node& b = f.nodes_[2 * size_t(node) + 2];
      const bool ea = a.begin == a.end, eb = b.begin == b.end;
      for (int k = 0; k < 3; ++k) {
        nd.lo[k] = ea ? b.lo[k] : eb ? a.lo[k] : std::min(a.lo[k], b.lo[k]);
        nd.hi[k] = ea ? b.hi[k] : eb ? a.hi[k] : std::max(a.hi[k], b.hi[k]);
      }
      nd.min_h = std::min(a.min_h, b.min_h);
    }
  }
  return f;
}

double VolumeSizeField::eval(const double* x, double upper_bound, double rel_tol) const {
  double best = upper_bound;
  const double keep = 1 - rel_tol;  // nodes that cannot beat keep * best are skipped
  if (core_ > 0) best = std::min(best, core_);
  if (!spheres_.empty()) best = std::min(best, refine_size(spheres_, x, g_));
  if (nodes_.empty()) return best;
  const int32_t first_leaf = int32_t(nodes_.size() / 2);
  auto lower_bound = [&](const Node& nd) {
    double d2 = 0;
    for (int k = 0; k < 3; ++k) {
      const double lo = nd.lo[k], hi = nd.hi[k];
      const double e = x[k] < lo ? lo - x[k] : x[k] > hi ? x[k] - hi : 0.0;
      d2 += e * e;
    }
    return nd.min_h + g_ * std::sqrt(d2);
  };
  // Depth-first, nearer (smaller bound) child first; the stack holds at
  // most one pending sibling per level.
  struct Item {
    int32_t node;
    double bound;
  };
  Item stack[64];
  int top = 0;
  stack[top++] = {0, lower_bound(nodes_[0])};
  while (top > 0) {
    const Item it = stack[--top];
    if (it.bound >= keep * best) continue;
    const Node& nd = nodes_[size_t(it.node)];
    if (it.node >= first_leaf) {
      for (int32_t i = nd.begin; i < nd.end; ++i) {
        const double* p = &pts_[3 * size_t(i)];
        const double dx = x[0] - p[0], dy = x[1] - p[1], dz = x[2] - p[2];
        const double h = size_[size_t(i)] + g_ * std::sqrt(dx * dx + dy * dy + dz * dz);
        best = std::min(best, h);
      }
      continue;
    }
    const int32_t a = 2 * it.node + 1, b = a + 1;
    const bool ea = nodes_[size_t(a)].begin == nodes_[size_t(a)].end;
    const bool eb = nodes_[size_t(b)].begin == nodes_[size_t(b)].end;
    const double la = ea ? INFINITY : lower_bound(nodes_[size_t(a)]);
    const double lb = eb ? INFINITY : lower_bound(nodes_[size_t(b)]);
    // Push the farther first so the nearer is popped next.
    if (la <= lb) {
      if (lb < keep * best) stack[top++] = {b, lb};
      if (la < keep * best) stack[top++] = {a, la};
    } else {
      if (la < keep * best) stack[top++] = {a, la};
      if (lb < keep * best) stack[top++] = {b, lb};
    }
  }
  return best;
}

}  // namespace vm
