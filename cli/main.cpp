// The `vesselmesh` command: parse arguments, call core, print results.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>
#include <new>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include "core/io/stl.h"
#include "core/phantom/vessel_phantom.h"
#include "core/pipeline/job_options.h"
#include "core/pipeline/mesh_job.h"
#include "core/pipeline/report_json.h"
#include "core/util/allocator_tuning.h"

namespace {

constexpr const char* kVersion = "0.1.0";

constexpr const char* kUsage =
    R"(vesselmesh: quality meshes for cardiovascular flow simulation

usage:
  vesselmesh info FILE.stl [--json]
      Read, weld and analyze a lumen surface: counts, openings, genus,
      non-manifold edges, triangle quality gamma_k.
  vesselmesh mesh FILE.stl -o OUT.msh [--surface-only] [size options]
                  [--inlet K] [--core-size H] [layer options]
                  [--param lscm|harmonic|floater] [--mesher2d frontal|delaunay|adapt]
                  [--msh-version 4.1|2.2] [--largest-component] [--report FILE.json]
                  [--no-remesh] [--verify]
      Remesh the surface by conformal maps, grow a boundary layer inward,
      cap each opening with a planar triangulation, fill the lumen with
      tetrahedra and write Gmsh MSH: surfaces `wall`, `inlet`, `outlet_1..k`,
      volume `lumen` (and with a vessel wall: `outer_wall`, `wall_inlet`,
      `wall_outlet_k`, volume `vessel_wall`).
      --surface-only writes the remeshed wall alone; --no-remesh uses the
      repaired input surface as it is. --inlet K names opening K (as
      `info` lists them, largest first) `inlet` instead of the largest.
      --verify checks the volume fully before writing it (conformity, the
      boundary faces are the surface triangles) and measures the layers'
      heights from the wall (report); no element is ever inverted.
      Size options (model units):
        --size H                 uniform target edge length
        --per-circumference N    h = 2 pi R(x) / N, R the local vessel radius
                                 (the default, with N = 20)
        --size-min H, --size-max H   clamps
        --gradation G            h grows at most G per unit length
        --curvature P            at least P edges per radian of curvature
        --feature-angle A        keep creases sharper than A degrees (default 60;
                                 180: none)
        --fidelity F             input vertices farther than F h from the wall get
                                 a wall vertex pinned onto them and a finer size
                                 around them, where quality and size allow
                                 (default 0.1; 0: none, bumps are smoothed over)
        --core-size H            target size in the core of the lumen (default:
                                 the uniform size, or grown from the wall's)
      Layer options (R = the local vessel radius):
        --layers N               viscous layers grown inward (default 4; 0: none)
        --layer-thickness F      their total thickness F R (default 0.2)
        --first-layer H1         or: first layer height H1, then x --growth G
        --growth G               height ratio of consecutive layers (default 1)
        --wall-thickness F       grow the vessel wall outward, F R thick (e.g. 0.1)
        --wall-layers N          its layers (default 4 with --wall-thickness)
        --tag-layer              the viscous layer as its own volume boundary_layer
        --prisms                 keep the layers' prisms (MSH type 6, quads at the
                                 openings) instead of 3 tetrahedra each
  vesselmesh phantom OUT.stl [--kind bifurcation|tube|aneurysm|torus]
                  [--voxel V] [--noise A] [--seed N] [--scale S] [--closed]
      Write a synthetic segmentation-like vessel surface (binary STL).
  vesselmesh --help | --version

Exit status: 0 success, 1 bad input or failure, 2 bad usage.
)";

int usage_error(const std::string& msg) {
  std::cerr << "vesselmesh: " << msg << "\n(run 'vesselmesh --help' for usage)\n";
  return 2;
}

int fail(const std::string& msg) {
  std::cerr << "vesselmesh: error: " << msg << "\n";
  return 1;
}

