// Whole-surface remeshing (Marchandise et al., sections 2.1 and 3) in
// phases: size field; partition into mapped patches; seams (the patch
// boundaries and the openings) cut into curves between corners and each
// curve resampled once in 3D; every patch meshed in its plane against the
// shared samples; assembly by sample ids; optimization on the input;
// fidelity: output vertices pinned onto far input vertices.
#include "core/surface/remesh_surface.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <unordered_map>

#include "core/geom/point_kdtree.h"
#include "core/geom/vec3.h"
#include "core/mesh/boundary_loops.h"
#include "core/mesh/self_intersection.h"
#include "core/mesh/star_visibility.h"
#include "core/mesh/surface_distance.h"
#include "core/param/fixed_boundary_map.h"
#include "core/quality/triangle_quality.h"
#include "core/surface/element_estimate.h"
#include "core/surface/pin_to_input.h"
#include "core/surface/resample_curve.h"
#include "core/surface/sharp_features.h"
#include "core/util/stage_timer.h"

namespace vm {
namespace {

uint64_t edge_key(int32_t a, int32_t b) {
  if (a > b) std::swap(a, b);
  return (uint64_t(uint32_t(a)) << 32) | uint32_t(b);
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

/// The target size at each output vertex: the mean of `h` (one per input
/// vertex) over its home triangle.
std::vector<double> output_sizes(const SurfaceMesh& input, const std::vector<int32_t>& home,
                                 const std::vector<double>& h) {
  std::vector<double> size(home.size());
  for (size_t v = 0; v < size.size(); ++v) {
    const int32_t* T = &input.triangles[3 * size_t(home[v])];
    size[v] = (h[size_t(T[0])] + h[size_t(T[1])] + h[size_t(T[2])]) / 3;
  }
  return size;
}

/// Edge length / mean target size of its ends (`size`: one per output
/// vertex), each edge once: 10th percentile, median, 90th percentile.
std::array<double, 3> edge_ratios(const RemeshedSurface& out, const std::vector<double>& size) {
  std::vector<double> ratio;
  ratio.reserve(out.mesh.triangles.size() / 2);
  for (size_t t = 0; t < out.mesh.num_triangles(); ++t)
    for (int k = 0; k < 3; ++k) {
      const int32_t a = out.mesh.triangles[3 * t + size_t(k)],
                    b = out.mesh.triangles[3 * t + size_t((k + 1) % 3)];
      if (a > b && !(out.on_opening[size_t(a)] && out.on_opening[size_t(b)])) continue;
      const double* pa = &out.mesh.points[3 * size_t(a)];
      const double* pb = &out.mesh.points[3 * size_t(b)];
      const double len =
          std::sqrt((pa[0] - pb[0]) * (pa[0] - pb[0]) + (pa[1] - pb[1]) * (pa[1] - pb[1]) +
                    (pa[2] - pb[2]) * (pa[2] - pb[2]));
      ratio.push_back(len / (0.5 * (size[size_t(a)] + size[size_t(b)])));
    }
  if (ratio.empty()) return {0, 0, 0};
  auto at = [&](double q) {
    auto it = ratio.begin() + std::ptrdiff_t(q * double(ratio.size() - 1));
    std::nth_element(ratio.begin(), it, ratio.end());
    return *it;
  };
  return {at(0.1), at(0.5), at(0.9)};
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
  return part;
}

/// A vertex whose star_visibility is below this is a needle (no boundary
/// layer could grow from it).
constexpr double kNeedle = 0.05;

/// Phase 6: output vertices pinned onto the input vertices farther than
/// options.fidelity h from the output (pin_to_input; h: `asked`, the size
/// asked for, one per input vertex, which the finer sizes of size rounds do
/// not change), then a few optimization passes around them; pins that cost
/// quality are freed, and a round is undone if the quality floors still
/// fail, or if it made a self-intersection or a needle. Updates out (mesh,
/// home, input_gaps), fixed and out_size (one per output vertex) and the
/// fidelity statistics.
void pin_far_input_vertices(const SurfaceMesh& input, const TriangleAdjacency& adj,
                            const RemeshOptions& options, const std::vector<double>& asked,
                            RemeshedSurface& out, std::vector<uint8_t>& fixed,
                            std::vector<double>& out_size, RemeshStats& stats) {
  const std::vector<double>& h = out.input_sizes;
  SurfaceOptimizeOptions again = options.optimize;
  again.passes = options.fidelity_passes;
  again.valence_passes = std::min(again.valence_passes, options.fidelity_passes);
  std::vector<uint8_t> given_up(input.num_vertices(), 0);
  std::vector<int32_t> pin_of(fixed.size(), -1);  // per output vertex: its input vertex
  PinSlack slack;
  slack.pin_of = &pin_of;
  slack.input_h = &h;
  slack.slack = options.fidelity_pin_slack * options.fidelity;
  // The vertices whose flag differs from `before` (or are new) and their
  // neighbors: where a fidelity round changed the mesh.
  auto around_changes = [&](const std::vector<uint8_t>& before) {
    std::vector<uint8_t> flag(fixed.size(), 0);
    for (size_t t = 0; t < out.mesh.num_triangles(); ++t) {
      const int32_t* T = &out.mesh.triangles[3 * t];
      bool changed = false;
      for (int c = 0; c < 3; ++c)
        changed |= size_t(T[c]) >= before.size() || before[size_t(T[c])] != fixed[size_t(T[c])];
      if (changed)
        for (int c = 0; c < 3; ++c) flag[size_t(T[c])] = 1;
    }
    return flag;
  };
  // The last surface that held the floors (first the one before pinning),
  // restored when a round is undone.
  struct Kept {
    SurfaceMesh mesh;
    std::vector<int32_t> home;
    std::vector<uint8_t> fixed;
    std::vector<int32_t> pin_of;
    size_t pinned = 0;
  } kept;
  // The floors: the seed's, or the quality before pinning if lower; and
  // no more self-intersections or needles than before pinning.
  double floor_min = 0, floor_mean = 0;
  size_t crossings = 0, needles = 0;
  // Self-intersecting pairs of the kept surface, when known exactly (-1:
  // not counted).
  int64_t kept_pairs = -1;
  auto count_needles = [&] {
    const std::vector<double> seen = star_visibility(out.mesh);
    return size_t(std::count_if(seen.begin(), seen.end(), [](double c) { return c < kNeedle; }));
  };
  auto holds = [&] {
    const QualityStats q = quality_stats(triangle_qualities(out.mesh));
    return q.min >= floor_min && q.mean >= floor_mean;
  };
  // Pairs of unchanged triangles are the kept surface's: when it had
  // none, only pairs with a changed triangle can be new.
  auto clean = [&] {
    if (count_needles() > needles) return false;
    if (crossings > 0) return find_self_intersections(out.mesh, 0).pairs <= crossings;
    return find_self_intersections_of(out.mesh, changed_triangles(kept.mesh, out.mesh), 0).pairs ==
           0;
  };
  auto keep = [&] { kept = {out.mesh, out.home, fixed, pin_of, stats.fidelity_pinned}; };
  auto restore = [&] {
    out.mesh = kept.mesh;
    out.home = kept.home;
    fixed = kept.fixed;
    pin_of = kept.pin_of;
    out_size = output_sizes(input, out.home, h);
    stats.fidelity_pinned = kept.pinned;
    stats.fidelity_reverted = true;
  };
  // The input vertices' distances to the output; returns how many are
  // beyond options.fidelity h (the asked h).
  auto measure_gaps = [&] {
    out.input_gaps = distances_to_surface(out.mesh, input.points, true).per_point;
    stats.max_input_gap = 0;
    stats.input_gap_vertices = 0;
    size_t far = 0;
    for (size_t v = 0; v < asked.size(); ++v) {
      const double rel = out.input_gaps[v] / asked[v];
      stats.max_input_gap = std::max(stats.max_input_gap, rel);
      stats.input_gap_vertices += rel > kReportedGap;
      far += rel > options.fidelity;
    }
    return far;
  };
  // A few optimization passes where the flags changed since `before`.
  auto relax = [&](const std::vector<uint8_t>& before) {
    out_size = output_sizes(input, out.home, h);
    const auto more = optimize_on_surface(out.mesh, out.home, fixed, out_size, input, adj, again,
                                          around_changes(before), &slack);
    stats.collapses += more.collapses;
    stats.swaps += more.swaps;
    stats.moves += more.moves;
  };
  // Frees the pins of triangles below min_gamma, then relaxes around them.
  auto unpin_and_relax = [&](double min_gamma) {
    const std::vector<uint8_t> before = fixed;
    const size_t freed = unpin_poor(out.mesh, fixed, pin_of, min_gamma, given_up);
    stats.fidelity_pinned -= freed;
    if (freed > 0) relax(before);
    return freed;
  };
  // The last rounds retry every vertex left far, accepting poorer
  // triangles around the pins (the floors still hold).
  const int rounds =
      options.fidelity_rounds + (options.fidelity_rounds > 0 ? options.fidelity_last_rounds : 0);
  // No size round may follow on a large wall: its last rounds accept
  // triangles down to the floor.
  const bool large_wall = out.mesh.num_vertices() > options.fidelity_small_surface;
  for (int round = 0;; ++round) {
    const size_t far = measure_gaps();
    // Noise everywhere (more pins than a share of the output's vertices)
    // would cost more quality than the floors allow: not tried.
    if (far == 0 || round >= rounds ||
        (round == 0 && double(far) > options.fidelity_max_share * double(out.mesh.num_vertices())))
      break;
    const double min_quality =
        round < options.fidelity_rounds ? options.fidelity_min_quality
        : large_wall ? std::min(options.fidelity_last_min_quality, options.fidelity_floor_min)
                     : options.fidelity_last_min_quality;
    if (round == options.fidelity_rounds) std::fill(given_up.begin(), given_up.end(), 0);
    if (round == 0) {
      const QualityStats q0 = quality_stats(triangle_qualities(out.mesh));
      floor_min = std::min(q0.min, options.fidelity_floor_min);
      floor_mean = std::min(q0.mean, options.fidelity_floor_mean);
      crossings = find_self_intersections(out.mesh, 0).pairs;
      kept_pairs = int64_t(crossings);
      needles = count_needles();
      keep();
    }
    const std::vector<uint8_t> before = fixed;
    const PinStats pinned = pin_to_input(out.mesh, out.home, fixed, pin_of, input, asked,
                                         out.input_gaps, options.fidelity, given_up);
    if (pinned.pinned == 0) {
      // Nothing left to try at this quality: on to the last rounds.
      if (round < options.fidelity_rounds) {
        round = options.fidelity_rounds - 1;
        continue;
      }
      break;
    }
    ++stats.fidelity_rounds;
    stats.fidelity_pinned += pinned.pinned;
    relax(before);
    // Quality first: pins left in poor triangles are freed and the mesh
    // relaxes around them again (pins only decrease, so this ends).
    for (int step = 0; step < 8 && unpin_and_relax(min_quality) > 0; ++step) {
    }
    // Then the quality floors: pins of ever better triangles are freed
    // until they hold; else, or if the round made a self-intersection or a
    // needle, it is undone (the pins freed stay given up, so the next
    // round tries the others).
    bool ok = holds();
    for (double strict = min_quality + 0.05; !ok && strict < 1; strict += 0.05)
      if (unpin_and_relax(strict) > 0) ok = holds();
    if (ok && clean()) {
      keep();
      // clean() allows no new pair: exact when there was none.
      kept_pairs = crossings == 0 ? 0 : -1;
    } else {
      restore();
    }
  }
  stats.self_intersections = kept_pairs;
}

/// Phases 2-6 at the sizes `sizes` (one per input vertex) on the features
/// of `part`, fidelity measured against `asked` (one per input vertex);
/// adds to `stats`.
Result<RemeshedSurface> remesh_at_sizes(const SurfaceMesh& input, const RemeshOptions& options,
                                        std::vector<double> sizes, const std::vector<double>& asked,
                                        Partition& part, RemeshStats& stats,
                                        const ProgressFn& progress) {
  RemeshedSurface out;
  out.input_sizes = std::move(sizes);
  const std::vector<double>& h = out.input_sizes;
  {
    std::vector<double> sorted = h;
    std::sort(sorted.begin(), sorted.end());
    stats.size_min = sorted.front();
    stats.size_max = sorted.back();
    stats.size_median = sorted[sorted.size() / 2];
  }
  stats.fidelity_rounds = stats.fidelity_pinned = 0;
  stats.fidelity_reverted = false;
  stats.self_intersections = -1;
  if (!report_progress(progress, 0.1, "partitioning")) return Status::Cancelled();
  auto t0 = std::chrono::steady_clock::now();
  const TriangleAdjacency& adj = part.adj;
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
  // Phases 2-4, again with the failing patch forced to split if its planar
  // boundary crosses itself (a coarse resampling of a tortuous boundary).
  std::vector<uint8_t> fixed;  // per output vertex: kFree, kOnOpening or kOnFeature
  for (;;) {
    if (part.patches.empty()) {
      PartitionStats pstats;
      auto patches = partition_for_maps(input, adj, map, part.options, &pstats);
      if (!patches.ok()) return patches.status();
      part.patches = std::move(patches).value();
      stats.bisections = pstats.bisections;
      stats.rejected_maps = pstats.rejected_maps;
      part.label.assign(input.num_triangles(), -1);
      for (size_t i = 0; i < part.patches.size(); ++i)
        for (int32_t t : part.patches[i].triangle_of) part.label[size_t(t)] = int32_t(i);
      stats.seconds_partition += seconds_since(t0);
    }
    stats.patches = part.patches.size();

    // Phase 3: seams.
    t0 = std::chrono::steady_clock::now();
    Seams seams = discretize_seams(input, part.full_adj, part.feature, part.label, h);
    stats.seam_points = seams.home.size();
    out.mesh.points = seams.points;
    out.mesh.triangles.clear();
    out.home = seams.home;
    fixed = seams.kind;

    // Phase 4: each patch in its plane, assembled by the shared sample ids.
    std::vector<int32_t> ids;
    Status failed = Status::Ok();
    size_t failed_patch = 0;
    for (size_t i = 0; i < part.patches.size() && failed.ok(); ++i) {
      const MappedPatch& p = part.patches[i];
      if (!report_progress(progress, 0.2 + 0.6 * double(i) / double(stats.patches),
                           "meshing patches"))
        return Status::Cancelled();
      auto boundary = patch_boundary(p, seams, ids);
      std::vector<double> local_h(p.vertex_of.size());
      for (size_t v = 0; v < local_h.size(); ++v) local_h[v] = h[size_t(p.vertex_of[v])];
      auto pm = boundary.ok()
                    ? mesh_mapped_patch(p.mesh, p.map.uv, local_h, boundary.value(), options.patch)
                    : Result<PatchMesh>(boundary.status());
      if (!pm.ok()) {
        failed = pm.status();
        failed_patch = i;
        break;
      }
      const PatchMesh& mesh = pm.value();
      const size_t nb = ids.size();
      std::vector<int32_t> global(mesh.mesh.num_vertices());
      for (size_t v = 0; v < global.size(); ++v) {
        if (v < nb) {
          global[v] = ids[v];
          continue;
        }
        global[v] = int32_t(out.home.size());
        out.mesh.points.insert(out.mesh.points.end(), &mesh.mesh.points[3 * v],
                               &mesh.mesh.points[3 * v] + 3);
        out.home.push_back(p.triangle_of[size_t(mesh.home[v])]);
        fixed.push_back(kFree);
      }
      for (int32_t v : mesh.mesh.triangles) out.mesh.triangles.push_back(global[size_t(v)]);
    }
    if (failed.ok()) break;
    const std::vector<int32_t> bad = part.patches[failed_patch].triangle_of;
    if (stats.retries >= 16 || bad.size() < 4) {
      // Where: the patch's centre; what helps: a surface with fewer folds
      // or creases at this size.
      Vec3 centre{0, 0, 0};
      for (int32_t t : bad)
        for (int k = 0; k < 3; ++k)
          centre = centre + (1.0 / (3.0 * double(bad.size()))) *
                                at(input.points, input.triangles[3 * size_t(t) + size_t(k)]);
      return Status::Error("meshing a patch of " + std::to_string(bad.size()) +
                           " input triangles near " + point_text(centre) +
                           " failed after " + std::to_string(stats.retries) +
                           " splits: " + failed.message() +
                           "; the surface is too folded there for the size: smooth it "
                           "({smooth} 10), give a smaller {size}, or turn crease detection "
                           "off ({feature_angle} 180)");
    }
    std::vector<int32_t>& limit = part.options.size_limit;
    if (limit.empty()) limit.assign(input.num_triangles(), 0);
    for (int32_t t : bad) limit[size_t(t)] = int32_t(bad.size());
    ++stats.retries;
    part.patches.clear();
    t0 = std::chrono::steady_clock::now();
  }
  stats.seconds_mesh += seconds_since(t0);
  if (!report_progress(progress, 0.85, "optimizing")) return Status::Cancelled();

  // Phase 5: swaps and smoothing on the input surface.
  t0 = std::chrono::steady_clock::now();
  std::vector<double> out_size = output_sizes(input, out.home, h);
  const auto ostats =
      optimize_on_surface(out.mesh, out.home, fixed, out_size, input, adj, options.optimize);
  stats.collapses = ostats.collapses;
  stats.swaps = ostats.swaps;
  stats.moves = ostats.moves;
  stats.seconds_optimize += seconds_since(t0);

  // Phase 6: fidelity.
  t0 = std::chrono::steady_clock::now();
  pin_far_input_vertices(input, adj, options, asked, out, fixed, out_size, stats);
  stats.seconds_fidelity += seconds_since(t0);
  out.sizes = out_size;
  out.on_opening.resize(fixed.size());
  out.on_feature.resize(fixed.size());
  for (size_t v = 0; v < fixed.size(); ++v) {
    out.on_opening[v] = fixed[v] == kOnOpening;
    out.on_feature[v] = fixed[v] == kOnFeature;
  }
  return out;
}

}  // namespace

Result<RemeshedSurface> remesh_surface(const SurfaceMesh& input, const RemeshOptions& options,
                                       RemeshStats* stats_out, const ProgressFn& progress) {
  RemeshStats stats;
  auto t0 = std::chrono::steady_clock::now();
  // Phase 1: size field.
  auto sizes = vertex_sizes(input, options.size);
  if (!sizes.ok()) return sizes.status();
  std::vector<double> h = std::move(sizes).value();
  const std::vector<double> asked = h;
  stats.seconds_size = seconds_since(t0);
  if (options.max_triangles > 0) {
    const double estimate = estimate_triangles(input, h);
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
  t0 = std::chrono::steady_clock::now();
  Partition part = find_features(input, options, h, stats);
  stats.seconds_partition = seconds_since(t0);
  auto result = remesh_at_sizes(input, options, h, asked, part, stats, progress);
  // Phase 7: where more than a few input vertices stay far from the output
  // (a bend tighter than h can follow, coarse facets), a finer size within
  // h of each (RemeshOptions::fidelity_size_rounds), and phases 3-6 again
  // on the same partition. Not when they are everywhere (noise: the surface
  // smooths over it).
  const PointCloud cloud{input.points};
  PointKdTree tree(3, cloud);
  if (options.fidelity_size_rounds > 0) tree.buildIndex();
  // The input vertices beyond fidelity h, given their gaps.
  auto far_vertices = [&](const std::vector<double>& gaps) {
    std::vector<int32_t> far;
    for (size_t v = 0; v < asked.size(); ++v)
      if (gaps[v] > options.fidelity * asked[v]) far.push_back(int32_t(v));
    return far;
  };
  // Each round refines the last one's sizes; the surface kept is the one
  // with the fewest far vertices (meshing is not monotone: a round can
  // leave a few more than the one before), `result` and `stats`.
  std::vector<double> gaps =
      result.ok() ? result.value().input_gaps : std::vector<double>(asked.size(), 0);
  size_t vertices = result.ok() ? result.value().mesh.num_vertices() : 0;
  size_t best_far = far_vertices(gaps).size();
  RemeshStats latest = stats;
  for (int round = 0; round < options.fidelity_size_rounds && result.ok(); ++round) {
    t0 = std::chrono::steady_clock::now();
    const std::vector<int32_t> far = far_vertices(gaps);
    const double share = double(far.size()) / double(vertices);
    if (far.empty() || share > options.fidelity_noise_share ||
        (vertices > options.fidelity_small_surface && !(share > options.fidelity_size_share)))
      break;
    std::vector<double> finer = h;
    std::vector<std::pair<uint32_t, double>> near;
    const nanoflann::SearchParams unsorted(32, 0, false);
    for (int32_t v : far) {
      // A chord's gap from a bend grows as h^2.
      const double rel = gaps[size_t(v)] / asked[size_t(v)];
      const double target =
          std::max(h[size_t(v)] * std::clamp(std::sqrt(0.8 * options.fidelity / rel), 0.5, 0.9),
                   options.size.size_min);
      tree.radiusSearch(&input.points[3 * size_t(v)], h[size_t(v)] * h[size_t(v)], near, unsorted);
      for (const auto& item : near) finer[item.first] = std::min(finer[item.first], target);
    }
    limit_gradation(input, finer, options.size.gradation);
    latest.seconds_fidelity += seconds_since(t0);
    RemeshStats next = latest;
    auto again = remesh_at_sizes(input, options, finer, asked, part, next, progress);
    if (!again.ok() && again.cancelled()) return again.status();
    // Only while the edges still follow the asked size (median within
    // fidelity_size_drift of it).
    if (!again.ok() ||
        edge_ratios(again.value(), output_sizes(input, again.value().home, asked))[1] <
            1 - options.fidelity_size_drift)
      break;
    h = std::move(finer);
    ++next.fidelity_size_rounds;
    latest = next;
    gaps = again.value().input_gaps;
    vertices = again.value().mesh.num_vertices();
    const size_t n_far = far_vertices(gaps).size();
    if (n_far < best_far) {
      best_far = n_far;
      stats = next;
      result = std::move(again);
    }
  }
  // The time and rounds spent, kept or not.
  stats.seconds_mesh = latest.seconds_mesh;
  stats.seconds_optimize = latest.seconds_optimize;
  stats.seconds_fidelity = latest.seconds_fidelity;
  stats.fidelity_size_rounds = latest.fidelity_size_rounds;
  if (result.ok()) {
    // How well the edges follow the asked size (the finer sizes of the
    // size rounds are the surface's own business).
    const std::array<double, 3> ratios =
        edge_ratios(result.value(), output_sizes(input, result.value().home, asked));
    stats.edge_ratio_p10 = ratios[0];
    stats.edge_ratio_median = ratios[1];
    stats.edge_ratio_p90 = ratios[2];
  }
  if (stats_out) *stats_out = stats;
  return result;
}

}  // namespace vm
