#include "core/volume/delaunay3d.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <set>
#include <thread>
#include <vector>

#include "core/geom/predicates.h"
#include "core/mesh/volume_mesh.h"
#include "core/util/parallel.h"
#include "tests/support/volume_inputs.h"

namespace vm {
namespace {

using D = Delaunay3D;

std::vector<double> grid(int n, double spacing = 1) {
  std::vector<double> p;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k) p.insert(p.end(), {i * spacing, j * spacing, k * spacing});
  return p;
}

// n random points rounded onto the unit sphere (3 doubles each).
std::vector<double> random_sphere_points(int n, uint32_t seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> g;
  std::vector<double> s;
  for (int i = 0; i < n; ++i) {
    double v[3] = {g(rng), g(rng), g(rng)};
    double l = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    s.insert(s.end(), {v[0] / l, v[1] / l, v[2] / l});
  }
  return s;
}

// Counting identities of a triangulated convex ball: V - E + F - T = 1
// over the finite complex, and the hull (ghosts) a triangulated sphere with
// H = 2 Vh - 4 faces; 4 T = 2 F_inner + H.
void expect_counting_identities(const D& d) {
  std::set<std::array<int32_t, 2>> edges;
  std::set<std::array<int32_t, 3>> faces;
  std::set<int32_t> verts, hull_verts;
  int64_t tets = 0, ghosts = 0;
  for (int32_t t = 0; t < int32_t(d.tet_capacity()); ++t) {
    if (!d.is_live(t)) continue;
    const int32_t* v = d.tet(t);
    if (d.is_ghost(t)) {
      ++ghosts;
      for (int k = 0; k < 4; ++k)
        if (v[k] != D::kInfinite) hull_verts.insert(v[k]);
      continue;
    }
    ++tets;
    for (int i = 0; i < 4; ++i) {
      verts.insert(v[i]);
      for (int j = i + 1; j < 4; ++j) edges.insert({std::min(v[i], v[j]), std::max(v[i], v[j])});
      std::array<int32_t, 3> f;
      for (int s = 0, m = 0; s < 4; ++s)
        if (s != i) f[m++] = v[s];
      std::sort(f.begin(), f.end());
      faces.insert(f);
    }
  }
  EXPECT_EQ(int64_t(verts.size()) - int64_t(edges.size()) + int64_t(faces.size()) - tets, 1);
  EXPECT_EQ(ghosts, 2 * int64_t(hull_verts.size()) - 4);
  EXPECT_EQ(4 * tets, 2 * (int64_t(faces.size()) - ghosts) + ghosts);
}

double total_volume(const D& d) {
  double vol = 0;
  d.for_each_finite_tet([&](int32_t t) {
    const int32_t* v = d.tet(t);
    vol += tet_volume6(d.point(v[0]), d.point(v[1]), d.point(v[2]), d.point(v[3])) / 6;
  });
  return vol;
}

// Brute force: no vertex strictly inside any circumsphere; every finite
// tetrahedron positive.
void expect_empty_spheres(const D& d) {
  int64_t violations = 0;
  d.for_each_finite_tet([&](int32_t t) {
    const int32_t* v = d.tet(t);
    const double* a = d.point(v[0]);
    const double* b = d.point(v[1]);
    const double* c = d.point(v[2]);
    const double* e = d.point(v[3]);
    EXPECT_GT(tet_volume6(a, b, c, e), 0);
    for (int32_t w = 0; w < int32_t(d.num_vertices()); ++w) {
      if (d.duplicate_of(w) >= 0) continue;
      violations += insphere(a, b, c, e, d.point(w)) < 0;
    }
  });
  EXPECT_EQ(violations, 0);
}

TEST(Delaunay3D, RandomPointsSatisfyAllInvariants) {
  for (int n : {4, 5, 10, 100, 400}) {
    auto r = D::build(testing::random_cube_points(n, uint32_t(n)));
    ASSERT_TRUE(r.ok()) << r.message();
    const D& d = r.value();
    ASSERT_TRUE(d.check(true).ok()) << d.check(true).message();
    expect_empty_spheres(d);
    expect_counting_identities(d);
    for (int32_t v = 0; v < n; ++v) EXPECT_GE(d.vertex_tet(v), 0);
  }
}

TEST(Delaunay3D, LargerRandomSetIsLocallyDelaunay) {
  auto r = D::build(testing::random_cube_points(30000, 1));
  ASSERT_TRUE(r.ok());
  EXPECT_TRUE(r.value().check(true).ok()) << r.value().check(true).message();
  expect_counting_identities(r.value());
  // About 6.5 tetrahedra per point for uniform points.
  double per_point = double(r.value().num_finite_tets()) / 30000;
  EXPECT_GT(per_point, 6.0);
  EXPECT_LT(per_point, 7.0);
}

TEST(Delaunay3D, GridIsCosphericalEverywhere) {
  for (int n : {2, 3, 6}) {
    auto r = D::build(grid(n, 0.5));
    ASSERT_TRUE(r.ok()) << r.message();
    const D& d = r.value();
    ASSERT_TRUE(d.check(true).ok()) << d.check(true).message();
    expect_empty_spheres(d);
    expect_counting_identities(d);
    const double side = (n - 1) * 0.5;
    EXPECT_NEAR(total_volume(d), side * side * side, 1e-12);
  }
}

TEST(Delaunay3D, PointsOnASphere) {
  // Exactly cospherical integer points (x^2 + y^2 + z^2 = 50) and random
  // points rounded onto the unit sphere: all on the hull.
  std::vector<double> p;
  for (int x = -7; x <= 7; ++x)
    for (int y = -7; y <= 7; ++y)
      for (int z = -7; z <= 7; ++z)
        if (x * x + y * y + z * z == 50) p.insert(p.end(), {double(x), double(y), double(z)});
  ASSERT_GT(p.size(), 3u * 50);
  auto r = D::build(p);
  ASSERT_TRUE(r.ok()) << r.message();
  ASSERT_TRUE(r.value().check(true).ok()) << r.value().check(true).message();
  expect_empty_spheres(r.value());
  expect_counting_identities(r.value());

  auto q = D::build(random_sphere_points(2000, 4));
  ASSERT_TRUE(q.ok());
  EXPECT_TRUE(q.value().check(true).ok()) << q.value().check(true).message();
  expect_counting_identities(q.value());
}

TEST(Delaunay3D, LargeCavitiesAndPointsFarOutsideTheBox) {
  // The star links small cavities through a table of local vertex ids and
  // large ones (more than kMaxTableFaces boundary faces) through a hash;
  // the static filter bounds grow with the box of the vertices. The centre
  // of points on a sphere conflicts with every tetrahedron; a point far
  // outside sees half the hull.
  auto r = D::build(random_sphere_points(600, 11));
  ASSERT_TRUE(r.ok());
  D d = std::move(r.value());
  const double centre[3] = {1e-3, -2e-3, 3e-3};
  ASSERT_EQ(d.insert(centre).status, D::InsertStatus::kInserted);
  EXPECT_EQ(d.last_inserted_tets().size(), size_t(2 * 600 - 4));  // every hull face
  ASSERT_TRUE(d.check(true).ok()) << d.check(true).message();
  const double far[3] = {100, 1, -2};
  ASSERT_EQ(d.insert(far).status, D::InsertStatus::kInserted);
  EXPECT_GT(d.last_inserted_tets().size(), size_t(124));
  ASSERT_TRUE(d.check(true).ok()) << d.check(true).message();
  expect_empty_spheres(d);
  expect_counting_identities(d);
  // Small cavities after the large ones, inside and outside the old box.
  for (const auto& q : {std::array<double, 3>{0.5, 0.1, 0.2}, std::array<double, 3>{-3, 0, 0},
                        std::array<double, 3>{0, 0, 1e4}})
    ASSERT_EQ(d.insert(q.data()).status, D::InsertStatus::kInserted);
  ASSERT_TRUE(d.check(true).ok()) << d.check(true).message();
  expect_empty_spheres(d);
  const double beyond[3] = {1e6, 0, 0}, inside[3] = {0.2, 0.2, 0.2};
  EXPECT_EQ(d.locate(beyond).type, D::LocationType::kOutside);
  EXPECT_EQ(d.locate(inside).type, D::LocationType::kInside);
}

TEST(Delaunay3D, PartitionedRoundInsertsOnlyInOwnTetrahedraWithAnyThreadCount) {
  // Two parts split at x = 0: each inserts its points at the same time as
  // the other, walking from a tetrahedron of its own; a point whose walk or
  // cavity needs the other part's tetrahedra is refused (kForeign) and
  // inserted after the round. The result is the Delaunay triangulation
  // (unconstrained, so the cavities are the conflict regions; points
  // outside the hull wait too: a part's insertion respects the hull), the new
  // vertices renumbered part by part, and the same on 1 or 2 threads.
  const std::vector<double> base = testing::random_cube_points(3000, 21);
  const std::vector<double> extra = testing::random_cube_points(4000, 22);
  struct Outcome {
    std::vector<double> points;
    std::vector<int32_t> tets;
    size_t foreign = 0;
  };
  auto run = [&](int threads) {
    set_thread_count(threads);
    auto r = D::build(base);
    EXPECT_TRUE(r.ok());
    D d = std::move(r.value());
    const size_t n0 = d.num_vertices();
    auto part_of = [](const double* x) { return x[0] < 0 ? 0 : 1; };
    std::vector<uint8_t> part(n0);
    for (size_t v = 0; v < n0; ++v) part[v] = uint8_t(part_of(d.point(int32_t(v))));
    d.begin_partitions(part, {{2500, 20000}, {2500, 20000}});
    EXPECT_EQ(d.part_vertex_begin(0), int32_t(n0));
    EXPECT_EQ(d.part_vertex_begin(1), int32_t(n0) + 2500);
    std::vector<std::vector<size_t>> refused(2), outside(2);
    std::vector<std::vector<std::pair<int32_t, size_t>>> made(2);  // round id, point
    // A first tetrahedron of each part (found before the parts start: a
    // part may only read its own tetrahedra and their neighbors).
    int32_t first[2] = {-1, -1};
    for (int32_t t = 0; t < int32_t(d.tet_capacity()); ++t)
      for (int k = 0; k < 2; ++k)
        if (first[k] < 0 && d.is_live(t) && d.in_part(k, t)) first[k] = t;
    parallel_for(2, 1, [&](size_t b, size_t e) {
      for (size_t k = b; k < e; ++k) {
        const int part_k = int(k);
        int32_t hint = first[k];
        for (size_t i = 0; i < extra.size() / 3; ++i) {
          const double* p = &extra[3 * i];
          if (part_of(p) != part_k) continue;
          const D::InsertResult ins = d.insert_in(part_k, p, hint, 0);
          if (ins.status == D::InsertStatus::kForeign) {
            refused[k].push_back(i);
          } else if (ins.status == D::InsertStatus::kOutsideHull) {
            outside[k].push_back(i);  // inserted after the round
          } else {
            EXPECT_EQ(ins.status, D::InsertStatus::kInserted);
            EXPECT_GE(ins.vertex, d.part_vertex_begin(part_k));
            made[k].push_back({ins.vertex, i});
            hint = d.vertex_tet(ins.vertex);  // a tetrahedron of the part
          }
        }
      }
    });
    const std::vector<int32_t> remap = d.end_partitions();
    Outcome out;
    size_t next = n0;
    for (int k = 0; k < 2; ++k)
      for (const auto& [id, i] : made[size_t(k)]) {
        // Renumbered part by part, in insertion order, the point unchanged.
        const int32_t v = remap[size_t(id) - n0];
        EXPECT_EQ(v, int32_t(next++));
        for (int c = 0; c < 3; ++c) EXPECT_EQ(d.point(v)[c], extra[3 * i + size_t(c)]);
      }
    EXPECT_EQ(d.num_vertices(), next);
    for (int k = 0; k < 2; ++k) {
      out.foreign += refused[size_t(k)].size();
      for (size_t i : refused[size_t(k)])
        EXPECT_EQ(d.insert(&extra[3 * i]).status, D::InsertStatus::kInserted);
      for (size_t i : outside[size_t(k)])
        EXPECT_EQ(d.insert(&extra[3 * i]).status, D::InsertStatus::kInserted);
    }
    EXPECT_TRUE(d.check(true).ok()) << d.check(true).message();
    expect_counting_identities(d);
    out.points = d.points();
    out.tets = d.finite_tets();
    set_thread_count(0);
    return out;
  };
  const Outcome one = run(1), two = run(2);
  // Most points go in during the round; those near the cut do not.
  EXPECT_GT(one.foreign, 0u);
  EXPECT_LT(one.foreign, extra.size() / 3 / 4);
  EXPECT_EQ(one.foreign, two.foreign);
  EXPECT_EQ(one.points, two.points);
  EXPECT_EQ(one.tets, two.tets);
}

// The finite tetrahedra as sorted vertex quadruples, sorted: the
// triangulation whatever the slots.
std::vector<std::array<int32_t, 4>> tet_set(const D& d) {
  std::vector<std::array<int32_t, 4>> out;
  d.for_each_finite_tet([&](int32_t t) {
    std::array<int32_t, 4> q;
    std::copy(d.tet(t), d.tet(t) + 4, q.begin());
    std::sort(q.begin(), q.end());
    out.push_back(q);
  });
  std::sort(out.begin(), out.end());
  return out;
}

TEST(Delaunay3D, BuildInSlabRoundsIsTheDelaunayTriangulationOnAnyThreadCount) {
  // 30,000 points in a cube and copies of three of them: past the first
  // 2 (3) x 4096 points, rounds of two (three) slabs insert at the same time.
  std::vector<double> p = testing::random_cube_points(30000, 31);
  for (int src : {100, 15000, 29999})
    for (int k = 0; k < 3; ++k) p.push_back(p[3 * size_t(src) + k]);
  struct Outcome {
    std::vector<int32_t> tets, dup;
    int64_t rounds = 0;
  };
  auto run = [&](int parts, int threads) {
    set_thread_count(threads);
    D::BuildOptions o;
    o.parts = parts;
    o.min_part_points = 4096;
    auto r = D::build(p, o);
    set_thread_count(0);
    EXPECT_TRUE(r.ok()) << r.message();
    const D& d = r.value();
    EXPECT_TRUE(d.check(true).ok()) << d.check(true).message();
    Outcome out;
    out.tets = d.finite_tets();
    for (int32_t v = 0; v < int32_t(d.num_vertices()); ++v) {
      out.dup.push_back(d.duplicate_of(v));
      if (d.duplicate_of(v) < 0) {
        EXPECT_GE(d.vertex_tet(v), 0);
      }
    }
    out.rounds = d.stats().build_rounds;
    return std::make_pair(out, tet_set(d));
  };
  const auto [sequential, sequential_set] = run(1, 2);
  EXPECT_EQ(sequential.rounds, 0);
  for (int parts : {2, 3}) {
    const auto [one, one_set] = run(parts, 1);
    const auto [two, two_set] = run(parts, 2);
    EXPECT_GT(one.rounds, 0);
    // The same slots on any thread count.
    EXPECT_EQ(one.tets, two.tets);
    EXPECT_EQ(one.dup, two.dup);
    EXPECT_EQ(one.rounds, two.rounds);
    // The Delaunay triangulation (unique, ties perturbed by input index),
    // and the same duplicates.
    EXPECT_EQ(one_set, sequential_set);
    EXPECT_EQ(one.dup, sequential.dup);
  }
  int dups = 0;
  for (int32_t o : sequential.dup) dups += o >= 0;
  EXPECT_EQ(dups, 3);
}

TEST(Delaunay3D, BuildOfPointsOnASurfaceStaysSequential) {
  // Every point on the hull: no part could insert one, so no round runs.
  D::BuildOptions o;
  o.min_part_points = 1024;
  auto r = D::build(random_sphere_points(8000, 3), o);
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r.value().stats().build_rounds, 0);
  EXPECT_TRUE(r.value().check(true).ok());
}

