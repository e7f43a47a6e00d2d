#include "core/volume/boundary_recovery.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include "core/geom/predicates.h"
#include "core/mesh/volume_mesh.h"
#include "core/phantom/vessel_phantom.h"

namespace vm {
namespace {

using P3 = std::array<double, 3>;

// A triangle soup welded by exact coordinates into an indexed surface.
struct Surf {
  std::vector<double> points;
  std::vector<int32_t> tris;
  std::vector<int32_t> tags;
  std::map<P3, int32_t> index;

  int32_t vertex(const P3& p) {
    auto [it, fresh] = index.try_emplace(p, int32_t(points.size() / 3));
    if (fresh) points.insert(points.end(), p.begin(), p.end());
    return it->second;
  }
  void tri(const P3& a, const P3& b, const P3& c, int32_t tag) {
    tris.insert(tris.end(), {vertex(a), vertex(b), vertex(c)});
    tags.push_back(tag);
  }
  // Quad a b c d (counterclockwise seen from outside) as two triangles.
  void quad(const P3& a, const P3& b, const P3& c, const P3& d, int32_t tag) {
    tri(a, b, c, tag);
    tri(a, c, d, tag);
  }
};

P3 lerp3(const P3& o, const P3& u, const P3& v, double s, double t) {
  return {o[0] + s * u[0] + t * v[0], o[1] + s * u[1] + t * v[1], o[2] + s * u[2] + t * v[2]};
}

// Box [0,lx]x[0,ly]x[0,lz] with an n[0] x n[1] x n[2] grid on its faces,
// one tag per face; `bump(p)` may move vertices (applied to coordinates
// before welding, so it must be a function of the position).
template <class Bump>
Surf box(P3 l, std::array<int, 3> n, Bump bump) {
  Surf s;
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side) {
      const int i = (axis + 1) % 3, j = (axis + 2) % 3;
      P3 o{0, 0, 0}, u{0, 0, 0}, v{0, 0, 0};
      o[axis] = side * l[axis];
      u[i] = l[i] / n[i];
      v[j] = l[j] / n[j];
      for (int a = 0; a < n[i]; ++a)
        for (int b = 0; b < n[j]; ++b) {
          P3 p00 = bump(lerp3(o, u, v, a, b)), p10 = bump(lerp3(o, u, v, a + 1, b));
          P3 p11 = bump(lerp3(o, u, v, a + 1, b + 1)), p01 = bump(lerp3(o, u, v, a, b + 1));
          // (u, v, axis) is right-handed: counterclockwise seen from +axis.
          if (side == 1)
            s.quad(p00, p10, p11, p01, 2 * axis + side);
          else
            s.quad(p00, p01, p11, p10, 2 * axis + side);
        }
    }
  return s;
}

Surf box(P3 l, std::array<int, 3> n) {
  return box(l, n, [](const P3& p) { return p; });
}

// Closed cylinder along z: radius r, length len, nt around, nz along, caps
// fanned from their centers (tags: 0 wall, 1 bottom, 2 top).
Surf tube(double r, double len, int nt, int nz, double cap_bump = 0) {
  Surf s;
  auto ring = [&](int k, int i) {
    const double a = 2 * M_PI * (k % nt) / nt;
    return P3{r * std::cos(a), r * std::sin(a), len * i / nz};
  };
  for (int i = 0; i < nz; ++i)
    for (int k = 0; k < nt; ++k)
      s.quad(ring(k, i), ring(k + 1, i), ring(k + 1, i + 1), ring(k, i + 1), 0);
  // Caps: a ring at half radius, slightly out of plane by cap_bump.
  for (int side = 0; side < 2; ++side) {
    const double z = side * len;
    const P3 c{0, 0, z + (side ? cap_bump : -cap_bump)};
    auto inner = [&](int k) {
      const double a = 2 * M_PI * (k % nt) / nt;
      const double bump = (k % 2 ? 1 : -1) * cap_bump;
      return P3{0.5 * r * std::cos(a), 0.5 * r * std::sin(a), z + bump};
    };
    for (int k = 0; k < nt; ++k) {
      P3 o0 = ring(k, side * nz), o1 = ring(k + 1, side * nz);
      if (side == 1) {
        s.quad(o0, o1, inner(k + 1), inner(k), 2);
        s.tri(c, inner(k), inner(k + 1), 2);
      } else {
        s.quad(o1, o0, inner(k), inner(k + 1), 1);
        s.tri(c, inner(k + 1), inner(k), 1);
      }
    }
  }
  return s;
}

Surf torus(double R, double r, int nu, int nv) {
  Surf s;
  auto at = [&](int i, int j) {
    const double u = 2 * M_PI * (i % nu) / nu, v = 2 * M_PI * (j % nv) / nv;
    return P3{(R + r * std::cos(v)) * std::cos(u), (R + r * std::cos(v)) * std::sin(u),
              r * std::sin(v)};
  };
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) s.quad(at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1), 0);
  return s;
}

