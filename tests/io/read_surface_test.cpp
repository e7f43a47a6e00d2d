#include "core/io/read_surface.h"

#include <gtest/gtest.h>

#include <array>
#include <cstring>
#include <random>
#include <set>
#include <string>

#include "core/mesh/enclosed_volume.h"
#include "core/mesh/weld.h"
#include "core/pipeline/prepare_surface.h"
#include "tests/io/reader_checks.h"
#include "tests/io/surface_writers.h"
#include "tests/support/icosphere.h"
#include "tests/support/test_meshes.h"

namespace vm {
namespace {

using testing::Bytes;
using testing::to_bytes;

constexpr const char* kNotASurface =
    "not a surface file this tool reads (binary or ASCII STL, VTK XML PolyData .vtp, legacy VTK "
    ".vtk, Wavefront .obj, PLY; any of them gzip-compressed): it starts with '";

// A tube whose coordinates are floats, so that every format (STL included)
// holds exactly the same numbers.
SurfaceMesh float_tube() {
  SurfaceMesh m = testing::open_tube(12, 4);
  for (double& x : m.points) x = double(float(x));
  return m;
}

struct Sample {
  std::string name;
  Bytes bytes;
  std::string format, id;
};

std::vector<Sample> samples(const SurfaceMesh& mesh) {
  testing::CellMesh cells = testing::cells_of(mesh);
  std::vector<Sample> s;
  s.push_back({"binary stl", write_stl_binary(mesh), "binary STL", "stl"});
  s.push_back({"ascii stl", to_bytes(testing::ascii_stl(mesh)), "ASCII STL", "stl"});
  testing::VtpStyle v;
  s.push_back({"vtp ascii", to_bytes(testing::vtp(cells, v)), "VTK XML PolyData (ascii)", "vtp"});
  v.encoding = testing::VtpStyle::kAppendedRaw;
  v.zlib = true;
  s.push_back({"vtp appended raw zlib", to_bytes(testing::vtp(cells, v)),
               "VTK XML PolyData (appended raw, zlib)", "vtp"});
  v.encoding = testing::VtpStyle::kAppendedBase64;
  v.float64_points = false;
  s.push_back({"vtp appended base64 zlib", to_bytes(testing::vtp(cells, v)),
               "VTK XML PolyData (appended base64, zlib)", "vtp"});
  v.encoding = testing::VtpStyle::kBinary;
  v.zlib = false;
  v.big_endian = true;
  s.push_back({"vtp binary big endian", to_bytes(testing::vtp(cells, v)),
               "VTK XML PolyData (binary, big endian)", "vtp"});
  testing::VtkStyle k;
  s.push_back({"vtk ascii", to_bytes(testing::vtk_legacy(cells, k)), "legacy VTK (ASCII)", "vtk"});
  k.binary = true;
  k.layout51 = true;
  s.push_back(
      {"vtk binary", to_bytes(testing::vtk_legacy(cells, k)), "legacy VTK (binary)", "vtk"});
  s.push_back({"obj", to_bytes(testing::obj(cells)), "Wavefront OBJ", "obj"});
  s.push_back({"ply ascii", to_bytes(testing::ply(cells, testing::PlyFormat::kAscii)),
               "PLY (ascii)", "ply"});
  s.push_back({"ply little", to_bytes(testing::ply(cells, testing::PlyFormat::kLittle)),
               "PLY (binary little endian)", "ply"});
  s.push_back({"ply big", to_bytes(testing::ply(cells, testing::PlyFormat::kBig)),
               "PLY (binary big endian)", "ply"});
  size_t n = s.size();
  for (size_t i = 0; i < n; ++i) {
    s.push_back({"gzip " + s[i].name, testing::gzip(s[i].bytes), "gzip, " + s[i].format, s[i].id});
  }
  return s;
}

SurfaceMesh welded(const SurfaceFile& f) {
  if (!f.soup.coords.empty()) return weld(f.soup);
  return weld(f.points, f.triangles);
}

TEST(ReadSurface, EveryFormatGivesTheSameTriangles) {
  SurfaceMesh mesh = float_tube();
  auto reference = read_surface(write_stl_binary(mesh));
  ASSERT_TRUE(reference.ok()) << reference.message();
  SurfaceMesh want = welded(reference.value());
  ASSERT_EQ(want.num_vertices(), mesh.num_vertices());
  ASSERT_EQ(want.num_triangles(), mesh.num_triangles());
  for (size_t c = 0; c < mesh.triangles.size(); ++c)  // same corners, renumbered
    for (int k = 0; k < 3; ++k)
      ASSERT_EQ(want.points[3 * size_t(want.triangles[c]) + size_t(k)],
                mesh.points[3 * size_t(mesh.triangles[c]) + size_t(k)]);
  for (const Sample& s : samples(mesh)) {
    SCOPED_TRACE(s.name);
    auto r = read_surface(s.bytes);
    ASSERT_TRUE(r.ok()) << r.message();
    EXPECT_EQ(r.value().format, s.format);
    EXPECT_EQ(r.value().format_id, s.id);
    EXPECT_EQ(r.value().gzip, s.name.starts_with("gzip"));
    EXPECT_EQ(r.value().num_triangles(), mesh.num_triangles());
    SurfaceMesh got = welded(r.value());
    EXPECT_EQ(got.points, want.points);
    EXPECT_EQ(got.triangles, want.triangles);
  }
}

TEST(ReadSurface, PreparedSurfaceIsTheSameFromEveryFormat) {
  SurfaceMesh mesh = float_tube();
  auto stl = prepare_surface(write_stl_binary(mesh));
  ASSERT_TRUE(stl.ok()) << stl.message();
  for (const Sample& s : samples(mesh)) {
    SCOPED_TRACE(s.name);
    auto p = prepare_surface(s.bytes);
    ASSERT_TRUE(p.ok()) << p.message();
    EXPECT_EQ(p.value().format, s.format);
    EXPECT_EQ(p.value().mesh.points, stl.value().mesh.points);
    EXPECT_EQ(p.value().mesh.triangles, stl.value().mesh.triangles);
    EXPECT_EQ(p.value().topology.openings.size(), 2u);
    EXPECT_EQ(p.value().topology.genus, 0);
  }
}

/// `m` moved by (d, d, d).
SurfaceMesh moved(SurfaceMesh m, double d) {
  for (double& x : m.points) x += d;
  return m;
}

/// How many distinct points `m` has once its coordinates are float32.
size_t distinct_as_floats(const SurfaceMesh& m) {
  std::set<std::array<float, 3>> seen;
  for (size_t v = 0; v < m.num_vertices(); ++v)
    seen.insert({float(m.points[3 * v]), float(m.points[3 * v + 1]), float(m.points[3 * v + 2])});
  return seen.size();
}

TEST(ReadSurface, AsciiStlFarFromTheOriginKeepsItsShape) {
  // A small sphere (edges ~0.01) and an open tube (edges ~0.005) 1e5 from the
  // origin, written with 17 digits. Rounded to float32 (spacing 2^-7 there)
  // their vertices would collide: the check below shows it.
  constexpr double kOffset = 1e5;
  const SurfaceMesh sphere = testing::icosphere(3, 0.05);
  const SurfaceMesh far_sphere = moved(sphere, kOffset);
  ASSERT_LT(distinct_as_floats(far_sphere), far_sphere.num_vertices());
  auto r = prepare_surface(to_bytes(testing::ascii_stl(far_sphere)));
  ASSERT_TRUE(r.ok()) << r.message();
  const PreparedSurface& s = r.value();
  EXPECT_TRUE(s.ascii);
  EXPECT_EQ(s.format, "ASCII STL");
  EXPECT_EQ(s.weld.merged_by_tolerance, 0u);
  EXPECT_EQ(s.mesh.num_vertices(), sphere.num_vertices());
  EXPECT_EQ(s.mesh.num_triangles(), sphere.num_triangles());
  EXPECT_TRUE(s.topology.openings.empty());
  EXPECT_EQ(s.topology.genus, 0);
  EXPECT_NEAR(enclosed_volume(s.mesh), enclosed_volume(sphere), 1e-6 * enclosed_volume(sphere));
  EXPECT_NEAR(s.box.min[0], bounding_box(sphere.points).min[0] + kOffset, 1e-9);

  const SurfaceMesh tube = testing::open_tube(24, 8, 0.02, 0.1);
  const SurfaceMesh far_tube = moved(tube, kOffset);
  ASSERT_LT(distinct_as_floats(far_tube), far_tube.num_vertices());
  r = prepare_surface(to_bytes(testing::ascii_stl(far_tube)));
  ASSERT_TRUE(r.ok()) << r.message();
  EXPECT_EQ(r.value().mesh.num_vertices(), tube.num_vertices());
  EXPECT_EQ(r.value().mesh.num_triangles(), tube.num_triangles());
  EXPECT_EQ(r.value().topology.openings.size(), 2u);
  EXPECT_TRUE(check_meshable(r.value()).ok()) << check_meshable(r.value()).message();
}

std::string error_of(const Bytes& b, const SurfaceReadOptions& o = {}) {
  auto r = read_surface(b, o);
  EXPECT_FALSE(r.ok());
  return r.message();
}

TEST(ReadSurface, PngIsNotASurface) {
  const uint8_t png[] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n', 0, 0, 0, 13,
                         'I',  'H', 'D', 'R', 0,    0,    1,    0,    0, 0, 1, 0};
  Bytes b(png, png + sizeof(png));
  b.resize(2000, 0x55);
  EXPECT_EQ(error_of(b), std::string(kNotASurface) +
                             "\\x89PNG\\r\\n\\x1a\\n\\x00\\x00\\x00\\rIHDR...' (a PNG image)");
}

TEST(ReadSurface, RandomBytesAndTextAreNotASurface) {
  std::mt19937 rng(7);
  for (size_t n : {1u, 50u, 84u, 134u, 1000u, 4096u, 100000u}) {
    Bytes b(n);
    for (uint8_t& x : b) x = uint8_t(rng());
    if (b[0] == 0x1f) b[0] = 0;
    std::string msg = error_of(b);
    EXPECT_EQ(msg.rfind(kNotASurface, 0), 0u) << msg;
  }
  EXPECT_EQ(error_of(to_bytes("this is not a mesh\n")),
            std::string(kNotASurface) + "this is not a me...'");
  EXPECT_EQ(error_of({}), "empty file");
}

TEST(ReadSurface, ClearlyStlKeepsStlMessages) {
  EXPECT_HAS(error_of(to_bytes("solid x\nfacet normal 0 0 1\nouter loop\n")), "ASCII STL, line");
  Bytes stl = write_stl_binary(float_tube());
  EXPECT_HAS(error_of(Bytes(stl.begin(), stl.begin() + 1000)), "truncated binary STL");
  // A binary STL with its normals zeroed is still recognised when truncated.
  Bytes zeroed = stl;
  for (size_t t = 0; t < 20; ++t) std::fill_n(zeroed.begin() + long(84 + 50 * t), 12, 0);
  EXPECT_HAS(error_of(Bytes(zeroed.begin(), zeroed.begin() + 700)), "truncated binary STL");
}

TEST(ReadSurface, Utf16TextIsRead) {
  const std::string ascii = testing::ascii_stl(float_tube());
  for (bool little : {true, false}) {
    Bytes b = little ? Bytes{0xFF, 0xFE} : Bytes{0xFE, 0xFF};
    for (char c : ascii) {
      b.push_back(little ? uint8_t(c) : 0);
      b.push_back(little ? 0 : uint8_t(c));
    }
    auto r = read_surface(b);
    ASSERT_TRUE(r.ok()) << r.message();
    EXPECT_EQ(r.value().num_triangles(), float_tube().num_triangles());
    ASSERT_FALSE(r.value().warnings.empty());
    EXPECT_HAS(r.value().warnings.back(), "UTF-16");
  }
}

TEST(ReadSurface, ObjWithClassicMacLineEnds) {
  auto r = read_surface(to_bytes("v 0 0 0\rv 1 0 0\rv 0 1 0\rv 0 0 1\rf 1 2 3\rf 1 2 4\r"));
  ASSERT_TRUE(r.ok()) << r.message();
  EXPECT_EQ(r.value().num_triangles(), 2u);
}

TEST(ReadSurface, SizeIsCheckedFromTheHeaderBeforeReading) {
  Bytes head(84, ' ');
  const uint32_t count = 25'000'001;
  std::memcpy(head.data() + 80, &count, 4);
  const uint64_t size = 84 + 50 * uint64_t(count);
  EXPECT_HAS(check_surface_size(head, size).message(),
             "the binary STL header announces 25000001 triangles, the limit of this build is "
             "25000000");
  // A header that does not fit the file's size is left to the reader.
  EXPECT_TRUE(check_surface_size(head, size - 1).ok());
  SurfaceReadOptions small;
  small.max_file_bytes = 1000;
  EXPECT_HAS(check_surface_size(head, 2000, small).message(), "file too large");
  Bytes stl = write_stl_binary(float_tube());
  EXPECT_TRUE(check_surface_size(Bytes(stl.begin(), stl.begin() + 84), stl.size()).ok());
}

TEST(ReadSurface, BinaryStlWhoseHeaderLooksLikeAnotherFormat) {
  for (const char* header : {"<?xml version", "ply\nformat", "# vtk DataFile", "v 1 2 3\n"}) {
    Bytes stl = write_stl_binary(float_tube(), header);
    auto r = read_surface(stl);
    ASSERT_TRUE(r.ok()) << r.message();
    EXPECT_EQ(r.value().format, "binary STL");
  }
}

TEST(ReadSurface, GzipErrors) {
  // The inner file's own error, prefixed.
  EXPECT_EQ(error_of(testing::gzip(to_bytes("hello"))),
            "gzip-compressed file: " + std::string(kNotASurface) + "hello'");
  EXPECT_EQ(error_of(testing::gzip(testing::gzip(to_bytes("v 0 0 0\n")))),
            "gzip-compressed file: it holds another gzip stream (compressed twice): decompress "
            "it once first");
  Bytes big = write_stl_binary(testing::open_tube(200, 200));
  SurfaceReadOptions o;
  o.max_decompressed_bytes = 100000;
  EXPECT_HAS(error_of(testing::gzip(big), o),
             "gzip-compressed file: decompressed data exceeds the limit of 100000 bytes "
             "(compression ratio over ");
  Bytes gz = testing::gzip(big);
  EXPECT_HAS(error_of(Bytes(gz.begin(), gz.begin() + 5000)),
             "gzip-compressed file: gzip data ends before the end of the compressed stream");
}

TEST(ReadSurface, GzipOfNoSurfaceIsRefusedFromItsStart) {
  // 64 MiB of zeros, with a limit below that but above the 64 KiB sniffed
  // first: the refusal names the content, so the rest was never inflated.
  const Bytes zeros = testing::gzip_zeros(size_t(64) << 20);
  SurfaceReadOptions o;
  o.max_decompressed_bytes = size_t(1) << 20;
  std::string zeros16;
  for (int i = 0; i < 16; ++i) zeros16 += "\\x00";
  EXPECT_EQ(error_of(zeros, o),
            "gzip-compressed file: its first 65536 decompressed bytes are not the start of a "
            "surface file this tool reads (binary or ASCII STL, VTK XML PolyData .vtp, legacy VTK "
            ".vtk, Wavefront .obj, PLY; any of them gzip-compressed): they are all zero bytes; the "
            "rest was not decompressed. Open the surface file itself (a download or export that "
            "failed can leave such a file)");
  EXPECT_EQ(error_of(zeros), error_of(zeros, o));
  // Uncompressed, zero bytes are named too.
  EXPECT_EQ(error_of(Bytes(100000, 0)),
            std::string(kNotASurface) + zeros16 + "...' (all zero bytes)");
  Bytes mostly_zero(200, 0);
  mostly_zero[40] = 7;
  EXPECT_HAS(error_of(mostly_zero), "...' (its first 40 bytes are zero)");
  // Another gzip stream inside, also told from the start.
  Bytes twice = testing::gzip(zeros);
  EXPECT_EQ(error_of(twice, o),
            "gzip-compressed file: it holds another gzip stream (compressed twice): decompress "
            "it once first");
  // A binary STL header over the triangle limit.
  Bytes stl = write_stl_binary(testing::open_tube(64, 40));
  ASSERT_GT(stl.size(), 65536u);
  o.max_triangles = 1000;
  EXPECT_EQ(error_of(testing::gzip(stl), o),
            "gzip-compressed file: file too large: the binary STL header announces 5120 "
            "triangles, the limit of this build is 1000");
}

TEST(ReadSurface, GzipReadsAsTheUncompressedBytes) {
  // Files longer than the 64 KiB sniffed first, one of each format, and one
  // whose text starts after 70,000 line ends.
  SurfaceMesh mesh = testing::open_tube(64, 40);
  for (double& x : mesh.points) x = double(float(x));
  std::vector<Sample> all = samples(mesh);
  all.push_back({"late text", to_bytes(std::string(70000, '\n') + testing::ascii_stl(mesh)),
                 "ASCII STL", "stl"});
  size_t checked = 0;
  for (const Sample& s : all) {
    if (s.name.starts_with("gzip") || s.bytes.size() <= 65536) continue;
    SCOPED_TRACE(s.name);
    ++checked;
    auto plain = read_surface(s.bytes);
    auto gz = read_surface(testing::gzip(s.bytes));
    ASSERT_TRUE(plain.ok()) << plain.message();
    ASSERT_TRUE(gz.ok()) << gz.message();
    EXPECT_EQ(gz.value().format, "gzip, " + plain.value().format);
    EXPECT_EQ(gz.value().points, plain.value().points);
    EXPECT_EQ(gz.value().triangles, plain.value().triangles);
    EXPECT_EQ(gz.value().soup.coords, plain.value().soup.coords);
    EXPECT_EQ(gz.value().face_labels, plain.value().face_labels);
    EXPECT_EQ(gz.value().warnings, plain.value().warnings);
  }
  // The late text and the 12 formats but the two VTK XML files with zlib
  // arrays (shorter than 64 KiB).
  EXPECT_EQ(checked, 11u);
}

TEST(ReadSurface, MisnamedContentIsStillRecognised) {
  // Sniffing ignores names and leading whitespace / byte order marks.
  std::string v = "\xEF\xBB\xBF\n  " + testing::vtp(testing::cells_of(float_tube()));
  auto r = read_surface(to_bytes(v));
  ASSERT_TRUE(r.ok()) << r.message();
  EXPECT_EQ(r.value().format_id, "vtp");
  r =
      read_surface(to_bytes("# exported\n\nmtllib a.mtl\no thing\nv 0 0 0\nv 1 0 0\nv 0 1 0\n"
                            "f 1 2 3\n"));
  ASSERT_TRUE(r.ok()) << r.message();
  EXPECT_EQ(r.value().format_id, "obj");
  EXPECT_EQ(r.value().face_names, (std::vector<std::pair<int32_t, std::string>>{{1, "thing"}}));
}

// Every sample cut short and with bytes changed: a result or a message,
// never a crash (this runs under ASan/UBSan in the sanitizer build).
TEST(ReadSurface, CorruptionsNeverCrash) {
  SurfaceMesh mesh = testing::open_tube(5, 2);
  std::mt19937 rng(11);
  for (const Sample& s : samples(mesh)) {
    SCOPED_TRACE(s.name);
    for (size_t n = 0; n < s.bytes.size(); n += 1 + s.bytes.size() / 97) {
      auto r = read_surface(Bytes(s.bytes.begin(), s.bytes.begin() + long(n)));
      if (!r.ok()) {
        EXPECT_FALSE(r.message().empty());
      }
    }
    for (int trial = 0; trial < 300; ++trial) {
      Bytes b = s.bytes;
      for (int k = 0; k < 1 + trial % 4; ++k) b[rng() % b.size()] = uint8_t(rng());
      auto r = read_surface(b);
      if (!r.ok()) {
        EXPECT_FALSE(r.message().empty());
      } else {
        const SurfaceFile& f = r.value();
        for (int32_t i : f.triangles) ASSERT_LT(size_t(i), f.points.size() / 3);
        ASSERT_TRUE(f.face_labels.empty() || f.face_labels.size() == f.num_triangles());
      }
    }
  }
}

}  // namespace
}  // namespace vm
