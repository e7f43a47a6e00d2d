#include "core/io/ply_reader.h"

#include <gtest/gtest.h>

#include <string>

#include "tests/io/reader_checks.h"
#include "tests/io/surface_writers.h"
#include "tests/support/test_meshes.h"

namespace vm {
namespace {

using testing::PlyFormat;
using testing::to_bytes;

constexpr auto kRead = [](const testing::Bytes& b) { return read_ply(b); };

testing::CellMesh sample() {
  SurfaceMesh tube = testing::open_tube(6, 2);
  testing::CellMesh m;
  m.points = tube.points;
  m.polys = testing::tube_quads(6, 2);
  for (int i = 0; i < 12; ++i) m.labels.push_back(10 + i / 6);
  return m;
}

TEST(PlyReader, AsciiAndBinaryWithExtraPropertiesAndElements) {
  SurfaceMesh tube = testing::open_tube(6, 2);
  for (PlyFormat f : {PlyFormat::kAscii, PlyFormat::kLittle, PlyFormat::kBig}) {
    auto r = read_ply(to_bytes(testing::ply(sample(), f)));
    ASSERT_TRUE(r.ok()) << r.message();
    EXPECT_EQ(r.value().points, tube.points);
    EXPECT_EQ(r.value().triangles, tube.triangles);
    ASSERT_EQ(r.value().face_labels.size(), 24u);
    for (size_t t = 0; t < 24; ++t) EXPECT_EQ(r.value().face_labels[t], 10 + int(t / 12));
    EXPECT_EQ(r.value().label_array, "label");
    EXPECT_EQ(r.value().format, f == PlyFormat::kAscii    ? "PLY (ascii)"
                                : f == PlyFormat::kLittle ? "PLY (binary little endian)"
                                                          : "PLY (binary big endian)");
    ASSERT_EQ(r.value().warnings.size(), 1u);
    EXPECT_EQ(r.value().warnings[0], "PLY elements 'edge' were ignored");
  }
}

TEST(PlyReader, PreferredLabelName) {
  auto r = read_ply(to_bytes(testing::ply(sample(), PlyFormat::kLittle, "ModelFaceID")));
  ASSERT_TRUE(r.ok()) << r.message();
  EXPECT_EQ(r.value().label_array, "ModelFaceID");
  r = read_ply(to_bytes(testing::ply(sample(), PlyFormat::kLittle, "colour")));
  ASSERT_TRUE(r.ok()) << r.message();
  EXPECT_TRUE(r.value().face_labels.empty());
}

std::string error_of(const std::string& text) { return testing::error_of(kRead, text); }

TEST(PlyReader, BadInputsGiveSpecificMessages) {
  const std::string head =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  EXPECT_EQ(error_of(head + "0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n"),
            "PLY face 0 refers to vertex 3 but there are 3 vertices");
  EXPECT_HAS(error_of(head + "0 0 0\n1 0 0\n"),
             "PLY element 'vertex' (header line 3) declares 3 elements of at least 6 bytes but "
             "only 12 bytes of data remain");
  EXPECT_HAS(error_of(head + "0 0 0\n1 0 0\n0 1 0\n3 0 1"),
             "PLY data ends in element 'face' number 0 of 1: its list 'vertex_indices' announces "
             "3 items");
  EXPECT_HAS(error_of(head + "0 0 0\n1 0 0\n0 1        \n"),
             "PLY data ends in element 'vertex' number 2 of 3");
  EXPECT_HAS(error_of("ply\nformat ascii 1.0\nelement vertex 3\nproperty float128 x\n"),
             "PLY header line 4: unknown property type 'float128'");
  EXPECT_HAS(error_of("ply\nformat binary_middle_endian 1.0\n"), "unknown format");
  std::string lying = testing::ply(sample(), PlyFormat::kLittle);
  lying.replace(lying.find("element vertex 18"), 17, "element vertex 1800000000");
  EXPECT_HAS(error_of(lying),
             "PLY element 'vertex' (header line 4) declares 1800000000 "
             "elements of at least 30 bytes but only");
  std::string cut = testing::ply(sample(), PlyFormat::kBig);
  EXPECT_HAS(error_of(cut.substr(0, cut.size() - 30)), "PLY data ends in element 'face' number");
  EXPECT_HAS(error_of("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nend_header\n1\n"),
             "PLY file without a 'face' element");
  EXPECT_HAS(error_of(head + "0 0 0\n1 0 0\n0 inf 0\n3 0 1 2\n"),
             "PLY vertex 2 has a non-finite coordinate (Inf)");
}

TEST(PlyReader, TruncationsNeverCrash) {
  for (PlyFormat f : {PlyFormat::kAscii, PlyFormat::kLittle, PlyFormat::kBig}) {
    std::string text = testing::ply(sample(), f);
    testing::expect_prefixes_answered(kRead, text, 3);
    testing::expect_changes_answered(kRead, text, 2, [](char c) { return char(c ^ 0xa5); });
  }
}

}  // namespace
}  // namespace vm
