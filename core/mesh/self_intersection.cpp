// Exact triangle-triangle intersection by segment-triangle tests (two closed
// triangles intersect iff an edge of one meets the other: the intersection is
// a segment or a polygon whose extreme points lie on edges), each decided by
// orient3d signs (the line through the segment pierces the triangle iff the
// three tetrahedra it makes with the triangle's edges have one sign), with a
// 2D fallback on a coordinate plane for coplanar configurations (Guigue and
// Devillers, "Fast and robust triangle-triangle overlap test using
// orientation predicates", J. Graphics Tools 8, 2003, for the approach).
// Before the exact tests, floating-point filters with safe margins prove most
// neighbor pairs disjoint (separating planes), which matters on flat regions
// where orient3d always needs its slow exact fallback. Candidate pairs come
// from a self-traversal of a box hierarchy.
#include "core/mesh/self_intersection.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>

#include "core/geom/predicates.h"
#include "core/geom/vec3.h"
#include "core/mesh/triangle_bvh.h"
#include "core/util/parallel.h"

namespace vm {
namespace {

int sign(double x) { return (x > 0) - (x < 0); }

// Projection of 3D points on the coordinate plane that drops axis `drop`.
struct P2 {
  double x[2];
};
P2 project(const double* p, int drop) {
  const int i = drop == 0 ? 1 : 0, j = drop == 2 ? 1 : 2;
  return {{p[i], p[j]}};
}

// An axis whose coordinate plane sees triangle a, b, c non-degenerate (its
// normal's largest component first), -1 if the triangle is degenerate.
int projection_axis(const double* a, const double* b, const double* c) {
  const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  const double n[3] = {std::abs(u[1] * v[2] - u[2] * v[1]), std::abs(u[2] * v[0] - u[0] * v[2]),
                       std::abs(u[0] * v[1] - u[1] * v[0])};
  int axes[3] = {0, 1, 2};
  std::stable_sort(axes, axes + 3, [&](int p, int q) { return n[p] > n[q]; });
  for (int d : axes) {
    const P2 A = project(a, d), B = project(b, d), C = project(c, d);
    if (orient2d(A.x, B.x, C.x) != 0) return d;
  }
  return -1;
}

// r on the closed segment pq, given p, q, r collinear.
bool on_collinear_segment(const P2& p, const P2& q, const P2& r) {
  for (int k = 0; k < 2; ++k)
    if (r.x[k] < std::min(p.x[k], q.x[k]) || r.x[k] > std::max(p.x[k], q.x[k])) return false;
  return true;
}

// Closed segments pq and rs of the plane share a point.
bool segments_meet_2d(const P2& p, const P2& q, const P2& r, const P2& s) {
  const int o1 = sign(orient2d(p.x, q.x, r.x)), o2 = sign(orient2d(p.x, q.x, s.x));
  const int o3 = sign(orient2d(r.x, s.x, p.x)), o4 = sign(orient2d(r.x, s.x, q.x));
  if (o1 * o2 < 0 && o3 * o4 < 0) return true;
  if (o1 == 0 && on_collinear_segment(p, q, r)) return true;
  if (o2 == 0 && on_collinear_segment(p, q, s)) return true;
  if (o3 == 0 && on_collinear_segment(r, s, p)) return true;
  if (o4 == 0 && on_collinear_segment(r, s, q)) return true;
  return false;
}

// p in the closed triangle abc of the plane (abc non-degenerate).
bool point_in_triangle_2d(const P2& p, const P2& a, const P2& b, const P2& c) {
  const int s1 = sign(orient2d(a.x, b.x, p.x)), s2 = sign(orient2d(b.x, c.x, p.x)),
            s3 = sign(orient2d(c.x, a.x, p.x));
  return (s1 >= 0 && s2 >= 0 && s3 >= 0) || (s1 <= 0 && s2 <= 0 && s3 <= 0);
}

// Closed segment pq meets closed triangle abc, all in one plane; `drop` an
// axis that sees abc non-degenerate.
bool coplanar_segment_triangle(const double* p, const double* q, const double* a, const double* b,
                               const double* c, int drop) {
  const P2 P = project(p, drop), Q = project(q, drop), A = project(a, drop), B = project(b, drop),
           C = project(c, drop);
  return point_in_triangle_2d(P, A, B, C) || point_in_triangle_2d(Q, A, B, C) ||
         segments_meet_2d(P, Q, A, B) || segments_meet_2d(P, Q, B, C) ||
         segments_meet_2d(P, Q, C, A);
}

// Closed segment pq meets closed non-degenerate triangle abc (its
// projection axis `drop` for the coplanar case).
bool segment_triangle(const double* p, const double* q, const double* a, const double* b,
                      const double* c, int drop) {
  const int op = sign(orient3d(a, b, c, p)), oq = sign(orient3d(a, b, c, q));
  if (op * oq > 0) return false;  // both strictly on one side
  if (op == 0 && oq == 0) return coplanar_segment_triangle(p, q, a, b, c, drop);
  // The segment reaches the plane; does its line pierce the closed triangle?
  const int s1 = sign(orient3d(p, q, a, b)), s2 = sign(orient3d(p, q, b, c)),
            s3 = sign(orient3d(p, q, c, a));
  return (s1 >= 0 && s2 >= 0 && s3 >= 0) || (s1 <= 0 && s2 <= 0 && s3 <= 0);
}

// Floating-point filters (phase 1 of every pair test): conservative proofs
// that two triangles do not intersect, so the exact predicates, whose exact
// fallback is slow, run only when a filter cannot decide. Neighbors in flat
// regions (caps, planar patches) are coplanar to rounding, where orient3d
// always falls back to exact arithmetic; these filters decide them in
// floating point. Each claim compares dot products computed relative to a
// local origin with a margin far above their rounding error (~1e-15 of
// |axis| * |point - origin|), so a "separated" answer is always right.
constexpr double kFilterMargin = 1e-12;

Vec3 sub3(const double* a, const double* b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }

// Triangles sharing vertex v, other corners a, b (first) and c, d (second):
// true if a plane through v is proven to leave a, b strictly on one side and
// c, d strictly on the other (then the triangles meet only at v), or c, d
// strictly on one side of the first triangle's plane, or a, b of the
// second's.
bool separated_at_vertex(const double* v, const double* a, const double* b, const double* c,
                         const double* d) {
  const Vec3 x[4] = {sub3(a, v), sub3(b, v), sub3(c, v), sub3(d, v)};
  double scale = 0;
  for (const Vec3& y : x) scale = std::max(scale, norm(y));
  const Vec3 n1 = cross(x[0], x[1]), n2 = cross(x[2], x[3]);
  auto side = [&](const Vec3& m, int i, int j, double sign) {  // x[i], x[j] strictly on `sign`
    const double eps = kFilterMargin * norm(m) * scale;
    return sign * dot(m, x[i]) > eps && sign * dot(m, x[j]) > eps;
  };
  auto splits = [&](const Vec3& m) {
    return (side(m, 0, 1, 1) && side(m, 2, 3, -1)) || (side(m, 0, 1, -1) && side(m, 2, 3, 1));
  };
  if (side(n1, 2, 3, 1) || side(n1, 2, 3, -1) || side(n2, 0, 1, 1) || side(n2, 0, 1, -1))
    return true;
  // Planes through v containing one of the four edges at v, perpendicular to
  // a face: the separators of two disjoint sectors of one plane.
  for (const Vec3& n : {n1, n2})
    for (const Vec3& e : x)
      if (splits(cross(n, e))) return true;
  return false;
}

// Triangles sharing edge (e0, e1), third corners c (first) and d (second):
// true if the components of c - e0 and d - e0 perpendicular to the edge are
// proven to point away from each other (more than 90 degrees apart), so the
// triangles cannot fold onto each other.
bool opened_at_edge(const double* e0, const double* e1, const double* c, const double* d) {
  const Vec3 e = sub3(e1, e0), x = sub3(c, e0), y = sub3(d, e0);
  const double ee = dot(e, e);
  if (!(ee > 0)) return false;
  const double fx = dot(x, e) / ee, fy = dot(y, e) / ee;
  const Vec3 wx = {x[0] - fx * e[0], x[1] - fx * e[1], x[2] - fx * e[2]};
  const Vec3 wy = {y[0] - fy * e[0], y[1] - fy * e[1], y[2] - fy * e[2]};
  return dot(wx, wy) < -1e-9 * norm(x) * norm(y);
}

// Triangles with no shared vertex: true if a separating axis (a face
// normal, or a face normal crossed with one of the six edges: the
// separators of coplanar triangles) is proven to separate them.
bool separated_apart(const double* const* p, const double* const* q) {
  const double* o = p[0];
  Vec3 x[6];
  double scale = 0;
  for (int k = 0; k < 3; ++k) {
    x[k] = sub3(p[k], o);
    x[k + 3] = sub3(q[k], o);
  }
  for (const Vec3& y : x) scale = std::max(scale, norm(y));
  const Vec3 n1 = cross(sub3(p[1], p[0]), sub3(p[2], p[0]));
  const Vec3 n2 = cross(sub3(q[1], q[0]), sub3(q[2], q[0]));
  auto separates = [&](const Vec3& m) {
    double lo1 = 1e300, hi1 = -1e300, lo2 = 1e300, hi2 = -1e300;
    for (int k = 0; k < 3; ++k) {
      const double s = dot(m, x[k]), t = dot(m, x[k + 3]);
      lo1 = std::min(lo1, s), hi1 = std::max(hi1, s);
      lo2 = std::min(lo2, t), hi2 = std::max(hi2, t);
    }
    const double eps = kFilterMargin * norm(m) * scale;
    return hi1 + eps < lo2 || hi2 + eps < lo1;
  };
  if (separates(n1) || separates(n2)) return true;
  for (int k = 0; k < 3; ++k) {
    const Vec3 e1 = sub3(p[(k + 1) % 3], p[k]), e2 = sub3(q[(k + 1) % 3], q[k]);
    if (separates(cross(n1, e1)) || separates(cross(n1, e2)) || separates(cross(n2, e1)) ||
        separates(cross(n2, e2)))
      return true;
  }
  return false;
}

struct Tri {
  const double* p[3];
  int32_t v[3];
  int drop;  // projection axis, -1 if degenerate
};

class PairTester {
 public:
  explicit PairTester(const SurfaceMesh& m) : m_(m) {}

