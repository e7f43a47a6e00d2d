#include "core/io/vtk_xml_reader.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "tests/io/reader_checks.h"
#include "tests/io/surface_writers.h"
#include "tests/support/test_meshes.h"

namespace vm {
namespace {

using testing::Bytes;
using testing::CellMesh;
using testing::to_bytes;
using testing::VtpStyle;

// Tube 6 around, 2 rings of quads: quads (polys) for ring 0 and a strip for
// ring 1, so both cell kinds are present; labels 7 (quads) and 9 (strip).
// Its triangles must equal open_tube(6, 2)'s, in the same order.
constexpr int kN = 6, kM = 2;

CellMesh quads_and_strip() {
  SurfaceMesh tube = testing::open_tube(kN, kM);
  CellMesh m;
  m.points = tube.points;
  auto quads = testing::tube_quads(kN, kM);
  m.polys.assign(quads.begin(), quads.begin() + kN);  // ring 0
  m.strips = {testing::tube_strips(kN, kM)[1]};       // ring 1
  m.labels.assign(kN, 7);
  m.labels.push_back(9);
  return m;
}

// Triangles of ring 1 of the tube in strip order: (a, d, c), (a, b, d) per quad.
std::vector<int32_t> expected_triangles() {
  SurfaceMesh tube = testing::open_tube(kN, kM);
  std::vector<int32_t> t(tube.triangles.begin(), tube.triangles.begin() + 6 * kN);
  for (int i = 0; i < kN; ++i) {
    const int32_t* q = &tube.triangles[size_t(6 * (kN + i))];  // (a, b, d), (a, d, c)
    t.insert(t.end(), {q[3], q[4], q[5], q[0], q[1], q[2]});
  }
  return t;
}

void expect_tube(const SurfaceFile& f, bool float_points) {
  SurfaceMesh tube = testing::open_tube(kN, kM);
  ASSERT_EQ(f.points.size(), tube.points.size());
  for (size_t i = 0; i < f.points.size(); ++i) {
    if (float_points)
      EXPECT_EQ(f.points[i], double(float(tube.points[i])));
    else
      EXPECT_EQ(f.points[i], tube.points[i]);
  }
  // Triangle strip: rotations of the same triangles are equal triangles.
  std::vector<int32_t> want = expected_triangles();
  ASSERT_EQ(f.triangles.size(), want.size());
  for (size_t t = 0; t < want.size() / 3; ++t) {
    bool same = false;
    for (int r = 0; r < 3; ++r)
      same |= f.triangles[3 * t] == want[3 * t + r] &&
              f.triangles[3 * t + 1] == want[3 * t + (r + 1) % 3] &&
              f.triangles[3 * t + 2] == want[3 * t + (r + 2) % 3];
    EXPECT_TRUE(same) << "triangle " << t;
  }
  ASSERT_EQ(f.face_labels.size(), want.size() / 3);
  for (size_t t = 0; t < f.face_labels.size(); ++t)
    EXPECT_EQ(f.face_labels[t], t < size_t(2 * kN) ? 7 : 9) << t;
  EXPECT_EQ(f.label_array, "ModelFaceID");
  EXPECT_EQ(f.format_id, "vtp");
}

struct Variant {
  const char* name;
  VtpStyle style;
  const char* format;
};

std::vector<Variant> variants() {
  std::vector<Variant> v;
  VtpStyle s;
  v.push_back({"ascii", s, "VTK XML PolyData (ascii)"});
  s.encoding = VtpStyle::kBinary;
  v.push_back({"binary_uint32", s, "VTK XML PolyData (binary)"});
  s.separate_header_base64 = true;
  v.push_back({"binary_uint32_separate_header", s, "VTK XML PolyData (binary)"});
  s.separate_header_base64 = false;
  s.uint64_header = true;
  v.push_back({"binary_uint64", s, "VTK XML PolyData (binary)"});
  s.zlib = true;
  s.block_size = 64;  // several blocks per array, a partial last one
  v.push_back({"binary_uint64_zlib", s, "VTK XML PolyData (binary, zlib)"});
  s = VtpStyle{};
  s.encoding = VtpStyle::kAppendedRaw;
  v.push_back({"appended_raw", s, "VTK XML PolyData (appended raw)"});
  s.zlib = true;
  s.block_size = 100;
  v.push_back({"appended_raw_zlib", s, "VTK XML PolyData (appended raw, zlib)"});
  s.uint64_header = true;
  s.big_endian = true;
  v.push_back({"appended_raw_zlib_uint64_big_endian", s,
               "VTK XML PolyData (appended raw, zlib, big endian)"});
  s = VtpStyle{};
  s.encoding = VtpStyle::kAppendedBase64;
  v.push_back({"appended_base64", s, "VTK XML PolyData (appended base64)"});
  s.zlib = true;
  s.float64_points = false;
  s.int64_ids = false;
  v.push_back(
      {"appended_base64_zlib_float32_int32", s, "VTK XML PolyData (appended base64, zlib)"});
  s.big_endian = true;
  v.push_back({"appended_base64_zlib_big_endian", s,
               "VTK XML PolyData (appended base64, zlib, big endian)"});
  s = VtpStyle{};
  s.encoding = VtpStyle::kBinary;
  s.big_endian = true;
  s.offsets_with_zero = true;
  v.push_back({"binary_big_endian_offsets_with_zero", s, "VTK XML PolyData (binary, big endian)"});
  return v;
}

TEST(VtkXmlReader, EveryEncodingGivesTheSamePointsTrianglesAndLabels) {
  for (const Variant& v : variants()) {
    SCOPED_TRACE(v.name);
    std::string text = testing::vtp(quads_and_strip(), v.style);
    auto r = read_vtk_xml(to_bytes(text));
    ASSERT_TRUE(r.ok()) << r.message();
    expect_tube(r.value(), !v.style.float64_points);
    EXPECT_EQ(r.value().format, v.format);
    EXPECT_TRUE(r.value().warnings.empty()) << r.value().warnings[0];
  }
}

TEST(VtkXmlReader, VertsAndLinesShiftTheCellDataAndAreIgnored) {
  CellMesh m = quads_and_strip();
  m.verts = {{0}, {1}};
  m.lines = {{0, 1, 2}};
  // Cell data order: verts, lines, polys, strips.
  m.labels.insert(m.labels.begin(), {100, 101, 102});
  for (VtpStyle::Encoding e : {VtpStyle::kAscii, VtpStyle::kAppendedRaw}) {
    VtpStyle s;
    s.encoding = e;
    auto r = read_vtk_xml(to_bytes(testing::vtp(m, s)));
    ASSERT_TRUE(r.ok()) << r.message();
    expect_tube(r.value(), false);
    ASSERT_EQ(r.value().warnings.size(), 1u);
    EXPECT_NE(r.value().warnings[0].find("2 vertex cells and 1 line cells"), std::string::npos);
  }
}

TEST(VtkXmlReader, PolygonsAreFannedAndSmallCellsSkipped) {
  CellMesh m;
  m.points = {0, 0, 0, 1, 0, 0, 2, 1, 0, 1, 2, 0, 0, 1, 0};
  m.polys = {{0, 1, 2, 3, 4}, {0, 1}, {2, 3, 4}};
  m.labels = {5, 6, 8};
  auto r = read_vtk_xml(to_bytes(testing::vtp(m)));
  ASSERT_TRUE(r.ok()) << r.message();
  EXPECT_EQ(r.value().triangles, (std::vector<int32_t>{0, 1, 2, 0, 2, 3, 0, 3, 4, 2, 3, 4}));
  EXPECT_EQ(r.value().face_labels, (std::vector<int32_t>{5, 5, 5, 8}));
  ASSERT_EQ(r.value().warnings.size(), 1u);
  EXPECT_NE(r.value().warnings[0].find("1 cells with fewer than 3 points"), std::string::npos);
}

TEST(VtkXmlReader, PiecesAreConcatenated) {
  CellMesh a;
  a.points = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  a.polys = {{0, 1, 2}};
  a.labels = {1};
  CellMesh b;
  b.points = {5, 0, 0, 6, 0, 0, 5, 1, 0, 6, 1, 0};
  b.polys = {{0, 1, 3, 2}};
  b.labels = {2};
  VtpStyle s;
  s.encoding = VtpStyle::kAppendedRaw;
  s.zlib = true;
  testing::VtpWriter w(s);
  auto r = read_vtk_xml(to_bytes(w.file({a, b})));
  ASSERT_TRUE(r.ok()) << r.message();
  EXPECT_EQ(r.value().points.size(), 21u);
  EXPECT_EQ(r.value().points[9], 5.0);
  EXPECT_EQ(r.value().triangles, (std::vector<int32_t>{0, 1, 2, 3, 4, 6, 3, 6, 5}));
  EXPECT_EQ(r.value().face_labels, (std::vector<int32_t>{1, 2, 2}));
}

TEST(VtkXmlReader, LabelArraysInOrderOfPreference) {
  CellMesh m;
  m.points = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  m.polys = {{0, 1, 2}};
  m.labels = {4};
  std::string text = testing::vtp(m);  // ModelFaceID = 4
  // Add a RegionId array before it: ModelFaceID must still win.
  size_t at = text.find("<DataArray type=\"Int32\" Name=\"ModelFaceID\"");
  ASSERT_NE(at, std::string::npos);
  text.insert(at, "<DataArray type=\"Int32\" Name=\"RegionId\" format=\"ascii\">3</DataArray>\n");
  auto r = read_vtk_xml(to_bytes(text));
  ASSERT_TRUE(r.ok()) << r.message();
  EXPECT_EQ(r.value().label_array, "ModelFaceID");
  EXPECT_EQ(r.value().face_labels, std::vector<int32_t>{4});
  // Without ModelFaceID, RegionId is used.
  VtpStyle s;
  s.label_name = "CellEntityIds";
  r = read_vtk_xml(to_bytes(testing::vtp(m, s)));
  ASSERT_TRUE(r.ok()) << r.message();
  EXPECT_EQ(r.value().label_array, "CellEntityIds");
  // An unknown name gives no labels.
  s.label_name = "Colors";
  r = read_vtk_xml(to_bytes(testing::vtp(m, s)));
  ASSERT_TRUE(r.ok()) << r.message();
  EXPECT_TRUE(r.value().face_labels.empty());
  EXPECT_TRUE(r.value().label_array.empty());
}

TEST(VtkXmlReader, InlineDataAfterInformationKeysAndComments) {
  std::string text =
      "\xEF\xBB\xBF<?xml version=\"1.0\"?>\n<!-- a comment <DataArray> -->\n"
      "<VTKFile type='PolyData' version='0.1' byte_order='LittleEndian'>\n"
      "<PolyData><Piece NumberOfPoints='3' NumberOfPolys='1'>\n"
      "<Points><DataArray type='Float32' NumberOfComponents='3' format='ascii'>\n"
      "<InformationKey name='L2_NORM_RANGE' location='vtkDataArray' length='2'>"
      "<Value index='0'>0</Value><Value index='1'>1</Value></InformationKey>\n"
      "0 0 0 1 0 0 0 1 0</DataArray></Points>\n"
      "<Polys><DataArray type='Int64' Name='connectivity' format='ascii'>0 1 2</DataArray>"
      "<DataArray type='Int64' Name='offsets' format='ascii'>3</DataArray></Polys>\n"
      "</Piece></PolyData></VTKFile>\n";
  auto r = read_vtk_xml(to_bytes(text));
  ASSERT_TRUE(r.ok()) << r.message();
  EXPECT_EQ(r.value().points, (std::vector<double>{0, 0, 0, 1, 0, 0, 0, 1, 0}));
  EXPECT_EQ(r.value().triangles, (std::vector<int32_t>{0, 1, 2}));
}

// ---- bad input --------------------------------------------------------------------

std::string error_of(const std::string& text, const SurfaceReadOptions& o = {}) {
  return testing::error_of([&o](const Bytes& b) { return read_vtk_xml(b, o); }, text);
}

TEST(VtkXmlReader, AppendedDataCutShort) {
  VtpStyle s;
  s.encoding = VtpStyle::kAppendedRaw;
  std::string text = testing::vtp(quads_and_strip(), s);
  size_t cut = text.find("</AppendedData>") - 40;
  std::string msg = error_of(text.substr(0, cut));
  EXPECT_HAS(msg, "the appended data ends at byte " + std::to_string(cut) + " but array");
  EXPECT_HAS(msg, "needs bytes up to");
}

TEST(VtkXmlReader, CompressedAppendedDataCutShort) {
  VtpStyle s;
  s.encoding = VtpStyle::kAppendedRaw;
  s.zlib = true;
  std::string text = testing::vtp(quads_and_strip(), s);
  // Cut inside the compressed blocks of the Points (the second array).
  size_t data = text.find('_', text.find("<AppendedData")) + 1;
  size_t points = std::stoul(text.substr(text.find("offset=", text.find("Name=\"Points\"")) + 8));
  size_t cut = data + points + 20;
  std::string msg = error_of(text.substr(0, cut));
  EXPECT_HAS(msg, "the appended data ends at byte " + std::to_string(cut) +
                      " but array 'Points' of <Points> needs bytes up to");
}

TEST(VtkXmlReader, BadBase64NamesThePosition) {
  VtpStyle s;
  s.encoding = VtpStyle::kBinary;
  std::string text = testing::vtp(quads_and_strip(), s);
  size_t at = text.find("format=\"binary\">\n", text.find("Name=\"Points\"")) + 17 + 5;
  text[at] = '#';
  std::string msg = error_of(text);
  EXPECT_HAS(msg, "array 'Points' of <Points>");
  EXPECT_HAS(msg, "bad base64 character '#' at position " + std::to_string(at));
}

TEST(VtkXmlReader, BadZlibStreamNamesArrayAndBlock) {
  VtpStyle s;
  s.encoding = VtpStyle::kAppendedRaw;
  s.zlib = true;
  s.block_size = 1 << 20;
  CellMesh m = quads_and_strip();
  std::string text = testing::vtp(m, s);
  // The Points array is the second appended array (after the labels):
  // corrupt bytes in the middle of its compressed block.
  testing::VtpWriter w(s);
  size_t labels_bytes =
      w.block(w.raw(m.labels)).first.size() + w.block(w.raw(m.labels)).second.size();
  size_t start = text.find('_', text.find("<AppendedData")) + 1 + labels_bytes + 16;
  for (size_t i = start; i < start + 8; ++i) text[i] = char(0xff);
  std::string msg = error_of(text);
  EXPECT_HAS(msg, "array 'Points' of <Points>, zlib block 1 of 1");
}

TEST(VtkXmlReader, HeaderThatLiesAboutSizes) {
  std::string good = testing::vtp(quads_and_strip());
  std::string text = good;
  text.replace(text.find("NumberOfPoints=\"18\""), 19, "NumberOfPoints=\"19\"");
  EXPECT_HAS(error_of(text),
             "ascii array 'Points' of <Points> has 54 values but the header "
             "declares 57");
  // The same lie in a binary file: the byte count disagrees.
  VtpStyle s;
  s.encoding = VtpStyle::kAppendedRaw;
  text = testing::vtp(quads_and_strip(), s);
  text.replace(text.find("NumberOfPoints=\"18\""), 19, "NumberOfPoints=\"99999999999\"");
  EXPECT_HAS(error_of(text),
             "array 'Points' of <Points> holds 432 bytes but the header declares "
             "299999999997 values");
  // Offsets past the connectivity.
  text = good;
  size_t off = text.find("Name=\"offsets\"", text.find("<Polys>"));
  size_t data = text.find('>', off) + 2;
  text.replace(data, 1, "40");
  EXPECT_HAS(error_of(text), "offsets of <Polys> are out of range: cell 0 spans entries 0 to 40");
  // Connectivity index past the points.
  text = good;
  size_t conn = text.find("Name=\"connectivity\"", text.find("<Polys>"));
  data = text.find('>', conn) + 2;
  text.replace(data, 1, "18");
  EXPECT_HAS(error_of(text), "<Polys> cell 0 refers to point 18 but there are 18 points");
  // Fewer offsets than cells (no labels, whose count would disagree first).
  CellMesh unlabelled = quads_and_strip();
  unlabelled.labels.clear();
  text = testing::vtp(unlabelled);
  text.replace(text.find("NumberOfPolys=\"6\""), 17, "NumberOfPolys=\"7\"");
  EXPECT_HAS(error_of(text), "has 6 values but the file declares 7 Polys cells");
  // A lying compression header: 8 compressed bytes cannot give 100 MB.
  s.zlib = true;
  text = testing::vtp(quads_and_strip(), s);
  size_t p = text.find('_', text.find("<AppendedData")) + 1;  // labels array header
  uint32_t lie[4] = {1, 100000000, 100000000, 8};
  std::memcpy(&text[p], lie, 16);
  text.replace(text.find("NumberOfPolys=\"6\""), 17, "NumberOfPolys=\"24999999\"");
  EXPECT_HAS(error_of(text), "8 compressed bytes cannot hold 100000000 bytes");
}

TEST(VtkXmlReader, DecompressedLimit) {
  VtpStyle s;
  s.encoding = VtpStyle::kAppendedBase64;
  s.zlib = true;
  SurfaceReadOptions o;
  o.max_decompressed_bytes = 100;
  EXPECT_HAS(error_of(testing::vtp(quads_and_strip(), s), o),
             "decompressed data exceeds the limit of 100 bytes");
}

TEST(VtkXmlReader, UnknownDataTypeIsNamed) {
  std::string text = testing::vtp(quads_and_strip());
  text.replace(text.find("Float64"), 7, "Float16");
  EXPECT_HAS(error_of(text),
             "array 'Points' of <Points> has data type 'Float16', which is not a "
             "VTK XML numeric type");
}

TEST(VtkXmlReader, MissingPointsNonFiniteAndWrongType) {
  std::string text = testing::vtp(quads_and_strip());
  size_t b = text.find("<Points>"), e = text.find("</Points>") + 9;
  EXPECT_HAS(error_of(text.substr(0, b) + text.substr(e)),
             "the file declares 18 points but has no <Points> array");
  text = testing::vtp(quads_and_strip());
  size_t v = text.find('>', text.find("Name=\"Points\"")) + 2;
  size_t sp = text.find(' ', text.find(' ', text.find(' ', v) + 1) + 1);  // point 1, x
  text.replace(sp + 1, text.find(' ', sp + 1) - sp - 1, "nan");
  EXPECT_HAS(error_of(text), "point 1 has a non-finite coordinate (NaN)");
  text = testing::vtp(quads_and_strip());
  text.replace(text.find("type=\"PolyData\""), 15, "type=\"UnstructuredGrid\"");
  EXPECT_HAS(error_of(text), "VTK XML file of type 'UnstructuredGrid' (.vtu): only PolyData");
  EXPECT_HAS(error_of("<?xml version='1.0'?><svg></svg>"), "root element is <svg>, not <VTKFile>");
}

TEST(VtkXmlReader, TooManyTriangles) {
  SurfaceReadOptions o;
  o.max_triangles = 10;
  EXPECT_HAS(error_of(testing::vtp(quads_and_strip()), o), "file too large: more than 10");
}

// Every prefix of a file, and every single-byte corruption in a sample of
// positions, must give a result or a message, never a crash (run under
// ASan/UBSan in the sanitizer build).
TEST(VtkXmlReader, TruncationsAndCorruptionsNeverCrash) {
  for (const Variant& v : variants()) {
    SCOPED_TRACE(v.name);
    std::string text = testing::vtp(quads_and_strip(), v.style);
    auto read = [](const Bytes& b) { return read_vtk_xml(b); };
    testing::expect_prefixes_answered(read, text, 7);
    for (char c : {'\0', '\xff', '<', '9'})
      testing::expect_changes_answered(read, text, 5, [c](char) { return c; });
  }
}

}  // namespace
}  // namespace vm
