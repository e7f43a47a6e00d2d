#include "core/surface/cap_openings.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <iostream>
#include <map>
#include <numbers>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "core/mesh/enclosed_volume.h"
#include "core/mesh/self_intersection.h"
#include "core/mesh/surface_distance.h"
#include "core/mesh/topology.h"
#include "core/phantom/vessel_phantom.h"
#include "core/quality/triangle_quality.h"
#include "core/surface/remesh_surface.h"
#include "tests/support/phantoms.h"
#include "tests/support/remesh_options.h"
#include "tests/support/test_meshes.h"

namespace vm {
namespace {

constexpr double kPi = std::numbers::pi;
using Curve = std::function<std::array<double, 3>(double)>;

// A tube between two closed curves (functions of the angle theta): ring j
// of m + 1 interpolates linearly from `bottom` to `top`, n vertices per ring
// at theta = 2 pi (i + 1/2) / n. Outward oriented when both curves turn
// counterclockwise around +z, like testing::open_tube.
SurfaceMesh tube_between(int n, int m, const Curve& bottom, const Curve& top) {
  SurfaceMesh s;
  for (int j = 0; j <= m; ++j)
    for (int i = 0; i < n; ++i) {
      const double t = 2 * kPi * (i + 0.5) / n, f = double(j) / m;
      const auto a = bottom(t), b = top(t);
      s.points.insert(s.points.end(), {(1 - f) * a[0] + f * b[0], (1 - f) * a[1] + f * b[1],
                                       (1 - f) * a[2] + f * b[2]});
    }
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < n; ++i) {
      const int32_t a = j * n + i, b = j * n + (i + 1) % n, c = a + n, d = b + n;
      s.triangles.insert(s.triangles.end(), {a, b, d, a, d, c});
    }
  return s;
}

Curve circle(double r, double z) {
  return [=](double t) { return std::array<double, 3>{r * std::cos(t), r * std::sin(t), z}; };
}

// A straight tube of radius r and length len with rings about equilateral.
SurfaceMesh straight_tube(int n, double r, double len) {
  const double edge = 2 * r * std::sin(kPi / n);
  const int m = std::max(1, int(std::round(len / (edge * std::sqrt(3.0) / 2))));
  return tube_between(n, m, circle(r, 0), circle(r, len));
}

const double* pt(const SurfaceMesh& m, int32_t v) { return &m.points[3 * size_t(v)]; }

struct CapQuality {
  double min = 1;         // over all cap triangles
  double worst_mean = 1;  // the lowest per-cap mean
  double mean = 0;        // over all cap triangles
};

// Checks the contract of cap_openings on `r` for input `wall`; returns the
// worst cap quality.
CapQuality check_capped(const SurfaceMesh& wall, const CappedSurface& r, const CapOptions& opt,
                        const std::string& name) {
  SCOPED_TRACE(name);
  CapQuality worst;
  const SurfaceMesh& m = r.mesh;
  const double diag = bounding_box(m.points).diagonal();
  EXPECT_EQ(r.wall_vertices, wall.num_vertices());
  EXPECT_EQ(r.wall_triangles, wall.num_triangles());
  EXPECT_EQ(r.triangle_tag.size(), m.num_triangles());
  // The wall keeps its triangles; only rim vertices move, by at most the
  // reported projection distance.
  EXPECT_TRUE(std::equal(wall.triangles.begin(), wall.triangles.end(), m.triangles.begin()));
  std::map<int32_t, size_t> rim_cap;  // rim vertex -> cap
  for (size_t c = 0; c < r.caps.size(); ++c)
    for (int32_t v : r.caps[c].rim) EXPECT_TRUE(rim_cap.emplace(v, c).second) << "vertex " << v;
  for (size_t v = 0; v < wall.num_vertices(); ++v) {
    const double d = std::sqrt(std::pow(pt(m, int32_t(v))[0] - pt(wall, int32_t(v))[0], 2) +
                               std::pow(pt(m, int32_t(v))[1] - pt(wall, int32_t(v))[1], 2) +
                               std::pow(pt(m, int32_t(v))[2] - pt(wall, int32_t(v))[2], 2));
    auto it = rim_cap.find(int32_t(v));
    if (it == rim_cap.end())
      EXPECT_EQ(d, 0.0) << "non-rim vertex " << v << " moved";
    else
      EXPECT_LE(d, r.caps[it->second].max_projection_distance + 1e-12 * diag);
  }
  for (size_t t = 0; t < r.wall_triangles; ++t) EXPECT_EQ(r.triangle_tag[t], 0);

  // Closed and consistently oriented: every directed edge once, with its
  // reverse.
  std::map<std::pair<int32_t, int32_t>, int> directed;
  for (size_t t = 0; t < m.num_triangles(); ++t)
    for (int k = 0; k < 3; ++k)
      ++directed[{m.triangles[3 * t + k], m.triangles[3 * t + (k + 1) % 3]}];
  size_t bad = 0;
  for (const auto& [e, count] : directed)
    if (count != 1 || !directed.count({e.second, e.first})) ++bad;
  EXPECT_EQ(bad, 0u) << "edges not shared by exactly two consistently oriented triangles";
  const TopologyReport topo = analyze_topology(m);
  EXPECT_TRUE(topo.closed);
  EXPECT_EQ(topo.nonmanifold_edges, 0u);
  EXPECT_EQ(topo.nonmanifold_vertices, 0u);
  EXPECT_EQ(topo.components, 1);
  EXPECT_GT(enclosed_volume(m), 0.0) << "not outward oriented";
  const SelfIntersectionReport si = find_self_intersections(m);
  EXPECT_EQ(si.pairs, 0u);
  EXPECT_EQ(si.degenerate_triangles, 0u);

  // Caps: names, tags, order, planarity, orientation, rim sharing.
  EXPECT_EQ(r.caps.size(), analyze_topology(wall).openings.size());
  std::vector<double> areas;
  for (const CapInfo& c : r.caps) areas.push_back(c.area);
  std::vector<double> sorted = areas;
  std::sort(sorted.rbegin(), sorted.rend());
  size_t next_vertex = wall.num_vertices(), next_triangle = wall.num_triangles();
  size_t cap_triangles = 0;
  for (size_t c = 0; c < r.caps.size(); ++c) {
    const CapInfo& info = r.caps[c];
    SCOPED_TRACE(info.name);
    EXPECT_EQ(info.tag, int32_t(c + 1));
    EXPECT_EQ(info.name, c == 0 ? std::string("inlet") : "outlet_" + std::to_string(c));
    if (c == 0) {
      EXPECT_NEAR(info.area, sorted[size_t(opt.inlet_index)], 1e-9 * sorted[0]);
    } else {
      // Outlets: decreasing area, skipping the inlet.
      const size_t rank = c - 1 < size_t(opt.inlet_index) ? c - 1 : c;
      EXPECT_NEAR(info.area, sorted[rank], 1e-9 * sorted[0]);
    }
    EXPECT_GE(info.rim.size(), 3u);
    EXPECT_EQ(info.first_triangle, next_triangle);
    next_triangle += info.triangles;
    EXPECT_NEAR(std::hypot(info.normal[0], info.normal[1], info.normal[2]), 1.0, 1e-12);
    const std::set<int32_t> rim(info.rim.begin(), info.rim.end());
    std::set<int32_t> interior;
    double area = 0, gsum = 0, gmin = 1;
    for (size_t t = info.first_triangle; t < info.first_triangle + info.triangles; ++t) {
      EXPECT_EQ(r.triangle_tag[t], info.tag);
      const int32_t* v = &m.triangles[3 * t];
      for (int k = 0; k < 3; ++k) {
        if (size_t(v[k]) < wall.num_vertices())
          EXPECT_TRUE(rim.count(v[k])) << "cap uses wall vertex " << v[k] << " off its rim";
        else
          interior.insert(v[k]);
        // Planar to 1e-9 of the diagonal.
        const double* p = pt(m, v[k]);
        const double h = (p[0] - info.centroid[0]) * info.normal[0] +
                         (p[1] - info.centroid[1]) * info.normal[1] +
                         (p[2] - info.centroid[2]) * info.normal[2];
        EXPECT_LE(std::abs(h), 1e-9 * diag);
      }
      const double *a = pt(m, v[0]), *b = pt(m, v[1]), *cc = pt(m, v[2]);
      const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
      const double w[3] = {cc[0] - a[0], cc[1] - a[1], cc[2] - a[2]};
      const double n[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2],
                           u[0] * w[1] - u[1] * w[0]};
      const double along = n[0] * info.normal[0] + n[1] * info.normal[1] + n[2] * info.normal[2];
      EXPECT_GT(along, 0) << "cap triangle " << t << " faces inward";
      area += 0.5 * along;
      const double g = triangle_gamma(a, b, cc);
      gsum += g;
      gmin = std::min(gmin, g);
    }
    EXPECT_NEAR(area, info.area, 1e-9 * info.area);
    EXPECT_EQ(interior.size(), info.interior_vertices);
    if (!interior.empty()) {
      EXPECT_EQ(size_t(*interior.begin()), next_vertex);
      EXPECT_EQ(size_t(*interior.rbegin()), next_vertex + interior.size() - 1);
    }
    next_vertex += interior.size();
    // Every rim vertex of the rim is used by the cap (no rim edge split).
    for (size_t j = 0; j < info.rim.size(); ++j) {
      const int32_t a = info.rim[j], b = info.rim[(j + 1) % info.rim.size()];
      EXPECT_EQ(directed.count({b, a}), 1u) << "rim edge " << j << " not closed by the cap";
    }
    const double mean = gsum / double(info.triangles);
    EXPECT_NEAR(info.quality_min, gmin, 1e-12);
    EXPECT_NEAR(info.quality_mean, mean, 1e-12);
    EXPECT_EQ(info.flipped_wall_triangles, 0u);
    worst.min = std::min(worst.min, gmin);
    worst.worst_mean = std::min(worst.worst_mean, mean);
    worst.mean += gsum;
    cap_triangles += info.triangles;
    std::cout << "[ info ] " << name << " " << info.name << ": area " << info.area << ", "
              << info.rim.size() << " rim + " << info.interior_vertices << " interior vertices, "
              << info.triangles << " triangles, gamma min " << gmin << " mean " << mean
              << ", max projection " << info.max_projection_distance << "\n";
  }
  EXPECT_EQ(next_vertex, m.num_vertices());
  EXPECT_EQ(next_triangle, m.num_triangles());
  if (cap_triangles > 0) worst.mean /= double(cap_triangles);
  return worst;
}

