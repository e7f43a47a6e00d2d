#include "core/io/msh_writer.h"

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <cstring>
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

// What a MSH 4.1 file holds, read back by either reader below.
struct Msh41 {
  std::string physical_names;                    ///< the $PhysicalNames section's text
  std::vector<std::array<int64_t, 3>> entities;  ///< dim, tag, physical tag
  std::vector<int64_t> node_tags;
  std::vector<double> coords;                  ///< 3 per node
  std::vector<std::array<int64_t, 4>> blocks;  ///< dim, entity, type, count
  std::vector<int64_t> elements;               ///< per element its tag, then its node tags
  bool operator==(const Msh41&) const = default;
};

std::string section_text(const std::string& file, const std::string& name) {
  const size_t a = file.find("$" + name + "\n"), b = file.find("$End" + name + "\n");
  if (a == std::string::npos || b == std::string::npos) return "";
  return file.substr(a + name.size() + 2, b - a - name.size() - 2);
}

// The ASCII file's sections (one node block, no parametric coordinates).
Msh41 read_ascii41(const std::string& file) {
  Msh41 r;
  r.physical_names = section_text(file, "PhysicalNames");
  std::istringstream en(section_text(file, "Entities"));
  int64_t counts[4];
  for (auto& c : counts) en >> c;
  for (int dim = 2; dim <= 3; ++dim)
    for (int64_t i = 0; i < counts[dim]; ++i) {
      int64_t tag, nphys, phys, nbound;
      double box[6];
      en >> tag;
      for (double& x : box) en >> x;
      en >> nphys >> phys >> nbound;
      r.entities.push_back({dim, tag, phys});
    }
  std::istringstream no(section_text(file, "Nodes"));
  int64_t blocks, nn, lo, hi, dim, tag, param, count;
  no >> blocks >> nn >> lo >> hi >> dim >> tag >> param >> count;
  r.node_tags.resize(size_t(count));
  r.coords.resize(3 * size_t(count));
  for (auto& t : r.node_tags) no >> t;
  for (auto& x : r.coords) no >> x;
  std::istringstream el(section_text(file, "Elements"));
  int64_t ne;
  el >> blocks >> ne >> lo >> hi;
  for (int64_t b = 0; b < blocks; ++b) {
    int64_t type;
    el >> dim >> tag >> type >> count;
    r.blocks.push_back({dim, tag, type, count});
    const int npe = nodes_per_element(MshElementType(type));
    for (int64_t e = 0, v = 0; e < count * (1 + npe); ++e) {
      el >> v;
      r.elements.push_back(v);
    }
  }
  return r;
}

// A reader of Gmsh's binary layout: little-endian int32 and uint64 (size_t)
// values at a cursor; fails the test where the layout is off.
class BinaryCursor {
 public:
  BinaryCursor(const std::string& file, size_t at) : file_(file), at_(at) {}
  template <class T>
  int64_t next() {
    T v{};
    EXPECT_LE(at_ + sizeof(T), file_.size());
    if (at_ + sizeof(T) <= file_.size()) std::memcpy(&v, file_.data() + at_, sizeof(T));
    at_ += sizeof(T);
    return int64_t(v);
  }
  double real() {
    double v = 0;
    if (at_ + 8 <= file_.size()) std::memcpy(&v, file_.data() + at_, 8);
    at_ += 8;
    return v;
  }
  size_t at() const { return at_; }

 private:
  const std::string& file_;
  size_t at_;
};

// Where the binary data of section `name` starts (after "$name\n").
size_t binary_section(const std::string& file, const std::string& name) {
  const size_t a = file.find("$" + name + "\n");
  EXPECT_NE(a, std::string::npos) << name;
  return a == std::string::npos ? file.size() : a + name.size() + 2;
}

