// Quadric-error half-edge collapse (Garland and Heckbert 1997) with the link
// condition (Dey et al. 1999), in phases:
//  1. plane quadrics per vertex (area-weighted, about the centre of the
//     bounding box), boundary vertices marked;
//  2. vertex stars as lists of corners, each with room for what
//     collapses add (renumbered along a Hilbert curve for locality);
//  3. per vertex, its cheapest valid collapse, in a bucket queue by cost;
//  4. collapses cheapest first; a candidate is checked again against the
//     current mesh when it comes out of the queue (lazy invalidation);
//  5. compaction of the vertices and triangles left, in input order.
#include "core/mesh/decimate.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <span>

#include "core/geom/hilbert_sort.h"
#include "core/geom/triangle_gamma.h"
#include "core/geom/vec3.h"
#include "core/mesh/adjacency.h"
#include "core/util/portable_math.h"

namespace vm {
namespace {

/// A symmetric 4x4 quadric: q[0..5] the 3x3 part (xx xy xz yy yz zz),
/// q[6..8] the linear part, q[9] the constant.
using Quadric = std::array<double, 10>;

double quadric_at(const Quadric& q, const Quadric& r, const Vec3& p) {
  auto qq = [&](int i) { return q[size_t(i)] + r[size_t(i)]; };
  const double x = p[0], y = p[1], z = p[2];
  return qq(0) * x * x + 2 * qq(1) * x * y + 2 * qq(2) * x * z + qq(3) * y * y + 2 * qq(4) * y * z +
         qq(5) * z * z + 2 * (qq(6) * x + qq(7) * y + qq(8) * z) + qq(9);
}

struct Candidate {
  double cost;
  int32_t v, u;  ///< collapse v onto u
  uint32_t stamp;
};

class Decimator {
 public:
  Decimator(const SurfaceMesh& input, const DecimateLimits& limits)
      : limits_(limits), tri_(input.triangles) {
    const size_t nv = input.num_vertices();
    const BoundingBox box = bounding_box(input.points);
    const Vec3 centre = {0.5 * (box.min[0] + box.max[0]), 0.5 * (box.min[1] + box.max[1]),
                         0.5 * (box.min[2] + box.max[2])};
    // Vertices renumbered along a Hilbert curve, so that a vertex's
    // neighbours are near it in memory.
    order_of_.resize(nv);
    for (size_t v = 0; v < nv; ++v) order_of_[v] = int32_t(v);
    hilbert_sort(input.points, order_of_.data(), int64_t(nv));
    rank_.resize(nv);
    for (size_t v = 0; v < nv; ++v) rank_[size_t(order_of_[v])] = int32_t(v);
    for (int32_t& v : tri_) v = rank_[size_t(v)];
    p_.resize(nv);
    max_error_.resize(nv);
    max_edge_.resize(nv);
    for (size_t v = 0; v < nv; ++v) {
      const int32_t old = order_of_[v];
      p_[v] = at(input.points, old) - centre;
      max_error_[v] = limits.max_error[size_t(old)];
      max_edge_[v] = limits.max_edge[size_t(old)];
    }
    cos_turn_ = pm::cos(limits.max_normal_turn_degrees * std::numbers::pi / 180);
    quadrics();
    boundary(input);
    stars();
  }

  DecimatedSurface run(const SurfaceMesh& input) {
    const size_t nv = p_.size();
    stamp_.assign(nv, 0);
    target_.assign(nv, -1);
    waiting_.assign(nv, 0);
    mark_.assign(nv, 0);
    for (size_t v = 0; v < nv; ++v) push_best(int32_t(v));
    collapse_all();
    return compact(input);
  }

