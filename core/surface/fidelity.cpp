// Fidelity rounds of the remeshed wall (Marchandise et al., section 2.1
// asks every new vertex to lie on the input; these rounds bring the input
// near the new surface): pinning rounds, and size rounds that mesh the
// surface again finer where input vertices stay far. See stage 3 of
// docs/ARCHITECTURE.md.
#include "core/surface/fidelity.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "core/geom/point_kdtree.h"
#include "core/mesh/self_intersection.h"
#include "core/mesh/star_visibility.h"
#include "core/mesh/surface_distance.h"
#include "core/quality/triangle_quality.h"
#include "core/surface/optimize_surface.h"
#include "core/surface/pin_to_input.h"
#include "core/surface/size_field.h"
#include "core/util/stage_timer.h"

namespace vm {

std::vector<double> output_sizes(const SurfaceMesh& input, const std::vector<int32_t>& home,
                                 const std::vector<double>& h) {
  std::vector<double> size(home.size());
  for (size_t v = 0; v < size.size(); ++v) {
    const int32_t* T = &input.triangles[3 * size_t(home[v])];
    size[v] = (h[size_t(T[0])] + h[size_t(T[1])] + h[size_t(T[2])]) / 3;
  }
  return size;
}

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

namespace {

/// `h` (one per input vertex) made at most target(v) within h[v] of each
/// input vertex v of `far`, then graded (`gradation`). `tree`: over
/// input.points.
template <class Target>
std::vector<double> finer_around(const SurfaceMesh& input, const PointKdTree& tree,
                                 std::vector<double> h, const std::vector<int32_t>& far,
                                 double gradation, Target target) {
  std::vector<double> finer = h;
  std::vector<std::pair<uint32_t, double>> near;
  const nanoflann::SearchParams unsorted(32, 0, false);
  for (int32_t v : far) {
    const double t = target(v);
    tree.radiusSearch(&input.points[3 * size_t(v)], h[size_t(v)] * h[size_t(v)], near, unsorted);
    for (const auto& item : near) finer[item.first] = std::min(finer[item.first], t);
  }
  limit_gradation(input, finer, gradation);
  return finer;
}

/// A vertex whose star_visibility is below this is a needle (no boundary
/// layer could grow from it).
constexpr double kNeedle = 0.05;

/// The last wall that held the floors (first the one before pinning),
/// restored when a round is undone.
struct KeptWall {
  SurfaceMesh mesh;
  std::vector<double> h;  ///< Pinning::h then
  std::vector<int32_t> home;
  std::vector<uint8_t> fixed;
  std::vector<int32_t> pin_of;
  size_t pinned = 0;  ///< stats.fidelity_pinned then
};

/// What a pinning round must not make worse: the worst and mean gamma_k
/// (the seed's floors, or the quality before pinning if lower), and the
/// self-intersecting pairs and needles before pinning.
struct Floors {
  double min = 0, mean = 0;
  size_t crossings = 0, needles = 0;
};

/// The state of the pinning rounds: the inputs (references), the wall
/// being pinned, and the bookkeeping the rounds share.
struct Pinning {
  const SurfaceMesh& input;
  const TriangleAdjacency& adj;      ///< of the input, cut along the features
  std::vector<double> h;             ///< per input vertex: the size meshed at, finer
                                     ///< where a local size round ran
  const std::vector<double>& asked;  ///< per input vertex: the size asked for
  const RemeshOptions& options;
  SurfaceMesh& mesh;
  WallVertices& wall;
  std::vector<double>& input_gaps;  ///< per input vertex
  RemeshStats& stats;
  TriangleBvh bvh{};                     ///< of `mesh` when its gaps were last measured
  SurfaceOptimizeOptions relax_options;  ///< the passes after a round
  PinSlack slack{};                      ///< lets pinned vertices slide
  std::vector<uint8_t> given_up{};       ///< per input vertex: not pinned again
  KeptWall kept{};
  Floors floors{};
  /// Self-intersecting pairs of the kept wall when known exactly, else -1.
  int64_t kept_pairs = -1;
  bool floors_set = false;  ///< set_floors ran
};

/// Flags (one per output vertex) the vertices whose `fixed` flag differs
/// from `before` (or that are new) and their neighbors: where a round
/// changed the mesh.
std::vector<uint8_t> around_changes(const SurfaceMesh& mesh, const std::vector<uint8_t>& fixed,
                                    const std::vector<uint8_t>& before) {
  std::vector<uint8_t> flag(fixed.size(), 0);
  for (size_t t = 0; t < mesh.num_triangles(); ++t) {
    const int32_t* T = &mesh.triangles[3 * t];
    bool changed = false;
    for (int c = 0; c < 3; ++c)
      changed |= size_t(T[c]) >= before.size() || before[size_t(T[c])] != fixed[size_t(T[c])];
    if (changed)
      for (int c = 0; c < 3; ++c) flag[size_t(T[c])] = 1;
  }
  return flag;
}

size_t count_needles(const SurfaceMesh& mesh) {
  const std::vector<double> seen = star_visibility(mesh);
  return size_t(std::count_if(seen.begin(), seen.end(), [](double c) { return c < kNeedle; }));
}

/// The floors' gamma_k part holds on the wall.
bool holds_floors(const Pinning& p) {
  const QualityStats q = quality_stats(triangle_qualities(p.mesh));
  return q.min >= p.floors.min && q.mean >= p.floors.mean;
}

/// No more needles and self-intersecting pairs than before pinning. Pairs
/// of unchanged triangles are the kept wall's: when it had none, only
/// pairs with a changed triangle can be new.
bool is_clean(const Pinning& p) {
  if (count_needles(p.mesh) > p.floors.needles) return false;
  if (p.floors.crossings > 0) return find_self_intersections(p.mesh, 0).pairs <= p.floors.crossings;
  return find_self_intersections_of(p.mesh, changed_triangles(p.kept.mesh, p.mesh), 0).pairs == 0;
}

void keep(Pinning& p) {
  p.kept = {p.mesh, p.h, p.wall.home, p.wall.fixed, p.wall.pin_of, p.stats.fidelity_pinned};
}

void restore(Pinning& p) {
  p.mesh = p.kept.mesh;
  p.h = p.kept.h;
  p.wall.home = p.kept.home;
  p.wall.fixed = p.kept.fixed;
  p.wall.pin_of = p.kept.pin_of;
  p.wall.size = output_sizes(p.input, p.wall.home, p.h);
  p.stats.fidelity_pinned = p.kept.pinned;
  p.stats.fidelity_reverted = true;
}

/// Measures the input vertices' distances to the wall (and the reported
/// gap statistics); returns how many are beyond options.fidelity times the
/// asked h.
size_t measure_gaps(Pinning& p) {
  p.bvh = build_triangle_bvh(p.mesh);
  p.input_gaps = distances_to_surface(p.mesh, p.bvh, p.input.points, true).per_point;
  return count_gaps(p.input_gaps, p.asked, p.options.fidelity, p.stats);
}

/// Before the first round: the floors, the kept wall.
void set_floors(Pinning& p) {
  const QualityStats q0 = quality_stats(triangle_qualities(p.mesh));
  p.floors.min = std::min(q0.min, p.options.fidelity_floor_min);
  p.floors.mean = std::min(q0.mean, p.options.fidelity_floor_mean);
  p.floors.crossings = find_self_intersections(p.mesh, 0).pairs;
  p.kept_pairs = int64_t(p.floors.crossings);
  p.floors.needles = count_needles(p.mesh);
  p.floors_set = true;
  keep(p);
}

/// A few optimization passes from the output vertices flagged in `start`
/// (one per output vertex), at the sizes p.h.
void relax_from(Pinning& p, const std::vector<uint8_t>& start) {
  p.wall.size = output_sizes(p.input, p.wall.home, p.h);
  const auto more =
      optimize_on_surface(p.mesh, p.wall, p.input, p.adj, p.relax_options, start, &p.slack);
  p.stats.collapses += more.collapses;
  p.stats.swaps += more.swaps;
  p.stats.moves += more.moves;
}

/// relax_from where the `fixed` flags changed since `before` (one per
/// output vertex of the wall then).
void relax(Pinning& p, const std::vector<uint8_t>& before) {
  relax_from(p, around_changes(p.mesh, p.wall.fixed, before));
}

/// Frees the pins of triangles below min_gamma (given up on), then relaxes
/// around them. Returns the number freed.
size_t unpin_and_relax(Pinning& p, double min_gamma) {
  const std::vector<uint8_t> before = p.wall.fixed;
  const size_t freed = unpin_poor(p.mesh, p.wall, min_gamma, p.given_up);
  p.stats.fidelity_pinned -= freed;
  if (freed > 0) relax(p, before);
  return freed;
}

/// After a round's pins: quality first (pins left in poor triangles are
/// freed and the wall relaxes again; pins only decrease, so this ends),
/// then the floors (pins of ever better triangles freed until they hold).
/// The round is kept when they hold and it made no self-intersection or
/// needle; else it is undone (the pins freed stay given up, so the next
/// round tries the others). Returns whether it was kept.
bool settle_round(Pinning& p, const std::vector<uint8_t>& before, double min_quality) {
  relax(p, before);
  for (int step = 0; step < 8 && unpin_and_relax(p, min_quality) > 0; ++step) {
  }
  bool ok = holds_floors(p);
  for (double strict = min_quality + 0.05; !ok && strict < 1; strict += 0.05)
    if (unpin_and_relax(p, strict) > 0) ok = holds_floors(p);
  if (ok && is_clean(p)) {
    keep(p);
    // is_clean allows no new pair: exact when there was none.
    p.kept_pairs = p.floors.crossings == 0 ? 0 : -1;
    return true;
  }
  restore(p);
  return false;
}

}  // namespace

bool worth_size_round(size_t far, size_t vertices, const RemeshOptions& options) {
  const double share = double(far) / double(std::max<size_t>(vertices, 1));
  return far > 0 && share <= options.fidelity_noise_share &&
         (vertices <= options.fidelity_small_surface || share > options.fidelity_size_share);
}

size_t count_gaps(const std::vector<double>& gaps, const std::vector<double>& asked,
                  double fidelity, RemeshStats& stats) {
  stats.max_input_gap = 0;
  stats.input_gap_vertices = 0;
  size_t far = 0;
  for (size_t v = 0; v < asked.size(); ++v) {
    const double rel = gaps[v] / asked[v];
    stats.max_input_gap = std::max(stats.max_input_gap, rel);
    stats.input_gap_vertices += rel > kReportedGap;
    far += rel > fidelity;
  }
  return far;
}

namespace {

/// The pinning rounds on p's wall (RemeshOptions::fidelity_rounds, then
/// fidelity_last_rounds): returns how many input vertices are left beyond
/// fidelity h, p.input_gaps and p.bvh measured on the wall left.
size_t pin_rounds(Pinning& p) {
  const RemeshOptions& options = p.options;
  // The last rounds retry every vertex left far, accepting poorer
  // triangles around the pins (the floors still hold).
  const int rounds =
      options.fidelity_rounds + (options.fidelity_rounds > 0 ? options.fidelity_last_rounds : 0);
  // No size round may follow on a large wall: its last rounds accept
  // triangles down to the floor.
  const bool large_wall = p.mesh.num_vertices() > options.fidelity_small_surface;
  std::fill(p.given_up.begin(), p.given_up.end(), 0);
  int undone = 0;  // rounds undone in a row
  for (int round = 0;; ++round) {
    const size_t far = measure_gaps(p);
    // Noise everywhere (more pins than a share of the output's vertices)
    // would cost more quality than the floors allow: not tried.
    if (far == 0 || round >= rounds ||
        (!p.floors_set && double(far) > options.fidelity_max_share * double(p.mesh.num_vertices())))
      return far;
    const double min_quality =
        round < options.fidelity_rounds ? options.fidelity_min_quality
        : large_wall ? std::min(options.fidelity_last_min_quality, options.fidelity_floor_min)
                     : options.fidelity_last_min_quality;
    if (round == options.fidelity_rounds) {
      std::fill(p.given_up.begin(), p.given_up.end(), 0);
      undone = 0;
    }
    if (!p.floors_set) set_floors(p);
    const std::vector<uint8_t> before = p.wall.fixed;
    const PinStats pinned = pin_to_input(p.mesh, p.wall, p.input, p.asked, p.input_gaps,
                                         options.fidelity, p.given_up, &p.bvh);
    if (pinned.pinned == 0) {
      // Nothing left to try at this quality: on to the last rounds.
      if (round < options.fidelity_rounds) {
        round = options.fidelity_rounds - 1;
        continue;
      }
      return far;
    }
    ++p.stats.fidelity_rounds;
    p.stats.fidelity_pinned += pinned.pinned;
    undone = settle_round(p, before, min_quality) ? 0 : undone + 1;
    // Twice undone in a row (the wall too noisy or too tight there for
    // these pins): on to the last rounds, or done (the wall is the kept
    // one, its gaps measured before the round).
    if (undone == 2) {
      undone = 0;
      if (round >= options.fidelity_rounds) return far;
      round = options.fidelity_rounds - 1;
    }
  }
}

/// A local size round (RemeshOptions::fidelity_local_rounds): p.h halved
/// within h of each input vertex still beyond fidelity h (graded), and the
/// wall split, swapped and smoothed from the output vertices whose target
/// size fell, so that it follows the input there; kept on the terms of a
/// pinning round (floors, no new needle or crossing), else undone.
/// `tree`: over p.input.points. Returns whether it was kept.
bool refine_around_far(Pinning& p, const PointKdTree& tree) {
  const std::vector<int32_t> far = far_input_vertices(p.input_gaps, p.asked, p.options.fidelity);
  std::vector<double> finer = finer_around(
      p.input, tree, p.h, far, p.options.size.gradation,
      [&](int32_t v) { return std::max(0.5 * p.h[size_t(v)], p.options.size.size_min); });
  const std::vector<double> old_size = p.wall.size;
  p.h = std::move(finer);
  const std::vector<double> new_size = output_sizes(p.input, p.wall.home, p.h);
  std::vector<uint8_t> start(new_size.size());
  for (size_t v = 0; v < start.size(); ++v) start[v] = new_size[v] < old_size[v];
  relax_from(p, start);
  if (holds_floors(p) && is_clean(p)) {
    keep(p);
    p.kept_pairs = p.floors.crossings == 0 ? 0 : -1;
    ++p.stats.fidelity_local_rounds;
    return true;
  }
  restore(p);
  return false;
}

}  // namespace

void pin_far_input_vertices(const SurfaceMesh& input, const TriangleAdjacency& adj,
                            std::vector<double>& h, const std::vector<double>& asked,
                            const RemeshOptions& options, SurfaceMesh& mesh, WallVertices& wall,
                            std::vector<double>& input_gaps, RemeshStats& stats) {
  stats.fidelity_rounds = stats.fidelity_pinned = stats.fidelity_local_rounds = 0;
  stats.fidelity_reverted = false;
  stats.self_intersections = -1;
  Pinning p{.input = input,
            .adj = adj,
            .h = h,
            .asked = asked,
            .options = options,
            .mesh = mesh,
            .wall = wall,
            .input_gaps = input_gaps,
            .stats = stats,
            .relax_options = options.optimize};
  p.relax_options.passes = options.fidelity_passes;
  p.relax_options.valence_passes =
      std::min(p.relax_options.valence_passes, options.fidelity_passes);
  p.relax_options.region_rings = options.fidelity_relax_rings;
  p.given_up.assign(input.num_vertices(), 0);
  wall.pin_of.assign(wall.fixed.size(), -1);
  p.slack.input_h = &p.h;
  p.slack.slack = options.fidelity_pin_slack * options.fidelity;
  size_t far = pin_rounds(p);
  if (p.floors_set && options.fidelity_local_rounds > 0 &&
      worth_size_round(far, mesh.num_vertices(), options)) {
    const PointCloud cloud{input.points};
    PointKdTree tree(3, cloud);
    tree.buildIndex();
    for (int local = 0; local < options.fidelity_local_rounds &&
                        worth_size_round(far, mesh.num_vertices(), options);
         ++local) {
      // Undone, the wall is the kept one its gaps were measured on.
      if (!refine_around_far(p, tree)) break;
      far = pin_rounds(p);
    }
  }
  h = std::move(p.h);
  stats.self_intersections = p.kept_pairs;
}

std::vector<double> finer_where_far(const SurfaceMesh& input, const PointKdTree& tree,
                                    const RemeshOptions& options, const std::vector<double>& h,
                                    const std::vector<double>& asked,
                                    const std::vector<int32_t>& far,
                                    const std::vector<double>& gaps) {
  return finer_around(input, tree, h, far, options.size.gradation, [&](int32_t v) {
    // A chord's gap from a bend grows as h^2.
    const double rel = gaps[size_t(v)] / asked[size_t(v)];
    return std::max(h[size_t(v)] * std::clamp(std::sqrt(0.8 * options.fidelity / rel), 0.5, 0.9),
                    options.size.size_min);
  });
}

std::vector<int32_t> far_input_vertices(const std::vector<double>& gaps,
                                        const std::vector<double>& asked, double fidelity) {
  std::vector<int32_t> far;
  for (size_t v = 0; v < asked.size(); ++v)
    if (gaps[v] > fidelity * asked[v]) far.push_back(int32_t(v));
  return far;
}

Status refine_size_where_far(const SurfaceMesh& input, const RemeshOptions& options,
                             std::vector<double> h, const std::vector<double>& asked,
                             Result<RemeshedSurface>& result, RemeshStats& stats,
                             const RemeshAtSizesFn& remesh) {
  const PointCloud cloud{input.points};
  PointKdTree tree(3, cloud);
  if (options.fidelity_size_rounds > 0) tree.buildIndex();
  auto far_vertices = [&](const std::vector<double>& gaps) {
    return far_input_vertices(gaps, asked, options.fidelity);
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
    auto t0 = std::chrono::steady_clock::now();
    const std::vector<int32_t> far = far_vertices(gaps);
    if (!worth_size_round(far.size(), vertices, options)) break;
    std::vector<double> finer = finer_where_far(input, tree, options, h, asked, far, gaps);
    latest.seconds_fidelity += seconds_since(t0);
    RemeshStats next = latest;
    auto again = remesh(finer, next);
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
  return Status::Ok();
}

}  // namespace vm