TEST(Delaunay3D, BuildOptionsOutOfRangeAreRefused) {
  const std::vector<double> p = testing::random_cube_points(100, 4);
  for (auto set : std::vector<void (*)(D::BuildOptions&)>{
           [](D::BuildOptions& o) { o.parts = 0; }, [](D::BuildOptions& o) { o.parts = 65; },
           [](D::BuildOptions& o) { o.min_part_points = 0; },
           [](D::BuildOptions& o) { o.retry_rounds = -1; }}) {
    D::BuildOptions o;
    set(o);
    auto r = D::build(p, o);
    ASSERT_FALSE(r.ok());
    EXPECT_NE(r.message().find("1 <= parts <= 64"), std::string::npos) << r.message();
  }
}

TEST(Delaunay3D, DuplicatePointsAreReported) {
  auto p = testing::random_cube_points(200, 9);
  auto g = grid(3);
  p.insert(p.end(), g.begin(), g.end());
  // Copies of points 5 and 7 and of a grid point.
  for (int src : {5, 7, 200 + 4, 5})
    for (int k = 0; k < 3; ++k) p.push_back(p[3 * size_t(src) + k]);
  const int n = int(p.size() / 3);
  auto r = D::build(p);
  ASSERT_TRUE(r.ok());
  const D& d = r.value();
  ASSERT_TRUE(d.check(true).ok()) << d.check(true).message();
  int dups = 0;
  for (int v = 0; v < n; ++v) {
    int32_t o = d.duplicate_of(v);
    if (o < 0) continue;
    ++dups;
    EXPECT_EQ(d.point(o)[0], d.point(v)[0]);
    EXPECT_EQ(d.point(o)[1], d.point(v)[1]);
    EXPECT_EQ(d.point(o)[2], d.point(v)[2]);
    EXPECT_LT(d.duplicate_of(o), 0);
  }
  EXPECT_EQ(dups, 4);
  expect_empty_spheres(d);
}