std::optional<std::vector<uint8_t>> read_file(const std::string& path, std::string& error) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) {
    error = "cannot open '" + path + "'";
    return std::nullopt;
  }
  std::streamsize size = in.tellg();
  if (size < 0) {
    error = "cannot read '" + path + "' (is it a directory?)";
    return std::nullopt;
  }
  in.seekg(0);
  std::vector<uint8_t> bytes(static_cast<size_t>(size));
  if (size > 0 && !in.read(reinterpret_cast<char*>(bytes.data()), size)) {
    error = "cannot read '" + path + "'";
    return std::nullopt;
  }
  return bytes;
}

bool write_file(const std::string& path, const void* data, size_t size, std::string& error) {
  std::ofstream out(path, std::ios::binary);
  if (!out || !out.write(static_cast<const char*>(data), std::streamsize(size))) {
    error = "cannot write '" + path + "'";
    return false;
  }
  return true;
}

// Simple option scanner: positional arguments and --flag [value].
struct Args {
  std::vector<std::string> positional;
  std::vector<std::pair<std::string, std::string>> options;
  std::string error;

  bool has(const std::string& name) const {
    for (auto& o : options)
      if (o.first == name) return true;
    return false;
  }
  std::optional<std::string> get(const std::string& name) const {
    for (auto& o : options)
      if (o.first == name) return o.second;
    return std::nullopt;
  }
};

Args parse(int argc, char** argv, int first, const std::vector<std::string>& with_value,
           const std::vector<std::string>& flags) {
  Args a;
  for (int i = first; i < argc; ++i) {
    std::string s = argv[i];
    if (s.size() > 1 && s[0] == '-') {
      std::string name = s, value;
      size_t eq = s.find('=');
      if (eq != std::string::npos) {
        name = s.substr(0, eq);
        value = s.substr(eq + 1);
      }
      bool takes = std::find(with_value.begin(), with_value.end(), name) != with_value.end();
      bool flag = std::find(flags.begin(), flags.end(), name) != flags.end();
      if (!takes && !flag) {
        a.error = "unknown option '" + name + "'";
        return a;
      }
      if (takes && eq == std::string::npos) {
        if (i + 1 >= argc) {
          a.error = "option '" + name + "' needs a value";
          return a;
        }
        value = argv[++i];
      }
      a.options.emplace_back(name, value);
    } else {
      a.positional.push_back(s);
    }
  }
  return a;
}

bool parse_double(const std::string& s, double& out) {
  char* end = nullptr;
  out = std::strtod(s.c_str(), &end);
  return !s.empty() && end == s.c_str() + s.size() && std::isfinite(out);
}

void print_text_report(const std::string& path, const vm::PreparedSurface& s) {
  const vm::TopologyReport& t = s.topology;
  std::printf("file:        %s (%s, %zu triangles)\n", path.c_str(), s.format.c_str(),
              s.input_triangles);
  std::printf("welded:      %zu vertices, %zu triangles, %zu edges\n", t.vertices, t.triangles,
              t.edges);
  std::printf("bounding box: [%g, %g, %g] - [%g, %g, %g] (diagonal %g)\n", s.box.min[0],
              s.box.min[1], s.box.min[2], s.box.max[0], s.box.max[1], s.box.max[2],
              s.box.diagonal());
  std::printf("components:  %d\n", t.components);
  std::printf("closed:      %s\n", t.closed ? "yes" : "no");
  if (t.genus >= 0)
    std::printf("genus:       %d\n", t.genus);
  else
    std::printf("genus:       undefined (non-manifold)\n");
  std::printf("euler char.: %ld\n", t.euler_characteristic);
  std::printf("non-manifold edges: %zu, vertices: %zu\n", t.nonmanifold_edges,
              t.nonmanifold_vertices);
  std::printf("openings:    %zu\n", t.openings.size());
  for (size_t i = 0; i < t.openings.size(); ++i) {
    const vm::Opening& o = t.openings[i];
    std::printf("  %zu: perimeter %g, radius %g, centroid (%g, %g, %g), %zu vertices\n", i + 1,
                o.perimeter, o.radius, o.centroid[0], o.centroid[1], o.centroid[2], o.loop.size());
  }
  std::printf("quality gamma_k: min %.4f, mean %.4f\n", s.quality_stats.min, s.quality_stats.mean);
  for (const std::string& w : s.warnings) std::printf("warning: %s\n", w.c_str());
}

