// Stage 1 of the pipeline (docs/ARCHITECTURE.md): read, weld, repair,
// smooth voxel staircases, recognise caps, analyze, decide the unit. This
// file: the phases' order (prepare_surface()), phase 1 (read and weld),
// 2e (the unit), 3 (the largest component), 4 (smoothing), 8 (analysis)
// and 9 (self-crossings); phase 2 (repairs) is prepare_surface_repair.cpp,
// phases 5-7 (caps, cuts, flow extensions) prepare_surface_openings.cpp.
#include "core/pipeline/prepare_surface.h"

#include <algorithm>
#include <cstdio>
#include <optional>

#include "core/geom/vec3.h"
#include "core/pipeline/prepare_surface_internal.h"
#include "core/util/parallel.h"

namespace vm {

using prepare_surface_detail::caps_wanted;
using prepare_surface_detail::clip;
using prepare_surface_detail::clip_one;
using prepare_surface_detail::extend_openings;
using prepare_surface_detail::find_caps;
using prepare_surface_detail::num;
using prepare_surface_detail::open_caps;
using prepare_surface_detail::repair;
using prepare_surface_detail::Work;

namespace {

Status cancelled() { return Status::Cancelled(); }

/// Phase 1: read the file, weld its corners or points.
Status read_and_weld(PreparedSurface& s, Work& w, std::span<const uint8_t> bytes,
                     const PrepareOptions& options) {
  SurfaceReadOptions read_options;
  read_options.max_triangles = options.read.max_triangles;
  Result<SurfaceFile> file = read_surface(bytes, read_options);
  if (!file.ok()) return file.status();
  SurfaceFile& f = file.value();
  s.ascii = f.soup.ascii;
  s.format = f.format;
  s.input_triangles = f.num_triangles();
  s.warnings = f.warnings;
  w.labels = std::move(f.face_labels);
  w.face_names = std::move(f.face_names);
  s.label_array = f.label_array;
  if (!f.soup.coords.empty())
    s.mesh = weld(std::move(f.soup), options.weld, &s.weld);
  else
    s.mesh = weld(f.points, f.triangles, options.weld, &s.weld);
  if (s.weld.merged_by_tolerance > 0)
    s.warnings.push_back(num(s.weld.merged_by_tolerance) +
                         " nearly coincident vertices were merged");
  return Status::Ok();
}

/// A surface whose inward chords meet the wall on less than this share of its
/// area is a sheet: a vessel's leave only through its openings (95-100% meet
/// on real models), a flat disk's or a trough's never.
constexpr double kSheetShare = 0.5;

/// "the surface encloses no volume: ..." when it is a sheet, else "".
std::string no_volume_text(const PreparedSurface& s) {
  const double share = s.scale.enclosed_share;
  if (!(share >= 0 && share < kSheetShare)) return "";
  return "the surface encloses no volume: it is a single sheet (a flat disk, one side of a "
         "wall), not a vessel's lumen: the inward normal on " +
         number_text(100 * (1 - share), 3) + "% of its area meets no other part of it, e.g. at " +
         point_text(s.scale.open_example) + " " + std::string(unit_symbol(s.unit.unit)) +
         "; export the lumen's whole surface, closed or as a tube cut open at its ends";
}

/// Phase 2e: the model's scale and unit, given or guessed from the scale on
/// the repaired surface (units.h): before smoothing, caps, cuts and flow
/// extensions, so that no option of theirs changes it. The openings weighed
/// are the surface's boundary loops but the holes left open.
void decide_model_unit(PreparedSurface& s, Work& w, const PrepareOptions& options) {
  std::vector<double> radii;
  for (const Opening& op : w.current_topology(s.mesh).openings) {
    bool hole = false;
    for (const Hole& h : s.holes) hole |= !h.closed && h.centroid == op.centroid;
    if (!hole) radii.push_back(op.radius);
  }
  s.scale = measure_vessel_scale(s.mesh, s.repair.orientable, radii, s.label_array);
  s.unit = decide_unit(options.units, s.scale);
  if (std::string sheet = no_volume_text(s); !sheet.empty())
    s.warnings.push_back(sheet + " (meshing refuses it)");
}

/// Phase 3: only the largest component, when asked.
void keep_largest_component(PreparedSurface& s, Work& w) {
  const TopologyReport parts = w.current_topology(s.mesh);
  if (parts.components <= 1) return;
  std::vector<uint8_t> other(s.mesh.num_triangles());
  for (size_t t = 0; t < other.size(); ++t) other[t] = parts.triangle_component[t] != 0;
  remove_triangles(s.mesh, other, &w.labels);
  w.adjacency = build_adjacency(s.mesh);
  w.topology.reset();
  s.warnings.push_back("kept the largest of " + std::to_string(parts.components) + " components (" +
                       num(parts.component_triangles[0]) + " of " + num(parts.triangles) +
                       " triangles)");
}

/// "0.12", or "0.7 x 0.7 x 1.5" for a voxel of unequal sides.
std::string voxel_text(const std::array<double, 3>& spacing) {
  char buf[96];
  const double lo = std::min({spacing[0], spacing[1], spacing[2]});
  const double hi = std::max({spacing[0], spacing[1], spacing[2]});
  if (hi - lo <= 1e-3 * hi)
    std::snprintf(buf, sizeof(buf), "%.4g", hi);
  else
    std::snprintf(buf, sizeof(buf), "%.4g x %.4g x %.4g", spacing[0], spacing[1], spacing[2]);
  return buf;
}

/// Phase 4: smoothing, per options.smoothing: auto smooths voxel staircases
/// (the passes from the voxel), N passes any surface, off nothing. The
/// staircase test runs in every mode, for the report.
void smooth(PreparedSurface& s, Work& w, const PrepareOptions& options,
            const StaircaseReport& staircase_test) {
  SmoothingOutcome& out = s.smoothing;
  out.mode = options.smoothing.mode;
  out.staircase = staircase_test;
  if (out.mode == Smoothing::Mode::kOff) return;
  const bool staircase = out.staircase.staircase;
  if (out.mode == Smoothing::Mode::kAuto && !staircase) return;
  if (w.adjacency.num_nonmanifold_edges > 0 || !s.repair.orientable) {
    s.warnings.push_back(
        std::string(staircase ? "the surface is a voxel staircase but it" : "the surface") +
        " was not smoothed: it has non-manifold edges or is not orientable");
    return;
  }
  SmoothOptions o;
  std::array<double, 3> spacing = out.staircase.spacing;
  if (!staircase) {
    const double edge = median_edge_length(s.mesh);
    spacing = {edge, edge, edge};
  }
  out.voxel = std::max({spacing[0], spacing[1], spacing[2]});
  if (!(out.voxel > 0)) return;
  for (int k = 0; k < 3; ++k) o.max_displacement[size_t(k)] = 0.5 * spacing[size_t(k)];
  // Planar caps (flat regions of a few voxels' area, not facing the grid of
  // a staircase) keep their plane and rims, for phase 5 to find them.
  o.flat_min_area = 16 * out.voxel * out.voxel;
  if (staircase) o.grid = spacing;
  o.passes = out.mode == Smoothing::Mode::kPasses ? options.smoothing.passes
                                                  : staircase_passes(s.mesh, out.voxel);
  out.report = smooth_surface(s.mesh, w.adjacency, o);
  out.applied = true;
  w.topology.reset();                    // the openings' measures changed
  w.smoothing_note = s.warnings.size();  // written once the unit is known
}

/// What phase 4 did, in words, lengths in `unit`.
std::string smoothing_note(const SmoothingOutcome& out, const std::string& unit) {
  const bool staircase = out.staircase.staircase;
  const std::string passes = std::to_string(out.report.passes);
  const std::string voxel =
      voxel_text(staircase ? out.staircase.spacing : std::array{out.voxel, out.voxel, out.voxel}) +
      " " + unit;
  if (out.mode == Smoothing::Mode::kAuto)
    return "the surface is a voxel staircase (voxel " + voxel + "): smoothed with " + passes +
           " passes, every vertex within half a voxel; turn it off with {smooth} off";
  if (staircase)
    return "the surface is a voxel staircase (voxel " + voxel + "): smoothed with " + passes +
           " passes ({smooth} " + passes + "), every vertex within half a voxel";
  return "smoothed with " + passes + " passes ({smooth} " + passes +
         "), every vertex within half the median edge length (" + voxel + ")";
}

/// Phase 8: topology, where each opening comes from, what later stages
/// will refuse.
void analyze(PreparedSurface& s, Work& w) {
  w.current_topology(s.mesh);
  s.topology = std::move(*w.topology);
  w.topology.reset();
  if (!w.order_of_vertex.empty())
    std::stable_sort(s.topology.openings.begin(), s.topology.openings.end(),
                     [&](const Opening& a, const Opening& b) {
                       return w.order_of_vertex[size_t(a.loop[0])] <
                              w.order_of_vertex[size_t(b.loop[0])];
                     });
  for (const Opening& op : s.topology.openings) {
    const int32_t src = w.source_of_vertex.empty() ? -1 : w.source_of_vertex[size_t(op.loop[0])];
    s.opening_sources.push_back(src >= 0 ? w.sources[size_t(src)] : OpeningSource{});
  }
  s.box = bounding_box(s.mesh.points);
  const TopologyReport& t = s.topology;
  if (t.nonmanifold_edges > 0)
    s.warnings.push_back(num(t.nonmanifold_edges) +
                         " non-manifold edges (shared by 3 or more triangles), e.g. near " +
                         point_text(t.nonmanifold_edge_example));
  if (t.nonmanifold_vertices > 0)
    s.warnings.push_back(num(t.nonmanifold_vertices) +
                         " non-manifold vertices (surface sheets touching at a single vertex)");
  if (t.components > 1)
    s.warnings.push_back(std::to_string(t.components) + " connected components; the largest has " +
                         num(t.component_triangles[0]) + " of " + num(t.triangles) + " triangles");
}

/// Phase 9 (after the unit is decided): where the surface crosses itself (up to
/// kSelfCrossingCheckLimit triangles): later stages fail on such a surface, in their own terms.
void find_crossings(PreparedSurface& s) {
  if (s.mesh.num_triangles() > kSelfCrossingCheckLimit) {
    s.warnings.push_back("the surface was not checked for crossing itself (" +
                         num(s.mesh.num_triangles()) + " triangles, over " +
                         num(kSelfCrossingCheckLimit) + ")");
    return;
  }
  s.self_crossings = find_self_crossings(s.mesh);
  s.self_crossings_checked = true;
  const SelfCrossings& c = s.self_crossings;
  if (c.pairs == 0) return;
  std::string at;
  for (size_t i = 0; i < c.places.size(); ++i) at += (i ? ", " : "") + point_text(c.places[i]);
  at += " " + std::string(unit_symbol(s.unit.unit));
  s.warnings.push_back(
      "the surface crosses itself at " +
      (c.place_count == 1 ? std::string("1 place") : num(c.place_count) + " places") + " (" +
      num(c.pairs) + " pairs of triangles)" + (c.place_count == 1 ? ", at " : ", e.g. at ") + at +
      ": a wall passes through another there (a wall pushed through the opposite one, or "
      "branches fused wrongly) and meshing may fail; fix it in the segmentation (or cut that "
      "part off with {clip_plane})");
}

}  // namespace

const char* opening_shape_name(OpeningSource::Shape shape) {
  switch (shape) {
    case OpeningSource::kNone:
      return "";
    case OpeningSource::kLabelled:
      return "labelled";
    case OpeningSource::kPlanar:
      return "planar";
    case OpeningSource::kFan:
      return "fan";
    case OpeningSource::kDome:
      return "dome";
    case OpeningSource::kBlindEnd:
      return "blind_end";
    case OpeningSource::kPlane:
      return "plane";
    case OpeningSource::kPoint:
      return "point";
    case OpeningSource::kDamagedEnd:
      return "damaged_end";
  }
  return "";
}

std::string self_crossing_prefix(const PreparedSurface& s) {
  const SelfCrossings& c = s.self_crossings;
  if (c.pairs == 0 || c.places.empty()) return "";
  return "the input crosses itself at " + point_text(c.places[0]) + " " +
         std::string(unit_symbol(s.unit.unit)) + " (" +
         (c.place_count == 1 ? std::string("1 place") : num(c.place_count) + " places") +
         "; fix it in the segmentation, or cut that part off with {clip_plane}): ";
}

Result<PreparedSurface> prepare_surface(std::span<const uint8_t> file_bytes,
                                        const PrepareOptions& options, const ProgressFn& progress) {
  PreparedSurface s;
  Work w;
  if (!report_progress(progress, 0.0, "read")) return cancelled();
  if (Status st = read_and_weld(s, w, file_bytes, options); !st.ok()) return st;
  if (!report_progress(progress, 0.3, "repair")) return cancelled();
  if (Status st = repair(s, w, options); !st.ok()) return st;
  decide_model_unit(s, w, options);
  if (options.largest_component_only) keep_largest_component(s, w);
  if (!report_progress(progress, 0.4, "smooth")) return cancelled();
  // The staircase test (phase 4) and the cap search (phase 5) read the same
  // surface: with threads they run side by side, and the caps are searched
  // again if the smoothing moved the surface.
  // Both read the triangles' normals, computed once.
  {
    const TriangleNormals normals = triangle_normals(s.mesh);
    StaircaseReport staircase;
    std::optional<CapRecognition> caps;
    const bool side_by_side = thread_count() > 1 && caps_wanted(s, w, options);
    parallel_for(side_by_side ? 2 : 1, 1, [&](size_t task, size_t) {
      if (task == 0)
        staircase = detect_staircase(s.mesh, {}, &normals);
      else
        caps = find_caps(s, w, options, &normals);
    });
    smooth(s, w, options, staircase);
    if (s.smoothing.applied) caps.reset();
    if (!report_progress(progress, 0.5, "caps")) return cancelled();
    open_caps(s, w, options, std::move(caps), s.smoothing.applied ? nullptr : &normals);
  }
  if (!report_progress(progress, 0.55, "clip")) return cancelled();
  if (Status st = clip(s, w, options); !st.ok()) return st;
  if (!report_progress(progress, 0.6, "extend")) return cancelled();
  if (Status st = extend_openings(s, w, options); !st.ok()) return st;
  if (!report_progress(progress, 0.6, "analyze")) return cancelled();
  analyze(s, w);
  if (w.smoothing_note != std::string::npos)
    s.warnings.insert(s.warnings.begin() + long(w.smoothing_note),
                      smoothing_note(s.smoothing, std::string(unit_symbol(s.unit.unit))));
  if (s.unit.guessed && s.unit.unit == LengthUnit::kM)
    s.warnings.push_back("the model is in metres (" + s.unit.reason +
                         "): lengths are read and written in metres; say otherwise with {units}");
  if (!report_progress(progress, 0.7, "self-crossings")) return cancelled();
  find_crossings(s);
  if (!report_progress(progress, 0.85, "quality")) return cancelled();
  s.quality = triangle_qualities(s.mesh);
  s.quality_stats = quality_stats(s.quality, options.histogram_bins);
  if (!report_progress(progress, 1.0, "done")) return cancelled();
  return s;
}

Status cut_openings_deeper(PreparedSurface& s, const std::vector<Vec3>& places, double depth) {
  const TopologyReport& t = s.topology;
  if (t.openings.empty()) return Status::Error("no opening to cut deeper");
  // The openings at the places, each once, nearest by a rim vertex.
  std::vector<size_t> which;
  for (const Vec3& p : places) {
    size_t best = 0;
    double best_d = 1e300;
    for (size_t o = 0; o < t.openings.size(); ++o)
      for (int32_t v : t.openings[o].loop)
        if (const double d = norm(at(s.mesh.points, v) - p); d < best_d) best_d = d, best = o;
    if (std::find(which.begin(), which.end(), best) == which.end()) which.push_back(best);
  }
  // The work of the phases, rebuilt from the prepared surface: each rim's
  // source, so the openings left keep theirs.
  Work w;
  w.adjacency = build_adjacency(s.mesh);
  w.sources = s.opening_sources;
  w.source_of_vertex.assign(s.mesh.num_vertices(), -1);
  for (size_t o = 0; o < t.openings.size(); ++o)
    for (int32_t v : t.openings[o].loop) w.source_of_vertex[size_t(v)] = int32_t(o);
  std::vector<ClipPlane> planes;
  for (size_t o : which) {
    const Opening& op = t.openings[o];
    // Out of the vessel: away from the wall's vertices near the rim.
    Vec3 n = normalized(Vec3(op.normal));
    Vec3 mean{0, 0, 0};
    size_t count = 0;
    for (size_t v = 0; v < s.mesh.num_vertices(); ++v)
      if (const Vec3 q = at(s.mesh.points, int32_t(v)); norm(q - Vec3(op.centroid)) < 2 * op.radius)
        mean = mean + q, ++count;
    if (count > 0 && dot((1.0 / double(count)) * mean - Vec3(op.centroid), n) > 0) n = -1.0 * n;
    planes.push_back({Vec3(op.centroid) - (depth * op.radius) * n, n});
  }
  for (size_t i = 0; i < planes.size(); ++i) {
    const Opening& op = t.openings[which[i]];
    const Vec3 was = op.centroid;
    const double radius = op.radius;
    if (Status st = clip_one(s, w, planes[i], OpeningSource::kPlane); !st.ok()) return st;
    s.warnings.push_back("the opening at " + point_text(was) + " (radius " + number_text(radius) +
                         ") was cut again " + number_text(depth, 2) +
                         " radii deeper: the wall met its plane at a grazing angle, where the "
                         "boundary layer cannot start");
  }
  s.opening_sources.clear();
  analyze(s, w);
  if (s.self_crossings_checked) {
    s.self_crossings = {};
    find_crossings(s);
  }
  s.quality = triangle_qualities(s.mesh);
  s.quality_stats = quality_stats(s.quality, int(s.quality_stats.histogram.size()));
  return Status::Ok();
}

Status check_meshable(const PreparedSurface& s) {
  const TopologyReport& t = s.topology;
  // Without the repairs, the remedy is to turn them on.
  const Remedy repair_on{s.repaired ? "" : "repair", {}, 0};
  if (t.nonmanifold_edges > 0) {
    return Status::Error("cannot mesh: the surface has " + num(t.nonmanifold_edges) +
                         " non-manifold edges (shared by 3 or more triangles), e.g. near " +
                         point_text(t.nonmanifold_edge_example) +
                         (s.repaired ? "; fix the segmentation or export a manifold surface"
                                     : "; split them into manifold sheets with {repair} auto"))
        .WithRemedy({repair_on.action, {t.nonmanifold_edge_example}, 0});
  }
  if (t.nonmanifold_vertices > 0) {
    return Status::Error("cannot mesh: the surface has " + num(t.nonmanifold_vertices) +
                         " non-manifold vertices (sheets touching at a vertex)" +
                         (s.repaired ? std::string() : "; split them with {repair} auto"))
        .WithRemedy(repair_on);
  }
  if (!s.repair.orientable) {
    return Status::Error("cannot mesh: the surface is not orientable" +
                         std::string(s.repaired ? "" : "; repair it with {repair} auto"))
        .WithRemedy(repair_on);
  }
  if (std::string sheet = no_volume_text(s); !sheet.empty())
    return Status::Error("cannot mesh: " + sheet);
  if (t.components > 1) {
    return Status::Error("cannot mesh: the surface has " + std::to_string(t.components) +
                         " connected components (the largest has " + num(t.component_triangles[0]) +
                         " of " + num(t.triangles) +
                         " triangles); keep only the largest ({largest_component_only}) or clean the "
                         "segmentation")
        .WithRemedy({"largest_component", {}, 0});
  }
  return Status::Ok();
}

}  // namespace vm