TEST(Delaunay3D, DegenerateInputsAreClearErrors) {
  EXPECT_FALSE(D::build({}).ok());
  EXPECT_FALSE(D::build({0, 0, 0, 1, 0, 0, 0, 1, 0}).ok());
  // Coplanar: a planar grid.
  std::vector<double> plane;
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 5; ++j) plane.insert(plane.end(), {double(i), double(j), 0.0});
  auto r = D::build(plane);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.message().find("coplanar"), std::string::npos);
  // Collinear and all-equal.
  std::vector<double> line, same;
  for (int i = 0; i < 10; ++i) line.insert(line.end(), {double(i), 2.0 * i, -1.0 * i});
  for (int i = 0; i < 10; ++i) same.insert(same.end(), {1.0, 2.0, 3.0});
  EXPECT_FALSE(D::build(line).ok());
  EXPECT_FALSE(D::build(same).ok());
  std::vector<double> nan = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, std::nan("")};
  EXPECT_FALSE(D::build(nan).ok());
  // The planar grid plus one apex: a valid pyramid of flat-bottomed tets.
  plane.insert(plane.end(), {2.0, 2.0, 3.0});
  auto q = D::build(plane);
  ASSERT_TRUE(q.ok()) << q.message();
  EXPECT_TRUE(q.value().check(true).ok()) << q.value().check(true).message();
  EXPECT_DOUBLE_EQ(total_volume(q.value()), 16.0 * 3 / 3);
  expect_empty_spheres(q.value());
}