 private:
  // Phase 1: area-weighted plane quadrics; the weight is the area.
  void quadrics() {
    q_.assign(p_.size(), Quadric{});
    w_.assign(p_.size(), 0.0);
    for (size_t t = 0; t < tri_.size() / 3; ++t) {
      const Vec3 n2 = cross(p_[c(t, 1)] - p_[c(t, 0)], p_[c(t, 2)] - p_[c(t, 0)]);
      const double len = norm(n2);
      if (len == 0) continue;
      const double area = 0.5 * len;
      const Vec3 n = (1 / len) * n2;
      const double d = -dot(n, p_[c(t, 0)]);
      const Quadric k = {n[0] * n[0], n[0] * n[1], n[0] * n[2], n[1] * n[1], n[1] * n[2],
                         n[2] * n[2], n[0] * d,    n[1] * d,    n[2] * d,    d * d};
      for (int j = 0; j < 3; ++j) {
        Quadric& q = q_[c(t, j)];
        for (size_t i = 0; i < 10; ++i) q[i] += area * k[i];
        w_[c(t, j)] += area;
      }
    }
  }

  void boundary(const SurfaceMesh& input) {
    const TriangleAdjacency adj = build_adjacency(input);
    on_boundary_.assign(p_.size(), 0);
    for (size_t h = 0; h < adj.opposite.size(); ++h)
      if (adj.opposite[h] < 0) {
        on_boundary_[size_t(rank_[size_t(half_edge_from(input, int32_t(h)))])] = 1;
        on_boundary_[size_t(rank_[size_t(half_edge_to(input, int32_t(h)))])] = 1;
      }
  }

  // Phase 2: stars as corner lists. Corner 3t+k holds tri_[3t+k]; v's
  // corners are corner_[first_[v] .. first_[v] + count_[v]), with room for
  // max(its degree, max_valence) corners, which collapses never exceed.
  void stars() {
    const size_t nv = p_.size();
    first_.assign(nv + 1, 0);
    for (int32_t v : tri_) ++first_[size_t(v) + 1];
    for (size_t v = 0; v < nv; ++v)
      first_[v + 1] = first_[v] + std::max(first_[v + 1], uint32_t(limits_.max_valence));
    count_.assign(nv, 0);
    corner_.resize(first_[nv]);
    for (size_t k = 0; k < tri_.size(); ++k) {
      const size_t v = size_t(tri_[k]);
      corner_[first_[v] + count_[v]++] = int32_t(k);
    }
    tri_alive_.assign(tri_.size() / 3, 1);
    removed_.assign(nv, 0);
  }

  std::span<const int32_t> corners(int32_t v) const {
    return {corner_.data() + first_[size_t(v)], count_[size_t(v)]};
  }

  size_t c(size_t t, int k) const { return size_t(tri_[3 * t + size_t(k)]); }

  /// The distinct neighbours of v: the corner after v in each triangle at v
  /// (each neighbour of an interior vertex once), and at a boundary vertex
  /// the corners before v that are no corner after.
  void neighbours(int32_t v, std::vector<int32_t>& out) const {
    out.clear();
    for (int32_t k : corners(v))
      out.push_back(tri_[size_t(k) - size_t(k) % 3 + (size_t(k) + 1) % 3]);
    if (!on_boundary_[size_t(v)]) return;
    const size_t after = out.size();
    for (int32_t k : corners(v)) {
      const int32_t w = tri_[size_t(k) - size_t(k) % 3 + (size_t(k) + 2) % 3];
      if (std::find(out.begin(), out.begin() + long(after), w) == out.begin() + long(after))
        out.push_back(w);
    }
  }

  double cost(int32_t v, int32_t u) const {
    return std::max(0.0, quadric_at(q_[size_t(v)], q_[size_t(u)], p_[size_t(u)])) /
           (w_[size_t(v)] + w_[size_t(u)]);
  }

  double max_cost(int32_t v, int32_t u) const {
    const double e = std::min(max_error_[size_t(v)], max_error_[size_t(u)]);
    return e * e;
  }

