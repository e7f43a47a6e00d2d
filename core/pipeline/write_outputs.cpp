// The files of a meshed result (write_outputs.h).
#include "core/pipeline/write_outputs.h"

#include <algorithm>
#include <cctype>
#include <numeric>

#include "core/io/foam_writer.h"
#include "core/io/mesh_complete_writer.h"
#include "core/io/stl.h"
#include "core/io/vtk_writer.h"
#include "core/mesh/face_elements.h"
#include "core/mesh/region_submesh.h"
#include "core/pipeline/option_values.h"

namespace vm {
namespace {

constexpr std::pair<OutputFormat, std::string_view> kFormats[] = {
    {OutputFormat::kMsh, "msh"},
    {OutputFormat::kVtu, "vtu"},
    {OutputFormat::kVtp, "vtp"},
    {OutputFormat::kStl, "stl"},
    {OutputFormat::kMeshComplete, "mesh-complete"},
    {OutputFormat::kFoam, "foam"}};

bool surface_only(const MeshJobResult& r) {
  return r.volume.tets.empty() && r.volume.prisms.empty();
}

/// Points scaled by `scale` (a copy only when it is not 1).
std::vector<double> scaled(const std::vector<double>& points, double scale) {
  std::vector<double> out(points);
  if (scale != 1)
    for (double& x : out) x *= scale;
  return out;
}

/// The result as a volume mesh with names, its tags renumbered to the
/// physical tags (physical_tags) minus one: every writer numbers a tag t as
/// t + 1, so that numbers are the same in every file. `surfaces[t]` and
/// `regions[r]` name the renumbered tags ("" = none: the regions' first k
/// entries, numbers taken by the surfaces). Surface only: the wall as the
/// boundary of nothing, `wall`.
struct Named {
  VolumeMesh mesh;
  std::vector<std::string> surfaces, regions;
};

Named named_mesh(const MeshJobResult& r, double scale);

/// svFSI's layout with a vessel wall: the fluid (every region but
/// `vessel_wall`) and the solid (`vessel_wall`) each a mesh-complete
/// folder, `fluid/` and `solid/`, whose `mesh-surfaces/wall.vtp` are the same
/// interface triangles on the same coordinates (each oriented out of its
/// own part). Without a vessel wall, one folder as usual.
Result<std::vector<OutputFile>> fsi_mesh_complete(const Named& n, const std::string& comment) {
  std::vector<int32_t> fluid, solid;
  for (size_t t = 0; t < n.regions.size(); ++t)
    if (!n.regions[t].empty())
      (n.regions[t] == "vessel_wall" ? solid : fluid).push_back(int32_t(t));
  if (solid.empty()) return mesh_complete_files(n.mesh, n.surfaces, n.regions, comment);
  std::vector<OutputFile> files;
  for (const auto& [folder, regions] : {std::pair{"fluid/", fluid}, std::pair{"solid/", solid}}) {
    auto part =
        mesh_complete_files(region_submesh(n.mesh, regions), n.surfaces, n.regions, comment);
    if (!part.ok()) return part.status();
    for (OutputFile& f : part.value()) files.push_back({folder + f.path, std::move(f.bytes)});
  }
  return files;
}

Named named_mesh(const MeshJobResult& r, double scale) {
  Named n;
  if (surface_only(r)) {
    n.mesh.points = scaled(r.output_surface.points, scale);
    n.mesh.triangles = r.output_surface.triangles;
    n.mesh.triangle_tag.assign(r.output_surface.num_triangles(), 0);
    n.surfaces = {"wall"};
    return n;
  }
  n.mesh = r.volume;
  if (scale != 1)
    for (double& x : n.mesh.points) x *= scale;
  const PhysicalTags tags = physical_tags(r.surface_names, r.region_names);
  auto renumber = [](std::vector<int32_t>& values, const std::vector<int>& number,
                     std::vector<std::string>& names, const std::vector<std::string>& from) {
    for (int32_t& v : values)
      if (v >= 0 && size_t(v) < number.size() && number[size_t(v)] > 0) v = number[size_t(v)] - 1;
    for (size_t t = 0; t < number.size(); ++t) {
      if (number[t] <= 0) continue;
      if (names.size() < size_t(number[t])) names.resize(size_t(number[t]));
      names[size_t(number[t]) - 1] = from[t];
    }
  };
  renumber(n.mesh.triangle_tag, tags.surface, n.surfaces, r.surface_names);
  renumber(n.mesh.quad_tag, tags.surface, n.surfaces, r.surface_names);
  renumber(n.mesh.tet_region, tags.region, n.regions, r.region_names);
  renumber(n.mesh.prism_region, tags.region, n.regions, r.region_names);
  return n;
}

}  // namespace

WriteOptions write_options(const MeshJobOptions& options) {
  WriteOptions wo;
  wo.msh_version = options.msh_version;
  wo.msh_binary = options.msh_binary;
  wo.vtk_compress = options.vtk_compress;
  wo.foam_binary = options.foam_binary;
  wo.units = options.output_units;
  return wo;
}

Result<MshEncoding> msh_encoding(MshVersion version, bool binary) {
  if (!binary) return MshEncoding::kAscii;
  if (version != MshVersion::k41)
    return Status::BadOption("msh_binary",
                             "writes MSH 4.1 only, and the MSH version is 2.2 (asked, or the "
                             "openfoam preset's: gmshToFoam reads text): give {msh_version} 4.1, "
                             "or drop {msh_binary}");
  return MshEncoding::kBinary;
}

bool volume_format(OutputFormat f) {
  return f == OutputFormat::kVtu || f == OutputFormat::kMeshComplete || f == OutputFormat::kFoam;
}

std::string_view format_name(OutputFormat format) {
  for (const auto& [f, name] : kFormats)
    if (f == format) return name;
  return "";
}

Result<OutputFormat> format_for_path(std::string_view path) {
  const size_t dot = path.rfind('.');
  const size_t slash = path.find_last_of("/\\");
  std::string ext;
  if (dot != std::string_view::npos && (slash == std::string_view::npos || dot > slash))
    for (char c : path.substr(dot + 1)) ext += char(std::tolower(static_cast<unsigned char>(c)));
  if (ext == "zip") return OutputFormat::kMeshComplete;
  if (ext == "foam") return OutputFormat::kFoam;
  if (ext == "msh" || ext == "vtu" || ext == "vtp" || ext == "stl") return parse_format(ext);
  return Result<OutputFormat>::Error(
      "cannot tell the output format from '" + std::string(path) +
      "': name it .msh (Gmsh), .vtu (VTK volume), .vtp (VTK boundary faces), .stl (the wall) or "
      ".zip (SimVascular mesh-complete), .foam (OpenFOAM case), or say {format}");
}

PhysicalTags physical_tags(const std::vector<std::string>& surface_names,
                           const std::vector<std::string>& region_names) {
  PhysicalTags tags;
  int next = 0;
  for (const std::string& name : surface_names) tags.surface.push_back(name.empty() ? 0 : ++next);
  for (const std::string& name : region_names) tags.region.push_back(name.empty() ? 0 : ++next);
  return tags;
}

std::vector<OutputGroup> output_groups(const MeshJobResult& r) {
  std::vector<OutputGroup> groups;
  if (surface_only(r)) {
    groups.push_back({2, 1, "wall", r.output_surface.num_triangles()});
    return groups;
  }
  const VolumeMesh& m = r.volume;
  const PhysicalTags tags = physical_tags(r.surface_names, r.region_names);
  auto count = [](const std::vector<int32_t>& values, size_t tag) {
    return size_t(std::count(values.begin(), values.end(), int32_t(tag)));
  };
  for (size_t tag = 0; tag < r.surface_names.size(); ++tag)
    if (!r.surface_names[tag].empty())
      groups.push_back({2, tags.surface[tag], r.surface_names[tag],
                        count(m.triangle_tag, tag) + count(m.quad_tag, tag)});
  for (size_t region = 0; region < r.region_names.size(); ++region)
    if (!r.region_names[region].empty())
      groups.push_back({3, tags.region[region], r.region_names[region],
                        count(m.tet_region, region) + count(m.prism_region, region)});
  return groups;
}

MshModel msh_model(const MeshJobResult& r, double scale) {
  MshModel model;
  const Named n = named_mesh(r, scale);
  model.points = std::move(n.mesh.points);
  // One entity per (group, element type); entity tags count up per dimension.
  int entity[4] = {0, 0, 0, 0};
  auto add_block = [&](MshElementType type, int physical, const std::vector<int32_t>& nodes,
                       const std::vector<int32_t>& tags, int32_t tag) {
    const size_t k = size_t(nodes_per_element(type));
    MshBlock b{type, ++entity[element_dimension(type)], physical, {}};
    for (size_t e = 0; e < tags.size(); ++e)
      if (tags[e] == tag) b.nodes.insert(b.nodes.end(), &nodes[k * e], &nodes[k * e] + k);
    if (b.nodes.empty())
      --entity[element_dimension(type)];
    else
      model.blocks.push_back(std::move(b));
  };
  const VolumeMesh& m = n.mesh;
  for (size_t tag = 0; tag < n.surfaces.size(); ++tag) {
    if (n.surfaces[tag].empty()) continue;
    model.physicals.push_back({2, int(tag) + 1, n.surfaces[tag]});
    add_block(MshElementType::kTriangle, int(tag) + 1, m.triangles, m.triangle_tag, int32_t(tag));
    add_block(MshElementType::kQuad, int(tag) + 1, m.quads, m.quad_tag, int32_t(tag));
  }
  for (size_t region = 0; region < n.regions.size(); ++region) {
    if (n.regions[region].empty()) continue;
    model.physicals.push_back({3, int(region) + 1, n.regions[region]});
    add_block(MshElementType::kTetrahedron, int(region) + 1, m.tets, m.tet_region, int32_t(region));
    add_block(MshElementType::kPrism, int(region) + 1, m.prisms, m.prism_region, int32_t(region));
  }
  return model;
}

Result<std::vector<OutputFile>> write_outputs(const MeshJobResult& r, OutputFormat format,
                                              const WriteOptions& options) {
  const LengthUnit from = r.surface.unit.unit;
  const double scale = options.units == LengthUnit::kGuess
                           ? 1
                           : metres_per_unit(from) / metres_per_unit(options.units);
  if (surface_only(r) && volume_format(format))
    return Status::BadOption("format", "cannot be " + std::string(format_name(format)) +
                                           ": it holds a volume mesh, and this one is surface "
                                           "only ({surface_only}); use msh, vtp or stl");
  VtkWriteOptions vtk;
  vtk.zlib = options.vtk_compress;
  vtk.comment = options.provenance;
  std::vector<OutputFile> files;
  switch (format) {
    case OutputFormat::kMsh: {
      MshModel model = msh_model(r, scale);
      model.comment = options.provenance;
      auto encoding = msh_encoding(options.msh_version, options.msh_binary);
      if (!encoding.ok()) return encoding.status();
      auto text = write_msh(model, options.msh_version, encoding.value());
      if (!text.ok()) return text.status();
      files.push_back({"mesh.msh", std::move(text).value()});
      break;
    }
    case OutputFormat::kVtu: {
      const Named n = named_mesh(r, scale);
      auto text = write_vtu(n.mesh, vtk);
      if (!text.ok()) return text.status();
      files.push_back({"mesh.vtu", std::move(text).value()});
      break;
    }
    case OutputFormat::kVtp: {
      const Named n = named_mesh(r, scale);
      VtpSurface s;
      s.points = n.mesh.points;
      s.triangles = n.mesh.triangles;
      s.quads = n.mesh.quads;
      for (int32_t tag : n.mesh.triangle_tag) s.face_ids.push_back(tag + 1);
      for (int32_t tag : n.mesh.quad_tag) s.face_ids.push_back(tag + 1);
      // With a volume, the ids that tie each face to the VTU of the same
      // mesh: its nodes' numbers and the element it bounds.
      std::vector<int32_t> node_ids;
      if (!surface_only(r)) {
        node_ids.resize(n.mesh.num_vertices());
        std::iota(node_ids.begin(), node_ids.end(), 1);
        s.global_node_ids = node_ids;
        for (int32_t e : face_elements(n.mesh).element) s.global_element_ids.push_back(e + 1);
      }
      auto text = write_vtp(s, vtk);
      if (!text.ok()) return text.status();
      files.push_back({"mesh.vtp", std::move(text).value()});
      break;
    }
    case OutputFormat::kStl: {
      SurfaceMesh wall = r.output_surface;
      if (scale != 1)
        for (double& x : wall.points) x *= scale;
      const std::vector<uint8_t> bytes = write_stl_binary(wall, options.provenance);
      files.push_back({"mesh.stl", std::string(bytes.begin(), bytes.end())});
      break;
    }
    case OutputFormat::kMeshComplete: {
      const Named n = named_mesh(r, scale);
      auto folder = r.preset.solver == "svfsi"
                        ? fsi_mesh_complete(n, options.provenance)
                        : mesh_complete_files(n.mesh, n.surfaces, n.regions, options.provenance);
      if (!folder.ok()) return folder.status();
      files = std::move(folder).value();
      break;
    }
    case OutputFormat::kFoam: {
      const Named n = named_mesh(r, scale);
      auto folder = foam_case_files(n.mesh, n.surfaces, n.regions, options.provenance,
                                    options.foam_binary ? FoamFormat::kBinary : FoamFormat::kAscii);
      if (!folder.ok()) return folder.status();
      files = std::move(folder).value();
      break;
    }
  }
  return files;
}

}  // namespace vm