// Icosphere: icosahedron subdivided `levels` times, projected on the unit
// sphere (vertices rounded, so not exactly cospherical).
Surf icosphere(int levels) {
  const double t = (1 + std::sqrt(5.0)) / 2;
  std::vector<P3> v = {{-1, t, 0},  {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t},  {0, 1, t},
                       {0, -1, -t}, {0, 1, -t}, {t, 0, -1},  {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
  std::vector<std::array<int, 3>> f = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                       {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                       {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                       {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  auto unit = [](P3 p) {
    double l = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    return P3{p[0] / l, p[1] / l, p[2] / l};
  };
  std::vector<std::array<P3, 3>> tris;
  for (auto& q : f) tris.push_back({unit(v[q[0]]), unit(v[q[1]]), unit(v[q[2]])});
  for (int l = 0; l < levels; ++l) {
    std::vector<std::array<P3, 3>> next;
    for (auto& q : tris) {
      auto mid = [](const P3& a, const P3& b) {
        return P3{(a[0] + b[0]) / 2, (a[1] + b[1]) / 2, (a[2] + b[2]) / 2};
      };
      P3 ab = unit(mid(q[0], q[1])), bc = unit(mid(q[1], q[2])), ca = unit(mid(q[2], q[0]));
      next.push_back({q[0], ab, ca});
      next.push_back({ab, q[1], bc});
      next.push_back({ca, bc, q[2]});
      next.push_back({ab, bc, ca});
    }
    tris.swap(next);
  }
  Surf s;
  for (auto& q : tris) s.tri(q[0], q[1], q[2], 0);
  return s;
}

double enclosed_volume(const std::vector<double>& p, const std::vector<int32_t>& tris) {
  double v6 = 0;
  for (size_t t = 0; t < tris.size(); t += 3) {
    const double* a = &p[3 * size_t(tris[t])];
    const double* b = &p[3 * size_t(tris[t + 1])];
    const double* c = &p[3 * size_t(tris[t + 2])];
    v6 += a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
          a[2] * (b[0] * c[1] - b[1] * c[0]);
  }
  return v6 / 6;
}

double area(const double* a, const double* b, const double* c) {
  double u[3], v[3];
  for (int k = 0; k < 3; ++k) u[k] = b[k] - a[k], v[k] = c[k] - a[k];
  double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
  return 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
}

// Rotates a triangle so its smallest index comes first (orientation kept).
std::array<int32_t, 3> canonical(std::array<int32_t, 3> t) {
  while (t[0] > t[1] || t[0] > t[2]) std::rotate(t.begin(), t.begin() + 1, t.end());
  return t;
}

RecoveredVolume recover_and_check(const Surf& s, const RecoveryOptions& options = {}) {
  auto r = recover_boundary(s.points, s.tris, s.tags, options);
  EXPECT_TRUE(r.ok()) << r.message();
  if (!r.ok()) return {};
  RecoveredVolume out = std::move(r.value());
  const VolumeMesh& m = out.mesh;
  // Input points first, unchanged.
  EXPECT_GE(m.points.size(), s.points.size());
  for (size_t i = 0; i < s.points.size(); ++i) EXPECT_EQ(m.points[i], s.points[i]);
  EXPECT_EQ(int64_t(m.num_vertices() - s.points.size() / 3), out.steiner_points);
  // Positive tetrahedra; boundary of the tetrahedra = output triangles,
  // with the same (outward) orientation.
  std::map<std::array<int32_t, 3>, int> faces;  // outward oriented, canonical
  double volume = 0;
  for (size_t t = 0; t < m.num_tets(); ++t) {
    const int32_t* v = &m.tets[4 * t];
    const double* q[4];
    for (int k = 0; k < 4; ++k) q[k] = &m.points[3 * size_t(v[k])];
    EXPECT_LT(orient3d(q[0], q[1], q[2], q[3]), 0) << "tet " << t << " not positive";
    volume += tet_volume6(q[0], q[1], q[2], q[3]) / 6;
    for (auto& f : kFaceOut) {
      auto key = canonical({v[f[0]], v[f[1]], v[f[2]]});
      auto rev = canonical({key[0], key[2], key[1]});
      auto it = faces.find(rev);
      if (it != faces.end()) {
        faces.erase(it);  // inner face, seen from both sides
      } else {
        faces[key]++;
      }
    }
  }
  std::set<std::array<int32_t, 3>> boundary;
  for (auto& [f, count] : faces) {
    EXPECT_EQ(count, 1);
    boundary.insert(f);
  }
  std::set<std::array<int32_t, 3>> output;
  for (size_t t = 0; t < m.num_triangles(); ++t)
    output.insert(canonical({m.triangles[3 * t], m.triangles[3 * t + 1], m.triangles[3 * t + 2]}));
  EXPECT_EQ(output.size(), m.num_triangles()) << "repeated output triangle";
  EXPECT_TRUE(boundary == output) << "the tetrahedra's boundary (" << boundary.size()
                                  << " faces) is not the output surface (" << output.size() << ")";
  // Each input triangle (as surface flips left it) is covered by its
  // pieces: same tag, same area, in its plane. Flips changed whole pairs
  // only.
  const size_t nt = s.tris.size() / 3;
  const std::vector<int32_t>& in = out.input_triangles;
  EXPECT_EQ(in.size(), s.tris.size());
  if (in.size() != s.tris.size()) return out;
  size_t changed = 0;
  for (size_t p = 0; p < nt; ++p)
    changed += !std::equal(&in[3 * p], &in[3 * p] + 3, &s.tris[3 * p]);
  EXPECT_EQ(changed, 2 * size_t(out.surface_flips));
  EXPECT_EQ(out.flipped_edges.size(), 2 * size_t(out.surface_flips));
  std::vector<double> piece_area(nt, 0);
  EXPECT_EQ(out.triangle_parent.size(), m.num_triangles());
  if (out.triangle_parent.size() != m.num_triangles()) return out;
  for (size_t t = 0; t < m.num_triangles(); ++t) {
    const int32_t p = out.triangle_parent[t];
    EXPECT_EQ(m.triangle_tag[t], s.tags[size_t(p)]);
    const double* q[3];
    for (int k = 0; k < 3; ++k) q[k] = &m.points[3 * size_t(m.triangles[3 * t + k])];
    piece_area[size_t(p)] += area(q[0], q[1], q[2]);
    const double* a = &s.points[3 * size_t(in[3 * size_t(p)])];
    const double* b = &s.points[3 * size_t(in[3 * size_t(p) + 1])];
    const double* c = &s.points[3 * size_t(in[3 * size_t(p) + 2])];
    for (int k = 0; k < 3; ++k) {
      double h = std::fabs(tet_volume6(a, b, c, q[k])) / (2 * area(a, b, c));
      EXPECT_LT(h, 1e-12 * (1 + std::sqrt(area(a, b, c)))) << "piece off its input triangle";
    }
  }
  for (size_t p = 0; p < nt; ++p) {
    const double* a = &s.points[3 * size_t(in[3 * p])];
    const double* b = &s.points[3 * size_t(in[3 * p + 1])];
    const double* c = &s.points[3 * size_t(in[3 * p + 2])];
    EXPECT_NEAR(piece_area[p], area(a, b, c), 1e-9 * area(a, b, c)) << "input triangle " << p;
  }
  // Volume: the tetrahedra fill the enclosed volume.
  const double enclosed = enclosed_volume(s.points, in);
  EXPECT_NEAR(volume, enclosed, 1e-9 * enclosed);
  // The kernel is valid, its constrained faces are the output triangles.
  EXPECT_TRUE(out.kernel.check(false).ok()) << out.kernel.check(false).message();
  size_t constrained = 0;
  for (int32_t t = 0; t < int32_t(out.kernel.tet_capacity()); ++t)
    if (out.kernel.is_live(t))
      for (int k = 0; k < 4; ++k) constrained += out.kernel.is_constrained(t, k);
  EXPECT_EQ(constrained, 2 * m.num_triangles());
  return out;
}

TEST(BoundaryRecovery, CubeWithCosphericalVertices) {
  // The 8 vertices are cospherical: the perturbation picks the diagonals of
  // the hull squares. Where they differ from the surface's, a 4-4 flip of
  // the hull faces recovers them when the edge has 4 tetrahedra; with 5
  // tetrahedra every fan of the ring is flat (the cube's diagonal planes),
  // and a Steiner point is inserted instead.
  auto out = recover_and_check(box({1, 1, 1}, {1, 1, 1}));
  EXPECT_LE(out.steiner_points, 4);
  EXPECT_GE(out.mesh.num_tets(), 5u);
}

// Triangular prism with the top rotated by `twist` (radians), side quads
// split by one of their two diagonals; with the "wrong" diagonal and a
// twist it is Schoenhardt's polyhedron, which has no tetrahedralization
// without Steiner points.
Surf twisted_prism(double twist, bool other_diagonal) {
  Surf s;
  auto a = [](int i) {
    double t = 2 * M_PI * (i % 3) / 3;
    return P3{std::cos(t), std::sin(t), 0};
  };
  auto b = [&](int i) {
    double t = 2 * M_PI * (i % 3) / 3 + twist;
    return P3{std::cos(t), std::sin(t), 1};
  };
  s.tri(a(0), a(2), a(1), 0);
  s.tri(b(0), b(1), b(2), 1);
  for (int i = 0; i < 3; ++i) {
    if (other_diagonal) {
      s.tri(a(i), a(i + 1), b(i), 2);
      s.tri(a(i + 1), b(i + 1), b(i), 2);
    } else {
      s.tri(a(i), a(i + 1), b(i + 1), 2);
      s.tri(a(i), b(i + 1), b(i), 2);
    }
  }
  return s;
}

TEST(BoundaryRecovery, SchoenhardtPolyhedronNeedsSteinerPoints) {
  // For any twist in (0, 60 degrees) one diagonal choice gives the convex
  // hull of the 6 points (recovered as is), the other a non-convex,
  // untetrahedralizable polyhedron (at least one Steiner point).
  for (double twist : {0.05, M_PI / 6, 0.9}) {
    int64_t steiner[2];
    for (bool other : {false, true})
      steiner[other] = recover_and_check(twisted_prism(twist, other)).steiner_points;
    EXPECT_EQ(std::min(steiner[0], steiner[1]), 0) << twist;
    EXPECT_GE(std::max(steiner[0], steiner[1]), 1) << twist;
  }
}

TEST(BoundaryRecovery, GridBoxCospherical) {
  // Every 5 surface vertices of a square are cospherical: the Delaunay
  // tetrahedralization is decided by the perturbation and may miss
  // diagonals of the faces; recovery must still conform.
  auto out = recover_and_check(box({2, 1, 1}, {4, 2, 2}));
  EXPECT_GT(out.mesh.num_tets(), 0u);
}

TEST(BoundaryRecovery, LongThinTube) {
  // Radius 0.05, length 10, 8 segments around and 6 along: wall triangles
  // of aspect ratio ~40, the Delaunay tetrahedralization of the vertices
  // misses most of them.
  auto s = tube(0.05, 10, 8, 6);
  auto out = recover_and_check(s);
  std::printf("thin tube: %zu triangles in, %zu out, %lld Steiner points, %lld flips%s\n",
              s.tags.size(), out.mesh.num_triangles(), (long long)out.steiner_points,
              (long long)out.flips,
              out.used_fallback ? (" (fallback: " + out.fallback_reason + ")").c_str() : "");
}

TEST(BoundaryRecovery, WallEdgesFlippedInsteadOfSplitWhereAllowed) {
  // The thin tube's wall misses most of its edges (see LongThinTube). With
  // surface flips allowed on the wall (tag 0), whole wall pairs are flipped
  // rather than split; the caps (other tags) never are.
  const Surf s = tube(0.05, 10, 8, 6);
  const RecoveredVolume plain = recover_and_check(s);
  RecoveryOptions o;
  std::vector<std::array<int32_t, 5>> asked;
  o.may_flip_surface = [&](int32_t a, int32_t b, int32_t c, int32_t d, int32_t tag) {
    asked.push_back({a, b, c, d, tag});
    return tag == 0;
  };
  const RecoveredVolume flipped = recover_and_check(s, o);
  EXPECT_FALSE(asked.empty());
  EXPECT_GT(flipped.surface_flips, 0);
  EXPECT_LT(flipped.steiner_points, plain.steiner_points);
  EXPECT_EQ(plain.surface_flips, 0);
  // Asked about each edge with the apexes of its two triangles, (a, b, c)
  // and (b, a, d) being input triangles; the flipped edges are (c, d).
  std::set<std::pair<int32_t, int32_t>> made;
  for (size_t e = 0; e < flipped.flipped_edges.size(); e += 2)
    made.insert(std::minmax(flipped.flipped_edges[e], flipped.flipped_edges[e + 1]));
  size_t allowed = 0;
  for (const auto& [a, b, c, d, tag] : asked) {
    EXPECT_NE(c, d);
    if (tag == 0) allowed += made.count(std::minmax(c, d));
  }
  EXPECT_EQ(allowed, size_t(flipped.surface_flips));
  // The flipped input has no cap triangle changed.
  for (size_t t = 0; t < s.tags.size(); ++t) {
    if (s.tags[t] != 0) {
      EXPECT_TRUE(std::equal(&s.tris[3 * t], &s.tris[3 * t] + 3, &flipped.input_triangles[3 * t]));
    }
  }
}

TEST(BoundaryRecovery, BoxWithNearlyCoplanarCaps) {
  // The top and bottom faces are bumped by +-1e-9 at interior grid points:
  // nearly coplanar triangles, coplanar with their neighbors up to 1e-9.
  auto s = box({1, 1, 0.2}, {5, 5, 1}, [](const P3& p) {
    P3 q = p;
    bool interior = p[0] > 0 && p[0] < 1 && p[1] > 0 && p[1] < 1;
    if (interior && (p[2] == 0 || p[2] == 0.2)) {
      int h = int(std::lround(p[0] * 5) * 7 + std::lround(p[1] * 5) * 3);
      q[2] += (h % 3 - 1) * 1e-9;
    }
    return q;
  });
  recover_and_check(s);
  // A tube whose caps are out of plane by 1e-10.
  recover_and_check(tube(1, 3, 12, 3, 1e-10));
}

TEST(BoundaryRecovery, SkinnyTriangles) {
  // Long faces split into 10 x 0.05 triangles (aspect 200).
  auto out = recover_and_check(box({10, 1, 1}, {1, 20, 20}));
  std::printf("skinny box: %zu triangles out, %lld Steiner points, %lld flips%s\n",
              out.mesh.num_triangles(), (long long)out.steiner_points, (long long)out.flips,
              out.used_fallback ? (" (fallback: " + out.fallback_reason + ")").c_str() : "");
}

TEST(BoundaryRecovery, CoarseSphere) {
  recover_and_check(icosphere(0));
  auto out = recover_and_check(icosphere(2));
  EXPECT_EQ(out.mesh.num_triangles() >= 320, true);
}

TEST(BoundaryRecovery, Torus) {
  auto s = torus(1, 0.3, 24, 8);
  auto out = recover_and_check(s);
  std::printf("torus: %zu triangles out, %lld Steiner points, %lld flips%s\n",
              out.mesh.num_triangles(), (long long)out.steiner_points, (long long)out.flips,
              out.used_fallback ? (" (fallback: " + out.fallback_reason + ")").c_str() : "");
  // A coarse, thin torus is harder.
  recover_and_check(torus(1, 0.1, 16, 5));
}

TEST(BoundaryRecovery, SteinerOnlyModeAlsoRecovers) {
  RecoveryOptions o;
  o.use_flips = false;
  auto out = recover_and_check(tube(0.05, 10, 8, 6), o);
  EXPECT_EQ(out.flips, 0);
}

TEST(BoundaryRecovery, ClosedPhantomSurfaces) {
  // Marching-cubes surfaces (staircase, needle triangles with angles down to
  // 0.01 degree), clean and noisy.
  for (PhantomKind kind : {PhantomKind::kTorus, PhantomKind::kBifurcation}) {
    for (double noise : {0.0, 0.3}) {
      PhantomOptions o;
      o.kind = kind;
      o.open_ends = false;
      o.voxel = 0.25;
      o.noise = noise;
      auto ph = make_vessel_phantom(o);
      ASSERT_TRUE(ph.ok()) << ph.message();
      Surf s;
      s.points = ph.value().points;
      s.tris = ph.value().triangles;
      s.tags.assign(s.tris.size() / 3, 0);
      auto out = recover_and_check(s);
      std::printf("phantom %d noise %.1f: %zu triangles in, %lld Steiner points, %lld flips%s\n",
                  int(kind), noise, s.tags.size(), (long long)out.steiner_points,
                  (long long)out.flips, out.used_fallback ? " (fallback)" : "");
      EXPECT_FALSE(out.used_fallback);
    }
  }
}

TEST(BoundaryRecovery, KernelAcceptsMorePointsInside) {
  auto out = recover_and_check(tube(1, 4, 12, 4));
  Delaunay3D& d = out.kernel;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-0.6, 0.6), z(0.2, 3.8);
  int inserted = 0;
  for (int i = 0; i < 200; ++i) {
    const double p[3] = {u(rng), u(rng), z(rng)};
    auto r = d.insert(p, -1, true);
    inserted += r.status == Delaunay3D::InsertStatus::kInserted;
  }
  EXPECT_GT(inserted, 150);
  ASSERT_TRUE(d.check(false).ok()) << d.check(false).message();
  // Still one inside region bounded by the constrained faces: the new
  // tetrahedra took the inside tag.
  double inside = 0;
  d.for_each_finite_tet([&](int32_t t) {
    if (d.tag(t) != kInsideTag) return;
    const int32_t* v = d.tet(t);
    inside += tet_volume6(d.point(v[0]), d.point(v[1]), d.point(v[2]), d.point(v[3])) / 6;
  });
  Surf s = tube(1, 4, 12, 4);
  EXPECT_NEAR(inside, enclosed_volume(s.points, s.tris), 1e-9);
}

TEST(BoundaryRecovery, SmallTubeFarFromTheOrigin) {
  // A closed tube of radius 0.01 moved 1e5 away (as an ASCII STL in
  // survey coordinates gives it): its orientation is still told from its
  // volume, outward recovered, inward refused.
  Surf s = tube(0.01, 0.1, 16, 4);
  for (double& x : s.points) x += 1e5;
  auto r = recover_boundary(s.points, s.tris, s.tags);
  ASSERT_TRUE(r.ok()) << r.message();
  EXPECT_GE(r.value().mesh.num_triangles(), s.tags.size());  // split where needed
  EXPECT_GT(r.value().mesh.num_tets(), 0u);
  for (size_t t = 0; t < s.tris.size(); t += 3) std::swap(s.tris[t + 1], s.tris[t + 2]);
  r = recover_boundary(s.points, s.tris, s.tags);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.message().find("inward"), std::string::npos) << r.message();
}

TEST(BoundaryRecovery, BadSurfacesAreClearErrors) {
  Surf cube = box({1, 1, 1}, {1, 1, 1});
  // Open: drop a triangle.
  auto open = cube;
  open.tris.resize(open.tris.size() - 3);
  open.tags.pop_back();
  auto r = recover_boundary(open.points, open.tris, open.tags);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.message().find("not closed"), std::string::npos) << r.message();
  // Inward.
  auto in = cube;
  for (size_t t = 0; t < in.tris.size(); t += 3) std::swap(in.tris[t + 1], in.tris[t + 2]);
  r = recover_boundary(in.points, in.tris, in.tags);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.message().find("inward"), std::string::npos) << r.message();
  // Inconsistent orientation of one triangle.
  auto flip = cube;
  std::swap(flip.tris[1], flip.tris[2]);
  r = recover_boundary(flip.points, flip.tris, flip.tags);
  ASSERT_FALSE(r.ok());
  // Index out of range, wrong tag count, degenerate triangle.
  auto bad = cube;
  bad.tris[0] = 99;
  EXPECT_FALSE(recover_boundary(bad.points, bad.tris, bad.tags).ok());
  EXPECT_FALSE(recover_boundary(cube.points, cube.tris, {}).ok());
  auto rep = cube;
  rep.tris[1] = rep.tris[0];
  EXPECT_FALSE(recover_boundary(rep.points, rep.tris, rep.tags).ok());
  // Two vertices at the same position.
  auto dup = cube;
  dup.points.insert(dup.points.end(), {dup.points[0], dup.points[1], dup.points[2]});
  for (size_t i = 0; i < dup.tris.size(); ++i)
    if (dup.tris[i] == 0) {
      dup.tris[i] = int32_t(dup.points.size() / 3 - 1);
      break;
    }
  EXPECT_FALSE(recover_boundary(dup.points, dup.tris, dup.tags).ok());
}

}  // namespace
}  // namespace vm
