#include "core/io/obj_reader.h"

#include <gtest/gtest.h>

#include <string>

#include "tests/io/reader_checks.h"
#include "tests/io/surface_writers.h"
#include "tests/support/test_meshes.h"

namespace vm {
namespace {

using testing::to_bytes;

constexpr auto kRead = [](const testing::Bytes& b) { return read_obj(b); };

TEST(ObjReader, GroupsBecomeLabelsInOrderOfFirstUse) {
  SurfaceMesh tube = testing::open_tube(6, 2);
  testing::CellMesh m;
  m.points = tube.points;
  m.polys = testing::tube_quads(6, 2);
  m.labels.assign(6, 1);
  m.labels.resize(12, 2);
  auto r = read_obj(to_bytes(testing::obj(m, {"wall", "cap part"})));
  ASSERT_TRUE(r.ok()) << r.message();
  EXPECT_EQ(r.value().points, tube.points);
  EXPECT_EQ(r.value().triangles, tube.triangles);
  std::vector<int32_t> want(12, 1);
  want.resize(24, 2);
  EXPECT_EQ(r.value().face_labels, want);
  EXPECT_EQ(r.value().label_array, "obj groups");
  ASSERT_EQ(r.value().face_names.size(), 2u);
  EXPECT_EQ(r.value().face_names[0], (std::pair<int32_t, std::string>(1, "wall")));
  EXPECT_EQ(r.value().face_names[1], (std::pair<int32_t, std::string>(2, "cap part")));
  EXPECT_EQ(r.value().format, "Wavefront OBJ");
  EXPECT_TRUE(r.value().warnings.empty());
}

TEST(ObjReader, SlashesNegativeIndicesAndReturningGroups) {
  std::string text =
      "# corners in every syntax\r\n"
      "v 0 0 0\r\nv 1 0 0 1.0\r\nv 1 1 0\r\nv 0 1 0 0.2 0.3 0.4\r\n"
      "vt 0 0\nvn 0 0 1\n"
      "o first\n"
      "f 1 2/1 3//1\n"
      "g second\n"
      "usemtl x\ns 1\n"
      "f -4/1/1 -2/1/1 -1/1/1 # trailing comment\n"
      "g first\n"
      "f 1 3 4\n"
      "l 1 2\np 3\n"
      "v 5 5 5\n"
      "f 2 3 -1 4\n";
  auto r = read_obj(to_bytes(text));
  ASSERT_TRUE(r.ok()) << r.message();
  EXPECT_EQ(r.value().points.size(), 15u);
  EXPECT_EQ(r.value().points[3], 1.0);
  EXPECT_EQ(r.value().triangles,
            (std::vector<int32_t>{0, 1, 2, 0, 2, 3, 0, 2, 3, 1, 2, 4, 1, 4, 3}));
  EXPECT_EQ(r.value().face_labels, (std::vector<int32_t>{1, 2, 1, 1, 1}));
  ASSERT_EQ(r.value().face_names.size(), 2u);
  EXPECT_EQ(r.value().face_names[1].second, "second");
}

TEST(ObjReader, WithoutGroupsNoLabels) {
  auto r = read_obj(to_bytes("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2\n"));
  ASSERT_TRUE(r.ok()) << r.message();
  EXPECT_TRUE(r.value().face_labels.empty());
  EXPECT_TRUE(r.value().label_array.empty());
  ASSERT_EQ(r.value().warnings.size(), 1u);
  EXPECT_HAS(r.value().warnings[0], "1 faces with fewer than 3 vertices were skipped");
}

std::string error_of(const std::string& text) { return testing::error_of(kRead, text); }

TEST(ObjReader, BadIndicesAndNumbers) {
  const std::string v = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  EXPECT_EQ(error_of(v + "f 0 1 2\n"), "OBJ line 4: face index 0 (OBJ indices start at 1)");
  EXPECT_EQ(error_of(v + "f 1 2 4\n"),
            "OBJ line 4: face index 4 is out of range: the file has 3 vertices");
  EXPECT_EQ(error_of(v + "f -1 -2 -4\n"),
            "OBJ line 4: relative face index -4 is out of range: only 3 vertices are defined "
            "before this line");
  EXPECT_EQ(error_of(v + "f 1 2 x/1\n"), "OBJ line 4: face corner 'x/1' is not a vertex index");
  EXPECT_EQ(error_of("v 0 zero 0\n"), "OBJ line 1: vertex coordinate 'zero' is not a number");
  EXPECT_EQ(error_of("v 0 0\n"), "OBJ line 1: a vertex needs 3 coordinates (v x y z)");
  EXPECT_EQ(error_of("v 0 0 0\nv nan 0 0\n"),
            "OBJ line 2: vertex 2 has a non-finite coordinate (NaN)");
  EXPECT_EQ(error_of(v), "OBJ file without any face (f) of 3 or more vertices");
}

}  // namespace
}  // namespace vm
