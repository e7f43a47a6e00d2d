// Fidelity of the remeshed wall to its input: the rounds that find input
// vertices farther than a fraction of h from the output and pin output
// vertices onto them (pin_to_input), or make the size finer around them
// and mesh the surface again. Marchandise et al., section 2.1 put every new
// vertex on the input; these rounds add the converse, the input lying near
// the new surface (stage 3 of docs/ARCHITECTURE.md).
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <vector>

#include "core/geom/point_kdtree.h"
#include "core/mesh/adjacency.h"
#include "core/mesh/surface_mesh.h"
#include "core/surface/remesh_surface.h"
#include "core/util/result.h"

namespace vm {

/// The target size at each output vertex: the mean of `h` (one per input
/// vertex, model unit) over its home triangle (`home`: one input triangle
/// per output vertex).
std::vector<double> output_sizes(const SurfaceMesh& input, const std::vector<int32_t>& home,
                                 const std::vector<double>& h);

/// Edge length / mean target size of its ends (`size`: one per output
/// vertex of `out.mesh`), each edge once: 10th percentile, median, 90th
/// percentile ({0, 0, 0} without edges).
std::array<double, 3> edge_ratios(const RemeshedSurface& out, const std::vector<double>& size);

/// Sets stats.max_input_gap and input_gap_vertices from `gaps` (each
/// input vertex's distance to the wall) over `asked` (its asked size, > 0);
/// returns how many gaps are beyond `fidelity` times the asked size.
size_t count_gaps(const std::vector<double>& gaps, const std::vector<double>& asked,
                  double fidelity, RemeshStats& stats);

/// The pinning rounds (RemeshOptions::fidelity .. fidelity_floor_mean):
/// output vertices pinned onto the input vertices farther than
/// options.fidelity times `asked` from the output (pin_to_input), then
/// options.fidelity_passes optimization passes around them; pins that cost
/// quality are freed, and a round is undone if the quality floors still
/// fail, or if it made a self-intersection or a needle (twice undone in a
/// row ends the rounds at that quality). Where vertices stay far, local
/// size rounds (options.fidelity_local_rounds) halve `h` around them and
/// split the wall there, on the same terms, and the pinning rounds run
/// again.
/// `input`: manifold, oriented, `adj` its adjacency with the sharp features
/// cut; `h`: the size the wall was meshed at (made finer where a local
/// size round was kept), `asked`: the size asked for (a distinct vector),
/// one per input vertex, > 0, model unit. `mesh`: the optimized wall,
/// manifold, oriented like the input, every vertex on it; `wall`: its
/// per-vertex data (home, fixed and size as the optimizer left them;
/// pin_of is reset to -1), kept in step with the mesh (size made
/// output_sizes(h) again where a round ran). On return `input_gaps` holds
/// each input vertex's distance to the wall (model unit), and `stats` the
/// fidelity counts (reset first), the self-intersections when counted
/// exactly, and the optimizer's counts added.
void pin_far_input_vertices(const SurfaceMesh& input, const TriangleAdjacency& adj,
                            std::vector<double>& h, const std::vector<double>& asked,
                            const RemeshOptions& options, SurfaceMesh& mesh, WallVertices& wall,
                            std::vector<double>& input_gaps, RemeshStats& stats);

/// Whether `far` input vertices left beyond fidelity h on a wall of
/// `vertices` call for a size round: some, not noise everywhere (at most
/// options.fidelity_noise_share of the vertices), and on a wall of more
/// than options.fidelity_small_surface vertices more than
/// options.fidelity_size_share of them.
bool worth_size_round(size_t far, size_t vertices, const RemeshOptions& options);

/// The input vertices (ascending ids) whose `gaps` to the wall exceed
/// `fidelity` times their `asked` size (both one per input vertex).
std::vector<int32_t> far_input_vertices(const std::vector<double>& gaps,
                                        const std::vector<double>& asked, double fidelity);

/// `h` (one per input vertex, model unit) made finer within h of each input
/// vertex of `far` (ids), to the size at which its gap (`gaps`, one per
/// input vertex) would fall within 0.8 options.fidelity of `asked` (a
/// chord's gap over a bend grows as h^2; each size at most 0.9 and at least
/// 0.5 times what it was, and not below options.size.size_min), then
/// graded (options.size.gradation). `tree`: over input.points.
std::vector<double> finer_where_far(const SurfaceMesh& input, const PointKdTree& tree,
                                    const RemeshOptions& options, const std::vector<double>& h,
                                    const std::vector<double>& asked,
                                    const std::vector<int32_t>& far,
                                    const std::vector<double>& gaps);

/// Meshes the whole surface again at `sizes` (one per input vertex, model
/// unit), adding its times and counts to `stats`.
using RemeshAtSizesFn =
    std::function<Result<RemeshedSurface>(const std::vector<double>& sizes, RemeshStats& stats)>;

/// The size rounds (RemeshOptions::fidelity_size_rounds): while input
/// vertices stay beyond options.fidelity times `asked` from the wall in
/// `result` (meshed at `h`, with `stats`), and not as noise everywhere, the
/// size is made finer within h of each and the surface meshed again by
/// `remesh`, from the last round's sizes; they stop when the median edge
/// falls more than options.fidelity_size_drift below the asked size.
/// `h`, `asked`: one per input vertex, model unit, > 0. Leaves in `result`
/// and `stats` the surface with the fewest far vertices (the time and
/// rounds spent in `stats` count every round, kept or not). Returns an
/// error only when `remesh` was cancelled (then `result` and `stats` are
/// unspecified).
Status refine_size_where_far(const SurfaceMesh& input, const RemeshOptions& options,
                             std::vector<double> h, const std::vector<double>& asked,
                             Result<RemeshedSurface>& result, RemeshStats& stats,
                             const RemeshAtSizesFn& remesh);

}  // namespace vm
