#include "core/mesh/volume_check.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <numeric>
#include <set>
#include <vector>

#include "core/mesh/prism_split.h"

namespace vm {
namespace {

// The reference prism: bottom (0,0,0) (1,0,0) (0,1,0), top one unit up.
const double kPrism[6][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {0, 1, 1}};

TEST(PrismSplit, EveryNumberingGivesThreePositiveTetsFillingThePrism) {
  std::array<int32_t, 6> ids = {0, 1, 2, 3, 4, 5};
  int permutations = 0;
  do {
    // Vertex k of the prism gets id ids[k]; points indexed by id.
    std::vector<double> pts(18);
    for (int k = 0; k < 6; ++k)
      for (int d = 0; d < 3; ++d) pts[3 * size_t(ids[size_t(k)]) + size_t(d)] = kPrism[k][d];
    double total = 0;
    for (const auto& t : split_prism(ids.data())) {
      const double v6 = tet_volume6(&pts[3 * size_t(t[0])], &pts[3 * size_t(t[1])],
                                    &pts[3 * size_t(t[2])], &pts[3 * size_t(t[3])]);
      ASSERT_GT(v6, 0);
      total += v6 / 6;
    }
    EXPECT_NEAR(total, 0.5, 1e-15);
    ++permutations;
  } while (std::next_permutation(ids.begin(), ids.end()));
  EXPECT_EQ(permutations, 720);
}

TEST(PrismSplit, NeighborsCutTheirSharedQuadTheSameWay) {
  // Two prisms side by side sharing the quad (1, 2, 5, 4) of the first:
  // whatever the numbering, both choose the same diagonal of it.
  for (uint32_t seed = 1; seed < 200; ++seed) {
    std::vector<int32_t> id(8);
    std::iota(id.begin(), id.end(), 0);
    uint32_t s = seed;
    for (size_t i = id.size(); i > 1; --i) {
      s = s * 1664525u + 1013904223u;
      std::swap(id[i - 1], id[(s >> 8) % i]);
    }
    // Prism A: bottom 0 1 2, top 3 4 5. Prism B across quad (1,2,5,4): bottom
    // 2 1 6, top 5 4 7 (mirror, still positive orientation).
    const int32_t a[6] = {id[0], id[1], id[2], id[3], id[4], id[5]};
    const int32_t b[6] = {id[2], id[1], id[6], id[5], id[4], id[7]};
    const std::set<int32_t> quad = {id[1], id[2], id[5], id[4]};
    auto diagonal = [&](const int32_t* p) {
      // The edge of the split lying in the quad and joining opposite corners.
      std::set<std::pair<int32_t, int32_t>> found;
      for (const auto& t : split_prism(p))
        for (int i = 0; i < 4; ++i)
          for (int j = i + 1; j < 4; ++j)
            if (quad.count(t[size_t(i)]) && quad.count(t[size_t(j)])) {
              const auto e = std::minmax(t[size_t(i)], t[size_t(j)]);
              const bool side =
                  (e.first == id[1] && e.second == id[2]) ||
                  (e.first == std::min(id[2], id[5]) && e.second == std::max(id[2], id[5])) ||
                  (e.first == std::min(id[5], id[4]) && e.second == std::max(id[5], id[4])) ||
                  (e.first == std::min(id[4], id[1]) && e.second == std::max(id[4], id[1])) ||
                  (e.first == std::min(id[1], id[2]) && e.second == std::max(id[1], id[2]));
              if (!side) found.insert(e);
            }
      return found;
    };
    const auto da = diagonal(a), db = diagonal(b);
    ASSERT_EQ(da.size(), 1u);
    EXPECT_EQ(da, db) << "seed " << seed;
  }
}

// The unit cube as 6 tetrahedra around the diagonal 0-7, with its 12
// boundary triangles oriented outward.
VolumeMesh cube() {
  VolumeMesh m;
  for (int z = 0; z < 2; ++z)
    for (int y = 0; y < 2; ++y)
      for (int x = 0; x < 2; ++x)
        m.points.insert(m.points.end(), {double(x), double(y), double(z)});
  // Vertex id = x + 2y + 4z. Paths 0 -> 7 through the cube's edges.
  const int32_t paths[6][2] = {{1, 3}, {1, 5}, {2, 3}, {2, 6}, {4, 5}, {4, 6}};
  for (const auto& p : paths) {
    int32_t t[4] = {0, p[0], p[1], 7};
    if (tet_volume6(&m.points[3 * size_t(t[0])], &m.points[3 * size_t(t[1])],
                    &m.points[3 * size_t(t[2])], &m.points[3 * size_t(t[3])]) < 0)
      std::swap(t[1], t[2]);
    m.tets.insert(m.tets.end(), t, t + 4);
    m.tet_region.push_back(0);
  }
  // Boundary: the faces used once, oriented like their tetrahedron's.
  const auto& f = kFaceOut;
  std::vector<std::array<int32_t, 3>> faces;
  for (size_t e = 0; e < m.num_tets(); ++e)
    for (const auto& k : f)
      faces.push_back({m.tets[4 * e + size_t(k[0])], m.tets[4 * e + size_t(k[1])],
                       m.tets[4 * e + size_t(k[2])]});
  for (const auto& a : faces) {
    std::array<int32_t, 3> sa = a;
    std::sort(sa.begin(), sa.end());
    int count = 0;
    for (const auto& b : faces) {
      std::array<int32_t, 3> sb = b;
      std::sort(sb.begin(), sb.end());
      count += sa == sb;
    }
    if (count == 1) {
      m.triangles.insert(m.triangles.end(), a.begin(), a.end());
      m.triangle_tag.push_back(0);
    }
  }
  return m;
}

TEST(VolumeCheck, AcceptsAValidCubeAndMeasuresIt) {
  const VolumeMesh m = cube();
  ASSERT_EQ(m.num_triangles(), 12u);
  auto c = check_volume_mesh(m);
  ASSERT_TRUE(c.ok()) << c.message();
  EXPECT_EQ(c.value().boundary_faces, 12u);
  EXPECT_NEAR(c.value().volume, 1.0, 1e-15);
  EXPECT_GT(c.value().min_volume6, 0);
}

TEST(VolumeCheck, FindsEachKindOfDefect) {
  {
    VolumeMesh m = cube();
    std::swap(m.tets[1], m.tets[2]);  // inverted
    auto c = check_volume_mesh(m);
    ASSERT_FALSE(c.ok());
    EXPECT_NE(c.message().find("inverted"), std::string::npos) << c.message();
  }
  {
    VolumeMesh m = cube();
    m.triangles.resize(m.triangles.size() - 3);  // a hole in the boundary
    auto c = check_volume_mesh(m);
    ASSERT_FALSE(c.ok());
    EXPECT_NE(c.message().find("not a surface triangle"), std::string::npos) << c.message();
  }
  {
    VolumeMesh m = cube();
    std::swap(m.triangles[0], m.triangles[1]);  // one triangle facing inward
    auto c = check_volume_mesh(m);
    ASSERT_FALSE(c.ok());
    EXPECT_NE(c.message().find("inward"), std::string::npos) << c.message();
  }
  {
    VolumeMesh m = cube();
    m.tets.insert(m.tets.end(), m.tets.begin(), m.tets.begin() + 4);  // a tet twice
    m.tet_region.push_back(0);
    auto c = check_volume_mesh(m);
    ASSERT_FALSE(c.ok());
    EXPECT_NE(c.message().find("overlap"), std::string::npos) << c.message();
  }
}

TEST(VolumeCheck, PrismsAreCheckedByTheirFacesAndSplit) {
  // Two stacked prisms: their side quads are boundary faces that no surface
  // triangle matches (only the two end triangles are listed), which the
  // check reports.
  VolumeMesh m;
  for (int z = 0; z < 3; ++z)
    for (const auto& p : {std::array<double, 2>{0, 0}, {1, 0}, {0, 1}})
      m.points.insert(m.points.end(), {p[0], p[1], double(z)});
  m.prisms = {0, 1, 2, 3, 4, 5, 3, 4, 5, 6, 7, 8};
  m.prism_region = {0, 0};
  m.triangles = {0, 2, 1, 6, 7, 8};
  m.triangle_tag = {0, 0};
  auto c = check_volume_mesh(m);
  ASSERT_FALSE(c.ok());
  EXPECT_NE(c.message().find("not a surface triangle"), std::string::npos) << c.message();
  // An inverted prism is found through its split.
  std::swap(m.prisms[1], m.prisms[2]);
  c = check_volume_mesh(m);
  ASSERT_FALSE(c.ok());
  EXPECT_NE(c.message().find("prism 0"), std::string::npos) << c.message();
}

}  // namespace
}  // namespace vm
