// The last step of both parameterizations (lscm, fixed_boundary_map): solve
// the assembled sparse system, refusing a failed factorization or a
// non-finite solution.
#pragma once

#include <Eigen/Sparse>
#include <string>

#include "core/util/result.h"

namespace vm {

/// x with L x = rhs, L factorized by `Solver` (an Eigen sparse solver:
/// SparseLU, SimplicialLDLT); `what` names the map in the error
/// ("<what>: the sparse factorization failed", "... solve failed").
template <class Solver, class Dense>
Result<Dense> solve_sparse(const Eigen::SparseMatrix<double>& L, const Dense& rhs,
                           const std::string& what) {
  Solver solver;
  solver.compute(L);
  if (solver.info() != Eigen::Success)
    return Result<Dense>::Error(what + ": the sparse factorization failed");
  Dense x = solver.solve(rhs);
  if (solver.info() != Eigen::Success || !x.allFinite())
    return Result<Dense>::Error(what + ": the sparse solve failed");
  return x;
}

}  // namespace vm
