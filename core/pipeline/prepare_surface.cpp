// Stage 1 of the pipeline (docs/ARCHITECTURE.md): read, weld, repair,
// smooth voxel staircases, recognise caps, analyze, decide the unit.
#include "core/pipeline/prepare_surface.h"

#include <algorithm>
#include <cstdio>
#include <optional>
#include <set>

#include "core/geom/vec3.h"
#include "core/mesh/chord_radius.h"
#include "core/prepare/cut_across_vessel.h"
#include "core/prepare/fill_holes.h"
#include "core/prepare/flow_extensions.h"
#include "core/prepare/vessel_ends.h"
#include "core/util/parallel.h"

namespace vm {
namespace {

std::string num(size_t n) { return std::to_string(n); }

Status cancelled() { return Status::Cancelled(); }

/// What the phases pass on besides the surface: face labels (one per
/// triangle, or empty), the file's face names, the adjacency of the current
/// mesh, and where openings come from: per vertex an index into `sources`
/// (-1: an opening of the file, or no opening).
struct Work {
  std::vector<int32_t> labels;
  std::vector<std::pair<int32_t, std::string>> face_names;
  TriangleAdjacency adjacency;
  /// The topology of the current mesh when it is known (analyze_topology
  /// with `adjacency`); reset by every phase that changes the mesh.
  std::optional<TopologyReport> topology;
  std::vector<OpeningSource> sources;
  std::vector<int32_t> source_of_vertex;
  /// Set by flow extensions: per vertex, the opening it bounds in the
  /// order before extension (-1: none), which the analysis keeps (an
  /// extension keeps an opening's area, but ties could reorder).
  std::vector<int32_t> order_of_vertex;
  /// Where phase 4's note goes among the warnings (none: npos).
  size_t smoothing_note = std::string::npos;

  /// The topology of the current mesh, analyzed once.
  const TopologyReport& current_topology(const SurfaceMesh& mesh) {
    if (!topology) topology = analyze_topology(mesh, adjacency);
    return *topology;
  }

