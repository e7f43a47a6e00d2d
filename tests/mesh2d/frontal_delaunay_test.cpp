#include "core/mesh2d/frontal_delaunay.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "core/geom/predicates.h"
#include "core/mesh2d/adapt2d.h"
#include "core/quality/triangle_quality.h"
#include "tests/mesh2d/mesh2d_test_shapes.h"
#include "tests/support/test_meshes.h"

namespace vm {
namespace {

using Mesher = std::function<Result<Mesh2D>(const std::vector<double>&, const std::vector<int32_t>&,
                                            const SizeField2D&)>;

Result<Mesh2D> run_frontal(const std::vector<double>& p, const std::vector<int32_t>& s,
                           const SizeField2D& h) {
  return frontal_delaunay(p, s, h);
}
Result<Mesh2D> run_adapt(const std::vector<double>& p, const std::vector<int32_t>& s,
                         const SizeField2D& h) {
  return adapt_mesh2d(p, s, h);
}

struct NamedMesher {
  const char* name;
  Mesher run;
  bool claims_quality;  // the frontal mesher alone targets equilateral triangles
};

const NamedMesher kMeshers[] = {{"frontal", run_frontal, true}, {"adapt", run_adapt, false}};

using testing::median;

// Square [0, L]^2 with its boundary split in round(L / h) edges per side.
void square(double L, double h, std::vector<double>& pts, std::vector<int32_t>& seg) {
  const int n = int(std::round(L / h));
  for (int side = 0; side < 4; ++side)
    for (int i = 0; i < n; ++i) {
      const double t = L * i / n;
      const double xy[4][2] = {{t, 0}, {L, t}, {L - t, L}, {0, L - t}};
      pts.insert(pts.end(), {xy[side][0], xy[side][1]});
    }
  const int32_t m = 4 * n;
  for (int32_t i = 0; i < m; ++i) seg.insert(seg.end(), {i, (i + 1) % m});
}

// Signed area enclosed by the segment loops (outer ccw minus holes): the
// sum of the shoelace terms over the segments, each loop oriented as given
// (the annulus helper gives both loops ccw, so the hole is subtracted).
double polygon_area(const std::vector<double>& pts, const std::vector<int32_t>& seg,
                    size_t outer_segments) {
  double outer = 0, inner = 0;
  for (size_t s = 0; 2 * s < seg.size(); ++s) {
    const double *a = &pts[2 * size_t(seg[2 * s])], *b = &pts[2 * size_t(seg[2 * s + 1])];
    (s < outer_segments ? outer : inner) += 0.5 * (a[0] * b[1] - a[1] * b[0]);
  }
  return outer - inner;
}

struct Report {
  double area = 0, min_gamma = 1, mean_gamma = 0;
  std::vector<double> edge_lengths;
  std::vector<std::pair<double, double>> edge_midpoints;  // parallel to edge_lengths
  size_t non_delaunay = 0, missing_segments = 0, clockwise = 0, bad_edges = 0;
};

// Checks the invariants every mesher output must satisfy and gathers the
// measures the tests compare.
Report check_mesh(const Mesh2D& m, const std::vector<int32_t>& seg) {
  Report r;
  // Undirected edge -> (triangle, corner opposite the edge) of its triangles.
  std::map<std::pair<int32_t, int32_t>, std::vector<std::pair<size_t, int>>> edges;
  for (size_t t = 0; t < m.num_triangles(); ++t) {
    const int32_t* v = &m.triangles[3 * t];
    double p[3][3];
    for (int k = 0; k < 3; ++k) {
      EXPECT_GE(v[k], 0);
      EXPECT_LT(size_t(v[k]), m.num_vertices());
      p[k][0] = m.points[2 * size_t(v[k])];
      p[k][1] = m.points[2 * size_t(v[k]) + 1];
      p[k][2] = 0;
    }
    if (orient2d(p[0], p[1], p[2]) <= 0) ++r.clockwise;
    r.area += 0.5 * ((p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) -
                     (p[1][1] - p[0][1]) * (p[2][0] - p[0][0]));
    const double g = triangle_gamma(p[0], p[1], p[2]);
    r.min_gamma = std::min(r.min_gamma, g);
    r.mean_gamma += g / double(m.num_triangles());
    for (int k = 0; k < 3; ++k)
      edges[std::minmax(v[(k + 1) % 3], v[(k + 2) % 3])].push_back({t, k});
  }
  std::map<std::pair<int32_t, int32_t>, int> is_segment;
  for (size_t s = 0; 2 * s < seg.size(); ++s) is_segment[std::minmax(seg[2 * s], seg[2 * s + 1])];
  for (auto& [e, s] : is_segment) {
    auto it = edges.find(e);
    if (it == edges.end() || it->second.size() != 1) ++r.missing_segments;
  }
  for (const auto& [e, uses] : edges) {
    const double *a = &m.points[2 * size_t(e.first)], *b = &m.points[2 * size_t(e.second)];
    r.edge_lengths.push_back(std::hypot(b[0] - a[0], b[1] - a[1]));
    r.edge_midpoints.push_back({0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])});
    const bool segment = is_segment.count(e) > 0;
    // Manifold, and the mesh boundary is exactly the segments.
    if (uses.size() > 2 || (uses.size() == 1) != segment) {
      ++r.bad_edges;
      continue;
    }
    if (uses.size() != 2) continue;
    // Locally Delaunay: the vertex across the edge is not strictly inside
    // the circumcircle of the triangle (counterclockwise corners).
    const int32_t* v0 = &m.triangles[3 * uses[0].first];
    const int32_t d = m.triangles[3 * uses[1].first + size_t(uses[1].second)];
    if (incircle(&m.points[2 * size_t(v0[0])], &m.points[2 * size_t(v0[1])],
                 &m.points[2 * size_t(v0[2])], &m.points[2 * size_t(d)]) > 0)
      ++r.non_delaunay;
  }
  return r;
}

