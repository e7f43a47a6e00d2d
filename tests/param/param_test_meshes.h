// Generated patches and similarity fits shared by the parametrization tests.
#pragma once

#include <array>
#include <cmath>
#include <complex>
#include <numbers>
#include <random>
#include <vector>

#include "core/mesh/surface_mesh.h"

namespace vm::testing {

using cplx = std::complex<double>;
inline constexpr double kPi = std::numbers::pi;

/// Polar-grid disk (rings x sectors) with jittered interior vertices; `z`
/// maps planar (x, y) to 3D. Outward (ccw from +z) oriented.
template <class Embed>
inline SurfaceMesh disk(int rings, int sectors, double jitter, Embed embed,
                        std::vector<cplx>* planar = nullptr) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-jitter, jitter);
  std::vector<cplx> xy = {0.0};
  for (int r = 1; r <= rings; ++r)
    for (int s = 0; s < sectors * r; ++s) {
      double rad = double(r) / rings, ang = 2 * kPi * s / (sectors * r);
      if (r < rings) rad += u(rng) / rings, ang += u(rng) / (sectors * r);
      xy.push_back(std::polar(rad, ang));
    }
  SurfaceMesh m;
  for (cplx p : xy) {
    auto q = embed(p.real(), p.imag());
    m.points.insert(m.points.end(), q.begin(), q.end());
  }
  // Ring r has sectors*r vertices starting at 1 + sectors*r*(r-1)/2.
  auto first = [&](int r) { return r == 0 ? 0 : 1 + sectors * r * (r - 1) / 2; };
  for (int s = 0; s < sectors; ++s)
    m.triangles.insert(m.triangles.end(), {0, first(1) + s, first(1) + (s + 1) % sectors});
  for (int r = 1; r < rings; ++r) {
    int n0 = sectors * r, n1 = sectors * (r + 1);
    // Merge the two rings by angle.
    int i = 0, j = 0;
    while (i < n0 || j < n1) {
      double ai = 2 * kPi * (i + 0.5) / n0, aj = 2 * kPi * (j + 0.5) / n1;
      int32_t a = first(r) + i % n0, b = first(r + 1) + j % n1;
      if (j < n1 && (i >= n0 || aj <= ai)) {
        m.triangles.insert(m.triangles.end(), {a, b, first(r + 1) + (j + 1) % n1});
        ++j;
      } else {
        m.triangles.insert(m.triangles.end(), {a, b, first(r) + (i + 1) % n0});
        ++i;
      }
    }
  }
  if (planar) *planar = xy;
  return m;
}

/// Max distance between w and the best similarity a z + b of z, relative to
/// the size of w.
inline double similarity_residual(const std::vector<cplx>& z, const std::vector<cplx>& w) {
  size_t n = z.size();
  cplx zm = 0, wm = 0;
  for (size_t i = 0; i < n; ++i) zm += z[i], wm += w[i];
  zm /= double(n), wm /= double(n);
  cplx num = 0;
  double den = 0, size = 0;
  for (size_t i = 0; i < n; ++i) {
    num += std::conj(z[i] - zm) * (w[i] - wm);
    den += std::norm(z[i] - zm);
    size = std::max(size, std::abs(w[i] - wm));
  }
  cplx a = num / den;
  double worst = 0;
  for (size_t i = 0; i < n; ++i) worst = std::max(worst, std::abs(a * (z[i] - zm) + wm - w[i]));
  return worst / size;
}

inline std::vector<cplx> as_complex(const std::vector<double>& uv) {
  std::vector<cplx> out(uv.size() / 2);
  for (size_t i = 0; i < out.size(); ++i) out[i] = {uv[2 * i], uv[2 * i + 1]};
  return out;
}

}  // namespace vm::testing
