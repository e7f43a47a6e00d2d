// Embind bindings: the WebAssembly face of vmcore. Thin on purpose: convert
// JS values in, call core, copy results out as owned typed arrays (heap views
// detach when memory grows), report errors as {ok: false, error}. Nothing
// throws across this boundary; JSON reports come from core/pipeline/
// report_json.h and are parsed by the JS wrapper.
#include <emscripten/bind.h>
#include <emscripten/val.h>

#include <string>
#include <vector>

#include "core/io/stl.h"
#include "core/phantom/vessel_phantom.h"
#include "core/pipeline/job_options.h"
#include "core/pipeline/mesh_job.h"
#include "core/pipeline/report_json.h"

namespace {

using emscripten::val;

constexpr const char* kVersion = "0.1.0";

std::vector<uint8_t> bytes_from(const val& array) {
  const size_t n = array["length"].as<size_t>();
  std::vector<uint8_t> bytes(n);
  val(emscripten::typed_memory_view(n, bytes.data())).call<void>("set", array);
  return bytes;
}

template <class T>
val copy_out(const T* data, size_t n, const char* type) {
  // Constructing a typed array from a view copies it out of the heap.
  return val::global(type).new_(val(emscripten::typed_memory_view(n, data)));
}

vm::ProgressFn progress_from(val fn) {
  if (fn.isUndefined() || fn.isNull()) return {};
  return [fn](double fraction, std::string_view stage) {
    val r = fn(fraction, std::string(stage));
    return !r.strictlyEquals(val(false));  // returning false cancels
  };
}

val error(const std::string& message) {
  val r = val::object();
  r.set("ok", false);
  r.set("error", message);
  if (message == vm::kCancelledMessage) r.set("cancelled", true);
  return r;
}

void set_surface(val& r, const vm::SurfaceMesh& m, const std::vector<float>& quality) {
  std::vector<float> positions(m.points.begin(), m.points.end());
  val s = val::object();
  s.set("positions", copy_out(positions.data(), positions.size(), "Float32Array"));
  s.set("triangles", copy_out(reinterpret_cast<const uint32_t*>(m.triangles.data()),
                              m.triangles.size(), "Uint32Array"));
  s.set("quality", copy_out(quality.data(), quality.size(), "Float32Array"));
  r.set("surface", s);
}

/// The volume mesh for display: positions, tets and their gamma_t and
/// region, the boundary triangles with their surface tag, and the names of
/// the tags.
void set_volume(val& r, const vm::MeshJobResult& res) {
  const vm::VolumeMesh& m = res.volume;
  std::vector<float> positions(m.points.begin(), m.points.end());
  val v = val::object();
  v.set("positions", copy_out(positions.data(), positions.size(), "Float32Array"));
  v.set("tets",
        copy_out(reinterpret_cast<const uint32_t*>(m.tets.data()), m.tets.size(), "Uint32Array"));
  v.set("tetQuality", copy_out(res.tet_quality.data(), res.tet_quality.size(), "Float32Array"));
  v.set("tetRegion", copy_out(m.tet_region.data(), m.tet_region.size(), "Int32Array"));
  v.set("tetPart", copy_out(res.tet_part.data(), res.tet_part.size(), "Uint8Array"));
  v.set("triangles", copy_out(reinterpret_cast<const uint32_t*>(m.triangles.data()),
                              m.triangles.size(), "Uint32Array"));
  v.set("triangleTag", copy_out(m.triangle_tag.data(), m.triangle_tag.size(), "Int32Array"));
  if (!m.prisms.empty()) {  // kept prisms and their faces at the openings
    v.set("prisms", copy_out(reinterpret_cast<const uint32_t*>(m.prisms.data()), m.prisms.size(),
                             "Uint32Array"));
    v.set("prismRegion", copy_out(m.prism_region.data(), m.prism_region.size(), "Int32Array"));
    v.set("quads", copy_out(reinterpret_cast<const uint32_t*>(m.quads.data()), m.quads.size(),
                            "Uint32Array"));
    v.set("quadTag", copy_out(m.quad_tag.data(), m.quad_tag.size(), "Int32Array"));
  }
  val names = val::array();
  for (const std::string& n : res.surface_names) names.call<void>("push", n);
  v.set("surfaceNames", names);
  val regions = val::array();
  for (const std::string& n : res.region_names) regions.call<void>("push", n);
  v.set("regionNames", regions);
  r.set("volume", v);
}

val analyze(val stl, val progress) {
  std::vector<uint8_t> bytes = bytes_from(stl);
  auto prepared = vm::prepare_surface(bytes, {}, progress_from(progress));
  if (!prepared.ok()) return error(prepared.message());
  val r = val::object();
  r.set("ok", true);
  r.set("analysisJson", vm::analysis_json(prepared.value()));
  set_surface(r, prepared.value().mesh, prepared.value().quality);
  return r;
}

/// options: a plain object of option name -> text value (names of
/// vm::set_job_option), plus booleans largestComponentOnly and remesh.
val mesh(val stl, val opts, val progress) {
  vm::MeshJobOptions options;
  for (std::string_view name : vm::job_option_names()) {
    val v = opts[std::string(name)];
    if (v.isUndefined()) continue;
    vm::Status st = vm::set_job_option(options, name, v.as<std::string>());
    if (!st.ok()) return error(st.message());
  }
  options.largest_component_only = opts["largestComponentOnly"].as<bool>();
  options.remesh = opts["remesh"].as<bool>();
  options.volume = !opts["surfaceOnly"].as<bool>();
  options.tag_layer = opts["tagLayer"].as<bool>();
  options.keep_prisms = opts["prisms"].as<bool>();
  std::vector<uint8_t> bytes = bytes_from(stl);
  auto result = vm::run_mesh_job(bytes, options, progress_from(progress));
  if (!result.ok()) return error(result.message());
  const vm::MeshJobResult& res = result.value();
  val r = val::object();
  r.set("ok", true);
  r.set("msh",
        copy_out(reinterpret_cast<const uint8_t*>(res.msh.data()), res.msh.size(), "Uint8Array"));
  r.set("reportJson", vm::mesh_report_json(res));
  set_surface(r, res.output_surface, res.output_quality);
  if (!res.volume.tets.empty()) set_volume(r, res);
  return r;
}

val make_phantom(std::string kind, double voxel, bool open_ends, double noise, double seed,
                 double scale) {
  vm::PhantomOptions o;
  if (kind == "tube")
    o.kind = vm::PhantomKind::kTube;
  else if (kind == "bifurcation")
    o.kind = vm::PhantomKind::kBifurcation;
  else if (kind == "aneurysm")
    o.kind = vm::PhantomKind::kAneurysm;
  else if (kind == "torus")
    o.kind = vm::PhantomKind::kTorus;
  else
    return error("unknown phantom kind '" + kind + "'");
  o.voxel = voxel;
  o.open_ends = open_ends;
  o.noise = noise;
  o.seed = uint32_t(seed);
  o.scale = scale;
  auto m = vm::make_vessel_phantom(o);
  if (!m.ok()) return error(m.message());
  std::vector<uint8_t> stl = vm::write_stl_binary(m.value(), "vesselmesh phantom " + kind);
  val r = val::object();
  r.set("ok", true);
  r.set("stl", copy_out(stl.data(), stl.size(), "Uint8Array"));
  return r;
}

std::string version() { return kVersion; }

}  // namespace

EMSCRIPTEN_BINDINGS(vesselmesh) {
  emscripten::function("analyze", &analyze);
  emscripten::function("mesh", &mesh);
  emscripten::function("makePhantom", &make_phantom);
  emscripten::function("version", &version);
}
