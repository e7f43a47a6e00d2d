// Finite-element least-squares conformal map of a disk-like patch
// (Marchandise et al., section 2.1, eqs. 2-9; Levy et al. 2002).
#pragma once

#include <cstdint>
#include <vector>

#include "core/mesh/surface_mesh.h"
#include "core/util/result.h"

namespace vm {

/// A map of a patch to the plane.
struct Parametrization {
  std::vector<double> uv;        ///< 2 * num_vertices: u, v of each vertex
  int32_t pinned[2] = {-1, -1};  ///< the two vertices fixed by the solve
  size_t flipped_triangles = 0;  ///< triangles with non-positive area in uv
  double conformal_energy = 0;   ///< E_LSCM of the result (eq. 2)
};

/// Minimizes E_LSCM = 1/2 sum_T |grad u^perp - grad v|^2 |T| with P1
/// elements, pinning the two boundary vertices farthest apart (found by two
/// sweeps on the longest boundary loop) at (0, 0) and (d, 0), d their 3D
/// distance, and solving the SPD system [A -C; C A] (A: cotangent stiffness,
/// C: the antisymmetric boundary term) with a sparse LDL^T factorization.
/// Preconditions: `patch` is connected, consistently oriented (the map then
/// preserves orientation with respect to the triangle normals), has at least
/// one boundary loop, and no triangle with a repeated vertex. Errors: no
/// boundary, fewer than 3 vertices, a failed factorization.
Result<Parametrization> lscm(const SurfaceMesh& patch);

/// E_LSCM of a map `uv` (2 doubles per vertex) of `patch`, summed per
/// triangle from eq. 2. Equals dirichlet_energy(u) + dirichlet_energy(v) -
/// signed_area(uv) (eq. 4 integrated).
double conformal_energy(const SurfaceMesh& patch, const std::vector<double>& uv);

/// 1/2 sum_T |grad f|^2 |T| for a P1 function f (one value per vertex).
double dirichlet_energy(const SurfaceMesh& patch, const std::vector<double>& f);

/// Signed area of the image of `patch` under `uv`.
double signed_area(const SurfaceMesh& patch, const std::vector<double>& uv);

/// Number of triangles whose image under `uv` has non-positive area.
size_t count_flipped(const SurfaceMesh& patch, const std::vector<double>& uv);

}  // namespace vm