TEST(CapOpenings, StraightTubeIsClosedByTwoDisks) {
  const double r = 1.0, len = 4.0;
  const int n = 48;
  const SurfaceMesh wall = straight_tube(n, r, len);
  auto res = cap_openings(wall, {});
  ASSERT_TRUE(res.ok()) << res.message();
  const CappedSurface& c = res.value();
  const CapQuality q = check_capped(wall, c, {}, "tube");
  ASSERT_EQ(c.caps.size(), 2u);
  // Equal areas: the tie goes to the rim with the smallest vertex id (z = 0).
  EXPECT_NEAR(c.caps[0].normal[2], -1.0, 1e-12);
  EXPECT_NEAR(c.caps[1].normal[2], 1.0, 1e-12);
  EXPECT_NEAR(c.caps[0].centroid[2], 0.0, 1e-12);
  EXPECT_NEAR(c.caps[1].centroid[2], len, 1e-12);
  EXPECT_NEAR(std::hypot(c.caps[1].centroid[0], c.caps[1].centroid[1]), 0.0, 1e-12);
  for (const CapInfo& cap : c.caps) {
    EXPECT_LE(cap.max_projection_distance, 1e-14);
    EXPECT_EQ(cap.rim.size(), size_t(n));
    EXPECT_NEAR(cap.perimeter, 2 * n * r * std::sin(kPi / n), 1e-12);
  }
  // The tube's quads are planar, so the capped tube is exactly the prism on
  // the inscribed n-gon; within discretization error of pi r^2 L.
  const double polygon = 0.5 * n * r * r * std::sin(2 * kPi / n);
  const double v = enclosed_volume(c.mesh);
  EXPECT_NEAR(v, polygon * len, 1e-12 * polygon * len);
  EXPECT_NEAR(v, kPi * r * r * len, 0.005 * kPi * r * r * len);
  EXPECT_NEAR(c.caps[0].area, polygon, 1e-12);
  // Quality of a cap on a circular opening (seed Table 1, frontal row:
  // min 0.55, mean 0.978 for the wall).
  EXPECT_GE(q.min, 0.55);
  EXPECT_GE(q.worst_mean, 0.97);
}

