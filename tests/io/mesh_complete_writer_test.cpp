#include "core/io/mesh_complete_writer.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "core/mesh/face_elements.h"
#include "tests/support/small_volumes.h"
#include "tests/support/vtk_xml_reader.h"

namespace vm {
namespace {

using testing::read_vtk_xml;
using testing::VtkFile;

const std::vector<std::string> kCubeFaces = {"x0", "x1", "y0", "y1", "z0", "z1", "interface"};

const OutputFile* find_file(const std::vector<OutputFile>& files, const std::string& path) {
  for (const auto& f : files)
    if (f.path == path) return &f;
  return nullptr;
}

VtkFile parse(const std::vector<OutputFile>& files, const std::string& path) {
  const OutputFile* f = find_file(files, path);
  EXPECT_NE(f, nullptr) << path;
  if (!f) return {};
  auto r = read_vtk_xml(f->bytes);
  EXPECT_TRUE(r.ok()) << r.message();
  return r.ok() ? r.value() : VtkFile{};
}

std::vector<std::string> paths(const std::vector<OutputFile>& files) {
  std::vector<std::string> p;
  for (const auto& f : files) p.push_back(f.path);
  return p;
}

/// The cells of a parsed VTP as lists of GlobalNodeIDs minus 1, i.e. the
/// volume's vertex indices.
std::vector<std::vector<int32_t>> cells_of(const VtkFile& f) {
  auto c = f.values<int32_t>("Polys", "connectivity");
  auto o = f.values<int64_t>("Polys", "offsets");
  auto ids = f.values<int32_t>("PointData", "GlobalNodeID");
  std::vector<std::vector<int32_t>> cells;
  int64_t at = 0;
  for (int64_t end : o) {
    std::vector<int32_t> cell;
    for (; at < end; ++at) cell.push_back(ids[size_t(c[size_t(at)])] - 1);
    cells.push_back(cell);
  }
  return cells;
}

/// True when `cell` is one of the outward faces of element e (its nodes in
/// VolumeMesh order), read in the same cyclic order.
bool outward_face_of(const VolumeMesh& m, int32_t e, const std::vector<int32_t>& cell) {
  std::vector<std::vector<int32_t>> faces;
  if (size_t(e) < m.num_tets()) {
    const int32_t* t = &m.tets[4 * size_t(e)];
    for (const auto& f : kFaceOut) faces.push_back({t[f[0]], t[f[1]], t[f[2]]});
  } else {
    const int32_t* p = &m.prisms[6 * (size_t(e) - m.num_tets())];
    faces = {{p[0], p[2], p[1]},
             {p[3], p[4], p[5]},
             {p[0], p[1], p[4], p[3]},
             {p[1], p[2], p[5], p[4]},
             {p[2], p[0], p[3], p[5]}};
  }
  for (auto f : faces) {
    if (f.size() != cell.size()) continue;
    for (size_t r = 0; r < f.size(); ++r) {
      if (f == cell) return true;
      std::rotate(f.begin(), f.begin() + 1, f.end());
    }
  }
  return false;
}

TEST(MeshCompleteWriter, CubeLayoutAndIds) {
  VolumeMesh m = testing::cube_tets(2);
  auto r = mesh_complete_files(m, kCubeFaces, {"lumen"}, "vesselmesh test; input xxh128:0");
  ASSERT_TRUE(r.ok()) << r.message();
  const auto& files = r.value();
  EXPECT_EQ(paths(files),
            (std::vector<std::string>{
                "mesh-complete.mesh.vtu", "mesh-complete.exterior.vtp", "mesh-surfaces/x0.vtp",
                "mesh-surfaces/x1.vtp", "mesh-surfaces/y0.vtp", "mesh-surfaces/y1.vtp",
                "mesh-surfaces/z0.vtp", "mesh-surfaces/z1.vtp", "mesh-complete.names.json"}));
  VtkFile vtu = parse(files, "mesh-complete.mesh.vtu");
  EXPECT_EQ(vtu.piece_count("NumberOfCells"), m.num_tets());
  EXPECT_EQ(vtu.comment, " vesselmesh test; input xxh128:0 ");

  VtkFile ext = parse(files, "mesh-complete.exterior.vtp");
  EXPECT_EQ(ext.piece_count("NumberOfPolys"), m.num_triangles());  // 6 faces x 8 triangles
  EXPECT_EQ(ext.piece_count("NumberOfPoints"), 26u);               // all but the centre
  auto face_ids = ext.values<int32_t>("CellData", "ModelFaceID");
  std::vector<int32_t> expected_ids;
  for (int32_t t : m.triangle_tag) expected_ids.push_back(t + 1);
  EXPECT_EQ(face_ids, expected_ids);
  auto cells = cells_of(ext);
  auto elements = ext.values<int32_t>("CellData", "GlobalElementID");
  ASSERT_EQ(cells.size(), m.num_triangles());
  for (size_t t = 0; t < cells.size(); ++t) {
    EXPECT_EQ(cells[t], std::vector<int32_t>(&m.triangles[3 * t], &m.triangles[3 * t] + 3));
    EXPECT_TRUE(outward_face_of(m, elements[t] - 1, cells[t])) << t;
  }

  VtkFile z1 = parse(files, "mesh-surfaces/z1.vtp");
  EXPECT_EQ(z1.piece_count("NumberOfPolys"), 8u);
  EXPECT_EQ(z1.piece_count("NumberOfPoints"), 9u);
  EXPECT_EQ(z1.values<int32_t>("CellData", "ModelFaceID"), std::vector<int32_t>(8, 6));
  for (int32_t id : z1.values<int32_t>("PointData", "GlobalNodeID"))
    EXPECT_EQ(m.points[3 * size_t(id - 1) + 2], 2.0);

  const OutputFile* names = find_file(files, "mesh-complete.names.json");
  ASSERT_NE(names, nullptr);
  EXPECT_NE(names->bytes.find("{\"id\":1,\"name\":\"x0\",\"file\":\"mesh-surfaces/x0.vtp\","
                              "\"triangles\":8,\"quads\":0,\"exterior\":true}"),
            std::string::npos)
      << names->bytes;
  EXPECT_NE(names->bytes.find("\"regions\":[{\"id\":1,\"name\":\"lumen\",\"elements\":48,"
                              "\"tetrahedra\":48,\"prisms\":0}]"),
            std::string::npos)
      << names->bytes;
  EXPECT_NE(names->bytes.find("\"provenance\":\"vesselmesh test; input xxh128:0\""),
            std::string::npos);
}

TEST(MeshCompleteWriter, InterfaceBetweenTwoTetRegionsIsNotExterior) {
  VolumeMesh m = testing::cube_tets(2);
  const size_t boundary = m.num_triangles();
  testing::split_regions(m, 6);
  const size_t interface = m.num_triangles() - boundary;
  ASSERT_GT(interface, 0u);
  auto r = mesh_complete_files(m, kCubeFaces, {"lumen", "vessel_wall"}, "");
  ASSERT_TRUE(r.ok()) << r.message();
  VtkFile ext = parse(r.value(), "mesh-complete.exterior.vtp");
  EXPECT_EQ(ext.piece_count("NumberOfPolys"), boundary);
  auto ids = ext.values<int32_t>("CellData", "ModelFaceID");
  EXPECT_EQ(std::count(ids.begin(), ids.end(), 7), 0);
  EXPECT_TRUE(ext.comment.empty());
  VtkFile in = parse(r.value(), "mesh-surfaces/interface.vtp");
  EXPECT_EQ(in.piece_count("NumberOfPolys"), interface);
  // Each interface face names the region-0 element it is outward of.
  auto cells = cells_of(in);
  auto elements = in.values<int32_t>("CellData", "GlobalElementID");
  for (size_t t = 0; t < cells.size(); ++t) {
    EXPECT_EQ(m.tet_region[size_t(elements[t] - 1)], 0);
    EXPECT_TRUE(outward_face_of(m, elements[t] - 1, cells[t]));
  }
  const std::string& json = r.value().back().bytes;
  EXPECT_NE(json.find("\"name\":\"interface\",\"file\":\"mesh-surfaces/interface.vtp\","
                      "\"triangles\":" +
                      std::to_string(interface) + ",\"quads\":0,\"exterior\":false}"),
            std::string::npos)
      << json;
  EXPECT_NE(json.find("{\"id\":2,\"name\":\"vessel_wall\",\"elements\":24"), std::string::npos);
}

TEST(MeshCompleteWriter, PrismsQuadsAndInterface) {
  VolumeMesh m = testing::prism_tet_stack();
  auto r = mesh_complete_files(m, {"bottom", "sides", "top", "wall"}, {"lumen", "layer"}, "p");
  ASSERT_TRUE(r.ok()) << r.message();
  VtkFile ext = parse(r.value(), "mesh-complete.exterior.vtp");
  // 2 bottom + 4 top triangles, then the 4 quads; not the 2 interface triangles.
  EXPECT_EQ(ext.piece_count("NumberOfPolys"), 10u);
  EXPECT_EQ(ext.values<int32_t>("CellData", "ModelFaceID"),
            (std::vector<int32_t>{1, 1, 3, 3, 3, 3, 2, 2, 2, 2}));
  EXPECT_EQ(ext.values<int64_t>("Polys", "offsets"),
            (std::vector<int64_t>{3, 6, 9, 12, 15, 18, 22, 26, 30, 34}));
  // Elements: tetrahedra 1-2, prisms 3-4.
  EXPECT_EQ(ext.values<int32_t>("CellData", "GlobalElementID"),
            (std::vector<int32_t>{3, 4, 1, 1, 2, 2, 3, 3, 4, 4}));
  auto cells = cells_of(ext);
  auto elements = ext.values<int32_t>("CellData", "GlobalElementID");
  for (size_t c = 0; c < cells.size(); ++c)
    EXPECT_TRUE(outward_face_of(m, elements[c] - 1, cells[c])) << c;
  VtkFile wall = parse(r.value(), "mesh-surfaces/wall.vtp");
  EXPECT_EQ(wall.values<int32_t>("CellData", "GlobalElementID"), (std::vector<int32_t>{1, 2}));
  VtkFile sides = parse(r.value(), "mesh-surfaces/sides.vtp");
  EXPECT_EQ(sides.piece_count("NumberOfPolys"), 4u);
  EXPECT_EQ(sides.piece_count("NumberOfPoints"), 8u);
  const std::string& json = r.value().back().bytes;
  EXPECT_NE(json.find("\"name\":\"wall\",\"file\":\"mesh-surfaces/wall.vtp\",\"triangles\":2,"
                      "\"quads\":0,\"exterior\":false"),
            std::string::npos)
      << json;
  EXPECT_NE(json.find("\"name\":\"sides\",\"file\":\"mesh-surfaces/sides.vtp\",\"triangles\":0,"
                      "\"quads\":4,\"exterior\":true"),
            std::string::npos);
  EXPECT_NE(json.find("{\"id\":2,\"name\":\"layer\",\"elements\":2,\"tetrahedra\":0,"
                      "\"prisms\":2}"),
            std::string::npos);
}

TEST(MeshCompleteWriter, UnusedAndUnnamedTags) {
  VolumeMesh m = testing::cube_tets(1);
  for (int32_t& t : m.triangle_tag) t = t == 0 ? 9 : 1;  // tags 1 and 9 only
  std::vector<std::string> names = {"", "sides"};        // tag 9 unnamed, beyond the list
  auto r = mesh_complete_files(m, names, {""}, "");
  ASSERT_TRUE(r.ok()) << r.message();
  EXPECT_EQ(paths(r.value()),
            (std::vector<std::string>{"mesh-complete.mesh.vtu", "mesh-complete.exterior.vtp",
                                      "mesh-surfaces/sides.vtp", "mesh-surfaces/face_10.vtp",
                                      "mesh-complete.names.json"}));
  EXPECT_NE(r.value().back().bytes.find("\"name\":\"region_1\""), std::string::npos);
}

TEST(MeshCompleteWriter, Errors) {
  VolumeMesh m = testing::cube_tets(1);
  EXPECT_FALSE(mesh_complete_files(m, {"../x"}, {"lumen"}, "").ok());
  EXPECT_FALSE(mesh_complete_files(m, {"a", "a", "b", "c", "d", "e"}, {"lumen"}, "").ok());
  VolumeMesh bad = m;
  bad.triangle_tag.pop_back();
  EXPECT_FALSE(mesh_complete_files(bad, kCubeFaces, {"lumen"}, "").ok());
  bad = m;
  bad.triangle_tag[0] = -2;
  EXPECT_FALSE(mesh_complete_files(bad, kCubeFaces, {"lumen"}, "").ok());
  bad = m;
  bad.triangles.insert(bad.triangles.end(), {1, 2, 4});  // no element's face
  bad.triangle_tag.push_back(0);
  auto r = mesh_complete_files(bad, kCubeFaces, {"lumen"}, "");
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.message().find("no element's face"), std::string::npos) << r.message();
  bad = m;
  bad.tets[0] = 100;
  EXPECT_FALSE(mesh_complete_files(bad, kCubeFaces, {"lumen"}, "").ok());
}

TEST(FaceElements, CountsAndOwners) {
  VolumeMesh m = testing::prism_tet_stack();
  FaceElements fe = face_elements(m);
  EXPECT_EQ(fe.uses, (std::vector<uint8_t>{1, 1, 1, 1, 1, 1, 2, 2, 1, 1, 1, 1}));
  EXPECT_EQ(fe.element, (std::vector<int32_t>{2, 3, 0, 0, 1, 1, 0, 1, 2, 2, 3, 3}));
  // A duplicated face is counted for each copy; the reversed copy is owned
  // by the element on its other side.
  m.triangles.insert(m.triangles.end(), {4, 5, 6});
  m.triangle_tag.push_back(3);
  fe = face_elements(m);
  EXPECT_EQ(fe.uses[6], 2);
  EXPECT_EQ(fe.uses[8], 2);
  EXPECT_EQ(fe.element[6], 0);
  EXPECT_EQ(fe.element[8], 2);
}

TEST(FaceElements, AnyIndicesGiveTheSameAnswers) {
  // Indices are only compared: negative ones, ones far beyond the points,
  // and an order-reversing renumbering give the same uses and elements.
  VolumeMesh m = testing::prism_tet_stack();
  m.triangles.insert(m.triangles.end(), {4, 5, 6, 0, 1, 8});  // a duplicate, a face of none
  m.triangle_tag.insert(m.triangle_tag.end(), {3, 0});
  const FaceElements want = face_elements(m);
  EXPECT_EQ(want.uses[8], 2);
  EXPECT_EQ(want.uses[9], 0);
  EXPECT_EQ(want.element[9], -1);
  for (int32_t (*map)(int32_t) :
       {+[](int32_t v) { return v - 4; }, +[](int32_t v) { return v * 100000 + 7; },
        +[](int32_t v) { return v * 200000000 - 900000000; }, +[](int32_t v) { return 8 - v; }}) {
    VolumeMesh n = m;
    n.points.clear();
    for (auto* a : {&n.tets, &n.prisms, &n.triangles, &n.quads})
      for (int32_t& v : *a) v = map(v);
    const FaceElements got = face_elements(n);
    EXPECT_EQ(got.uses, want.uses);
    EXPECT_EQ(got.element, want.element);
  }
}

}  // namespace
}  // namespace vm
