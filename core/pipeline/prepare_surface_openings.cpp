// Phases 5-7 of prepare_surface() (prepare_surface.h): the openings. (5)
// caps recognised (core/prepare/recognize_caps) and removed, fans and
// domes by a cut at their rim's plane; (6) cuts by given planes, across
// vessels at given points (core/prepare/cut_across_vessel) and at the blind
// vessel ends (core/prepare/vessel_ends), each by
// core/prepare/clip_surface; (7) flow extensions
// (core/prepare/flow_extensions). Every new opening keeps where it comes
// from (Work::sources), and each change is reported in s.warnings.
#include <algorithm>
#include <optional>

#include "core/geom/vec3.h"
#include "core/pipeline/prepare_surface_internal.h"
#include "core/prepare/cut_across_vessel.h"
#include "core/prepare/flow_extensions.h"
#include "core/prepare/vessel_ends.h"

namespace vm {
namespace prepare_surface_detail {
namespace {

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

}  // namespace

/// Whether phase 5 looks for caps on this surface.
bool caps_wanted(const PreparedSurface& s, const Work& w, const PrepareOptions& options) {
  return !options.keep_caps && w.adjacency.num_nonmanifold_edges == 0 && s.repair.orientable;
}

/// `normals`: triangle_normals(s.mesh) if known.
CapRecognition find_caps(const PreparedSurface& s, const Work& w, const PrepareOptions& options,
                         const TriangleNormals* normals) {
  return recognize_caps(s.mesh, w.adjacency, w.labels, w.face_names, options.caps, normals);
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

}  // namespace prepare_surface_detail
}  // namespace vm