TEST(CapOpenings, NamesFollowAreaAndInletIndexIsHonored) {
  // A frustum: the bottom opening (r = 1) is larger than the top (r = 0.6).
  const SurfaceMesh wall = tube_between(40, 30, circle(1.0, 0), circle(0.6, 3.0));
  auto a = cap_openings(wall, {});
  ASSERT_TRUE(a.ok()) << a.message();
  check_capped(wall, a.value(), {}, "frustum");
  EXPECT_EQ(a.value().caps[0].name, "inlet");
  EXPECT_NEAR(a.value().caps[0].centroid[2], 0.0, 1e-12);
  EXPECT_NEAR(a.value().caps[1].centroid[2], 3.0, 1e-12);
  EXPECT_GT(a.value().caps[0].area, a.value().caps[1].area);

  CapOptions o;
  o.inlet_index = 1;
  auto b = cap_openings(wall, {}, o);
  ASSERT_TRUE(b.ok()) << b.message();
  check_capped(wall, b.value(), o, "frustum, inlet_index 1");
  EXPECT_EQ(b.value().caps[0].name, "inlet");
  EXPECT_EQ(b.value().caps[1].name, "outlet_1");
  EXPECT_NEAR(b.value().caps[0].centroid[2], 3.0, 1e-12);  // the small one
  EXPECT_NEAR(b.value().caps[1].centroid[2], 0.0, 1e-12);
  EXPECT_EQ(b.value().caps[0].area, a.value().caps[1].area);
}

