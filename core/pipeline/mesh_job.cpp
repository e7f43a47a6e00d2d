// The whole job, stages 1 to 7 of docs/ARCHITECTURE.md: prepare, size field
// and surface remeshing, boundary layers, caps, volume, assembly and checks.
#include "core/pipeline/mesh_job.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <new>
#include <numbers>
#include <numeric>
#include <optional>
#include <string>
#include <string_view>
#include <tuple>

#include "core/geom/vec3.h"
#include "core/layers/extrude_layers.h"
#include "core/layers/flip_wall_edges.h"
#include "core/layers/layered_volume.h"
#include "core/mesh/chord_radius.h"
#include "core/mesh/edge_lengths.h"
#include "core/mesh/enclosed_volume.h"
#include "core/mesh/prism_split.h"
#include "core/mesh/self_intersection.h"
#include "core/mesh/surface_distance.h"
#include "core/mesh/volume_check.h"
#include "core/pipeline/element_budget.h"
#include "core/pipeline/opening_names.h"
#include "core/pipeline/size_preview.h"
#include "core/pipeline/validate_options.h"
#include "core/pipeline/write_outputs.h"
#include "core/quality/tet_quality.h"
#include "core/surface/element_estimate.h"
#include "core/surface/relax_wall.h"
#include "core/surface/vessel_radius.h"
#include "core/util/parallel.h"
#include "core/util/stage_timer.h"
#include "core/volume/boundary_recovery.h"
#include "core/volume/fill_volume.h"

