// Embind bindings: the WebAssembly face of vmcore. Thin on purpose: convert
// JS values in, call core, copy results out as owned typed arrays (heap views
// detach when memory grows), report errors as {ok: false, error}. Nothing
// throws across this boundary; JSON reports come from core/pipeline/
// report_json.h and are parsed by the JS wrapper. No state is kept here
// between calls: analyze() and mesh() give their result as a handle (an
// Embind object of class Analysis or Mesh, owned by JS and freed with its
// delete()) and the calls on an analysis or a mesh take it (the JS wrapper
// checks it is one of its live handles: a deleted one would throw).
#include <emscripten/bind.h>
#include <emscripten/em_asm.h>
#include <emscripten/heap.h>
#include <emscripten/val.h>
#include <malloc.h>

#include <array>
#include <cmath>
#include <cstdlib>
#include <new>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "core/io/provenance.h"
#include "core/io/stl.h"
#include "core/io/vtk_writer.h"
#include "core/io/zip_writer.h"
#include "core/layers/layer_thickness.h"
#include "core/mesh/adjacency.h"
#include "core/mesh/prism_split.h"
#include "core/mesh/tet_face_adjacency.h"
#include "core/phantom/vessel_phantom.h"
#include "core/pipeline/mesh_family.h"
#include "core/pipeline/mesh_job.h"
#include "core/pipeline/opening_names.h"
#include "core/pipeline/option_table.h"
#include "core/pipeline/report_json.h"
#include "core/pipeline/size_preview.h"
#include "core/pipeline/solver_preset.h"
#include "core/pipeline/validate_options.h"
#include "core/pipeline/write_outputs.h"
#include "core/prepare/cut_across_vessel.h"
#include "core/quality/tet_quality.h"
#include "core/report/methods_report.h"
#include "core/report/render_views.h"
#include "core/util/parallel.h"
#include "core/util/version.h"

