#include "core/io/foam_writer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <set>
#include <sstream>

#include "tests/support/small_volumes.h"

namespace vm {
namespace {

const std::vector<std::string> kCubeFaces = {"x0", "x1", "y0", "y1", "z0", "z1", "interface"};

const std::string& file(const std::vector<OutputFile>& files, const std::string& path) {
  static const std::string none;
  for (const auto& f : files)
    if (f.path == path) return f.bytes;
  ADD_FAILURE() << "no file " << path;
  return none;
}

/// The text after the FoamFile header's closing brace, with '(' and ')'
/// spaced out so that a stream reads them as tokens.
std::istringstream body(const std::string& text) {
  const size_t at = text.find("\n}\n");
  std::string s = at == std::string::npos ? "" : text.substr(at + 3);
  std::string spaced;
  for (char c : s) {
    if (c == '(' || c == ')' || c == ';') {
      spaced += ' ';
      spaced += c;
      spaced += ' ';
    } else {
      spaced += c;
    }
  }
  return std::istringstream(spaced);
}

/// The FoamFile header's entry `key` ("" when absent).
std::string header_entry(const std::string& text, const std::string& key) {
  const size_t at = text.find("\n    " + key + " ");
  if (at == std::string::npos) return "";
  const size_t from = text.find_first_not_of(' ', at + 5 + key.size());
  return text.substr(from, text.find(';', from) - from);
}

struct Patch {
  std::string name, type;
  size_t n = 0, start = 0;
};

/// A polyMesh read back from the files.
struct PolyMesh {
  std::vector<double> points;               // 3 a point
  std::vector<std::vector<int64_t>> faces;  // vertex cycles
  std::vector<int64_t> owner, neighbour;
  std::vector<Patch> patches;
  std::map<std::string, std::vector<int64_t>> cell_zones, face_zones, flip_maps;
  size_t num_cells() const {
    int64_t n = -1;
    for (int64_t c : owner) n = std::max(n, c);
    for (int64_t c : neighbour) n = std::max(n, c);
    return size_t(n + 1);
  }
};

std::vector<int64_t> read_labels(std::istream& in) {
  size_t n = 0;
  std::string tok;
  in >> n >> tok;  // "("
  std::vector<int64_t> v(n);
  for (auto& x : v) in >> x;
  in >> tok;  // ")"
  EXPECT_EQ(tok, ")");
  return v;
}

/// Zones: "N ( name { type T ; labels List<label> n ( ... ) ; [flipMap ...] } ... )".
void read_zones(const std::string& text, const char* labels,
                std::map<std::string, std::vector<int64_t>>& zones,
                std::map<std::string, std::vector<int64_t>>* flips) {
  auto in = body(text);
  size_t n = 0;
  std::string tok, name;
  in >> n >> tok;
  for (size_t z = 0; z < n; ++z) {
    in >> name >> tok;  // "{"
    while (in >> tok && tok != "}") {
      if (tok == labels) {
        in >> tok;  // List<label>
        zones[name] = read_labels(in);
      } else if (tok == "flipMap" && flips) {
        in >> tok;  // List<bool>
        (*flips)[name] = read_labels(in);
      }
    }
  }
}

PolyMesh read_poly_mesh(const std::vector<OutputFile>& files) {
  PolyMesh m;
  const std::string dir = "constant/polyMesh/";
  {
    auto in = body(file(files, dir + "points"));
    size_t n = 0;
    std::string tok;
    in >> n >> tok;
    m.points.resize(3 * n);
    for (size_t i = 0; i < n; ++i)
      in >> tok >> m.points[3 * i] >> m.points[3 * i + 1] >> m.points[3 * i + 2] >> tok;
    in >> tok;
    EXPECT_EQ(tok, ")");
  }
  {
    auto in = body(file(files, dir + "faces"));
    size_t n = 0;
    std::string tok;
    in >> n >> tok;
    m.faces.resize(n);
    for (auto& f : m.faces) {
      size_t k = 0;
      in >> k >> tok;
      f.resize(k);
      for (auto& v : f) in >> v;
      in >> tok;
    }
    in >> tok;
    EXPECT_EQ(tok, ")");
  }
  {
    auto in = body(file(files, dir + "owner"));
    m.owner = read_labels(in);
  }
  {
    auto in = body(file(files, dir + "neighbour"));
    m.neighbour = read_labels(in);
  }
  {
    auto in = body(file(files, dir + "boundary"));
    size_t n = 0;
    std::string tok;
    in >> n >> tok;
    for (size_t p = 0; p < n; ++p) {
      Patch patch;
      in >> patch.name >> tok;
      while (in >> tok && tok != "}") {
        if (tok == "type") in >> patch.type;
        if (tok == "nFaces") in >> patch.n;
        if (tok == "startFace") in >> patch.start;
      }
      m.patches.push_back(patch);
    }
  }
  read_zones(file(files, dir + "cellZones"), "cellLabels", m.cell_zones, nullptr);
  for (const auto& f : files)
    if (f.path == dir + "faceZones") read_zones(f.bytes, "faceLabels", m.face_zones, &m.flip_maps);
  return m;
}

using V3 = std::array<double, 3>;

V3 point(const PolyMesh& m, int64_t v) {
  return {m.points[3 * size_t(v)], m.points[3 * size_t(v) + 1], m.points[3 * size_t(v) + 2]};
}

/// A face's area vector (right-hand rule, fan from vertex 0) and centroid.
std::pair<V3, V3> area_centre(const PolyMesh& m, const std::vector<int64_t>& f) {
  V3 a{0, 0, 0}, c{0, 0, 0};
  const V3 p0 = point(m, f[0]);
  for (size_t k = 0; k < f.size(); ++k) {
    const V3 p = point(m, f[k]);
    for (int i = 0; i < 3; ++i) c[size_t(i)] += p[size_t(i)] / double(f.size());
  }
  for (size_t k = 1; k + 1 < f.size(); ++k) {
    const V3 p = point(m, f[k]), q = point(m, f[k + 1]);
    const V3 u{p[0] - p0[0], p[1] - p0[1], p[2] - p0[2]},
        w{q[0] - p0[0], q[1] - p0[1], q[2] - p0[2]};
    a[0] += 0.5 * (u[1] * w[2] - u[2] * w[1]);
    a[1] += 0.5 * (u[2] * w[0] - u[0] * w[2]);
    a[2] += 0.5 * (u[0] * w[1] - u[1] * w[0]);
  }
  return {a, c};
}

/// The properties every polyMesh must have; returns the total volume.
double check_poly_mesh(const PolyMesh& m, size_t cells, size_t points) {
  EXPECT_EQ(m.points.size(), 3 * points);
  EXPECT_EQ(m.owner.size(), m.faces.size());
  EXPECT_EQ(m.num_cells(), cells);
  const size_t ni = m.neighbour.size();
  // Internal faces: owner < neighbour, upper-triangular order, each once.
  std::set<std::vector<int64_t>> seen;
  for (size_t f = 0; f < m.faces.size(); ++f) {
    std::vector<int64_t> key = m.faces[f];
    std::sort(key.begin(), key.end());
    EXPECT_TRUE(seen.insert(key).second) << "face " << f << " twice";
    for (int64_t v : m.faces[f]) EXPECT_TRUE(v >= 0 && size_t(v) < points);
  }
  for (size_t f = 0; f < ni; ++f) {
    EXPECT_LT(m.owner[f], m.neighbour[f]) << f;
    if (f > 0) {
      EXPECT_TRUE(std::pair(m.owner[f - 1], m.neighbour[f - 1]) <
                  std::pair(m.owner[f], m.neighbour[f]))
          << f;
    }
  }
  // Patches: contiguous after the internal faces, covering the rest.
  size_t at = ni;
  for (const Patch& p : m.patches) {
    EXPECT_EQ(p.start, at) << p.name;
    EXPECT_GT(p.n, 0u) << p.name;
    at += p.n;
  }
  EXPECT_EQ(at, m.faces.size());
  // Cells: centroids (mean of their face centres), closure, orientation.
  std::vector<V3> sum(cells, V3{0, 0, 0}), centre(cells, V3{0, 0, 0});
  std::vector<int> nfaces(cells, 0);
  std::vector<double> volume(cells, 0);
  auto add = [&](int64_t c, const V3& a, const V3& x, double sign) {
    for (int i = 0; i < 3; ++i) {
      sum[size_t(c)][size_t(i)] += sign * a[size_t(i)];
      centre[size_t(c)][size_t(i)] += x[size_t(i)];
    }
    volume[size_t(c)] += sign * (a[0] * x[0] + a[1] * x[1] + a[2] * x[2]) / 3;
    ++nfaces[size_t(c)];
  };
  for (size_t f = 0; f < m.faces.size(); ++f) {
    const auto [a, x] = area_centre(m, m.faces[f]);
    add(m.owner[f], a, x, 1);
    if (f < ni) add(m.neighbour[f], a, x, -1);
  }
  double total = 0;
  for (size_t c = 0; c < cells; ++c) {
    EXPECT_TRUE(nfaces[c] == 4 || nfaces[c] == 5) << "cell " << c;
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(sum[c][size_t(i)], 0, 1e-12) << "cell " << c;
    for (auto& x : centre[c]) x /= nfaces[c];
    EXPECT_GT(volume[c], 0) << "cell " << c;
    total += volume[c];
  }
  // Every face's normal points away from its owner's centroid.
  for (size_t f = 0; f < m.faces.size(); ++f) {
    const auto [a, x] = area_centre(m, m.faces[f]);
    const V3& o = centre[size_t(m.owner[f])];
    EXPECT_GT(a[0] * (x[0] - o[0]) + a[1] * (x[1] - o[1]) + a[2] * (x[2] - o[2]), 0) << f;
  }
  return total;
}

TEST(FoamWriter, CubeOfTetrahedra) {
  const VolumeMesh cube = testing::cube_tets(2);
  auto r = foam_case_files(cube, kCubeFaces, {"lumen"}, "vesselmesh test; input xxh128:0");
  ASSERT_TRUE(r.ok()) << r.message();
  std::vector<std::string> paths;
  for (const auto& f : r.value()) paths.push_back(f.path);
  EXPECT_EQ(paths,
            (std::vector<std::string>{"constant/polyMesh/points", "constant/polyMesh/faces",
                                      "constant/polyMesh/owner", "constant/polyMesh/neighbour",
                                      "constant/polyMesh/boundary", "constant/polyMesh/cellZones",
                                      "system/controlDict", "system/fvSchemes", "system/fvSolution",
                                      "case.foam"}));
  const PolyMesh m = read_poly_mesh(r.value());
  EXPECT_NEAR(check_poly_mesh(m, cube.num_tets(), cube.num_vertices()), 8, 1e-12);
  // 48 tetrahedra: 4 * 48 = 2 * internal + boundary (8 triangles a side).
  EXPECT_EQ(m.faces.size() - m.neighbour.size(), 48u);
  EXPECT_EQ(m.neighbour.size(), (4 * 48 - 48) / 2);
  ASSERT_EQ(m.patches.size(), 6u);
  for (size_t p = 0; p < 6; ++p) {
    EXPECT_EQ(m.patches[p].name, kCubeFaces[p]);
    EXPECT_EQ(m.patches[p].type, "patch");
    EXPECT_EQ(m.patches[p].n, 8u);
    // Each patch face lies on its cube side: x, y or z = 0 or 2.
    for (size_t f = m.patches[p].start; f < m.patches[p].start + 8; ++f)
      for (int64_t v : m.faces[f]) EXPECT_EQ(m.points[3 * size_t(v) + p / 2], p % 2 ? 2 : 0);
  }
  ASSERT_EQ(m.cell_zones.size(), 1u);
  EXPECT_EQ(m.cell_zones.at("lumen").size(), 48u);
  const std::string& owner = file(r.value(), "constant/polyMesh/owner");
  EXPECT_EQ(header_entry(owner, "note"),
            "\"nPoints:27  nCells:48  nFaces:120  nInternalFaces:72\"");
  EXPECT_EQ(header_entry(owner, "class"), "labelList");
  EXPECT_NE(owner.find("// vesselmesh test; input xxh128:0\n"), std::string::npos);
  EXPECT_EQ(header_entry(file(r.value(), "constant/polyMesh/faces"), "class"), "faceList");
  EXPECT_EQ(header_entry(file(r.value(), "constant/polyMesh/points"), "class"), "vectorField");
  EXPECT_EQ(file(r.value(), "case.foam"), "");
}

TEST(FoamWriter, WallIsAWallAndOthersArePatches) {
  const VolumeMesh cube = testing::cube_tets(1);
  auto r = foam_case_files(cube, {"wall", "inlet", "outlet_1", "outlet_2", "side", "outer_wall"},
                           {"lumen"}, "");
  ASSERT_TRUE(r.ok()) << r.message();
  const PolyMesh m = read_poly_mesh(r.value());
  std::map<std::string, std::string> types;
  for (const Patch& p : m.patches) types[p.name] = p.type;
  EXPECT_EQ(types, (std::map<std::string, std::string>{{"wall", "wall"},
                                                       {"inlet", "patch"},
                                                       {"outlet_1", "patch"},
                                                       {"outlet_2", "patch"},
                                                       {"side", "patch"},
                                                       {"outer_wall", "wall"}}));
  EXPECT_NE(file(r.value(), "constant/polyMesh/boundary")
                .find("        type            wall;\n        inGroups        List<word> 1(wall);"),
            std::string::npos);
  EXPECT_EQ(file(r.value(), "constant/polyMesh/boundary").find("//"), std::string::npos);
}

TEST(FoamWriter, InterfaceIsAFaceZoneOfInternalFaces) {
  VolumeMesh m = testing::cube_tets(2);
  testing::split_regions(m, 6);
  const size_t interface = size_t(std::count(m.triangle_tag.begin(), m.triangle_tag.end(), 6));
  ASSERT_GT(interface, 0u);
  auto r = foam_case_files(m, kCubeFaces, {"lumen", "vessel_wall"}, "");
  ASSERT_TRUE(r.ok()) << r.message();
  const PolyMesh p = read_poly_mesh(r.value());
  EXPECT_NEAR(check_poly_mesh(p, m.num_tets(), m.num_vertices()), 8, 1e-12);
  EXPECT_EQ(p.patches.size(), 6u);  // no patch for the interface
  ASSERT_EQ(p.cell_zones.size(), 2u);
  EXPECT_EQ(p.cell_zones.at("lumen").size() + p.cell_zones.at("vessel_wall").size(), 48u);
  std::set<int64_t> lumen(p.cell_zones.at("lumen").begin(), p.cell_zones.at("lumen").end());
  for (size_t c = 0; c < m.num_tets(); ++c)
    EXPECT_EQ(lumen.count(int64_t(c)), m.tet_region[c] == 0 ? 1u : 0u);
  ASSERT_EQ(p.face_zones.count("interface"), 1u);
  const auto& zone = p.face_zones.at("interface");
  const auto& flip = p.flip_maps.at("interface");
  ASSERT_EQ(zone.size(), interface);
  ASSERT_EQ(flip.size(), interface);
  for (size_t i = 0; i < zone.size(); ++i) {
    const size_t f = size_t(zone[i]);
    ASSERT_LT(f, p.neighbour.size());  // internal
    const bool owner_in_lumen = lumen.count(p.owner[f]) > 0;
    EXPECT_NE(owner_in_lumen, lumen.count(p.neighbour[f]) > 0);
    // The tagged triangles face out of region 0 (lumen): flipped when the
    // face's owner is the other region.
    EXPECT_EQ(flip[i], owner_in_lumen ? 0 : 1) << i;
  }
}

TEST(FoamWriter, PrismsAndTetrahedra) {
  const VolumeMesh m = testing::prism_tet_stack();
  auto r = foam_case_files(m, {"bottom", "sides", "top", "wall"}, {"lumen", "layer"}, "p");
  ASSERT_TRUE(r.ok()) << r.message();
  const PolyMesh p = read_poly_mesh(r.value());
  // The unit cube of prisms (1) and the pyramid of tetrahedra (1/3).
  EXPECT_NEAR(check_poly_mesh(p, 4, m.num_vertices()), 1 + 1.0 / 3, 1e-12);
  ASSERT_EQ(p.patches.size(), 3u);
  EXPECT_EQ(p.patches[0].name, "bottom");
  EXPECT_EQ(p.patches[0].n, 2u);
  EXPECT_EQ(p.patches[1].name, "sides");
  EXPECT_EQ(p.patches[1].n, 4u);
  for (size_t f = p.patches[1].start; f < p.patches[1].start + 4; ++f)
    EXPECT_EQ(p.faces[f].size(), 4u);
  EXPECT_EQ(p.patches[2].name, "top");
  EXPECT_EQ(p.patches[2].n, 4u);
  // Internal: prism-prism (1), prism-tet (2: the interface), tet-tet (1).
  EXPECT_EQ(p.neighbour.size(), 4u);
  EXPECT_EQ(p.face_zones.at("wall").size(), 2u);
  EXPECT_EQ(p.cell_zones.at("lumen"), (std::vector<int64_t>{0, 1}));
  EXPECT_EQ(p.cell_zones.at("layer"), (std::vector<int64_t>{2, 3}));
}

/// The lists of a binary file after its header, decoded here: each "n\n"
/// then, when n > 0, "(" + n * `width` raw bytes + ")\n".
std::vector<std::string> binary_lists(const std::string& text, size_t width) {
  std::vector<std::string> lists;
  size_t at = text.find("\n}\n") + 3;
  while (at < text.size()) {
    at = text.find_first_not_of('\n', at);
    if (at == std::string::npos) break;
    const size_t eol = text.find('\n', at);
    const size_t n = std::stoull(text.substr(at, eol - at));
    at = eol + 1;
    if (n == 0) {
      lists.emplace_back();
      continue;
    }
    EXPECT_EQ(text[at], '(');
    lists.push_back(text.substr(at + 1, n * width));
    at += 1 + n * width;
    EXPECT_EQ(text.substr(at, 2), ")\n");
    at += 2;
  }
  return lists;
}

template <class T>
std::vector<T> values_of(const std::string& bytes) {
  std::vector<T> v(bytes.size() / sizeof(T));
  std::memcpy(v.data(), bytes.data(), bytes.size());
  return v;
}

// FoamFormat::kBinary: points, faces (compact: offsets, then vertices),
// owner and neighbour decode to the text case's values, exactly; the
// dictionaries are the text case's bytes.
TEST(FoamWriter, BinaryListsAreTheTextCase) {
  const VolumeMesh m = testing::prism_tet_stack();
  const std::vector<std::string> surfaces = {"bottom", "sides", "top", "wall"};
  auto text = foam_case_files(m, surfaces, {"lumen", "layer"}, "p");
  auto binary = foam_case_files(m, surfaces, {"lumen", "layer"}, "p", FoamFormat::kBinary);
  ASSERT_TRUE(text.ok() && binary.ok()) << binary.message();
  const PolyMesh a = read_poly_mesh(text.value());
  const std::string dir = "constant/polyMesh/";
  for (const char* f : {"points", "faces", "owner", "neighbour"}) {
    const std::string& bytes = file(binary.value(), dir + f);
    EXPECT_EQ(header_entry(bytes, "format"), "binary") << f;
    EXPECT_NE(bytes.find("\n    arch        \"LSB;label=32;scalar=64\";\n"), std::string::npos)
        << f;
  }
  EXPECT_EQ(header_entry(file(binary.value(), dir + "faces"), "class"), "faceCompactList");
  EXPECT_EQ(header_entry(file(binary.value(), dir + "owner"), "note"),
            header_entry(file(text.value(), dir + "owner"), "note"));

  const auto points = binary_lists(file(binary.value(), dir + "points"), 24);
  ASSERT_EQ(points.size(), 1u);
  EXPECT_EQ(values_of<double>(points[0]), a.points);
  EXPECT_EQ(values_of<double>(points[0]), m.points);  // exact
  const auto faces = binary_lists(file(binary.value(), dir + "faces"), 4);
  ASSERT_EQ(faces.size(), 2u);
  const auto offsets = values_of<int32_t>(faces[0]), vertices = values_of<int32_t>(faces[1]);
  ASSERT_EQ(offsets.size(), a.faces.size() + 1);
  EXPECT_EQ(offsets[0], 0);
  EXPECT_EQ(size_t(offsets.back()), vertices.size());
  for (size_t f = 0; f < a.faces.size(); ++f)
    EXPECT_EQ(
        std::vector<int64_t>(vertices.begin() + offsets[f], vertices.begin() + offsets[f + 1]),
        a.faces[f])
        << f;
  for (const auto& [name, labels] :
       {std::pair{"owner", &a.owner}, std::pair{"neighbour", &a.neighbour}}) {
    const auto lists = binary_lists(file(binary.value(), dir + name), 4);
    ASSERT_EQ(lists.size(), 1u);
    const auto v = values_of<int32_t>(lists[0]);
    EXPECT_EQ(std::vector<int64_t>(v.begin(), v.end()), *labels) << name;
  }
  for (const char* f : {"constant/polyMesh/boundary", "constant/polyMesh/cellZones",
                        "constant/polyMesh/faceZones", "system/fvSchemes"})
    EXPECT_EQ(file(binary.value(), f), file(text.value(), f)) << f;
  EXPECT_NE(file(binary.value(), "system/controlDict").find("writeFormat     binary;"),
            std::string::npos);

  // One tetrahedron: no internal face, the neighbour list "0" (no brackets).
  VolumeMesh one;
  one.points = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  one.tets = {0, 1, 2, 3};
  one.tet_region = {0};
  one.triangles = {0, 2, 1, 0, 1, 3, 1, 2, 3, 0, 3, 2};
  one.triangle_tag = {0, 0, 0, 0};
  auto single = foam_case_files(one, {"wall"}, {"lumen"}, "", FoamFormat::kBinary);
  ASSERT_TRUE(single.ok()) << single.message();
  const std::string& neighbour = file(single.value(), dir + "neighbour");
  EXPECT_EQ(neighbour.substr(neighbour.find("\n}\n") + 3), "\n0\n");
  EXPECT_EQ(binary_lists(file(single.value(), dir + "owner"), 4)[0].size(), 16u);
}

TEST(FoamWriter, UnnamedTagsGetNames) {
  VolumeMesh m = testing::cube_tets(1);
  for (int32_t& t : m.triangle_tag) t = t == 0 ? 9 : 1;
  m.tet_region.assign(m.num_tets(), 2);
  auto r = foam_case_files(m, {}, {}, "");
  ASSERT_TRUE(r.ok()) << r.message();
  const PolyMesh p = read_poly_mesh(r.value());
  ASSERT_EQ(p.patches.size(), 2u);
  EXPECT_EQ(p.patches[0].name, "patch_2");
  EXPECT_EQ(p.patches[1].name, "patch_10");
  EXPECT_EQ(p.cell_zones.count("zone_3"), 1u);
}

TEST(FoamWriter, Errors) {
  const VolumeMesh cube = testing::cube_tets(1);
  VolumeMesh bad = cube;
  bad.triangles.resize(bad.triangles.size() - 3);  // one boundary face untagged
  bad.triangle_tag.pop_back();
  auto r = foam_case_files(bad, kCubeFaces, {"lumen"}, "");
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.message().find("has no surface tag"), std::string::npos) << r.message();
  EXPECT_NE(r.message().find("at ("), std::string::npos) << r.message();
  bad = cube;
  bad.points.insert(bad.points.end(), {5, 5, 5});  // a triangle through a free point
  bad.triangles.insert(bad.triangles.end(), {0, 1, int32_t(bad.num_vertices() - 1)});
  bad.triangle_tag.push_back(0);
  r = foam_case_files(bad, kCubeFaces, {"lumen"}, "");
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.message().find("a face of x0 at (0, 0, 0) is no cell's face"), std::string::npos)
      << r.message();
  bad = cube;
  bad.tets.insert(bad.tets.end(), bad.tets.begin(), bad.tets.begin() + 4);  // a face 3 times
  bad.tet_region.push_back(0);
  EXPECT_FALSE(foam_case_files(bad, kCubeFaces, {"lumen"}, "").ok());
  EXPECT_FALSE(foam_case_files(cube, {"x 0", "x1", "y0", "y1", "z0", "z1"}, {"lumen"}, "").ok());
  EXPECT_FALSE(foam_case_files(cube, {"a", "a", "y0", "y1", "z0", "z1"}, {"lumen"}, "").ok());
  bad = cube;
  bad.tet_region.pop_back();
  EXPECT_FALSE(foam_case_files(bad, kCubeFaces, {"lumen"}, "").ok());
  bad = cube;
  bad.tets[0] = 1000;
  EXPECT_FALSE(foam_case_files(bad, kCubeFaces, {"lumen"}, "").ok());
  EXPECT_FALSE(foam_case_files(VolumeMesh{}, {}, {}, "").ok());
}

}  // namespace
}  // namespace vm
