#include "core/io/vtk_legacy_reader.h"

#include <gtest/gtest.h>

#include <string>
#include <utility>

#include "tests/io/reader_checks.h"
#include "tests/io/surface_writers.h"
#include "tests/support/test_meshes.h"

namespace vm {
namespace {

using testing::CellMesh;
using testing::to_bytes;
using testing::VtkStyle;

constexpr auto kRead = [](const testing::Bytes& b) { return read_vtk_legacy(b); };

// open_tube(6, 2): ring 0 as quads (label 3), ring 1 as one strip (label 5),
// two vertex cells and a line before them (labels 90, 91, 92: VTK's cell
// order is verts, lines, polys, strips).
CellMesh sample() {
  SurfaceMesh tube = testing::open_tube(6, 2);
  CellMesh m;
  m.points = tube.points;
  auto quads = testing::tube_quads(6, 2);
  m.polys.assign(quads.begin(), quads.begin() + 6);
  m.strips = {testing::tube_strips(6, 2)[1]};
  m.verts = {{0}, {1}};
  m.lines = {{2, 3}};
  m.labels = {90, 91, 92, 3, 3, 3, 3, 3, 3, 5};
  return m;
}

void expect_sample(const SurfaceFile& f) {
  SurfaceMesh tube = testing::open_tube(6, 2);
  EXPECT_EQ(f.points, tube.points);  // %.17g and binary doubles are exact
  ASSERT_EQ(f.triangles.size(), tube.triangles.size());
  // Ring 0: the tube's own triangles in order.
  for (size_t i = 0; i < 36; ++i) EXPECT_EQ(f.triangles[i], tube.triangles[i]) << i;
  // Ring 1 from the strip: (a, d, c), (a, b, d) per quad, up to rotation.
  for (int q = 0; q < 6; ++q) {
    const int32_t* t = &tube.triangles[size_t(36 + 6 * q)];
    const int32_t* g = &f.triangles[size_t(36 + 6 * q)];
    std::vector<int32_t> want = {t[3], t[4], t[5], t[0], t[1], t[2]};
    for (int k = 0; k < 2; ++k) {
      bool same = false;
      for (int r = 0; r < 3; ++r)
        same |= g[3 * k] == want[size_t(3 * k + r)] &&
                g[3 * k + 1] == want[size_t(3 * k + (r + 1) % 3)] &&
                g[3 * k + 2] == want[size_t(3 * k + (r + 2) % 3)];
      EXPECT_TRUE(same) << "quad " << q << " triangle " << k;
    }
  }
  ASSERT_EQ(f.face_labels.size(), 24u);
  for (size_t t = 0; t < 24; ++t) EXPECT_EQ(f.face_labels[t], t < 12 ? 3 : 5) << t;
  EXPECT_EQ(f.label_array, "ModelFaceID");
  EXPECT_EQ(f.format_id, "vtk");
  ASSERT_FALSE(f.warnings.empty());
  EXPECT_HAS(f.warnings[0], "2 vertex cells and 1 line cells");
}

TEST(VtkLegacyReader, AsciiAndBinaryInBothCellLayouts) {
  for (bool binary : {false, true})
    for (bool layout51 : {false, true})
      for (bool field : {false, true}) {
        SCOPED_TRACE(std::string(binary ? "binary" : "ascii") + (layout51 ? " 5.1" : " classic") +
                     (field ? " field" : " scalars"));
        VtkStyle s;
        s.binary = binary;
        s.layout51 = layout51;
        s.field_labels = field;
        s.metadata = layout51;
        auto r = read_vtk_legacy(to_bytes(testing::vtk_legacy(sample(), s)));
        ASSERT_TRUE(r.ok()) << r.message();
        expect_sample(r.value());
        EXPECT_EQ(r.value().format, binary ? "legacy VTK (binary)" : "legacy VTK (ASCII)");
      }
}

TEST(VtkLegacyReader, FloatPointsAndOtherLabelNames) {
  std::string text =
      "# vtk DataFile Version 2.0\nx\nASCII\nDATASET POLYDATA\nPOINTS 4 float\n"
      "0 0 0 1 0 0 1 1 0 0 1 0\nPOLYGONS 2 8\n3 0 1 2\n3 0 2 3\n"
      "CELL_DATA 2\nSCALARS RegionId int\nLOOKUP_TABLE default\n4 6\n"
      "SCALARS CapID short 1\nLOOKUP_TABLE default\n1 2\n";
  auto r = read_vtk_legacy(to_bytes(text));
  ASSERT_TRUE(r.ok()) << r.message();
  EXPECT_EQ(r.value().triangles, (std::vector<int32_t>{0, 1, 2, 0, 2, 3}));
  EXPECT_EQ(r.value().label_array, "CapID");  // preferred over RegionId
  EXPECT_EQ(r.value().face_labels, (std::vector<int32_t>{1, 2}));
}

TEST(VtkLegacyReader, UnstructuredGridOfSurfaceCells) {
  std::string text =
      "# vtk DataFile Version 3.0\nug\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 5 double\n"
      "0 0 0 1 0 0 1 1 0 0 1 0 0 0 1\nCELLS 3 14\n4 0 1 2 3\n3 0 1 4\n4 0 1 2 4\n"
      "CELL_TYPES 3\n9\n5\n10\nCELL_DATA 3\nSCALARS CellEntityIds int\nLOOKUP_TABLE default\n"
      "1 2 3\n";
  auto r = read_vtk_legacy(to_bytes(text));
  ASSERT_TRUE(r.ok()) << r.message();
  EXPECT_EQ(r.value().triangles, (std::vector<int32_t>{0, 1, 2, 0, 2, 3, 0, 1, 4}));
  EXPECT_EQ(r.value().face_labels, (std::vector<int32_t>{1, 1, 2}));
  ASSERT_EQ(r.value().warnings.size(), 1u);
  EXPECT_HAS(r.value().warnings[0], "1 cells that are not surface cells");
}

std::string error_of(const std::string& text) { return testing::error_of(kRead, text); }

TEST(VtkLegacyReader, BadInputsGiveSpecificMessages) {
  const std::string head = "# vtk DataFile Version 3.0\nx\nASCII\nDATASET POLYDATA\n";
  // Each text and a phrase of its message.
  const std::pair<std::string, std::string> cases[] = {
      {head + "POINTS 3 float\n0 0 0 1 0 0 0 1 0\nPOLYGONS 1 4\n3 0 1 3\n",
       "POLYGONS cell 0 refers to point 3 but there are 3 points"},
      {head + "POINTS 3 float16\n0 0 0 1 0 0 0 1 0\n",
       "line 5: POINTS has data type 'float16', which is not a legacy VTK type"},
      {head + "POINTS 3 float\n0 0 0 1 0 0 0 1\n", "POINTS: the file ends after 8 of 9 values"},
      {head + "POINTS 3 float\n0 0 0 1 0 0 0 1 0\nPOLYGONS 2 4\n3 0 1 2\n",
       "POLYGONS declares 2 cells but its 4 values hold only 1"},
      {head + "POINTS 3 float\n0 0 0 1 nan 0 0 1 0\nPOLYGONS 1 4\n3 0 1 2\n",
       "point 1 has a non-finite coordinate (NaN)"},
      {head + "POINTS 99999999999 float\n0 0 0\n", "file too large: 99999999999 points"},
      {head + "POINTS 300000000 float\n0 0 0\n",
       "POINTS: 900000000 values are announced but the file has only"},
      {head + "BOGUS 3\n", "unknown keyword 'BOGUS'"},
      {"# vtk DataFile Version 3.0\nx\nASCII\nDATASET STRUCTURED_POINTS\n",
       "DATASET STRUCTURED_POINTS: only POLYDATA"},
  };
  for (const auto& [text, phrase] : cases) EXPECT_HAS(error_of(text), phrase);
  // Binary data cut short.
  VtkStyle s;
  s.binary = true;
  std::string bin = testing::vtk_legacy(sample(), s);
  std::string cut = bin.substr(0, bin.find("POINTS") + 100);
  EXPECT_HAS(error_of(cut), "POINTS: the file ends at byte " + std::to_string(cut.size()) +
                                " but 54 values of 8 bytes are announced");
}

TEST(VtkLegacyReader, TruncationsNeverCrash) {
  for (bool binary : {false, true})
    for (bool layout51 : {false, true}) {
      VtkStyle s;
      s.binary = binary;
      s.layout51 = layout51;
      s.field_labels = true;
      s.metadata = true;
      std::string text = testing::vtk_legacy(sample(), s);
      testing::expect_prefixes_answered(kRead, text, 3);
      testing::expect_changes_answered(kRead, text, 3, [](char c) { return char(c ^ 0x5a); });
    }
}

}  // namespace
}  // namespace vm