namespace {

using emscripten::val;

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

/// {ok: false, error, kind, option?, cancelled?, remedy?}: the error phrased
/// with the JS API's option names; remedy {action, places, value} when core
/// knows what the user can do (vm::Remedy).
val error(const vm::Status& st) {
  val r = val::object();
  r.set("ok", false);
  r.set("error", vm::phrase_error(st, vm::kFaceJs));
  static constexpr const char* kKinds[] = {"none", "bad_input", "bad_option", "cancelled",
                                           "internal"};
  r.set("kind", std::string(kKinds[int(st.kind())]));
  if (st.kind() == vm::ErrorKind::kBadOption) {
    if (const vm::OptionSpec* spec = vm::find_option(st.option()))
      r.set("option", std::string(spec->js));
  }
  if (st.cancelled()) r.set("cancelled", true);
  const vm::Remedy& remedy = st.remedy();
  if (!remedy.action.empty()) {
    val m = val::object();
    m.set("action", remedy.action);
    val places = val::array();
    for (const auto& p : remedy.places) {
      val q = val::array();
      for (double x : p) q.call<void>("push", x);
      places.call<void>("push", q);
    }
    m.set("places", places);
    m.set("value", remedy.value);
    r.set("remedy", m);
  }
  return r;
}

/// One JS value of option `spec` as an OptionValue: numbers stay numbers,
/// booleans booleans, lists arrays; per-opening options take {K: value} (or
/// a plain value for all openings when optional).
vm::Result<std::vector<vm::OptionValue>> values_from(const vm::OptionSpec& spec, const val& v) {
  using R = vm::Result<std::vector<vm::OptionValue>>;
  const std::string js(spec.js);
  auto one = [&](const val& x, int opening) -> vm::Result<vm::OptionValue> {
    vm::OptionValue o;
    o.opening = opening;
    const std::string type = x.typeOf().as<std::string>();
    switch (spec.type) {
      case vm::OptionType::kNumber:
      case vm::OptionType::kInteger:
        if (type != "number")
          return vm::Status::BadOption(std::string(spec.id), "must be a number");
        o.number = x.as<double>();
        break;
      case vm::OptionType::kFlag:
        if (type != "boolean")
          return vm::Status::BadOption(std::string(spec.id), "must be true or false");
        o.flag = x.as<bool>();
        break;
      case vm::OptionType::kChoice:
      case vm::OptionType::kText:
        // A whole number stands for its text ({smooth: 5} as '5').
        if (type == "number" && spec.type == vm::OptionType::kText &&
            std::abs(x.as<double>()) < 1e15 && x.as<double>() == double(int64_t(x.as<double>()))) {
          o.text = std::to_string(int64_t(x.as<double>()));
          break;
        }
        if (type != "string")
          return vm::Status::BadOption(std::string(spec.id), "must be a string");
        o.text = x.as<std::string>();
        break;
      case vm::OptionType::kNumbers: {
        if (!x.isArray())
          return vm::Status::BadOption(std::string(spec.id), "must be an array of numbers");
        const size_t n = x["length"].as<size_t>();
        for (size_t i = 0; i < n && i < 64; ++i) {
          if (x[i].typeOf().as<std::string>() != "number")
            return vm::Status::BadOption(std::string(spec.id), "must be an array of numbers");
          o.numbers.push_back(x[i].as<double>());
        }
        if (n > 64) o.numbers.resize(65);
        break;
      }
    }
    vm::Status st = vm::check_option_value(spec, o);
    if (!st.ok()) return st;
    return o;
  };
  std::vector<vm::OptionValue> out;
  auto add = [&](const val& x, int opening) -> vm::Status {
    auto o = one(x, opening);
    if (!o.ok()) return o.status();
    out.push_back(std::move(o).value());
    return vm::Status::Ok();
  };
  const bool keyed_object = spec.per_opening != vm::PerOpening::kNo &&
                            v.typeOf().as<std::string>() == "object" && !v.isNull() && !v.isArray();
  if (keyed_object) {
    val keys = val::global("Object").call<val>("keys", v);
    const size_t n = keys["length"].as<size_t>();
    for (size_t i = 0; i < n; ++i) {
      const std::string key = keys[i].as<std::string>();
      char* end = nullptr;
      const long k = std::strtol(key.c_str(), &end, 10);
      if (key.empty() || *end != '\0' || k < 1 || k > 1000000)
        return vm::Status::BadOption(std::string(spec.id),
                                     "keys must be opening numbers >= 1 (got '" + key + "')");
      if (vm::Status st = add(v[key], int(k)); !st.ok()) return st;
    }
  } else if (spec.repeatable && v.isArray() &&
             !(spec.type == vm::OptionType::kNumbers &&
               (v["length"].as<size_t>() == 0 || v[0].typeOf().as<std::string>() == "number"))) {
    // A list of values; for a list option, one list stands alone too.

    const size_t n = v["length"].as<size_t>();
    for (size_t i = 0; i < n; ++i)
      if (vm::Status st = add(v[i], 0); !st.ok()) return st;
  } else if (vm::Status st = add(v, 0); !st.ok()) {
    return st;
  }
  return R(std::move(out));
}

using Applied = std::vector<std::pair<const vm::OptionSpec*, vm::OptionValue>>;

/// Applies a JS options object to `target` (MeshJobOptions or
/// PhantomOptions) for `command`; unknown keys are errors, undefined values
/// are skipped. The values applied are appended to `applied` when given.
template <class Target>
vm::Status apply_js_options(Target& target, const val& opts, vm::OptionCommand command,
                            Applied* applied = nullptr) {
  if (opts.isUndefined() || opts.isNull()) return vm::Status::Ok();
  val keys = val::global("Object").call<val>("keys", opts);
  const size_t n = keys["length"].as<size_t>();
  Applied given;
  for (size_t i = 0; i < n; ++i) {
    const std::string key = keys[i].as<std::string>();
    const val v = opts[key];
    if (v.isUndefined()) continue;
    const vm::OptionSpec* spec = vm::find_js_option(key, command);
    if (!spec) return vm::Status::BadOption("", "unknown option '" + key + "'");
    auto values = values_from(*spec, v);
    if (!values.ok()) return values.status();
    for (const vm::OptionValue& o : values.value()) given.emplace_back(spec, o);
  }
  if (applied) applied->insert(applied->end(), given.begin(), given.end());
  if constexpr (std::is_same_v<Target, vm::MeshJobOptions>) {
    return vm::apply_options(target, given);  // the solver preset first
  } else {
    for (const auto& [spec, o] : given)
      if (vm::Status st = vm::apply_option(target, *spec, o); !st.ok()) return st;
    return vm::Status::Ok();
  }
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

/// The clipped view's face adjacency of the view's tetrahedra `tets` (the
/// mesh's, then with prisms their split) with its boundary `triangles` (the
/// mesh's, then the quads' halves) tagged `tags`: per face f of view
/// tetrahedron t (opposite vertex f), across[4t+f] = the view tetrahedron
/// across, or on the boundary -1 - g with g the tag of the triangle there
/// (0x7fff when none): web/src/clip.js's encoding. If the adjacency fails
/// (a face of three tetrahedra: never in a mesh check_volume_mesh passed),
/// every face is a boundary face.
std::vector<int32_t> view_across(const std::vector<int32_t>& tets, size_t num_vertices,
                                 const std::vector<int32_t>& triangles,
                                 const std::vector<int32_t>& tags) {
  constexpr int32_t kUnknownTag = 0x7fff;  // clip.js's UNKNOWN_TAG
  const size_t nt = tets.size() / 4;
  auto links = vm::tet_face_adjacency(tets.data(), nt, num_vertices);
  // A face of three tetrahedra (never in a checked mesh): all faces shown.
  std::vector<int32_t> across =
      links.ok() ? std::move(links).value() : std::vector<int32_t>(4 * nt, vm::kNoTetAcross);
  const std::vector<int32_t> on = vm::boundary_face_triangles(
      tets.data(), nt, across, triangles.data(), triangles.size() / 3);
  for (size_t i = 0; i < across.size(); ++i)
    across[i] = across[i] >= 0 ? across[i] >> 2 : -1 - (on[i] >= 0 ? tags[size_t(on[i])] : kUnknownTag);
  return across;
}

/// The volume mesh for display: positions, tets and their gamma_t and
/// region, the boundary triangles with their surface tag, the names of
/// the tags, and the face adjacency of the clipped view (view_across).
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
  // The clipped view's tetrahedra and boundary (with prisms, their split
  // appended, as web/src/prisms.js appends it).
  std::vector<int32_t> view_tets = m.tets, view_triangles = m.triangles,
                       view_tags = m.triangle_tag;
  if (!m.prisms.empty()) {  // kept prisms and their faces at the openings
    v.set("prisms", copy_out(reinterpret_cast<const uint32_t*>(m.prisms.data()), m.prisms.size(),
                             "Uint32Array"));
    v.set("prismRegion", copy_out(m.prism_region.data(), m.prism_region.size(), "Int32Array"));
    v.set("quads", copy_out(reinterpret_cast<const uint32_t*>(m.quads.data()), m.quads.size(),
                            "Uint32Array"));
    v.set("quadTag", copy_out(m.quad_tag.data(), m.quad_tag.size(), "Int32Array"));
    // For a view of tetrahedra only: each prism's 3 tetrahedra (the core's
    // split rule, so neighbours agree) with their gamma_t, each quad's 2
    // triangles.
    std::vector<int32_t> split(12 * m.num_prisms());
    std::vector<float> quality(3 * m.num_prisms());
    for (size_t p = 0; p < m.num_prisms(); ++p) {
      const auto tets = vm::split_prism(&m.prisms[6 * p]);
      for (size_t k = 0; k < 3; ++k) {
        std::copy(tets[k].begin(), tets[k].end(), &split[12 * p + 4 * k]);
        auto point = [&](int32_t i) { return &m.points[3 * size_t(tets[k][size_t(i)])]; };
        quality[3 * p + k] = float(vm::tet_gamma(point(0), point(1), point(2), point(3)));
      }
    }
    std::vector<int32_t> quad_triangles(6 * m.num_quads());
    for (size_t q = 0; q < m.num_quads(); ++q) {
      const auto tris = vm::split_quad(&m.quads[4 * q]);
      for (size_t k = 0; k < 2; ++k)
        std::copy(tris[k].begin(), tris[k].end(), &quad_triangles[6 * q + 3 * k]);
    }
    v.set("prismTets",
          copy_out(reinterpret_cast<const uint32_t*>(split.data()), split.size(), "Uint32Array"));
    v.set("prismTetQuality", copy_out(quality.data(), quality.size(), "Float32Array"));
    v.set("quadTriangles", copy_out(reinterpret_cast<const uint32_t*>(quad_triangles.data()),
                                    quad_triangles.size(), "Uint32Array"));
    view_tets.insert(view_tets.end(), split.begin(), split.end());
    view_triangles.insert(view_triangles.end(), quad_triangles.begin(), quad_triangles.end());
    for (size_t q = 0; q < 2 * m.num_quads(); ++q) view_tags.push_back(m.quad_tag[q / 2]);
  }
  const std::vector<int32_t> across =
      view_across(view_tets, m.num_vertices(), view_triangles, view_tags);
  v.set("across", copy_out(across.data(), across.size(), "Int32Array"));
  val names = val::array();
  for (const std::string& n : res.surface_names) names.call<void>("push", n);
  v.set("surfaceNames", names);
  val regions = val::array();
  for (const std::string& n : res.region_names) regions.call<void>("push", n);
  v.set("regionNames", regions);
  r.set("volume", v);
}

/// An analyzed surface, owned by JS: analyze() gives it as an Embind object
/// (`handle`), freed with its delete(); openingNames(), cutAt() and
/// sizeField() take it.
struct Analysis {
  vm::PreparedSurface surface;
  /// Its local vessel radius once sizeField() computed it (it depends on
  /// the surface only), else empty.
  std::vector<double> radius;
};

/// The bytes this module's memory can still give a job: its maximum
/// (MAXIMUM_MEMORY) less what is allocated now (the analyses and meshes
/// JS holds). The job's sizes are checked against it before meshing.
double free_memory() { return double(emscripten_get_heap_max()) - double(mallinfo().uordblks); }

/// The mesh options `opts` for a call on an analyzed surface, or an
/// option's error.
vm::Result<vm::MeshJobOptions> mesh_options(const val& opts) {
  vm::MeshJobOptions options;
  if (vm::Status st = apply_js_options(options, opts, vm::kCommandMesh); !st.ok()) return st;
  options.memory_bytes = free_memory();
  return options;
}

/// options: the JS API's analyze options (the table's info options).
/// {ok, analysisJson, surface, handle: the Analysis} or the error.
val analyze(val stl, val opts, val progress) {
  vm::MeshJobOptions options;
  if (vm::Status st = apply_js_options(options, opts, vm::kCommandInfo); !st.ok()) return error(st);
  std::vector<uint8_t> bytes = bytes_from(stl);
  auto prepared = vm::prepare_surface(bytes, options.prepare, progress_from(progress));
  if (!prepared.ok()) return error(prepared.status());
  val r = val::object();
  r.set("ok", true);
  r.set("analysisJson", vm::analysis_json(prepared.value(), vm::kFaceJs));
  set_surface(r, prepared.value().mesh, prepared.value().quality);
  r.set("handle", val(Analysis{std::move(prepared).value(), {}}));
  return r;
}

/// A meshed result, owned by JS: mesh() gives it as an Embind object
/// (`handle`), freed with its delete(); exportMesh() writes it in another
/// format without meshing again, with its input's provenance, and
/// methodsReport() reports it.
struct Mesh {
  vm::MeshJobResult result;
  std::string input_hash;
  Applied options;         ///< as given to mesh(), for provenance
  vm::MeshJobOptions job;  ///< the options the result was meshed with
  /// When mesh() made a family: its table (`result` is its first member).
  std::optional<vm::MeshFamily> family;
};

/// The files of `mesh` in `format` as one file (a zip for
/// mesh-complete and foam): {file, fileName} on `r`; false with `r` an error.
/// `extra`: export()'s own options, recorded after mesh()'s in the
/// provenance (a later value of an option wins).
bool set_file(val& r, const Mesh& mesh, vm::OutputFormat format,
              const vm::MeshJobOptions& options, const Applied& extra = {}) {
  vm::WriteOptions wo = vm::write_options(options);
  Applied all = mesh.options;
  all.insert(all.end(), extra.begin(), extra.end());
  wo.provenance =
      vm::provenance_text(vm::kVersion, mesh.input_hash, vm::options_provenance(all));
  auto files = vm::write_outputs(mesh.result, format, wo);
  if (!files.ok()) {
    r = error(files.status());
    return false;
  }
  std::string bytes, name;
  if (format == vm::OutputFormat::kMeshComplete || format == vm::OutputFormat::kFoam) {
    auto zip = vm::write_zip(files.value());
    if (!zip.ok()) {
      r = error(zip.status());
      return false;
    }
    bytes = std::move(zip).value();
    name = format == vm::OutputFormat::kFoam ? "openfoam-case.zip" : "mesh-complete.zip";
  } else {
    bytes = std::move(files.value()[0].bytes);
    name = files.value()[0].path;
  }
  r.set("file",
        copy_out(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size(), "Uint8Array"));
  r.set("fileName", name);
  r.set("format", std::string(vm::format_name(format)));
  return true;
}

/// The files a family's member k adds to the family's zip: its files in
/// `format`, as "mesh_k.<ext>" (a folder format: under "mesh_k/").
vm::Status add_member_files(std::vector<vm::OutputFile>& zip, int k, const vm::MeshJobResult& res,
                            vm::OutputFormat format, vm::WriteOptions wo) {
  wo.provenance += " family_member=" + std::to_string(k);
  auto files = vm::write_outputs(res, format, wo);
  if (!files.ok()) return files.status();
  const std::string member = "mesh_" + std::to_string(k);
  const bool folder =
      format == vm::OutputFormat::kMeshComplete || format == vm::OutputFormat::kFoam;
  for (vm::OutputFile& f : files.value()) {
    const std::string ext = f.path.substr(f.path.rfind('.'));
    f.path = folder ? member + "/" + f.path : member + ext;
    zip.push_back(std::move(f));
  }
  return vm::Status::Ok();
}

/// mesh() with options.family > 1: the family's files and tables as one
/// zip ({file, fileName "mesh-family.zip"}), the table as `familyJson` and
/// `familyCsv`; the first member is the handle's mesh (with the table).
val mesh_family(const std::vector<uint8_t>& bytes, const vm::MeshJobOptions& options,
                vm::OutputFormat format, Applied applied, const std::string& hash, val progress) {
  vm::WriteOptions wo = vm::write_options(options);
  wo.provenance = vm::provenance_text(vm::kVersion, hash, vm::options_provenance(applied));
  std::vector<vm::OutputFile> zip;
  std::optional<Mesh> first;
  auto family = vm::run_mesh_family(
      bytes, options,
      [&](int k, const vm::MeshJobOptions& member, const vm::MeshJobResult& res) {
        if (vm::Status st = add_member_files(zip, k, res, format, wo); !st.ok()) return st;
        if (k == 0) first = Mesh{res, hash, applied, member, std::nullopt};
        return vm::Status::Ok();
      },
      progress_from(progress));
  if (!family.ok()) return error(family.status());
  vm::MeshFamily& fam = family.value();
  for (size_t k = 0; k < fam.rows.size(); ++k) {
    const std::string stem = "mesh_" + std::to_string(k);
    for (const vm::OutputFile& f : zip)
      if (f.path.rfind(stem, 0) == 0 &&
          (f.path[stem.size()] == '.' || f.path[stem.size()] == '/')) {
        fam.rows[k].file = f.path[stem.size()] == '/' ? stem + "/" : f.path;
        break;
      }
  }
  const std::string csv = vm::family_csv(fam), json = vm::family_json(fam);
  zip.push_back({"family.csv", csv});
  zip.push_back({"family.json", json + "\n"});
  auto archive = vm::write_zip(zip);
  if (!archive.ok()) return error(archive.status());
  first->family = std::move(fam);
  const vm::MeshJobResult& res = first->result;
  val r = val::object();
  r.set("ok", true);
  const std::string& z = archive.value();
  r.set("file", copy_out(reinterpret_cast<const uint8_t*>(z.data()), z.size(), "Uint8Array"));
  r.set("fileName", std::string("mesh-family.zip"));
  r.set("format", std::string(vm::format_name(format)));
  r.set("familyJson", json);
  r.set("familyCsv", csv);
  r.set("reportJson", vm::mesh_report_json(res, vm::kFaceJs));
  set_surface(r, res.output_surface, res.output_quality);
  if (!res.volume.tets.empty()) set_volume(r, res);
  r.set("handle", val(std::move(*first)));
  return r;
}

/// options: the JS API's mesh options (the table's mesh options, by their
/// JS keys, with JS types). {ok, file, fileName, format, reportJson,
/// surface, volume?, handle: the Mesh} or the error.
val mesh(val stl, val opts, val progress) {
  vm::MeshJobOptions options;
  Applied applied;
  if (vm::Status st = apply_js_options(options, opts, vm::kCommandMesh, &applied); !st.ok())
    return error(st);
  const vm::OutputFormat format = vm::resolve_output_format(options, std::nullopt);
  if (vm::Status st = vm::validate_options(options, format); !st.ok()) return error(st);
  options.memory_bytes = free_memory();
  std::vector<uint8_t> bytes = bytes_from(stl);
  // The file's hash for the provenance; its bytes are freed once prepared.
  const std::string hash = vm::input_hash(bytes);
  if (options.family > 1) return mesh_family(bytes, options, format, applied, hash, progress);
  auto result = vm::run_mesh_job(bytes, options, progress_from(progress),
                                 [&] { std::vector<uint8_t>().swap(bytes); });
  if (!result.ok()) return error(result.status());
  Mesh mesh{std::move(result).value(), hash, std::move(applied), options, std::nullopt};
  const vm::MeshJobResult& res = mesh.result;
  val r = val::object();
  r.set("ok", true);
  if (!set_file(r, mesh, format, options)) return r;
  r.set("reportJson", vm::mesh_report_json(res, vm::kFaceJs));
  set_surface(r, res.output_surface, res.output_quality);
  if (!res.volume.tets.empty()) set_volume(r, res);
  r.set("handle", val(std::move(mesh)));
  return r;
}

/// The methods report of `mesh` (after a family: its first member, with the
/// family's table): {file: the HTML's bytes, fileName}. options: inputName
/// (the input file's name), images ([{title, alt, png: Uint8Array}], the
/// page's views; absent: rendered here without a GPU).
val methods_report(const Mesh& mesh, val opts) {
  vm::MethodsReportInput in;
  in.result = &mesh.result;
  in.options = &mesh.job;
  in.input_hash = mesh.input_hash;
  in.options_text = vm::options_provenance(mesh.options);
  in.version = vm::kVersion;
  if (mesh.family) in.family = &*mesh.family;
  const bool given = !opts.isUndefined() && !opts.isNull();
  if (given && opts["inputName"].isString()) in.input_name = opts["inputName"].as<std::string>();
  if (given && opts["images"].isArray()) {
    const val images = opts["images"];
    for (size_t i = 0; i < images["length"].as<size_t>(); ++i) {
      const val im = images[i];
      vm::ReportImage image;
      if (im["title"].isString()) image.title = im["title"].as<std::string>();
      if (im["alt"].isString()) image.alt = im["alt"].as<std::string>();
      const std::vector<uint8_t> png = bytes_from(im["png"]);
      image.png.assign(png.begin(), png.end());
      if (image.png.size() < 8 || image.png.compare(1, 3, "PNG") != 0)
        return error(vm::Status::Error(
            "report: image " + std::to_string(i + 1) + " ('" + image.title + "', " +
            std::to_string(png.size()) +
            " bytes) is not a PNG file: give PNG bytes (canvas.toBlob with 'image/png'), or no "
            "images for views rendered by the core"));
      in.images.push_back(std::move(image));
    }
  } else {
    in.images = vm::render_report_views(mesh.result);
  }
  const std::string html = vm::methods_report_html(in);
  val r = val::object();
  r.set("ok", true);
  r.set("file", copy_out(reinterpret_cast<const uint8_t*>(html.data()), html.size(), "Uint8Array"));
  r.set("fileName", std::string("vesselmesh-report.html"));
  return r;
}

/// `mesh` in another format, without meshing again.
/// options: format (required), mshVersion, mshBinary, vtkCompress, foamBinary,
/// outputUnits.
val export_mesh(const Mesh& mesh, val opts) {
  vm::MeshJobOptions options;
  if (!opts.isUndefined() && !opts.isNull()) {
    val keys = val::global("Object").call<val>("keys", opts);
    for (size_t i = 0; i < keys["length"].as<size_t>(); ++i) {
      const std::string key = keys[i].as<std::string>();
      if (key != "format" && key != "mshVersion" && key != "mshBinary" && key != "vtkCompress" &&
          key != "foamBinary" && key != "outputUnits")
        return error(vm::Status::BadOption("", "unknown export option '" + key +
                                                   "' (format, mshVersion, mshBinary, "
                                                   "vtkCompress, foamBinary, outputUnits)"));
    }
  }
  Applied applied;
  if (vm::Status st = apply_js_options(options, opts, vm::kCommandMesh, &applied); !st.ok())
    return error(st);
  // The mesh's solver preset (its unit and MSH version), then the export's
  // own options, which win.
  Applied all;
  for (const auto& given : mesh.options)
    if (given.first->id == "solver") all.push_back(given);
  all.insert(all.end(), applied.begin(), applied.end());
  options = vm::MeshJobOptions{};
  if (vm::Status st = vm::apply_options(options, all); !st.ok()) return error(st);
  if (!options.format)
    return error(
        vm::Status::BadOption("format", "is needed: msh, vtu, vtp, stl, mesh-complete or foam"));
  val r = val::object();
  r.set("ok", true);
  set_file(r, mesh, *options.format, options, applied);
  return r;
}

/// The group names the openings of `analysis` would get with these mesh
/// options (names, inlet; others ignored): {ok, names} or the error meshing
/// would give.
val opening_names(const Analysis& analysis, val opts) {
  auto options = mesh_options(opts);
  if (!options.ok()) return error(options.status());
  auto names = vm::opening_names(analysis.surface, options.value().opening_names,
                                 options.value().inlet);
  if (!names.ok()) return error(names.status());
  val r = val::object();
  r.set("ok", true);
  val list = val::array();
  for (const std::string& n : names.value()) list.call<void>("push", n);
  r.set("names", list);
  return r;
}

/// The cut across the vessel at the point of `analysis` nearest `point`
/// ([x, y, z], model coordinates):
/// {ok, point, normal (toward the side removed), radius, areaRemoved}.
val cut_at(const Analysis& analysis, val point) {
  if (!point.isArray() || point["length"].as<size_t>() != 3)
    return error(vm::Status::Error("cutAt needs a point [x, y, z]"));
  std::array<double, 3> p{};
  for (size_t k = 0; k < 3; ++k) {
    if (point[k].typeOf().as<std::string>() != "number" || !std::isfinite(point[k].as<double>()))
      return error(vm::Status::Error("cutAt needs a point [x, y, z] of 3 finite numbers"));
    p[k] = point[k].as<double>();
  }
  const vm::SurfaceMesh& mesh = analysis.surface.mesh;
  auto cut = vm::cut_across_vessel(mesh, vm::build_adjacency(mesh), p);
  if (!cut.ok()) return error(cut.status());
  val r = val::object();
  r.set("ok", true);
  r.set("point", copy_out(cut.value().plane.point.data(), 3, "Float64Array"));
  r.set("normal", copy_out(cut.value().plane.normal.data(), 3, "Float64Array"));
  r.set("radius", cut.value().radius);
  r.set("areaRemoved", cut.value().area_removed);
  return r;
}

/// The size field the mesh options would remesh `analysis` with
/// (size_preview.h): {ok, positions, triangles (its vertices and triangles,
/// as analyze() gave them), radius (R a vertex), size (h a vertex), unit}
/// or the error mesh() would give for these size options. The radius is
/// kept on `analysis` for the next call.
val size_field(Analysis& analysis, val opts) {
  auto options = mesh_options(opts);
  if (!options.ok()) return error(options.status());
  auto preview = vm::size_preview(analysis.surface, options.value(), analysis.radius);
  if (!preview.ok()) return error(preview.status());
  const vm::SurfaceMesh& m = analysis.surface.mesh;
  analysis.radius = preview.value().radius;
  val r = val::object();
  r.set("ok", true);
  std::vector<float> positions(m.points.begin(), m.points.end());
  r.set("positions", copy_out(positions.data(), positions.size(), "Float32Array"));
  r.set("triangles", copy_out(reinterpret_cast<const uint32_t*>(m.triangles.data()),
                              m.triangles.size(), "Uint32Array"));
  const std::vector<float> radius(preview.value().radius.begin(), preview.value().radius.end());
  const std::vector<float> size(preview.value().size.begin(), preview.value().size.end());
  r.set("radius", copy_out(radius.data(), radius.size(), "Float32Array"));
  r.set("size", copy_out(size.data(), size.size(), "Float32Array"));
  r.set("unit", std::string(vm::unit_symbol(analysis.surface.unit.unit)));
  return r;
}

/// The cumulative height fractions of the layers (N + 1 values, 0 to 1)
/// for these mesh options (layers, growth; others ignored).
val layer_fractions(val opts) {
  vm::MeshJobOptions options;
  if (vm::Status st = apply_js_options(options, opts, vm::kCommandMesh); !st.ok()) return error(st);
  const std::vector<double> f = vm::layer_fractions(options.viscous);
  val r = val::object();
  r.set("ok", true);
  r.set("fractions", copy_out(f.data(), f.size(), "Float64Array"));
  return r;
}

/// options: the JS API's makePhantom options.
val make_phantom(val opts) {
  vm::PhantomOptions o;
  if (vm::Status st = apply_js_options(o, opts, vm::kCommandPhantom); !st.ok()) return error(st);
  vm::PhantomTruth truth;
  auto m = vm::make_vessel_phantom(o, &truth);
  if (!m.ok()) return error(m.status());
  std::vector<uint8_t> stl = vm::write_stl_binary(m.value(), "vesselmesh phantom");
  val r = val::object();
  r.set("ok", true);
  r.set("stl", copy_out(stl.data(), stl.size(), "Uint8Array"));
  // A labelled kind also as VTK XML PolyData with its ModelFaceID.
  if (!truth.face_labels.empty()) {
    vm::VtkWriteOptions wo;
    wo.comment = "vesselmesh phantom";
    auto vtp = vm::write_surface_vtp(m.value(), truth.face_labels, wo);
    if (!vtp.ok()) return error(vtp.status());
    r.set("vtp", copy_out(reinterpret_cast<const uint8_t*>(vtp.value().data()), vtp.value().size(),
                          "Uint8Array"));
  }
  return r;
}

std::string option_table() { return vm::option_table_json(); }

std::string solver_presets() { return vm::solver_presets_json(); }

std::string version() { return vm::kVersion; }

/// Caps the threads of every later job at `limit` (the threaded module's
/// pool of Web Workers plus the calling thread) and returns the most a job
/// may use: min(limit, the cores the browser reports), or 1 in the
/// single-threaded module.
int set_thread_limit(int limit) {
  vm::set_thread_limit(limit);
  vm::set_thread_count(0);
  return vm::thread_count();
}

/// What a failed allocation does (std::set_new_handler): abort the module
/// as Emscripten's own out-of-memory does, "Aborted(OOM)". This build does
/// not catch C++ exceptions, so std::bad_alloc cannot become an error value
/// here (run_mesh_job's catch is the native build's); without the handler
/// the module aborts with no reason given. The JS API turns the abort into
/// an out-of-memory failure (vesselmesh.js stopped()) and the worker client
/// replaces the module.
void abort_out_of_memory() { EM_ASM(abort('OOM')); }

}  // namespace

EMSCRIPTEN_BINDINGS(vesselmesh) {
  std::set_new_handler(abort_out_of_memory);
  // Handles: made only by analyze() and mesh(), owned by JS (delete()).
  emscripten::class_<Analysis>("Analysis");
  emscripten::class_<Mesh>("Mesh");
  emscripten::function("analyze", &analyze);
  emscripten::function("mesh", &mesh);
  emscripten::function("makePhantom", &make_phantom);
  emscripten::function("version", &version);
  emscripten::function("setThreadLimit", &set_thread_limit);
  emscripten::function("optionTable", &option_table);
  emscripten::function("solverPresets", &solver_presets);
  emscripten::function("exportMesh", &export_mesh);
  emscripten::function("methodsReport", &methods_report);
  emscripten::function("openingNames", &opening_names);
  emscripten::function("cutAt", &cut_at);
  emscripten::function("layerFractions", &layer_fractions);
  emscripten::function("sizeField", &size_field);
}
