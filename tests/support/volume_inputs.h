// Generated inputs of the volume stage (the contract of boundary recovery:
// a Delaunay kernel whose region is tagged 1 and closed by constrained
// faces, and a size per vertex), for tests and benchmarks: convex surfaces
// (cube, sphere, capped cylinder) whose hull faces are the surface, and a
// torus whose fine surface triangles happen to be Delaunay faces.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>
#include <vector>

#include "core/mesh/surface_mesh.h"
#include "core/mesh/volume_mesh.h"
#include "core/volume/delaunay3d.h"
#include "core/volume/tet_mesh.h"
#include "core/volume/tet_topology.h"
#include "tests/support/icosphere.h"

namespace vm::testing {

struct VolumeInput {
  Delaunay3D kernel;
  /// The constrained faces (outward oriented) over the kernel's vertices.
  SurfaceMesh surface;
  /// Per kernel vertex: mean length of its surface edges (0 if none).
  std::vector<double> sizes;
};

namespace detail {

inline void fill_surface_and_sizes(VolumeInput& in) {
  const Delaunay3D& d = in.kernel;
  in.surface.points = d.points();
  in.surface.triangles.clear();
  d.for_each_finite_tet([&](int32_t t) {
    if (d.tag(t) != 1) return;
    for (int k = 0; k < 4; ++k) {
      if (!d.is_constrained(t, k)) continue;
      const int32_t u = d.neighbor(t, k) >> 2;
      if (!d.is_ghost(u) && d.tag(u) == 1) continue;
      for (int s : kFaceOut[k]) in.surface.triangles.push_back(d.tet(t)[s]);
    }
  });
  std::vector<double> sum(d.num_vertices(), 0.0), cnt(d.num_vertices(), 0.0);
  const auto& tr = in.surface.triangles;
  for (size_t i = 0; i < tr.size(); i += 3)
    for (int k = 0; k < 3; ++k) {
      const int32_t a = tr[i + size_t(k)], b = tr[i + size_t((k + 1) % 3)];
      const double* p = d.point(a);
      const double* q = d.point(b);
      const double l = std::sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
                                 (p[2] - q[2]) * (p[2] - q[2]));
      sum[size_t(a)] += l, cnt[size_t(a)] += 1;
      sum[size_t(b)] += l, cnt[size_t(b)] += 1;
    }
  in.sizes.assign(d.num_vertices(), 0.0);
  for (size_t v = 0; v < sum.size(); ++v)
    if (cnt[v] > 0) in.sizes[v] = sum[v] / cnt[v];
}

}  // namespace detail

/// The Delaunay tetrahedralization of points in convex position (and their
/// hull): every finite tetrahedron tagged 1, every hull face constrained.
/// Returns false when the kernel refuses the points.
inline bool convex_input(std::vector<double> points, VolumeInput* out) {
  auto r = Delaunay3D::build(std::move(points));
  if (!r.ok()) return false;
  out->kernel = std::move(r.value());
  Delaunay3D& d = out->kernel;
  for (int32_t t = 0; t < int32_t(d.tet_capacity()); ++t) {
    if (!d.is_live(t) || d.is_ghost(t)) continue;
    d.set_tag(t, 1);
    for (int k = 0; k < 4; ++k)
      if (d.is_ghost(d.neighbor(t, k) >> 2)) d.set_constrained(t, k, true);
  }
  detail::fill_surface_and_sizes(*out);
  return true;
}

/// Points of the surface of the cube [0, side]^3 on a grid of n intervals
/// per edge (spacing side / n), each point once.
inline std::vector<double> cube_surface_points(int n, double side = 1.0) {
  std::vector<double> p;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j)
      for (int k = 0; k <= n; ++k)
        if (i == 0 || i == n || j == 0 || j == n || k == 0 || k == n)
          p.insert(p.end(), {side * i / n, side * j / n, side * k / n});
  return p;
}

namespace detail {

// Deterministic relative jitter in [-amount, amount] of each radius (about
// the origin, or the torus's core circle when R > 0): exactly cospherical
// or cocircular inputs send every predicate of the kernel to exact
// arithmetic, which is slow (and slower under sanitizers); a 1e-7 jitter
// keeps the geometry and lets the floating-point filters decide.
inline void jitter(std::vector<double>& p, double amount, double R = 0) {
  uint64_t s = 0x9e3779b97f4a7c15ull;
  for (size_t i = 0; i < p.size(); i += 3) {
    s = s * 6364136223846793005ull + 1442695040888963407ull;
    const double f = 1 + amount * (double(s >> 11) * 0x1p-53 * 2 - 1);
    double c[3] = {0, 0, 0};
    if (R > 0) {
      const double l = std::sqrt(p[i] * p[i] + p[i + 1] * p[i + 1]);
      c[0] = R * p[i] / l, c[1] = R * p[i + 1] / l;
    }
    for (int k = 0; k < 3; ++k) p[i + size_t(k)] = c[k] + f * (p[i + size_t(k)] - c[k]);
  }
}

}  // namespace detail

/// n points uniformly random in the cube [-1, 1]^3 (x, y, z a point),
/// the same for the same seed.
inline std::vector<double> random_cube_points(int n, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<double> p(3 * size_t(n));
  for (double& x : p) x = u(rng);
  return p;
}

/// Vertices of the icosphere of `levels` subdivisions (radius r, radii
/// jittered by 1e-7 relative).
inline std::vector<double> sphere_points(int levels, double r = 1.0) {
  std::vector<double> p = icosphere(levels, r).points;
  detail::jitter(p, 1e-7);
  return p;
}