TEST(Delaunay3D, InsertAfterBuildInsideOutsideAndDuplicate) {
  auto r = D::build(testing::random_cube_points(300, 2));
  ASSERT_TRUE(r.ok());
  D d = std::move(r.value());
  auto more = testing::random_cube_points(300, 3);
  for (double& x : more) x *= 1.5;  // some outside the hull
  for (size_t i = 0; i < more.size(); i += 3) {
    auto ins = d.insert(&more[i]);
    ASSERT_EQ(ins.status, D::InsertStatus::kInserted);
    EXPECT_EQ(ins.vertex, int32_t(d.num_vertices()) - 1);
  }
  ASSERT_TRUE(d.check(true).ok()) << d.check(true).message();
  expect_empty_spheres(d);
  const size_t nv = d.num_vertices();
  auto dup = d.insert(d.point(17));
  EXPECT_EQ(dup.status, D::InsertStatus::kDuplicate);
  EXPECT_EQ(dup.vertex, 17);
  EXPECT_EQ(d.num_vertices(), nv);
  const double inf[3] = {0, INFINITY, 0};
  EXPECT_EQ(d.insert(inf).status, D::InsertStatus::kInvalid);
}

TEST(Delaunay3D, InsertRefusesAPointTooCloseToACavityVertex) {
  auto r = D::build(testing::random_cube_points(400, 5));
  ASSERT_TRUE(r.ok());
  D d = std::move(r.value());
  // The nearest vertex of a query point is always a vertex of its cavity
  // (a Delaunay neighbor once inserted): refused within that distance,
  // accepted just below it, for both cavity searches.
  auto queries = testing::random_cube_points(50, 6);
  for (double& x : queries) x *= 0.7;  // inside the hull
  auto nearest_to = [&](const double* q) {
    double nearest = 1e300;
    for (int32_t v = 0; v < int32_t(d.num_vertices()); ++v) {
      const double* x = d.point(v);
      nearest = std::min(nearest, std::hypot(x[0] - q[0], x[1] - q[1], x[2] - q[2]));
    }
    return nearest;
  };
  for (bool constrained : {false, true}) {
    for (size_t i = 0; i < queries.size(); i += 3) {
      const double* q = &queries[i];
      const double nearest = nearest_to(q);
      const size_t nv = d.num_vertices(), nt = d.num_finite_tets();
      EXPECT_EQ(d.insert(q, -1, constrained, nearest * 1.001).status, D::InsertStatus::kTooClose);
      EXPECT_EQ(d.num_vertices(), nv);
      EXPECT_EQ(d.num_finite_tets(), nt);
    }
    ASSERT_TRUE(d.check(true).ok()) << d.check(true).message();
  }
  for (size_t i = 0; i < queries.size(); i += 3) {
    const double* q = &queries[i];
    EXPECT_EQ(d.insert(q, -1, false, nearest_to(q) * 0.999).status, D::InsertStatus::kInserted);
  }
  ASSERT_TRUE(d.check(true).ok()) << d.check(true).message();
  expect_empty_spheres(d);
}

