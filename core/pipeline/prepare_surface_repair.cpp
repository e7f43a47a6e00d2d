// Phase 2 of prepare_surface() (prepare_surface.h): repairs. Always the
// safe ones (zero-area, flat and duplicate triangles removed), outward
// orientation, specks dropped and holes found; with {repair} auto also
// (2a) the surface re-made where it crosses itself
// (core/prepare/resurface_crossings), (2b) damaged vessel ends trimmed
// (core/prepare/trim_damaged_ends) and non-manifold edges split
// (core/mesh/manifold_repair), (2c) the holes closed
// (core/prepare/fill_holes) and (2d) non-manifold vertices split. Each
// change is reported in s.warnings.
#include <algorithm>
#include <set>

#include "core/geom/vec3.h"
#include "core/mesh/chord_radius.h"
#include "core/pipeline/prepare_surface_internal.h"
#include "core/prepare/fill_holes.h"

namespace vm {
namespace prepare_surface_detail {
namespace {

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

}  // namespace

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

}  // namespace prepare_surface_detail
}  // namespace vm