Msh41 read_binary41(const std::string& file) {
  Msh41 r;
  r.physical_names = section_text(file, "PhysicalNames");
  auto ends = [&](const BinaryCursor& c, const std::string& name) {
    EXPECT_EQ(file.compare(c.at(), name.size() + 6, "\n$End" + name + "\n"), 0) << name;
  };
  BinaryCursor en(file, binary_section(file, "Entities"));
  int64_t counts[4];
  for (auto& c : counts) c = en.next<uint64_t>();
  for (int dim = 2; dim <= 3; ++dim)
    for (int64_t i = 0; i < counts[dim]; ++i) {
      const int64_t tag = en.next<int32_t>();
      for (int k = 0; k < 6; ++k) en.real();
      EXPECT_EQ(en.next<uint64_t>(), 1);
      const int64_t phys = en.next<int32_t>();
      EXPECT_EQ(en.next<uint64_t>(), 0);
      r.entities.push_back({dim, tag, phys});
    }
  ends(en, "Entities");
  BinaryCursor no(file, binary_section(file, "Nodes"));
  const int64_t blocks = no.next<uint64_t>(), nn = no.next<uint64_t>();
  EXPECT_EQ(blocks, 1);
  EXPECT_EQ(no.next<uint64_t>(), 1);
  EXPECT_EQ(no.next<uint64_t>(), nn);
  no.next<int32_t>();  // the entity's dimension and tag
  no.next<int32_t>();
  EXPECT_EQ(no.next<int32_t>(), 0);  // not parametric
  const int64_t count = no.next<uint64_t>();
  for (int64_t i = 0; i < count; ++i) r.node_tags.push_back(no.next<uint64_t>());
  for (int64_t i = 0; i < 3 * count; ++i) r.coords.push_back(no.real());
  ends(no, "Nodes");
  BinaryCursor el(file, binary_section(file, "Elements"));
  const int64_t nb = el.next<uint64_t>(), ne = el.next<uint64_t>();
  EXPECT_EQ(el.next<uint64_t>(), 1);
  EXPECT_EQ(el.next<uint64_t>(), ne);
  for (int64_t b = 0; b < nb; ++b) {
    const int64_t dim = el.next<int32_t>(), tag = el.next<int32_t>(), type = el.next<int32_t>();
    const int64_t n = el.next<uint64_t>();
    r.blocks.push_back({dim, tag, type, n});
    const int npe = nodes_per_element(MshElementType(type));
    for (int64_t e = 0; e < n * (1 + npe); ++e) r.elements.push_back(el.next<uint64_t>());
  }
  ends(el, "Elements");
  return r;
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

TEST(MshWriter, BinaryHoldsTheAsciiMesh) {
  MshModel m = tube_model();
  m.comment = "vesselmesh test";
  // A prism block too, and coordinates that need every bit.
  m.physicals.push_back({3, 8, "vessel_wall"});
  m.blocks.push_back({MshElementType::kPrism, 6, 8, {0, 1, 2, 10, 11, 12}});
  m.points[4] = 1.0 / 3.0;
  auto ascii = write_msh(m, MshVersion::k41);
  auto binary = write_msh(m, MshVersion::k41, MshEncoding::kBinary);
  ASSERT_TRUE(ascii.ok() && binary.ok()) << binary.message();
  const std::string& b = binary.value();
  const std::string header = "$MeshFormat\n4.1 1 8\n" + std::string("\x01\0\0\0", 4) +  // the int 1
                             "\n$EndMeshFormat\n";
  EXPECT_EQ(b.compare(0, header.size(), header), 0);
  EXPECT_NE(b.find("$Comments\nvesselmesh test\n$EndComments\n"), std::string::npos);
  const Msh41 from_binary = read_binary41(b), from_ascii = read_ascii41(ascii.value());
  EXPECT_EQ(from_binary.physical_names, "3\n2 1 \"wall\"\n3 7 \"lumen\"\n3 8 \"vessel_wall\"\n");
  EXPECT_EQ(from_binary.entities,
            (std::vector<std::array<int64_t, 3>>{{2, 1, 1}, {3, 5, 7}, {3, 6, 8}}));
  EXPECT_EQ(from_binary.coords, m.points);
  ASSERT_EQ(from_binary.blocks.size(), 3u);
  EXPECT_EQ(from_binary.blocks[2], (std::array<int64_t, 4>{3, 6, 6, 1}));
  // The prism: tag 62, nodes one-based.
  EXPECT_EQ(std::vector<int64_t>(from_binary.elements.end() - 7, from_binary.elements.end()),
            (std::vector<int64_t>{62, 1, 2, 3, 11, 12, 13}));
  EXPECT_TRUE(from_binary == from_ascii);
  EXPECT_EQ(b.substr(b.size() - 14), "\n$EndElements\n");
}

TEST(MshWriter, BinaryIsVersion41Only) {
  auto r = write_msh(tube_model(), MshVersion::k22, MshEncoding::kBinary);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.message().find("4.1 only"), std::string::npos) << r.message();
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