  /// After vertices were renumbered (old -> new, -1 removed).
  void remap_vertices(const std::vector<int32_t>& remap, size_t new_count) {
    if (source_of_vertex.empty()) return;
    std::vector<int32_t> moved(new_count, -1);
    for (size_t v = 0; v < remap.size() && v < source_of_vertex.size(); ++v)
      if (remap[v] >= 0) moved[size_t(remap[v])] = source_of_vertex[v];
    source_of_vertex = std::move(moved);
  }
};

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

/// "(x, y, z), (x, y, z) and 3 more": the first few places of a list.
std::string places_text(const std::vector<Vec3>& places) {
  std::string out;
  const size_t shown = std::min<size_t>(places.size(), 3);
  for (size_t i = 0; i < shown; ++i) out += (i ? ", " : "") + point_text(places[i]);
  if (places.size() > shown) out += " and " + num(places.size() - shown) + " more";
  return out;
}

/// A boundary loop that passes a vertex more than once (holes touching at
/// a vertex) as simple cycles, in order.
std::vector<std::vector<int32_t>> simple_cycles(const std::vector<int32_t>& loop) {
  std::vector<std::vector<int32_t>> out;
  std::vector<int32_t> stack;
  for (int32_t v : loop) {
    auto it = std::find(stack.begin(), stack.end(), v);
    if (it != stack.end()) {
      out.emplace_back(it, stack.end());
      stack.erase(it + 1, stack.end());
    } else {
      stack.push_back(v);
    }
  }
  if (!stack.empty()) {
    // The loop closes on its first vertex: what is left is a cycle too.
    out.push_back(std::move(stack));
  }
  return out;
}

/// Phase 2, after orientation, always: specks, separate pieces with less than 1% of the
/// largest piece's triangles or area (stray triangles, segmentation
/// islands), are removed, saying where.
void drop_specks(PreparedSurface& s, Work& w) {
  const TopologyReport& parts = w.current_topology(s.mesh);
  if (parts.components <= 1) return;
  std::vector<double> area(size_t(parts.components), 0);
  std::vector<Vec3> where(size_t(parts.components), Vec3{0, 0, 0});
  for (size_t t = 0; t < s.mesh.num_triangles(); ++t) {
    const int32_t* c = &s.mesh.triangles[3 * t];
    const Vec3 a = at(s.mesh.points, c[0]), b = at(s.mesh.points, c[1]),
               d = at(s.mesh.points, c[2]);
    const size_t k = size_t(parts.triangle_component[t]);
    area[k] += 0.5 * norm(cross(b - a, d - a));
    where[k] = a;
  }
  std::vector<uint8_t> speck(size_t(parts.components), 0);
  size_t count = 0, triangles = 0;
  std::string example;
  for (size_t k = 1; k < speck.size(); ++k)
    if (parts.component_triangles[k] < 0.01 * double(parts.component_triangles[0]) ||
        area[k] < 0.01 * area[0]) {
      speck[k] = 1;
      ++count;
      triangles += parts.component_triangles[k];
      if (example.empty()) example = point_text(where[k]);
    }
  if (count == 0) return;
  std::vector<uint8_t> remove(s.mesh.num_triangles());
  for (size_t t = 0; t < remove.size(); ++t) remove[t] = speck[size_t(parts.triangle_component[t])];
  remove_triangles(s.mesh, remove, &w.labels);
  w.adjacency = build_adjacency(s.mesh);
  w.topology.reset();
  s.specks_removed = count;
  s.warnings.push_back(count == 1
                           ? "removed a small separate piece (" + num(triangles) +
                                 (triangles == 1 ? " triangle" : " triangles") +
                                 ", under 1% of the surface) at " + example
                           : "removed " + num(count) + " small separate pieces (" + num(triangles) +
                                 " triangles, each under 1% of the surface), e.g. at " + example);
}

/// Phase 2b ({repair} auto): fins dropped, non-manifold edges split.
void repair_edges(PreparedSurface& s, Work& w) {
  ManifoldRepairStats& m = s.manifold;
  split_nonmanifold_edges(s.mesh, &w.labels, m, &w.adjacency);
  if (m.fins_removed > 0)
    s.warnings.push_back(num(m.fins_removed) +
                         " fin triangles hanging on non-manifold edges were removed, e.g. at " +
                         point_text(m.fin_example));
  // A local twist (at most 20 triangles or 0.1% of them) is cut out; the
  // holes it leaves are closed with the others.
  const size_t budget = std::max<size_t>(20, s.mesh.num_triangles() / 1000);
  if (remove_orientation_twists(s.mesh, &w.labels, m, budget, &w.adjacency) > 0)
    s.warnings.push_back(num(m.twisted_removed) +
                         " triangles whose orientation contradicted their neighbors' (a local "
                         "twist that made the surface non-orientable) were removed, e.g. at " +
                         point_text(m.twisted_example) +
                         "; the holes they leave are closed when smaller than {hole_fraction} of "
                         "the local radius");
  if (m.edges_split > 0)
    s.warnings.push_back(num(m.edges_split) +
                         " non-manifold edges were split into manifold sheets (their triangles "
                         "paired in angular order around the edge), e.g. at " +
                         point_text(m.edge_example) + "; turn this off with {repair} off");
}

/// Phase 2c: boundary loops smaller than {hole_fraction} of the local
/// vessel radius are holes; closed when {repair} is auto. The local radius
/// is the median, over the loop's vertices, of the half chord across the
/// lumen along the inward normal (chord_radius, the measure the layers use):
/// at the rim of a real opening it is about the opening's own radius, at a
/// defect in the wall it is the vessel's, whatever the loop's size.
/// Needs an orientable surface; the chords are cast on a copy whose
/// non-manifold vertices are split (same vertex numbers, copies appended).
void find_and_close_holes(PreparedSurface& s, Work& w, const PrepareOptions& options) {
  if (!s.repair.orientable || w.adjacency.num_nonmanifold_edges > 0) return;
  const TopologyReport& t = w.current_topology(s.mesh);
  if (t.openings.empty() || !(options.hole_fraction > 0) || s.mesh.num_triangles() > 2'000'000)
    return;
  std::vector<double> chord;
  if (t.nonmanifold_vertices > 0) {
    SurfaceMesh manifold = s.mesh;
    ManifoldRepairStats unused;
    split_nonmanifold_vertices(manifold, unused);
    chord = chord_radius(manifold);
  } else {
    chord = chord_radius(s.mesh);
  }
  // Loops through a vertex twice are split into simple cycles; a cycle
  // whose edges another loop has already is not listed twice.
  std::vector<Opening> candidates;
  std::set<std::pair<int32_t, int32_t>> taken;
  auto take = [&](const std::vector<int32_t>& loop) {
    bool fresh = false;
    for (size_t i = 0; i < loop.size(); ++i)
      fresh |= taken.insert({loop[i], loop[(i + 1) % loop.size()]}).second;
    return fresh;
  };
  for (const Opening& op : t.openings)
    if (std::set<int32_t>(op.loop.begin(), op.loop.end()).size() == op.loop.size() && take(op.loop))
      candidates.push_back(op);
  for (const Opening& op : t.openings) {
    if (std::set<int32_t>(op.loop.begin(), op.loop.end()).size() == op.loop.size()) continue;
    for (std::vector<int32_t>& cycle : simple_cycles(op.loop))
      if (cycle.size() >= 3 && take(cycle))
        candidates.push_back(describe_loop(s.mesh, std::move(cycle)));
  }
  std::vector<std::vector<int32_t>> loops;
  for (const Opening& op : candidates) {
    if (!(op.perimeter > 0) || op.loop.size() < 3) continue;  // never a zero-length loop
    std::vector<double> r;
    for (int32_t v : op.loop) r.push_back(chord[size_t(v)]);
    std::nth_element(r.begin(), r.begin() + long(r.size() / 2), r.end());
    const double local = r[r.size() / 2];
    if (!(op.radius < options.hole_fraction * local)) continue;
    Hole h;
    h.perimeter = op.perimeter;
    h.radius = op.radius;
    h.centroid = op.centroid;
    h.vessel_radius = local;
    s.holes.push_back(h);
    loops.push_back(op.loop);
  }
  if (s.holes.empty()) return;
  const std::string fraction = number_text(options.hole_fraction);
  if (!options.repair) {
    std::vector<Vec3> where;
    for (const Hole& h : s.holes) where.push_back(h.centroid);
    s.warnings.push_back(num(s.holes.size()) + " holes smaller than " + fraction +
                         " of the local vessel radius were left open ({repair} off), at " +
                         places_text(where) + ": they would be meshed as openings");
    return;
  }
  const std::vector<HoleFill> fills = fill_holes(s.mesh, loops, &w.labels);
  w.topology.reset();  // `t` is not used below
  std::vector<Vec3> closed, open;
  for (size_t i = 0; i < fills.size(); ++i) {
    Hole& h = s.holes[i];
    h.closed = fills[i].filled;
    h.triangles_added = fills[i].triangles_added;
    h.min_angle = fills[i].min_angle;
    (h.closed ? closed : open).push_back(h.centroid);
  }
  if (!closed.empty())
    s.warnings.push_back(num(closed.size()) + " holes smaller than " + fraction +
                         " of the local vessel radius ({hole_fraction}) were closed, at " +
                         places_text(closed) + "; keep them open with {repair} off");
  if (!open.empty())
    s.warnings.push_back(num(open.size()) +
                         " holes could not be closed (their fill would repeat "
                         "an edge of the surface), at " +
                         places_text(open) + ": they stay openings; fix the segmentation there");
}

/// Phase 2d ({repair} auto): vertices where several fans meet duplicated.
/// Nothing to do when the current topology is known to have none.
void repair_vertices(PreparedSurface& s, Work& w) {
  if (w.topology && w.topology->nonmanifold_vertices == 0) return;
  ManifoldRepairStats& m = s.manifold;
  // The adjacency is current unless holes were closed.
  split_nonmanifold_vertices(s.mesh, m, s.holes.empty() ? &w.adjacency : nullptr);
  if (m.vertices_split > 0) w.topology.reset();
  if (m.vertices_split > 0)
    s.warnings.push_back(num(m.vertices_split) +
                         " non-manifold vertices (several triangle fans meeting) were split, one "
                         "copy per fan, e.g. at " +
                         point_text(m.vertex_example));
}

/// Phase 2a ({repair} auto): where the surface crosses itself, the part
/// around the crossing is re-surfaced as the boundary of the union of what
/// it encloses (overlapping shells, a patch glued over the wall, vessels
/// passing into each other).
void resurface(PreparedSurface& s, Work& w) {
  s.resurfaced = resurface_crossings(s.mesh, &w.labels);
  const ResurfaceReport& r = s.resurfaced;
  if (r.resolved() > 0) {
    w.adjacency = build_adjacency(s.mesh);
    w.topology.reset();
  }
  for (const ResurfacedPlace& p : r.places) {
    if (p.resolved)
      s.warnings.push_back(
          "the surface crossed itself at " + point_text(p.where) + " (" + num(p.pairs) +
          " pairs of triangles: overlapping or intersecting sheets): re-surfaced there as the "
          "boundary of what the sheets enclose together, between " +
          point_text(p.box_min) + " and " + point_text(p.box_max) + " (" +
          num(p.triangles_removed) + " triangles replaced by " + num(p.triangles_added) +
          "); turn this off with {repair} off");
    else if (!p.near_opening)
      s.warnings.push_back(
          "the surface crosses itself at " + point_text(p.where) + " (" + num(p.pairs) +
          " pairs of triangles) and could not be re-surfaced there (" + p.why + ")");
  }
}

/// Phase 2b ({repair} auto): damaged vessel ends (crossing, folded or
/// twisted triangles beside an opening) lose their damaged part; the clean
/// cross-section is cut in phase 6 (trim_planes).
void trim_ends(PreparedSurface& s, Work& w) {
  s.trimmed_ends = trim_damaged_ends(s.mesh, &w.labels, s.resurfaced.left);
  s.resurfaced.left.clear();
  bool changed = false;
  for (const TrimmedEnd& e : s.trimmed_ends) {
    changed |= e.triangles_removed > 0;
    std::string what;
    auto add = [&](size_t n, const char* kind) {
      if (n > 0) what += (what.empty() ? "" : ", ") + num(n) + " " + kind;
    };
    add(e.crossing, "crossing");
    add(e.misoriented, "twisted or folded");
    add(e.nonmanifold, "non-manifold");
    add(e.tiny_loops, "around tiny loops");
    s.warnings.push_back(
        "the vessel end at " + point_text(e.where) + " (radius " + number_text(e.radius) +
        ") is damaged (triangles " + what + ")" +
        (e.trimmed ? ": trimmed back to its first clean cross-section, " +
                         number_text(e.depth / e.radius, 2) +
                         (e.depth == e.radius ? " radius" : " radii") +
                         " in; turn this off with {repair} off"
                   : ": it was not trimmed (the damage reaches more than 3 radii in, or the "
                     "trim would take a fifth of the surface); cut the vessel across below it "
                     "with {clip_at}"));
  }
  if (changed) {
    w.adjacency = build_adjacency(s.mesh);
    w.topology.reset();
  }
}

/// Phase 2: safe repairs (degenerate and duplicate triangles), then with
/// {repair} auto non-manifold edges split; outward orientation; holes
/// found (and closed with {repair} auto); non-manifold vertices split.
Status repair(PreparedSurface& s, Work& w, const PrepareOptions& options) {
  remove_degenerate_and_duplicates(s.mesh, s.repair, &w.labels);
  const RepairStats& r = s.repair;
  if (r.degenerate_removed > 0)
    s.warnings.push_back(num(r.degenerate_removed) + " zero-area triangles were removed, e.g. at " +
                         point_text(r.degenerate_example));
  if (r.collinear_repaired > 0)
    s.warnings.push_back(num(r.collinear_repaired) +
                         " flat triangles (collinear corners) were removed by "
                         "splitting their neighbors, e.g. at " +
                         point_text(r.collinear_example));
  if (r.duplicates_removed > 0)
    s.warnings.push_back(num(r.duplicates_removed) + " duplicate triangles were removed, e.g. at " +
                         point_text(r.duplicate_example));
  if (s.mesh.num_triangles() == 0)
    return Status::Error("no triangle left: all " + num(s.input_triangles) +
                         " triangles of the file have zero area");
  s.repaired = options.repair;
  // One adjacency, kept current through the steps that change the mesh.
  w.adjacency = build_adjacency(s.mesh);
  if (options.repair && s.mesh.num_triangles() <= kSelfCrossingCheckLimit) {
    resurface(s, w);
    trim_ends(s, w);
  }
  if (options.repair) repair_edges(s, w);
  orient_consistently(s.mesh, s.repair, &w.adjacency, true);
  if (!s.repair.orientable) {
    s.warnings.push_back("the surface is not orientable: it cannot bound a volume");
  } else if (s.repair.flipped == s.mesh.num_triangles()) {
    s.warnings.push_back("the normals pointed inward: all triangles were reversed to face out");
  } else if (s.repair.flipped > 0) {
    s.warnings.push_back(
        num(s.repair.flipped) + (s.repair.flipped == 1 ? " triangle was" : " triangles were") +
        " re-oriented (consistent, outward), e.g. at " + point_text(s.repair.flipped_example));
  }
  drop_specks(s, w);
  find_and_close_holes(s, w, options);
  if (options.repair) {
    repair_vertices(s, w);
    if (!s.holes.empty() || s.manifold.vertices_split > 0) w.adjacency = build_adjacency(s.mesh);
  }
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

/// Whether phase 5 looks for caps on this surface.
bool caps_wanted(const PreparedSurface& s, const Work& w, const PrepareOptions& options) {
  return !options.keep_caps && w.adjacency.num_nonmanifold_edges == 0 && s.repair.orientable;
}

/// `normals`: triangle_normals(s.mesh) if known.
CapRecognition find_caps(const PreparedSurface& s, const Work& w, const PrepareOptions& options,
                         const TriangleNormals* normals) {
  return recognize_caps(s.mesh, w.adjacency, w.labels, w.face_names, options.caps, normals);
}

/// Cuts the surface with one plane; the new opening's vertices get
/// `source`. Returns the cut, or the error of clip_surface.
Result<ClipCut> cut_open(PreparedSurface& s, Work& w, const ClipPlane& plane,
                         const OpeningSource& source) {
  Result<ClipResult> r = clip_surface(s.mesh, w.labels, std::span(&plane, 1));
  if (!r.ok()) return r.status();
  ClipResult& c = r.value();
  std::vector<int32_t> sources(c.mesh.num_vertices(), -1);
  for (size_t v = 0; v < sources.size(); ++v) {
    const int32_t in = c.input_vertex[v];
    if (in >= 0 && size_t(in) < w.source_of_vertex.size())
      sources[v] = w.source_of_vertex[size_t(in)];
  }
  const int32_t index = int32_t(w.sources.size());
  w.sources.push_back(source);
  for (size_t v = 0; v < sources.size(); ++v)
    if (c.cut_of_vertex[v] == 0) sources[v] = index;
  w.source_of_vertex = std::move(sources);
  s.mesh = std::move(c.mesh);
  w.labels = std::move(c.labels);
  w.topology.reset();
  if (c.components_dropped > 0)
    s.warnings.push_back("the cut at " + point_text(plane.point) + " left " +
                         std::to_string(c.components_dropped) + " separate pieces (" +
                         num(c.triangles_dropped) + " triangles): removed");
  w.adjacency = build_adjacency(s.mesh);
  return c.cuts[0];
}

/// A cut by clipping ({clip} auto, {clip_plane}, {clip_at}): an opening of
/// source "clip", listed in s.clips.
Status clip_one(PreparedSurface& s, Work& w, const ClipPlane& plane, OpeningSource::Shape why) {
  OpeningSource source;
  source.kind = OpeningSource::kClip;
  source.shape = why;
  Result<ClipCut> cut = cut_open(s, w, plane, source);
  if (!cut.ok()) return cut.status();
  s.clips.push_back(cut.value());
  return Status::Ok();
}

/// How a recognised cap is said in a warning: "a fan at (x, y, z), radius
/// r, 0.1 radius high" ("face 3 (aorta) at ..." for a labelled one).
std::string cap_text(const RecognizedCap& cap, const std::string& label_array) {
  std::string what;
  switch (cap.shape) {
    case CapShape::kLabelled:
      what = (label_array.empty() ? std::string("face") : label_array) + " " +
             std::to_string(cap.label) + (cap.name.empty() ? "" : " (" + cap.name + ")");
      break;
    case CapShape::kPlanar:
      what = "a planar cap";
      break;
    case CapShape::kFan:
      what = "a fan";
      break;
    case CapShape::kDome:
      what = "a dome";
      break;
  }
  what += " at " + point_text(cap.centroid) + ", radius " + number_text(cap.radius);
  if (cap.cut_at_rim) what += ", " + number_text(cap.height / cap.radius, 2) + " radius high";
  return what;
}

/// The opening shape of a cap's shape.
OpeningSource::Shape opening_shape(CapShape shape) {
  switch (shape) {
    case CapShape::kLabelled:
      return OpeningSource::kLabelled;
    case CapShape::kFan:
      return OpeningSource::kFan;
    case CapShape::kDome:
      return OpeningSource::kDome;
    case CapShape::kPlanar:
      break;
  }
  return OpeningSource::kPlanar;
}

/// Phase 5: caps removed, their rims openings of source "cap": planar
/// (labelled or by shape) ones by removing their triangles, then fans and
/// domes by a cut at their rim's best-fit plane (kept as wall if that cut
/// fails). `found`: the caps already recognised on the current surface, if
/// any; `normals`: the current surface's, if known.
void open_caps(PreparedSurface& s, Work& w, const PrepareOptions& options,
               std::optional<CapRecognition> found, const TriangleNormals* normals) {
  if (!caps_wanted(s, w, options)) return;
  const CapRecognition caps = found ? std::move(*found) : find_caps(s, w, options, normals);
  for (const std::string& note : caps.notes) s.warnings.push_back(note);
  if (caps.caps.empty()) return;
  std::vector<uint8_t> remove(s.mesh.num_triangles(), 0);
  w.source_of_vertex.resize(s.mesh.num_vertices(), -1);
  for (const RecognizedCap& cap : caps.caps) {
    if (cap.cut_at_rim) continue;
    const int32_t source = int32_t(w.sources.size());
    OpeningSource src;
    src.kind = OpeningSource::kCap;
    src.label = cap.label;
    src.name = cap.name;
    src.shape = opening_shape(cap.shape);
    w.sources.push_back(src);
    for (int32_t t : cap.triangles) {
      remove[size_t(t)] = 1;
      for (int k = 0; k < 3; ++k)
        w.source_of_vertex[size_t(s.mesh.triangles[3 * size_t(t) + k])] = source;
    }
  }
  if (std::any_of(remove.begin(), remove.end(), [](uint8_t r) { return r != 0; })) {
    const std::vector<int32_t> remap = remove_triangles(s.mesh, remove, &w.labels);
    w.remap_vertices(remap, s.mesh.num_vertices());
    w.adjacency = build_adjacency(s.mesh);
    w.topology.reset();
  }
  size_t removed = 0, fans = 0, domes = 0;
  std::string list;
  for (const RecognizedCap& cap : caps.caps) {
    if (cap.cut_at_rim) {
      OpeningSource src;
      src.kind = OpeningSource::kCap;
      src.shape = opening_shape(cap.shape);
      const Result<ClipCut> cut = cut_open(s, w, ClipPlane{cap.centroid, cap.normal}, src);
      if (!cut.ok()) {
        s.warnings.push_back("the " + std::string(cap_shape_name(cap.shape)) + " cap at " +
                             point_text(cap.centroid) +
                             " was kept as wall: it could not be cut at its rim (" + cut.message() +
                             ")");
        continue;
      }
      fans += cap.shape == CapShape::kFan;
      domes += cap.shape == CapShape::kDome;
    }
    ++removed;
    list += (list.empty() ? "" : "; ") + cap_text(cap, s.label_array);
  }
  s.caps_removed = removed;
  if (removed == 0) return;
  if (fans + domes == 0)
    s.warnings.push_back(num(removed) + (removed == 1 ? " planar cap was" : " planar caps were") +
                         " recognised and removed: their rims are openings now (keep them with "
                         "{keep_caps}): " +
                         list);
  else
    s.warnings.push_back(num(removed) + (removed == 1 ? " cap was" : " caps were") +
                         " recognised and removed (" + num(removed - fans - domes) + " planar, " +
                         num(fans) + (fans == 1 ? " fan, " : " fans, ") + num(domes) +
                         (domes == 1 ? " dome" : " domes") +
                         "): their rims are openings now, each fan and dome cut at its rim's "
                         "best-fit plane (keep them with {keep_caps}): " +
                         list);
}

/// Phase 7: flow extensions at the openings asked for, their new ends
/// keeping where the openings came from.
Status extend_openings(PreparedSurface& s, Work& w, const PrepareOptions& options) {
  if (options.flow_extension <= 0 && options.flow_extensions.empty()) return Status::Ok();
  const TopologyReport before = w.current_topology(s.mesh);
  const size_t n = before.openings.size();
  std::vector<double> lengths(n, options.flow_extension);
  for (const auto& [k, length] : options.flow_extensions) {
    if (k < 0 || size_t(k) >= n)
      return Status::BadOption(
          "flow_extension",
          "names opening " + std::to_string(k + 1) + ", but there " +
              (n == 1 ? std::string("is 1 opening") : "are " + num(n) + " openings"));
    lengths[size_t(k)] = length;
  }
  std::vector<int32_t> opening_of_new_vertex;
  const size_t first_new = s.mesh.num_vertices();
  auto added =
      add_flow_extensions(s.mesh, &w.labels, before.openings, lengths, &opening_of_new_vertex);
  if (!added.ok()) return added.status();
  // The new ends take their opening's source, with the extension's length.
  w.source_of_vertex.resize(first_new, -1);
  std::vector<int32_t> source_of_opening(n, -1);
  for (const FlowExtension& e : added.value()) {
    const int32_t old = w.source_of_vertex[size_t(before.openings[e.opening].loop[0])];
    OpeningSource src = old >= 0 ? w.sources[size_t(old)] : OpeningSource{};
    src.extension = e.length;
    source_of_opening[e.opening] = int32_t(w.sources.size());
    w.sources.push_back(src);
  }
  for (int32_t o : opening_of_new_vertex)
    w.source_of_vertex.push_back(source_of_opening[size_t(o)]);
  w.topology.reset();
  w.order_of_vertex.assign(s.mesh.num_vertices(), -1);
  for (size_t o = 0; o < n; ++o)
    for (int32_t v : before.openings[o].loop) w.order_of_vertex[size_t(v)] = int32_t(o);
  for (size_t i = 0; i < opening_of_new_vertex.size(); ++i)
    w.order_of_vertex[first_new + i] = opening_of_new_vertex[i];
  w.adjacency = build_adjacency(s.mesh);
  std::string where;
  for (const FlowExtension& e : added.value())
    where += (where.empty() ? "" : ", ") + std::to_string(e.opening + 1) + " (" +
             std::to_string(e.rings) + " rings)";
  if (!added.value().empty())
    s.warnings.push_back("flow extensions added at opening " + where +
                         ": straight along each opening's normal, ending in a circle of its area");
  return Status::Ok();
}

/// How the cut at a vessel end is said: "(x, y, z) radius r", with why it
/// lies deeper than {clip_distance} or that the end is a short root.
std::string end_cut_text(const VesselEnd& e, const ClipCut& c, double clip_distance) {
  std::string text = point_text(c.centroid) + " radius " + number_text(c.radius);
  if (e.short_end) text += " (a short, wide root)";
  if (e.cut_depth != clip_distance)
    text += " (" + number_text(e.cut_depth) +
            " radii in: the end is flat and oblique, a cut nearer its tip would cross it)";
  return text;
}

/// Phase 6: cuts by the planes given ({clip_plane}) and across the vessels
/// at the points given ({clip_at}), then at the blind vessel ends left
/// ({clip} auto: whether the surface is closed or open already; {clip} off
/// keeps them and lists them as proposals); each cut's rim is an opening
/// of source "clip".
Status clip(PreparedSurface& s, Work& w, const PrepareOptions& options) {
  const bool manifold = w.adjacency.num_nonmanifold_edges == 0 && s.repair.orientable;
  auto closed = [&] {
    return std::none_of(w.adjacency.opposite.begin(), w.adjacency.opposite.end(),
                        [](int32_t o) { return o == TriangleAdjacency::kBoundary; });
  };
  // The clean cross-sections of the damaged ends trimmed in phase 2b.
  for (const TrimmedEnd& e : s.trimmed_ends) {
    if (!e.trimmed) continue;
    Status st = manifold ? clip_one(s, w, e.plane, OpeningSource::kDamagedEnd)
                         : Status::Error("the surface is not manifold and orientable");
    if (!st.ok())
      s.warnings.push_back("the trimmed end at " + point_text(e.where) + " was not cut flat (" +
                           st.message() + "): its opening is the rim the trim left");
  }
  for (const ClipPlane& plane : options.clip_planes) {
    if (!manifold)
      return Status::Error("cannot cut with the plane at " + point_text(plane.point) +
                           ": the surface is not manifold and orientable");
    if (Status st = clip_one(s, w, plane, OpeningSource::kPlane); !st.ok()) return st;
    const ClipCut& c = s.clips.back();
    s.warnings.push_back("cut by the plane at " + point_text(plane.point) + ": an opening at " +
                         point_text(c.centroid) + " of radius " + number_text(c.radius) + " (" +
                         number_text(c.area_removed) + " of area removed)");
  }
  for (const std::array<double, 3>& at_point : options.clip_at) {
    if (!manifold)
      return Status::Error("cannot cut across the vessel at " + point_text(at_point) +
                           ": the surface is not manifold and orientable");
    Result<VesselCut> across = cut_across_vessel(s.mesh, w.adjacency, at_point);
    if (!across.ok()) return across.status();
    if (Status st = clip_one(s, w, across.value().plane, OpeningSource::kPoint); !st.ok())
      return st;
    const ClipCut& c = s.clips.back();
    s.warnings.push_back("cut across the vessel at " + point_text(at_point) + ": an opening at " +
                         point_text(c.centroid) + " of radius " + number_text(c.radius) + " (" +
                         number_text(c.area_removed) + " of area removed)");
  }
  const bool was_closed = closed();
  if (!manifold) {
    if (options.clip_auto && was_closed)
      s.warnings.push_back("{clip} auto cut nothing: the surface is not manifold and orientable");
    return Status::Ok();
  }
  VesselEndOptions eo;
  eo.clip_distance = options.clip_distance;
  const VesselEnds ends = find_vessel_ends(s.mesh, eo);
  if (!options.clip_auto) {
    s.clip_proposals = ends.ends;
    const size_t n = ends.ends.size();
    if (was_closed)
      s.warnings.push_back(
          "the surface is closed: it has no opening to be an inlet or outlet; " +
          (n == 0
               ? std::string("no vessel end was found to cut: give the cuts with {clip_plane} or "
                             "{clip_at}")
               : num(n) + (n == 1 ? " vessel end was" : " vessel ends were") +
                     " found: cut them open with {clip} auto (or give {clip_plane} or "
                     "{clip_at})"));
    else if (n > 0)
      s.warnings.push_back(num(n) + (n == 1 ? " blind vessel end was" : " blind vessel ends were") +
                           " kept closed ({clip} off): cut them open with {clip} auto (or give "
                           "{clip_plane} or {clip_at})");
    return Status::Ok();
  }
  std::string cut;
  size_t count = 0;
  for (const VesselEnd& e : ends.ends) {
    if (Status st = clip_one(s, w, e.plane, OpeningSource::kBlindEnd); !st.ok()) {
      s.warnings.push_back("the vessel end at " + point_text(e.tip) +
                           " was not cut: " + st.message());
      continue;
    }
    cut += (count++ ? "; " : "") + end_cut_text(e, s.clips.back(), options.clip_distance);
  }
  if (count > 0)
    s.warnings.push_back("cut " + num(count) + (count == 1 ? " vessel end" : " vessel ends") +
                         " open ({clip} auto, " + number_text(options.clip_distance) +
                         (options.clip_distance == 1 ? " local radius" : " local radii") +
                         " in from each tip; change with {clip_distance}, keep them closed with "
                         "{clip} off): at " +
                         cut);
  else if (was_closed)
    s.warnings.push_back(
        "{clip} auto found no vessel end to cut: no end of the surface is a tube with a "
        "rounded or flat end; give the cuts with {clip_plane}");
  // Where the surface had no opening, what was not cut is worth a word.
  if (was_closed)
    for (const NotAVesselEnd& r : ends.rejected)
      s.warnings.push_back("the extremity at " + point_text(r.where) +
                           " was not cut: it is no vessel end (" + r.why +
                           "; an aneurysm dome, or a vessel too short to cut); cut it with "
                           "{clip_plane} if it is one");
  return Status::Ok();
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