TEST(CapOpenings, NonPlanarRimsAreProjectedAndReported) {
  // Top rim waves by +-0.05 around z = 3 (sin 3 theta: best plane z = 3);
  // bottom rim lies exactly in the tilted plane z = 0.5 y.
  const double amp = 0.05;
  Curve wavy = [=](double t) {
    return std::array<double, 3>{std::cos(t), std::sin(t), 3.0 + amp * std::sin(3 * t)};
  };
  Curve tilted = [](double t) {
    return std::array<double, 3>{std::cos(t), std::sin(t), 0.5 * std::sin(t)};
  };
  const SurfaceMesh wall = tube_between(48, 30, tilted, wavy);
  auto res = cap_openings(wall, {});
  ASSERT_TRUE(res.ok()) << res.message();
  const CappedSurface& c = res.value();
  check_capped(wall, c, {}, "wavy and tilted rims");
  // The tilted ellipse (area pi * 1 * sqrt(1.25)) is larger: the inlet.
  const CapInfo& tilted_cap = c.caps[0];
  const CapInfo& wavy_cap = c.caps[1];
  EXPECT_LE(tilted_cap.max_projection_distance, 1e-14);
  const double s = std::sqrt(1.25);
  EXPECT_NEAR(tilted_cap.normal[0], 0.0, 1e-12);
  EXPECT_NEAR(tilted_cap.normal[1], 0.5 / s, 1e-12);
  EXPECT_NEAR(tilted_cap.normal[2], -1.0 / s, 1e-12);
  EXPECT_NEAR(wavy_cap.normal[2], 1.0, 1e-12);
  double sampled = 0;  // the largest |sin 3 theta| at the rim samples
  for (int i = 0; i < 48; ++i)
    sampled = std::max(sampled, std::abs(std::sin(3 * 2 * kPi * (i + 0.5) / 48)));
  EXPECT_NEAR(wavy_cap.max_projection_distance, amp * sampled, 1e-12);
  EXPECT_NEAR(wavy_cap.centroid[2], 3.0, 1e-12);
}