void expect_valid(const Report& r, double domain_area, const char* name) {
  EXPECT_EQ(r.clockwise, 0u) << name << ": triangles not counterclockwise";
  EXPECT_EQ(r.missing_segments, 0u) << name << ": boundary segments not mesh boundary edges";
  EXPECT_EQ(r.bad_edges, 0u) << name << ": non-manifold edges or a boundary off the segments";
  EXPECT_NEAR(r.area, domain_area, 1e-9) << name;
}

TEST(FrontalDelaunay, UniformSizeOnTheUnitSquare) {
  const double h = 0.05;
  std::vector<double> pts;
  std::vector<int32_t> seg;
  square(1.0, h, pts, seg);
  for (const NamedMesher& m : kMeshers) {
    auto r = m.run(pts, seg, [&](double, double) { return h; });
    ASSERT_TRUE(r.ok()) << m.name << ": " << r.message();
    // The input points keep their indices and coordinates.
    ASSERT_GE(r.value().points.size(), pts.size());
    for (size_t i = 0; i < pts.size(); ++i) EXPECT_EQ(r.value().points[i], pts[i]) << m.name;
    Report rep = check_mesh(r.value(), seg);
    expect_valid(rep, 1.0, m.name);
    EXPECT_EQ(rep.non_delaunay, 0u) << m.name << ": edges not locally Delaunay";
    EXPECT_NEAR(median(rep.edge_lengths), h, 0.15 * h) << m.name;
    if (m.claims_quality) {
      EXPECT_GT(rep.mean_gamma, 0.9) << m.name;
      EXPECT_GT(rep.min_gamma, 0.3) << m.name;
    }
    std::cout << "[ info ] square " << m.name << ": " << r.value().num_triangles()
              << " triangles, median edge " << median(rep.edge_lengths) << ", gamma min "
              << rep.min_gamma << " mean " << rep.mean_gamma << "\n";
  }
}