TEST(Delaunay3D, LocateClassifiesThePosition) {
  auto r = D::build(grid(3));
  ASSERT_TRUE(r.ok());
  const D& d = r.value();
  const double vertex[3] = {1, 1, 1}, inside[3] = {0.3, 0.4, 0.45}, out[3] = {5, 0, 0};
  auto l = d.locate(vertex);
  EXPECT_EQ(l.type, D::LocationType::kOnVertex);
  EXPECT_EQ(l.vertex, 13);
  EXPECT_EQ(d.locate(out).type, D::LocationType::kOutside);
  EXPECT_TRUE(d.is_ghost(d.locate(out).tet));
  auto li = d.locate(inside);
  EXPECT_NE(li.type, D::LocationType::kOutside);
  EXPECT_FALSE(d.is_ghost(li.tet));
  // An edge midpoint of the grid is on an edge (or a face diagonal).
  const double mid[3] = {0.5, 0, 0};
  EXPECT_EQ(d.locate(mid).type, D::LocationType::kOnEdge);
}

TEST(Delaunay3D, Flip23Then32RestoresTheTetrahedra) {
  auto r = D::build(testing::random_cube_points(60, 21));
  ASSERT_TRUE(r.ok());
  D d = std::move(r.value());
  auto before = d.finite_tets();
  std::set<std::set<int32_t>> before_set;
  for (size_t i = 0; i < before.size(); i += 4)
    before_set.insert({before[i], before[i + 1], before[i + 2], before[i + 3]});
  // Find an interior face whose 2-3 flip is valid.
  bool flipped = false;
  for (int32_t t = 0; t < int32_t(d.tet_capacity()) && !flipped; ++t) {
    if (!d.is_live(t) || d.is_ghost(t)) continue;
    for (int k = 0; k < 4 && !flipped; ++k) {
      auto f = d.flip23(t, k);
      if (!f.ok()) {
        ASSERT_TRUE(d.check(false).ok()) << "a refused flip changed something";
        continue;
      }
      flipped = true;
      ASSERT_TRUE(d.check(false).ok()) << d.check(false).message();
      EXPECT_FALSE(d.is_delaunay());
      // The three new tetrahedra share the new edge; flip it back.
      const int32_t* v = d.tet(f.value()[0]);
      const int32_t* w = d.tet(f.value()[1]);
      std::vector<int32_t> common;
      for (int i = 0; i < 4; ++i)
        if (std::find(w, w + 4, v[i]) != w + 4 &&
            std::find(d.tet(f.value()[2]), d.tet(f.value()[2]) + 4, v[i]) !=
                d.tet(f.value()[2]) + 4)
          common.push_back(v[i]);
      ASSERT_EQ(common.size(), 2u);
      auto back = d.flip32(f.value()[0], common[0], common[1]);
      ASSERT_TRUE(back.ok()) << back.message();
      ASSERT_TRUE(d.check(true).ok()) << d.check(true).message();
    }
  }
  ASSERT_TRUE(flipped);
  auto after = d.finite_tets();
  std::set<std::set<int32_t>> after_set;
  for (size_t i = 0; i < after.size(); i += 4)
    after_set.insert({after[i], after[i + 1], after[i + 2], after[i + 3]});
  EXPECT_EQ(before_set, after_set);
}