TEST(CapOpenings, RemeshedBifurcationGetsThreeNamedCaps) {
  PhantomTruth truth;
  const SurfaceMesh in = testing::noisy_bifurcation(0.15, &truth);
  ASSERT_EQ(truth.openings, 3);
  const double h = 0.2;
  auto remeshed = remesh_surface(in, testing::uniform_remesh(h));
  ASSERT_TRUE(remeshed.ok()) << remeshed.message();
  const SurfaceMesh& wall = remeshed.value().mesh;
  const std::vector<double> sizes(wall.num_vertices(), h);
  auto res = cap_openings(wall, sizes);
  ASSERT_TRUE(res.ok()) << res.message();
  const CappedSurface& c = res.value();
  const CapQuality q = check_capped(wall, c, {}, "bifurcation");
  ASSERT_EQ(c.caps.size(), 3u);
  EXPECT_EQ(c.caps[2].name, "outlet_2");
  // The caps are the phantom's openings, largest truth radius = inlet.
  std::vector<double> truth_radius;
  for (const CapInfo& cap : c.caps) {
    const size_t k = testing::nearest_truth_opening(truth, cap.centroid.data());
    truth_radius.push_back(truth.opening_radii[k]);
    EXPECT_NEAR(std::sqrt(cap.area / kPi), truth.opening_radii[k], 0.15 * truth.opening_radii[k]);
  }
  EXPECT_GE(truth_radius[0], truth_radius[1]);
  EXPECT_GE(truth_radius[1], truth_radius[2]);
  // The wall stays on the input surface (rims within their projection).
  double max_projection = 0;
  for (const CapInfo& cap : c.caps)
    max_projection = std::max(max_projection, cap.max_projection_distance);
  const std::vector<double> wall_points(c.mesh.points.begin(),
                                        c.mesh.points.begin() + 3 * long(c.wall_vertices));
  const DistanceReport d = distances_to_surface(in, wall_points);
  EXPECT_LE(d.max, max_projection + 1e-6 * bounding_box(in.points).diagonal());
  EXPECT_LT(max_projection, 0.5 * h);
  // Small rims (about 20 vertices) lower the mean: a larger share of the
  // triangles touches the fixed rim.
  EXPECT_GE(q.min, 0.55);
  EXPECT_GE(q.worst_mean, 0.93);
  EXPECT_GE(q.mean, 0.96);
  std::cout << "[ info ] bifurcation caps: gamma min " << q.min << ", mean " << q.mean << "\n";
}

TEST(CapOpenings, AneurysmAtPerCircumferenceSizes) {
  // The pipeline's default: h = 2 pi R / 20 from the vessel radius.
  const SurfaceMesh in = testing::phantom(PhantomKind::kAneurysm, true, 0.12, 0.3);
  ASSERT_GT(in.num_triangles(), 0u);
  RemeshOptions ro;
  auto remeshed = remesh_surface(in, ro);
  ASSERT_TRUE(remeshed.ok()) << remeshed.message();
  const SurfaceMesh& wall = remeshed.value().mesh;
  auto sizes = vertex_sizes(wall, ro.size);
  ASSERT_TRUE(sizes.ok()) << sizes.message();
  auto res = cap_openings(wall, sizes.value());
  ASSERT_TRUE(res.ok()) << res.message();
  const CapQuality q = check_capped(wall, res.value(), {}, "aneurysm, N = 20");
  EXPECT_EQ(res.value().caps.size(), 3u);
  EXPECT_GE(q.min, 0.55);
  EXPECT_GE(q.worst_mean, 0.93);
}

