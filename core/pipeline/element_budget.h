// The element budget of a job ({max_elements}) checked on the size field
// before meshing (our own): the wall's triangles and the lumen's tetrahedra
// estimated by core/surface/element_estimate.h. A size the user gave that
// would exceed it is refused with the size that fits (a "coarser" remedy);
// the default size, neither {size} nor {per_circumference} given, is
// coarsened to the largest whole number per circumference that fits, never
// below the fewest that keep the vessels' volume (fewest_per_circumference).
#pragma once

#include <span>
#include <string>
#include <vector>

#include "core/mesh/surface_mesh.h"
#include "core/mesh/topology.h"
#include "core/surface/size_field.h"
#include "core/util/result.h"

namespace vm {

/// The largest element budget {max_elements} takes.
inline constexpr double kMostElements = 1e9;

/// Peak bytes of memory a tetrahedron of the mesh takes in the WebAssembly
/// build, everything the job holds at its peak and the MSH file it writes
/// included: measured as 263-289 B on the aortic arch from 2.6M to 11.9M
/// tetrahedra, 301 B from one to the next (docs/decisions.md, "Memory per
/// tetrahedron"; natively 188-199 B).
inline constexpr double kWasmBytesPerTetrahedron = 300;

/// The tetrahedra that fit in `memory_bytes` at kWasmBytesPerTetrahedron
/// each (0: no limit, for memory_bytes 0).
double tetrahedra_in_memory(double memory_bytes);

/// "the mesher's memory (4.2 GB free: about 1.4e+07 tetrahedra at 300
/// bytes each)": what a refusal for `memory_bytes` says.
std::string memory_text(double memory_bytes);

/// What the budget weighs: MeshJobOptions' fields of the same names (volume:
/// a volume is meshed, its tetrahedra counted at the wall's median size
/// unless core_size > 0, which check_volume_budget weighs); size_given: the
/// wall's size was given, so it is refused, never coarsened; coarsening
/// stops at fewest_per_circumference(max_volume_change). memory_bytes > 0
/// caps the tetrahedra further at tetrahedra_in_memory(memory_bytes).
struct ElementBudget {
  double max_elements = 15e6, core_size = 0, max_volume_change = 0.05, memory_bytes = 0;
  bool volume = true, size_given = false;
};

/// What fitting the default size to the budget did (coarsened false: it
/// fitted, or the size was given).
struct BudgetFit {
  bool coarsened = false;
  double asked_per_circumference = 0;  ///< the default N
  double per_circumference = 0;        ///< the N used
  /// The estimate that was over the budget ("triangles" on the wall or
  /// "tetrahedra" in the lumen), at the default N and at the N used.
  std::string counted;
  double asked_elements = 0, elements = 0;
  double max_elements = 0;
  /// A budget the default N fits in (rounded up to two significant digits).
  double enough = 0;
  /// The memory (ElementBudget::memory_bytes), not {max_elements}, was the
  /// limit: no larger budget makes the finer mesh fit.
  bool memory = false;
  double memory_bytes = 0;
};

/// The tetrahedra a job may make: {max_elements}, or fewer when they fit
/// in less memory (`memory` then true).
struct TetrahedronLimit {
  double tetrahedra = 0;
  bool memory = false;
};
TetrahedronLimit tetrahedron_limit(double max_elements, double memory_bytes);

/// What a coarsening did, in a warning's words ("the default size
/// ({per_circumference} 20) would make about ... coarsened to ... ask for
/// the finer mesh with {per_circumference} 20 and {max_elements} M").
std::string budget_warning(const BudgetFit& fit);

/// The volume `wall` encloses with each of its `openings` (boundary loops
/// of `wall`) closed by a fan from the loop's centroid: model units cubed,
/// positive for an outward wall.
double volume_closed_by_fans(const SurfaceMesh& wall, const std::vector<Opening>& openings);

/// The fewest edges per circumference the default is coarsened to: an
/// inscribed regular N-gon loses about (2 pi / N)^2 / 6 of a circle's area,
/// kept within 0.8 {max_volume_change} (13 for the default 5%).
double fewest_per_circumference(double max_volume_change);

/// The smallest uniform size, rounded up to two significant digits, whose
/// estimates fit `max_elements`: triangles over a wall of `area` (model
/// units squared), tetrahedra in `volume` (model units cubed; 0: none).
double fitting_size(double area, double volume, double max_elements);

/// Checks the size field `size` would give on `wall` (its boundary loops
/// `openings`; `radius`: R per vertex of `wall` as vessel_radius gives it,
/// needed in the per-circumference mode) against `budget`. Over the budget:
/// the default size is coarsened (size.per_circumference lowered, `fit`
/// says by how much); a given size is refused (kBadOption, its option
/// named, remedy "coarser" with the {size} or {per_circumference} that
/// fits); a default that cannot fit is refused naming {max_elements}. Over
/// the memory (budget.memory_bytes) the same, said as the memory's limit.
/// Errors of vertex_sizes pass through. `sizes`: when not null, receives
/// the field finally asked for (one per vertex of `wall`).
Status fit_element_budget(const SurfaceMesh& wall, const std::vector<Opening>& openings,
                          std::span<const double> radius, const ElementBudget& budget,
                          SizeOptions& size, BudgetFit& fit, std::vector<double>* sizes = nullptr);

}  // namespace vm
