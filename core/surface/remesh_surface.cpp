// Whole-surface remeshing by finite element conformal maps (Marchandise et
// al., section 2.1 and Fig. 2; qualities of section 3), in phases:
//  1. the size field (seed eq. 11: core/surface/size_field), and an input
//     far finer than it decimated (core/mesh/decimate);
//  2. the sharp features, and the partition into patches of disk topology
//     and moderate aspect ratio, each mapped to the plane (Fig. 2 step 1);
//  3. the seams (patch boundaries, features and openings) cut into curves
//     between corners, each resampled once in 3D, so that neighbors share
//     their samples;
//  4. every patch meshed in its parameter plane against the shared samples
//     and mapped back (Fig. 2 steps 2-4), assembled by sample ids;
//  5. optimization on the input surface;
//  6. and 7. fidelity: output vertices pinned onto input vertices left far,
//     then finer sizes where they stay far (core/surface/fidelity).
// See stage 3 of docs/ARCHITECTURE.md.
#include "core/surface/remesh_surface.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>
#include <unordered_map>

#include "core/geom/hilbert_sort.h"
#include "core/geom/vec3.h"
#include "core/mesh/boundary_loops.h"
#include "core/mesh/decimate.h"
#include "core/mesh/surface_distance.h"
#include "core/mesh/triangle_bvh.h"
#include "core/param/fixed_boundary_map.h"
#include "core/quality/triangle_quality.h"
#include "core/surface/element_estimate.h"
#include "core/surface/fidelity.h"
#include "core/surface/resample_curve.h"
#include "core/surface/sharp_features.h"
#include "core/util/parallel.h"
#include "core/util/stage_timer.h"