int cmd_info(int argc, char** argv) {
  Args a = parse(argc, argv, 2, {}, {"--json"});
  if (!a.error.empty()) return usage_error(a.error);
  if (a.positional.size() != 1) return usage_error("info needs exactly one FILE.stl");
  std::string err;
  auto bytes = read_file(a.positional[0], err);
  if (!bytes) return fail(err);
  auto r = vm::prepare_surface(*bytes);
  if (!r.ok()) return fail(a.positional[0] + ": " + r.message());
  if (a.has("--json")) {
    std::printf("%s\n", vm::analysis_json(r.value()).c_str());
  } else {
    print_text_report(a.positional[0], r.value());
  }
  return 0;
}

int cmd_mesh(int argc, char** argv) {
  std::vector<std::string> valued = {"-o", "--output", "--report"};
  for (std::string_view name : vm::job_option_names()) valued.push_back("--" + std::string(name));
  Args a = parse(argc, argv, 2, valued,
                 {"--largest-component", "--quiet", "--surface-only", "--no-remesh", "--verify",
                  "--tag-layer", "--prisms"});
  if (!a.error.empty()) return usage_error(a.error);
  if (a.positional.size() != 1) return usage_error("mesh needs exactly one FILE.stl");
  auto out = a.get("-o") ? a.get("-o") : a.get("--output");
  if (!out) return usage_error("mesh needs an output file: -o OUT.msh");
  vm::MeshJobOptions options;
  for (const auto& [name, value] : a.options) {
    if (name.rfind("--", 0) != 0) continue;
    const std::string key = name.substr(2);
    const auto& names = vm::job_option_names();
    if (std::find(names.begin(), names.end(), key) == names.end()) continue;
    vm::Status st = vm::set_job_option(options, key, value);
    if (!st.ok()) return usage_error(st.message());
  }
  options.largest_component_only = a.has("--largest-component");
  options.remesh = !a.has("--no-remesh");
  options.volume = !a.has("--surface-only");
  options.verify = a.has("--verify");
  options.tag_layer = a.has("--tag-layer");
  options.keep_prisms = a.has("--prisms");
  std::string err;
  auto bytes = read_file(a.positional[0], err);
  if (!bytes) return fail(err);
  auto r = vm::run_mesh_job(*bytes, options);
  if (!r.ok()) return fail(a.positional[0] + ": " + r.message());
  const vm::MeshJobResult& res = r.value();
  if (!write_file(*out, res.msh.data(), res.msh.size(), err)) return fail(err);
  if (auto rep = a.get("--report")) {
    std::string json = vm::mesh_report_json(res) + "\n";
    if (!write_file(*rep, json.data(), json.size(), err)) return fail(err);
  }
  if (!a.has("--quiet")) {
    for (const std::string& w : res.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
    std::printf("wrote %s in %.3f s:", out->c_str(), res.seconds_total);
    for (const vm::OutputGroup& g : res.groups)
      std::printf(" %s %zu%s", g.name.c_str(), g.elements, &g == &res.groups.back() ? "\n" : ",");
    std::printf("wall: %zu vertices, %zu triangles, gamma_k min %.4f mean %.4f\n",
                res.output_surface.num_vertices(), res.output_surface.num_triangles(),
                res.output_quality_stats.min, res.output_quality_stats.mean);
    if (!res.volume.tets.empty()) {
      const vm::VolumeStats& vs = res.volume_stats;
      std::printf(
          "volume: %zu vertices, %zu tetrahedra, core gamma_t min %.4f mean %.4f; %zu Steiner "
          "points; time: layers %.2f s, caps %.2f s, recovery %.2f s, refinement %.2f s, check "
          "%.2f s\n",
          res.volume.num_vertices(), res.volume.num_tets(), res.core_quality_stats.min,
          res.core_quality_stats.mean, vs.steiner_points, vs.seconds_layers, vs.seconds_caps,
          vs.seconds_recovery, vs.seconds_refinement, vs.seconds_check);
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
          "remeshed: %zu patches, %zu seam points, size %.4g..%.4g (median %.4g); "
          "time: size %.2f s, partition %.2f s, meshing %.2f s, optimization %.2f s\n",
          st.patches, st.seam_points, st.size_min, st.size_max, st.size_median, st.seconds_size,
          st.seconds_partition, st.seconds_mesh, st.seconds_optimize);
    }
  }
  return 0;
}

