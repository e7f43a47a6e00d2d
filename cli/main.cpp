// The `vesselmesh` command: parse arguments, call core, print results.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <new>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include "cli/args.h"
#include "cli/read_input.h"
#include "core/io/provenance.h"
#include "core/io/stl.h"
#include "core/io/vtk_writer.h"
#include "core/io/zip_writer.h"
#include "core/phantom/vessel_phantom.h"
#include "core/pipeline/mesh_family.h"
#include "core/pipeline/mesh_job.h"
#include "core/pipeline/opening_names.h"
#include "core/pipeline/report_json.h"
#include "core/pipeline/size_preview.h"
#include "core/pipeline/solver_preset.h"
#include "core/pipeline/validate_options.h"
#include "core/pipeline/write_outputs.h"
#include "core/report/methods_report.h"
#include "core/report/render_views.h"
#include "core/util/allocator_tuning.h"
#include "core/util/parallel.h"
#include "core/util/version.h"

namespace {

using vm::cli::Args;

constexpr const char* kIntro =
    R"(vesselmesh: quality meshes for cardiovascular flow simulation

usage:
  vesselmesh info FILE [options]
      Read, weld, repair and analyze a lumen surface: counts, openings,
      holes, genus, non-manifold edges, triangle quality gamma_k; with
      --size-field OUT.vtp, the local radius and the size the size options
      ask for at each vertex, before meshing.
  vesselmesh mesh FILE -o OUT.msh [options]
      Remesh the surface by conformal maps, grow a boundary layer inward,
      cap each opening with a planar triangulation, fill the lumen with
      tetrahedra and write Gmsh MSH: surfaces `wall`, `inlet`, `outlet_1..k`,
      volume `lumen` (and with a vessel wall: `outer_wall`, `wall_inlet`,
      `wall_outlet_k`, volume `vessel_wall`).
  vesselmesh phantom OUT.stl|OUT.vtp [options]
      Write a synthetic segmentation-like vessel surface (binary STL, or
      VTK XML PolyData with its face labels as ModelFaceID when OUT ends
      in .vtp: SimVascular's, 1 the wall, 2.. each flat cap).
  vesselmesh options [--json | --markdown]
      Print the option table (JSON: for tools; Markdown: the list in
      docs/options.md).
  vesselmesh --help | --version

FILE may be '-': the surface is read from standard input (a pipe).
Lengths are in the model's unit; R is the local vessel radius.
)";

int usage_error(const std::string& msg) {
  std::cerr << "vesselmesh: " << msg << "\n(run 'vesselmesh --help' for usage)\n";
  return 2;
}

int fail(const std::string& msg) {
  std::cerr << "vesselmesh: error: " << msg << "\n";
  return 1;
}

/// The input file's bytes ('-': standard input) within the read limits of
/// `options`; the error message on failure.
std::optional<vm::cli::InputBytes> read_file(const std::string& path,
                                             const vm::MeshJobOptions& options,
                                             std::string& error) {
  vm::SurfaceReadOptions limits;
  limits.max_triangles = options.prepare.read.max_triangles;
  auto bytes = vm::cli::read_input(path, limits);
  if (!bytes.ok()) {
    error = bytes.message();
    return std::nullopt;
  }
  return std::move(bytes.value());
}

bool write_file(const std::string& path, const void* data, size_t size, std::string& error) {
  std::ofstream out(path, std::ios::binary);
  if (!out || !out.write(static_cast<const char*>(data), std::streamsize(size))) {
    error = "cannot write '" + path + "'";
    return false;
  }
  return true;
}

void print_text_report(const std::string& path, const vm::PreparedSurface& s) {
  const vm::TopologyReport& t = s.topology;
  const std::string u(vm::unit_symbol(s.unit.unit));
  const char* unit = u.c_str();
  std::printf("file:        %s (%s, %zu triangles)\n", path.c_str(), s.format.c_str(),
              s.input_triangles);
  std::printf("units:       %s\n",
              vm::phrase_options(vm::unit_summary(s.unit), vm::kFaceCli).c_str());
  std::printf("welded:      %zu vertices, %zu triangles, %zu edges\n", t.vertices, t.triangles,
              t.edges);
  std::printf("bounding box: [%g, %g, %g] - [%g, %g, %g] %s (diagonal %g %s)\n", s.box.min[0],
              s.box.min[1], s.box.min[2], s.box.max[0], s.box.max[1], s.box.max[2], unit,
              s.box.diagonal(), unit);
  std::printf("components:  %d\n", t.components);
  std::printf("closed:      %s\n", t.closed ? "yes" : "no");
  if (t.genus >= 0)
    std::printf("genus:       %d\n", t.genus);
  else
    std::printf("genus:       undefined (non-manifold)\n");
  std::printf("euler char.: %ld\n", t.euler_characteristic);
  std::printf("non-manifold edges: %zu, vertices: %zu\n", t.nonmanifold_edges,
              t.nonmanifold_vertices);
  std::printf(
      "openings:    %zu%s\n", t.openings.size(),
      s.caps_removed ? (" (" + std::to_string(s.caps_removed) + " from caps)").c_str() : "");
  auto names = vm::opening_names(s, {}, 0);
  for (size_t i = 0; i < t.openings.size(); ++i) {
    const vm::Opening& o = t.openings[i];
    const vm::OpeningSource& src = s.opening_sources[i];
    std::string from = src.kind == vm::OpeningSource::kFile
                           ? std::string()
                           : std::string(", from a ") + vm::opening_source_name(src.kind);
    if (src.shape != vm::OpeningSource::kNone && src.shape != vm::OpeningSource::kLabelled) {
      std::string shape = vm::opening_shape_name(src.shape);
      std::replace(shape.begin(), shape.end(), '_', ' ');
      from += " (" + shape + ")";
    }
    if (src.label >= 0) from += " (" + s.label_array + " " + std::to_string(src.label) + ")";
    std::printf("  %zu: %s: perimeter %g %s, radius %g %s, centroid (%g, %g, %g), %zu vertices%s\n",
                i + 1, names.ok() ? names.value()[i].c_str() : "?", o.perimeter, unit, o.radius,
                unit, o.centroid[0], o.centroid[1], o.centroid[2], o.loop.size(), from.c_str());
  }
  size_t closed = 0;
  for (const vm::Hole& h : s.holes) closed += h.closed;
  std::printf("holes:       %zu (%zu closed)\n", s.holes.size(), closed);
  for (size_t i = 0; i < s.holes.size(); ++i) {
    const vm::Hole& h = s.holes[i];
    std::printf(
        "  %zu: perimeter %g %s, radius %g %s (local vessel radius %g %s), centroid (%g, %g, "
        "%g)%s\n",
        i + 1, h.perimeter, unit, h.radius, unit, h.vessel_radius, unit, h.centroid[0],
        h.centroid[1], h.centroid[2], h.closed ? ", closed" : ", open");
  }
  if (!t.slits.empty()) {
    const vm::Opening& o = t.slits[0];
    std::printf(
        "slits:       %zu (boundary loops of 2 vertices, no area: the free edges of a fin; "
        "--repair auto removes it), e.g. at (%g, %g, %g)\n",
        t.slits.size(), o.centroid[0], o.centroid[1], o.centroid[2]);
  }
  const vm::SelfCrossings& x = s.self_crossings;
  if (!s.self_crossings_checked)
    std::printf("self-crossings: not looked for (over %zu triangles)\n",
                vm::kSelfCrossingCheckLimit);
  else if (x.pairs == 0)
    std::printf("self-crossings: none\n");
  else
    std::printf("self-crossings: %zu %s (%zu pairs of triangles)\n", x.place_count,
                x.place_count == 1 ? "place" : "places", x.pairs);
  for (size_t i = 0; i < x.places.size(); ++i)
    std::printf("  %zu: at (%g, %g, %g) %s\n", i + 1, x.places[i][0], x.places[i][1],
                x.places[i][2], unit);
  if (!s.clip_proposals.empty()) {
    std::printf("vessel ends: %zu (the cuts --clip auto would make)\n", s.clip_proposals.size());
    for (size_t i = 0; i < s.clip_proposals.size(); ++i) {
      const vm::VesselEnd& e = s.clip_proposals[i];
      const auto& [q, n] = e.plane;
      std::printf("  %zu: radius %g %s: --clip-plane %g,%g,%g,%.4f,%.4f,%.4f\n", i + 1,
                  e.cut_radius, unit, q[0], q[1], q[2], n[0], n[1], n[2]);
    }
  }
  const vm::SmoothingOutcome& sm = s.smoothing;
  char staircase[96] = "not a voxel staircase";
  if (sm.staircase.staircase)
    std::snprintf(staircase, sizeof(staircase), "a voxel staircase, voxel %.4g %s",
                  sm.staircase.voxel, unit);
  if (sm.applied)
    std::printf("smoothing:   %d passes (%s), vertices moved at most %g %s (%.2f of the %s)\n",
                sm.report.passes, staircase, sm.report.max_displacement, unit,
                0.5 * sm.report.max_displacement_ratio,
                sm.staircase.staircase ? "voxel" : "median edge");
  else
    std::printf("smoothing:   none (%s%s)\n", staircase,
                sm.mode == vm::Smoothing::Mode::kOff ? ", --smooth off" : "");
  std::printf("quality gamma_k: min %.4f, mean %.4f\n", s.quality_stats.min, s.quality_stats.mean);
  for (const std::string& w : s.warnings)
    std::printf("warning: %s\n", vm::phrase_options(w, vm::kFaceCli).c_str());
}

void print_mesh_summary(const std::string& out, const vm::MeshJobResult& res) {
  const std::string unit_text(vm::unit_symbol(res.surface.unit.unit));
  const char* unit = unit_text.c_str();
  for (const std::string& w : res.warnings)
    std::fprintf(stderr, "warning: %s\n", vm::phrase_options(w, vm::kFaceCli).c_str());
  if (!res.preset.solver.empty()) {
    std::printf("preset %s\n", vm::preset_summary(res.preset).c_str());
    if (!res.preset.note.empty()) std::printf("  %s\n", res.preset.note.c_str());
  }
  if (const auto& y = res.first_layer_yplus) {
    std::printf(
        "first layer: %.4g %s (%.4g m) for y+ %g at the inlet %s (diameter %.4g %s, U %g m/s, rho "
        "%g kg/m^3, mu %g Pa s: Re %.4g, Cf %.4g, tau_w %.4g Pa, u_tau %.4g m/s; Cf = 0.026 "
        "Re^(-1/7))\n",
        y->height, unit, y->estimate.height, y->target.yplus, y->inlet.c_str(), y->inlet_diameter,
        unit, y->target.velocity, y->target.density, y->target.viscosity, y->estimate.reynolds,
        y->estimate.skin_friction, y->estimate.wall_shear_stress, y->estimate.friction_velocity);
  }
  std::printf("units: %s\n",
              vm::phrase_options(vm::unit_summary(res.surface.unit), vm::kFaceCli).c_str());
  std::printf("wrote %s in %.3f s:", out.c_str(), res.seconds_total);
  for (const vm::OutputGroup& g : res.groups)
    std::printf(" %s %zu%s", g.name.c_str(), g.elements, &g == &res.groups.back() ? "\n" : ",");
  std::printf("wall: %zu vertices, %zu triangles, gamma_k min %.4f mean %.4f",
              res.output_surface.num_vertices(), res.output_surface.num_triangles(),
              res.output_quality_stats.min, res.output_quality_stats.mean);
  if (res.remeshed)
    std::printf("; volume %+.2f%% of the input's", 100 * res.fidelity.volume_change);
  std::printf("\n");
  if (!res.volume.tets.empty()) {
    const vm::VolumeStats& vs = res.volume_stats;
    std::printf(
        "volume: %zu vertices, %zu tetrahedra, core gamma_t min %.4f mean %.4f; %zu Steiner "
        "points (%zu in the layer, %zu on the wall, %zu slid), %zu wall edges flipped; time: "
        "layers %.2f s, caps %.2f s, recovery "
        "%.2f s, refinement %.2f s, check "
        "%.2f s\n",
        res.volume.num_vertices(), res.volume.num_tets(), res.core_quality_stats.min,
        res.core_quality_stats.mean, vs.steiner_points, vs.absorbed_steiner_points,
        vs.wall_steiner_points, vs.reoptimized_steiner_points, vs.wall_edges_flipped,
        vs.seconds_layers, vs.seconds_caps, vs.seconds_recovery, vs.seconds_refinement,
        vs.seconds_check);
    // The surfaces as written (after boundary recovery): gamma_k a group,
    // the layers' rings at the openings apart.
    std::printf("written surfaces gamma_k:");
    for (const vm::SurfaceGroupQuality& g : res.written_quality) {
      std::printf(" %s", g.name.c_str());
      if (g.quality.count > 0) std::printf(" min %.3f mean %.3f", g.quality.min, g.quality.mean);
      if (g.ring.count > 0)
        std::printf(g.quality.count > 0 ? " (layer ring min %.3f)" : " layer ring min %.3f",
                    g.ring.min);
      std::printf("%s", &g == &res.written_quality.back() ? "\n" : ",");
    }
    for (const auto& [name, ls, layers] :
         {std::tuple{"boundary layer", &vs.boundary_layer, vs.viscous_layers},
          std::tuple{"vessel wall", &vs.vessel_wall, vs.wall_layers}})
      if (layers > 0)
        std::printf(
            "%s: %d layers, thickness reduced on %.1f%% of the wall (min factor %.2f), "
            "within 10%% of the request on %.1f%%\n",
            name, layers, 100 * ls->reduced_area_fraction, ls->min_factor,
            100 * ls->thickness_within_10pct);
  }
  if (res.remeshed) {
    const vm::RemeshStats& st = res.remesh_stats;
    std::printf(
        "remeshed: %zu patches, %zu seam points, size %.4g..%.4g %s (median %.4g %s); "
        "time: size %.2f s, partition %.2f s, meshing %.2f s, optimization %.2f s\n",
        st.patches, st.seam_points, st.size_min, st.size_max, unit, st.size_median, unit,
        st.seconds_size, st.seconds_partition, st.seconds_mesh, st.seconds_optimize);
    if (st.decimated_triangles > 0)
      std::printf("decimated: %zu of the input's %zu triangles left before remeshing (%.2f s)\n",
                  st.decimated_triangles, res.surface.mesh.num_triangles(), st.seconds_decimate);
  }
}

/// Exit status of a core error: 2 for an unusable option, else 1.
int fail(const std::string& file, const vm::Status& st) {
  const std::string message = vm::phrase_error(st, vm::kFaceCli);
  if (st.kind() == vm::ErrorKind::kBadOption) return usage_error(message);
  return fail(file.empty() ? message : file + ": " + message);
}

/// `info --size-field OUT.vtp`: the prepared surface with the radius and
/// the asked size at its vertices (size_preview.h), and a line saying their
/// ranges when `say`.
int write_size_field(const std::string& file, const std::string& path,
                     const vm::PreparedSurface& surface, const vm::MeshJobOptions& options,
                     bool say) {
  auto preview = vm::size_preview(surface, options);
  if (!preview.ok()) return fail(file, preview.status());
  const vm::SizePreview& p = preview.value();
  vm::VtpSurface s;
  s.points = surface.mesh.points;
  s.triangles = surface.mesh.triangles;
  s.face_ids.assign(surface.mesh.num_triangles(), 1);
  s.point_scalars = {{"radius", p.radius}, {"size", p.size}};
  vm::VtkWriteOptions wo;
  wo.comment = "vesselmesh " + std::string(vm::kVersion) +
               " size field: radius = local vessel radius R, size = asked edge length h (" +
               std::string(vm::unit_symbol(surface.unit.unit)) + ")";
  auto vtp = vm::write_vtp(s, wo);
  if (!vtp.ok()) return fail(file, vtp.status());
  std::string err;
  if (!write_file(path, vtp.value().data(), vtp.value().size(), err)) return fail(err);
  if (say) {
    const auto [r0, r1] = std::minmax_element(p.radius.begin(), p.radius.end());
    const auto [h0, h1] = std::minmax_element(p.size.begin(), p.size.end());
    const std::string u(vm::unit_symbol(surface.unit.unit));
    std::printf("size field:  wrote %s: radius %.4g..%.4g %s, size %.4g..%.4g %s\n", path.c_str(),
                *r0, *r1, u.c_str(), *h0, *h1, u.c_str());
  }
  return 0;
}

/// The usage error of a command that takes exactly one positional argument
/// (`what`), or "" when its arguments parsed.
std::string one_argument_error(const Args& a, const std::string& command, const char* what) {
  if (!a.error.empty()) return a.error;
  if (a.positional.size() != 1) return command + " needs exactly one " + what;
  return "";
}

int cmd_info(int argc, char** argv) {
  Args a = vm::cli::parse_args(argc, argv, 2, vm::kCommandInfo);
  if (std::string e = one_argument_error(a, "info", "FILE"); !e.empty()) return usage_error(e);
  vm::MeshJobOptions options;
  if (std::string e = vm::cli::apply_all(a, options); !e.empty()) return usage_error(e);
  vm::set_thread_count(options.threads);
  std::string err;
  auto bytes = read_file(a.positional[0], options, err);
  if (!bytes) return fail(err);
  auto r = vm::prepare_surface(*bytes, options.prepare);
  if (!r.ok()) return fail(a.positional[0], r.status());
  if (a.get("json")) {
    std::printf("%s\n", vm::analysis_json(r.value()).c_str());
  } else {
    print_text_report(a.positional[0], r.value());
  }
  if (const vm::OptionValue* out = a.get("size_field"))
    return write_size_field(a.positional[0], out->text, r.value(), options, !a.get("json"));
  return 0;
}

/// Where and how `mesh` writes: the format (--format, else the output's
/// extension; a folder means mesh-complete, or foam when it is an OpenFOAM
/// case already). Both write a folder unless the name ends in .zip. An OpenFOAM case named
/// NAME.foam: the case is the folder NAME.foam is in, and NAME.foam its (empty) marker file for
/// ParaView.
struct Destination {
  vm::OutputFormat format = vm::OutputFormat::kMsh;
  bool zip = false, folder = false;
  std::string folder_path;  ///< the folder written into, when `folder`
  std::string marker;       ///< foam: the marker file's name in the folder
};

std::optional<Destination> destination(const std::string& path, vm::MeshJobOptions& options,
                                       std::string& error) {
  Destination d;
  const bool ends_zip = path.size() > 4 && path.compare(path.size() - 4, 4, ".zip") == 0;
  const bool dir = !path.empty() && (path.back() == '/' || std::filesystem::is_directory(path));
  // What the name says (a folder: an existing OpenFOAM case, one with
  // system/controlDict, gets its polyMesh, else mesh-complete; an
  // extension), else a preset's default.
  std::optional<vm::OutputFormat> from_name;
  if (dir) {
    const bool foam_case =
        std::filesystem::is_regular_file(std::filesystem::path(path) / "system" / "controlDict");
    from_name = foam_case ? vm::OutputFormat::kFoam : vm::OutputFormat::kMeshComplete;
  } else if (auto f = vm::format_for_path(path); f.ok()) {
    from_name = f.value();
  } else if (!options.format && options.solver == vm::Solver::kNone) {
    error = vm::phrase_error(f.status(), vm::kFaceCli);
    return std::nullopt;
  }
  d.format = vm::resolve_output_format(options, from_name);
  if (d.format == vm::OutputFormat::kMeshComplete || d.format == vm::OutputFormat::kFoam) {
    d.zip = ends_zip;
    d.folder = !ends_zip;
    d.folder_path = path;
  }
  const bool ends_foam = path.size() > 5 && path.compare(path.size() - 5, 5, ".foam") == 0;
  if (d.format == vm::OutputFormat::kFoam && ends_foam && !dir) {
    const std::filesystem::path p(path);
    d.folder_path = p.has_parent_path() ? p.parent_path().string() : ".";
    d.marker = p.filename().string();
  }
  if (vm::Status st = vm::validate_options(options, d.format); !st.ok()) {
    error = vm::phrase_error(st, vm::kFaceCli);
    return std::nullopt;
  }
  return d;
}

/// Writes the files of `d` at `path`: one file, a zip, or a folder.
bool write_outputs(const std::string& path, const Destination& d,
                   const std::vector<vm::OutputFile>& files, std::string& error) {
  if (d.zip) {
    auto zip = vm::write_zip(files);
    if (!zip.ok()) {
      error = zip.message();
      return false;
    }
    return write_file(path, zip.value().data(), zip.value().size(), error);
  }
  if (!d.folder) return write_file(path, files[0].bytes.data(), files[0].bytes.size(), error);
  if (d.format == vm::OutputFormat::kFoam) {
    // Zones of a mesh this one replaces would name faces it does not have.
    for (const char* zones : {"faceZones", "pointZones"}) {
      const std::string rel = std::string("constant/polyMesh/") + zones;
      bool written = false;
      for (const vm::OutputFile& f : files) written |= f.path == rel;
      std::error_code ec;
      if (!written) std::filesystem::remove(std::filesystem::path(d.folder_path) / rel, ec);
    }
  }
  for (const vm::OutputFile& f : files) {
    const bool foam = d.format == vm::OutputFormat::kFoam;
    const bool marker = foam && f.path == "case.foam";
    const std::filesystem::path target =
        std::filesystem::path(d.folder_path) / (marker && !d.marker.empty() ? d.marker : f.path);
    // A case's own settings (system/, its marker) are kept; only the mesh is replaced.
    if (foam && f.path.rfind("constant/", 0) != 0 && std::filesystem::exists(target)) continue;
    std::error_code ec;
    std::filesystem::create_directories(target.parent_path(), ec);
    if (ec) {
      error = "cannot create the folder '" + target.parent_path().string() + "': " + ec.message();
      return false;
    }
    if (!write_file(target.string(), f.bytes.data(), f.bytes.size(), error)) return false;
  }
  return true;
}

/// `path` with "_k" after its last component's stem ("run/mesh.msh" ->
/// "run/mesh_1.msh", "case/" -> "case_1/"): where a family's member k goes.
std::string member_path(const std::string& path, int k) {
  std::string p = path;
  const bool slash = !p.empty() && p.back() == '/';
  if (slash) p.pop_back();
  const std::filesystem::path fp(p);
  const bool dir = slash || std::filesystem::is_directory(fp);
  const std::string stem = dir ? fp.filename().string() : fp.stem().string();
  const std::string ext = dir ? "" : fp.extension().string();
  return (fp.parent_path() / (stem + "_" + std::to_string(k) + ext)).string() + (slash ? "/" : "");
}

/// Where member k of a family goes: its path and destination (a folder
/// format: its own folder; an OpenFOAM case NAME.foam: its own case folder
/// with the same marker).
std::pair<std::string, Destination> member_destination(const std::string& path,
                                                       const Destination& d, int k) {
  Destination m = d;
  if (!d.marker.empty()) {
    m.folder_path = member_path(d.folder_path + "/", k);
    m.folder_path.pop_back();
    return {(std::filesystem::path(m.folder_path) / d.marker).string(), m};
  }
  const std::string p = member_path(path, k);
  if (d.folder) m.folder_path = p;
  return {p, m};
}

/// The family's table as the CLI prints it.
void print_family(const vm::MeshFamily& family) {
  std::printf("family: %d meshes, ratio %g, layers %s (h = (V/N)^(1/3), %s)\n", family.members,
              family.ratio, std::string(vm::family_layers_name(family.layers)).c_str(),
              family.unit.c_str());
  for (const vm::FamilyMember& m : family.rows) {
    std::printf("  %d %s: %zu nodes, %zu cells, h %.4g", m.index, m.file.c_str(), m.nodes, m.cells,
                m.h);
    if (m.ratio > 0) std::printf(" (ratio %.3f)", m.ratio);
    std::printf(", gamma_t min %.3f mean %.3f, %.2f s\n", m.quality.min, m.quality.mean, m.seconds);
  }
}

/// The methods report of `res` (the family's first member when `family`)
/// to `path`, with pictures rendered here.
bool write_methods_report(const std::string& path, const std::string& input,
                          const vm::MeshJobResult& res, const vm::MeshJobOptions& options,
                          const std::string& hash, const std::string& options_text,
                          const vm::MeshFamily* family, std::string& err) {
  vm::MethodsReportInput in;
  in.result = &res;
  in.options = &options;
  in.input_name = std::filesystem::path(input).filename().string();
  in.input_hash = hash;
  in.options_text = options_text;
  in.version = vm::kVersion;
  in.family = family;
  in.images = vm::render_report_views(res);
  const std::string html = vm::methods_report_html(in);
  return write_file(path, html.data(), html.size(), err);
}

int cmd_mesh(int argc, char** argv) {
  Args a = vm::cli::parse_args(argc, argv, 2, vm::kCommandMesh);
  if (std::string e = one_argument_error(a, "mesh", "FILE"); !e.empty()) return usage_error(e);
  const vm::OptionValue* out = a.get("output");
  if (!out) return usage_error("mesh needs an output file: -o OUT.msh");
  vm::MeshJobOptions options;
  if (std::string e = vm::cli::apply_all(a, options); !e.empty()) return usage_error(e);
  std::string err;
  const auto dest = destination(out->text, options, err);
  if (!dest) return usage_error(err);
  auto bytes = read_file(a.positional[0], options, err);
  if (!bytes) return fail(err);
  // The file's hash for the provenance; its bytes are freed once prepared.
  const std::string hash = vm::input_hash(*bytes);
  const std::string options_text = vm::options_provenance(a.values);
  vm::WriteOptions wo = vm::write_options(options);
  wo.provenance = vm::provenance_text(vm::kVersion, hash, options_text);
  const vm::OptionValue* report_html = a.get("report_html");
  if (options.family > 1) {
    // Each member is written once meshed; the first is kept for the report.
    std::optional<vm::MeshJobResult> first;
    vm::MeshJobOptions first_options;
    std::vector<std::string> paths;
    auto write_member = [&](int k, const vm::MeshJobOptions& member,
                            const vm::MeshJobResult& res) -> vm::Status {
      vm::WriteOptions mo = wo;
      mo.provenance = vm::provenance_text(vm::kVersion, hash,
                                          options_text + " family_member=" + std::to_string(k));
      auto files = vm::write_outputs(res, dest->format, mo);
      if (!files.ok()) return files.status();
      auto [path, d] = member_destination(out->text, *dest, k);
      std::string error;
      if (!write_outputs(path, d, files.value(), error)) return vm::Status::Error(error);
      paths.push_back(path);
      if (!a.get("quiet")) {
        for (const std::string& w : res.warnings)
          std::fprintf(stderr, "warning: member %d: %s\n", k,
                       vm::phrase_options(w, vm::kFaceCli).c_str());
        std::printf("wrote %s (member %d of %d) in %.3f s\n", path.c_str(), k + 1, options.family,
                    res.seconds_total);
      }
      if (k == 0 && (report_html || a.get("report"))) {
        first = res;
        first_options = member;
      }
      return vm::Status::Ok();
    };
    auto family = vm::run_mesh_family(*bytes, options, write_member);
    bytes.reset();
    if (!family.ok()) return fail(a.positional[0], family.status());
    vm::MeshFamily& fam = family.value();
    for (size_t k = 0; k < fam.rows.size() && k < paths.size(); ++k) fam.rows[k].file = paths[k];
    std::string stem = out->text;
    if (!stem.empty() && stem.back() == '/') stem.pop_back();
    const std::filesystem::path sp(stem);
    const std::string table =
        (sp.parent_path() / ((dest->folder ? sp.filename() : sp.stem()).string() + "_family"))
            .string();
    const std::string csv = vm::family_csv(fam), json = vm::family_json(fam) + "\n";
    if (!write_file(table + ".csv", csv.data(), csv.size(), err) ||
        !write_file(table + ".json", json.data(), json.size(), err))
      return fail(err);
    if (const vm::OptionValue* rep = a.get("report"); rep && first) {
      std::string json = vm::mesh_report_json(*first) + "\n";
      if (!write_file(rep->text, json.data(), json.size(), err)) return fail(err);
    }
    if (report_html && first &&
        !write_methods_report(report_html->text, a.positional[0], *first, first_options, hash,
                              options_text, &fam, err))
      return fail(err);
    if (!a.get("quiet")) {
      print_family(fam);
      std::printf("wrote %s.csv and %s.json\n", table.c_str(), table.c_str());
    }
    return 0;
  }
  auto r = vm::run_mesh_job(*bytes, options, {}, [&] { bytes.reset(); });
  if (!r.ok()) return fail(a.positional[0], r.status());
  const vm::MeshJobResult& res = r.value();
  auto files = vm::write_outputs(res, dest->format, wo);
  if (!files.ok()) return fail(a.positional[0], files.status());
  if (!write_outputs(out->text, *dest, files.value(), err)) return fail(err);
  if (const vm::OptionValue* rep = a.get("report")) {
    std::string json = vm::mesh_report_json(res) + "\n";
    if (!write_file(rep->text, json.data(), json.size(), err)) return fail(err);
  }
  if (report_html && !write_methods_report(report_html->text, a.positional[0], res, options, hash,
                                           options_text, nullptr, err))
    return fail(err);
  if (!a.get("quiet")) print_mesh_summary(out->text, res);
  return 0;
}

int cmd_phantom(int argc, char** argv) {
  Args a = vm::cli::parse_args(argc, argv, 2, vm::kCommandPhantom);
  if (std::string e = one_argument_error(a, "phantom", "OUT.stl or OUT.vtp"); !e.empty())
    return usage_error(e);
  vm::PhantomOptions o;
  if (std::string e = vm::cli::apply_all(a, o); !e.empty()) return usage_error(e);
  vm::PhantomTruth truth;
  auto r = vm::make_vessel_phantom(o, &truth);
  if (!r.ok()) return fail("", r.status());
  // .vtp: the labelled surface, as SimVascular writes one; else STL.
  const std::string& path = a.positional[0];
  const bool vtp = path.size() > 4 && path.compare(path.size() - 4, 4, ".vtp") == 0;
  std::vector<uint8_t> bytes;
  if (vtp) {
    vm::VtkWriteOptions wo;
    wo.comment = "vesselmesh phantom";
    auto text = vm::write_surface_vtp(r.value(), truth.face_labels, wo);
    if (!text.ok()) return fail("", text.status());
    bytes.assign(text.value().begin(), text.value().end());
  } else {
    bytes = vm::write_stl_binary(r.value(), "vesselmesh phantom");
  }
  std::string err;
  if (!write_file(path, bytes.data(), bytes.size(), err)) return fail(err);
  std::printf("wrote %s: %zu triangles\n", path.c_str(), r.value().num_triangles());
  return 0;
}

int cmd_options(int argc, char** argv) {
  const std::string format = argc > 2 ? argv[2] : "";
  if (argc > 3 || (argc == 3 && format != "--json" && format != "--markdown"))
    return usage_error("options takes --json or --markdown");
  if (format == "--json")
    std::printf("%s\n", vm::option_table_json().c_str());
  else if (format == "--markdown")
    std::fputs(vm::cli::options_markdown().c_str(), stdout);
  else
    std::fputs(vm::cli::options_help().c_str(), stdout);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  vm::keep_freed_memory_for_reuse();
  if (argc < 2) {
    std::fputs(kIntro, stderr);
    return 2;
  }
  std::string cmd = argv[1];
  try {
    if (cmd == "--help" || cmd == "-h" || cmd == "help") {
      std::fputs(kIntro, stdout);
      std::fputs(vm::cli::options_help().c_str(), stdout);
      std::fputs("\nExit status: 0 success, 1 bad input or failure, 2 bad usage.\n", stdout);
      return 0;
    }
    if (cmd == "--version") {
      std::printf("vesselmesh %s\n", vm::kVersion);
      return 0;
    }
    if (cmd == "info") return cmd_info(argc, argv);
    if (cmd == "mesh") return cmd_mesh(argc, argv);
    if (cmd == "phantom") return cmd_phantom(argc, argv);
    if (cmd == "options") return cmd_options(argc, argv);
  } catch (const std::bad_alloc&) {
    return fail(
        "out of memory: this job needs more memory than the machine has; lower the element "
        "budget (--max-elements) or ask for larger elements");
  } catch (const std::exception& e) {
    return fail(std::string("internal error: ") + e.what() + " (please report it)");
  }
  return usage_error("unknown command '" + cmd + "'");
}
