#include "core/phantom/outlets_phantom.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <numbers>
#include <set>

#include "core/geom/vec3.h"
#include "core/mesh/enclosed_volume.h"
#include "core/mesh/topology.h"
#include "core/phantom/vessel_phantom.h"

namespace vm {
namespace {

TEST(OutletsPhantom, ClosedOutwardWithEveryFaceLabelledAndTinyFlatCaps) {
  const OutletsPhantom p = make_outlets_phantom(2);
  const SurfaceMesh& m = p.mesh;
  const TopologyReport t = analyze_topology(m);
  EXPECT_EQ(t.components, 1);
  EXPECT_TRUE(t.closed);
  EXPECT_EQ(t.genus, 0);
  EXPECT_EQ(t.nonmanifold_edges, 0u);
  EXPECT_EQ(t.nonmanifold_vertices, 0u);
  // Outward, and about the tube's volume (radius 2, length 25.1, the
  // 24-gon's area) plus the branches'.
  const double length = 2 * 2 * std::numbers::pi / 24 * 48;
  const double tube = 0.5 * 24 * 4 * std::sin(2 * std::numbers::pi / 24) * length;
  const double volume = enclosed_volume(m);
  EXPECT_GT(volume, tube);
  EXPECT_LT(volume, 1.03 * tube);
  // One label per triangle, 186 faces.
  ASSERT_EQ(p.labels.size(), m.num_triangles());
  std::map<int32_t, std::vector<size_t>> faces;
  for (size_t f = 0; f < p.labels.size(); ++f) faces[p.labels[f]].push_back(f);
  EXPECT_EQ(faces.size(), size_t(kOutletsWallFaces + 2 * kOutletsBranches + 2));
  EXPECT_GE(faces.size(), 150u);
  // The caps: the last labels, flat, around their centres, facing out; the
  // branches' of 6 triangles.
  ASSERT_EQ(p.cap_centers.size(), size_t(kOutletsBranches + 2));
  const int32_t first_cap = kOutletsWallFaces + kOutletsBranches + 1;
  for (size_t c = 0; c < p.cap_centers.size(); ++c) {
    SCOPED_TRACE(c);
    const std::vector<size_t>& tris = faces[first_cap + int32_t(c)];
    EXPECT_EQ(tris.size(), p.cap_triangles[c]);
    EXPECT_EQ(tris.size(), c < 2 ? 24u : 6u);
    for (size_t f : tris) {
      const int32_t* T = &m.triangles[3 * f];
      const Vec3 a = at(m.points, T[0]), b = at(m.points, T[1]), d = at(m.points, T[2]);
      const Vec3 n = cross(b - a, d - a);
      EXPECT_GT(dot(n, p.cap_normals[c]), 0.999 * norm(n));
      for (const Vec3& x : {a, b, d}) {
        EXPECT_NEAR(dot(x - p.cap_centers[c], p.cap_normals[c]), 0, 1e-12);
        EXPECT_LE(norm(x - p.cap_centers[c]), p.cap_radii[c] * (1 + 1e-12));
      }
    }
  }
}

TEST(OutletsPhantom, IsAPhantomKindWithItsLabelsInTheTruth) {
  PhantomOptions o;
  o.kind = PhantomKind::kOutlets;
  PhantomTruth truth;
  auto r = make_vessel_phantom(o, &truth);
  ASSERT_TRUE(r.ok()) << r.message();
  EXPECT_EQ(truth.face_labels.size(), r.value().num_triangles());
  EXPECT_EQ(truth.openings, 0);
  EXPECT_EQ(truth.opening_centers.size(), size_t(kOutletsBranches + 2));
  EXPECT_EQ(std::set<int32_t>(truth.face_labels.begin(), truth.face_labels.end()).size(), 186u);
}

}  // namespace
}  // namespace vm
