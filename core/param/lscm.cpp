// Least-squares conformal map, finite-element form of Marchandise et al.
// (section 2.1): assemble A_kj = int grad phi_k . grad phi_j (cotangent
// weights) and C_kj = int n . (grad phi_k x grad phi_j) (+-1/2 per oriented
// edge of each triangle, so only boundary edges survive), pin two far-apart
// boundary vertices, solve [A -C; C A] (U; V) = rhs.
#include "core/param/lscm.h"

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>

#include "core/geom/vec3.h"
#include "core/mesh/adjacency.h"
#include "core/mesh/boundary_loops.h"
#include "core/param/sparse_solve.h"

namespace vm {
namespace {

Vec3 sub(const double* a, const double* b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }

const double* point(const SurfaceMesh& m, int32_t v) { return &m.points[3 * size_t(v)]; }

// The two vertices of `loop` farthest apart, by two sweeps (exact for
// convex-ish loops, a good choice otherwise, as the seed recommends).
std::pair<int32_t, int32_t> far_pair(const SurfaceMesh& m, const std::vector<int32_t>& loop) {
  auto farthest_from = [&](int32_t a) {
    int32_t best = loop[0];
    double best_d = -1;
    for (int32_t v : loop) {
      double d = norm(sub(point(m, v), point(m, a)));
      if (d > best_d) best_d = d, best = v;
    }
    return best;
  };
  int32_t a = farthest_from(loop[0]);
  return {a, farthest_from(a)};
}

// Gradients of the three P1 shape functions of triangle t in 3D, and its
// area and unit normal. Returns false for a zero-area triangle.
bool shape_gradients(const SurfaceMesh& m, size_t t, Vec3 grad[3], double& area) {
  const int32_t* v = &m.triangles[3 * t];
  Vec3 e0 = sub(point(m, v[2]), point(m, v[1]));  // opposite vertex 0
  Vec3 e1 = sub(point(m, v[0]), point(m, v[2]));
  Vec3 e2 = sub(point(m, v[1]), point(m, v[0]));
  Vec3 n = cross(e2, sub(point(m, v[2]), point(m, v[0])));
  double twice_area = norm(n);
  if (!(twice_area > 0)) return false;
  area = 0.5 * twice_area;
  Vec3 un = {n[0] / twice_area, n[1] / twice_area, n[2] / twice_area};
  // grad phi_i = (n x e_i) / (2 area).
  const Vec3 e[3] = {e0, e1, e2};
  for (int i = 0; i < 3; ++i) {
    Vec3 g = cross(un, e[i]);
    grad[i] = {g[0] / twice_area, g[1] / twice_area, g[2] / twice_area};
  }
  return true;
}

// The gradient in triangle t (g: its shape_gradients) of the P1 function
// with value f(v) at vertex v.
template <class F>
Vec3 p1_gradient(const SurfaceMesh& m, size_t t, const Vec3 g[3], F f) {
  Vec3 grad = {0, 0, 0};
  for (int i = 0; i < 3; ++i) {
    const double fi = f(size_t(m.triangles[3 * t + i]));
    grad = {grad[0] + fi * g[i][0], grad[1] + fi * g[i][1], grad[2] + fi * g[i][2]};
  }
  return grad;
}

// The integral over the surface of an energy density constant in each
// triangle: the sum of density(t, g) times the area over the triangles of
// nonzero area (g: their shape_gradients).
template <class Density>
double integrate(const SurfaceMesh& m, Density density) {
  double e = 0;
  for (size_t t = 0; t < m.num_triangles(); ++t) {
    Vec3 g[3];
    double area;
    if (!shape_gradients(m, t, g, area)) continue;
    e += density(t, g) * area;
  }
  return e;
}

// Twice the signed area of the image of triangle t under uv.
double twice_uv_area(const SurfaceMesh& m, const std::vector<double>& uv, size_t t) {
  const double* a = &uv[2 * size_t(m.triangles[3 * t])];
  const double* b = &uv[2 * size_t(m.triangles[3 * t + 1])];
  const double* c = &uv[2 * size_t(m.triangles[3 * t + 2])];
  return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
}

}  // namespace

Result<Parametrization> lscm(const SurfaceMesh& m) {
  const size_t nv = m.num_vertices(), nt = m.num_triangles();
  if (nv < 3 || nt == 0) return Result<Parametrization>::Error("patch has fewer than 3 vertices");
  TriangleAdjacency adj = build_adjacency(m);
  std::vector<std::vector<int32_t>> loops = boundary_loops(m, adj);
  if (loops.empty())
    return Result<Parametrization>::Error("patch has no boundary: a closed surface must be cut");
  const auto& longest = *std::max_element(
      loops.begin(), loops.end(), [](const auto& a, const auto& b) { return a.size() < b.size(); });
  auto [p0, p1] = far_pair(m, longest);

  Parametrization out;
  out.pinned[0] = p0;
  out.pinned[1] = p1;
  out.uv.assign(2 * nv, 0.0);
  out.uv[2 * size_t(p1)] = norm(sub(point(m, p1), point(m, p0)));

  // Unknown numbering: free vertices get rows 0..nf-1 for u and nf..2nf-1
  // for v; pinned vertices are moved to the right-hand side.
  std::vector<int32_t> row(nv, -1);
  int32_t nf = 0;
  for (size_t v = 0; v < nv; ++v)
    if (int32_t(v) != p0 && int32_t(v) != p1) row[v] = nf++;
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(nt * 9 * 4);
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(2 * nf);
  // Adds coefficient `a` of the quadratic form's matrix at (unknown i of
  // block bi, unknown j of block bj), block 0 = u, 1 = v.
  auto add = [&](int32_t vi, int bi, int32_t vj, int bj, double a) {
    if (row[vi] < 0) return;  // pinned rows are not equations
    int32_t r = row[vi] + bi * nf;
    if (row[vj] >= 0) {
      triplets.emplace_back(r, row[vj] + bj * nf, a);
    } else {
      rhs[r] -= a * out.uv[2 * size_t(vj) + size_t(bj)];
    }
  };
  for (size_t t = 0; t < nt; ++t) {
    const int32_t* v = &m.triangles[3 * t];
    Vec3 g[3];
    double area = 0;
    bool ok = shape_gradients(m, t, g, area);
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) {
        if (ok) {
          double a = dot(g[i], g[j]) * area;  // A_ij
          add(v[i], 0, v[j], 0, a);
          add(v[i], 1, v[j], 1, a);
        }
        // C_ij = +1/2 when j follows i counterclockwise, -1/2 when it
        // precedes it (independent of the shape), so zero-area triangles
        // still cancel their neighbors' interior-edge terms.
        double c = j == (i + 1) % 3 ? 0.5 : (i == (j + 1) % 3 ? -0.5 : 0.0);
        if (c != 0) {
          add(v[i], 0, v[j], 1, -c);  // [A -C; C A]
          add(v[i], 1, v[j], 0, c);
        }
      }
    }
  }
  Eigen::SparseMatrix<double> L(2 * nf, 2 * nf);
  L.setFromTriplets(triplets.begin(), triplets.end());
  auto solved =
      solve_sparse<Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>>(L, rhs, "conformal map");
  if (!solved.ok()) return solved.status();
  const Eigen::VectorXd& x = solved.value();
  for (size_t v = 0; v < nv; ++v) {
    if (row[v] < 0) continue;
    out.uv[2 * v] = x[row[v]];
    out.uv[2 * v + 1] = x[row[v] + nf];
  }
  out.flipped_triangles = count_flipped(m, out.uv);
  out.conformal_energy = conformal_energy(m, out.uv);
  return out;
}

