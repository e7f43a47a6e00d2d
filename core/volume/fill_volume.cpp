// Volume fill after boundary recovery (Marchandise et al., sections 2.2 and
// 3); see fill_volume.h.
//
// Phases: (1) checks and the region's initial vertices; (2) size field from
// their sizes; (3) refinement in the kernel; (4) the region as a TetMesh,
// initial vertices first in their order, new vertices along a Hilbert curve
// (memory locality for the optimizer); (5) optimization; (6) extraction.
#include "core/volume/fill_volume.h"

#include <chrono>
#include <cmath>
#include <string>

#include "core/geom/hilbert_sort.h"
#include "core/util/parallel.h"
#include "core/util/stage_timer.h"
#include "core/volume/size_field3d.h"
#include "core/volume/tet_mesh.h"

namespace vm {

Result<VolumeMesh> fill_volume(Delaunay3D& kernel, const std::vector<double>& vertex_size,
                               const FillOptions& options, FillStats* stats,
                               const ProgressFn& progress) {
  using R = Result<VolumeMesh>;
  using clock = std::chrono::steady_clock;
  const auto t_start = clock::now();
  FillStats st;
  // Phase 1: checks; the region's vertices.
  const size_t n0 = kernel.num_vertices();
  if (vertex_size.size() != n0) return R::Error("fill volume: one size per kernel vertex expected");
  const int32_t tag = options.region_tag;
  std::vector<uint8_t> used(n0, 0);
  size_t region_tets = 0;
  for (int32_t t = 0; t < int32_t(kernel.tet_capacity()); ++t) {
    if (!kernel.is_live(t) || kernel.is_ghost(t) || kernel.tag(t) != tag) continue;
    ++region_tets;
    for (int k = 0; k < 4; ++k) used[size_t(kernel.tet(t)[k])] = 1;
  }
  if (region_tets == 0) return R::Error("fill volume: no tetrahedron carries the region tag");
  std::vector<double> bpts, bsize;
  for (size_t v = 0; v < n0; ++v) {
    if (!used[v]) {
      ++st.unused_vertices;
      continue;
    }
    const double h = vertex_size[v];
    if (!(h > 0) || !std::isfinite(h))
      return R::Error("fill volume: vertex " + std::to_string(v) + " has a size that is not > 0");
    bpts.insert(bpts.end(), kernel.point(int32_t(v)), kernel.point(int32_t(v)) + 3);
    bsize.push_back(h);
  }
  st.boundary_vertices = bsize.size();
  if (!report_progress(progress, 0.0, "size field")) return Status::Cancelled();

  // Phase 2: size field; h at every kernel vertex.
  auto t = clock::now();
  VolumeSizeOptions fo;
  fo.core_size = options.core_size;
  fo.gradation = options.gradation;
  fo.spheres = options.spheres;
  auto field = VolumeSizeField::build(bpts, bsize, fo);
  if (!field.ok()) return R::Error("fill volume: " + field.message());
  std::vector<double> vertex_h(n0);
  parallel_for(n0, 1024, [&](size_t begin, size_t end) {
    for (size_t v = begin; v < end; ++v) vertex_h[v] = field.value()(kernel.point(int32_t(v)));
  });
  st.size_field_seconds = seconds_since(t);

  // Phase 3: refinement.
  t = clock::now();
  RefineOptions ro = options.refine;
  ro.region_tag = tag;
  auto sub_progress = [&](double lo, double hi) -> ProgressFn {
    if (!progress) return {};
    return [&progress, lo, hi](double f, std::string_view stage) {
      return progress(lo + (hi - lo) * f, stage);
    };
  };
  Status s =
      refine_volume(kernel, field.value(), vertex_h, ro, &st.refine, sub_progress(0.02, 0.5));
  if (!s.ok()) return s.cancelled() ? s : s.Prefixed("fill volume: ");
  st.refine_seconds = seconds_since(t);

  // Phase 4: the region as a TetMesh.
  t = clock::now();
  const size_t nk = kernel.num_vertices();
  std::vector<int32_t> vmap(nk, -1);
  int32_t nv = 0;
  for (size_t v = 0; v < n0; ++v)
    if (used[v]) vmap[v] = nv++;
  std::vector<int32_t> added;
  for (size_t v = n0; v < nk; ++v) added.push_back(int32_t(v));
  hilbert_sort(kernel.points(), added.data(), int64_t(added.size()));
  for (int32_t v : added) vmap[size_t(v)] = nv++;
  std::vector<uint8_t> fixed(size_t(nv), 0);
  std::vector<double> h(static_cast<size_t>(nv));
  for (size_t v = 0; v < nk; ++v) {
    if (vmap[v] < 0) continue;
    fixed[size_t(vmap[v])] = v < n0;
    h[size_t(vmap[v])] = vertex_h[v];
  }
  auto mesh = TetMesh::from_kernel(kernel, tag, vmap, nv, std::move(fixed));
  if (!mesh.ok()) return R::Error("fill volume: " + mesh.message());
  st.extract_seconds = seconds_since(t);
  st.inserted_vertices = added.size();

  // Phase 5: optimization.
  t = clock::now();
  if (options.optimize) {
    s = optimize_volume(mesh.value(), h, options.optimize_options, &st.optimize,
                        sub_progress(0.5, 1.0));
    if (!s.ok()) return s.cancelled() ? s : s.Prefixed("fill volume: ");
  }
  st.optimize_seconds = seconds_since(t);

  // Phase 6: extraction.
  t = clock::now();
  VolumeMesh out;
  out.points = mesh.value().points();
  out.tets = mesh.value().tets();
  // Vertices left unused (none is expected: an optimizer insertion that
  // fails leaves one) are dropped; the boundary ones are all used.
  std::vector<int32_t> renumber(out.points.size() / 3, -1);
  for (int32_t v : out.tets) renumber[size_t(v)] = 0;
  int32_t next = 0;
  for (size_t v = 0; v < renumber.size(); ++v)
    renumber[v] = renumber[v] == 0 || v < st.boundary_vertices ? next++ : -1;
  if (size_t(next) != renumber.size()) {
    std::vector<double> pts(3 * size_t(next));
    for (size_t v = 0; v < renumber.size(); ++v)
      if (renumber[v] >= 0)
        for (int c = 0; c < 3; ++c)
          pts[3 * size_t(renumber[v]) + size_t(c)] = out.points[3 * v + size_t(c)];
    out.points.swap(pts);
    for (int32_t& v : out.tets) v = renumber[size_t(v)];
  }
  out.tet_region.assign(out.tets.size() / 4, 0);
  st.extract_seconds += seconds_since(t);
  st.tets = out.num_tets();
  st.seconds = seconds_since(t_start);
  if (!report_progress(progress, 1.0, "optimize volume")) return Status::Cancelled();
  if (stats) *stats = st;
  return out;
}

}  // namespace vm
