#include "core/io/stl.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>

#include "core/mesh/weld.h"
#include "tests/io/reader_checks.h"
#include "tests/support/test_meshes.h"

namespace vm {
namespace {

using testing::ascii_stl;
using testing::bytes_of;

// The message of read_stl's refusal of `bytes` (a test failure if it reads them).
std::string error_of(std::span<const uint8_t> bytes, const StlReadOptions& options = {}) {
  auto r = read_stl(bytes, options);
  EXPECT_FALSE(r.ok());
  return r.message();
}

TEST(Stl, BinaryRoundTripKeepsCoordinates) {
  SurfaceMesh tube = testing::open_tube(12, 5);
  std::vector<uint8_t> bytes = write_stl_binary(tube);
  ASSERT_EQ(bytes.size(), 84u + 50u * tube.num_triangles());
  auto r = read_stl(bytes);
  ASSERT_TRUE(r.ok()) << r.message();
  EXPECT_FALSE(r.value().ascii);
  ASSERT_EQ(r.value().num_triangles(), tube.num_triangles());
  for (size_t t = 0; t < tube.num_triangles(); ++t)
    for (int k = 0; k < 3; ++k)
      for (int c = 0; c < 3; ++c)
        EXPECT_FLOAT_EQ(r.value().coords[9 * t + 3 * k + c],
                        float(tube.points[3 * tube.triangles[3 * t + k] + c]));
}

TEST(Stl, BinaryHeaderStartingWithSolidIsStillBinary) {
  SurfaceMesh tet = testing::tetrahedron();
  std::vector<uint8_t> bytes = write_stl_binary(tet, "x");
  std::memcpy(bytes.data(), "solid looks like ascii", 22);
  auto r = read_stl(bytes);
  ASSERT_TRUE(r.ok()) << r.message();
  EXPECT_FALSE(r.value().ascii);
  EXPECT_EQ(r.value().num_triangles(), 4u);
}

TEST(Stl, AsciiIsRead) {
  auto r = read_stl(bytes_of(ascii_stl(testing::tetrahedron(), "tet")));
  ASSERT_TRUE(r.ok()) << r.message();
  EXPECT_TRUE(r.value().ascii);
  EXPECT_EQ(r.value().num_triangles(), 4u);
  EXPECT_EQ(r.value().header, "tet");
  EXPECT_TRUE(r.value().coords.empty());
  // Indexed: the tetrahedron's 4 distinct corners once each, every corner
  // where the tetrahedron has it.
  const SurfaceMesh tet = testing::tetrahedron();
  const TriangleSoup& soup = r.value();
  ASSERT_EQ(soup.points.size(), 12u);
  ASSERT_EQ(soup.triangles.size(), 12u);
  for (size_t c = 0; c < 12; ++c)
    for (size_t k = 0; k < 3; ++k)
      EXPECT_EQ(soup.points[3 * size_t(soup.triangles[c]) + k],
                tet.points[3 * size_t(tet.triangles[c]) + k]);
}

TEST(Stl, AsciiKeepsEveryDigitFarFromTheOrigin) {
  // Two triangles 1e5 from the origin written with 17 digits. Corner d is
  // corner a moved by one part in 1e9 (1e-4): float32 (spacing 2^-7 there)
  // would make them one point, doubles keep them apart. Repeated text is one
  // point, and so are a (z = -0) and a0 (z = 0).
  const double o = 1e5 + 0.123456789;
  const double a[3] = {o, o, -0.0}, b[3] = {o + 1, o, 0.0}, c[3] = {o, o + 1, 0.0};
  const double a0[3] = {o, o, 0.0}, d[3] = {o * (1 + 1e-9), o, 0.0};
  ASSERT_EQ(float(a[0]), float(d[0]));  // what float32 would have done
  std::string text = "solid far\n";
  const double* const triangles[2][3] = {{a, b, c}, {a0, c, d}};
  for (const auto& t : triangles) {
    text += "facet normal 0 0 1\nouter loop\n";
    for (int k = 0; k < 3; ++k) {
      char buf[128];
      std::snprintf(buf, sizeof(buf), "vertex %.17g %.17g %.17g\n", t[k][0], t[k][1], t[k][2]);
      text += buf;
    }
    text += "endloop\nendfacet\n";
  }
  text += "endsolid far\n";
  auto r = read_stl(bytes_of(text));
  ASSERT_TRUE(r.ok()) << r.message();
  const TriangleSoup& soup = r.value();
  EXPECT_EQ(soup.num_triangles(), 2u);
  EXPECT_EQ(soup.triangles, (std::vector<int32_t>{0, 1, 2, 0, 2, 3}));
  ASSERT_EQ(soup.points.size(), 12u);
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(soup.points[k], a[k]);
    EXPECT_EQ(soup.points[3 + k], b[k]);
    EXPECT_EQ(soup.points[6 + k], c[k]);
    EXPECT_EQ(soup.points[9 + k], d[k]);
  }
  EXPECT_NE(soup.points[9], soup.points[0]);
  // The weld keeps them apart too (1e-4 is far above its tolerance here).
  const SurfaceMesh m = weld(soup.points, soup.triangles);
  EXPECT_EQ(m.num_vertices(), 4u);
  EXPECT_EQ(m.points, soup.points);
}

TEST(Stl, AsciiAcceptsUpperCaseAndCrLf) {
  std::string s =
      "SOLID x\r\nFACET NORMAL 0 0 1\r\nOUTER LOOP\r\nVERTEX 0 0 0\r\n"
      "VERTEX 1 0 0\r\nVERTEX 0 1 0\r\nENDLOOP\r\nENDFACET\r\nENDSOLID x\r\n";
  auto r = read_stl(bytes_of(s));
  ASSERT_TRUE(r.ok()) << r.message();
  EXPECT_EQ(r.value().num_triangles(), 1u);
}

TEST(Stl, AsciiNumbersParseLikeStrtod) {
  // Every syntax the reader accepts, compared with strtod (kept as a double).
  const char* numbers[] = {"0",           "-0",
                           "1",           "-1.5",
                           "+2.25",       "3.",
                           ".5",          "-.125",
                           "1e3",         "1E-3",
                           "1.5e+2",      "123456789.123456789",
                           "0.000001234", "6.02214076e23",
                           "-7.5e-30",    "1234567890123456789012",
                           "3.4e38"};
  for (const char* num : numbers) {
    std::string s = "solid n\nfacet normal 0 0 0\nouter loop\nvertex " + std::string(num) +
                    " 0 0\nvertex 0 1 0\nvertex 0 0 1\nendloop\nendfacet\nendsolid n\n";
    auto r = read_stl(bytes_of(s));
    ASSERT_TRUE(r.ok()) << num << ": " << r.message();
    ASSERT_EQ(r.value().triangles[0], 0);
    EXPECT_EQ(r.value().points[0], std::strtod(num, nullptr)) << num;
  }
  for (const char* bad : {"1e", "--1", "1.2.3", "e5", "+", "0x1p3z"}) {
    std::string s = "solid n\nfacet normal 0 0 0\nouter loop\nvertex " + std::string(bad) +
                    " 0 0\nvertex 0 1 0\nvertex 0 0 1\nendloop\nendfacet\nendsolid n\n";
    EXPECT_FALSE(read_stl(bytes_of(s)).ok()) << bad;
  }
}

TEST(Stl, EmptyFileIsRefused) {
  auto r = read_stl({});
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.message(), "empty file");
}