namespace vm {

namespace {

/// For each cap, the input opening it closes: pairs taken by increasing
/// distance between the cap's centroid and the opening's (the wall moved
/// them little: remeshing keeps vertices on the input).
std::vector<size_t> cap_openings_map(const CappedSurface& capped,
                                     const std::vector<Opening>& openings) {
  std::vector<std::tuple<double, size_t, size_t>> pairs;
  for (size_t c = 0; c < capped.caps.size(); ++c)
    for (size_t i = 0; i < openings.size(); ++i) {
      double d2 = 0;
      for (int k = 0; k < 3; ++k) {
        const double d = capped.caps[c].centroid[size_t(k)] - openings[i].centroid[size_t(k)];
        d2 += d * d;
      }
      pairs.emplace_back(d2, c, i);
    }
  std::sort(pairs.begin(), pairs.end());
  std::vector<size_t> of_cap(capped.caps.size(), SIZE_MAX);
  std::vector<uint8_t> taken(openings.size(), 0);
  for (const auto& [d2, c, i] : pairs)
    if (of_cap[c] == SIZE_MAX && !taken[i]) of_cap[c] = i, taken[i] = 1;
  return of_cap;
}

/// Caps on the openings of `surface`, each named after the input opening it
/// closes; tags in the order of the names: the chosen inlet first (tag 1),
/// then the others in the analysis' order.
Result<CappedSurface> cap_and_name(const MeshJobResult& r, const SurfaceMesh& surface,
                                   const std::vector<double>& sizes, int inlet) {
  auto result = cap_openings(surface, sizes);
  if (!result.ok() || result.value().caps.empty()) return result;
  CappedSurface& capped = result.value();
  const std::vector<Opening>& in = r.surface.topology.openings;
  if (capped.caps.size() != in.size())
    return Status::Internal("the wall has " + std::to_string(capped.caps.size()) +
                            " openings, the input " + std::to_string(in.size()));
  const std::vector<size_t> of_cap = cap_openings_map(capped, in);
  std::vector<size_t> order(of_cap.size());  // caps in their new tag order
  std::iota(order.begin(), order.end(), 0);
  auto rank = [&](size_t c) { return of_cap[c] == size_t(inlet) ? 0 : of_cap[c] + 1; };
  std::stable_sort(order.begin(), order.end(),
                   [&](size_t a, size_t b) { return rank(a) < rank(b); });
  std::vector<CapInfo> caps;
  std::vector<int32_t> new_tag(capped.caps.size() + 1, 0);
  for (size_t k = 0; k < order.size(); ++k) {
    caps.push_back(std::move(capped.caps[order[k]]));
    new_tag[size_t(caps.back().tag)] = int32_t(k + 1);
    caps.back().tag = int32_t(k + 1);
    caps.back().name = r.opening_names[of_cap[order[k]]];
  }
  capped.caps = std::move(caps);
  for (int32_t& tag : capped.triangle_tag) tag = new_tag[size_t(tag)];
  return result;
}

/// Refuses a remeshed wall whose volume differs from its input's by more
/// than options.max_volume_change: the size is too coarse for the vessels.
/// The loss of a polygonal section goes as h^2, so the size suggested is
/// scaled by sqrt(2% / change) (20 edges a circumference lose about 1.6%).
Status check_volume_change(const SurfaceFidelity& f, const MeshJobOptions& options) {
  const double change = std::abs(f.volume_change);
  if (!(change > options.max_volume_change)) return Status::Ok();
  const SizeOptions& so = options.remesh_options.size;
  const double scale = 0.8 * std::sqrt(0.02 / change);
  const bool uniform = so.mode == SizeMode::kUniform;
  char buf[400];
  std::snprintf(buf, sizeof buf,
                "%.4g makes a wall that encloses %.3g%% %s volume than the input (%.4g "
                "against %.4g): the size is too coarse for the vessels; use %s %.3g or %s (or "
                "accept the change with {max_volume_change} %.2g)",
                uniform ? so.size : so.per_circumference, 100 * change,
                f.volume_change < 0 ? "less" : "more", f.output_volume, f.input_volume,
                uniform ? "{size}" : "{per_circumference}",
                uniform ? so.size * scale : std::ceil(so.per_circumference / scale),
                uniform ? "smaller" : "more", std::ceil(100 * change + 1) / 100);
  return Status::BadOption(uniform ? "size" : "per_circumference", buf);
}

/// Warnings on layers the user may not have meant: a vessel wall asked for
/// by its number of layers alone, and a first layer so thin against the
/// wall's size (below 1e-3 of its smallest edge) that its elements are flat.
void warn_about_layers(MeshJobResult& r, const MeshJobOptions& options,
                       const std::vector<double>& wall_sizes) {
  if (options.vessel.layers > 0 && !options.wall_thickness_given) {
    r.warnings.push_back("a vessel wall of " + std::to_string(options.vessel.layers) + " layers, " +
                         number_text(options.vessel.thickness_fraction) +
                         " R thick (the default {wall_thickness}), was grown outward because "
                         "{wall_layers} was given; without {wall_layers} there is no vessel wall");
  }
  const double first = options.viscous.first_height;
  if (options.viscous.layers <= 0 || first <= 0 || wall_sizes.empty()) return;
  const double h = *std::min_element(wall_sizes.begin(), wall_sizes.end());
  if (first >= 1e-3 * h) return;
  r.warnings.push_back("{first_layer} " + number_text(first) + " is " + number_text(first / h, 2) +
                       " of the smallest wall edge (" + number_text(h) +
                       "): the layer's elements are nearly flat (quality near 0) and solvers "
                       "may reject them; use {first_layer} " +
                       number_text(1e-3 * h, 2) + " or more");
}

/// Records where boundary recovery changed the wall (edges flipped, points
/// splitting its triangles; ids below the wall's vertex count are the
/// wall's in r.volume) and warns with the written wall's quality.
void warn_about_wall_recovery(MeshJobResult& r, const RecoveredVolume& rec,
                              const std::vector<double>& split_places) {
  VolumeStats& st = r.volume_stats;
  std::vector<std::array<double, 3>>& places = st.wall_change_places;
  for (size_t e = 0; e < rec.flipped_edges.size(); e += 2) {
    const double* p = &r.volume.points[3 * size_t(rec.flipped_edges[e])];
    const double* q = &r.volume.points[3 * size_t(rec.flipped_edges[e + 1])];
    places.push_back({0.5 * (p[0] + q[0]), 0.5 * (p[1] + q[1]), 0.5 * (p[2] + q[2])});
  }
  for (size_t i = 0; i < split_places.size(); i += 3)
    places.push_back({split_places[i], split_places[i + 1], split_places[i + 2]});
  if (places.empty()) return;
  double written = 1;
  for (const SurfaceGroupQuality& g : r.written_quality)
    if (g.tag == 0) written = g.quality.min;
  std::string where;
  for (size_t i = 0; i < std::min<size_t>(places.size(), 3); ++i)
    where += (i ? ", " : "") + point_text(places[i]);
  if (places.size() > 3) where += ", ...";
  r.warnings.push_back(
      "the volume's boundary recovery changed the wall at " + std::to_string(places.size()) +
      " place" + (places.size() > 1 ? "s" : "") + " (" + where +
      "): " + std::to_string(st.wall_edges_flipped) + " edge(s) flipped, " +
      std::to_string(st.wall_steiner_points) + " point(s) splitting its triangles (" +
      std::to_string(st.reoptimized_steiner_points) + " slid along their edge); the written " +
      "wall's gamma_k min is " + number_text(written, 3) + " (remeshed " +
      number_text(r.output_quality_stats.min, 3) + ")");
}

/// Stages 4 to 7: boundary layers, caps on the openings, the tetrahedra of
/// the lumen, assembly; checks the result before anything is written.
/// The element budget of the volume: the tetrahedra estimated from the
/// volume `wall` encloses (its `openings` closed by fans) and the size in
/// the core: the one asked, else the uniform size, else the median of
/// `wall_sizes` (an overestimate for a size growing into the core); no
/// check when none is known yet (empty `wall_sizes`, radius-based sizes).
Status check_volume_budget(const SurfaceMesh& wall, const std::vector<Opening>& openings,
                           const MeshJobOptions& options, std::vector<double> wall_sizes) {
  const SizeOptions& so = options.remesh_options.size;
  double h = options.core_size > 0                             ? options.core_size
             : options.remesh && so.mode == SizeMode::kUniform ? so.size
                                                               : 0;
  if (h == 0 && !wall_sizes.empty()) {
    std::nth_element(wall_sizes.begin(), wall_sizes.begin() + long(wall_sizes.size() / 2),
                     wall_sizes.end());
    h = wall_sizes[wall_sizes.size() / 2];
  }
  if (!(h > 0)) return Status::Ok();
  const double volume = std::abs(volume_closed_by_fans(wall, openings));
  const double estimate = estimate_tetrahedra(volume, h);
  const TetrahedronLimit limit = tetrahedron_limit(options.max_elements, options.memory_bytes);
  if (estimate <= limit.tetrahedra) return Status::Ok();
  // The remedy: the blamed option's value that fits.
  const char* option = options.core_size > 0           ? "core_size"
                       : so.mode == SizeMode::kUniform ? "size"
                                                       : "per_circumference";
  const double fits =
      options.core_size > 0 ? fitting_size(0, volume, limit.tetrahedra)
      : so.mode == SizeMode::kUniform
          ? fitting_size(surface_area(wall), volume, limit.tetrahedra)
          : std::floor(so.per_circumference / (1.02 * std::cbrt(estimate / limit.tetrahedra)));
  char buf[400];
  if (limit.memory)
    std::snprintf(buf, sizeof buf,
                  "makes about %.*g tetrahedra in the lumen, more than fit in %s: ask for larger "
                  "elements ({%s} %s fits)",
                  estimate < 1e6 ? 6 : 3, estimate, memory_text(options.memory_bytes).c_str(),
                  option, number_text(fits).c_str());
  else
    std::snprintf(buf, sizeof buf,
                  "makes about %.*g tetrahedra in the lumen, more than the element budget "
                  "({max_elements} %.0f) allows: ask for larger elements ({%s} %s fits)",
                  estimate < 1e6 ? 6 : 3, estimate, options.max_elements, option,
                  number_text(fits).c_str());
  Status refused = Status::BadOption(option, buf);
  const bool usable =
      so.mode == SizeMode::kPerCircumference && !(options.core_size > 0) ? fits >= 3 : fits > 0;
  return usable ? refused.WithRemedy({"coarser", {}, fits}) : refused;
}

Status mesh_volume(MeshJobResult& r, const MeshJobOptions& options,
                   const std::vector<double>& wall_sizes, const ProgressFn& progress) {
  const std::vector<Opening>& openings =
      r.remeshed ? r.output_topology.openings : r.surface.topology.openings;
  if (Status st = check_volume_budget(r.output_surface, openings, options, wall_sizes); !st.ok())
    return st;
  VolumeStats& st = r.volume_stats;
  auto t0 = std::chrono::steady_clock::now();
  // Stage 4: boundary layers, inward (viscous) and outward (vessel wall),
  // thickness relative to the local radius (half the lumen chord).
  std::optional<LayerMesh> inner, outer;
  if (options.viscous.layers > 0 || options.vessel.layers > 0) {
    if (!report_progress(progress, 0.9, "boundary layers")) return Status::Cancelled();
    const std::vector<double> radius = chord_radius(r.output_surface);
    for (bool out : {false, true}) {
      LayerSpec spec = out ? options.vessel : options.viscous;
      if (spec.layers <= 0) continue;
      spec.outward = out;
      spec.measure = options.verify;  // the heights as distances to the wall too
      LayerStats ls;
      auto layer = extrude_layers(r.output_surface, radius, spec, &ls);
      // Where a needle or fold of the wall stops the layer, the wall is
      // relaxed there, a little wider each time, and the layer tried again.
      for (int attempt = 1; !layer.ok() && attempt <= 3; ++attempt) {
        const std::vector<Vec3> places = layer.status().remedy().places;
        if (places.empty()) break;
        // The wall's size where it failed: at the vertex nearest the place.
        size_t nearest = 0;
        for (size_t v = 1; v < r.output_surface.num_vertices(); ++v)
          if (norm(at(r.output_surface.points, int32_t(v)) - places[0]) <
              norm(at(r.output_surface.points, int32_t(nearest)) - places[0]))
            nearest = v;
        const double reach =
            (1.0 + attempt) * (nearest < wall_sizes.size() ? wall_sizes[nearest] : 0.0);
        const WallRelaxation relaxed =
            relax_wall_near(r.output_surface, places, reach, 5 * attempt);
        if (!relaxed.applied) break;
        r.warnings.push_back(
            std::string(out ? "the vessel wall" : "the boundary layer") + " could not grow at " +
            point_text(places[0]) +
            (places.size() > 1 ? " and " + std::to_string(places.size() - 1) + " more places"
                               : "") +
            " (a needle-like spike or fold the wall follows from the input): the wall was "
            "smoothed there (" +
            std::to_string(relaxed.vertices) + " vertices, moved at most " +
            number_text(relaxed.max_displacement) + ")");
        const std::vector<double> relaxed_radius = chord_radius(r.output_surface);
        ls = {};
        layer = extrude_layers(r.output_surface, relaxed_radius, spec, &ls);
      }
      if (!layer.ok())
        return Status::Error(std::string(out ? "vessel wall" : "boundary layer") + ": " +
                             layer.message() + " (a wall too irregular for layers: remesh it, or " +
                             (out ? "drop {wall_thickness})" : "use {layers} 0)"))
            .WithRemedy(layer.status().remedy());
      (out ? outer : inner) = std::move(layer).value();
      (out ? st.vessel_wall : st.boundary_layer) = ls;
      (out ? st.wall_layers : st.viscous_layers) = spec.layers;
    }
  }
  st.seconds_layers = seconds_since(t0);
  warn_about_layers(r, options, wall_sizes);

  // Stage 5: caps on the core's boundary (the viscous layer's front, else
  // the wall with its rims on their planes).
  t0 = std::chrono::steady_clock::now();
  if (!report_progress(progress, 0.91, "caps")) return Status::Cancelled();
  SurfaceMesh core_surface = inner ? front_surface(*inner) : r.output_surface;
  if (!inner && outer)
    std::copy(outer->points.begin(), outer->points.begin() + long(core_surface.points.size()),
              core_surface.points.begin());
  auto capped = cap_and_name(r, core_surface, wall_sizes, options.inlet);
  if (!capped.ok()) return capped.status();
  r.capped = std::move(capped).value();
  for (const CapInfo& c : r.capped.caps)
    if (c.max_projection_distance > 0.2 * c.perimeter / (2 * std::numbers::pi))
      r.warnings.push_back("opening " + c.name + " is far from planar: its rim moved up to " +
                           std::to_string(c.max_projection_distance) + " onto the cap plane");
  st.seconds_caps = seconds_since(t0);

  t0 = std::chrono::steady_clock::now();
  if (!report_progress(progress, 0.92, "tetrahedra")) return Status::Cancelled();
  // Wall edges recovery cannot recover flip on the wall where it keeps its
  // shape, rather than split (none when the layer's top slice takes them).
  RecoveryOptions recovery;
  recovery.may_flip_surface =
      wall_flip_rule(inner ? &*inner : nullptr, outer ? &*outer : nullptr, r.capped.mesh.points,
                     core_surface.num_vertices(), options.keep_prisms);
  auto recovered = recover_boundary(r.capped.mesh.points, r.capped.mesh.triangles,
                                    r.capped.triangle_tag, recovery);
  if (!recovered.ok()) return Status::Error("volume meshing failed: " + recovered.message());
  RecoveredVolume& rec = recovered.value();
  st.steiner_points = size_t(rec.steiner_points);
  st.edges_recovered_by_flips = size_t(rec.edges_recovered_along);
  st.wall_edges_flipped = size_t(rec.surface_flips);
  st.seconds_recovery = seconds_since(t0);

  // Refinement and optimization inside, towards the sizes of the surface
  // vertices (wall: the remeshing's; caps: their edge lengths; Steiner
  // points: those of the triangle they split) graded into the core.
  t0 = std::chrono::steady_clock::now();
  std::vector<double> size = mean_edge_lengths(r.capped.mesh);
  std::copy(wall_sizes.begin(), wall_sizes.end(), size.begin());
  const size_t surface_vertices = size.size();
  size.resize(rec.mesh.num_vertices(), 0.0);
  for (size_t t = 0; t < rec.mesh.num_triangles(); ++t) {
    const int32_t* parent = &r.capped.mesh.triangles[3 * size_t(rec.triangle_parent[t])];
    for (int k = 0; k < 3; ++k) {
      const size_t v = size_t(rec.mesh.triangles[3 * t + size_t(k)]);
      if (v >= surface_vertices && size[v] == 0)
        size[v] = (size[size_t(parent[0])] + size[size_t(parent[1])] + size[size_t(parent[2])]) / 3;
    }
  }
  FillOptions fo;
  // The field's default in the core: a uniform size stays uniform, a
  // radius-based one grows from the wall by the gradation.
  const SizeOptions& so = options.remesh_options.size;
  fo.core_size = options.core_size > 0                             ? options.core_size
                 : options.remesh && so.mode == SizeMode::kUniform ? so.size
                                                                   : 0;
  fo.spheres = so.spheres;
  fo.gradation /= options.gradation_divisor;
  FillStats fs;
  ProgressFn fill_progress = [&](double f, std::string_view stage) {
    return report_progress(progress, 0.92 + 0.06 * f, stage);
  };
  auto filled = fill_volume(rec.kernel, size, fo, &fs, fill_progress);
  if (!filled.ok()) return Status::Error("volume meshing failed: " + filled.message());
  if (fs.unused_vertices != 0) return Status::Internal("a surface vertex is not in the volume");
  st.inserted_points = fs.inserted_vertices;
  st.seconds_refinement = seconds_since(t0);
  st.seconds_fill_refine = fs.refine_seconds;
  st.seconds_fill_optimize = fs.optimize_seconds;

  // The layers and the core in one mesh, named.
  t0 = std::chrono::steady_clock::now();
  auto assembled =
      assemble_layered_volume(inner ? &*inner : nullptr, outer ? &*outer : nullptr, r.capped, rec,
                              filled.value(), options.tag_layer, options.keep_prisms);
  if (!assembled.ok()) return Status::Error("volume meshing failed: " + assembled.message());
  r.volume = std::move(assembled.value().mesh);
  r.surface_names = std::move(assembled.value().surface_names);
  r.written_quality =
      surface_group_quality(r.volume, r.surface_names, assembled.value().ring_first,
                            assembled.value().ring_end, options.prepare.histogram_bins);
  r.region_names = std::move(assembled.value().region_names);
  st.front_steiner_points = assembled.value().front_steiner_points;
  st.absorbed_steiner_points = assembled.value().absorbed_steiner_points;
  st.wall_steiner_points = assembled.value().wall_steiner_points;
  st.reoptimized_steiner_points = assembled.value().reoptimized_steiner_points;
  warn_about_wall_recovery(r, rec, assembled.value().wall_steiner_places);
  const size_t core_first = assembled.value().core_first;
  const size_t core_count = assembled.value().core_count;
  // Layer tets come before the core's, the vessel wall's after.
  r.tet_part.assign(r.volume.num_tets(), 0);
  std::fill(r.tet_part.begin(), r.tet_part.begin() + long(core_first), uint8_t(1));
  std::fill(r.tet_part.begin() + long(core_first + core_count), r.tet_part.end(), uint8_t(2));
  st.seconds_assembly = seconds_since(t0);

  // Never write an inverted element; with verify, also check conformity and
  // the boundary (correct by construction, and slower).
  t0 = std::chrono::steady_clock::now();
  auto check = options.verify ? check_volume_mesh(r.volume) : check_volume_orientation(r.volume);
  if (!check.ok()) return Status::Internal("the volume mesh is invalid: " + check.message());
  st.seconds_check = seconds_since(t0);
  r.tet_quality = tet_qualities(r.volume);
  r.tet_quality_stats = quality_stats(r.tet_quality, options.prepare.histogram_bins);
  for (size_t t = 0; t < r.volume.num_tets(); ++t) {
    if (r.tet_part[t] == 2) continue;  // the vessel wall
    const int32_t* v = &r.volume.tets[4 * t];
    auto p = [&](int k) { return &r.volume.points[3 * size_t(v[k])]; };
    st.lumen_volume += tet_volume6(p(0), p(1), p(2), p(3)) / 6;
  }
  for (size_t q = 0; q < r.volume.num_prisms(); ++q) {
    if (r.volume.prism_region[q] == kRegionVesselWall) continue;
    for (const auto& tet : split_prism(&r.volume.prisms[6 * q])) {
      auto p = [&](int k) { return &r.volume.points[3 * size_t(tet[size_t(k)])]; };
      st.lumen_volume += tet_volume6(p(0), p(1), p(2), p(3)) / 6;
    }
  }
  r.core_quality_stats =
      quality_stats(std::vector<float>(r.tet_quality.begin() + long(core_first),
                                       r.tet_quality.begin() + long(core_first + core_count)),
                    options.prepare.histogram_bins);
  return Status::Ok();
}

/// The first layer's height from options.yplus (when asked) at the chosen
/// inlet of the prepared surface, in the model's unit: set in `options`
/// and recorded in `r`. Errors: no layer to size, {first_layer} given too,
/// no inlet velocity, no opening.
Status first_layer_from_yplus(MeshJobResult& r, MeshJobOptions& options) {
  // The options were checked before (validate_options): a target y+ comes
  // with a velocity, layers and no {first_layer}.
  const YPlusTarget& t = options.yplus;
  if (!(t.yplus > 0)) return Status::Ok();
  const std::vector<Opening>& openings = r.surface.topology.openings;
  if (openings.empty())
    return Status::Error(
        "{first_layer_yplus} needs an inlet to take the flow's diameter from, and this surface "
        "is closed: cut it open ({clip} auto) or give {first_layer}");
  const size_t inlet = size_t(options.inlet) < openings.size() ? size_t(options.inlet) : 0;
  const double metres = metres_per_unit(r.surface.unit.unit);
  FirstLayerFromYPlus f;
  f.target = t;
  f.inlet = r.opening_names[inlet];
  f.inlet_diameter = 2 * openings[inlet].radius;
  f.estimate = first_layer_height_for_yplus(t, f.inlet_diameter * metres);
  f.height = f.estimate.height / metres;
  options.viscous.first_height = f.height;
  r.first_layer_yplus = f;
  return Status::Ok();
}

/// The element budget on the size field before remeshing (element_budget.h):
/// the default size coarsened to fit it (said in a warning and r.budget), a
/// given size refused. `radius` receives R per vertex of the prepared wall
/// (per-circumference sizes), for the remeshing to reuse.
Status fit_budget(MeshJobResult& r, MeshJobOptions& options, std::vector<double>& radius) {
  SizeOptions& so = options.remesh_options.size;
  if (so.mode == SizeMode::kPerCircumference) radius = vessel_radius(r.output_surface);
  if (Status st = fit_element_budget(r.output_surface, r.surface.topology.openings, radius,
                                     element_budget(options), so, r.budget);
      !st.ok())
    return st;
  if (r.budget.coarsened) r.warnings.push_back(budget_warning(r.budget));
  return Status::Ok();
}

/// Stages 2 to 7 on the prepared surface `r.surface`: checks, size field and
/// remeshing, then mesh_volume. `options` gets what the surface decides.
Status mesh_prepared(MeshJobResult& r, MeshJobOptions& options, const ProgressFn& progress) {
  Status meshable = check_meshable(r.surface);
  if (!meshable.ok()) return meshable;
  auto names = opening_names(r.surface, options.opening_names, options.inlet);
  if (!names.ok()) return names.status();
  r.opening_names = std::move(names).value();
  if (Status st = first_layer_from_yplus(r, options); !st.ok()) return st;
  if (Status st = check_refine_sizes(options.remesh_options.size.spheres, r.surface.box.diagonal(),
                                     unit_symbol(r.surface.unit.unit));
      !st.ok())
    return st;
  if (options.output_units != LengthUnit::kGuess && r.surface.unit.guessed &&
      !r.surface.unit.certain)
    r.warnings.push_back("the mesh is written in " +
                         std::string(unit_symbol(options.output_units)) + " from a guessed unit, " +
                         std::string(unit_symbol(r.surface.unit.unit)) + " (" +
                         std::string(confidence_name(r.surface.unit.confidence)) + ": " +
                         r.surface.unit.reason + "); say {units} if it is not");
  r.output_surface = r.surface.mesh;
  if (options.volume) {
    // Known sizes are checked against the budget before remeshing.
    Status budget = check_volume_budget(r.output_surface, r.surface.topology.openings, options, {});
    if (!budget.ok()) return budget;
  }
  std::vector<double> wall_sizes;  // target size per wall vertex
  std::vector<double> radius;      // R per input vertex, for the size field
  if (options.remesh) {
    const auto sized = std::chrono::steady_clock::now();
    if (Status st = fit_budget(r, options, radius); !st.ok()) return st;
    const double seconds_radius = seconds_since(sized);
    ProgressFn remesh_progress = [&](double f, std::string_view stage) {
      return report_progress(progress, 0.2 + 0.7 * f, stage);
    };
    const TopologyReport in = analyze_topology(r.output_surface);
    RemeshOptions remesh_options = options.remesh_options;
    remesh_options.max_triangles = options.max_elements;
    remesh_options.radius = radius;
    auto remeshed =
        remesh_surface(r.output_surface, remesh_options, &r.remesh_stats, remesh_progress);
    if (!remeshed.ok()) return remeshed.status();
    for (const FallbackPatch& f : r.remesh_stats.fallback_patches)
      r.warnings.push_back(fallback_warning(f, unit_symbol(r.surface.unit.unit)));
    r.remesh_stats.seconds_size += seconds_radius;  // the radius, computed for the budget
    wall_sizes = remeshed.value().sizes;
    const SurfaceMesh input = std::move(r.output_surface);
    r.output_surface = std::move(remeshed.value().mesh);
    r.remeshed = true;
    // Fidelity: output vertices on the input, input vertices near the output.
    r.fidelity.max_vertex_offset = distances_to_surface(input, r.output_surface.points).max /
                                   bounding_box(input.points).diagonal();
    r.fidelity.max_input_gap = r.remesh_stats.max_input_gap;
    r.fidelity.input_gap_vertices = r.remesh_stats.input_gap_vertices;
    // Never write a surface whose topology differs from the input's.
    r.output_topology = analyze_topology(r.output_surface);
    const TopologyReport& out = r.output_topology;
    if (out.components != in.components || out.genus != in.genus ||
        out.openings.size() != in.openings.size() || out.nonmanifold_edges > 0 ||
        out.nonmanifold_vertices > 0)
      return Status::Error(
          "the remeshed surface lost the input's topology (genus " + std::to_string(in.genus) +
          " -> " + std::to_string(out.genus) + ", openings " + std::to_string(in.openings.size()) +
          " -> " + std::to_string(out.openings.size()) + ", non-manifold edges " +
          std::to_string(out.nonmanifold_edges) +
          "): the size is too coarse for some feature; try a smaller {size} or a larger "
          "{per_circumference}");
    // Never a wall that loses the vessels' volume (a size too coarse).
    r.fidelity.input_volume = volume_closed_by_fans(input, in.openings);
    r.fidelity.output_volume = volume_closed_by_fans(r.output_surface, out.openings);
    r.fidelity.volume_change =
        r.fidelity.input_volume != 0 ? r.fidelity.output_volume / r.fidelity.input_volume - 1 : 0;
    if (Status st = check_volume_change(r.fidelity, options); !st.ok()) return st;
    // Counted by the fidelity stage when it ran; else here.
    r.fidelity.self_intersections = r.remesh_stats.self_intersections >= 0
                                        ? size_t(r.remesh_stats.self_intersections)
                                        : find_self_intersections(r.output_surface, 0).pairs;
    if (r.fidelity.self_intersections > 0)
      r.warnings.push_back("the remeshed surface intersects itself (" +
                           std::to_string(r.fidelity.self_intersections) +
                           " pairs of triangles): try a smaller size");
  }

  if (wall_sizes.empty()) wall_sizes = mean_edge_lengths(r.output_surface);
  if (!report_progress(progress, 0.9, "quality")) return Status::Cancelled();
  r.output_quality = triangle_qualities(r.output_surface);
  r.output_quality_stats = quality_stats(r.output_quality, options.prepare.histogram_bins);

  if (options.volume) {
    Status st = mesh_volume(r, options, wall_sizes, progress);
    if (!st.ok()) return st;
  }
  r.groups = output_groups(r);
  report_progress(progress, 1.0, "done");
  return Status::Ok();
}

}  // namespace

ElementBudget element_budget(const MeshJobOptions& options) {
  ElementBudget budget;
  budget.max_elements = options.max_elements;
  budget.volume = options.volume;
  budget.core_size = options.core_size;
  budget.size_given = options.size_given;
  budget.max_volume_change = options.max_volume_change;
  budget.memory_bytes = options.memory_bytes;
  return budget;
}

Status out_of_memory_error(std::string_view stage, double fraction) {
  const std::string during = stage.empty() ? std::string("before its first stage")
                                           : "during \"" + std::string(stage) + "\" (" +
                                                 std::to_string(int(std::lround(100 * fraction))) +
                                                 "% of the job)";
  return Status::Error("out of memory " + during +
                       ": the mesh needs more memory than there is; try a coarser size (a larger "
                       "{size} or a smaller {per_circumference}), or a smaller {max_elements}");
}

namespace {

/// `job` run with `progress`, an allocation that fails (std::bad_alloc) in
/// it returned as out_of_memory_error, at the last stage `progress` heard.
template <class Job>
Result<MeshJobResult> guarded(const ProgressFn& progress, const Job& job) {
  std::string stage;
  double fraction = 0;
  ProgressFn heard = [&](double f, std::string_view s) {
    stage = s;
    fraction = f;
    return !progress || progress(f, s);
  };
  try {
    return job(heard);
  } catch (const std::bad_alloc&) {
    return out_of_memory_error(stage, fraction);
  }
}

}  // namespace

namespace {

Result<MeshJobResult> mesh_surface(PreparedSurface surface, const MeshJobOptions& given,
                                   const ProgressFn& progress);

/// run_mesh_job unguarded.
Result<MeshJobResult> mesh_file(std::span<const uint8_t> file_bytes, const MeshJobOptions& given,
                                const ProgressFn& progress,
                                const std::function<void()>& input_read) {
  auto t0 = std::chrono::steady_clock::now();
  if (Status st = validate_options(given, given.format); !st.ok()) return st;
  set_thread_count(given.threads);
  // Stage 1 takes the first fifth of the progress bar, remeshing most of the rest.
  ProgressFn sub = [&](double f, std::string_view stage) {
    return report_progress(progress, 0.2 * f, stage);
  };
  Result<PreparedSurface> prepared = prepare_surface(file_bytes, given.prepare, sub);
  if (input_read) input_read();
  if (!prepared.ok()) return prepared.status();
  auto r = mesh_surface(std::move(prepared).value(), given, progress);
  if (r.ok())
    r.value().seconds_total =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

/// run_mesh_job_on unguarded.
Result<MeshJobResult> mesh_surface(PreparedSurface surface, const MeshJobOptions& given,
                                   const ProgressFn& progress) {
  auto t0 = std::chrono::steady_clock::now();
  if (Status st = validate_options(given, given.format); !st.ok()) return st;
  MeshJobOptions options = given;  // with what the surface decides (a y+ height)
  set_thread_count(options.threads);
  MeshJobResult r;
  r.preset = options.preset;
  r.surface = std::move(surface);
  r.warnings = r.surface.warnings;
  // Every later stage's error passes here: on a surface that crosses itself
  // (the likely cause), it first says where (an option's value or a
  // cancellation is not the surface's doing).
  Status st = mesh_prepared(r, options, progress);
  // A layer that cannot start at an opening whose plane the wall meets at a
  // grazing angle: that opening is cut deeper, where the wall crosses its
  // plane, and the job runs again from the prepared surface (twice at most).
  for (int attempt = 1; !st.ok() && st.remedy().action == "trim_end" && attempt <= 2; ++attempt) {
    MeshJobResult again;
    again.preset = r.preset;
    again.surface = std::move(r.surface);
    if (!cut_openings_deeper(again.surface, st.remedy().places, 0.5 * attempt).ok()) break;
    again.warnings = again.surface.warnings;
    options = given;
    r = std::move(again);
    st = mesh_prepared(r, options, progress);
  }
  if (!st.ok()) {
    if (st.cancelled() || st.kind() == ErrorKind::kBadOption) return st;
    st = st.Prefixed(self_crossing_prefix(r.surface));
    // Crossings left by {repair} off: the remedy is the repair, at its places.
    if (r.surface.self_crossings.pairs > 0 && !r.surface.repaired)
      st = st.WithRemedy({"repair", r.surface.self_crossings.places, 0});
    return st;
  }
  r.seconds_total = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

}  // namespace

Result<MeshJobResult> run_mesh_job(std::span<const uint8_t> file_bytes, const MeshJobOptions& given,
                                   const ProgressFn& progress,
                                   const std::function<void()>& input_read) {
  return guarded(progress, [&](const ProgressFn& heard) {
    return mesh_file(file_bytes, given, heard, input_read);
  });
}

Result<MeshJobResult> run_mesh_job_on(PreparedSurface surface, const MeshJobOptions& given,
                                      const ProgressFn& progress) {
  return guarded(progress, [&](const ProgressFn& heard) {
    return mesh_surface(std::move(surface), given, heard);
  });
}

}  // namespace vm
