// Fidelity of a remeshed surface to its input: input vertices farther than
// a fraction of h from the output (segmentation bumps and ridges sharper
// than h can follow) get an output vertex moved onto them and pinned there.
// Marchandise et al., section 2.1 ask every new vertex to lie on the input;
// this adds the converse, the input lying near the new surface.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/mesh/surface_mesh.h"

namespace vm {

struct PinStats {
  size_t far = 0;     ///< input vertices beyond the limit before pinning
  size_t pinned = 0;  ///< output vertices moved onto them
};

/// For each input vertex v with gaps[v] > limit * h[v] (largest relative
/// gap first): the free corner (fixed == kFree) of the output triangle
/// closest to v that can move onto v without folding its triangles (each
/// turns by less than 60 degrees and keeps gamma_k >= 0.1) moves there,
/// gets home = a triangle of v and fixed = kPinned. At most one corner of
/// each output triangle per call. `output` is manifold and oriented like
/// `input`; home, fixed: one per output vertex; h and gaps: one per input
/// vertex, h > 0 (gaps: distances_to_surface(output, input.points)). The
/// output's connectivity is unchanged.
/// Input vertices flagged in `skip` (empty, or one per input vertex) are
/// left alone.
PinStats pin_to_input(SurfaceMesh& output, std::vector<int32_t>& home, std::vector<uint8_t>& fixed,
                      const SurfaceMesh& input, const std::vector<double>& h,
                      const std::vector<double>& gaps, double limit,
                      const std::vector<uint8_t>& skip);

/// Frees (fixed = kFree) every pinned vertex of a triangle of `output` with
/// gamma_k < min_gamma, and flags in `skip` (one per input vertex) the
/// input vertex it was pinned to, so that it is not pinned again. Returns
/// the number freed.
size_t unpin_poor(const SurfaceMesh& output, std::vector<uint8_t>& fixed, const SurfaceMesh& input,
                  double min_gamma, std::vector<uint8_t>& skip);

}  // namespace vm