TEST(Delaunay3D, Flip44OnAnOctahedron) {
  // The regular octahedron (cospherical): 4 tetrahedra around one axis,
  // chosen by the perturbation, with a planar ring.
  std::vector<double> p = {1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1};
  auto r = D::build(p);
  ASSERT_TRUE(r.ok());
  D d = std::move(r.value());
  ASSERT_TRUE(d.check(true).ok());
  EXPECT_EQ(d.num_finite_tets(), 4u);
  int32_t a = -1, t = -1;
  for (int32_t axis = 0; axis < 6 && t < 0; axis += 2)
    if ((t = d.find_edge(axis, axis + 1)) >= 0) a = axis;
  ASSERT_GE(t, 0);
  std::vector<int32_t> ring_tets, ring;
  d.edge_ring(t, a, a + 1, ring_tets, ring);
  ASSERT_EQ(ring.size(), 4u);
  auto f = d.flip44(t, a, a + 1, ring[0]);
  ASSERT_TRUE(f.ok()) << f.message();
  ASSERT_TRUE(d.check(false).ok()) << d.check(false).message();
  EXPECT_LT(d.find_edge(a, a + 1), 0);
  int32_t e = d.find_edge(ring[0], ring[2]);
  EXPECT_GE(e, 0);
  EXPECT_DOUBLE_EQ(total_volume(d), 4.0 / 3);
  // The new edge is on the hull: no 3-2 flip there; a refused flip changes
  // nothing.
  EXPECT_FALSE(d.flip32(e, ring[0], ring[2]).ok());
  EXPECT_TRUE(d.check(false).ok());
}

TEST(Delaunay3D, RemoveEdgeWithManyTetrahedra) {
  // A ring of 7 points around the segment (0,0,-1)-(0,0,1): its edge has 7
  // tetrahedra; removing it leaves 2 * 5 = 10.
  std::vector<double> p = {0, 0, -1, 0, 0, 1};
  for (int i = 0; i < 7; ++i)
    p.insert(p.end(), {3 * std::cos(2 * M_PI * i / 7), 3 * std::sin(2 * M_PI * i / 7), 0.01 * i});
  auto r = D::build(p);
  ASSERT_TRUE(r.ok());
  D d = std::move(r.value());
  int32_t t = d.find_edge(0, 1);
  ASSERT_GE(t, 0);
  std::vector<int32_t> ring_tets, ring;
  d.edge_ring(t, 0, 1, ring_tets, ring);
  ASSERT_EQ(ring.size(), 7u);
  double vol = total_volume(d);
  auto res = d.remove_edge(t, 0, 1);
  ASSERT_TRUE(res.ok()) << res.message();
  EXPECT_EQ(res.value().size(), 10u);
  ASSERT_TRUE(d.check(false).ok()) << d.check(false).message();
  EXPECT_LT(d.find_edge(0, 1), 0);
  EXPECT_NEAR(total_volume(d), vol, 1e-12 * vol);
  // Insertion still works (checked cavity) after flips.
  for (double z : {0.1, -0.2, 0.3}) {
    const double q[3] = {0.2, -0.1, z};
    ASSERT_EQ(d.insert(q).status, D::InsertStatus::kInserted);
    ASSERT_TRUE(d.check(false).ok()) << d.check(false).message();
  }
}

TEST(Delaunay3D, ConstrainedFaceSurvivesInsertion) {
  auto r = D::build(grid(4));
  ASSERT_TRUE(r.ok());
  D d = std::move(r.value());
  // Constrain every face in the plane x = 1.
  int constrained = 0;
  for (int32_t t = 0; t < int32_t(d.tet_capacity()); ++t) {
    if (!d.is_live(t) || d.is_ghost(t)) continue;
    for (int k = 0; k < 4; ++k) {
      bool on = true;
      for (int s = 0; s < 4; ++s)
        if (s != k) on = on && d.point(d.tet(t)[s])[0] == 1;
      if (on && !d.is_constrained(t, k)) {
        d.set_constrained(t, k, true);
        ++constrained;
      }
    }
  }
  EXPECT_EQ(constrained, 2 * 9);
  // Points just beside the plane: their circumspheres cross it.
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> u(0.05, 2.95);
  for (int i = 0; i < 200; ++i) {
    const double q[3] = {i % 2 ? 0.999 : 1.001, u(rng), u(rng)};
    auto ins = d.insert(q, -1, true);
    ASSERT_TRUE(ins.status == D::InsertStatus::kInserted ||
                ins.status == D::InsertStatus::kBlocked);
    ASSERT_TRUE(d.check(false).ok()) << d.check(false).message();
  }
  // Still 18 constrained faces, all in the plane, and no tetrahedron
  // crosses it.
  int count = 0;
  for (int32_t t = 0; t < int32_t(d.tet_capacity()); ++t) {
    if (!d.is_live(t) || d.is_ghost(t)) continue;
    bool left = false, right = false;
    for (int s = 0; s < 4; ++s) {
      left = left || d.point(d.tet(t)[s])[0] < 1;
      right = right || d.point(d.tet(t)[s])[0] > 1;
    }
    EXPECT_FALSE(left && right);
    for (int k = 0; k < 4; ++k) count += d.is_constrained(t, k);
  }
  EXPECT_EQ(count, 2 * 18);
  // A point on a constrained face is refused, outside the hull too.
  const double on_face[3] = {1, 1.2, 1.3}, outside[3] = {9, 9, 9};
  EXPECT_EQ(d.insert(on_face, -1, true).status, D::InsertStatus::kBlocked);
  EXPECT_EQ(d.insert(outside, -1, true).status, D::InsertStatus::kOutsideHull);
  EXPECT_TRUE(d.check(false).ok());
}

