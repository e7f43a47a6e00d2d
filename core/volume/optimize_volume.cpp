// Tetrahedral mesh improvement: flips and edge removal maximizing the
// smallest gamma_t (Shewchuk 2002; Klingner and Shewchuk 2007; ring
// triangulations by Klincsek 1980), smart smoothing toward an ODT-like
// position (Freitag and Ollivier-Gooch 1997; Chen and Xu 2004; Alliez,
// Cohen-Steiner, Yvinec and Desbrun 2005) and a sliver phase climbing the
// worst quality; see optimize_volume.h.
//
// Phases: (1) qualities of every tetrahedron (cached per slot); (2) `passes`
// rounds of flips on the tetrahedra below flip_threshold (in id order, for
// memory locality) then smoothing of every free vertex, and one more round
// of flips; (3) the sliver phase (worst first); (4) statistics from the
// cached qualities. The flip and smoothing rounds of (2) run on eight slabs
// of vertices at the same time (on the threads), then sequentially on what
// crosses slabs: parallel_flips() and smooth_pass() say why no slab reads
// what another writes.
//
// Files: this one (the driver, the quality cache, the slabs),
// optimize_volume_flips.cpp (the flip pass), optimize_volume_smooth.cpp
// (smoothing and the sliver phase's climb), optimize_volume_slivers.cpp
// (the sliver phase); their shared state: optimize_volume_internal.h.
#include "core/volume/optimize_volume.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <vector>

#include "core/quality/tet_quality.h"
#include "core/util/parallel.h"
#include "core/util/stage_timer.h"
#include "core/volume/optimize_volume_internal.h"
#include "core/volume/slabs.h"

namespace vm {
namespace optimize_volume_detail {

void compute_all_qualities(Optimizer& op) {
  op.q.assign(op.m.capacity(), 2.0);
  op.dirty.assign(op.m.capacity(), 1);
  op.all_dirty = true;
  op.touched.clear();
  parallel_for(op.m.capacity(), 1 << 14, [&](size_t begin, size_t end) {
    for (size_t t = begin; t < end; ++t)
      if (op.m.is_live(int32_t(t))) op.q[t] = op.quality(int32_t(t));
  });
}

QualityStats cached_quality_stats(const Optimizer& op) {
  std::vector<float> q;
  q.reserve(op.m.num_tets());
  for (int32_t t = 0; t < int32_t(op.m.capacity()); ++t)
    if (op.m.is_live(t)) q.push_back(float(std::clamp(op.cached(t), -1.0, 1.0)));
  return quality_stats(q, 20);
}

std::vector<uint8_t> vertex_slabs(const Optimizer& op, size_t parts, bool halfway) {
  const size_t nv = op.m.num_vertices();
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (size_t v = 0; v < nv; ++v)
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], op.m.point(int32_t(v))[k]);
      hi[k] = std::max(hi[k], op.m.point(int32_t(v))[k]);
    }
  int axis = 0;
  for (int k = 1; k < 3; ++k)
    if (hi[k] - lo[k] > hi[axis] - lo[axis]) axis = k;
  std::vector<double> xs(nv);
  for (size_t v = 0; v < nv; ++v) xs[v] = op.m.point(int32_t(v))[axis];
  const Slabs slabs = equal_count_slabs(xs, axis, parts, halfway);
  std::vector<uint8_t> part(nv);
  for (size_t v = 0; v < nv; ++v) part[v] = uint8_t(slabs.of(op.m.point(int32_t(v))));
  return part;
}

}  // namespace optimize_volume_detail

Status optimize_volume(TetMesh& mesh, const std::vector<double>& vertex_h,
                       const OptimizeOptions& options, OptimizeStats* stats,
                       const ProgressFn& progress) {
  using clock = std::chrono::steady_clock;
  const auto t0 = clock::now();
  if (vertex_h.size() != mesh.num_vertices())
    return Status::Error("optimize: one size per vertex expected");
  for (double h : vertex_h)
    if (!(h > 0) || !std::isfinite(h))
      return Status::Error("optimize: sizes must be finite and > 0");
  using optimize_volume_detail::cached_quality_stats;
  using optimize_volume_detail::compute_all_qualities;
  using optimize_volume_detail::flip_pass;
  using optimize_volume_detail::Optimizer;
  using optimize_volume_detail::sliver_phase;
  using optimize_volume_detail::smooth_pass;
  OptimizeStats st;
  Optimizer op(mesh, vertex_h, options, st);
  compute_all_qualities(op);
  st.before = cached_quality_stats(op);
  const int steps = 2 * options.passes + 1;
  int step = 0;
  for (int pass = 0; pass < options.passes; ++pass) {
    if (!report_progress(progress, double(step++) / steps, "optimize volume"))
      return Status::Cancelled();
    auto t = clock::now();
    flip_pass(op, options.flip_threshold, false);
    st.flip_seconds += seconds_since(t);
    if (!report_progress(progress, double(step++) / steps, "optimize volume"))
      return Status::Cancelled();
    t = clock::now();
    smooth_pass(op);
    st.smooth_seconds += seconds_since(t);
  }
  if (!report_progress(progress, double(step++) / steps, "optimize volume"))
    return Status::Cancelled();
  auto t = clock::now();
  flip_pass(op, options.flip_threshold, false);
  st.flip_seconds += seconds_since(t);
  t = clock::now();
  sliver_phase(op);
  st.sliver_seconds += seconds_since(t);
  st.after = cached_quality_stats(op);
  st.seconds = seconds_since(t0);
  if (stats) *stats = st;
  return Status::Ok();
}

}  // namespace vm
