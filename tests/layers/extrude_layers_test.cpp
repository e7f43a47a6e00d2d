#include "core/layers/extrude_layers.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <numbers>
#include <set>
#include <string>
#include <vector>

#include "core/mesh/chord_radius.h"
#include "core/mesh/self_intersection.h"
#include "core/mesh/surface_distance.h"
#include "core/mesh/volume_check.h"
#include "core/mesh/volume_mesh.h"
#include "core/phantom/vessel_phantom.h"
#include "core/quality/triangle_quality.h"
#include "core/surface/cap_openings.h"
#include "core/surface/remesh_surface.h"
#include "core/surface/vessel_radius.h"
#include "tests/support/phantoms.h"
#include "tests/support/remesh_options.h"
#include "tests/support/test_meshes.h"

namespace vm {
namespace {

constexpr double kPi = std::numbers::pi;

const double* pt(const std::vector<double>& pts, int32_t v) { return &pts[3 * size_t(v)]; }

double dist(const double* a, const double* b) {
  return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                   (a[2] - b[2]) * (a[2] - b[2]));
}

double tri_area(const std::vector<double>& pts, const int32_t* t, const double* normal = nullptr,
                double* signed_dot = nullptr) {
  const double *a = pt(pts, t[0]), *b = pt(pts, t[1]), *c = pt(pts, t[2]);
  const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double w[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  const double n[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2],
                       u[0] * w[1] - u[1] * w[0]};
  const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  if (normal && signed_dot)
    *signed_dot = (n[0] * normal[0] + n[1] * normal[1] + n[2] * normal[2]) / len;
  return 0.5 * len;
}

// A tube of radius r around the arc of radius `bend` in the xy-plane
// (angles 0..sweep around z), `along` segments along the arc and `around`
// around it: an open bent tube, outward oriented, planar end rims.
SurfaceMesh bent_tube(int around, int along, double bend, double r, double sweep) {
  SurfaceMesh s;
  const int cols = along + 1;
  for (int j = 0; j < around; ++j)
    for (int i = 0; i < cols; ++i) {
      const double u = sweep * i / along, v = 2 * kPi * j / around;
      s.points.insert(s.points.end(), {(bend + r * std::cos(v)) * std::cos(u),
                                       (bend + r * std::cos(v)) * std::sin(u), r * std::sin(v)});
    }
  for (int j = 0; j < around; ++j)
    for (int i = 0; i < along; ++i) {
      const int32_t a = j * cols + i, b = a + 1, c = ((j + 1) % around) * cols + i, d = c + 1;
      s.triangles.insert(s.triangles.end(), {a, b, d, a, d, c});
    }
  return s;
}

// A straight tube along z whose top rim is the planar-ish curve z = len +
// tilt x + wave sin(3 theta) (not planar when wave != 0).
SurfaceMesh cut_tube(int n, int m, double r, double len, double tilt, double wave) {
  SurfaceMesh s = testing::open_tube(n, m, r, len);
  for (int j = 0; j <= m; ++j)
    for (int i = 0; i < n; ++i) {
      const double a = 2 * kPi * i / n, f = double(j) / m;
      double* p = &s.points[3 * size_t(j * n + i)];
      p[2] = f * (len + tilt * p[0] + wave * std::sin(3 * a));
    }
  return s;
}

struct LayerCheck {
  double min_volume6 = 0;
  double max_rim_offset = 0;  // largest distance of a column point from its plane / diagonal
};

// The contract of extrude_layers on m for input `wall`.
LayerCheck check_layers(const SurfaceMesh& wall, const LayerMesh& m, const LayerSpec& spec,
                        const std::string& name) {
  SCOPED_TRACE(name);
  LayerCheck out;
  const size_t nv = wall.num_vertices(), nt = wall.num_triangles();
  const size_t n = size_t(spec.layers);
  EXPECT_EQ(m.wall_vertices, nv);
  EXPECT_EQ(m.num_vertices(), nv * (n + 1));
  EXPECT_EQ(m.num_prisms(), nt * n);
  EXPECT_EQ(m.front.size(), 3 * nt);
  const double diag = bounding_box(m.points).diagonal();

  // Every prism's three sub-tetrahedra positive; the whole layer conforming,
  // its boundary exactly wall + front + rings (check_volume_mesh is exact).
  const VolumeMesh vol = layer_volume(m, true);
  out.min_volume6 = 1e300;
  for (size_t t = 0; t < vol.num_tets(); ++t) {
    const int32_t* v = &vol.tets[4 * t];
    out.min_volume6 =
        std::min(out.min_volume6, tet_volume6(pt(vol.points, v[0]), pt(vol.points, v[1]),
                                              pt(vol.points, v[2]), pt(vol.points, v[3])));
  }
  EXPECT_GT(out.min_volume6, 0);
  const auto check = check_volume_mesh(vol);
  EXPECT_TRUE(check.ok()) << check.message();
  if (check.ok()) {
    EXPECT_EQ(check.value().boundary_faces, vol.num_triangles());
  }

  // Non-rim wall vertices unchanged; every column has all N layers, heights
  // in the requested proportions.
  std::vector<uint8_t> rim(nv, 0);
  for (const LayerOpening& op : m.openings)
    for (int32_t v : op.rim) rim[size_t(v)] = 1;
  for (size_t v = 0; v < nv; ++v) {
    if (!rim[v]) {
      for (int k = 0; k < 3; ++k)
        EXPECT_EQ(m.points[3 * v + size_t(k)], wall.points[3 * v + size_t(k)]);
    }
    const double total =
        dist(pt(m.points, int32_t(v)), pt(m.points, m.layer_vertex(int32_t(v), spec.layers)));
    EXPECT_GT(total, 0);
    EXPECT_NEAR(total, m.thickness[v], 1e-9 * diag);
    for (size_t k = 1; k <= n; ++k) {
      const double h = dist(pt(m.points, m.layer_vertex(int32_t(v), int(k - 1))),
                            pt(m.points, m.layer_vertex(int32_t(v), int(k))));
      EXPECT_GT(h, 0);
      EXPECT_NEAR(h, (m.fraction[k] - m.fraction[k - 1]) * m.thickness[v], 1e-9 * diag);
    }
  }
  // The front is the wall's triangles on the last layer.
  size_t front_mismatch = 0;
  for (size_t i = 0; i < 3 * nt; ++i)
    front_mismatch += m.front[i] != m.layer_vertex(wall.triangles[i], spec.layers);
  EXPECT_EQ(front_mismatch, 0u);
  const SurfaceMesh front = front_surface(m);
  EXPECT_EQ(find_self_intersections(front, 1).pairs, 0u);

  // Columns on the rims lie in their planes; ring triangles planar, facing
  // along the plane normal, closing the annulus.
  for (size_t o = 0; o < m.openings.size(); ++o) {
    const LayerOpening& op = m.openings[o];
    EXPECT_EQ(op.columns.size(), op.rim.size() * (n + 1));
    for (int32_t id : op.columns) {
      const double* p = pt(m.points, id);
      double off = 0;
      for (int k = 0; k < 3; ++k) off += (p[k] - op.origin[k]) * op.normal[k];
      out.max_rim_offset = std::max(out.max_rim_offset, std::abs(off) / diag);
    }
    const std::vector<int32_t> ring = ring_triangles(m, o);
    EXPECT_EQ(ring.size(), 6 * n * op.rim.size());
    for (size_t t = 0; t < ring.size(); t += 3) {
      double s = 0;
      tri_area(m.points, &ring[t], op.normal.data(), &s);
      EXPECT_GT(s, 1 - 1e-9);
    }
  }
  EXPECT_LE(out.max_rim_offset, 1e-9);
  return out;
}

double ring_area(const LayerMesh& m, size_t o) {
  const std::vector<int32_t> ring = ring_triangles(m, o);
  double a = 0;
  for (size_t t = 0; t < ring.size(); t += 3) a += tri_area(m.points, &ring[t]);
  return a;
}

void print_stats(const std::string& name, const LayerStats& s) {
  std::cout << "[ info ] " << name << ": reduced area " << 100 * s.reduced_area_fraction
            << "% (min factor " << s.min_factor << ", mean over reduced " << s.mean_reduced_factor
            << "; gap " << s.limited_by_gap << ", validity " << s.limited_by_validity
            << ", intersection " << s.limited_by_intersection << " vertices), total within 10% "
            << 100 * s.thickness_within_10pct << "%, measured first/total within 10% "
            << 100 * s.measured_first_within_10pct << "% / " << 100 * s.measured_total_within_10pct
            << "% (mean ratio " << s.measured_first_mean_ratio << " / "
            << s.measured_total_mean_ratio << "), front gamma min " << s.front_quality_min
            << " mean " << s.front_quality_mean << " (wall min " << s.wall_quality_min
            << "), min volume ratio " << s.min_volume_ratio << ", visibility " << s.min_visibility
            << ", rounds " << s.rounds << ", " << s.seconds_total << " s (dir "
            << s.seconds_directions << ", gap " << s.seconds_gap << ", validity "
            << s.seconds_validity << ", verify " << s.seconds_verify << ", measure "
            << s.seconds_measure << ")\n";
}

/// extrude_layers(wall, radius, spec, st); when it succeeds, its layers
/// checked (check_layers) and its stats printed, both under `name`.
Result<LayerMesh> extrude_checked(const SurfaceMesh& wall, const std::vector<double>& radius,
                                  const LayerSpec& spec, LayerStats* st, const std::string& name) {
  auto r = extrude_layers(wall, radius, spec, st);
  if (r.ok()) {
    check_layers(wall, r.value(), spec, name);
    print_stats(name, *st);
  }
  return r;
}

TEST(Layers, StraightTubeInwardUniform) {
  const int n = 40;
  const SurfaceMesh wall = testing::open_tube(n, 30, 1.0, 4.0);
  const std::vector<double> radius(wall.num_vertices(), 1.0);
  LayerSpec spec;  // 4 layers, 0.2 R
  spec.measure = true;
  LayerStats st;
  auto r = extrude_checked(wall, radius, spec, &st, "tube inward");
  ASSERT_TRUE(r.ok()) << r.message();
  const LayerMesh& m = r.value();
  // Thickness F R everywhere measured from the wall's facets (the column
  // is lengthened by 1 / cos(pi / n), the facets' tilt from a vertex
  // normal), nothing reduced, the first layer a quarter of it; columns
  // point at the axis.
  EXPECT_EQ(st.reduced_area, 0);
  EXPECT_EQ(st.min_factor, 1);
  const double column = 0.2 / std::cos(kPi / n);
  for (size_t v = 0; v < wall.num_vertices(); ++v) {
    const double* p = pt(m.points, int32_t(v));
    const double* q = pt(m.points, m.layer_vertex(int32_t(v), 4));
    const double* q1 = pt(m.points, m.layer_vertex(int32_t(v), 1));
    EXPECT_NEAR(dist(p, q), column, 1e-9);
    EXPECT_NEAR(dist(p, q1), column / 4, 1e-9);
    EXPECT_NEAR(std::hypot(q[0], q[1]), 1 - column, 1e-9);
    EXPECT_NEAR(q[2], p[2], 1e-9);
  }
  EXPECT_GE(st.thickness_within_10pct, 0.999);
  EXPECT_GE(st.measured_total_within_10pct, 0.95);
  EXPECT_GE(st.measured_first_within_10pct, 0.95);
  // Ring = the polygonal annulus between R and R - column: exactly, and
  // pi (R^2 - (R - T)^2) up to the polygon's discretization.
  ASSERT_EQ(m.openings.size(), 2u);
  const double polygon = 0.5 * n * std::sin(2 * kPi / n) * (1 - (1 - column) * (1 - column));
  for (size_t o = 0; o < 2; ++o) {
    EXPECT_NEAR(ring_area(m, o), polygon, 1e-9);
    EXPECT_NEAR(ring_area(m, o), kPi * (1 - 0.8 * 0.8), 0.005 * kPi * (1 - 0.8 * 0.8));
  }
  EXPECT_GT(st.front_quality_min, 0.9 * st.wall_quality_min);
}

TEST(Layers, FirstHeightAndGrowth) {
  const SurfaceMesh wall = testing::open_tube(40, 30, 1.0, 4.0);
  const double lean = std::cos(kPi / 40);  // the facets' tilt from a vertex normal
  LayerSpec spec;
  spec.layers = 5;
  spec.first_height = 0.02;
  spec.growth = 1.3;
  LayerStats st;
  auto r = extrude_layers(wall, {}, spec, &st);  // absolute heights: no radius needed
  ASSERT_TRUE(r.ok()) << r.message();
  const LayerMesh& m = r.value();
  check_layers(wall, m, spec, "growth");
  for (size_t v = 0; v < wall.num_vertices(); ++v) {
    double h = 0.02;
    for (int k = 1; k <= 5; ++k, h *= 1.3) {
      const double got = dist(pt(m.points, m.layer_vertex(int32_t(v), k - 1)),
                              pt(m.points, m.layer_vertex(int32_t(v), k)));
      EXPECT_NEAR(got * lean, h, 1e-12) << "layer " << k;
    }
  }
  EXPECT_EQ(st.reduced_area, 0);
  // Seed 4.2: 4 uniform layers of h_BL.
  spec.layers = 4;
  spec.first_height = 0.03;
  spec.growth = 1;
  r = extrude_layers(wall, {}, spec, &st);
  ASSERT_TRUE(r.ok()) << r.message();
  check_layers(wall, r.value(), spec, "uniform h_BL");
  for (size_t v = 0; v < wall.num_vertices(); ++v)
    for (int k = 1; k <= 4; ++k)
      EXPECT_NEAR(dist(pt(r.value().points, r.value().layer_vertex(int32_t(v), k - 1)),
                       pt(r.value().points, r.value().layer_vertex(int32_t(v), k))) *
                      lean,
                  0.03, 1e-12);
}

TEST(Layers, HeightsMeasuredFromACoarselyFacetedWall) {
  // A hexagonal tube: its facets lean 30 degrees from the vertex normals,
  // so a column of the requested length would end only cos 30 = 0.87 of it
  // from the wall. Inward and outward, the first layer and the front must
  // be at the requested distance from the wall (closest point).
  const SurfaceMesh wall = testing::open_tube(6, 12, 1.0, 4.0);
  const std::vector<double> radius(wall.num_vertices(), 1.0);
  for (bool outward : {false, true}) {
    LayerSpec spec;
    spec.outward = outward;
    spec.thickness_fraction = 0.1;
    spec.measure = true;
    LayerStats st;
    auto r = extrude_layers(wall, radius, spec, &st);
    ASSERT_TRUE(r.ok()) << r.message();
    check_layers(wall, r.value(), spec, outward ? "hexagon outward" : "hexagon inward");
    EXPECT_GE(st.measured_first_within_10pct, 0.95) << outward;
    EXPECT_GE(st.measured_total_within_10pct, 0.95) << outward;
    EXPECT_NEAR(st.measured_total_mean_ratio, 1, 0.03) << outward;
  }
}

TEST(Layers, StraightTubeOutwardWallRings) {
  const int n = 40;
  const SurfaceMesh wall = testing::open_tube(n, 30, 1.0, 4.0);
  const std::vector<double> radius(wall.num_vertices(), 1.0);
  LayerSpec spec;
  spec.outward = true;
  spec.thickness_fraction = 0.1;  // seed 4.3: 0.1 R in 4 layers
  LayerStats st;
  auto r = extrude_checked(wall, radius, spec, &st, "tube outward");
  ASSERT_TRUE(r.ok()) << r.message();
  const LayerMesh& m = r.value();
  EXPECT_EQ(st.reduced_area, 0);
  for (size_t v = 0; v < wall.num_vertices(); ++v) {
    const double* q = pt(m.points, m.layer_vertex(int32_t(v), 4));
    EXPECT_NEAR(std::hypot(q[0], q[1]), 1.1, 0.0011);
  }
  const double polygon = 0.5 * n * std::sin(2 * kPi / n) * (1.1 * 1.1 - 1);
  for (size_t o = 0; o < 2; ++o) EXPECT_NEAR(ring_area(m, o), polygon, 1e-9);
}

TEST(Layers, RimsMovedExactlyAsCapsMoveThem) {
  // A tilted, wavy top rim: not planar, so the rim vertices move onto the
  // fitted plane; the layer's wall points must be cap_openings's, bitwise,
  // for both directions, and the columns stay in the plane.
  const SurfaceMesh wall = cut_tube(36, 24, 1.0, 3.0, 0.6, 0.02);
  const std::vector<double> radius = chord_radius(wall);
  auto capped = cap_openings(wall, {});
  ASSERT_TRUE(capped.ok()) << capped.message();
  for (bool outward : {false, true}) {
    LayerSpec spec;
    spec.outward = outward;
    spec.thickness_fraction = outward ? 0.1 : 0.2;
    LayerStats st;
    auto r = extrude_layers(wall, radius, spec, &st);
    ASSERT_TRUE(r.ok()) << r.message();
    const LayerMesh& m = r.value();
    const LayerCheck c = check_layers(wall, m, spec, outward ? "cut outward" : "cut inward");
    print_stats(outward ? "tilted wavy rim outward" : "tilted wavy rim inward", st);
    for (size_t i = 0; i < 3 * wall.num_vertices(); ++i)
      ASSERT_EQ(m.points[i], capped.value().mesh.points[i]) << "coordinate " << i;
    EXPECT_LE(c.max_rim_offset, 1e-12);
    // The planes are the caps' planes.
    for (const CapInfo& cap : capped.value().caps) {
      const LayerOpening* op = nullptr;
      for (const LayerOpening& o : m.openings)
        if (std::find(cap.rim.begin(), cap.rim.end(), o.rim[0]) != cap.rim.end()) op = &o;
      ASSERT_NE(op, nullptr);
      EXPECT_EQ(op->rim, cap.rim);
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(op->normal[k], cap.normal[k], 1e-12);
    }
    EXPECT_GE(st.thickness_within_10pct, 0.95);
  }
}

TEST(Layers, TorusInwardUnreducedOutwardShrinksOnlyInside) {
  // Closed wall, genus 1 (R = 3, r = 1).
  const SurfaceMesh wall = testing::torus(60, 20, 3.0, 1.0);
  const std::vector<double> radius(wall.num_vertices(), 1.0);
  LayerSpec spec;
  LayerStats st;
  auto r = extrude_checked(wall, radius, spec, &st, "torus inward");
  ASSERT_TRUE(r.ok()) << r.message();
  EXPECT_EQ(st.reduced_area, 0);
  EXPECT_TRUE(r.value().openings.empty());

  // A tight torus (R = 1.6) grown outward by 1.0: the hole's side converges
  // (focal distance R - r = 0.6), the outer side has all the room it wants.
  const SurfaceMesh tight = testing::torus(48, 24, 1.6, 1.0);
  spec.outward = true;
  spec.thickness_fraction = 1.0;
  r = extrude_checked(tight, std::vector<double>(tight.num_vertices(), 1.0), spec, &st,
                      "tight torus outward");
  ASSERT_TRUE(r.ok()) << r.message();
  EXPECT_GT(st.reduced_area_fraction, 0.05);
  EXPECT_LT(st.reduced_area_fraction, 0.6);
  for (size_t v = 0; v < tight.num_vertices(); ++v) {
    const double* p = pt(tight.points, int32_t(v));
    const double rho = std::hypot(p[0], p[1]);
    if (rho > 1.6 + 0.5) {
      EXPECT_EQ(r.value().factor[v], 1) << "outer side reduced at " << rho;
    }
    if (rho < 0.8) {
      EXPECT_LT(r.value().factor[v], 0.7) << "inner side not reduced at " << rho;
    }
  }
}

TEST(Layers, BentTubeShrinksOnlyWhereNeeded) {
  // Bend radius 2, tube radius 1, a quarter turn.
  const SurfaceMesh wall = bent_tube(32, 16, 2.0, 1.0, kPi / 2);
  const std::vector<double> radius(wall.num_vertices(), 1.0);
  for (bool outward : {false, true}) {
    LayerSpec spec;
    spec.outward = outward;
    spec.thickness_fraction = outward ? 0.1 : 0.2;
    LayerStats st;
    auto r = extrude_checked(wall, radius, spec, &st,
                             outward ? "bent tube outward 0.1R" : "bent tube inward 0.2R");
    ASSERT_TRUE(r.ok()) << r.message();
    EXPECT_EQ(st.reduced_area, 0) << "nothing needs reducing";
  }
  // Outward by 0.9 R: the inside of the bend (distance 1 from the bend's
  // axis) converges and must shrink; the outside must not.
  LayerSpec spec;
  spec.outward = true;
  spec.thickness_fraction = 0.9;
  LayerStats st;
  auto r = extrude_checked(wall, radius, spec, &st, "bent tube outward 0.9R");
  ASSERT_TRUE(r.ok()) << r.message();
  EXPECT_GT(st.reduced_area_fraction, 0.02);
  for (size_t v = 0; v < wall.num_vertices(); ++v) {
    const double* p = pt(wall.points, int32_t(v));
    const double rho = std::hypot(p[0], p[1]);
    if (rho > 2.5) {
      EXPECT_EQ(r.value().factor[v], 1) << "outer side reduced at " << rho;
    }
    if (rho < 1.05) {
      EXPECT_LT(r.value().factor[v], 1) << "inner side not reduced at " << rho;
    }
  }
}

// The bifurcation phantom remeshed at a uniform size.
const SurfaceMesh& remeshed_bifurcation() {
  static const SurfaceMesh wall = [] {
    auto out = remesh_surface(testing::noisy_bifurcation(0.15), testing::uniform_remesh(0.15));
    EXPECT_TRUE(out.ok()) << out.message();
    return out.ok() ? out.value().mesh : SurfaceMesh{};
  }();
  return wall;
}

TEST(Layers, BifurcationPhantomInwardAndOutward) {
  const SurfaceMesh& wall = remeshed_bifurcation();
  ASSERT_GT(wall.num_triangles(), 0u);
  const std::vector<double> radius = chord_radius(wall);
  for (bool outward : {false, true}) {
    LayerSpec spec;
    spec.outward = outward;
    spec.thickness_fraction = outward ? 0.1 : 0.2;
    spec.measure = true;
    LayerStats st;
    auto r = extrude_layers(wall, radius, spec, &st);
    ASSERT_TRUE(r.ok()) << r.message();
    const std::string name = outward ? "bifurcation outward 0.1R" : "bifurcation inward 0.2R";
    check_layers(wall, r.value(), spec, name);
    print_stats(name, st);
    EXPECT_EQ(r.value().openings.size(), 3u);
    // The accuracy target: within 10% on >= 95% of the wall area.
    EXPECT_GE(st.thickness_within_10pct, 0.95);
    EXPECT_GE(st.measured_total_within_10pct, 0.95);
    EXPECT_GE(st.measured_first_within_10pct, 0.95);
    EXPECT_GE(st.front_quality_min, 0.5 * st.wall_quality_min);
  }
}

TEST(Layers, NarrowBranchFrontsWouldCollide) {
  // 4 layers of 0.125 (total 0.5, the seed's absolute h_BL setting) in a
  // bifurcation whose branches have radii 0.6-0.78: across the smaller
  // branch the fronts would come within 0.2 of each other or meet; the gap
  // limit shrinks them to 2 x 0.4 of the radius there.
  const SurfaceMesh& wall = remeshed_bifurcation();
  ASSERT_GT(wall.num_triangles(), 0u);
  LayerSpec spec;
  spec.first_height = 0.125;
  LayerStats st;
  auto r = extrude_checked(wall, {}, spec, &st, "bifurcation inward 4 x 0.125");
  ASSERT_TRUE(r.ok()) << r.message();
  EXPECT_GT(st.reduced_area_fraction, 0.1);
  EXPECT_LT(st.min_factor, 1);
  EXPECT_GT(st.limited_by_gap, 0u);
  // No front point comes near another part of the wall: its distance to
  // the wall is at least half its own column (a front crossing the branch
  // would come within the other side's layer).
  const LayerMesh& m = r.value();
  std::vector<double> front_points;
  for (size_t v = 0; v < wall.num_vertices(); ++v) {
    const double* p = pt(m.points, m.layer_vertex(int32_t(v), spec.layers));
    front_points.insert(front_points.end(), p, p + 3);
  }
  const DistanceReport d = distances_to_surface(wall, front_points, true);
  size_t close = 0;
  for (size_t v = 0; v < wall.num_vertices(); ++v) close += d.per_point[v] < 0.5 * m.thickness[v];
  EXPECT_EQ(close, 0u);
}

TEST(Layers, BifurcationCrotchOutward) {
  // A vessel wall of 0.6 R grown outward: between the branches (the crotch)
  // the two fronts would cross; they shrink there, and only there.
  const SurfaceMesh& wall = remeshed_bifurcation();
  ASSERT_GT(wall.num_triangles(), 0u);
  LayerSpec spec;
  spec.outward = true;
  spec.thickness_fraction = 0.6;
  LayerStats st;
  auto r = extrude_checked(wall, chord_radius(wall), spec, &st, "bifurcation outward 0.6R");
  ASSERT_TRUE(r.ok()) << r.message();
  EXPECT_GT(st.reduced_area_fraction, 0.005);
  EXPECT_GT(st.limited_by_gap, 0u);
  // The most reduced vertices lie between the branches: above the
  // bifurcation (z > 0.5), near the plane between them (|x| < 1.2).
  const LayerMesh& m = r.value();
  size_t worst = 0;
  for (size_t v = 0; v < wall.num_vertices(); ++v)
    if (m.factor[v] < m.factor[worst]) worst = v;
  const double* p = pt(wall.points, int32_t(worst));
  EXPECT_GT(p[2], 0.5);
  EXPECT_LT(std::abs(p[0]), 1.2);
}

TEST(Layers, KeptPrismsAndHelpers) {
  const SurfaceMesh wall = testing::open_tube(24, 12, 1.0, 2.0);
  LayerSpec spec;
  spec.layers = 3;
  auto r = extrude_layers(wall, std::vector<double>(wall.num_vertices(), 1.0), spec);
  ASSERT_TRUE(r.ok()) << r.message();
  const LayerMesh& m = r.value();
  // prisms_to_tets: 3 positive tetrahedra per prism, split_prism's.
  const std::vector<int32_t> tets = prisms_to_tets(m.prisms);
  EXPECT_EQ(tets.size(), 12 * m.num_prisms());
  // Each ring quad is two ring triangles (same vertices, same orientation).
  for (size_t o = 0; o < m.openings.size(); ++o) {
    const std::vector<int32_t> q = ring_quads(m, o), t = ring_triangles(m, o);
    ASSERT_EQ(q.size() / 4, t.size() / 6);
    for (size_t i = 0; i < q.size() / 4; ++i) {
      std::set<int32_t> a(q.begin() + long(4 * i), q.begin() + long(4 * i + 4));
      std::set<int32_t> b(t.begin() + long(6 * i), t.begin() + long(6 * i + 6));
      EXPECT_EQ(a, b);
    }
  }
  // The layer volume keeps the prisms on request.
  const VolumeMesh kept = layer_volume(m, false);
  EXPECT_EQ(kept.num_prisms(), m.num_prisms());
  EXPECT_EQ(kept.num_tets(), 0u);
}

TEST(Layers, Errors) {
  const SurfaceMesh wall = testing::open_tube(16, 8, 1.0, 2.0);
  const std::vector<double> radius(wall.num_vertices(), 1.0);
  LayerSpec spec;
  EXPECT_FALSE(extrude_layers(wall, {1.0}, spec).ok());  // radius size
  spec.layers = 0;
  EXPECT_FALSE(extrude_layers(wall, radius, spec).ok());
  spec = {};
  spec.growth = 0;
  EXPECT_FALSE(extrude_layers(wall, radius, spec).ok());
  spec = {};
  std::vector<double> bad = radius;
  bad[3] = -1;
  EXPECT_FALSE(extrude_layers(wall, bad, spec).ok());
  // An inward-facing wall.
  SurfaceMesh flipped = wall;
  for (size_t t = 0; t < flipped.num_triangles(); ++t) testing::flip_triangle(flipped, t);
  auto r = extrude_layers(flipped, radius, spec);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.message().find("inward"), std::string::npos) << r.message();
  // Inconsistent orientation.
  SurfaceMesh mixed = wall;
  testing::flip_triangle(mixed, 5);
  EXPECT_FALSE(extrude_layers(mixed, radius, spec).ok());
  // An isolated vertex.
  SurfaceMesh isolated = wall;
  isolated.points.insert(isolated.points.end(), {9, 9, 9});
  std::vector<double> r2 = radius;
  r2.push_back(1);
  EXPECT_FALSE(extrude_layers(isolated, r2, spec).ok());
}

}  // namespace
}  // namespace vm