  Tri tri(int32_t t) const {
    Tri T;
    for (int k = 0; k < 3; ++k) {
      T.v[k] = m_.triangles[3 * size_t(t) + size_t(k)];
      T.p[k] = &m_.points[3 * size_t(T.v[k])];
    }
    T.drop = T.v[0] == T.v[1] || T.v[1] == T.v[2] || T.v[0] == T.v[2]
                 ? -1
                 : projection_axis(T.p[0], T.p[1], T.p[2]);
    return T;
  }

  // Both non-degenerate.
  static bool intersect(const Tri& A, const Tri& B) {
    // Shared vertices by index: positions in A and B.
    int ia[3], ib[3], shared = 0;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        if (A.v[i] == B.v[j]) ia[shared] = i, ib[shared] = j, ++shared;
    if (shared >= 3) return true;  // the same triangle twice
    if (shared == 2) {
      // Common edge: only a coplanar fold (both on one side of it) overlaps.
      const int c = 3 - ia[0] - ia[1], d = 3 - ib[0] - ib[1];
      const double* e0 = A.p[ia[0]];
      const double* e1 = A.p[ia[1]];
      if (opened_at_edge(e0, e1, A.p[c], B.p[d])) return false;
      if (orient3d(e0, e1, A.p[c], B.p[d]) != 0) return false;
      const P2 E0 = project(e0, A.drop), E1 = project(e1, A.drop), C = project(A.p[c], A.drop),
               D = project(B.p[d], A.drop);
      return sign(orient2d(E0.x, E1.x, C.x)) * sign(orient2d(E0.x, E1.x, D.x)) > 0;
    }
    if (shared == 1) {
      // Common vertex v: the triangles meet elsewhere iff the edge opposite
      // v in one meets the other (the far end of their common part lies on
      // such an edge).
      const int a = ia[0], b = ib[0];
      if (separated_at_vertex(A.p[a], A.p[(a + 1) % 3], A.p[(a + 2) % 3], B.p[(b + 1) % 3],
                              B.p[(b + 2) % 3]))
        return false;
      return segment_triangle(A.p[(a + 1) % 3], A.p[(a + 2) % 3], B.p[0], B.p[1], B.p[2], B.drop) ||
             segment_triangle(B.p[(b + 1) % 3], B.p[(b + 2) % 3], A.p[0], A.p[1], A.p[2], A.drop);
    }
    // Disjoint indices. Reject when one lies strictly on one side of the
    // other's plane.
    if (separated_apart(A.p, B.p)) return false;
    int sb[3], sa[3];
    for (int k = 0; k < 3; ++k) sb[k] = sign(orient3d(A.p[0], A.p[1], A.p[2], B.p[k]));
    if (sb[0] == sb[1] && sb[1] == sb[2] && sb[0] != 0) return false;
    for (int k = 0; k < 3; ++k) sa[k] = sign(orient3d(B.p[0], B.p[1], B.p[2], A.p[k]));
    if (sa[0] == sa[1] && sa[1] == sa[2] && sa[0] != 0) return false;
    if (sb[0] == 0 && sb[1] == 0 && sb[2] == 0) {
      // Coplanar: an edge of A meets B, or B lies inside A.
      for (int k = 0; k < 3; ++k)
        if (coplanar_segment_triangle(A.p[k], A.p[(k + 1) % 3], B.p[0], B.p[1], B.p[2], B.drop))
          return true;
      const P2 q = project(B.p[0], A.drop);
      return point_in_triangle_2d(q, project(A.p[0], A.drop), project(A.p[1], A.drop),
                                  project(A.p[2], A.drop));
    }
    for (int k = 0; k < 3; ++k)
      if (segment_triangle(A.p[k], A.p[(k + 1) % 3], B.p[0], B.p[1], B.p[2], B.drop)) return true;
    for (int k = 0; k < 3; ++k)
      if (segment_triangle(B.p[k], B.p[(k + 1) % 3], A.p[0], A.p[1], A.p[2], A.drop)) return true;
    return false;
  }

