#include "core/pipeline/size_preview.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/io/stl.h"
#include "core/phantom/vessel_phantom.h"
#include "core/surface/size_field.h"

namespace vm {
namespace {

/// A bifurcation phantom (parent radius 1, noisy staircase) through the
/// job's preparation, with what the generator knows of it.
PreparedSurface prepared_bifurcation(PhantomTruth& truth) {
  PhantomOptions o;
  o.kind = PhantomKind::kBifurcation;
  o.voxel = 0.08;
  o.noise = 0.3;
  auto m = make_vessel_phantom(o, &truth);
  EXPECT_TRUE(m.ok()) << m.message();
  const std::vector<uint8_t> stl = write_stl_binary(m.value(), "phantom");
  auto p = prepare_surface(stl, PrepareOptions{});
  EXPECT_TRUE(p.ok()) << p.message();
  return p.ok() ? std::move(p).value() : PreparedSurface{};
}

double median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + long(v.size() / 2), v.end());
  return v[v.size() / 2];
}

/// The default mesh options with one refinement sphere.
MeshJobOptions refining(const RefineSphere& sphere) {
  MeshJobOptions o;
  o.remesh_options.size.spheres = {sphere};
  return o;
}

TEST(SizePreview, RadiusIsThePhantomsNearEachVesselEnd) {
  PhantomTruth truth;
  const PreparedSurface s = prepared_bifurcation(truth);
  auto p = size_preview(s, MeshJobOptions{});
  ASSERT_TRUE(p.ok()) << p.message();
  ASSERT_EQ(p.value().radius.size(), s.mesh.num_vertices());
  ASSERT_EQ(truth.end_tips.size(), truth.end_radii.size());
  ASSERT_EQ(truth.opening_centers.size(), 3u);
  for (size_t e = 0; e < truth.opening_centers.size(); ++e) {
    // Vertices of the tube between 0.5 and 2 radii in from the opening's
    // cut (away from the rim, before the branches meet).
    const auto& c = truth.opening_centers[e];
    const double r_true = truth.opening_radii[e];
    // The end whose tip is nearest this opening gives the vessel's direction.
    size_t end = 0;
    double best = 1e300;
    for (size_t k = 0; k < truth.end_tips.size(); ++k) {
      double d = 0;
      for (int i = 0; i < 3; ++i) d += std::pow(truth.end_tips[k][size_t(i)] - c[size_t(i)], 2);
      if (d < best) best = d, end = k;
    }
    const auto& dir = truth.end_directions[end];
    std::vector<double> near;
    for (size_t v = 0; v < s.mesh.num_vertices(); ++v) {
      const double* x = &s.mesh.points[3 * v];
      double axial = 0, d2 = 0;
      for (int i = 0; i < 3; ++i) {
        axial += (x[i] - c[size_t(i)]) * dir[size_t(i)];
        d2 += std::pow(x[i] - c[size_t(i)], 2);
      }
      const double radial = std::sqrt(std::max(0.0, d2 - axial * axial));
      if (axial < -0.5 * r_true && axial > -2 * r_true && radial < 1.5 * r_true)
        near.push_back(p.value().radius[v]);
    }
    ASSERT_GT(near.size(), 20u) << "opening " << e;
    EXPECT_NEAR(median(near), r_true, 0.1 * r_true) << "opening " << e;
  }
}

TEST(SizePreview, PerCircumferenceSizeIsTwoPiROverN) {
  PhantomTruth truth;
  const PreparedSurface s = prepared_bifurcation(truth);
  MeshJobOptions o;
  o.remesh_options.size.per_circumference = 16;
  o.remesh_options.size.gradation = 0;  // the base size itself
  auto p = size_preview(s, o);
  ASSERT_TRUE(p.ok()) << p.message();
  const SizePreview& v = p.value();
  ASSERT_EQ(v.size.size(), s.mesh.num_vertices());
  for (size_t i = 0; i < v.size.size(); ++i)
    ASSERT_NEAR(v.size[i], 2 * std::numbers::pi * v.radius[i] / 16, 1e-12 * v.radius[i]) << i;
  // With the default gradation the size is only ever lowered.
  o.remesh_options.size.gradation = 0.2;
  auto graded = size_preview(s, o);
  ASSERT_TRUE(graded.ok());
  for (size_t i = 0; i < v.size.size(); ++i)
    EXPECT_LE(graded.value().size[i], v.size[i] * (1 + 1e-12));
}

TEST(SizePreview, IsTheFieldTheRemeshingAsksFor) {
  PhantomTruth truth;
  const PreparedSurface s = prepared_bifurcation(truth);
  MeshJobOptions o;
  o.remesh_options.size.size_max = 0.3;
  o.remesh_options.size.curvature_points = 4;
  auto p = size_preview(s, o);
  ASSERT_TRUE(p.ok()) << p.message();
  // vertex_sizes as remesh_surface calls it (its own radius).
  auto asked = vertex_sizes(s.mesh, o.remesh_options.size);
  ASSERT_TRUE(asked.ok());
  EXPECT_EQ(p.value().size, asked.value());
  for (double h : p.value().size) EXPECT_LE(h, 0.3);
}

TEST(SizePreview, RefinementSphereBoundsTheSizeInsideIt) {
  PhantomTruth truth;
  const PreparedSurface s = prepared_bifurcation(truth);
  // Radius 1.5: the rim is about 1 from the opening's centre.
  const RefineSphere sphere{truth.opening_centers[0], 1.5, 0.03};
  auto p = size_preview(s, refining(sphere));
  ASSERT_TRUE(p.ok()) << p.message();
  auto plain = size_preview(s, MeshJobOptions{});
  ASSERT_TRUE(plain.ok());
  size_t inside = 0;
  for (size_t v = 0; v < s.mesh.num_vertices(); ++v) {
    const double* x = &s.mesh.points[3 * v];
    const double d =
        std::hypot(x[0] - sphere.center[0], x[1] - sphere.center[1], x[2] - sphere.center[2]);
    if (d <= sphere.radius) {
      ++inside;
      EXPECT_LE(p.value().size[v], sphere.size * (1 + 1e-12));
    }
    EXPECT_LE(p.value().size[v], plain.value().size[v] * (1 + 1e-12));
    EXPECT_EQ(p.value().radius[v], plain.value().radius[v]);  // R knows no sphere
  }
  EXPECT_GT(inside, 10u);
  EXPECT_NEAR(*std::min_element(p.value().size.begin(), p.value().size.end()), sphere.size, 1e-12);
}

TEST(SizePreview, RefusesWhatTheJobRefuses) {
  PhantomTruth truth;
  const PreparedSurface s = prepared_bifurcation(truth);
  auto p = size_preview(s, refining({truth.opening_centers[0], 0.5, 1e-9}));
  ASSERT_FALSE(p.ok());
  EXPECT_EQ(p.status().kind(), ErrorKind::kBadOption);
  EXPECT_EQ(p.status().option(), "refine");
  MeshJobOptions bad;
  bad.remesh_options.size.per_circumference = 2;
  auto q = size_preview(s, bad);
  ASSERT_FALSE(q.ok());
  EXPECT_EQ(q.status().option(), "per_circumference");
}

}  // namespace
}  // namespace vm
