#include "core/io/vtk_writer.h"

#include <gtest/gtest.h>

#include <cstring>

#include "tests/support/small_volumes.h"
#include "tests/support/vtk_xml_reader.h"

namespace vm {
namespace {

using testing::read_vtk_xml;
using testing::VtkFile;

VtkFile parse(const Result<std::string>& written) {
  EXPECT_TRUE(written.ok()) << written.message();
  if (!written.ok()) return {};
  auto r = read_vtk_xml(written.value());
  EXPECT_TRUE(r.ok()) << r.message();
  return r.ok() ? r.value() : VtkFile{};
}

std::vector<int32_t> iota1(size_t n) {
  std::vector<int32_t> v(n);
  for (size_t i = 0; i < n; ++i) v[i] = int32_t(i + 1);
  return v;
}

TEST(VtkWriter, VtuOfACubeOfSixTetrahedra) {
  VolumeMesh m = testing::cube_tets(1);
  ASSERT_EQ(m.num_tets(), 6u);
  VtkFile f = parse(write_vtu(m));
  EXPECT_EQ(f.dataset, "UnstructuredGrid");
  EXPECT_EQ(f.file_attributes["header_type"], "UInt64");
  EXPECT_EQ(f.file_attributes["byte_order"], "LittleEndian");
  EXPECT_EQ(f.file_attributes.count("compressor"), 0u);
  EXPECT_EQ(f.piece_count("NumberOfPoints"), 8u);
  EXPECT_EQ(f.piece_count("NumberOfCells"), 6u);
  const testing::VtkArray* points = f.find("Points", "");
  ASSERT_NE(points, nullptr);
  EXPECT_EQ(points->type, "Float64");
  EXPECT_EQ(points->components, 3);
  EXPECT_EQ(f.values<double>("Points", ""), m.points);
  EXPECT_EQ(f.values<int32_t>("Cells", "connectivity"), m.tets);
  EXPECT_EQ(f.values<int64_t>("Cells", "offsets"), (std::vector<int64_t>{4, 8, 12, 16, 20, 24}));
  EXPECT_EQ(f.values<uint8_t>("Cells", "types"), std::vector<uint8_t>(6, 10));
  EXPECT_EQ(f.values<int32_t>("CellData", "ModelRegionID"), std::vector<int32_t>(6, 1));
  EXPECT_EQ(f.values<int32_t>("CellData", "GlobalElementID"), iota1(6));
  EXPECT_EQ(f.values<int32_t>("PointData", "GlobalNodeID"), iota1(8));
  EXPECT_EQ(f.find("CellData", "GlobalElementID")->type, "Int32");
  // VTK's tetra is positive for ((b-a)x(c-a)).(d-a) > 0, as written.
  auto c = f.values<int32_t>("Cells", "connectivity");
  for (size_t e = 0; e < 6; ++e)
    EXPECT_GT(tet_volume6(&m.points[3 * c[4 * e]], &m.points[3 * c[4 * e + 1]],
                          &m.points[3 * c[4 * e + 2]], &m.points[3 * c[4 * e + 3]]),
              0);
}

TEST(VtkWriter, VtuPrismsAreWedgesWithTheFirstTriangleFacingAway) {
  VolumeMesh m = testing::prism_tet_stack();
  VtkFile f = parse(write_vtu(m));
  EXPECT_EQ(f.piece_count("NumberOfCells"), 4u);
  auto c = f.values<int32_t>("Cells", "connectivity");
  ASSERT_EQ(c.size(), 2 * 4 + 2 * 6u);
  EXPECT_EQ(std::vector<int32_t>(c.begin(), c.begin() + 8), m.tets);
  EXPECT_EQ(std::vector<int32_t>(c.begin() + 8, c.begin() + 14),
            (std::vector<int32_t>{0, 2, 1, 4, 6, 5}));
  EXPECT_EQ(f.values<int64_t>("Cells", "offsets"), (std::vector<int64_t>{4, 8, 14, 20}));
  EXPECT_EQ(f.values<uint8_t>("Cells", "types"), (std::vector<uint8_t>{10, 10, 13, 13}));
  EXPECT_EQ(f.values<int32_t>("CellData", "ModelRegionID"), (std::vector<int32_t>{1, 1, 2, 2}));
  EXPECT_EQ(f.values<int32_t>("CellData", "GlobalElementID"), iota1(4));
  const double* p = m.points.data();
  for (size_t w = 0; w < 2; ++w) {
    const int32_t* n = &c[8 + 6 * w];
    // VTK: the first triangle's right-hand normal points away from the second.
    EXPECT_LT(tet_volume6(p + 3 * n[0], p + 3 * n[1], p + 3 * n[2], p + 3 * n[3]), 0);
    EXPECT_GT(tet_volume6(p + 3 * n[3], p + 3 * n[4], p + 3 * n[5], p + 3 * n[0]), 0);
  }
}

TEST(VtkWriter, ZlibBlocksRoundTripToTheRawArrays) {
  VolumeMesh m = testing::cube_tets(12);  // 10368 tetrahedra: several 32 KiB blocks
  VtkFile raw = parse(write_vtu(m));
  VtkWriteOptions o;
  o.zlib = true;
  Result<std::string> packed = write_vtu(m, o);
  VtkFile z = parse(packed);
  EXPECT_EQ(z.file_attributes["compressor"], "vtkZLibDataCompressor");
  ASSERT_EQ(z.arrays.size(), raw.arrays.size());
  for (size_t i = 0; i < raw.arrays.size(); ++i) {
    SCOPED_TRACE(raw.arrays[i].name);
    EXPECT_EQ(z.arrays[i].name, raw.arrays[i].name);
    EXPECT_EQ(z.arrays[i].bytes, raw.arrays[i].bytes);
    EXPECT_EQ(z.arrays[i].block_size, 32768u);
    EXPECT_EQ(z.arrays[i].blocks, (raw.arrays[i].bytes.size() + 32767) / 32768);
    EXPECT_EQ(z.arrays[i].last_size, raw.arrays[i].bytes.size() % 32768);
  }
  const testing::VtkArray* connectivity = z.find("Cells", "connectivity");
  EXPECT_GT(connectivity->blocks, 1u);
  EXPECT_LT(packed.value().size(), write_vtu(m).value().size());
}

TEST(VtkWriter, ZlibArrayOfWholeBlocksHasNoPartialBlock) {
  VolumeMesh m = testing::cube_tets(1);
  m.points.resize(3 * 8192, 5.0);  // GlobalNodeID: exactly 32768 bytes
  VtkWriteOptions o;
  o.zlib = true;
  VtkFile f = parse(write_vtu(m, o));
  const testing::VtkArray* ids = f.find("PointData", "GlobalNodeID");
  ASSERT_NE(ids, nullptr);
  EXPECT_EQ(ids->blocks, 1u);
  EXPECT_EQ(ids->last_size, 0u);
  EXPECT_EQ(f.values<int32_t>("PointData", "GlobalNodeID"), iota1(8192));
  EXPECT_EQ(f.values<double>("Points", ""), m.points);
}

TEST(VtkWriter, CommentIsEscapedAndValidUtf8) {
  VtkWriteOptions o;
  o.comment = "vesselmesh 0.1.0; options: --layers 4 ---\nsecond line\t\xc3\xa9 \xff end-";
  Result<std::string> w = write_vtu(testing::cube_tets(1), o);
  ASSERT_TRUE(w.ok());
  EXPECT_EQ(w.value().rfind("<?xml version=\"1.0\"?>\n<!-- ", 0), 0u);
  VtkFile f = parse(w);
  EXPECT_EQ(f.comment,
            " vesselmesh 0.1.0; options: - -layers 4 - - -\nsecond line \xc3\xa9 ? end- ");
  EXPECT_EQ(f.comment.find("--"), std::string::npos);
  EXPECT_EQ(f.piece_count("NumberOfCells"), 6u);
}

TEST(VtkWriter, VtuErrors) {
  VolumeMesh m = testing::cube_tets(1);
  m.tets[5] = 8;
  EXPECT_FALSE(write_vtu(m).ok());
  m = testing::cube_tets(1);
  m.tet_region.pop_back();
  EXPECT_FALSE(write_vtu(m).ok());
  m = testing::cube_tets(1);
  m.tet_region[0] = -1;
  EXPECT_FALSE(write_vtu(m).ok());
  m.tet_region.clear();  // no tags: region 0
  VtkFile f = parse(write_vtu(m));
  EXPECT_EQ(f.values<int32_t>("CellData", "ModelRegionID"), std::vector<int32_t>(6, 1));
}

TEST(VtkWriter, VtpKeepsUsedPointsAndTheirGlobalIds) {
  // 6 points, 1 unused (index 2); a triangle and a quad.
  const std::vector<double> points = {0, 0, 0, 1, 0, 0, 9, 9, 9, 1, 1, 0, 0, 1, 0, 2, 0, 0};
  const std::vector<int32_t> ids = {10, 11, 12, 13, 14, 15};
  VtpSurface s;
  s.points = points;
  s.triangles = {1, 5, 3};
  s.quads = {0, 1, 3, 4};
  s.face_ids = {3, 7};
  s.global_node_ids = ids;
  s.global_element_ids = {100, 200};
  for (bool zlib : {false, true}) {
    VtkWriteOptions o;
    o.zlib = zlib;
    VtkFile f = parse(write_vtp(s, o));
    EXPECT_EQ(f.dataset, "PolyData");
    EXPECT_EQ(f.piece_count("NumberOfPoints"), 5u);
    EXPECT_EQ(f.piece_count("NumberOfPolys"), 2u);
    EXPECT_EQ(f.piece_count("NumberOfVerts"), 0u);
    EXPECT_EQ(f.values<double>("Points", ""),
              (std::vector<double>{0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 2, 0, 0}));
    EXPECT_EQ(f.values<int32_t>("PointData", "GlobalNodeID"),
              (std::vector<int32_t>{10, 11, 13, 14, 15}));
    EXPECT_EQ(f.values<int32_t>("Polys", "connectivity"),
              (std::vector<int32_t>{1, 4, 2, 0, 1, 2, 3}));
    EXPECT_EQ(f.values<int64_t>("Polys", "offsets"), (std::vector<int64_t>{3, 7}));
    EXPECT_EQ(f.values<int32_t>("CellData", "ModelFaceID"), (std::vector<int32_t>{3, 7}));
    EXPECT_EQ(f.values<int32_t>("CellData", "GlobalElementID"), (std::vector<int32_t>{100, 200}));
  }
  // Optional arrays left out.
  s.global_node_ids = {};
  s.global_element_ids.clear();
  VtkFile f = parse(write_vtp(s));
  EXPECT_EQ(f.find("PointData", "GlobalNodeID"), nullptr);
  EXPECT_EQ(f.find("CellData", "GlobalElementID"), nullptr);
  EXPECT_NE(f.find("CellData", "ModelFaceID"), nullptr);
}

TEST(VtkWriter, VtpPointScalarsFollowTheirPoints) {
  // Point 2 is unused: its values are dropped with it.
  const std::vector<double> points = {0, 0, 0, 1, 0, 0, 9, 9, 9, 0, 1, 0};
  const std::vector<double> radius = {1.5, 2.5, 99, 3.5}, size = {0.1, 0.2, 99, 0.3};
  VtpSurface s;
  s.points = points;
  s.triangles = {0, 1, 3};
  s.face_ids = {1};
  s.point_scalars = {{"radius", radius}, {"size", size}};
  for (bool zlib : {false, true}) {
    VtkWriteOptions o;
    o.zlib = zlib;
    VtkFile f = parse(write_vtp(s, o));
    EXPECT_EQ(f.values<double>("PointData", "radius"), (std::vector<double>{1.5, 2.5, 3.5}));
    EXPECT_EQ(f.values<double>("PointData", "size"), (std::vector<double>{0.1, 0.2, 0.3}));
  }
  const std::vector<double> short_values = {1, 2};
  s.point_scalars = {{"radius", short_values}};
  EXPECT_FALSE(write_vtp(s).ok());
  s.point_scalars = {{"a\"b", radius}};
  EXPECT_FALSE(write_vtp(s).ok());
}

TEST(VtkWriter, VtpErrors) {
  const std::vector<double> points = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  VtpSurface s;
  s.points = points;
  s.triangles = {0, 1, 2};
  s.face_ids = {1};
  EXPECT_TRUE(write_vtp(s).ok());
  s.face_ids = {};
  EXPECT_FALSE(write_vtp(s).ok());
  s.face_ids = {1};
  s.triangles = {0, 1, 3};
  EXPECT_FALSE(write_vtp(s).ok());
  s.triangles = {0, 1, 2};
  s.global_element_ids = {1, 2};
  EXPECT_FALSE(write_vtp(s).ok());
  s.global_element_ids = {};
  const std::vector<int32_t> two = {1, 2};
  s.global_node_ids = two;
  EXPECT_FALSE(write_vtp(s).ok());
}

}  // namespace
}  // namespace vm