TEST(Stl, TruncatedBinaryIsRefusedWithCounts) {
  std::vector<uint8_t> bytes = write_stl_binary(testing::open_tube(8, 2));
  bytes.resize(bytes.size() - 30);
  const std::string error = error_of(bytes);
  EXPECT_HAS(error, "truncated binary STL");
  EXPECT_HAS(error, "32 triangles");
}

TEST(Stl, HeaderCountLargerThanFileIsRefused) {
  std::vector<uint8_t> bytes = write_stl_binary(testing::tetrahedron());
  bytes[80] = 200;  // claims 200 triangles, has 4
  EXPECT_HAS(error_of(bytes), "announces 200 triangles");
}

TEST(Stl, TrailingBytesAreToleratedWithWarning) {
  std::vector<uint8_t> bytes = write_stl_binary(testing::tetrahedron());
  bytes.push_back(0);
  bytes.push_back(0);
  auto r = read_stl(bytes);
  ASSERT_TRUE(r.ok()) << r.message();
  EXPECT_EQ(r.value().num_triangles(), 4u);
  ASSERT_EQ(r.value().warnings.size(), 1u);
  EXPECT_NE(r.value().warnings[0].find("2 bytes"), std::string::npos);
}

TEST(Stl, AsciiGarbageIsRefusedWithLine) {
  EXPECT_HAS(error_of(bytes_of("hello world, this is not a mesh\n")), "not an STL");

  std::string bad =
      "solid x\n facet normal 0 0 1\n outer loop\n vertex 0 0 0\n"
      " vertex 1 zero 0\n";
  const std::string error = error_of(bytes_of(bad));
  EXPECT_HAS(error, "line 5");
  EXPECT_HAS(error, "zero");
}

