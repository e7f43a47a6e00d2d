#include "core/io/msh_writer.h"

#include <gtest/gtest.h>

#include <sstream>

#include "tests/support/test_meshes.h"

namespace vm {
namespace {

MshModel tube_model() {
  SurfaceMesh tube = testing::open_tube(10, 3);
  MshModel m;
  m.points = tube.points;
  m.physicals = {{2, 1, "wall"}, {3, 7, "lumen"}};
  MshBlock wall{MshElementType::kTriangle, 1, 1, tube.triangles};
  // One tetrahedron to exercise the 3D path.
  MshBlock vol{MshElementType::kTetrahedron, 5, 7, {0, 1, 10, 2}};
  m.blocks = {wall, vol};
  return m;
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) out.push_back(l);
  return out;
}

size_t index_of(const std::vector<std::string>& lines, const std::string& what) {
  for (size_t i = 0; i < lines.size(); ++i)
    if (lines[i] == what) return i;
  return lines.size();
}

TEST(MshWriter, Version41Structure) {
  MshModel m = tube_model();
  auto r = write_msh(m, MshVersion::k41);
  ASSERT_TRUE(r.ok()) << r.message();
  auto L = lines_of(r.value());
  ASSERT_GE(L.size(), 3u);
  EXPECT_EQ(L[0], "$MeshFormat");
  EXPECT_EQ(L[1], "4.1 0 8");
  size_t pn = index_of(L, "$PhysicalNames");
  ASSERT_LT(pn, L.size());
  EXPECT_EQ(L[pn + 1], "2");
  EXPECT_EQ(L[pn + 2], "2 1 \"wall\"");
  EXPECT_EQ(L[pn + 3], "3 7 \"lumen\"");
  size_t en = index_of(L, "$Entities");
  EXPECT_EQ(L[en + 1], "0 0 1 1");
  size_t nodes = index_of(L, "$Nodes");
  EXPECT_EQ(L[nodes + 1], "1 40 1 40");
  EXPECT_EQ(L[nodes + 2], "3 5 0 40");  // nodes on the volume entity
  size_t el = index_of(L, "$Elements");
  EXPECT_EQ(L[el + 1], "2 61 1 61");
  EXPECT_EQ(L[el + 2], "2 1 2 60");
  EXPECT_EQ(L[el + 63], "3 5 4 1");
  EXPECT_EQ(L[el + 64], "61 1 2 11 3");
  EXPECT_EQ(L.back(), "$EndElements");
}

TEST(MshWriter, Version22Structure) {
  auto r = write_msh(tube_model(), MshVersion::k22);
  ASSERT_TRUE(r.ok()) << r.message();
  auto L = lines_of(r.value());
  EXPECT_EQ(L[1], "2.2 0 8");
  size_t nodes = index_of(L, "$Nodes");
  EXPECT_EQ(L[nodes + 1], "40");
  size_t el = index_of(L, "$Elements");
  EXPECT_EQ(L[el + 1], "61");
  // tag type ntags physical entity nodes...
  EXPECT_EQ(L[el + 2].substr(0, 11), "1 2 2 1 1 1");
  EXPECT_EQ(L[el + 62], "61 4 2 7 5 1 2 11 3");
}

TEST(MshWriter, CoordinatesRoundTripExactly) {
  MshModel m;
  m.points = {0.1, 1.0 / 3.0, -2.5e-7, 1, 2, 3, 4, 5, 6};
  m.physicals = {{2, 1, "wall"}};
  m.blocks = {{MshElementType::kTriangle, 1, 1, {0, 1, 2}}};
  auto L = lines_of(write_msh(m).value());
  size_t nodes = index_of(L, "$Nodes");
  std::istringstream in(L[nodes + 6]);
  double x, y, z;
  in >> x >> y >> z;
  EXPECT_EQ(x, 0.1);
  EXPECT_EQ(y, 1.0 / 3.0);
  EXPECT_EQ(z, -2.5e-7);
}

TEST(MshWriter, RefusesInconsistentModels) {
  MshModel m = tube_model();
  m.blocks[0].physical_tag = 9;
  auto r = write_msh(m);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.message().find("missing physical group 9"), std::string::npos);

  m = tube_model();
  m.blocks[1].nodes[2] = 400;
  EXPECT_FALSE(write_msh(m).ok());

  m = tube_model();
  m.blocks[0].nodes.pop_back();
  EXPECT_FALSE(write_msh(m).ok());
}

TEST(MshWriter, VersionParsing) {
  EXPECT_TRUE(parse_msh_version("4.1").ok());
  EXPECT_TRUE(parse_msh_version("2.2").ok());
  auto r = parse_msh_version("3.0");
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.message().find("4.1 or 2.2"), std::string::npos);
}

}  // namespace
}  // namespace vm
