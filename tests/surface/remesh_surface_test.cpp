#include "core/surface/remesh_surface.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <numbers>
#include <set>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/geom/closest_point.h"
#include "core/geom/vec3.h"
#include "core/mesh/adjacency.h"
#include "core/mesh/topology.h"
#include "core/phantom/vessel_phantom.h"
#include "core/quality/triangle_quality.h"
#include "core/surface/optimize_surface.h"
#include "core/surface/resample_curve.h"
#include "core/util/parallel.h"
#include "tests/support/phantoms.h"
#include "tests/support/remesh_options.h"
#include "tests/support/test_meshes.h"

namespace vm {
namespace {

constexpr double kPi = std::numbers::pi;

using testing::median;

double dist(const double* a, const double* b) {
  return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                   (a[2] - b[2]) * (a[2] - b[2]));
}

const double* pt(const SurfaceMesh& m, int32_t v) { return &m.points[3 * size_t(v)]; }

// Distance from x to triangle t of m.
double distance_to_triangle(const SurfaceMesh& m, size_t t, const double* x) {
  double q[3];
  return std::sqrt(closest_point_on_triangle(x, pt(m, m.triangles[3 * t]),
                                             pt(m, m.triangles[3 * t + 1]),
                                             pt(m, m.triangles[3 * t + 2]), q));
}

// Distance from x to the nearest triangle of m (brute force).
double distance_to_surface(const SurfaceMesh& m, const double* x) {
  double best = 1e300;
  for (size_t t = 0; t < m.num_triangles(); ++t)
    best = std::min(best, distance_to_triangle(m, t, x));
  return best;
}

// Distance from x to the nearest boundary edge of m.
double distance_to_boundary(const SurfaceMesh& m, const TriangleAdjacency& adj, const double* x) {
  double best = 1e300;
  for (size_t h = 0; h < adj.opposite.size(); ++h) {
    if (adj.opposite[h] != TriangleAdjacency::kBoundary) continue;
    const double *a = pt(m, half_edge_from(m, int32_t(h))), *b = pt(m, half_edge_to(m, int32_t(h)));
    double d[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    double t = ((x[0] - a[0]) * d[0] + (x[1] - a[1]) * d[1] + (x[2] - a[2]) * d[2]) /
               (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    t = std::clamp(t, 0.0, 1.0);
    const double q[3] = {a[0] + t * d[0], a[1] + t * d[1], a[2] + t * d[2]};
    best = std::min(best, dist(x, q));
  }
  return best;
}

std::vector<double> edge_lengths(const SurfaceMesh& m) {
  std::map<std::pair<int32_t, int32_t>, int> seen;
  std::vector<double> out;
  for (size_t t = 0; t < m.num_triangles(); ++t)
    for (int k = 0; k < 3; ++k) {
      const int32_t a = m.triangles[3 * t + k], b = m.triangles[3 * t + (k + 1) % 3];
      if (seen[std::minmax(a, b)]++ == 0) out.push_back(dist(pt(m, a), pt(m, b)));
    }
  return out;
}

// Signed volume (closed surfaces; for open ones a fan-dependent number).
double signed_volume(const SurfaceMesh& m) {
  double v = 0;
  for (size_t t = 0; t < m.num_triangles(); ++t) {
    const double *a = pt(m, m.triangles[3 * t]), *b = pt(m, m.triangles[3 * t + 1]),
                 *c = pt(m, m.triangles[3 * t + 2]);
    v += (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
          a[2] * (b[0] * c[1] - b[1] * c[0])) /
         6;
  }
  return v;
}

// Directed edges used twice: the orientation is not consistent there.
size_t inconsistent_edges(const SurfaceMesh& m) {
  std::map<std::pair<int32_t, int32_t>, int> directed;
  size_t bad = 0;
  for (size_t t = 0; t < m.num_triangles(); ++t)
    for (int k = 0; k < 3; ++k)
      if (directed[{m.triangles[3 * t + k], m.triangles[3 * t + (k + 1) % 3]}]++ == 1) ++bad;
  return bad;
}

using testing::phantom;

struct Expectations {
  bool check_size_and_quality = true;
  double median_tolerance = 0.1;  // relative
  double min_gamma = 0.3, mean_gamma = 0.9;
};

// Checks the contract of remesh_surface on `out` for input `in` at uniform
// size h.
void check_remesh(const SurfaceMesh& in, const RemeshedSurface& out, double h,
                  const Expectations& e, const std::string& name) {
  SCOPED_TRACE(name);
  const SurfaceMesh& m = out.mesh;
  ASSERT_GT(m.num_triangles(), 0u);
  ASSERT_EQ(out.home.size(), m.num_vertices());
  ASSERT_EQ(out.on_opening.size(), m.num_vertices());
  ASSERT_EQ(out.input_sizes.size(), in.num_vertices());
  for (double x : out.input_sizes) ASSERT_EQ(x, h);
  for (int32_t v : m.triangles) ASSERT_TRUE(v >= 0 && size_t(v) < m.num_vertices());
  // Every vertex used, no degenerate index triple.
  std::vector<uint8_t> used(m.num_vertices(), 0);
  for (size_t t = 0; t < m.num_triangles(); ++t) {
    const int32_t* v = &m.triangles[3 * t];
    ASSERT_TRUE(v[0] != v[1] && v[1] != v[2] && v[0] != v[2]) << "triangle " << t;
    for (int k = 0; k < 3; ++k) used[size_t(v[k])] = 1;
  }
  EXPECT_EQ(size_t(std::count(used.begin(), used.end(), 0)), 0u) << "unused output vertices";

  // Same topology, manifold, consistently oriented like the input.
  const TopologyReport ti = analyze_topology(in), to = analyze_topology(m);
  EXPECT_EQ(to.components, 1);
  EXPECT_EQ(to.nonmanifold_edges, 0u);
  EXPECT_EQ(to.nonmanifold_vertices, 0u);
  EXPECT_EQ(to.genus, ti.genus);
  EXPECT_EQ(to.openings.size(), ti.openings.size());
  EXPECT_EQ(to.closed, ti.closed);
  EXPECT_EQ(inconsistent_edges(m), 0u);
  if (ti.closed) {
    const double vi = signed_volume(in), vo = signed_volume(m);
    EXPECT_GT(vo * vi, 0) << "orientation flipped";
    EXPECT_NEAR(vo, vi, 0.05 * std::abs(vi));
  }

  // Every vertex on the input surface, within its home triangle.
  const double tol = 1e-6 * bounding_box(in.points).diagonal();
  const TriangleAdjacency in_adj = build_adjacency(in);
  size_t off_home = 0, off_surface = 0, off_boundary = 0;
  double worst_home = 0, worst_surface = 0;
  for (size_t v = 0; v < m.num_vertices(); ++v) {
    const double* x = pt(m, int32_t(v));
    const int32_t home = out.home[v];
    ASSERT_TRUE(home >= 0 && size_t(home) < in.num_triangles()) << "vertex " << v;
    const double dh = distance_to_triangle(in, size_t(home), x);
    if (dh > tol) {
      ++off_home;
      worst_home = std::max(worst_home, dh);
      // Not on its home triangle: is it on the surface at all?
      const double ds = distance_to_surface(in, x);
      if (ds > tol) ++off_surface;
      worst_surface = std::max(worst_surface, ds);
    }
    if (out.on_opening[v] && distance_to_boundary(in, in_adj, x) > tol) ++off_boundary;
  }
  EXPECT_EQ(off_surface, 0u) << "vertices off the input surface, worst " << worst_surface
                             << " (tolerance " << tol << ")";
  EXPECT_EQ(off_home, 0u) << "vertices off their home triangle, worst " << worst_home;
  EXPECT_EQ(off_boundary, 0u) << "on_opening vertices off the input openings";
  // The output's boundary vertices are exactly flagged as on an opening.
  const TriangleAdjacency out_adj = build_adjacency(m);
  size_t unflagged = 0;
  for (size_t he = 0; he < out_adj.opposite.size(); ++he)
    if (out_adj.opposite[he] == TriangleAdjacency::kBoundary &&
        !out.on_opening[size_t(half_edge_from(m, int32_t(he)))])
      ++unflagged;
  EXPECT_EQ(unflagged, 0u) << "output boundary vertices not flagged on_opening";

  // Size and quality.
  const std::vector<double> lengths = edge_lengths(m);
  const double med = median(lengths);
  const QualityStats q = quality_stats(triangle_qualities(m));
  if (e.check_size_and_quality) {
    EXPECT_NEAR(med, h, e.median_tolerance * h);
    EXPECT_GT(q.min, e.min_gamma);
    EXPECT_GT(q.mean, e.mean_gamma);
    // Openings resampled at the target size.
    for (const Opening& op : to.openings) {
      const double mean_edge = op.perimeter / double(op.loop.size());
      EXPECT_NEAR(mean_edge, h, 0.15 * h) << "opening of radius " << op.radius;
    }
  } else {
    EXPECT_GT(q.min, 0.0);
  }
  std::cout << "[ info ] " << name << ": " << in.num_triangles() << " -> " << m.num_triangles()
            << " triangles, median edge " << med << " (h " << h << "), gamma min " << q.min
            << " mean " << q.mean << "\n";
}

// Remeshes `in` at the uniform size h and checks the result (check_remesh).
void remesh_uniform_and_check(const SurfaceMesh& in, double h, const std::string& name) {
  auto r = remesh_surface(in, testing::uniform_remesh(h));
  ASSERT_TRUE(r.ok()) << r.message();
  check_remesh(in, r.value(), h, {}, name);
}

TEST(RemeshSurface, NoisyBifurcationAtUniformSize) {
  const SurfaceMesh in = phantom(PhantomKind::kBifurcation, true, 0.15, 0.3);
  ASSERT_GT(in.num_triangles(), 0u);
  ASSERT_EQ(analyze_topology(in).openings.size(), 3u);
  const double h = 0.2;
  RemeshStats stats;
  auto t0 = std::chrono::steady_clock::now();
  auto r = remesh_surface(in, testing::uniform_remesh(h), &stats);
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ASSERT_TRUE(r.ok()) << r.message();
  check_remesh(in, r.value(), h, {}, "noisy bifurcation");
  EXPECT_GE(stats.patches, 3u);
  EXPECT_EQ(stats.size_min, h);
  EXPECT_EQ(stats.size_max, h);
  std::cout << "[ info ] " << stats.patches << " patches, " << stats.seam_points << " seam points, "
            << s << " s\n";
}

TEST(RemeshSurface, ClosedPhantomAtUniformSize) {
  const SurfaceMesh in = phantom(PhantomKind::kTube, false, 0.15, 0.3);
  ASSERT_GT(in.num_triangles(), 0u);
  ASSERT_TRUE(analyze_topology(in).closed);
  remesh_uniform_and_check(in, 0.2, "closed tube");
}

TEST(RemeshSurface, TorusKeepsItsGenus) {
  const SurfaceMesh in = phantom(PhantomKind::kTorus, true, 0.15, 0.3);
  ASSERT_GT(in.num_triangles(), 0u);
  ASSERT_EQ(analyze_topology(in).genus, 1);
  remesh_uniform_and_check(in, 0.2, "torus");
}

TEST(RemeshSurface, OtherMapsAndMeshersKeepTheTopology) {
  const SurfaceMesh in = phantom(PhantomKind::kBifurcation, true, 0.2, 0.3);
  ASSERT_GT(in.num_triangles(), 0u);
  const double h = 0.25;
  struct Variant {
    const char* name;
    ParamMethod param;
    Mesher2D mesher;
  };
  const Variant variants[] = {
      {"harmonic + frontal", ParamMethod::kHarmonic, Mesher2D::kFrontal},
      {"floater + frontal", ParamMethod::kFloater, Mesher2D::kFrontal},
      {"lscm + delaunay", ParamMethod::kLscm, Mesher2D::kDelaunay},
      {"lscm + adapt", ParamMethod::kLscm, Mesher2D::kAdapt},
  };
  for (const Variant& v : variants) {
    RemeshOptions o = testing::uniform_remesh(h);
    o.param = v.param;
    o.patch.mesher = v.mesher;
    auto r = remesh_surface(in, o);
    ASSERT_TRUE(r.ok()) << v.name << ": " << r.message();
    Expectations e;
    e.check_size_and_quality = false;
    check_remesh(in, r.value(), h, e, v.name);
  }
}

TEST(RemeshSurface, AnOversampledInputIsDecimatedFirstAndTheOutputStaysOnIt) {
  // A tube with edges of about h/10: 50 times the triangles h asks for.
  const SurfaceMesh in = testing::open_tube(320, 100, 1.0, 4.0);
  const double h = 0.25;
  RemeshOptions o = testing::uniform_remesh(h);
  o.decimate_min_triangles = 10000;
  RemeshStats on, off;
  auto decimated = remesh_surface(in, o, &on);
  ASSERT_TRUE(decimated.ok()) << decimated.status().message();
  EXPECT_GT(on.decimated_triangles, 0u);
  EXPECT_LT(on.decimated_triangles, in.num_triangles() / 5);  // the rims stay fine
  // The full contract against the input itself: every vertex on its home
  // triangle of the input, sizes and gaps per input vertex.
  check_remesh(in, decimated.value(), h, {}, "decimated tube");
  ASSERT_EQ(decimated.value().input_gaps.size(), in.num_vertices());
  EXPECT_LE(on.max_input_gap, 0.1);

  o.decimate = false;
  auto full = remesh_surface(in, o, &off);
  ASSERT_TRUE(full.ok()) << full.status().message();
  EXPECT_EQ(off.decimated_triangles, 0u);
  check_remesh(in, full.value(), h, {}, "tube as it is");
  // Below the threshold nothing is decimated either.
  o.decimate = true;
  o.decimate_min_triangles = in.num_triangles() + 1;
  RemeshStats small;
  ASSERT_TRUE(remesh_surface(in, o, &small).ok());
  EXPECT_EQ(small.decimated_triangles, 0u);
  // The decimation says so to the progress callback, which may cancel it.
  o.decimate_min_triangles = 10000;
  std::vector<std::string> stages;
  auto cancelled = remesh_surface(in, o, nullptr, [&](double, std::string_view stage) {
    stages.emplace_back(stage);
    return stage != "decimating";
  });
  EXPECT_TRUE(cancelled.cancelled());
  EXPECT_EQ(stages, std::vector<std::string>{"decimating"});
}

TEST(RemeshSurface, AFailedPatchFallsBackConformingAndIsReported) {
  // One patch forced to the fallback (as when its planar meshing keeps
  // failing): the wall keeps the whole contract, and the patch is reported
  // where it is with its quality.
  const SurfaceMesh in = phantom(PhantomKind::kBifurcation, true, 0.15, 0.3);
  const double h = 0.2;
  RemeshOptions o = testing::uniform_remesh(h);
  const std::array<double, 3> asked = {in.points[0], in.points[1], in.points[2]};
  o.fallback_at = {asked};
  RemeshStats stats;
  auto r = remesh_surface(in, o, &stats);
  ASSERT_TRUE(r.ok()) << r.message();
  check_remesh(in, r.value(), h, {}, "one patch by the fallback");
  ASSERT_EQ(stats.fallback_patches.size(), 1u);
  const FallbackPatch& f = stats.fallback_patches[0];
  EXPECT_EQ(f.reason, "the fallback was asked for");
  EXPECT_GT(f.input_triangles, 0u);
  EXPECT_GT(f.triangles, 0u);
  EXPECT_LT(f.triangles, r.value().mesh.num_triangles());
  // Its place is the patch's centre: within the patch's reach of the point.
  EXPECT_LT(norm(Vec3(f.place) - Vec3(asked)), 0.1 * std::sqrt(double(f.input_triangles)));
  EXPECT_GT(f.quality_min, 0.3);
  EXPECT_GT(f.quality_mean, 0.9);
  EXPECT_LE(f.quality_min, f.quality_mean);
  const std::string w = fallback_warning(f, "mm");
  EXPECT_NE(w.find(point_text(f.place) + " mm"), std::string::npos) << w;
  EXPECT_NE(w.find("gamma_k min"), std::string::npos) << w;
}

TEST(RemeshSurface, EveryPatchByTheFallbackStillConforms) {
  // Every patch meshed by the fallback: neighbours meet on their shared
  // seam points only, so the wall is one manifold surface of the input's
  // topology.
  const SurfaceMesh in = phantom(PhantomKind::kBifurcation, true, 0.2, 0.3);
  const double h = 0.25;
  RemeshOptions o = testing::uniform_remesh(h);
  for (size_t v = 0; v < in.num_vertices(); v += 7)
    o.fallback_at.push_back({in.points[3 * v], in.points[3 * v + 1], in.points[3 * v + 2]});
  RemeshStats stats;
  auto r = remesh_surface(in, o, &stats);
  ASSERT_TRUE(r.ok()) << r.message();
  EXPECT_EQ(stats.fallback_patches.size(), stats.patches);
  check_remesh(in, r.value(), h, {}, "every patch by the fallback");
}

TEST(RemeshSurface, PatchesWhosePlanarMeshingFailsAreSplitThenFallBack) {
  // The raw staircase of a noisy binary mask (no smoothing): some patches'
  // planar boundaries cross themselves. Every failing patch is split at
  // each round; with no split allowed they fall back at once, and the wall
  // still keeps the whole contract.
  PhantomOptions po;
  po.kind = PhantomKind::kAneurysm;
  po.binary = true;
  po.noise = 0.5;
  po.voxel = 0.15;
  const SurfaceMesh in = phantom(po);
  const double h = 0.15;
  RemeshOptions o = testing::uniform_remesh(h);
  RemeshStats split_stats;
  auto split = remesh_surface(in, o, &split_stats);
  ASSERT_TRUE(split.ok()) << split.message();
  Expectations e;
  e.check_size_and_quality = false;
  check_remesh(in, split.value(), h, e, "staircase, split");
  o.max_splits = 0;
  RemeshStats stats;
  auto r = remesh_surface(in, o, &stats);
  ASSERT_TRUE(r.ok()) << r.message();
  check_remesh(in, r.value(), h, e, "staircase, fallback");
  EXPECT_EQ(stats.retries, 0u);
  ASSERT_GT(split_stats.retries + stats.fallback_patches.size(), 0u) << "no patch failed";
  for (const FallbackPatch& f : stats.fallback_patches) {
    EXPECT_EQ(f.splits, 0u);
    EXPECT_FALSE(f.reason.empty());
    EXPECT_GT(f.triangles, 0u);
    EXPECT_GT(f.quality_min, 0.0);
    std::cout << "[ info ] fallback: " << f.input_triangles << " input triangles -> " << f.triangles
              << ", gamma min " << f.quality_min << " mean " << f.quality_mean << " (" << f.reason
              << ")\n";
  }
}

TEST(RemeshSurface, InvalidSizeIsAnError) {
  const SurfaceMesh tube = testing::open_tube(16, 8);
  for (double s : {0.0, -0.5}) {
    auto r = remesh_surface(tube, testing::uniform_remesh(s));
    EXPECT_FALSE(r.ok()) << "size " << s;
  }
  RemeshOptions o = testing::uniform_remesh(0.3);
  o.size.size_min = 1;
  o.size.size_max = 0.5;
  EXPECT_FALSE(remesh_surface(tube, o).ok());
}

TEST(RemeshSurface, CancelledByProgress) {
  const SurfaceMesh tube = testing::open_tube(24, 12);
  auto r = remesh_surface(tube, testing::uniform_remesh(0.3), nullptr,
                          [](double, std::string_view) { return false; });
  ASSERT_FALSE(r.ok());
  EXPECT_TRUE(r.cancelled());
}

// ---- optimize_on_surface / project_near ------------------------------------

// The boundary edges of m, each as its sorted pair of vertices, sorted.
std::vector<std::pair<int32_t, int32_t>> sorted_boundary_edges(const SurfaceMesh& m) {
  const TriangleAdjacency adj = build_adjacency(m);
  std::vector<std::pair<int32_t, int32_t>> edges;
  for (size_t he = 0; he < adj.opposite.size(); ++he)
    if (adj.opposite[he] == TriangleAdjacency::kBoundary)
      edges.push_back(std::minmax(half_edge_from(m, int32_t(he)), half_edge_to(m, int32_t(he))));
  std::sort(edges.begin(), edges.end());
  return edges;
}

/// A fine cylinder (the input) and a coarse one whose vertices are points
/// of the input jittered along it, so it is poorly shaped; its ends fixed.
struct JitteredCylinder {
  SurfaceMesh in;
  TriangleAdjacency in_adj;
  SurfaceMesh m;
  WallVertices wall;
};

JitteredCylinder jittered_cylinder() {
  JitteredCylinder j;
  // Input: a fine cylinder. Mesh: a coarse one whose vertices are points of
  // the input, jittered along it, so it is poorly shaped.
  const double R = 1.0, L = 4.0;
  j.in = testing::open_tube(64, 32, R, L);
  j.in_adj = build_adjacency(j.in);
  j.m = testing::open_tube(16, 8, R, L);
  const SurfaceMesh& in = j.in;
  SurfaceMesh& m = j.m;
  WallVertices& wall = j.wall;
  std::vector<uint8_t>& fixed = wall.fixed;
  std::vector<int32_t>& home = wall.home;
  fixed.assign(m.num_vertices(), 0);
  home.assign(m.num_vertices(), 0);
  uint32_t state = 12345;
  auto rnd = [&] {
    state = state * 1664525u + 1013904223u;
    return double(state >> 8) / double(1u << 24) - 0.5;
  };
  for (size_t v = 0; v < m.num_vertices(); ++v) {
    double* x = &m.points[3 * v];
    const bool boundary = x[2] == 0 || x[2] == L;
    fixed[v] = boundary;
    if (!boundary) {
      // Move along the surface: turn by up to 0.25 step, shift by up to
      // 0.25 ring.
      const double a = std::atan2(x[1], x[0]) + rnd() * 0.5 * (2 * kPi / 16);
      const double z = x[2] + rnd() * 0.5 * (L / 8);
      const double q[3] = {R * std::cos(a), R * std::sin(a), z};
      double on[3];
      // Project onto the facetted input and find its triangle by brute force.
      double best = 1e300;
      for (size_t t = 0; t < in.num_triangles(); ++t) {
        double c[3];
        const double d = closest_point_on_triangle(q, pt(in, in.triangles[3 * t]),
                                                   pt(in, in.triangles[3 * t + 1]),
                                                   pt(in, in.triangles[3 * t + 2]), c);
        if (d < best) best = d, home[v] = int32_t(t), std::copy(c, c + 3, on);
      }
      std::copy(on, on + 3, x);
    } else {
      double best = 1e300;
      for (size_t t = 0; t < in.num_triangles(); ++t) {
        const double d = distance_to_triangle(in, t, x);
        if (d < best) best = d, home[v] = int32_t(t);
      }
    }
  }
  return j;
}

TEST(OptimizeSurface, ImprovesAJitteredCylinderAndStaysOnIt) {
  JitteredCylinder j = jittered_cylinder();
  const SurfaceMesh& in = j.in;
  const TriangleAdjacency& in_adj = j.in_adj;
  SurfaceMesh& m = j.m;
  WallVertices& wall = j.wall;
  const std::vector<uint8_t>& fixed = wall.fixed;
  std::vector<int32_t>& home = wall.home;
  const SurfaceMesh before = m;
  const QualityStats qb = quality_stats(triangle_qualities(m));
  const std::vector<std::pair<int32_t, int32_t>> boundary_before = sorted_boundary_edges(m);

  // No sizes (wall.size empty), no collapse: the vertex count stays.
  SurfaceOptimizeStats s = optimize_on_surface(m, wall, in, in_adj);
  const QualityStats qa = quality_stats(triangle_qualities(m));
  EXPECT_GT(s.moves + s.swaps, 0u);
  EXPECT_GE(qa.min, qb.min);
  EXPECT_GT(qa.mean, qb.mean);
  ASSERT_EQ(m.num_vertices(), before.num_vertices());
  ASSERT_EQ(m.num_triangles(), before.num_triangles());
  // Fixed vertices do not move; every vertex stays on the input, in its home.
  const double tol = 1e-6 * bounding_box(in.points).diagonal();
  for (size_t v = 0; v < m.num_vertices(); ++v) {
    if (fixed[v]) {
      for (int k = 0; k < 3; ++k) EXPECT_EQ(m.points[3 * v + k], before.points[3 * v + k]);
    }
    EXPECT_LE(distance_to_triangle(in, size_t(home[v]), pt(m, int32_t(v))), tol) << "vertex " << v;
  }
  // The boundary edges never change; the mesh stays a manifold tube.
  EXPECT_EQ(sorted_boundary_edges(m), boundary_before);
  const TopologyReport t = analyze_topology(m);
  EXPECT_EQ(t.nonmanifold_edges, 0u);
  EXPECT_EQ(t.openings.size(), 2u);
  EXPECT_EQ(t.genus, 0);
  EXPECT_EQ(inconsistent_edges(m), 0u);
  std::cout << "[ info ] optimize: gamma min " << qb.min << " -> " << qa.min << ", mean " << qb.mean
            << " -> " << qa.mean << " (" << s.moves << " moves, " << s.swaps << " swaps)\n";
}

TEST(OptimizeSurface, ARegionKeepsALocalChangeLocal) {
  // From one vertex, with and without a region of one ring around it.
  JitteredCylinder j = jittered_cylinder();
  size_t start_vertex = 0;
  while (j.wall.fixed[start_vertex]) ++start_vertex;
  std::vector<uint8_t> start(j.m.num_vertices(), 0);
  start[start_vertex] = 1;
  // The region: the vertex and its neighbours.
  std::vector<uint8_t> region = start;
  for (size_t t = 0; t < j.m.num_triangles(); ++t) {
    const int32_t* T = &j.m.triangles[3 * t];
    if (start[size_t(T[0])] || start[size_t(T[1])] || start[size_t(T[2])])
      for (int c = 0; c < 3; ++c) region[size_t(T[c])] = 1;
  }
  SurfaceOptimizeOptions options;
  SurfaceMesh free_mesh = j.m, local_mesh = j.m;
  WallVertices free_wall = j.wall, local_wall = j.wall;
  const SurfaceOptimizeStats free_stats =
      optimize_on_surface(free_mesh, free_wall, j.in, j.in_adj, options, start);
  options.region_rings = 1;
  const SurfaceOptimizeStats local_stats =
      optimize_on_surface(local_mesh, local_wall, j.in, j.in_adj, options, start);
  std::cout << "[ info ] moves from one vertex: " << free_stats.moves << " anywhere, "
            << local_stats.moves << " within one ring\n";
  EXPECT_GT(local_stats.moves, 0u);
  EXPECT_LT(local_stats.moves, free_stats.moves);
  ASSERT_EQ(local_mesh.num_vertices(), j.m.num_vertices());
  size_t moved = 0;
  for (size_t v = 0; v < region.size(); ++v) {
    const bool same =
        std::equal(&local_mesh.points[3 * v], &local_mesh.points[3 * v + 3], &j.m.points[3 * v]);
    if (!region[v]) {
      EXPECT_TRUE(same) << "vertex " << v << " outside the region moved";
    }
    moved += !same;
  }
  EXPECT_GT(moved, 0u);
  // Triangles with a corner outside the region are unchanged.
  std::set<std::array<int32_t, 3>> before, after;
  auto outside = [&](const SurfaceMesh& m, std::set<std::array<int32_t, 3>>& out) {
    for (size_t t = 0; t < m.num_triangles(); ++t) {
      std::array<int32_t, 3> T{m.triangles[3 * t], m.triangles[3 * t + 1], m.triangles[3 * t + 2]};
      if (!region[size_t(T[0])] || !region[size_t(T[1])] || !region[size_t(T[2])]) out.insert(T);
    }
  };
  outside(j.m, before);
  outside(local_mesh, after);
  EXPECT_EQ(before, after);
}

TEST(OptimizeSurface, CollapsesShortEdgesAndRegularizesValences) {
  // Input: a fine cylinder. Mesh: a coarse regular one (valence 6) where
  // every fourth triangle is split at its centroid, which makes valence-3
  // vertices, short edges and poor triangles.
  const double R = 1.0, L = 4.0;
  const SurfaceMesh in = testing::open_tube(64, 32, R, L);
  const TriangleAdjacency in_adj = build_adjacency(in);
  SurfaceMesh m = testing::open_tube(16, 12, R, L);
  const double regular_mean = quality_stats(triangle_qualities(m)).mean;
  const size_t split = m.num_triangles();
  for (size_t t = 0; t < split; t += 4) {
    const int32_t a = m.triangles[3 * t], b = m.triangles[3 * t + 1], c = m.triangles[3 * t + 2];
    const int32_t v = int32_t(m.num_vertices());
    for (int k = 0; k < 3; ++k) m.points.push_back((pt(m, a)[k] + pt(m, b)[k] + pt(m, c)[k]) / 3);
    m.triangles[3 * t + 2] = v;
    m.triangles.insert(m.triangles.end(), {b, c, v, c, a, v});
  }
  WallVertices wall;
  std::vector<uint8_t>& fixed = wall.fixed;
  std::vector<int32_t>& home = wall.home;
  fixed.assign(m.num_vertices(), 0);
  home.assign(m.num_vertices(), 0);
  for (size_t v = 0; v < m.num_vertices(); ++v) {
    const double* x = pt(m, int32_t(v));
    fixed[v] = x[2] == 0 || x[2] == L;
    double best = 1e300;
    for (size_t t = 0; t < in.num_triangles(); ++t) {
      const double d = distance_to_triangle(in, t, x);
      if (d < best) best = d, home[v] = int32_t(t);
    }
  }
  const double h = 2 * kPi * R / 16;
  std::vector<double>& size = wall.size;
  size.assign(m.num_vertices(), h);
  auto short_edges = [&](const SurfaceMesh& s) {
    size_t n = 0;
    for (size_t t = 0; t < s.num_triangles(); ++t)
      for (int k = 0; k < 3; ++k)
        n += dist(pt(s, s.triangles[3 * t + k]), pt(s, s.triangles[3 * t + (k + 1) % 3])) < 0.7 * h;
    return n;
  };
  auto valence3 = [](const SurfaceMesh& s, const std::vector<uint8_t>& boundary) {
    std::vector<int> valence(s.num_vertices(), 0);
    for (int32_t v : s.triangles) ++valence[size_t(v)];
    size_t n = 0;
    for (size_t v = 0; v < valence.size(); ++v) n += !boundary[v] && valence[v] == 3;
    return n;
  };
  const QualityStats qb = quality_stats(triangle_qualities(m));
  const size_t short_before = short_edges(m);
  ASSERT_GT(short_before, 0u);
  ASSERT_GT(valence3(m, fixed), 0u);
  std::vector<double> fixed_points;
  for (size_t v = 0; v < m.num_vertices(); ++v)
    if (fixed[v]) fixed_points.insert(fixed_points.end(), pt(m, int32_t(v)), pt(m, int32_t(v)) + 3);

  SurfaceOptimizeStats s = optimize_on_surface(m, wall, in, in_adj);
  EXPECT_GT(s.collapses, 0u);
  ASSERT_EQ(home.size(), m.num_vertices());
  ASSERT_EQ(fixed.size(), m.num_vertices());
  ASSERT_EQ(size.size(), m.num_vertices());
  const QualityStats qa = quality_stats(triangle_qualities(m));
  EXPECT_GT(qa.min, qb.min);
  EXPECT_GT(qa.mean, regular_mean - 0.01);  // the unsplit grid's triangles
  EXPECT_LT(short_edges(m), short_before / 4);
  EXPECT_EQ(valence3(m, fixed), 0u);  // no interior vertex of valence 3 left
  // Same topology, consistently oriented, every vertex used and on the
  // input, the opening vertices where they were.
  const TopologyReport t = analyze_topology(m);
  EXPECT_EQ(t.nonmanifold_edges, 0u);
  EXPECT_EQ(t.openings.size(), 2u);
  EXPECT_EQ(t.genus, 0);
  EXPECT_EQ(inconsistent_edges(m), 0u);
  std::vector<uint8_t> used(m.num_vertices(), 0);
  for (int32_t v : m.triangles) used[size_t(v)] = 1;
  EXPECT_EQ(size_t(std::count(used.begin(), used.end(), 1)), m.num_vertices());
  const double tol = 1e-6 * bounding_box(in.points).diagonal();
  std::vector<double> fixed_after;
  for (size_t v = 0; v < m.num_vertices(); ++v) {
    EXPECT_LE(distance_to_triangle(in, size_t(home[v]), pt(m, int32_t(v))), tol) << "vertex " << v;
    if (fixed[v]) fixed_after.insert(fixed_after.end(), pt(m, int32_t(v)), pt(m, int32_t(v)) + 3);
  }
  EXPECT_EQ(fixed_after, fixed_points);
  std::cout << "[ info ] collapse: gamma min " << qb.min << " -> " << qa.min << ", mean " << qb.mean
            << " -> " << qa.mean << " (" << s.collapses << " collapses, " << s.swaps << " swaps)\n";
}

TEST(OptimizeSurface, SameMeshOnAnyThreadCount) {
  // The input tube's grid, every interior vertex moved along the input by
  // up to 0.3 of a step: 8,320 vertices, more than the smoothing's blocks,
  // in row order (most in their block's inside, the rows at the blocks'
  // ends colored).
  const int n = 128, rows = 64;
  const SurfaceMesh in = testing::open_tube(n, rows, 1.0, 4.0);
  const TriangleAdjacency in_adj = build_adjacency(in);
  SurfaceMesh m0 = in;
  WallVertices wall0;
  wall0.fixed.assign(m0.num_vertices(), 0);
  wall0.home.assign(m0.num_vertices(), 0);
  uint32_t state = 777;
  auto rnd = [&] {
    state = state * 1664525u + 1013904223u;
    return double(state >> 8) / double(1u << 24) - 0.5;
  };
  for (int j = 0; j <= rows; ++j)
    for (int i = 0; i < n; ++i) {
      const size_t v = size_t(j * n + i);
      // A triangle of the vertex's row of quads (the last row: the one below).
      const int32_t start = int32_t(2 * (std::min(j, rows - 1) * n + i));
      if (j == 0 || j == rows) {
        wall0.fixed[v] = kOnOpening;
        wall0.home[v] = start;
        continue;
      }
      const double a = 2 * kPi * (i + 0.6 * rnd()) / n, z = 4.0 * (j + 0.6 * rnd()) / rows;
      const double q[3] = {std::cos(a), std::sin(a), z};
      wall0.home[v] = project_near(q, start, in, in_adj, &m0.points[3 * v]);
    }
  const double q0 = quality_stats(triangle_qualities(m0)).mean;
  SurfaceMesh reference;
  WallVertices reference_wall;
  for (int threads : {1, 2, 3}) {
    set_thread_count(threads);
    SurfaceMesh m = m0;
    WallVertices wall = wall0;
    const SurfaceOptimizeStats s = optimize_on_surface(m, wall, in, in_adj);
    EXPECT_GT(s.moves, m.num_vertices());
    EXPECT_GT(quality_stats(triangle_qualities(m)).mean, q0 + 0.05);
    if (threads == 1) {
      reference = m;
      reference_wall = wall;
      continue;
    }
    EXPECT_EQ(m.points, reference.points) << threads << " threads";
    EXPECT_EQ(m.triangles, reference.triangles) << threads << " threads";
    EXPECT_EQ(wall.home, reference_wall.home) << threads << " threads";
  }
  set_thread_count(0);
}

TEST(OptimizeSurface, ProjectNearFindsTheClosestPoint) {
  const SurfaceMesh in = testing::open_tube(32, 16, 1.0, 4.0);
  const TriangleAdjacency adj = build_adjacency(in);
  // Points off the cylinder, starting the walk a few triangles away.
  for (int i = 0; i < 20; ++i) {
    const double a = 0.3 + 0.29 * i, z = 0.5 + 0.15 * i, r = 0.8 + 0.02 * i;
    const double q[3] = {r * std::cos(a), r * std::sin(a), z};
    // A start triangle near q: the brute-force closest, then a neighbor
    // of a neighbor.
    size_t best_t = 0;
    double best = 1e300;
    for (size_t t = 0; t < in.num_triangles(); ++t) {
      const double d = distance_to_triangle(in, t, q);
      if (d < best) best = d, best_t = t;
    }
    int32_t start = int32_t(best_t);
    for (int step = 0; step < 2; ++step) {
      const int32_t o = adj.opposite[3 * size_t(start)];
      if (o >= 0) start = o / 3;
    }
    double out[3];
    const int32_t t = project_near(q, start, in, adj, out);
    ASSERT_TRUE(t >= 0 && size_t(t) < in.num_triangles());
    EXPECT_LE(distance_to_triangle(in, size_t(t), out), 1e-12);
    EXPECT_NEAR(dist(q, out), best, 1e-9) << "point " << i;
  }
}

// ---- resample_curve -----------------------------------------------------------

// Arc length of sample s on the polyline (segments wrap for a closed one).
double arc_of(const std::vector<double>& pts, const CurveSample& s) {
  const size_t n = pts.size() / 3;
  double acc = 0;
  for (size_t i = 0; i < s.segment; ++i) acc += dist(&pts[3 * i], &pts[3 * ((i + 1) % n)]);
  return acc + s.t * dist(&pts[3 * s.segment], &pts[3 * ((s.segment + 1) % n)]);
}

TEST(ResampleCurve, EvenSamplesOnAStraightPolyline) {
  // Unevenly spaced points on a straight line of length 3.7.
  const std::vector<double> xs = {0, 0.1, 0.35, 1.2, 1.25, 2.9, 3.7};
  const double dir[3] = {0.6, 0, 0.8};
  std::vector<double> pts;
  for (double x : xs) pts.insert(pts.end(), {1 + x * dir[0], -2 + x * dir[1], 0.5 + x * dir[2]});
  const double L = 3.7;
  for (double h : {0.1, 0.3, 0.37, 0.5, 1.1}) {
    const std::vector<double> sizes(xs.size(), h);
    const auto s = resample_curve(pts, sizes, false, 1);
    const size_t n = size_t(std::lround(L / h));
    ASSERT_EQ(s.size(), n) << "h = " << h;
    EXPECT_EQ(s[0].segment, 0u);
    EXPECT_EQ(s[0].t, 0.0);
    for (size_t i = 0; i < s.size(); ++i) {
      ASSERT_LT(s[i].segment, xs.size() - 1);
      EXPECT_GE(s[i].t, 0.0);
      EXPECT_LE(s[i].t, 1.0);
      EXPECT_NEAR(arc_of(pts, s[i]), L * double(i) / double(n), 1e-9) << "h = " << h;
    }
  }
  // min_segments wins over a coarse size.
  const auto s = resample_curve(pts, std::vector<double>(xs.size(), 10.0), false, 3);
  ASSERT_EQ(s.size(), 3u);
  for (size_t i = 0; i < 3; ++i) EXPECT_NEAR(arc_of(pts, s[i]), L * double(i) / 3, 1e-9);
}

TEST(ResampleCurve, ClosedLoopIncludesTheClosingSegment) {
  // A 2 x 1 rectangle, perimeter 6.
  const std::vector<double> pts = {0, 0, 0, 2, 0, 0, 2, 1, 0, 0, 1, 0};
  const auto s = resample_curve(pts, std::vector<double>(4, 0.25), true, 3);
  ASSERT_EQ(s.size(), 24u);
  bool on_closing = false;
  for (size_t i = 0; i < s.size(); ++i) {
    ASSERT_LT(s[i].segment, 4u);
    on_closing |= s[i].segment == 3;
    EXPECT_NEAR(arc_of(pts, s[i]), 0.25 * double(i), 1e-9);
  }
  EXPECT_TRUE(on_closing);
}

// Straight line of length 4 along x, h = 0.1 + 0.1 x at its points (so h
// is linear along the whole line), split into `n_pts - 1` segments. The
// integral of 1 / h from 0 to x is F(x) = 10 ln(1 + x).
void graded_line(int n_pts, std::vector<double>& pts, std::vector<double>& sizes) {
  for (int i = 0; i < n_pts; ++i) {
    const double x = 4.0 * i / (n_pts - 1);
    pts.insert(pts.end(), {x, 0, 0});
    sizes.push_back(0.1 + 0.1 * x);
  }
}
double graded_integral(double x) { return 10 * std::log(1 + x); }

TEST(ResampleCurve, GradedSizeStretchesTheSpacing) {
  std::vector<double> pts, sizes;
  const int n_pts = 9;
  graded_line(n_pts, pts, sizes);
  const auto s = resample_curve(pts, sizes, false, 1);
  const double integral = graded_integral(4.0);
  ASSERT_EQ(s.size(), size_t(std::lround(integral)));
  std::vector<double> at;
  for (const auto& c : s) at.push_back(arc_of(pts, c));
  at.push_back(4.0);
  EXPECT_EQ(at[0], 0.0);
  // Spacing never shrinks where h grows, and ends about 5 times coarser.
  for (size_t i = 1; i + 1 < at.size(); ++i)
    EXPECT_GE(at[i + 1] - at[i], at[i] - at[i - 1] - 1e-12) << "sample " << i;
  EXPECT_GT(at[at.size() - 1] - at[at.size() - 2], 3 * (at[1] - at[0]));
  // Each polyline segment holds its share of the integral, to one sample.
  for (int seg = 0; seg + 1 < n_pts; ++seg) {
    const double x0 = 4.0 * seg / (n_pts - 1), x1 = 4.0 * (seg + 1) / (n_pts - 1);
    const double share = (graded_integral(x1) - graded_integral(x0)) * double(s.size()) / integral;
    const auto in_seg = std::count_if(
        s.begin(), s.end(), [&](const CurveSample& c) { return c.segment == size_t(seg); });
    EXPECT_NEAR(double(in_seg), share, 1.0) << "segment " << seg;
  }
}

TEST(ResampleCurve, GradedSamplesAtUnitStepsOfTheIntegralWithinASegment) {
  std::vector<double> pts, sizes;
  graded_line(9, pts, sizes);
  const auto s = resample_curve(pts, sizes, false, 1);
  const double integral = graded_integral(4.0);
  ASSERT_EQ(s.size(), size_t(std::lround(integral)));
  // Sample i at F = i * integral / count (the count rounds the integral,
  // so the unit step is stretched evenly).
  for (size_t i = 0; i < s.size(); ++i)
    EXPECT_NEAR(graded_integral(arc_of(pts, s[i])), double(i) * integral / double(s.size()), 0.02)
        << "sample " << i;
}

}  // namespace
}  // namespace vm
