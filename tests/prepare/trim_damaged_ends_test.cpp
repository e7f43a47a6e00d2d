#include "core/prepare/trim_damaged_ends.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/io/stl.h"
#include "core/mesh/repair.h"
#include "core/mesh/self_intersection.h"
#include "core/phantom/dirty_phantom.h"
#include "core/pipeline/prepare_surface.h"
#include "tests/support/phantoms.h"

namespace vm {
namespace {

/// The bifurcation with damaged ends, and what the damage was.
SurfaceMesh damaged_bifurcation(std::vector<DamagedEnd>* damage, PhantomTruth* truth) {
  PhantomOptions o;
  o.kind = PhantomKind::kBifurcation;
  o.voxel = 0.12;
  SurfaceMesh m = testing::phantom(o, truth);
  *damage = add_damaged_ends(m, 3);
  return m;
}

TEST(TrimDamagedEnds, RepairOffKeepsTheRefusal) {
  std::vector<DamagedEnd> damage;
  PhantomTruth truth;
  const SurfaceMesh m = damaged_bifurcation(&damage, &truth);
  ASSERT_EQ(damage.size(), 3u);
  PrepareOptions off;
  off.repair = false;
  auto r = prepare_surface(write_stl_binary(m), off);
  ASSERT_TRUE(r.ok()) << r.message();
  EXPECT_FALSE(check_meshable(r.value()).ok());
  EXPECT_GT(r.value().self_crossings.pairs, 0u);
  EXPECT_TRUE(r.value().trimmed_ends.empty());
}

TEST(TrimDamagedEnds, EachEndIsCutFlatJustBelowItsDamage) {
  std::vector<DamagedEnd> damage;
  PhantomTruth truth;
  const SurfaceMesh m = damaged_bifurcation(&damage, &truth);
  auto r = prepare_surface(write_stl_binary(m));
  ASSERT_TRUE(r.ok()) << r.message();
  const PreparedSurface& s = r.value();
  EXPECT_TRUE(check_meshable(s).ok()) << check_meshable(s).message();
  EXPECT_EQ(s.self_crossings.pairs, 0u);
  ASSERT_EQ(s.trimmed_ends.size(), 3u);
  ASSERT_EQ(s.topology.openings.size(), 3u);
  EXPECT_TRUE(s.holes.empty() ||
              std::all_of(s.holes.begin(), s.holes.end(), [](const Hole& h) { return h.closed; }));
  for (size_t i = 0; i < s.topology.openings.size(); ++i) {
    const Opening& op = s.topology.openings[i];
    EXPECT_EQ(s.opening_sources[i].kind, OpeningSource::kClip);
    // Which damaged end it replaces: the nearest.
    const DamagedEnd* d = &damage[0];
    for (const DamagedEnd& e : damage)
      if (norm(Vec3(op.centroid) - Vec3(e.center)) < norm(Vec3(op.centroid) - Vec3(d->center)))
        d = &e;
    const Vec3 axis = d->axis;
    const double in = dot(Vec3(d->center) - Vec3(op.centroid), axis);
    EXPECT_GT(in, d->depth) << "the cut lies below the damage";
    EXPECT_LT(in, d->depth + 1.5 * d->radius) << "no deeper than needed";
    EXPECT_NEAR(op.radius, d->radius, 0.1 * d->radius);
    // Flat: every rim vertex on one plane, across the vessel.
    const Vec3 n = op.normal;
    EXPECT_GT(std::abs(dot(n, axis)), std::cos(20 * 3.14159 / 180));
    for (int32_t v : op.loop)
      EXPECT_NEAR(dot(at(s.mesh.points, v) - Vec3(op.centroid), n), 0, 1e-6 * d->radius);
  }
  for (const std::string& w : s.warnings) {
    if (w.find("damaged") != std::string::npos) {
      EXPECT_NE(w.find("trimmed back"), std::string::npos) << w;
    }
  }
}

TEST(TrimDamagedEnds, LeavesCleanEndsAlone) {
  SurfaceMesh m = testing::phantom(PhantomKind::kBifurcation, true, 0.12);
  const SurfaceMesh before = m;
  const std::vector<TrimmedEnd> ends = trim_damaged_ends(m, nullptr, {});
  EXPECT_TRUE(ends.empty());
  EXPECT_EQ(m.triangles, before.triangles);
}

}  // namespace
}  // namespace vm
