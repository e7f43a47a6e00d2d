#include "core/pipeline/report_json.h"

#include <tuple>

#include "core/pipeline/opening_names.h"
#include "core/util/json_writer.h"

namespace vm {
namespace {

void write_quality(JsonWriter& j, const QualityStats& q) {
  j.begin_object();
  j.key("min").value(q.min);
  j.key("mean").value(q.mean);
  j.key("max").value(q.max);
  j.key("count").value(q.count);
  j.key("histogram").array(q.histogram);
  j.end_object();
}

/// {"min": min, "mean": mean}
void write_min_mean(JsonWriter& j, double min, double mean) {
  j.begin_object();
  j.key("min").value(min);
  j.key("mean").value(mean);
  j.end_object();
}

/// The patches remeshed by the fallback: place, input triangles, why,
/// rounds of splits before, triangles there at the end and their gamma_k.
void write_fallback_patches(JsonWriter& j, const std::vector<FallbackPatch>& patches) {
  j.begin_array();
  for (const FallbackPatch& f : patches) {
    j.begin_object();
    j.key("place").array(std::vector<double>(f.place.begin(), f.place.end()));
    j.key("input_triangles").value(f.input_triangles);
    j.key("reason").value(f.reason);
    j.key("splits").value(f.splits);
    j.key("triangles").value(f.triangles);
    j.key("quality");
    write_min_mean(j, f.quality_min, f.quality_mean);
    j.key("seconds").value(f.seconds);
    j.end_object();
  }
  j.end_array();
}

void write_smoothing(JsonWriter& j, const SmoothingOutcome& s) {
  const StaircaseReport& st = s.staircase;
  j.begin_object();
  j.key("mode").value(smoothing_mode_name(s.mode));
  j.key("staircase").value(st.staircase);
  j.key("direction_fraction").value(st.direction_fraction);
  j.key("lattice_fraction").value(st.lattice_fraction);
  j.key("terraces").value(st.terraces);
  if (st.staircase)
    j.key("voxel").value(st.voxel);
  else
    j.key("voxel").null();
  j.key("spacing").array(st.spacing);
  j.key("applied").value(s.applied);
  j.key("passes").value(s.applied ? s.report.passes : 0);
  j.key("clamp_voxel").value(s.voxel);
  j.key("flat_regions").value(s.report.flat_regions);
  j.key("max_displacement").value(s.report.max_displacement);
  j.key("max_displacement_voxels").value(0.5 * s.report.max_displacement_ratio);
  j.key("volume_change")
      .value(s.applied && s.report.volume_before != 0
                 ? s.report.volume_after / s.report.volume_before - 1
                 : 0.0);
  j.end_object();
}

void write_warnings(JsonWriter& j, const std::vector<std::string>& warnings, OptionFace face) {
  j.key("warnings").begin_array();
  for (const std::string& w : warnings) j.value(phrase_options(w, face));
  j.end_array();
}

}  // namespace

std::string analysis_json(const PreparedSurface& s, OptionFace face) {
  const TopologyReport& t = s.topology;
  JsonWriter j;
  j.begin_object();
  j.key("vertices").value(t.vertices);
  j.key("triangles").value(t.triangles);
  j.key("input_triangles").value(s.input_triangles);
  j.key("format").value(s.format);
  j.key("label_array").value(s.label_array);
  j.key("units").begin_object();
  j.key("unit").value(unit_symbol(s.unit.unit));
  j.key("guessed").value(s.unit.guessed);
  j.key("certain").value(s.unit.certain);
  j.key("reason").value(s.unit.reason);
  // A guess: how sure (certain, likely, unsure), the next unit that gives
  // human vessel sizes ("" none), and the measures weighed (model units).
  j.key("confidence").value(confidence_name(s.unit.confidence));
  j.key("alternative").value(unit_symbol(s.unit.alternative));
  const VesselScale& v = s.scale;
  j.key("measures").begin_object();
  j.key("largest_radius").value(v.large_radius);
  j.key("median_radius").value(v.median_radius);
  j.key("smallest_radius").value(v.smallest());
  j.key("diagonal").value(v.extent);
  j.key("label_array").value(v.label_array);
  j.end_object();
  j.end_object();
  // The share of the wall whose inward chord meets the wall again (-1: not
  // measured); a sheet (below one half) encloses no volume.
  j.key("enclosed_share").value(v.enclosed_share);
  j.key("bounding_box").begin_object();
  j.key("min").array(s.box.min);
  j.key("max").array(s.box.max);
  j.key("diagonal").value(s.box.diagonal());
  j.end_object();
  j.key("components").value(t.components);
  j.key("component_triangles").array(t.component_triangles);
  auto names = opening_names(s, {}, 0);
  j.key("openings").begin_array();
  for (size_t i = 0; i < t.openings.size(); ++i) {
    const Opening& op = t.openings[i];
    const OpeningSource& src = s.opening_sources[i];
    j.begin_object();
    j.key("source").value(opening_source_name(src.kind));
    j.key("shape");
    if (src.shape == OpeningSource::kNone)
      j.null();
    else
      j.value(opening_shape_name(src.shape));
    j.key("label").value(src.label);
    j.key("extension").value(src.extension);
    j.key("name").value(names.ok() ? names.value()[i] : std::string());
    j.key("perimeter").value(op.perimeter);
    j.key("radius").value(op.radius);
    j.key("centroid").array(op.centroid);
    j.key("normal").array(op.normal);
    j.key("vertices").array(op.loop);
    j.end_object();
  }
  j.end_array();
  j.key("holes").begin_array();
  for (const Hole& h : s.holes) {
    j.begin_object();
    j.key("perimeter").value(h.perimeter);
    j.key("radius").value(h.radius);
    j.key("centroid").array(h.centroid);
    j.key("vessel_radius").value(h.vessel_radius);
    j.key("closed").value(h.closed);
    j.key("triangles_added").value(h.triangles_added);
    j.key("min_angle").value(h.min_angle);
    j.end_object();
  }
  j.end_array();
  j.key("slits").begin_array();
  for (const Opening& o : t.slits) {
    j.begin_object();
    j.key("perimeter").value(o.perimeter);
    j.key("centroid").array(o.centroid);
    j.end_object();
  }
  j.end_array();
  j.key("caps_removed").value(s.caps_removed);
  j.key("smoothing");
  write_smoothing(j, s.smoothing);
  j.key("specks_removed").value(s.specks_removed);
  j.key("clip_proposals").begin_array();
  for (const VesselEnd& e : s.clip_proposals) {
    j.begin_object();
    j.key("point").array(e.plane.point);
    j.key("normal").array(e.plane.normal);
    j.key("radius").value(e.cut_radius);
    j.key("tip").array(e.tip);
    j.key("depth").value(e.cut_depth);
    j.key("short_root").value(e.short_end);
    j.end_object();
  }
  j.end_array();
  j.key("clips").begin_array();
  for (const ClipCut& c : s.clips) {
    j.begin_object();
    j.key("point").array(c.plane.point);
    j.key("normal").array(c.plane.normal);
    j.key("centroid").array(c.centroid);
    j.key("radius").value(c.radius);
    j.key("perimeter").value(c.perimeter);
    j.key("area_removed").value(c.area_removed);
    j.end_object();
  }
  j.end_array();
  j.key("self_crossings").begin_object();
  j.key("checked").value(s.self_crossings_checked);
  j.key("pairs").value(s.self_crossings.pairs);
  j.key("place_count").value(s.self_crossings.place_count);
  j.key("places").begin_array();
  for (const Vec3& p : s.self_crossings.places) j.array(p);
  j.end_array();
  j.end_object();
  j.key("closed").value(t.closed);
  if (t.genus >= 0)
    j.key("genus").value(t.genus);
  else
    j.key("genus").null();
  j.key("euler_characteristic").value(t.euler_characteristic);
  j.key("edges").value(t.edges);
  j.key("boundary_edges").value(t.boundary_edges);
  j.key("nonmanifold_edges").value(t.nonmanifold_edges);
  j.key("nonmanifold_vertices").value(t.nonmanifold_vertices);
  j.key("orientable").value(s.repair.orientable);
  j.key("repairs").begin_object();
  j.key("welded_corners").value(s.weld.corners);
  j.key("merged_by_tolerance").value(s.weld.merged_by_tolerance);
  j.key("degenerate_removed").value(s.repair.degenerate_removed);
  j.key("collinear_repaired").value(s.repair.collinear_repaired);
  j.key("duplicates_removed").value(s.repair.duplicates_removed);
  j.key("flipped").value(s.repair.flipped);
  j.key("unused_vertices_removed").value(s.repair.unused_vertices_removed);
  j.key("fins_removed").value(s.manifold.fins_removed);
  j.key("nonmanifold_edges_split").value(s.manifold.edges_split);
  j.key("nonmanifold_vertices_split").value(s.manifold.vertices_split);
  j.key("twisted_removed").value(s.manifold.twisted_removed);
  j.key("crossings_resurfaced").begin_array();
  for (const ResurfacedPlace& p : s.resurfaced.places) {
    j.begin_object();
    j.key("where").array(p.where);
    j.key("pairs").value(p.pairs);
    j.key("resolved").value(p.resolved);
    j.key("box_min").array(p.box_min);
    j.key("box_max").array(p.box_max);
    j.key("triangles_removed").value(p.triangles_removed);
    j.key("triangles_added").value(p.triangles_added);
    if (!p.resolved) j.key("why").value(p.near_opening ? "at an opening" : p.why);
    j.end_object();
  }
  j.end_array();
  j.key("damaged_ends").begin_array();
  for (const TrimmedEnd& e : s.trimmed_ends) {
    j.begin_object();
    j.key("where").array(e.where);
    j.key("radius").value(e.radius);
    j.key("trimmed").value(e.trimmed);
    j.key("depth").value(e.depth);
    j.key("point").array(e.plane.point);
    j.key("normal").array(e.plane.normal);
    j.key("triangles_removed").value(e.triangles_removed);
    j.key("crossing").value(e.crossing);
    j.key("misoriented").value(e.misoriented);
    j.key("nonmanifold").value(e.nonmanifold);
    j.key("tiny_loops").value(e.tiny_loops);
    j.end_object();
  }
  j.end_array();
  j.end_object();
  j.key("quality");
  write_quality(j, s.quality_stats);
  write_warnings(j, s.warnings, face);
  j.end_object();
  return j.str();
}

std::string mesh_report_json(const MeshJobResult& r, OptionFace face) {
  JsonWriter j;
  j.begin_object();
  j.key("input").raw(analysis_json(r.surface, face));
  if (!r.preset.solver.empty()) {
    j.key("preset").begin_object();
    j.key("solver").value(r.preset.solver);
    j.key("settings").begin_array();
    for (const PresetSetting& s : r.preset.settings) {
      j.begin_object();
      j.key("option").value(phrase_options("{" + s.id + "}", face));
      j.key("value").value(s.value);
      j.key("from").value(s.from_preset ? "preset" : "user");
      j.end_object();
    }
    j.end_array();
    j.key("note").value(r.preset.note);
    j.end_object();
  }
  if (const auto& y = r.first_layer_yplus) {
    j.key("first_layer_yplus").begin_object();
    j.key("yplus").value(y->target.yplus);
    j.key("inlet_velocity").value(y->target.velocity);
    j.key("density").value(y->target.density);
    j.key("viscosity").value(y->target.viscosity);
    j.key("inlet").value(y->inlet);
    j.key("inlet_diameter").value(y->inlet_diameter);
    j.key("reynolds").value(y->estimate.reynolds);
    j.key("skin_friction").value(y->estimate.skin_friction);
    j.key("wall_shear_stress").value(y->estimate.wall_shear_stress);
    j.key("friction_velocity").value(y->estimate.friction_velocity);
    j.key("height_m").value(y->estimate.height);
    j.key("height").value(y->height);
    j.key("correlation").value("Cf = 0.026 Re^(-1/7)");
    j.end_object();
  }
  // The element budget: the default size coarsened to fit it (else
  // coarsened false and the default's N fitted, or the size was given).
  j.key("element_budget").begin_object();
  j.key("max_elements").value(r.budget.max_elements);
  j.key("coarsened").value(r.budget.coarsened);
  if (r.budget.coarsened) {
    j.key("counted").value(r.budget.counted);
    j.key("asked_per_circumference").value(r.budget.asked_per_circumference);
    j.key("asked_elements").value(r.budget.asked_elements);
    j.key("per_circumference").value(r.budget.per_circumference);
    j.key("elements").value(r.budget.elements);
    j.key("enough").value(r.budget.enough);
  }
  j.end_object();
  j.key("output").begin_object();
  // Lengths of the report are in the input's unit.
  j.key("unit").value(unit_symbol(r.surface.unit.unit));
  j.key("vertices").value(r.output_surface.num_vertices());
  j.key("triangles").value(r.output_surface.num_triangles());
  j.key("quality");
  write_quality(j, r.output_quality_stats);
  if (r.remeshed) {
    const RemeshStats& st = r.remesh_stats;
    j.key("genus").value(r.output_topology.genus);
    j.key("openings").value(r.output_topology.openings.size());
    j.key("remesh").begin_object();
    j.key("patches").value(st.patches);
    j.key("seam_points").value(st.seam_points);
    j.key("feature_edges").value(st.feature_edges);
    j.key("size").begin_object();
    j.key("min").value(st.size_min);
    j.key("median").value(st.size_median);
    j.key("max").value(st.size_max);
    j.end_object();
    j.key("edge_to_size").begin_object();
    j.key("p10").value(st.edge_ratio_p10);
    j.key("median").value(st.edge_ratio_median);
    j.key("p90").value(st.edge_ratio_p90);
    j.end_object();
    j.key("fidelity").begin_object();
    j.key("max_vertex_offset").value(r.fidelity.max_vertex_offset);
    j.key("max_input_gap").value(r.fidelity.max_input_gap);
    j.key("self_intersections").value(r.fidelity.self_intersections);
    j.key("input_volume").value(r.fidelity.input_volume);
    j.key("output_volume").value(r.fidelity.output_volume);
    j.key("volume_change").value(r.fidelity.volume_change);
    j.key("input_gap_vertices").value(r.fidelity.input_gap_vertices);
    j.key("pinned_vertices").value(st.fidelity_pinned);
    j.key("pinning_rounds").value(st.fidelity_rounds);
    j.key("pinning_reverted").value(st.fidelity_reverted);
    j.key("size_rounds").value(st.fidelity_size_rounds);
    j.key("local_rounds").value(st.fidelity_local_rounds);
    j.end_object();
    j.key("splits").value(st.retries);
    j.key("fallback_patches");
    write_fallback_patches(j, st.fallback_patches);
    j.key("decimated_triangles").value(st.decimated_triangles);
    j.key("swaps").value(st.swaps);
    j.key("moves").value(st.moves);
    j.key("collapses").value(st.collapses);
    j.key("seconds").begin_object();
    j.key("size").value(st.seconds_size);
    j.key("decimate").value(st.seconds_decimate);
    j.key("partition").value(st.seconds_partition);
    j.key("mesh").value(st.seconds_mesh);
    j.key("optimize").value(st.seconds_optimize);
    j.key("fidelity").value(st.seconds_fidelity);
    j.end_object();
    j.end_object();
  }
  if (!r.volume.tets.empty()) {
    j.key("caps").begin_array();
    for (const CapInfo& c : r.capped.caps) {
      j.begin_object();
      j.key("name").value(c.name);
      j.key("area").value(c.area);
      j.key("perimeter").value(c.perimeter);
      j.key("centroid").array(std::vector<double>(c.centroid.begin(), c.centroid.end()));
      j.key("normal").array(std::vector<double>(c.normal.begin(), c.normal.end()));
      j.key("triangles").value(c.triangles);
      j.key("max_projection_distance").value(c.max_projection_distance);
      j.key("quality");
      write_min_mean(j, c.quality_min, c.quality_mean);
      j.end_object();
    }
    j.end_array();
    const VolumeStats& vs = r.volume_stats;
    j.key("volume").begin_object();
    j.key("vertices").value(r.volume.num_vertices());
    j.key("tetrahedra").value(r.volume.num_tets());
    j.key("lumen_volume").value(r.volume_stats.lumen_volume);
    j.key("boundary_triangles").value(r.volume.num_triangles());
    j.key("steiner_points").value(vs.steiner_points);
    // Boundary recovery on the wall: its points (Steiner points) and where
    // they went, the edges flips recovered instead, the wall edges flipped,
    // and the wall's quality written against remeshed.
    j.key("wall_recovery").begin_object();
    j.key("steiner_points").value(vs.steiner_points);
    j.key("on_layer_front").value(vs.front_steiner_points);
    j.key("absorbed_in_layer").value(vs.absorbed_steiner_points);
    j.key("splitting_wall").value(vs.wall_steiner_points);
    j.key("reoptimized").value(vs.reoptimized_steiner_points);
    j.key("edges_recovered_by_flips").value(vs.edges_recovered_by_flips);
    j.key("wall_edges_flipped").value(vs.wall_edges_flipped);
    j.key("places").begin_array();
    for (const auto& p : vs.wall_change_places) j.array(p);
    j.end_array();
    j.key("remeshed_wall_quality_min").value(r.output_quality_stats.min);
    for (const SurfaceGroupQuality& g : r.written_quality)
      if (g.tag == 0) j.key("written_wall_quality_min").value(g.quality.min);
    j.end_object();
    j.key("inserted_points").value(vs.inserted_points);
    j.key("quality");
    write_quality(j, r.tet_quality_stats);
    j.key("core_quality");
    write_quality(j, r.core_quality_stats);
    // gamma_k of the surfaces as written (after recovery), per group; the
    // layers' rings at the openings apart.
    j.key("surfaces").begin_array();
    for (const SurfaceGroupQuality& g : r.written_quality) {
      j.begin_object();
      j.key("name").value(g.name);
      j.key("quality");
      write_quality(j, g.quality);
      if (g.ring.count > 0) {
        j.key("ring_quality");
        write_quality(j, g.ring);
      }
      j.end_object();
    }
    j.end_array();
    for (const auto& [name, ls, layers] :
         {std::tuple{"boundary_layer", &vs.boundary_layer, vs.viscous_layers},
          std::tuple{"vessel_wall", &vs.vessel_wall, vs.wall_layers}}) {
      if (layers <= 0) continue;
      j.key(name).begin_object();
      j.key("layers").value(layers);
      j.key("reduced_area_fraction").value(ls->reduced_area_fraction);
      j.key("min_factor").value(ls->min_factor);
      j.key("mean_factor").value(ls->mean_factor);
      j.key("thickness_within_10pct").value(ls->thickness_within_10pct);
      if (ls->measured_total_mean_ratio > 0) {  // measured (--verify)
        j.key("measured_first_within_10pct").value(ls->measured_first_within_10pct);
        j.key("measured_total_within_10pct").value(ls->measured_total_within_10pct);
        j.key("measured_first_mean_ratio").value(ls->measured_first_mean_ratio);
        j.key("measured_total_mean_ratio").value(ls->measured_total_mean_ratio);
      }
      j.key("front_quality_min").value(ls->front_quality_min);
      j.key("seconds").value(ls->seconds_total);
      j.end_object();
    }
    j.key("seconds").begin_object();
    j.key("layers").value(vs.seconds_layers);
    j.key("caps").value(vs.seconds_caps);
    j.key("recovery").value(vs.seconds_recovery);
    j.key("refinement").value(vs.seconds_refinement);
    j.key("insertion").value(vs.seconds_fill_refine);
    j.key("optimization").value(vs.seconds_fill_optimize);
    j.key("assembly").value(vs.seconds_assembly);
    j.key("check").value(vs.seconds_check);
    j.end_object();
    j.end_object();
  }
  j.key("groups").begin_array();
  for (const OutputGroup& g : r.groups) {
    j.begin_object();
    j.key("dim").value(g.dim);
    j.key("tag").value(g.tag);
    j.key("name").value(g.name);
    j.key("elements").value(g.elements);
    j.end_object();
  }
  j.end_array();
  j.end_object();
  write_warnings(j, r.warnings, face);
  j.key("seconds").value(r.seconds_total);
  j.end_object();
  return j.str();
}

}  // namespace vm