TEST(Stl, AsciiQuadFacetIsRefused) {
  std::string s =
      "solid q\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
      "vertex 1 1 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid q\n";
  EXPECT_HAS(error_of(bytes_of(s)), "exactly 3 vertices");
}

TEST(Stl, AsciiWithoutEndsolidIsRefused) {
  std::string s = ascii_stl(testing::tetrahedron());
  s.resize(s.find("endsolid"));
  EXPECT_HAS(error_of(bytes_of(s)), "missing 'endsolid'");
}

TEST(Stl, NonFiniteCoordinatesAreRefused) {
  SurfaceMesh tet = testing::tetrahedron();
  tet.points[4] = std::numeric_limits<double>::quiet_NaN();  // vertex 1, y
  EXPECT_HAS(error_of(write_stl_binary(tet)), "NaN");

  std::string s =
      "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex inf 0 0\n"
      "vertex 0 1 0\nendloop\nendfacet\nendsolid x\n";
  EXPECT_HAS(error_of(bytes_of(s)), "Inf");
}

TEST(Stl, TooManyTrianglesIsRefusedBeforeAllocating) {
  std::vector<uint8_t> bytes(84, 0);
  uint32_t huge = 4000000000u;
  std::memcpy(bytes.data() + 80, &huge, 4);
  // 84 bytes that claim 4e9 triangles are a truncated file, refused
  // without allocating for the claim.
  EXPECT_HAS(error_of(bytes), "truncated binary STL: the header announces 4000000000 triangles");

  StlReadOptions small;
  small.max_triangles = 3;
  EXPECT_HAS(error_of(write_stl_binary(testing::tetrahedron()), small), "too large");
}

TEST(Stl, ShortBinaryIsRefused) {
  std::vector<uint8_t> bytes = {1, 2, 3, 0, 0};
  EXPECT_HAS(error_of(bytes), "shorter than a binary STL header");
}

TEST(Stl, AsciiAsSegmentationToolsWriteIt) {
  const std::string facets =
      "facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
      "endloop\nendfacet\n";
  const std::string body = facets + "endsolid t\n";
  std::string mac = "solid t\n" + body;
  std::replace(mac.begin(), mac.end(), '\n', '\r');
  const std::string cases[] = {
      "\xEF\xBB\xBFsolid t\n" + body,                 // UTF-8 byte order mark
      std::string("solid a\fb\0c\n", 12) + body,      // form feed and NUL in the name
      mac,                                            // classic Mac line ends
      "solid " + std::string(90, 'x') + "\n" + body,  // a name past byte 84
  };
  for (const std::string& text : cases) {
    auto r = read_stl(bytes_of(text));
    ASSERT_TRUE(r.ok()) << r.message();
    EXPECT_TRUE(r.value().ascii);
    EXPECT_EQ(r.value().num_triangles(), 1u);
    EXPECT_EQ(r.value().points[3 * size_t(r.value().triangles[1])], 1.0);
  }
  // Lines are counted with lone CRs too.
  std::string bad = "solid t\rfacet normal 0 0 1\router loop\rvertex 0 0 0\rvertex 1 x 0\r";
  EXPECT_HAS(error_of(bytes_of(bad)), "line 5");
}

TEST(Stl, TextThatIsNotStlSaysSo) {
  const std::string error = error_of(bytes_of(std::string(200, 'a') + "\n"));
  EXPECT_HAS(error, "not an STL file: text that is not an ASCII STL");
  EXPECT_EQ(error.find("too large"), std::string::npos) << error;
}

}  // namespace
}  // namespace vm
