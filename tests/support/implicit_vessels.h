// Closed vessel-like surfaces from signed distance functions (capsules
// joined by a smooth minimum, bulbs, truncations), extracted by marching
// cubes: shapes the phantom generator does not make (a sidewall aneurysm, a
// U-bend, obliquely truncated ends).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <vector>

#include "core/mesh/surface_mesh.h"
#include "core/mesh/marching_cubes.h"

namespace vm::testing {

using Point = std::array<double, 3>;
using Sdf = std::function<double(const Point&)>;

/// The zero set of `sdf` (negative inside) in the box [lo, hi], sampled
/// every `voxel`.
inline SurfaceMesh implicit_surface(const Sdf& sdf, const Point& lo, const Point& hi,
                                    double voxel) {
  GridSpec g;
  g.spacing = voxel;
  int n[3];
  for (int k = 0; k < 3; ++k) {
    g.origin[k] = lo[size_t(k)] - 2 * voxel;
    n[k] = int(std::ceil((hi[size_t(k)] - lo[size_t(k)]) / voxel)) + 5;
  }
  g.nx = n[0], g.ny = n[1], g.nz = n[2];
  return marching_cubes(g, [&](int k, float* plane) {
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i)
        plane[size_t(i) + size_t(g.nx) * size_t(j)] =
            float(sdf({g.origin[0] + voxel * i, g.origin[1] + voxel * j, g.origin[2] + voxel * k}));
  });
}

/// Distance from p to the segment ab minus r: a capsule.
inline double capsule_sdf(const Point& p, const Point& a, const Point& b, double r) {
  double ab[3], ap[3], t = 0, len2 = 0;
  for (int k = 0; k < 3; ++k) {
    ab[k] = b[size_t(k)] - a[size_t(k)];
    ap[k] = p[size_t(k)] - a[size_t(k)];
    t += ab[k] * ap[k];
    len2 += ab[k] * ab[k];
  }
  t = len2 > 0 ? std::clamp(t / len2, 0.0, 1.0) : 0;
  double d2 = 0;
  for (int k = 0; k < 3; ++k) d2 += (ap[k] - t * ab[k]) * (ap[k] - t * ab[k]);
  return std::sqrt(d2) - r;
}

inline double sphere_sdf(const Point& p, const Point& c, double r) {
  return std::hypot(p[0] - c[0], p[1] - c[1], p[2] - c[2]) - r;
}

/// Polynomial smooth minimum (blend width k).
inline double smooth_min(double a, double b, double k) {
  const double h = std::max(k - std::abs(a - b), 0.0) / k;
  return std::min(a, b) - h * h * k * 0.25;
}

/// A straight vessel along z (radius 1, from z = -6 to 6, rounded ends)
/// with a saccular aneurysm on its side: a bulb of radius 1.5 centred 2.3
/// from the axis, joined by a narrow neck. Its dome, at (3.8, 0, 0), is a
/// prominent extremity but no vessel end.
inline SurfaceMesh sidewall_aneurysm(double voxel) {
  return implicit_surface(
      [](const Point& p) {
        return smooth_min(capsule_sdf(p, {0, 0, -6}, {0, 0, 6}, 1.0),
                          sphere_sdf(p, {2.3, 0, 0}, 1.5), 0.3);
      },
      {-1.2, -1.6, -7.2}, {4.0, 1.6, 7.2}, voxel);
}

/// A U-bend: two straight legs (radius 1, 5 long) joined by a half ring of
/// centerline radius 3; the ends at (+-3, 0, 6) point up (+z).
inline SurfaceMesh u_bend(double voxel) {
  return implicit_surface(
      [](const Point& p) {
        double d = std::min(capsule_sdf(p, {3, 0, 0}, {3, 0, 5}, 1.0),
                            capsule_sdf(p, {-3, 0, 0}, {-3, 0, 5}, 1.0));
        // The half ring below z = 0: distance to the circle of radius 3 in
        // the xz plane.
        if (p[2] <= 0) {
          const double rho = std::hypot(p[0], p[2]);
          d = std::min(d, std::hypot(rho - 3, p[1]) - 1.0);
        }
        return d;
      },
      {-4.2, -1.2, -4.2}, {4.2, 1.2, 6.2}, voxel);
}

/// A vessel along z (radius 1, z from -6 to 6) whose top end is truncated
/// by a plane tilted by `tilt` radians (a flat oblique end, sharp rim) and
/// whose bottom end is rounded.
inline SurfaceMesh oblique_end_tube(double tilt, double voxel) {
  const double c = std::cos(tilt), s = std::sin(tilt);
  return implicit_surface(
      [=](const Point& p) {
        const double tube = capsule_sdf(p, {0, 0, -6}, {0, 0, 8}, 1.0);
        const double plane = s * p[0] + c * (p[2] - 5);  // > 0 beyond the cut
        return std::max(tube, plane);
      },
      {-1.2, -1.2, -7.2}, {1.2, 1.2, 6.5}, voxel);
}

/// A parent vessel (radius 1.2) branching into two (radius 0.8 and 0.5);
/// the thin branch is only `short_length` long.
inline SurfaceMesh short_branch(double short_length, double voxel) {
  return implicit_surface(
      [=](const Point& p) {
        double d = capsule_sdf(p, {0, 0, -8}, {0, 0, 0}, 1.2);
        d = smooth_min(d, capsule_sdf(p, {0, 0, 0}, {0, 0, 8}, 0.8), 0.3);
        d = smooth_min(d, capsule_sdf(p, {0, 0, -2}, {short_length, 0, -2}, 0.5), 0.3);
        return d;
      },
      {-1.4, -1.4, -9.4}, {short_length + 0.7, 1.4, 9}, voxel);
}

}  // namespace vm::testing