// The tetrahedra around v as a sorted list.
std::vector<int32_t> sorted_star(const D& d, int32_t v) {
  std::vector<int32_t> s;
  d.tets_around_vertex(v, s);
  std::sort(s.begin(), s.end());
  return s;
}

TEST(Delaunay3D, LastInsertedTetsAreTheStarOfTheNewVertex) {
  auto r = D::build(testing::random_cube_points(300, 11));
  ASSERT_TRUE(r.ok());
  D d = std::move(r.value());
  std::mt19937 rng(12);
  std::uniform_real_distribution<double> u(-1.5, 1.5);  // outside the hull too
  for (int i = 0; i < 200; ++i) {
    const double q[3] = {u(rng), u(rng), u(rng)};
    auto ins = d.insert(q);
    ASSERT_EQ(ins.status, D::InsertStatus::kInserted);
    std::vector<int32_t> last = d.last_inserted_tets();
    std::sort(last.begin(), last.end());
    EXPECT_EQ(last, sorted_star(d, ins.vertex));
  }
  EXPECT_TRUE(d.check(true).ok()) << d.check(true).message();
}

TEST(Delaunay3D, QueriesWithTheirOwnScratchGiveTheSameAnswers) {
  // Every edge and face of some tetrahedra, and pairs and triples that are
  // mostly not edges or faces, looked up both ways, the scratch queries on
  // three threads at the same time.
  auto r = D::build(testing::random_cube_points(2000, 31));
  ASSERT_TRUE(r.ok());
  const D& d = r.value();
  std::vector<std::array<int32_t, 3>> asked;
  std::mt19937 rng(32);
  std::uniform_int_distribution<int32_t> any(0, 1999);
  for (int32_t t : d.finite_tets()) {
    const int32_t* v = d.tet(t);
    if (t % 7 == 0) asked.push_back({v[0], v[1], v[2]});
    if (t % 11 == 0) asked.push_back({v[3], v[1], v[0]});
  }
  for (int i = 0; i < 2000; ++i) asked.push_back({any(rng), any(rng), any(rng)});
  std::vector<std::array<int32_t, 3>> shared(asked.size()), own(asked.size());
  int edges = 0, faces = 0;
  for (size_t i = 0; i < asked.size(); ++i) {
    const auto [a, b, c] = asked[i];
    int k = -1;
    const int32_t e = d.find_edge(a, b), f = d.find_face(a, b, c, &k);
    shared[i] = {e, f, f >= 0 ? k : -1};
    edges += shared[i][0] >= 0;
    faces += shared[i][1] >= 0;
  }
  ASSERT_GT(faces, 100);
  ASSERT_LT(faces, int(asked.size()) - 1000);
  ASSERT_GT(edges, faces);
  std::vector<std::thread> threads;
  for (size_t j = 0; j < 3; ++j)
    threads.emplace_back([&, j] {
      D::AroundScratch s;
      for (size_t i = j; i < asked.size(); i += 3) {
        const auto [a, b, c] = asked[i];
        int k = -1;
        const int32_t e = d.find_edge(a, b, s), f = d.find_face(a, b, c, &k, s);
        own[i] = {e, f, f >= 0 ? k : -1};
      }
    });
  for (std::thread& t : threads) t.join();
  EXPECT_EQ(own, shared);
}