namespace vm {
namespace {

uint64_t edge_key(int32_t a, int32_t b) {
  if (a > b) std::swap(a, b);
  return (uint64_t(uint32_t(a)) << 32) | uint32_t(b);
}

/// The mean of the corners of the triangles `tris` of `m`: where a patch
/// is, for messages.
Vec3 patch_centre(const SurfaceMesh& m, const std::vector<int32_t>& tris) {
  Vec3 centre{0, 0, 0};
  for (int32_t t : tris)
    for (int k = 0; k < 3; ++k)
      centre = centre + (1.0 / (3.0 * double(tris.size()))) *
                            at(m.points, m.triangles[3 * size_t(t) + size_t(k)]);
  return centre;
}

/// The shared discretization of every patch boundary.
struct Seams {
  std::vector<double> points;      ///< 3 per sample
  std::vector<int32_t> home;       ///< an input triangle containing each sample
  std::vector<uint8_t> kind;       ///< kOnOpening, kOnFeature or kFree (a plain seam)
  std::vector<int32_t> at_vertex;  ///< input vertex -> sample there, or -1
  /// Input edge (min, max) -> samples strictly inside it: (fraction from
  /// the min vertex, sample id).
  std::unordered_map<uint64_t, std::vector<std::pair<double, int32_t>>> on_edge;
};

/// Phase 3: curves between corners of the boundary graph, resampled. The
/// graph's edges are the openings, and the edges between two patches: sharp
/// features (flag `feature` per half-edge, may be empty) or plain seams.
Seams discretize_seams(const SurfaceMesh& m, const TriangleAdjacency& adj,
                       const std::vector<uint8_t>& feature, const std::vector<int32_t>& label,
                       const std::vector<double>& h) {
  const size_t nv = m.num_vertices();
  struct Edge {
    int32_t a, b, tri;
    uint8_t kind;  // kFree (a seam), kOnOpening or kOnFeature
  };
  std::vector<Edge> edges;
  for (size_t he = 0; he < adj.opposite.size(); ++he) {
    const int32_t o = adj.opposite[he], t = int32_t(he / 3);
    const bool opening = o < 0;
    if (!opening && (label[size_t(o / 3)] == label[size_t(t)] || o < int32_t(he))) continue;
    const uint8_t kind = opening                           ? kOnOpening
                         : !feature.empty() && feature[he] ? kOnFeature
                                                           : kFree;
    edges.push_back({half_edge_from(m, int32_t(he)), half_edge_to(m, int32_t(he)), t, kind});
  }
  std::vector<std::vector<int32_t>> at(nv);
  std::vector<uint8_t> kinds(nv, 0);  // bit per kind of edge at the vertex
  for (size_t e = 0; e < edges.size(); ++e) {
    for (int32_t v : {edges[e].a, edges[e].b}) {
      at[size_t(v)].push_back(int32_t(e));
      kinds[size_t(v)] |= uint8_t(1 << edges[e].kind);
    }
  }
  Seams s;
  s.at_vertex.assign(nv, -1);
  auto add_sample = [&](const double* x, int32_t tri, uint8_t kind) {
    s.points.insert(s.points.end(), x, x + 3);
    s.home.push_back(tri);
    s.kind.push_back(kind);
    return int32_t(s.home.size() - 1);
  };
  // Corners: ends of curves and vertices where curves of two kinds meet. A
  // corner is fixed like the most constrained curve through it.
  std::vector<uint8_t> corner(nv, 0);
  for (size_t v = 0; v < nv; ++v) {
    const uint8_t k = kinds[v];
    corner[v] = !at[v].empty() && (at[v].size() != 2 || (k & (k - 1)) != 0);
    if (corner[v])
      s.at_vertex[v] = add_sample(&m.points[3 * v], edges[size_t(at[v][0])].tri,
                                  (k & (1 << kOnOpening))   ? kOnOpening
                                  : (k & (1 << kOnFeature)) ? kOnFeature
                                                            : kFree);
  }
  std::vector<uint8_t> used(edges.size(), 0);
  // Walks a curve from vertex v along edge e, to a corner or back to start.
  auto trace = [&](int32_t v, int32_t e) {
    std::vector<int32_t> chain = {v}, chain_edges;
    const int32_t start = v;
    while (true) {
      used[size_t(e)] = 1;
      chain_edges.push_back(e);
      v = edges[size_t(e)].a == v ? edges[size_t(e)].b : edges[size_t(e)].a;
      if (v == start || corner[size_t(v)]) break;
      chain.push_back(v);
      int32_t next = -1;
      for (int32_t f : at[size_t(v)])
        if (!used[size_t(f)]) next = f;
      if (next < 0) break;
      e = next;
    }
    const bool closed = v == start && !corner[size_t(v)];
    if (!closed) chain.push_back(v);
    std::vector<double> pts, sizes;
    for (int32_t c : chain) {
      pts.insert(pts.end(), &m.points[3 * size_t(c)], &m.points[3 * size_t(c)] + 3);
      sizes.push_back(h[size_t(c)]);
    }
    // At least 2 segments per curve, so every patch boundary has 3 points.
    const size_t min_segments = closed ? 3 : 2;
    const uint8_t kind = edges[size_t(chain_edges[0])].kind;
    for (const CurveSample& cs : resample_curve(pts, sizes, closed, min_segments)) {
      const size_t i = cs.segment, j = (i + 1) % chain.size();
      const int32_t a = chain[i], b = chain[j];
      if (cs.t == 0 || cs.t == 1) {
        const int32_t at_v = cs.t == 0 ? a : b;
        if (s.at_vertex[size_t(at_v)] < 0)
          s.at_vertex[size_t(at_v)] =
              add_sample(&m.points[3 * size_t(at_v)], edges[size_t(chain_edges[i])].tri, kind);
        continue;
      }
      double x[3];
      for (int k = 0; k < 3; ++k)
        x[k] = (1 - cs.t) * m.points[3 * size_t(a) + k] + cs.t * m.points[3 * size_t(b) + k];
      const int32_t id = add_sample(x, edges[size_t(chain_edges[i])].tri, kind);
      s.on_edge[edge_key(a, b)].push_back({a < b ? cs.t : 1 - cs.t, id});
    }
  };
  for (size_t v = 0; v < nv; ++v)
    if (corner[v])
      for (int32_t e : at[v])
        if (!used[size_t(e)]) trace(int32_t(v), e);
  for (size_t e = 0; e < edges.size(); ++e)
    if (!used[e]) trace(edges[e].a, int32_t(e));
  for (auto& [key, list] : s.on_edge) std::sort(list.begin(), list.end());
  return s;
}

/// Phase 4 input: the boundary of a patch as shared samples, in loop order.
Result<std::vector<PatchBoundaryPoint>> patch_boundary(const MappedPatch& p, const Seams& s,
                                                       std::vector<int32_t>& ids) {
  using R = Result<std::vector<PatchBoundaryPoint>>;
  auto loops = boundary_loops(p.mesh, build_adjacency(p.mesh));
  if (loops.size() != 1) return R::Error("a patch is not a disk");
  const auto& loop = loops[0];
  std::vector<PatchBoundaryPoint> out;
  ids.clear();
  for (size_t i = 0; i < loop.size(); ++i) {
    const int32_t la = loop[i], lb = loop[(i + 1) % loop.size()];
    const int32_t a = p.vertex_of[size_t(la)], b = p.vertex_of[size_t(lb)];
    if (s.at_vertex[size_t(a)] >= 0) {
      out.push_back({la, lb, 0});
      ids.push_back(s.at_vertex[size_t(a)]);
    }
    auto it = s.on_edge.find(edge_key(a, b));
    if (it == s.on_edge.end()) continue;
    const auto& list = it->second;
    for (size_t j = 0; j < list.size(); ++j) {
      const auto& [f, id] = a < b ? list[j] : list[list.size() - 1 - j];
      out.push_back({la, lb, a < b ? f : 1 - f});
      ids.push_back(id);
    }
  }
  if (out.size() < 3)
    return R::Error("a patch boundary has fewer than 3 points at this size: use a smaller size");
  return out;
}

/// Phase 2: the sharp features (at the asked sizes) and the partition into
/// mapped patches, which sees the features as cuts (so no patch crosses a
/// crease). The partition does not depend on the sizes, so the size rounds
/// reuse it; a patch that fails to mesh empties `patches` and is split.
struct Partition {
  TriangleAdjacency full_adj;    ///< of the input
  std::vector<uint8_t> feature;  ///< per half-edge: a sharp feature
  TriangleAdjacency adj;         ///< full_adj cut along the features
  PartitionOptions options;
  std::vector<MappedPatch> patches;  ///< empty: to be computed
  std::vector<int32_t> label;        ///< per input triangle: its patch
  /// The input triangles nearest RemeshOptions::fallback_at, and per
  /// patch whether it holds one (takes the fallback at once).
  std::vector<int32_t> forced_triangles;
  std::vector<uint8_t> forced;
};

Partition find_features(const SurfaceMesh& input, const RemeshOptions& options,
                        const std::vector<double>& h, RemeshStats& stats) {
  Partition part;
  part.full_adj = build_adjacency(input);
  part.feature = sharp_feature_edges(input, part.full_adj, h, options.feature_angle_degrees);
  part.adj = part.full_adj;
  stats.feature_edges = 0;
  for (size_t he = 0; he < part.feature.size(); ++he)
    if (part.feature[he])
      part.adj.opposite[he] = TriangleAdjacency::kBoundary, ++stats.feature_edges;
  stats.feature_edges /= 2;
  part.options = options.partition;
  for (const std::array<double, 3>& x : options.fallback_at) {
    int32_t nearest = 0;
    double best = 1e300;
    for (size_t t = 0; t < input.num_triangles(); ++t) {
      const double d = norm(patch_centre(input, {int32_t(t)}) - x);
      if (d < best) best = d, nearest = int32_t(t);
    }
    part.forced_triangles.push_back(nearest);
  }
  return part;
}

/// Phase 2 (seed 2.1, Fig. 2 step 1): the partition of the input, cut
/// along the features, into patches whose map by options.param neither
/// folds nor crowds (part.patches and part.label).
Status partition_into_patches(const SurfaceMesh& input, const RemeshOptions& options,
                              Partition& part, RemeshStats& stats) {
  PatchMapFn map = [&](const SurfaceMesh& patch) -> Result<Parametrization> {
    switch (options.param) {
      case ParamMethod::kHarmonic:
        return map_to_disk(patch, DiskWeights::kHarmonic);
      case ParamMethod::kFloater:
        return map_to_disk(patch, DiskWeights::kMeanValue);
      default:
        return lscm(patch);
    }
  };
  PartitionStats pstats;
  auto patches = partition_for_maps(input, part.adj, map, part.options, &pstats);
  if (!patches.ok()) return patches.status();
  part.patches = std::move(patches).value();
  stats.bisections = pstats.bisections;
  stats.rejected_maps = pstats.rejected_maps;
  part.label.assign(input.num_triangles(), -1);
  for (size_t i = 0; i < part.patches.size(); ++i)
    for (int32_t t : part.patches[i].triangle_of) part.label[size_t(t)] = int32_t(i);
  part.forced.assign(part.patches.size(), 0);
  for (int32_t t : part.forced_triangles) part.forced[size_t(part.label[size_t(t)])] = 1;
  return Status::Ok();
}

/// Why phase 4 stopped: the patches that failed to mesh and their errors
/// (in patch order), or a cancellation (`status` cancelled), or nothing.
struct PatchFailure {
  Status status = Status::Ok();
  std::vector<std::pair<size_t, Status>> patches;
  bool ok() const { return status.ok() && patches.empty(); }
};

/// An edge of a patch's mesh inside the patch between two of its seam
/// samples (global vertex ids a < b), from one of its two triangles.
struct Chord {
  int32_t a = 0, b = 0, triangle = 0;
  size_t patch = 0;
};

/// Appends to `chords` the chords of the mesh `m` of patch `patch` (its
/// first `n_seam` vertices its boundary samples in loop order; `global`:
/// their wall ids; its triangles to become the wall's from
/// `first_triangle` on).
void note_chords(const SurfaceMesh& m, size_t patch, size_t n_seam,
                 const std::vector<int32_t>& global, size_t first_triangle,
                 std::vector<Chord>& chords) {
  for (size_t t = 0; t < m.num_triangles(); ++t)
    for (int k = 0; k < 3; ++k) {
      const size_t u = size_t(m.triangles[3 * t + size_t(k)]),
                   v = size_t(m.triangles[3 * t + size_t(k + 1) % 3]);
      if (u >= n_seam || v >= n_seam || (u + 1) % n_seam == v || (v + 1) % n_seam == u) continue;
      chords.push_back({std::min(global[u], global[v]), std::max(global[u], global[v]),
                        int32_t(first_triangle + t), patch});
    }
}

/// The end of phase 4: a chord that another patch's triangles use too
/// (an edge of more than two triangles) is split at its midpoint on the
/// input in the patch it crosses, so the wall stays manifold. Patches
/// meshed in the plane or by the fallback may join two seam samples inside
/// them; neighbours only share the seams.
void split_shared_chords(const SurfaceMesh& input, const TriangleAdjacency& adj,
                         const std::vector<Chord>& chords, SurfaceMesh& mesh, WallVertices& wall) {
  if (chords.empty()) return;
  std::unordered_map<uint64_t, int> uses;
  for (const Chord& c : chords) uses[edge_key(c.a, c.b)] = 0;
  for (size_t t = 0; t < mesh.num_triangles(); ++t)
    for (int k = 0; k < 3; ++k) {
      auto it = uses.find(
          edge_key(mesh.triangles[3 * t + size_t(k)], mesh.triangles[3 * t + size_t(k + 1) % 3]));
      if (it != uses.end()) ++it->second;
    }
  for (const Chord& c : chords) {
    // Each chord is noted from both its triangles: split from the one with
    // the directed edge (a, b), t = (a, b, x), whose neighbour across it in
    // the same patch is u = (b, a, y); into (a, m, x), (m, b, x), (b, m, y),
    // (m, a, y).
    if (uses[edge_key(c.a, c.b)] <= 2) continue;
    int32_t* T = &mesh.triangles[3 * size_t(c.triangle)];
    int k = 0;
    while (k < 3 && !(T[k] == c.a && T[(k + 1) % 3] == c.b)) ++k;
    if (k == 3) continue;
    const int32_t x = T[(k + 2) % 3];
    // Its partner: the triangle noted for the same chord with (b, a).
    int32_t partner = -1, y = -1;
    for (const Chord& d : chords) {
      if (d.a != c.a || d.b != c.b || d.patch != c.patch || d.triangle == c.triangle) continue;
      const int32_t* U = &mesh.triangles[3 * size_t(d.triangle)];
      for (int j = 0; j < 3; ++j)
        if (U[j] == c.b && U[(j + 1) % 3] == c.a) partner = d.triangle, y = U[(j + 2) % 3];
    }
    if (partner < 0) continue;
    const Vec3 mid = 0.5 * (at(mesh.points, c.a) + at(mesh.points, c.b));
    double p[3];
    const int32_t m = int32_t(wall.home.size());
    wall.home.push_back(project_near(mid.data(), wall.home[size_t(c.a)], input, adj, p));
    wall.fixed.push_back(kFree);
    mesh.points.insert(mesh.points.end(), p, p + 3);
    int32_t* U = &mesh.triangles[3 * size_t(partner)];
    T[0] = c.a, T[1] = m, T[2] = x;
    U[0] = c.b, U[1] = m, U[2] = y;
    mesh.triangles.insert(mesh.triangles.end(), {m, c.b, x, m, c.a, y});
  }
}

/// Phase 4 for patch `i` of `part`: meshed in its plane (mesh_mapped_patch),
/// else by the fallback (see mesh_patches), which then says why in `why`
/// (else empty); `ids` gets the seam samples of its boundary, in order.
Result<PatchMesh> mesh_one_patch(const Partition& part, size_t i, const Seams& seams,
                                 const std::vector<double>& h, const RemeshOptions& options,
                                 size_t splits, std::vector<int32_t>& ids, std::string& why) {
  const MappedPatch& p = part.patches[i];
  why.clear();
  auto boundary = patch_boundary(p, seams, ids);
  if (!boundary.ok()) return boundary.status();
  std::vector<double> local_h(p.vertex_of.size());
  for (size_t v = 0; v < local_h.size(); ++v) local_h[v] = h[size_t(p.vertex_of[v])];
  if (p.unmappable.empty() && !part.forced[i]) {
    auto planar = mesh_mapped_patch(p.mesh, p.map.uv, local_h, boundary.value(), options.patch);
    if (planar.ok() || (splits < options.max_splits && p.triangle_of.size() >= 4)) return planar;
    why = planar.message();
  } else {
    why = !p.unmappable.empty() ? p.unmappable : "the fallback was asked for";
  }
  auto fallback = isotropic_remesh_patch(p.mesh, local_h, boundary.value(), options.fallback);
  if (!fallback.ok()) {
    const Status failed = fallback.status().Prefixed(why + "; the fallback remesher failed too: ");
    why.clear();
    return failed;
  }
  return fallback;
}

/// Phase 4 (seed 2.1, Fig. 2 steps 2-4): each patch meshed in its plane at
/// the sizes `h` (one per input vertex) against the shared seam samples,
/// mapped back, and assembled into `mesh` by the sample ids; `wall` gets
/// home and fixed of every output vertex (the seams' first). A patch the
/// partition could not map, or asked for (Partition::forced), or whose
/// planar meshing fails after `splits` splits of failed patches (at
/// options.max_splits) or too small to split, is remeshed on its own
/// triangles instead (isotropic_remesh_patch) and listed in `fallbacks`
/// (`fallback_of`: their patches).
PatchFailure mesh_patches(const SurfaceMesh& input, const Partition& part, const Seams& seams,
                          const std::vector<double>& h, const RemeshOptions& options, size_t splits,
                          SurfaceMesh& mesh, WallVertices& wall,
                          std::vector<FallbackPatch>& fallbacks, std::vector<size_t>& fallback_of,
                          const ProgressFn& progress) {
  mesh.points = seams.points;
  mesh.triangles.clear();
  wall.home = seams.home;
  wall.fixed = seams.kind;
  fallbacks.clear();
  fallback_of.clear();
  // Batches of patches: within a batch the patches are meshed on the
  // threads (each depends only on its own input and the seams), then
  // assembled in patch order, so the wall does not depend on the thread
  // count; progress and cancellation between batches.
  constexpr size_t kBatch = 16;
  const size_t np = part.patches.size();
  std::vector<std::vector<int32_t>> ids(kBatch);
  std::vector<std::optional<Result<PatchMesh>>> meshed(kBatch);
  std::vector<std::string> fell_back(kBatch);  // why, when the fallback meshed it
  std::vector<double> fallback_seconds(kBatch);
  std::vector<Chord> chords;
  PatchFailure failure;
  for (size_t b0 = 0; b0 < np; b0 += kBatch) {
    if (!report_progress(progress, 0.2 + 0.6 * double(b0) / double(np), "meshing patches"))
      return {Status::Cancelled(), {}};
    const size_t nb = std::min(np - b0, kBatch);
    parallel_for(nb, 1, [&](size_t begin, size_t end) {
      for (size_t j = begin; j < end; ++j) {
        const auto t0 = std::chrono::steady_clock::now();
        meshed[j] = mesh_one_patch(part, b0 + j, seams, h, options, splits, ids[j], fell_back[j]);
        fallback_seconds[j] = seconds_since(t0);
      }
    });
    for (size_t j = 0; j < nb; ++j) {
      // Every patch is meshed, so that all those that fail are split at once;
      // after a failure the others are not assembled.
      const Result<PatchMesh>& pm = *meshed[j];
      if (!pm.ok()) failure.patches.emplace_back(b0 + j, pm.status());
      if (!failure.patches.empty()) continue;
      const MappedPatch& p = part.patches[b0 + j];
      if (!fell_back[j].empty()) {
        FallbackPatch f;
        f.place = patch_centre(input, p.triangle_of);
        f.input_triangles = p.triangle_of.size();
        f.reason = fell_back[j];
        f.splits = splits;
        f.seconds = fallback_seconds[j];
        fallbacks.push_back(std::move(f));
        fallback_of.push_back(b0 + j);
      }
      const PatchMesh& patch_mesh = pm.value();
      const size_t n_seam = ids[j].size();
      std::vector<int32_t> global(patch_mesh.mesh.num_vertices());
      for (size_t v = 0; v < global.size(); ++v) {
        if (v < n_seam) {
          global[v] = ids[j][v];
          continue;
        }
        global[v] = int32_t(wall.home.size());
        mesh.points.insert(mesh.points.end(), &patch_mesh.mesh.points[3 * v],
                           &patch_mesh.mesh.points[3 * v] + 3);
        wall.home.push_back(p.triangle_of[size_t(patch_mesh.home[v])]);
        wall.fixed.push_back(kFree);
      }
      note_chords(patch_mesh.mesh, b0 + j, n_seam, global, mesh.num_triangles(), chords);
      for (int32_t v : patch_mesh.mesh.triangles) mesh.triangles.push_back(global[size_t(v)]);
    }
  }
  if (!failure.patches.empty()) return failure;
  split_shared_chords(input, part.full_adj, chords, mesh, wall);
  return {};
}

/// The quality of the fallback patches (`fallbacks`, of the patches
/// `fallback_of`) in the finished wall `mesh` (homes `home` on `input`):
/// each output triangle counts for the patch holding the input point
/// nearest its centroid.
void measure_fallbacks(const SurfaceMesh& input, const Partition& part, const SurfaceMesh& mesh,
                       const std::vector<int32_t>& home, std::vector<FallbackPatch>& fallbacks,
                       const std::vector<size_t>& fallback_of) {
  if (fallbacks.empty()) return;
  std::vector<int32_t> slot(part.patches.size(), -1);
  for (size_t i = 0; i < fallback_of.size(); ++i) slot[fallback_of[i]] = int32_t(i);
  std::vector<double> sum(fallbacks.size(), 0);
  for (FallbackPatch& f : fallbacks) f.quality_min = 1, f.triangles = 0;
  for (size_t t = 0; t < mesh.num_triangles(); ++t) {
    const int32_t* T = &mesh.triangles[3 * t];
    const Vec3 centroid =
        (1.0 / 3.0) * (at(mesh.points, T[0]) + at(mesh.points, T[1]) + at(mesh.points, T[2]));
    double x[3];
    const int32_t on = project_near(centroid.data(), home[size_t(T[0])], input, part.full_adj, x);
    const int32_t i = slot[size_t(part.label[size_t(on)])];
    if (i < 0) continue;
    const double q = triangle_gamma(&mesh.points[3 * size_t(T[0])], &mesh.points[3 * size_t(T[1])],
                                    &mesh.points[3 * size_t(T[2])]);
    FallbackPatch& f = fallbacks[size_t(i)];
    f.quality_min = std::min(f.quality_min, q);
    sum[size_t(i)] += q;
    ++f.triangles;
  }
  for (size_t i = 0; i < fallbacks.size(); ++i) {
    if (fallbacks[i].triangles == 0) fallbacks[i].quality_min = 0;
    fallbacks[i].quality_mean =
        fallbacks[i].triangles ? sum[i] / double(fallbacks[i].triangles) : 0;
  }
}

/// After phase 4 failed on some patches: their triangles get a size limit
/// so that the next partition splits them (part.patches emptied), one
/// split more (stats.retries). An error after options.max_splits splits,
/// or for a patch too small to split (where the fallback failed too).
Status split_failed_patches(const SurfaceMesh& input, const RemeshOptions& options,
                            const PatchFailure& failure, Partition& part, RemeshStats& stats) {
  for (const auto& [patch, status] : failure.patches) {
    const std::vector<int32_t>& bad = part.patches[patch].triangle_of;
    if (stats.retries < options.max_splits && bad.size() >= 4) continue;
    // Where: the patch's centre; what helps: a surface with fewer folds
    // or creases at this size.
    const Vec3 centre = patch_centre(input, bad);
    return Status::Error("meshing a patch of " + std::to_string(bad.size()) +
                         " input triangles near " + point_text(centre) + " failed after " +
                         std::to_string(stats.retries) + " rounds of splits: " + status.message() +
                         "; the surface is too folded there for the size: smooth it "
                         "({smooth} 10), give a smaller {size}, or turn crease detection "
                         "off ({feature_angle} 180)")
        .WithRemedy({"smooth", {centre}, 10});
  }
  std::vector<int32_t>& limit = part.options.size_limit;
  if (limit.empty()) limit.assign(input.num_triangles(), 0);
  for (const auto& [patch, status] : failure.patches) {
    const std::vector<int32_t>& bad = part.patches[patch].triangle_of;
    for (int32_t t : bad) limit[size_t(t)] = int32_t(bad.size());
  }
  ++stats.retries;
  part.patches.clear();
  return Status::Ok();
}

/// The end of phase 4: vertices renumbered along a Hilbert curve and
/// triangles sorted by their smallest new vertex id (stable), so that
/// consecutive ids are near each other on the wall, as the optimizer's
/// sweeps and blocks want (patches are assembled seams first).
void renumber_along_curve(SurfaceMesh& mesh, WallVertices& wall) {
  const size_t n = mesh.num_vertices();
  std::vector<int32_t> order(n);
  for (size_t v = 0; v < n; ++v) order[v] = int32_t(v);
  hilbert_sort(mesh.points, order.data(), int64_t(n));
  std::vector<int32_t> renumber(n);
  std::vector<double> points(mesh.points.size());
  std::vector<int32_t> home(n);
  std::vector<uint8_t> fixed(n);
  for (size_t i = 0; i < n; ++i) {
    const size_t v = size_t(order[i]);
    renumber[v] = int32_t(i);
    std::copy_n(&mesh.points[3 * v], 3, &points[3 * i]);
    home[i] = wall.home[v];
    fixed[i] = wall.fixed[v];
  }
  const size_t nt = mesh.num_triangles();
  std::vector<std::pair<int32_t, int32_t>> by_first(nt);
  for (size_t t = 0; t < nt; ++t) {
    int32_t* T = &mesh.triangles[3 * t];
    for (int k = 0; k < 3; ++k) T[k] = renumber[size_t(T[k])];
    by_first[t] = {std::min({T[0], T[1], T[2]}), int32_t(t)};
  }
  std::sort(by_first.begin(), by_first.end());
  std::vector<int32_t> triangles(mesh.triangles.size());
  for (size_t i = 0; i < nt; ++i)
    std::copy_n(&mesh.triangles[3 * size_t(by_first[i].second)], 3, &triangles[3 * i]);
  mesh.points.swap(points);
  mesh.triangles.swap(triangles);
  wall.home.swap(home);
  wall.fixed.swap(fixed);
}

/// The opening and feature flags of `out` from `wall.fixed`.
void set_flags(const WallVertices& wall, RemeshedSurface& out) {
  out.on_opening.resize(wall.fixed.size());
  out.on_feature.resize(wall.fixed.size());
  for (size_t v = 0; v < wall.fixed.size(); ++v) {
    out.on_opening[v] = wall.fixed[v] == kOnOpening;
    out.on_feature[v] = wall.fixed[v] == kOnFeature;
  }
}

/// A wall after phases 2-5, before phase 6 pins it: the surface (mesh and
/// input_sizes; input_gaps measured when asked), its per-vertex data and
/// the patches the fallback meshed (`fallback_of`: their patch ids).
struct OptimizedWall {
  RemeshedSurface out;
  WallVertices wall;
  std::vector<FallbackPatch> fallbacks;
  std::vector<size_t> fallback_of;
};

/// Phases 2-4 at the sizes `sizes` (one per input vertex) on the features
/// of `part`; adds to `stats`.
Result<OptimizedWall> mesh_wall(const SurfaceMesh& input, const RemeshOptions& options,
                                std::vector<double> sizes, Partition& part, RemeshStats& stats,
                                const ProgressFn& progress) {
  OptimizedWall o;
  RemeshedSurface& out = o.out;
  WallVertices& wall = o.wall;
  out.input_sizes = std::move(sizes);
  const std::vector<double>& h = out.input_sizes;
  {
    std::vector<double> sorted = h;
    std::sort(sorted.begin(), sorted.end());
    stats.size_min = sorted.front();
    stats.size_max = sorted.back();
    stats.size_median = sorted[sorted.size() / 2];
  }
  if (!report_progress(progress, 0.1, "partitioning")) return Status::Cancelled();
  auto t0 = std::chrono::steady_clock::now();
  // Phases 2-4, again with the failing patch forced to split if its planar
  // boundary crosses itself (a coarse resampling of a tortuous boundary).
  for (;;) {
    if (part.patches.empty()) {
      const Status partitioned = partition_into_patches(input, options, part, stats);
      if (!partitioned.ok()) return partitioned;
      stats.seconds_partition += seconds_since(t0);
    }
    stats.patches = part.patches.size();
    // Phase 3: seams.
    t0 = std::chrono::steady_clock::now();
    const Seams seams = discretize_seams(input, part.full_adj, part.feature, part.label, h);
    stats.seam_points = seams.home.size();
    // Phase 4: each patch in its plane.
    const PatchFailure failure = mesh_patches(input, part, seams, h, options, stats.retries,
                                              out.mesh, wall, o.fallbacks, o.fallback_of, progress);
    if (failure.ok()) break;
    if (failure.status.cancelled()) return failure.status;
    const Status split = split_failed_patches(input, options, failure, part, stats);
    if (!split.ok()) return split;
    t0 = std::chrono::steady_clock::now();
  }
  renumber_along_curve(out.mesh, wall);
  set_flags(wall, out);
  stats.seconds_mesh += seconds_since(t0);
  return o;
}

/// Phase 5 on `o` (from mesh_wall, its sizes in o.out.input_sizes): swaps
/// and smoothing on the input surface (seed section 3); adds to `stats`.
Status optimize_wall(const SurfaceMesh& input, const RemeshOptions& options, const Partition& part,
                     OptimizedWall& o, RemeshStats& stats, const ProgressFn& progress) {
  if (!report_progress(progress, 0.85, "optimizing")) return Status::Cancelled();
  const auto t0 = std::chrono::steady_clock::now();
  WallVertices& wall = o.wall;
  wall.size = output_sizes(input, wall.home, o.out.input_sizes);
  const auto ostats = optimize_on_surface(o.out.mesh, wall, input, part.adj, options.optimize);
  stats.collapses = ostats.collapses;
  stats.swaps = ostats.swaps;
  stats.moves = ostats.moves;
  set_flags(wall, o.out);
  stats.seconds_optimize += seconds_since(t0);
  return Status::Ok();
}

/// Phases 2-5 (mesh_wall, optimize_wall).
Result<OptimizedWall> mesh_and_optimize(const SurfaceMesh& input, const RemeshOptions& options,
                                        std::vector<double> sizes, Partition& part,
                                        RemeshStats& stats, const ProgressFn& progress) {
  auto o = mesh_wall(input, options, std::move(sizes), part, stats, progress);
  if (!o.ok()) return o;
  const Status optimized = optimize_wall(input, options, part, o.value(), stats, progress);
  if (!optimized.ok()) return optimized;
  return o;
}

/// Phase 6 on `o` (fidelity measured against `asked`, one per input
/// vertex): output vertices pinned onto far input vertices; then the
/// fallback patches' quality and the per-vertex data into the surface.
RemeshedSurface pin_and_finish(const SurfaceMesh& input, const RemeshOptions& options,
                               const std::vector<double>& asked, const Partition& part,
                               OptimizedWall&& o, RemeshStats& stats) {
  RemeshedSurface out = std::move(o.out);
  WallVertices& wall = o.wall;
  const auto t0 = std::chrono::steady_clock::now();
  pin_far_input_vertices(input, part.adj, out.input_sizes, asked, options, out.mesh, wall,
                         out.input_gaps, stats);
  stats.seconds_fidelity += seconds_since(t0);
  measure_fallbacks(input, part, out.mesh, wall.home, o.fallbacks, o.fallback_of);
  stats.fallback_patches = std::move(o.fallbacks);
  out.home = std::move(wall.home);
  out.sizes = std::move(wall.size);
  set_flags(wall, out);
  return out;
}

/// Phases 2-6 at the sizes `sizes` (one per input vertex) on the features
/// of `part`, fidelity measured against `asked` (one per input vertex);
/// adds to `stats`.
Result<RemeshedSurface> remesh_at_sizes(const SurfaceMesh& input, const RemeshOptions& options,
                                        std::vector<double> sizes, const std::vector<double>& asked,
                                        Partition& part, RemeshStats& stats,
                                        const ProgressFn& progress) {
  auto o = mesh_and_optimize(input, options, std::move(sizes), part, stats, progress);
  if (!o.ok()) return o.status();
  return pin_and_finish(input, options, asked, part, std::move(o).value(), stats);
}

/// Phase 7 before phases 5 and 6 (RemeshOptions::fidelity_probe_rounds):
/// the wall `o` just meshed at the sizes `h` (phases 2-4) probes its own
/// chord error. Where it leaves input vertices beyond fidelity times
/// `asked`, worth a size round, the sizes around them are made finer
/// (finer_where_far) and phases 2-4 run again on the same partition, so
/// that few vertices are left for the pins. A finer wall replaces `o` (and
/// `h`) unless its edges drift from the asked size
/// (RemeshOptions::fidelity_size_drift). Then phase 5 on `o`. The meshing
/// of the walls replaced (the first one took `probe_seconds`, counted in
/// stats.seconds_mesh) counts as fidelity's. Returns an error only when
/// cancelled.
Status size_by_chord_error(const SurfaceMesh& input, const RemeshOptions& options,
                           const std::vector<double>& asked, Partition& part, OptimizedWall& o,
                           std::vector<double>& h, double probe_seconds, RemeshStats& stats,
                           const ProgressFn& progress) {
  std::optional<PointKdTree> tree;
  const PointCloud cloud{input.points};
  for (int round = 0; round < options.fidelity_probe_rounds; ++round) {
    const auto t0 = std::chrono::steady_clock::now();
    const std::vector<double> gaps = distances_to_surface(o.out.mesh, input.points, true).per_point;
    const std::vector<int32_t> far = far_input_vertices(gaps, asked, options.fidelity);
    if (!worth_size_round(far.size(), o.out.mesh.num_vertices(), options)) {
      stats.seconds_fidelity += seconds_since(t0);
      break;
    }
    if (!tree) {
      tree.emplace(3, cloud);
      tree->buildIndex();
    }
    std::vector<double> finer = finer_where_far(input, *tree, options, h, asked, far, gaps);
    stats.seconds_fidelity += seconds_since(t0);
    RemeshStats next = stats;
    auto again = mesh_wall(input, options, finer, part, next, progress);
    if (!again.ok() && again.cancelled()) return again.status();
    const double seconds = next.seconds_mesh - stats.seconds_mesh;
    const bool kept =
        again.ok() &&
        edge_ratios(again.value().out, output_sizes(input, again.value().wall.home, asked))[1] >=
            1 - options.fidelity_size_drift;
    if (!kept) {
      stats.seconds_partition = next.seconds_partition;
      stats.seconds_fidelity += seconds;
      break;
    }
    // The wall replaced was the price of fidelity.
    o = std::move(again).value();
    h = std::move(finer);
    stats = next;
    stats.seconds_mesh -= seconds;
    stats.seconds_fidelity += probe_seconds;
    probe_seconds = seconds;
    ++stats.fidelity_size_rounds;
  }
  return optimize_wall(input, options, part, o, stats, progress);
}

/// Phases 2-7 on `input` at the sizes `asked` (one per input vertex).
Result<RemeshedSurface> remesh_at(const SurfaceMesh& input, const RemeshOptions& options,
                                  const std::vector<double>& asked, RemeshStats& stats,
                                  const ProgressFn& progress) {
  auto t0 = std::chrono::steady_clock::now();
  Partition part = find_features(input, options, asked, stats);
  stats.seconds_partition += seconds_since(t0);
  // Phases 2-4, finer sizes where the wall's chord error calls for them
  // (and phases 2-4 again), phase 5, then phase 6.
  const bool sized = options.fidelity_rounds > 0 && options.fidelity_size_rounds > 0 &&
                     options.fidelity_probe_rounds > 0;
  const double mesh_seconds = stats.seconds_mesh;
  auto optimized = mesh_wall(input, options, asked, part, stats, progress);
  if (!optimized.ok()) return optimized.status();
  std::vector<double> h = asked;
  const Status sized_ok =
      sized ? size_by_chord_error(input, options, asked, part, optimized.value(), h,
                                  stats.seconds_mesh - mesh_seconds, stats, progress)
            : optimize_wall(input, options, part, optimized.value(), stats, progress);
  if (!sized_ok.ok()) return sized_ok;
  Result<RemeshedSurface> result =
      pin_and_finish(input, options, asked, part, std::move(optimized).value(), stats);
  // Phase 7: where more than a few input vertices stay far from the output
  // (a bend tighter than h can follow, coarse facets), a finer size within
  // h of each, and phases 3-6 again on the same partition.
  const Status refined = refine_size_where_far(
      input, options, h, asked, result, stats,
      [&](const std::vector<double>& finer, RemeshStats& round_stats) {
        return remesh_at_sizes(input, options, finer, asked, part, round_stats, progress);
      });
  if (!refined.ok()) return refined;
  if (result.ok()) {
    // How well the edges follow the asked size (the finer sizes of the
    // size rounds are the surface's own business).
    const std::array<double, 3> ratios =
        edge_ratios(result.value(), output_sizes(input, result.value().home, asked));
    stats.edge_ratio_p10 = ratios[0];
    stats.edge_ratio_median = ratios[1];
    stats.edge_ratio_p90 = ratios[2];
  }
  return result;
}

/// Whether `input` has far more triangles than the sizes `asked` call for
/// (RemeshOptions::decimate ... decimate_ratio).
bool oversampled(const SurfaceMesh& input, const RemeshOptions& options,
                 const std::vector<double>& asked) {
  return options.decimate && input.num_triangles() >= options.decimate_min_triangles &&
         double(input.num_triangles()) > options.decimate_ratio * estimate_triangles(input, asked);
}

/// Phase 1b: `input` decimated within the options' share of the sizes
/// `asked` (one per input vertex).
DecimatedSurface decimate_for_sizes(const SurfaceMesh& input, const RemeshOptions& options,
                                    const std::vector<double>& asked) {
  std::vector<double> max_error(asked.size()), max_edge(asked.size());
  for (size_t v = 0; v < asked.size(); ++v) {
    max_error[v] = options.decimate_error * asked[v];
    max_edge[v] = options.decimate_edge * asked[v];
  }
  return decimate_surface(input, {.max_error = max_error, .max_edge = max_edge});
}

}  // namespace

std::string fallback_warning(const FallbackPatch& f, std::string_view unit) {
  std::string why = f.reason;
  if (f.splits > 0) why = "after " + std::to_string(f.splits) + " rounds of splits: " + why;
  return "a patch of " + std::to_string(f.input_triangles) + " input triangles near " +
         point_text(f.place) + " " + std::string(unit) + " could not be meshed through its map (" +
         why + "): it was remeshed on the surface itself instead, " + std::to_string(f.triangles) +
         " triangles there, gamma_k min " + number_text(f.quality_min, 3) + ", mean " +
         number_text(f.quality_mean, 3) + "; the surface is likely folded or crossing itself there";
}

Result<RemeshedSurface> remesh_surface(const SurfaceMesh& input, const RemeshOptions& options,
                                       RemeshStats* stats_out, const ProgressFn& progress) {
  RemeshStats stats;
  auto t0 = std::chrono::steady_clock::now();
  // Phase 1: size field (seed eq. 11).
  auto sizes = options.size.mode == SizeMode::kPerCircumference &&
                       options.radius.size() == input.num_vertices()
                   ? vertex_sizes(input, options.size, options.radius)
                   : vertex_sizes(input, options.size);
  if (!sizes.ok()) return sizes.status();
  const std::vector<double> asked = std::move(sizes).value();
  stats.seconds_size = seconds_since(t0);
  if (options.max_triangles > 0) {
    const double estimate = estimate_triangles(input, asked);
    if (estimate > options.max_triangles) {
      char buf[160];
      std::snprintf(buf, sizeof buf,
                    "makes about %.3g triangles on the wall, more than the element budget "
                    "({max_elements} %.0f) allows: ask for larger elements",
                    estimate, options.max_triangles);
      return Status::BadOption(
          options.size.mode == SizeMode::kUniform ? "size" : "per_circumference", buf);
    }
  }
  if (!oversampled(input, options, asked)) {
    auto result = remesh_at(input, options, asked, stats, progress);
    if (stats_out) *stats_out = stats;
    return result;
  }
  if (!report_progress(progress, 0.05, "decimating")) return Status::Cancelled();
  t0 = std::chrono::steady_clock::now();
  const DecimatedSurface decimated = decimate_for_sizes(input, options, asked);
  stats.seconds_decimate = seconds_since(t0);
  // Phases 2-7 on the decimated surface, at the sizes of its vertices.
  stats.decimated_triangles = decimated.mesh.num_triangles();
  std::vector<double> kept_asked(decimated.input_vertex.size());
  for (size_t v = 0; v < kept_asked.size(); ++v)
    kept_asked[v] = asked[size_t(decimated.input_vertex[v])];
  auto result = remesh_at(decimated.mesh, options, kept_asked, stats, progress);
  if (result.ok()) {
    // Every output vertex onto the input (it lay on the decimated surface,
    // within about decimate_error h of it), homed there; then sizes and gaps
    // of every input vertex, the gaps measured again.
    t0 = std::chrono::steady_clock::now();
    RemeshedSurface& out = result.value();
    const TriangleBvh bvh = build_triangle_bvh(input);
    for (size_t v = 0; v < out.home.size(); ++v) {
      const SurfacePoint on = closest_surface_point(input, bvh, &out.mesh.points[3 * v]);
      put(out.mesh.points, int32_t(v), on.point);
      out.home[v] = on.triangle;
    }
    out.input_sizes = asked;
    out.input_gaps = distances_to_surface(out.mesh, input.points, true).per_point;
    count_gaps(out.input_gaps, asked, options.fidelity, stats);
    stats.seconds_fidelity += seconds_since(t0);
  }
  if (stats_out) *stats_out = stats;
  return result;
}

}  // namespace vm