/// Points of a closed cylinder (radius R, axis z from 0 to len) at spacing
/// about h: aligned rings on the side (square quads, so the hull splits
/// them into right triangles; staggered rings would give 30-30-120
/// triangles, the hull preferring the straight vertical diagonals),
/// concentric staggered rings on the two disks.
inline std::vector<double> capped_cylinder_points(double R, double len, double h) {
  std::vector<double> p;
  const double pi = std::numbers::pi;
  const int n = std::max(6, int(std::lround(2 * pi * R / h)));
  const int m = std::max(1, int(std::lround(len * n / (2 * pi * R))));
  for (int j = 0; j <= m; ++j)
    for (int i = 0; i < n; ++i) {
      const double a = 2 * pi * i / n;
      p.insert(p.end(), {R * std::cos(a), R * std::sin(a), len * j / m});
    }
  // Disks: rings of radius R - k dr, dr about h sqrt(3) / 2, without the rim.
  const int rings = std::max(1, int(std::lround(R / (h * std::sqrt(3.0) / 2))));
  for (double z : {0.0, len})
    for (int k = 1; k < rings; ++k) {
      const double r = R * (rings - k) / rings;
      const int nk = std::max(3, int(std::lround(2 * pi * r / h)));
      for (int i = 0; i < nk; ++i) {
        const double a = 2 * pi * (i + 0.5 * (k % 2)) / nk;
        p.insert(p.end(), {r * std::cos(a), r * std::sin(a), z});
      }
    }
  for (double z : {0.0, len}) p.insert(p.end(), {0.0, 0.0, z});
  return p;
}

/// Torus (major radius R, minor r) sampled on a staggered nu x nv grid
/// (minor radii jittered by 1e-7 relative);
/// the region inside it when every surface triangle is a face of the
/// Delaunay tetrahedralization of the points (then constrained); false if
/// one is missing (not recoverable without flips).
inline bool torus_input(int nu, int nv, double R, double r, VolumeInput* out) {
  const double pi = std::numbers::pi;
  std::vector<double> pts;
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      const double u = 2 * pi * (i + 0.5 * (j % 2)) / nu, v = 2 * pi * j / nv;
      pts.insert(pts.end(), {(R + r * std::cos(v)) * std::cos(u),
                             (R + r * std::cos(v)) * std::sin(u), r * std::sin(v)});
    }
  detail::jitter(pts, 1e-7, R);
  std::vector<int32_t> tris;
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      const int jn = (j + 1) % nv;
      const int32_t a = j * nu + i, b = j * nu + (i + 1) % nu;
      // Row j is shifted by half a step when odd; nv even keeps it periodic.
      const int32_t c = jn * nu + (i + (j % 2)) % nu, d = jn * nu + (i + (j % 2) + nu - 1) % nu;
      tris.insert(tris.end(), {a, b, c, a, c, d});
    }
  auto res = Delaunay3D::build(pts);
  if (!res.ok()) return false;
  out->kernel = std::move(res.value());
  Delaunay3D& dk = out->kernel;
  for (size_t i = 0; i < tris.size(); i += 3) {
    int k = -1;
    const int32_t t = dk.find_face(tris[i], tris[i + 1], tris[i + 2], &k);
    if (t < 0) return false;
    dk.set_constrained(t, k, true);
  }
  // Outside: flood fill from the ghosts across unconstrained faces.
  std::vector<int32_t> stack;
  std::vector<uint8_t> outside(dk.tet_capacity(), 0);
  for (int32_t t = 0; t < int32_t(dk.tet_capacity()); ++t)
    if (dk.is_live(t) && dk.is_ghost(t)) outside[size_t(t)] = 1, stack.push_back(t);
  while (!stack.empty()) {
    const int32_t t = stack.back();
    stack.pop_back();
    for (int k = 0; k < 4; ++k) {
      if (dk.is_constrained(t, k)) continue;
      const int32_t u = dk.neighbor(t, k) >> 2;
      if (!outside[size_t(u)]) outside[size_t(u)] = 1, stack.push_back(u);
    }
  }
  dk.for_each_finite_tet([&](int32_t t) { dk.set_tag(t, outside[size_t(t)] ? 0 : 1); });
  detail::fill_surface_and_sizes(*out);
  return out->surface.num_triangles() == tris.size() / 3;
}

/// The octahedron of vertices (0, 0, -1), (0, 0, 1) and the unit square
/// around the z axis, as the 4 positive tetrahedra around its edge (0, 1),
/// every vertex flagged `fixed` (a test failure on error).
inline TetMesh octahedron_tets(uint8_t fixed) {
  std::vector<double> p = {0, 0, -1, 0, 0, 1, 1, 0, 0, 0, 1, 0, -1, 0, 0, 0, -1, 0};
  std::vector<int32_t> t;
  for (int i = 0; i < 4; ++i) {
    std::array<int32_t, 4> q = {0, 1, 2 + i, 2 + (i + 1) % 4};
    if (tet_volume6(&p[3 * q[0]], &p[3 * q[1]], &p[3 * q[2]], &p[3 * q[3]]) < 0)
      std::swap(q[2], q[3]);
    t.insert(t.end(), q.begin(), q.end());
  }
  auto r = TetMesh::from_arrays(p, t, std::vector<uint8_t>(6, fixed));
  EXPECT_TRUE(r.ok()) << r.message();
  return std::move(r.value());
}

}  // namespace vm::testing
