#include "core/pipeline/write_outputs.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>

#include "core/io/stl.h"
#include "core/pipeline/option_table.h"
#include "core/pipeline/option_values.h"
#include "core/pipeline/validate_options.h"
#include "tests/support/meshed_tube.h"
#include "tests/support/test_meshes.h"
#include "tests/support/vtk_xml_reader.h"

namespace vm {
namespace {

/// A meshed open tube (uniform size, 2 layers), in mm, once; and the same
/// surface only.
const MeshJobResult& tube(bool volume) {
  auto make = [](bool with_volume) {
    MeshJobOptions o;
    EXPECT_TRUE(set_option_text(o, "size", "0.4").ok());
    EXPECT_TRUE(set_option_text(o, "layers", "2").ok());
    EXPECT_TRUE(set_option_text(o, "units", "mm").ok());
    o.volume = with_volume;
    return testing::meshed_tube(o);
  };
  static const MeshJobResult with = make(true), without = make(false);
  return volume ? with : without;
}

size_t total(const std::vector<OutputGroup>& groups, int dim) {
  size_t n = 0;
  for (const OutputGroup& g : groups) n += g.dim == dim ? g.elements : 0;
  return n;
}

TEST(WriteOutputs, FormatsByNameAndExtension) {
  EXPECT_EQ(format_for_path("a/b/Mesh.VTU").value(), OutputFormat::kVtu);
  EXPECT_EQ(format_for_path("x.zip").value(), OutputFormat::kMeshComplete);
  EXPECT_EQ(format_for_path("x.msh").value(), OutputFormat::kMsh);
  EXPECT_EQ(format_for_path("case/Aorta.FOAM").value(), OutputFormat::kFoam);
  auto bad = format_for_path("dir.v2/mesh");
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.message().find(".msh (Gmsh), .vtu"), std::string::npos) << bad.message();
  EXPECT_NE(bad.message().find(".foam (OpenFOAM case)"), std::string::npos) << bad.message();
  EXPECT_NE(phrase_options(bad.message(), kFaceCli).find("--format"), std::string::npos);
  for (auto f : {OutputFormat::kMsh, OutputFormat::kVtu, OutputFormat::kVtp, OutputFormat::kStl,
                 OutputFormat::kMeshComplete, OutputFormat::kFoam})
    EXPECT_EQ(parse_format(format_name(f)).value(), f);
}

TEST(WriteOutputs, GroupsCountTheElementsOfEachTag) {
  const MeshJobResult& r = tube(true);
  const auto groups = output_groups(r);
  ASSERT_EQ(groups.size(), 4u);  // wall, inlet, outlet_1, lumen
  EXPECT_EQ(groups[0].name, "wall");
  EXPECT_EQ(groups[3].name, "lumen");
  EXPECT_EQ(total(groups, 2), r.volume.num_triangles());
  EXPECT_EQ(total(groups, 3), r.volume.num_tets());
  EXPECT_EQ(output_groups(tube(false)).size(), 1u);
}

TEST(WriteOutputs, MshHasTheProvenanceAndTheUnitAsked) {
  const MeshJobResult& r = tube(true);
  WriteOptions o;
  o.provenance = "vesselmesh test; input xxh128:0; options: size=0.4";
  o.units = LengthUnit::kM;
  auto files = write_outputs(r, OutputFormat::kMsh, o);
  ASSERT_TRUE(files.ok()) << files.message();
  ASSERT_EQ(files.value().size(), 1u);
  const std::string& msh = files.value()[0].bytes;
  EXPECT_EQ(files.value()[0].path, "mesh.msh");
  EXPECT_NE(msh.find("$Comments\n" + o.provenance + "\n$EndComments\n"), std::string::npos);
  // In metres: the model (mm) is 1000 times smaller.
  const MshModel mm = msh_model(r), m = msh_model(r, 1e-3);
  ASSERT_EQ(mm.points.size(), m.points.size());
  for (size_t i = 0; i < mm.points.size(); i += 97)
    EXPECT_DOUBLE_EQ(m.points[i], 1e-3 * mm.points[i]);
  double max_coordinate = 0;
  for (double x : mm.points) max_coordinate = std::max(max_coordinate, std::abs(x));
  EXPECT_NEAR(max_coordinate, 4.0, 1e-9);
}

TEST(WriteOutputs, VtkFilesCarryIdsAndProvenance) {
  const MeshJobResult& r = tube(true);
  WriteOptions o;
  o.provenance = "made by a test";
  auto vtu = write_outputs(r, OutputFormat::kVtu, o);
  ASSERT_TRUE(vtu.ok()) << vtu.message();
  auto grid = testing::read_vtk_xml(vtu.value()[0].bytes);
  ASSERT_TRUE(grid.ok()) << grid.message();
  EXPECT_EQ(grid.value().comment, " made by a test ");
  EXPECT_EQ(grid.value().piece_count("NumberOfCells"), r.volume.num_tets());
  auto vtp = write_outputs(r, OutputFormat::kVtp, o);
  ASSERT_TRUE(vtp.ok()) << vtp.message();
  auto poly = testing::read_vtk_xml(vtp.value()[0].bytes);
  ASSERT_TRUE(poly.ok()) << poly.message();
  const auto ids = poly.value().values<int32_t>("CellData", "ModelFaceID");
  ASSERT_EQ(ids.size(), r.volume.num_triangles());
  for (size_t t = 0; t < ids.size(); ++t) ASSERT_EQ(ids[t], r.volume.triangle_tag[t] + 1);
  const auto elements = poly.value().values<int32_t>("CellData", "GlobalElementID");
  ASSERT_EQ(elements.size(), ids.size());
  for (int32_t e : elements) ASSERT_GE(e, 1);
}

// {vtk_compress}: the VTU and VTP files' arrays in zlib blocks, inflated by
// the test reader (zlib's uncompress, the block header parsed here) to the
// raw files' bytes: points, connectivity, offsets, types, ids.
TEST(WriteOutputs, VtkCompressGivesTheRawArraysInZlibBlocks) {
  MeshJobOptions job;
  ASSERT_TRUE(set_option_text(job, "vtk_compress", "").ok());
  const WriteOptions o = write_options(job);
  EXPECT_TRUE(o.vtk_compress);
  for (OutputFormat f : {OutputFormat::kVtu, OutputFormat::kVtp}) {
    SCOPED_TRACE(format_name(f));
    auto raw = write_outputs(tube(true), f), packed = write_outputs(tube(true), f, o);
    ASSERT_TRUE(raw.ok() && packed.ok()) << packed.message();
    auto a = testing::read_vtk_xml(raw.value()[0].bytes);
    auto b = testing::read_vtk_xml(packed.value()[0].bytes);
    ASSERT_TRUE(a.ok() && b.ok()) << b.message();
    EXPECT_EQ(a.value().file_attributes.count("compressor"), 0u);
    EXPECT_EQ(b.value().file_attributes["compressor"], "vtkZLibDataCompressor");
    EXPECT_EQ(b.value().file_attributes["header_type"], "UInt64");
    EXPECT_EQ(b.value().piece, a.value().piece);
    ASSERT_EQ(b.value().arrays.size(), a.value().arrays.size());
    for (size_t i = 0; i < a.value().arrays.size(); ++i) {
      const testing::VtkArray &x = a.value().arrays[i], &y = b.value().arrays[i];
      EXPECT_EQ(y.section + "/" + y.name, x.section + "/" + x.name);
      EXPECT_EQ(y.bytes, x.bytes) << x.section << "/" << x.name;
      EXPECT_EQ(y.blocks, (x.bytes.size() + 32767) / 32768);
    }
    EXPECT_EQ(b.value().values<uint8_t>("Cells", "types").size(),
              f == OutputFormat::kVtu ? tube(true).volume.num_tets() : 0u);
    EXPECT_LT(packed.value()[0].bytes.size(), raw.value()[0].bytes.size() / 2);
  }
  // The mesh-complete folder stays raw (svFSI's input).
  auto folder = write_outputs(tube(true), OutputFormat::kMeshComplete, o);
  ASSERT_TRUE(folder.ok()) << folder.message();
  for (const OutputFile& file : folder.value())
    EXPECT_EQ(file.bytes.find("compressor="), std::string::npos) << file.path;
}

TEST(WriteOutputs, MeshCompleteAndTheWallAlone) {
  auto folder = write_outputs(tube(true), OutputFormat::kMeshComplete);
  ASSERT_TRUE(folder.ok()) << folder.message();
  std::vector<std::string> paths;
  for (const OutputFile& f : folder.value()) paths.push_back(f.path);
  for (const char* p :
       {"mesh-complete.mesh.vtu", "mesh-complete.exterior.vtp", "mesh-surfaces/wall.vtp",
        "mesh-surfaces/inlet.vtp", "mesh-surfaces/outlet_1.vtp", "mesh-complete.names.json"})
    EXPECT_NE(std::find(paths.begin(), paths.end(), p), paths.end()) << p;
  auto stl = write_outputs(tube(true), OutputFormat::kStl);
  ASSERT_TRUE(stl.ok());
  const std::string& bytes = stl.value()[0].bytes;
  auto soup = read_stl(std::span(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size()));
  ASSERT_TRUE(soup.ok()) << soup.message();
  EXPECT_EQ(soup.value().num_triangles(), tube(true).output_surface.num_triangles());
}

TEST(WriteOutputs, SvFsiWithAVesselWallGetsAFluidAndASolidFolder) {
  MeshJobOptions o;
  ASSERT_TRUE(set_option_text(o, "size", "0.4").ok());
  ASSERT_TRUE(set_option_text(o, "wall_thickness", "0.1").ok());
  ASSERT_TRUE(set_option_text(o, "wall_layers", "2").ok());
  o.preset.solver = "svfsi";
  auto r = run_mesh_job(write_stl_binary(testing::open_tube(24, 8, 1.0, 4.0)), o);
  ASSERT_TRUE(r.ok()) << r.message();
  auto folder = write_outputs(r.value(), OutputFormat::kMeshComplete);
  ASSERT_TRUE(folder.ok()) << folder.message();
  std::map<std::string, std::string> files;
  for (const OutputFile& f : folder.value()) files[f.path] = f.bytes;
  for (const char* p : {"fluid/mesh-complete.mesh.vtu", "fluid/mesh-surfaces/wall.vtp",
                        "fluid/mesh-surfaces/inlet.vtp", "solid/mesh-complete.mesh.vtu",
                        "solid/mesh-surfaces/wall.vtp", "solid/mesh-surfaces/outer_wall.vtp",
                        "solid/mesh-surfaces/wall_inlet.vtp"})
    EXPECT_TRUE(files.count(p)) << p;
  EXPECT_FALSE(files.count("fluid/mesh-surfaces/outer_wall.vtp"));
  EXPECT_FALSE(files.count("solid/mesh-surfaces/inlet.vtp"));
  // The interface: as many triangles on each side (the files' Polys count).
  const auto polys = [](const std::string& vtp) {
    const size_t at = vtp.find("NumberOfPolys=\"");
    return at == std::string::npos ? std::string() : vtp.substr(at, vtp.find(' ', at) - at);
  };
  EXPECT_EQ(polys(files["fluid/mesh-surfaces/wall.vtp"]),
            polys(files["solid/mesh-surfaces/wall.vtp"]));
  EXPECT_FALSE(polys(files["fluid/mesh-surfaces/wall.vtp"]).empty());
}

TEST(WriteOutputs, FoamCaseInMetres) {
  WriteOptions o;
  o.units = LengthUnit::kM;
  o.provenance = "vesselmesh test";
  auto files = write_outputs(tube(true), OutputFormat::kFoam, o);
  ASSERT_TRUE(files.ok()) << files.message();
  std::map<std::string, std::string> by_path;
  for (const OutputFile& f : files.value()) by_path[f.path] = f.bytes;
  for (const char* p :
       {"constant/polyMesh/points", "constant/polyMesh/faces", "constant/polyMesh/owner",
        "constant/polyMesh/neighbour", "constant/polyMesh/boundary", "constant/polyMesh/cellZones",
        "system/controlDict", "case.foam"})
    EXPECT_EQ(by_path.count(p), 1u) << p;
  EXPECT_EQ(by_path.count("constant/polyMesh/faceZones"), 0u);  // no interface
  const MeshJobResult& r = tube(true);
  const std::string note = "nPoints:" + std::to_string(r.volume.num_vertices()) +
                           "  nCells:" + std::to_string(r.volume.num_tets());
  EXPECT_NE(by_path["constant/polyMesh/owner"].find(note), std::string::npos);
  const std::string& boundary = by_path["constant/polyMesh/boundary"];
  for (const char* patch : {"    wall\n    {\n        type            wall;",
                            "    inlet\n    {\n        type            patch;",
                            "    outlet_1\n    {\n        type            patch;"})
    EXPECT_NE(boundary.find(patch), std::string::npos) << patch;
  EXPECT_NE(by_path["constant/polyMesh/cellZones"].find("\nlumen\n"), std::string::npos);
  // In metres: the tube (4 mm long) ends at z = 0.004.
  const std::string& points = by_path["constant/polyMesh/points"];
  double max_z = 0;
  for (size_t at = points.find("\n(\n") + 3; points[at] == '('; at = points.find('\n', at) + 1) {
    double x, y, z;
    ASSERT_EQ(std::sscanf(points.c_str() + at, "(%lf %lf %lf)", &x, &y, &z), 3);
    max_z = std::max(max_z, std::abs(z));
  }
  EXPECT_NEAR(max_z, 0.004, 1e-12);
}

// {foam_binary}: the same case's files, the mesh's lists in binary (their
// decoding is tested in tests/io/foam_writer_test.cpp).
TEST(WriteOutputs, FoamBinaryWritesTheListsInBinary) {
  MeshJobOptions job;
  ASSERT_TRUE(set_option_text(job, "foam_binary", "").ok());
  auto text = write_outputs(tube(true), OutputFormat::kFoam);
  auto binary = write_outputs(tube(true), OutputFormat::kFoam, write_options(job));
  ASSERT_TRUE(text.ok() && binary.ok()) << binary.message();
  ASSERT_EQ(binary.value().size(), text.value().size());
  for (size_t i = 0; i < text.value().size(); ++i) {
    const OutputFile &a = text.value()[i], &b = binary.value()[i];
    EXPECT_EQ(b.path, a.path);
    const bool list = b.path.starts_with("constant/polyMesh/") && !b.path.ends_with("boundary") &&
                      !b.path.ends_with("Zones");
    EXPECT_EQ(b.bytes.find("format      binary;") != std::string::npos, list) << b.path;
    if (b.path.ends_with("points")) {
      EXPECT_LT(b.bytes.size(), a.bytes.size() / 2);  // doubles in 8 bytes, not ~20 characters
    }
  }
}

TEST(WriteOutputs, VolumeFormatsNeedAVolume) {
  for (auto f : {OutputFormat::kVtu, OutputFormat::kMeshComplete, OutputFormat::kFoam}) {
    auto r = write_outputs(tube(false), f);
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.status().option(), "format");
    EXPECT_NE(r.message().find("surface only ({surface_only})"), std::string::npos) << r.message();
    MeshJobOptions o;
    o.volume = false;
    EXPECT_FALSE(validate_options(o, f).ok());
    o.volume = true;
    EXPECT_TRUE(validate_options(o, f).ok());
  }
  for (auto f : {OutputFormat::kMsh, OutputFormat::kVtp, OutputFormat::kStl})
    EXPECT_TRUE(write_outputs(tube(false), f).ok());
}

}  // namespace
}  // namespace vm
