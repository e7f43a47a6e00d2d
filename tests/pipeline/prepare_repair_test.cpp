// Phase 2 of the preparation on dirty surfaces ({repair} auto): dirty
// phantoms (holes, touching holes, a fin, duplicates, a flipped patch, a
// zero-area band) are repaired, their holes told from their openings and
// closed, and they mesh with the default options.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>
#include <string>

#include "core/io/stl.h"
#include "core/mesh/adjacency.h"
#include "core/mesh/repair.h"
#include "core/mesh/volume_check.h"
#include "core/phantom/vessel_phantom.h"
#include "core/pipeline/mesh_job.h"
#include "core/pipeline/option_table.h"
#include "core/pipeline/prepare_surface.h"
#include "core/pipeline/report_json.h"

namespace vm {
namespace {

struct Dirty {
  std::vector<uint8_t> stl;
  PhantomTruth truth;
};

Dirty dirty_phantom(PhantomKind kind, bool dirty = true) {
  PhantomOptions o;
  o.kind = kind;
  o.dirty = dirty;
  Dirty d;
  auto r = make_vessel_phantom(o, &d.truth);
  EXPECT_TRUE(r.ok()) << r.message();
  d.stl = write_stl_binary(r.ok() ? r.value() : SurfaceMesh{});
  return d;
}

bool has_warning(const PreparedSurface& s, const std::string& text) {
  for (const std::string& w : s.warnings)
    if (w.find(text) != std::string::npos) return true;
  return false;
}

class DirtyPhantom : public ::testing::TestWithParam<PhantomKind> {};

TEST_P(DirtyPhantom, IsRepairedItsHolesClosedAndItsOpeningsKept) {
  const Dirty d = dirty_phantom(GetParam());
  ASSERT_GE(d.truth.holes, 7);
  auto r = prepare_surface(d.stl);
  ASSERT_TRUE(r.ok()) << r.message();
  const PreparedSurface& s = r.value();
  EXPECT_EQ(int(s.holes.size()), d.truth.holes);
  for (const Hole& h : s.holes) {
    EXPECT_TRUE(h.closed) << point_text(h.centroid);
    EXPECT_GT(h.perimeter, 0);
    EXPECT_LT(h.radius, 0.25 * h.vessel_radius);
    EXPECT_GT(h.min_angle, 0);
  }
  EXPECT_EQ(int(s.topology.openings.size()), d.truth.openings);
  EXPECT_EQ(s.topology.nonmanifold_edges, 0u);
  EXPECT_EQ(s.topology.nonmanifold_vertices, 0u);
  EXPECT_EQ(s.topology.components, 1);
  EXPECT_EQ(s.topology.genus, 0);
  EXPECT_TRUE(s.repair.orientable);
  EXPECT_EQ(s.manifold.fins_removed, 1u);
  EXPECT_EQ(s.repair.duplicates_removed, 6u);
  EXPECT_GT(s.repair.flipped, 0u);
  EXPECT_TRUE(check_meshable(s).ok());
  EXPECT_TRUE(has_warning(s,
                          "holes smaller than 0.25 of the local vessel radius ({hole_fraction}) "
                          "were closed, at ("));
  EXPECT_TRUE(
      has_warning(s, "fin triangles hanging on non-manifold edges were removed, e.g. at ("));
  EXPECT_TRUE(has_warning(s, "6 duplicate triangles were removed, e.g. at ("));
  EXPECT_TRUE(has_warning(s, "zero-area triangles were removed, e.g. at ("));
  EXPECT_TRUE(has_warning(s, "triangles were re-oriented (consistent, outward), e.g. at ("));
  // The analysis lists the holes apart from the openings.
  const std::string json = analysis_json(s);
  EXPECT_NE(json.find("\"holes\":[{\"perimeter\":"), std::string::npos);
  EXPECT_NE(json.find("\"closed\":true"), std::string::npos);
}

TEST_P(DirtyPhantom, MeshesWithTheDefaultOptions) {
  const Dirty d = dirty_phantom(GetParam());
  auto r = run_mesh_job(d.stl);
  ASSERT_TRUE(r.ok()) << r.message();
  const MeshJobResult& m = r.value();
  EXPECT_EQ(int(m.output_topology.openings.size()), d.truth.openings);
  EXPECT_EQ(m.output_topology.genus, 0);
  EXPECT_GE(m.output_quality_stats.min, 0.3);
  EXPECT_GE(m.core_quality_stats.min, 0.2);
  EXPECT_TRUE(check_volume_mesh(m.volume).ok());
}

TEST_P(DirtyPhantom, RepairOffListsTheHolesAndRefuses) {
  const Dirty d = dirty_phantom(GetParam());
  MeshJobOptions o;
  ASSERT_TRUE(set_option_text(o, "repair", "off").ok());
  auto r = prepare_surface(d.stl, o.prepare);
  ASSERT_TRUE(r.ok()) << r.message();
  const PreparedSurface& s = r.value();
  EXPECT_GT(s.topology.nonmanifold_edges, 0u);
  EXPECT_FALSE(check_meshable(s).ok());
  for (const Hole& h : s.holes) EXPECT_FALSE(h.closed);
  // The fin's free edges form a loop of 2 vertices: a slit, never an
  // opening of radius 0; it is in the analysis with its place.
  for (const Opening& op : s.topology.openings) {
    EXPECT_GE(op.loop.size(), 3u);
    EXPECT_GT(op.radius, 0);
  }
  ASSERT_FALSE(s.topology.slits.empty());
  EXPECT_NE(analysis_json(s).find("\"slits\":[{\"perimeter\":"), std::string::npos);
}

INSTANTIATE_TEST_SUITE_P(Kinds, DirtyPhantom,
                         ::testing::Values(PhantomKind::kTube, PhantomKind::kBifurcation,
                                           PhantomKind::kAneurysm));

TEST(PrepareRepair, ADirtyAneurysmInMetresIsRepairedLikeInMillimetres) {
  PhantomOptions o;
  o.kind = PhantomKind::kAneurysm;
  o.dirty = true;
  o.scale = 0.001;
  o.seed = 7;
  PhantomTruth truth;
  auto phantom = make_vessel_phantom(o, &truth);
  ASSERT_TRUE(phantom.ok());
  auto r = prepare_surface(write_stl_binary(phantom.value()));
  ASSERT_TRUE(r.ok()) << r.message();
  const PreparedSurface& s = r.value();
  EXPECT_EQ(s.unit.unit, LengthUnit::kM);
  EXPECT_EQ(int(s.holes.size()), truth.holes);
  for (const Hole& h : s.holes) EXPECT_TRUE(h.closed);
  EXPECT_EQ(int(s.topology.openings.size()), truth.openings);
  EXPECT_TRUE(check_meshable(s).ok());
}

TEST(PrepareRepair, RealOpeningsAreNeverClosed) {
  // Clean phantoms: every opening is as large as its vessel (the branches'
  // smaller than the parent's), so none is a hole, even at half a radius.
  for (PhantomKind kind : {PhantomKind::kTube, PhantomKind::kBifurcation, PhantomKind::kAneurysm})
    for (const char* fraction : {"0.25", "0.5"}) {
      const Dirty d = dirty_phantom(kind, false);
      MeshJobOptions o;
      ASSERT_TRUE(set_option_text(o, "hole_fraction", fraction).ok());
      auto r = prepare_surface(d.stl, o.prepare);
      ASSERT_TRUE(r.ok()) << r.message();
      EXPECT_TRUE(r.value().holes.empty()) << int(kind) << " " << fraction;
      EXPECT_EQ(int(r.value().topology.openings.size()), d.truth.openings);
    }
}

TEST(PrepareRepair, AMoebiusStripStaysRefused) {
  SurfaceMesh m;
  const int n = 24;
  for (int i = 0; i < n; ++i) {
    const double u = 2 * std::numbers::pi * i / n;
    for (int s = -1; s <= 1; s += 2) {
      const double w = 0.3 * s;
      m.points.insert(m.points.end(),
                      {(1 + w * std::cos(u / 2)) * std::cos(u),
                       (1 + w * std::cos(u / 2)) * std::sin(u), w * std::sin(u / 2)});
    }
  }
  for (int i = 0; i < n; ++i) {
    const int32_t a = 2 * i, b = 2 * i + 1;
    const int32_t c = i + 1 < n ? 2 * (i + 1) : 1, e = i + 1 < n ? 2 * (i + 1) + 1 : 0;
    m.triangles.insert(m.triangles.end(), {a, c, b, b, c, e});
  }
  auto r = prepare_surface(write_stl_binary(m));
  ASSERT_TRUE(r.ok()) << r.message();
  EXPECT_FALSE(r.value().repair.orientable);
  EXPECT_TRUE(r.value().holes.empty());
  EXPECT_FALSE(check_meshable(r.value()).ok());
}

TEST(PrepareRepair, ALocalTwistIsCutOutAndItsHolesClosed) {
  // A tube with a crosscap: the 1-ring of a valence-5 vertex replaced by
  // the 5-triangle Moebius band whose boundary is the ring's rim, which
  // makes the surface non-orientable through edges of two triangles only.
  PhantomOptions po;
  po.kind = PhantomKind::kTube;
  PhantomTruth truth;
  auto phantom = make_vessel_phantom(po, &truth);
  ASSERT_TRUE(phantom.ok());
  SurfaceMesh m = phantom.value();
  const TriangleAdjacency adj = build_adjacency(m);
  int32_t v = -1;
  for (size_t c = m.num_vertices() / 2; c < m.num_vertices() && v < 0; ++c) {
    if (adj.star_offsets[c + 1] - adj.star_offsets[c] != 5) continue;
    bool interior = true;
    for (int32_t i = adj.star_offsets[c]; i < adj.star_offsets[c + 1]; ++i)
      for (int k = 0; k < 3; ++k)
        interior &= adj.opposite[3 * size_t(adj.star[size_t(i)]) + size_t(k)] >= 0;
    if (interior) v = int32_t(c);
  }
  ASSERT_GE(v, 0);
  // The rim in order: each star triangle (v, a, b) leads from a to b.
  std::vector<std::pair<int32_t, int32_t>> arcs;
  std::vector<uint8_t> remove(m.num_triangles(), 0);
  for (int32_t i = adj.star_offsets[size_t(v)]; i < adj.star_offsets[size_t(v) + 1]; ++i) {
    const int32_t t = adj.star[size_t(i)];
    int k = 0;
    while (m.triangles[3 * size_t(t) + size_t(k)] != v) ++k;
    arcs.emplace_back(m.triangles[3 * size_t(t) + size_t(k + 1) % 3],
                      m.triangles[3 * size_t(t) + size_t(k + 2) % 3]);
    remove[size_t(t)] = 1;
  }
  std::vector<int32_t> rim{arcs[0].first};
  while (rim.size() < 5)
    for (auto [a, b] : arcs)
      if (a == rim.back()) {
        rim.push_back(b);
        break;
      }
  // Band vertex j sits at rim position j * 3 mod 5 (boundary 0 2 4 1 3).
  std::array<int32_t, 5> band{};
  for (int j = 0; j < 5; ++j) band[size_t(j * 3 % 5)] = rim[size_t(j)];
  for (int i = 0; i < 5; ++i)
    m.triangles.insert(m.triangles.end(),
                       {band[size_t(i)], band[size_t(i + 1) % 5], band[size_t(i + 2) % 5]});
  remove.resize(m.num_triangles(), 0);
  remove_triangles(m, remove);
  RepairStats before;
  SurfaceMesh copy = m;
  orient_consistently(copy, before);
  ASSERT_FALSE(before.orientable);

  auto r = prepare_surface(write_stl_binary(m));
  ASSERT_TRUE(r.ok()) << r.message();
  const PreparedSurface& s = r.value();
  EXPECT_TRUE(s.repair.orientable);
  // The band's triangles cross each other, so the place is re-surfaced
  // (core/prepare/resurface_crossings.h) before the twist could be cut out;
  // either repair leaves a clean tube and says so.
  const bool resurfaced = s.resurfaced.resolved() == 1;
  EXPECT_TRUE(resurfaced || s.manifold.twisted_removed > 0);
  EXPECT_LE(s.manifold.twisted_removed, 10u);
  for (const Hole& h : s.holes) EXPECT_TRUE(h.closed);
  EXPECT_EQ(int(s.topology.openings.size()), truth.openings);
  EXPECT_EQ(s.topology.genus, 0);
  EXPECT_EQ(s.topology.nonmanifold_edges, 0u);
  EXPECT_EQ(s.self_crossings.pairs, 0u);
  EXPECT_TRUE(check_meshable(s).ok());
  EXPECT_TRUE(resurfaced ? has_warning(s, "re-surfaced there")
                         : has_warning(s, "(a local twist that made the surface non-orientable) were removed"));
  auto job = run_mesh_job(write_stl_binary(m));
  EXPECT_TRUE(job.ok()) << job.message();
}

TEST(PrepareRepair, ANonManifoldEdgeOfTwoSheetsIsSplit) {
  // Two closed tetrahedra sharing one edge (4 triangles on it): paired by
  // angle into the two tetrahedra, the edge's ends duplicated.
  SurfaceMesh m;
  m.points = {0, 0, 0, 0, 0, 1, 1, 0, 0.5, 0.5, 1, 0.5, -1, 0, 0.5, -0.5, -1, 0.5};
  m.triangles = {0, 2, 1, 0, 3, 2, 1, 2, 3, 0, 1, 3, 0, 4, 1, 0, 5, 4, 1, 4, 5, 0, 1, 5};
  auto r = prepare_surface(write_stl_binary(m));
  ASSERT_TRUE(r.ok()) << r.message();
  const PreparedSurface& s = r.value();
  EXPECT_EQ(s.manifold.edges_split, 1u);
  EXPECT_EQ(s.topology.nonmanifold_edges, 0u);
  EXPECT_EQ(s.topology.nonmanifold_vertices, 0u);
  EXPECT_EQ(s.topology.components, 2);
  EXPECT_TRUE(s.repair.orientable);
  EXPECT_TRUE(has_warning(s, "1 non-manifold edges were split into manifold sheets"));
}

}  // namespace
}  // namespace vm