  /// Whether collapsing v onto u keeps every edge at u within the length
  /// limits, every moved triangle unfolded and well shaped, and the surface
  /// manifold (the link condition: v's and u's only common neighbours are
  /// the two vertices opposite their edge) with no vertex of too many
  /// neighbours. `nv` = neighbours(v). Cheapest tests first.
  bool valid(int32_t v, int32_t u, const std::vector<int32_t>& nv) {
    const Vec3& pu = p_[size_t(u)];
    for (int32_t w : nv) {
      if (w == u) continue;
      const Vec3 e = p_[size_t(w)] - pu;
      const double limit = std::min(max_edge_[size_t(u)], max_edge_[size_t(w)]);
      if (dot(e, e) > limit * limit) return false;
    }
    for (int32_t k : corners(v)) {
      const size_t t = size_t(k) / 3, j = size_t(k) % 3;
      const int32_t b = tri_[3 * t + (j + 1) % 3], cc = tri_[3 * t + (j + 2) % 3];
      if (b == u || cc == u) continue;  // removed by the collapse
      const Vec3 &pb = p_[size_t(b)], &pc = p_[size_t(cc)];
      const Vec3 before = cross(pb - p_[size_t(v)], pc - p_[size_t(v)]);
      const Vec3 after = cross(pb - pu, pc - pu);
      const double nb = norm(before), na = norm(after);
      if (na == 0 || dot(before, after) < cos_turn_ * nb * na) return false;
      const double q_after = triangle_gamma(pu.data(), pb.data(), pc.data());
      if (q_after < limits_.min_quality &&
          q_after < triangle_gamma(p_[size_t(v)].data(), pb.data(), pc.data()))
        return false;
    }
    neighbours(u, nu_);
    ++epoch_;
    for (int32_t w : nv) mark_[size_t(w)] = epoch_;
    size_t common = 0;
    for (int32_t w : nu_) common += mark_[size_t(w)] == epoch_;
    if (common != 2) return false;
    // u's valence afterwards: its neighbours and v's, less v, u and the two common.
    const size_t valence = nv.size() + nu_.size() - 4;
    return valence <= size_t(limits_.max_valence) || valence < nu_.size();
  }

  void push(const Candidate& k, double limit) {
    const double share = limit > 0 ? std::sqrt(k.cost / limit) : 0;
    const size_t bin = std::min(kBins - 1, size_t(share * double(kBins)));
    bins_[bin].push_back(k);
    lowest_ = std::min(lowest_, bin);
  }

  /// Phase 3: v's cheapest valid collapse, if any, into the queue.
  void push_best(int32_t v) {
    target_[size_t(v)] = -1;
    if (removed_[size_t(v)] || on_boundary_[size_t(v)]) return;
    neighbours(v, nv_);
    order_.clear();
    for (int32_t u : nv_) {
      const double k = cost(v, u);
      if (k <= max_cost(v, u)) order_.push_back({k, v, u, stamp_[size_t(v)]});
    }
    std::sort(order_.begin(), order_.end(), [](const Candidate& a, const Candidate& b) {
      return a.cost != b.cost ? a.cost < b.cost : a.u < b.u;
    });
    for (const Candidate& k : order_) {
      if (valid(v, k.u, nv_)) {
        push(k, max_cost(v, k.u));
        target_[size_t(v)] = k.u;
        return;
      }
    }
  }

  /// Removes corner k from its vertex's star.
  void unlink(size_t k) {
    const size_t v = size_t(tri_[k]);
    int32_t* begin = corner_.data() + first_[v];
    int32_t* last = begin + --count_[v];
    *std::find(begin, last, int32_t(k)) = *last;
  }

  void collapse(int32_t v, int32_t u) {
    for (size_t i = 0; i < 10; ++i) q_[size_t(u)][i] += q_[size_t(v)][i];
    w_[size_t(u)] += w_[size_t(v)];
    // The two triangles on edge (v, u) go first, so that u's star never
    // holds more than it will.
    for (int32_t k : corners(v)) {
      const size_t t = size_t(k) / 3;
      if (tri_[3 * t] != u && tri_[3 * t + 1] != u && tri_[3 * t + 2] != u) continue;
      tri_alive_[t] = 0;
      for (size_t j = 0; j < 3; ++j)
        if (3 * t + j != size_t(k)) unlink(3 * t + j);
    }
    for (int32_t k : corners(v)) {
      if (!tri_alive_[size_t(k) / 3]) continue;
      tri_[size_t(k)] = u;
      corner_[first_[size_t(u)] + count_[size_t(u)]++] = k;
    }
    count_[size_t(v)] = 0;
    removed_[size_t(v)] = 1;
  }