int cmd_phantom(int argc, char** argv) {
  Args a =
      parse(argc, argv, 2, {"--kind", "--voxel", "--noise", "--seed", "--scale"}, {"--closed"});
  if (!a.error.empty()) return usage_error(a.error);
  if (a.positional.size() != 1) return usage_error("phantom needs exactly one OUT.stl");
  vm::PhantomOptions o;
  if (auto k = a.get("--kind")) {
    if (*k == "tube")
      o.kind = vm::PhantomKind::kTube;
    else if (*k == "bifurcation")
      o.kind = vm::PhantomKind::kBifurcation;
    else if (*k == "aneurysm")
      o.kind = vm::PhantomKind::kAneurysm;
    else if (*k == "torus")
      o.kind = vm::PhantomKind::kTorus;
    else
      return usage_error("unknown phantom kind '" + *k + "' (tube, bifurcation, aneurysm, torus)");
  }
  double d;
  if (auto v = a.get("--voxel")) {
    if (!parse_double(*v, d)) return usage_error("--voxel needs a number");
    o.voxel = d;
  }
  if (auto v = a.get("--noise")) {
    if (!parse_double(*v, d)) return usage_error("--noise needs a number");
    o.noise = d;
  }
  if (auto v = a.get("--scale")) {
    if (!parse_double(*v, d)) return usage_error("--scale needs a number");
    o.scale = d;
  }
  if (auto v = a.get("--seed")) {
    if (!parse_double(*v, d) || d < 0) return usage_error("--seed needs a non-negative integer");
    o.seed = uint32_t(d);
  }
  o.open_ends = !a.has("--closed");
  auto r = vm::make_vessel_phantom(o);
  if (!r.ok()) return fail(r.message());
  std::vector<uint8_t> stl = vm::write_stl_binary(r.value(), "vesselmesh phantom");
  std::string err;
  if (!write_file(a.positional[0], stl.data(), stl.size(), err)) return fail(err);
  std::printf("wrote %s: %zu triangles\n", a.positional[0].c_str(), r.value().num_triangles());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  vm::keep_freed_memory_for_reuse();
  if (argc < 2) {
    std::fputs(kUsage, stderr);
    return 2;
  }
  std::string cmd = argv[1];
  try {
    if (cmd == "--help" || cmd == "-h" || cmd == "help") {
      std::fputs(kUsage, stdout);
      return 0;
    }
    if (cmd == "--version") {
      std::printf("vesselmesh %s\n", kVersion);
      return 0;
    }
    if (cmd == "info") return cmd_info(argc, argv);
    if (cmd == "mesh") return cmd_mesh(argc, argv);
    if (cmd == "phantom") return cmd_phantom(argc, argv);
  } catch (const std::bad_alloc&) {
    return fail("out of memory: the input is too large for this machine");
  }
  return usage_error("unknown command '" + cmd + "'");
}
