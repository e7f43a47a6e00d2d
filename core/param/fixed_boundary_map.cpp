// Fixed-boundary disk maps: Tutte-style embedding with harmonic (cotangent)
// or Floater's mean-value weights (Floater, "Mean value coordinates", CAGD
// 20, 2003), as compared in Marchandise et al. section 3. The boundary loop
// is placed on the unit circle by cumulative chord length; the interior
// solves sum_j w_ij (x_i - x_j) = 0 with a sparse LU factorization.
#include "core/param/fixed_boundary_map.h"

#include <Eigen/Sparse>
#include <Eigen/SparseLU>
#include <cmath>
#include <numbers>

#include "core/mesh/adjacency.h"
#include "core/mesh/boundary_loops.h"
#include "core/param/sparse_solve.h"
#include "core/util/portable_math.h"

namespace vm {
namespace {

const double* point(const SurfaceMesh& m, int32_t v) { return &m.points[3 * size_t(v)]; }

double angle_at(const double* p, const double* q, const double* r) {
  double u[3], w[3], d = 0, nu = 0, nw = 0;
  for (int k = 0; k < 3; ++k) {
    u[k] = q[k] - p[k];
    w[k] = r[k] - p[k];
    d += u[k] * w[k];
    nu += u[k] * u[k];
    nw += w[k] * w[k];
  }
  double c = d / std::sqrt(nu * nw);
  return pm::acos(std::max(-1.0, std::min(1.0, c)));
}

double distance(const double* p, const double* q) {
  return std::sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
                   (p[2] - q[2]) * (p[2] - q[2]));
}

}  // namespace

Result<Parametrization> map_to_disk(const SurfaceMesh& m, DiskWeights weights) {
  const size_t nv = m.num_vertices(), nt = m.num_triangles();
  if (nv < 3 || nt == 0) return Result<Parametrization>::Error("patch has fewer than 3 vertices");
  TriangleAdjacency adj = build_adjacency(m);
  auto loops = boundary_loops(m, adj);
  if (loops.size() != 1)
    return Result<Parametrization>::Error("a disk map needs exactly one boundary loop, found " +
                                          std::to_string(loops.size()));
  Parametrization out;
  out.uv.assign(2 * nv, 0.0);
  // Phase 1: boundary on the unit circle by chord length.
  const auto& loop = loops[0];
  std::vector<double> along(loop.size() + 1, 0.0);
  for (size_t i = 0; i < loop.size(); ++i)
    along[i + 1] = along[i] + distance(point(m, loop[i]), point(m, loop[(i + 1) % loop.size()]));
  std::vector<int32_t> row(nv, 0);
  for (size_t i = 0; i < loop.size(); ++i) {
    // The loop runs along the boundary half-edges, counterclockwise around
    // the patch seen from its normal side: keep that direction on the circle.
    double a = 2 * std::numbers::pi * along[i] / along.back();
    out.uv[2 * size_t(loop[i])] = pm::cos(a);
    out.uv[2 * size_t(loop[i]) + 1] = pm::sin(a);
    row[loop[i]] = -1;
  }
  int32_t n = 0;
  for (size_t v = 0; v < nv; ++v)
    if (row[v] == 0)
      row[v] = n++;
    else
      row[v] = -1;
  // Phase 2: weights. Each triangle adds, for each corner i and each other
  // corner j, its part of w_ij: cot of the angle opposite edge ij (harmonic,
  // half of the pair) or tan(half the angle at i) / |x_i - x_j| (mean value).
  std::vector<Eigen::Triplet<double>> triplets;
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(n, 2);
  for (size_t t = 0; t < nt; ++t) {
    const int32_t* v = &m.triangles[3 * t];
    double ang[3];
    for (int k = 0; k < 3; ++k)
      ang[k] = angle_at(point(m, v[k]), point(m, v[(k + 1) % 3]), point(m, v[(k + 2) % 3]));
    for (int k = 0; k < 3; ++k) {
      int32_t i = v[k];
      if (row[i] < 0) continue;
      for (int s = 1; s <= 2; ++s) {
        int32_t j = v[(k + s) % 3];
        int other = (k + 3 - s) % 3;  // the third corner, opposite edge ij
        double w = weights == DiskWeights::kHarmonic
                       ? 0.5 / pm::tan(ang[other])
                       : pm::tan(0.5 * ang[k]) / distance(point(m, i), point(m, j));
        triplets.emplace_back(row[i], row[i], w);
        if (row[j] >= 0) {
          triplets.emplace_back(row[i], row[j], -w);
        } else {
          rhs(row[i], 0) += w * out.uv[2 * size_t(j)];
          rhs(row[i], 1) += w * out.uv[2 * size_t(j) + 1];
        }
      }
    }
  }
  if (n > 0) {
    Eigen::SparseMatrix<double> L(n, n);
    L.setFromTriplets(triplets.begin(), triplets.end());
    auto solved = solve_sparse<Eigen::SparseLU<Eigen::SparseMatrix<double>>>(L, rhs, "disk map");
    if (!solved.ok()) return solved.status();
    const Eigen::MatrixXd& x = solved.value();
    for (size_t v = 0; v < nv; ++v) {
      if (row[v] < 0) continue;
      out.uv[2 * v] = x(row[v], 0);
      out.uv[2 * v + 1] = x(row[v], 1);
    }
  }
  out.flipped_triangles = count_flipped(m, out.uv);
  out.conformal_energy = conformal_energy(m, out.uv);
  return out;
}

}  // namespace vm