  // Phase 4. A vertex that had no valid collapse waits until the queue is
  // empty, then is tried again if its neighbourhood changed meanwhile
  // (sweeps, until one collapses nothing).
  void collapse_all() {
    for (;;) {
      while (lowest_ < kBins) {
        if (bins_[lowest_].empty()) {
          ++lowest_;
          continue;
        }
        const Candidate top = bins_[lowest_].back();
        bins_[lowest_].pop_back();
        const int32_t v = top.v, u = top.u;
        if (removed_[size_t(v)] || removed_[size_t(u)] || top.stamp != stamp_[size_t(v)]) continue;
        neighbours(v, nv_);
        if (cost(v, u) > max_cost(v, u) || !valid(v, u, nv_)) {
          ++stamp_[size_t(v)];
          push_best(v);
          continue;
        }
        collapse(v, u);
        // Costs changed where u is a vertex of the pair: u's own, and its
        // neighbours' that collapsed onto u or v. Other candidates near u
        // are checked again when they come out.
        neighbours(u, around_);
        around_.push_back(u);
        for (int32_t w : around_) {
          const int32_t t = target_[size_t(w)];
          if (t == -1) {
            if (!waiting_[size_t(w)]) waiting_list_.push_back(w);
            waiting_[size_t(w)] = 1;
          } else if (w == u || t == u || t == v) {
            ++stamp_[size_t(w)];
            push_best(w);
          }
        }
      }
      if (waiting_list_.empty()) return;
      std::sort(waiting_list_.begin(), waiting_list_.end());
      for (int32_t w : waiting_list_) {
        waiting_[size_t(w)] = 0;
        ++stamp_[size_t(w)];
        push_best(w);
      }
      waiting_list_.clear();
    }
  }

  // Phase 5.
  DecimatedSurface compact(const SurfaceMesh& input) const {
    DecimatedSurface out;
    std::vector<int32_t> index(p_.size(), -1);  // by internal number
    for (size_t v = 0; v < p_.size(); ++v) {
      const size_t r = size_t(rank_[v]);
      if (removed_[r]) continue;
      index[r] = int32_t(out.input_vertex.size());
      out.input_vertex.push_back(int32_t(v));
      for (size_t i = 0; i < 3; ++i) out.mesh.points.push_back(input.points[3 * v + i]);
    }
    for (size_t t = 0; t < tri_alive_.size(); ++t)
      if (tri_alive_[t])
        for (size_t j = 0; j < 3; ++j) out.mesh.triangles.push_back(index[c(t, int(j))]);
    return out;
  }

  const DecimateLimits& limits_;
  std::vector<int32_t> tri_;              ///< 3 per triangle, current vertices
  std::vector<int32_t> order_of_, rank_;  ///< internal -> input number, and back
  std::vector<Vec3> p_;                   ///< positions about the box centre
  std::vector<double> max_error_, max_edge_;
  std::vector<Quadric> q_;
  std::vector<double> w_;
  std::vector<uint8_t> on_boundary_, removed_, tri_alive_;
  std::vector<uint32_t> first_, count_;
  std::vector<int32_t> corner_;
  std::vector<uint32_t> stamp_;
  std::vector<int32_t> target_;   ///< per vertex: its candidate's u (-1: none)
  std::vector<uint8_t> waiting_;  ///< per vertex: in waiting_list_
  std::vector<uint32_t> mark_;    ///< per vertex: epoch_ when in the current link
  uint32_t epoch_ = 0;
  std::vector<int32_t> waiting_list_;
  double cos_turn_ = 0;
  /// The candidates in bins of cost over the limit (kBins on a square-root
  /// scale); a bin is a stack, so the latest (nearby) candidate comes first.
  static constexpr size_t kBins = 128;
  std::array<std::vector<Candidate>, kBins> bins_;
  size_t lowest_ = kBins;                  ///< no candidate in a bin below
  std::vector<int32_t> nv_, nu_, around_;  ///< scratch
  std::vector<Candidate> order_;           ///< scratch
};

}  // namespace

DecimatedSurface decimate_surface(const SurfaceMesh& input, const DecimateLimits& limits) {
  Decimator d(input, limits);
  return d.run(input);
}

}  // namespace vm