TEST(CapOpenings, FarFromOriginAndLargeScale) {
  // Coordinates in the hundreds, sizes in the tens: tolerances are relative.
  SurfaceMesh wall = straight_tube(32, 12.0, 60.0);
  for (size_t i = 0; i < wall.points.size(); i += 3) {
    wall.points[i] += 250.0;
    wall.points[i + 1] -= 430.0;
    wall.points[i + 2] += 1200.0;
  }
  auto res = cap_openings(wall, {});
  ASSERT_TRUE(res.ok()) << res.message();
  check_capped(wall, res.value(), {}, "far tube");
  const double polygon = 0.5 * 32 * 144 * std::sin(2 * kPi / 32);
  EXPECT_NEAR(enclosed_volume(res.value().mesh), polygon * 60, 1e-9 * polygon * 60);
}

TEST(CapOpenings, RequestedSizeCoarsensTheInterior) {
  const SurfaceMesh wall = straight_tube(64, 1.0, 2.0);  // rim edges ~0.098
  auto fine = cap_openings(wall, {});
  ASSERT_TRUE(fine.ok()) << fine.message();
  const std::vector<double> coarse_size(wall.num_vertices(), 0.2);
  auto coarse = cap_openings(wall, coarse_size);
  ASSERT_TRUE(coarse.ok()) << coarse.message();
  const CapQuality q = check_capped(wall, coarse.value(), {}, "coarse interior");
  EXPECT_LT(coarse.value().caps[0].interior_vertices,
            0.6 * double(fine.value().caps[0].interior_vertices));
  EXPECT_GE(q.min, 0.4);
}

TEST(CapOpenings, ClosedSurfaceGetsNoCap) {
  const SurfaceMesh torus = testing::torus(30, 12);
  CapOptions o;
  o.inlet_index = 3;  // ignored: no opening
  auto res = cap_openings(torus, {}, o);
  ASSERT_TRUE(res.ok()) << res.message();
  EXPECT_TRUE(res.value().caps.empty());
  EXPECT_EQ(res.value().mesh.points, torus.points);
  EXPECT_EQ(res.value().mesh.triangles, torus.triangles);
  EXPECT_EQ(res.value().triangle_tag, std::vector<int32_t>(torus.num_triangles(), 0));
}

void expect_error(const Result<CappedSurface>& r, const std::string& fragment) {
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.message().find(fragment), std::string::npos) << r.message();
}

TEST(CapOpenings, ClearErrors) {
  const SurfaceMesh wall = straight_tube(24, 1.0, 2.0);
  CapOptions o;
  o.inlet_index = 2;
  expect_error(cap_openings(wall, {}, o), "inlet_index 2 is out of range (2 openings)");
  o.inlet_index = -1;
  expect_error(cap_openings(wall, {}, o), "inlet_index");
  expect_error(cap_openings(wall, std::vector<double>(3, 0.1)), "sizes for");
  std::vector<double> sizes(wall.num_vertices(), 0.1);
  sizes[0] = 0;  // a rim vertex
  expect_error(cap_openings(wall, sizes), "not positive");
  SurfaceMesh flipped = wall;
  testing::flip_triangle(flipped, 5);
  expect_error(cap_openings(flipped, {}), "not consistently oriented");
  SurfaceMesh inward = wall;
  for (size_t t = 0; t < inward.num_triangles(); ++t) testing::flip_triangle(inward, t);
  expect_error(cap_openings(inward, {}), "faces inward");
  // A rim that is a figure eight in its plane.
  Curve eight = [](double t) {
    return std::array<double, 3>{2 * std::sin(t), std::sin(2 * t), 3.0};
  };
  const SurfaceMesh twisted = tube_between(40, 20, circle(1.0, 0), eight);
  expect_error(cap_openings(twisted, {}), "intersects itself");
  // A rim whose points are collinear.
  Curve segment = [](double t) { return std::array<double, 3>{std::cos(t), 0.0, 3.0}; };
  const SurfaceMesh flat = tube_between(40, 20, circle(1.0, 0), segment);
  auto r = cap_openings(flat, {});
  ASSERT_FALSE(r.ok());
  std::cout << "[ info ] collinear rim: " << r.message() << "\n";
}

}  // namespace
}  // namespace vm