// Constrained insertions into a triangulation made non-Delaunay by flips:
// mostly the verified Bowyer-Watson cavity, some grown and shrunk; either
// way valid, no constrained face lost, the new vertex's star as reported.
TEST(Delaunay3D, ConstrainedInsertionAfterFlipsStaysValid) {
  auto r = D::build(testing::random_cube_points(2000, 21));
  ASSERT_TRUE(r.ok());
  D d = std::move(r.value());
  // Constrain the faces of a few tetrahedra, then flip some other faces.
  std::set<std::array<int32_t, 3>> constrained;
  auto face_key = [&](int32_t t, int k) {
    std::array<int32_t, 3> f;
    for (int s = 0, m = 0; s < 4; ++s)
      if (s != k) f[size_t(m++)] = d.tet(t)[s];
    std::sort(f.begin(), f.end());
    return f;
  };
  for (int32_t t = 0; t < int32_t(d.tet_capacity()); t += 97) {
    if (!d.is_live(t) || d.is_ghost(t)) continue;
    for (int k = 0; k < 4; ++k) {
      if (d.is_ghost(d.neighbor(t, k) >> 2)) continue;
      d.set_constrained(t, k, true);
      constrained.insert(face_key(t, k));
    }
  }
  int flips = 0;
  for (int32_t t = 0; t < int32_t(d.tet_capacity()) && flips < 100; t += 13)
    if (d.is_live(t) && !d.is_ghost(t) && d.flip23(t, t % 4).ok()) ++flips;
  ASSERT_GT(flips, 10);
  ASSERT_FALSE(d.is_delaunay());
  ASSERT_TRUE(d.check(false).ok());
  std::mt19937 rng(22);
  std::uniform_real_distribution<double> u(-0.95, 0.95);
  int inserted = 0;
  int64_t shrunk = 0;
  for (int i = 0; i < 3000; ++i) {
    const double q[3] = {u(rng), u(rng), u(rng)};
    auto ins = d.insert(q, -1, true);
    ASSERT_TRUE(ins.status == D::InsertStatus::kInserted ||
                ins.status == D::InsertStatus::kBlocked ||
                ins.status == D::InsertStatus::kOutsideHull);
    if (ins.status != D::InsertStatus::kInserted) continue;
    ++inserted;
    std::vector<int32_t> last = d.last_inserted_tets();
    std::sort(last.begin(), last.end());
    ASSERT_EQ(last, sorted_star(d, ins.vertex));
    // The first 100 shrunk cavities are checked at once, the others now
    // and then.
    if ((d.stats().shrunk_cavities > shrunk && shrunk < 100) || i % 500 == 0) {
      ASSERT_TRUE(d.check(false).ok()) << d.check(false).message();
    }
    shrunk = d.stats().shrunk_cavities;
  }
  EXPECT_GT(inserted, 2500);
  ASSERT_TRUE(d.check(false).ok()) << d.check(false).message();
  // Every constrained face is still a face, still flagged.
  std::set<std::array<int32_t, 3>> now;
  for (int32_t t = 0; t < int32_t(d.tet_capacity()); ++t) {
    if (!d.is_live(t)) continue;
    for (int k = 0; k < 4; ++k)
      if (d.is_constrained(t, k)) now.insert(face_key(t, k));
  }
  EXPECT_EQ(now, constrained);
  // Most cavities needed no shrinking (not timed: a count); those that
  // did were mostly shrunk in place, not searched again.
  std::cout << "[ info ] " << inserted << " inserted, " << d.stats().shrunk_cavities
            << " cavities shrunk, " << d.stats().checked_cavities << " searched again\n";
  EXPECT_GT(d.stats().shrunk_cavities, 0);
  EXPECT_LT(d.stats().shrunk_cavities + d.stats().checked_cavities, inserted / 2);
}

// Every hull face has all vertices on its inner side or in its plane.
bool hull_is_convex(const D& d) {
  for (int32_t t = 0; t < int32_t(d.tet_capacity()); ++t) {
    if (!d.is_live(t) || !d.is_ghost(t)) continue;
    const int32_t* v = d.tet(t);
    for (int32_t w = 0; w < int32_t(d.num_vertices()); ++w) {
      const double* q[4];
      for (int k = 0; k < 4; ++k) q[k] = v[k] == D::kInfinite ? d.point(w) : d.point(v[k]);
      if (orient3d(q[0], q[1], q[2], q[3]) < 0) return false;
    }
  }
  return true;
}

TEST(Delaunay3D, HullFlipsKeepTheHullConvex) {
  // Cube corners: the diagonal of a square hull face can be flipped (the
  // two hull triangles are coplanar) when 4 tetrahedra surround it.
  std::vector<double> cube = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0,
                              0, 0, 1, 1, 0, 1, 0, 1, 1, 1, 1, 1};
  auto r = D::build(cube);
  ASSERT_TRUE(r.ok());
  D d = std::move(r.value());
  int flipped = 0;
  const int diag[12][2] = {{0, 3}, {1, 2}, {4, 7}, {5, 6}, {0, 5}, {1, 4},
                           {2, 7}, {3, 6}, {0, 6}, {2, 4}, {1, 7}, {3, 5}};
  for (auto& e : diag) {
    const int32_t t = d.find_edge(e[0], e[1]);
    if (t < 0) continue;
    std::vector<int32_t> ring_tets, ring;
    d.edge_ring(t, e[0], e[1], ring_tets, ring);
    if (ring.size() != 4) continue;
    auto f = d.remove_edge(t, e[0], e[1]);
    ASSERT_TRUE(f.ok()) << f.message();
    ++flipped;
    ASSERT_TRUE(d.check(false).ok()) << d.check(false).message();
    EXPECT_TRUE(hull_is_convex(d));
    EXPECT_LT(d.find_edge(e[0], e[1]), 0);
  }
  EXPECT_GT(flipped, 0);
  EXPECT_DOUBLE_EQ(total_volume(d), 1.0);
  // Random points: hull edges join non-coplanar hull faces; removing one
  // would dent the hull and is refused.
  auto q = D::build(testing::random_cube_points(100, 6));
  ASSERT_TRUE(q.ok());
  D e = std::move(q.value());
  int refused = 0;
  for (int32_t t = 0; t < int32_t(e.tet_capacity()) && refused < 20; ++t) {
    if (!e.is_live(t) || !e.is_ghost(t)) continue;
    const int32_t* v = e.tet(t);
    int32_t a = -1, b = -1;
    for (int k = 0; k < 4; ++k)
      if (v[k] != D::kInfinite) (a < 0 ? a : b) = v[k];
    EXPECT_FALSE(e.remove_edge(t, a, b).ok());
    ++refused;
  }
  EXPECT_TRUE(e.check(true).ok()) << e.check(true).message();
}

}  // namespace
}  // namespace vm