 private:
  const SurfaceMesh& m_;
};

}  // namespace

bool triangles_intersect(const SurfaceMesh& mesh, int32_t t1, int32_t t2) {
  PairTester tester(mesh);
  const Tri A = tester.tri(t1), B = tester.tri(t2);
  if (A.drop < 0 || B.drop < 0) return false;
  return PairTester::intersect(A, B);
}

namespace {

// The triangles of a mesh prepared for pair tests (plane, box), and the
// test of one pair, counted into a report (one per chunk of work on the
// threads; merged in order by add()).
class PairCounter {
 public:
  PairCounter(const SurfaceMesh& mesh, size_t max_examples) : max_examples_(max_examples) {
    const PairTester tester(mesh);
    const size_t nt = mesh.num_triangles();
    tris_.resize(nt);
    box_.resize(6 * nt);
    for (size_t t = 0; t < nt; ++t) {
      tris_[t] = tester.tri(int32_t(t));
      if (tris_[t].drop < 0) ++degenerate_;
      for (int d = 0; d < 3; ++d) {
        box_[6 * t + size_t(d)] = std::min({tris_[t].p[0][d], tris_[t].p[1][d], tris_[t].p[2][d]});
        box_[6 * t + 3 + size_t(d)] =
            std::max({tris_[t].p[0][d], tris_[t].p[1][d], tris_[t].p[2][d]});
      }
    }
  }
  const double* lo(int32_t t) const { return &box_[6 * size_t(t)]; }
  const double* hi(int32_t t) const { return &box_[6 * size_t(t) + 3]; }
  void test(int32_t s, int32_t t, SelfIntersectionReport& report) const {
    const Tri &A = tris_[size_t(s)], &B = tris_[size_t(t)];
    if (A.drop < 0 || B.drop < 0) return;
    if (!boxes_overlap(lo(s), hi(s), lo(t), hi(t))) return;
    ++report.tested_pairs;
    if (!PairTester::intersect(A, B)) return;
    ++report.pairs;
    if (report.examples.size() < max_examples_)
      report.examples.push_back({std::min(s, t), std::max(s, t)});
  }
  /// The whole report from the parts' (in the order the work had
  /// sequentially: the first examples are the sequential search's).
  SelfIntersectionReport merge(const std::vector<SelfIntersectionReport>& parts) const {
    SelfIntersectionReport report;
    report.degenerate_triangles = degenerate_;
    for (const SelfIntersectionReport& p : parts) {
      report.pairs += p.pairs;
      report.tested_pairs += p.tested_pairs;
      for (const auto& e : p.examples)
        if (report.examples.size() < max_examples_) report.examples.push_back(e);
    }
    return report;
  }

