// mesh-complete layout: the VTU of the volume, then the exterior faces and
// each tag's faces as VTPs sharing the volume's point numbering
// (SimVascular's svMeshSim/TetGen export, which svFSI reads).
#include "core/io/mesh_complete_writer.h"

#include <set>

#include "core/io/vtk_writer.h"
#include "core/mesh/face_elements.h"
#include "core/util/json_writer.h"

namespace vm {
namespace {

bool is_file_name(const std::string& s) {
  if (s.empty()) return false;
  for (char c : s)
    if (!((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
          c == '-'))
      return false;
  return true;
}

std::string name_or(const std::vector<std::string>& names, size_t tag, const char* prefix) {
  if (tag < names.size() && !names[tag].empty()) return names[tag];
  return prefix + std::to_string(tag + 1);
}

/// Per surface tag: its faces (indices into triangles then quads).
struct TagFaces {
  std::vector<int32_t> faces;
  size_t triangles = 0, quads = 0, exterior = 0;
};

}  // namespace

Result<std::vector<OutputFile>> mesh_complete_files(const VolumeMesh& mesh,
                                                    const std::vector<std::string>& surface_names,
                                                    const std::vector<std::string>& region_names,
                                                    const std::string& comment) {
  using R = Result<std::vector<OutputFile>>;
  const size_t ntri = mesh.num_triangles(), nf = ntri + mesh.num_quads();
  if (mesh.triangle_tag.size() != ntri || mesh.quad_tag.size() != mesh.num_quads())
    return R::Error("mesh-complete: surface tags are not one per triangle and quad");
  VtkWriteOptions vtk;
  vtk.comment = comment;
  Result<std::string> vtu = write_vtu(mesh, vtk);
  if (!vtu.ok()) return vtu.status();

  // Phase 1: faces by tag, and the elements beside each.
  const FaceElements fe = face_elements(mesh);
  auto tag_of = [&](size_t f) { return f < ntri ? mesh.triangle_tag[f] : mesh.quad_tag[f - ntri]; };
  std::vector<TagFaces> tags;
  for (size_t f = 0; f < nf; ++f) {
    const int32_t tag = tag_of(f);
    const char* what = f < ntri ? "triangle " : "quad ";
    const size_t index = f < ntri ? f : f - ntri;
    if (tag < 0 || tag == INT32_MAX)
      return R::Error("mesh-complete: surface " + std::string(what) + std::to_string(index) +
                      " has a tag out of range");
    if (fe.uses[f] == 0 || fe.uses[f] > 2)
      return R::Error("mesh-complete: surface " + std::string(what) + std::to_string(index) + " (" +
                      name_or(surface_names, size_t(tag), "face_") + ") is " +
                      (fe.uses[f] == 0 ? "no element's face" : "shared by more than two elements"));
    if (size_t(tag) >= tags.size()) tags.resize(size_t(tag) + 1);
    TagFaces& t = tags[size_t(tag)];
    t.faces.push_back(int32_t(f));
    ++(f < ntri ? t.triangles : t.quads);
    if (fe.uses[f] == 1) ++t.exterior;
  }
  std::set<std::string> names;
  for (size_t tag = 0; tag < tags.size(); ++tag) {
    if (tags[tag].faces.empty()) continue;
    const std::string name = name_or(surface_names, tag, "face_");
    if (!is_file_name(name))
      return R::Error("mesh-complete: surface name \"" + name +
                      "\" is not a file name (letters, digits, '_' and '-' only)");
    if (!names.insert(name).second)
      return R::Error("mesh-complete: two surfaces are named \"" + name + "\"");
  }

  // Phase 2: the files.
  std::vector<int32_t> node_ids(mesh.num_vertices());
  for (size_t v = 0; v < node_ids.size(); ++v) node_ids[v] = int32_t(v + 1);
  // A VTP of the faces `faces` (ascending, so triangles come first).
  auto surface_vtp = [&](const std::vector<int32_t>& faces) {
    VtpSurface s;
    s.points = mesh.points;
    s.global_node_ids = node_ids;
    for (int32_t f : faces) {
      if (size_t(f) < ntri)
        s.triangles.insert(s.triangles.end(), &mesh.triangles[3 * size_t(f)],
                           &mesh.triangles[3 * size_t(f)] + 3);
      else
        s.quads.insert(s.quads.end(), &mesh.quads[4 * (size_t(f) - ntri)],
                       &mesh.quads[4 * (size_t(f) - ntri)] + 4);
      s.face_ids.push_back(tag_of(size_t(f)) + 1);
      s.global_element_ids.push_back(fe.element[size_t(f)] + 1);
    }
    return write_vtp(s, vtk);
  };
  std::vector<OutputFile> files;
  files.push_back({"mesh-complete.mesh.vtu", std::move(vtu).value()});
  std::vector<int32_t> exterior;
  for (size_t f = 0; f < nf; ++f)
    if (fe.uses[f] == 1) exterior.push_back(int32_t(f));
  Result<std::string> vtp = surface_vtp(exterior);
  if (!vtp.ok()) return vtp.status();
  files.push_back({"mesh-complete.exterior.vtp", std::move(vtp).value()});

  JsonWriter json;
  json.begin_object().key("faces").begin_array();
  for (size_t tag = 0; tag < tags.size(); ++tag) {
    const TagFaces& t = tags[tag];
    if (t.faces.empty()) continue;
    const std::string name = name_or(surface_names, tag, "face_");
    const std::string path = "mesh-surfaces/" + name + ".vtp";
    vtp = surface_vtp(t.faces);
    if (!vtp.ok()) return vtp.status();
    files.push_back({path, std::move(vtp).value()});
    json.begin_object().key("id").value(int(tag) + 1).key("name").value(name);
    json.key("file").value(path).key("triangles").value(t.triangles).key("quads").value(t.quads);
    json.key("exterior").value(t.exterior == t.faces.size()).end_object();
  }
  json.end_array().key("regions").begin_array();
  std::vector<size_t> tets, prisms;
  auto count = [](std::vector<size_t>& n, const std::vector<int32_t>& region, size_t elements) {
    for (size_t e = 0; e < elements; ++e) {
      const size_t r = region.empty() ? 0 : size_t(region[e]);  // >= 0: checked by write_vtu
      if (r >= n.size()) n.resize(r + 1, 0);
      ++n[r];
    }
  };
  count(tets, mesh.tet_region, mesh.num_tets());
  count(prisms, mesh.prism_region, mesh.num_prisms());
  tets.resize(std::max(tets.size(), prisms.size()), 0);
  prisms.resize(tets.size(), 0);
  for (size_t r = 0; r < tets.size(); ++r) {
    if (tets[r] + prisms[r] == 0) continue;
    json.begin_object().key("id").value(int(r) + 1);
    json.key("name").value(name_or(region_names, r, "region_"));
    json.key("elements").value(tets[r] + prisms[r]).key("tetrahedra").value(tets[r]);
    json.key("prisms").value(prisms[r]).end_object();
  }
  json.end_array().key("provenance").value(comment).end_object();
  files.push_back({"mesh-complete.names.json", json.str() + "\n"});
  return files;
}

}  // namespace vm