TEST(FrontalDelaunay, UniformSizeOnAnAnnulusKeepsTheHole) {
  // Boundary edges about h long on both circles.
  const double h = 0.06, r_in = 0.4;
  const int n_out = int(std::round(2 * std::numbers::pi / h));
  const int n_in = int(std::round(2 * std::numbers::pi * r_in / h));
  std::vector<double> pts;
  std::vector<int32_t> seg;
  testing::annulus(n_out, n_in, r_in, pts, seg);
  const double area = polygon_area(pts, seg, size_t(n_out));
  ASSERT_GT(area, 2.5);  // the hole is subtracted (pi (1 - 0.16) ~ 2.64)
  for (const NamedMesher& m : kMeshers) {
    auto r = m.run(pts, seg, [&](double, double) { return h; });
    ASSERT_TRUE(r.ok()) << m.name << ": " << r.message();
    Report rep = check_mesh(r.value(), seg);
    expect_valid(rep, area, m.name);
    EXPECT_EQ(rep.non_delaunay, 0u) << m.name << ": edges not locally Delaunay";
    EXPECT_NEAR(median(rep.edge_lengths), h, 0.15 * h) << m.name;
    if (m.claims_quality) {
      EXPECT_GT(rep.mean_gamma, 0.9) << m.name;
      EXPECT_GT(rep.min_gamma, 0.3) << m.name;
    }
    // Nothing in the hole: no vertex used by a triangle lies inside it.
    for (int32_t v : r.value().triangles) {
      const double x = r.value().points[2 * size_t(v)], y = r.value().points[2 * size_t(v) + 1];
      EXPECT_GT(std::hypot(x, y), r_in * std::cos(std::numbers::pi / n_in) - 1e-12) << m.name;
    }
    std::cout << "[ info ] annulus " << m.name << ": " << r.value().num_triangles()
              << " triangles, median edge " << median(rep.edge_lengths) << ", gamma min "
              << rep.min_gamma << " mean " << rep.mean_gamma << "\n";
  }
}

TEST(FrontalDelaunay, GradedSizeGivesLongerEdgesOnTheCoarseSide) {
  std::vector<double> pts;
  std::vector<int32_t> seg;
  square(1.0, 0.02, pts, seg);
  auto size = [](double u, double) { return 0.02 + 0.1 * u; };
  for (const NamedMesher& m : kMeshers) {
    auto r = m.run(pts, seg, size);
    ASSERT_TRUE(r.ok()) << m.name << ": " << r.message();
    Report rep = check_mesh(r.value(), seg);
    expect_valid(rep, 1.0, m.name);
    // Interior edges only (the boundary is given at 0.02 everywhere).
    std::vector<double> left, right;
    for (size_t i = 0; i < rep.edge_lengths.size(); ++i) {
      const auto [x, y] = rep.edge_midpoints[i];
      if (y < 0.1 || y > 0.9) continue;
      if (x > 0.05 && x < 0.2) left.push_back(rep.edge_lengths[i]);
      if (x > 0.7 && x < 0.85) right.push_back(rep.edge_lengths[i]);
    }
    ASSERT_GT(left.size(), 10u) << m.name;
    ASSERT_GT(right.size(), 10u) << m.name;
    EXPECT_GT(median(right), 1.8 * median(left)) << m.name;
    // The coarse side follows the field there (0.092 at x = 0.72, 0.105 at
    // x = 0.85), within the meshers' tolerance.
    EXPECT_NEAR(median(right), size(0.78, 0), 0.35 * size(0.78, 0)) << m.name;
    std::cout << "[ info ] graded " << m.name << ": median left " << median(left) << " right "
              << median(right) << "\n";
  }
}

TEST(FrontalDelaunay, RefusesANonPositiveSize) {
  std::vector<double> pts;
  std::vector<int32_t> seg;
  square(1.0, 0.25, pts, seg);
  for (const NamedMesher& m : kMeshers)
    for (double bad : {0.0, -0.1, std::nan("")}) {
      auto r = m.run(pts, seg, [&](double, double) { return bad; });
      EXPECT_FALSE(r.ok()) << m.name << " accepted size " << bad;
    }
  // Positive on the left half only: still an error, not a mesh.
  for (const NamedMesher& m : kMeshers) {
    auto r = m.run(pts, seg, [](double u, double) { return u < 0.5 ? 0.1 : 0.0; });
    EXPECT_FALSE(r.ok()) << m.name << " accepted a size that is zero on half the domain";
  }
}

TEST(FrontalDelaunay, SizeCoarserThanTheBoundaryKeepsTheBoundary) {
  // A boundary split finer than the size: no point is added and the
  // boundary stays conforming (nothing may be inserted on a segment).
  std::vector<double> pts;
  std::vector<int32_t> seg;
  square(1.0, 0.05, pts, seg);
  for (const NamedMesher& m : kMeshers) {
    auto r = m.run(pts, seg, [](double, double) { return 0.4; });
    ASSERT_TRUE(r.ok()) << m.name << ": " << r.message();
    Report rep = check_mesh(r.value(), seg);
    expect_valid(rep, 1.0, m.name);
    EXPECT_EQ(rep.non_delaunay, 0u) << m.name;
  }
}

}  // namespace
}  // namespace vm