 private:
  size_t max_examples_;
  size_t degenerate_ = 0;
  std::vector<Tri> tris_;
  std::vector<double> box_;  // 6 per triangle: lo, hi
};

// The self-traversal is cut into at least this many jobs (chunks of work
// that do not depend on the thread count).
constexpr size_t kPairJobs = 256;

}  // namespace

SelfIntersectionReport find_self_intersections(const SurfaceMesh& mesh, size_t max_examples) {
  if (mesh.num_triangles() < 2) return {};
  const PairCounter pairs(mesh, max_examples);
  const TriangleBvh bvh = build_triangle_bvh(mesh, 8);
  const std::vector<LeafPairJob> jobs = leaf_pair_jobs(bvh, kPairJobs);
  std::vector<SelfIntersectionReport> parts(jobs.size());
  parallel_for(jobs.size(), 1, [&](size_t begin, size_t end) {
    for (size_t k = begin; k < end; ++k)
      for_each_leaf_pair(bvh, jobs[k], [&](int32_t i, int32_t j) {
        pairs.test(bvh.order[size_t(i)], bvh.order[size_t(j)], parts[k]);
      });
  });
  return pairs.merge(parts);
}

std::vector<uint8_t> changed_triangles(const SurfaceMesh& before, const SurfaceMesh& now) {
  using Key = std::array<double, 9>;
  auto key = [](const SurfaceMesh& m, size_t t) {
    std::array<const double*, 3> c;
    for (int k = 0; k < 3; ++k)
      c[size_t(k)] = &m.points[3 * size_t(m.triangles[3 * t + size_t(k)])];
    std::sort(c.begin(), c.end(), [](const double* a, const double* b) {
      return std::lexicographical_compare(a, a + 3, b, b + 3);
    });
    Key out;
    for (int k = 0; k < 3; ++k) std::copy(c[size_t(k)], c[size_t(k)] + 3, &out[3 * size_t(k)]);
    return out;
  };
  auto hash = [](const Key& k) {
    uint64_t h = 1469598103934665603ull;
    for (double x : k) {
      uint64_t bits;
      std::memcpy(&bits, &x, sizeof bits);  // (no std::bit_cast in Emscripten's libc++)
      h = (h ^ bits) * 1099511628211ull;
    }
    return h ^ (h >> 29);
  };
  // An open-addressing set of the old triangles' keys (slot: triangle + 1).
  const size_t nb = before.num_triangles();
  size_t size = 16;
  while (size < 2 * nb) size *= 2;
  const uint64_t mask = size - 1;
  std::vector<Key> old_key(nb);
  std::vector<int32_t> slot(size, 0);
  parallel_for(nb, 4096, [&](size_t b, size_t e) {
    for (size_t t = b; t < e; ++t) old_key[t] = key(before, t);
  });
  for (size_t t = 0; t < nb; ++t) {
    uint64_t h = hash(old_key[t]) & mask;
    while (slot[h] != 0) h = (h + 1) & mask;
    slot[h] = int32_t(t + 1);
  }
  std::vector<uint8_t> changed(now.num_triangles());
  parallel_for(changed.size(), 4096, [&](size_t b, size_t e) {
    for (size_t t = b; t < e; ++t) {
      const Key k = key(now, t);
      bool found = false;
      for (uint64_t h = hash(k) & mask; slot[h] != 0 && !found; h = (h + 1) & mask)
        found = old_key[size_t(slot[h] - 1)] == k;
      changed[t] = !found;
    }
  });
  return changed;
}

SelfIntersectionReport find_self_intersections_of(const SurfaceMesh& mesh,
                                                  const std::vector<uint8_t>& flagged,
                                                  size_t max_examples) {
  const size_t nt = mesh.num_triangles();
  SurfaceMesh part;  // the flagged triangles (ids: position among them)
  part.points = mesh.points;
  std::vector<int32_t> id;
  for (size_t t = 0; t < nt; ++t)
    if (flagged[t]) {
      id.push_back(int32_t(t));
      part.triangles.insert(part.triangles.end(), &mesh.triangles[3 * t],
                            &mesh.triangles[3 * t] + 3);
    }
  if (id.empty() || nt < 2) return {};
  const PairCounter pairs(mesh, max_examples);
  const TriangleBvh bvh = build_triangle_bvh(part, 8);
  // One query per triangle; a pair of two flagged ones from the smaller.
  constexpr size_t kGrain = 2048;
  std::vector<SelfIntersectionReport> parts((nt + kGrain - 1) / kGrain);
  parallel_for(nt, kGrain, [&](size_t begin, size_t end) {
    SelfIntersectionReport& report = parts[begin / kGrain];
    std::vector<int32_t> nodes;
    for (int32_t t = int32_t(begin); t < int32_t(end); ++t) {
      nodes.assign(1, 0);
      while (!nodes.empty()) {
        const TriangleBvh::Node& n = bvh.nodes[size_t(nodes.back())];
        nodes.pop_back();
        if (!boxes_overlap(n.lo, n.hi, pairs.lo(t), pairs.hi(t))) continue;
        if (!TriangleBvh::is_leaf(n)) {
          nodes.push_back(n.first);
          nodes.push_back(n.first + 1);
          continue;
        }
        for (int32_t i = n.first; i < n.first + n.count; ++i) {
          const int32_t u = id[size_t(bvh.order[size_t(i)])];
          if (u != t && (!flagged[size_t(t)] || t < u)) pairs.test(t, u, report);
        }
      }
    }
  });
  return pairs.merge(parts);
}

}  // namespace vm