double dirichlet_energy(const SurfaceMesh& m, const std::vector<double>& f) {
  return integrate(m, [&](size_t t, const Vec3 g[3]) {
    const Vec3 grad = p1_gradient(m, t, g, [&](size_t v) { return f[v]; });
    return 0.5 * dot(grad, grad);
  });
}

double signed_area(const SurfaceMesh& m, const std::vector<double>& uv) {
  double s = 0;
  for (size_t t = 0; t < m.num_triangles(); ++t) s += 0.5 * twice_uv_area(m, uv, t);
  return s;
}

size_t count_flipped(const SurfaceMesh& m, const std::vector<double>& uv) {
  size_t n = 0;
  for (size_t t = 0; t < m.num_triangles(); ++t) n += twice_uv_area(m, uv, t) <= 0;
  return n;
}

double conformal_energy(const SurfaceMesh& m, const std::vector<double>& uv) {
  return integrate(m, [&](size_t t, const Vec3 g[3]) {
    Vec3 n = cross(sub(point(m, m.triangles[3 * t + 1]), point(m, m.triangles[3 * t])),
                   sub(point(m, m.triangles[3 * t + 2]), point(m, m.triangles[3 * t])));
    double nn = norm(n);
    n = {n[0] / nn, n[1] / nn, n[2] / nn};
    const Vec3 gu = p1_gradient(m, t, g, [&](size_t v) { return uv[2 * v]; });
    const Vec3 gv = p1_gradient(m, t, g, [&](size_t v) { return uv[2 * v + 1]; });
    Vec3 r = cross(n, gu);  // grad u rotated by +90 degrees in the plane
    Vec3 d = {r[0] - gv[0], r[1] - gv[1], r[2] - gv[2]};
    return 0.5 * dot(d, d);
  });
}

}  // namespace vm
