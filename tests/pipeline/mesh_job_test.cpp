#include "core/pipeline/mesh_job.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "core/io/vtk_writer.h"
#include "core/mesh/enclosed_volume.h"
#include "core/mesh/volume_check.h"
#include "core/phantom/outlets_phantom.h"
#include "core/phantom/vessel_phantom.h"
#include "core/pipeline/option_table.h"
#include "core/pipeline/report_json.h"
#include "core/pipeline/write_outputs.h"
#include "tests/support/expect_has.h"
#include "tests/support/phantoms.h"
#include "tests/support/test_meshes.h"
#include "tests/support/tet_volume.h"

namespace vm {
namespace {

std::vector<uint8_t> two_components_stl() {
  SurfaceMesh a = testing::open_tube(12, 4);
  SurfaceMesh b = testing::tetrahedron();
  int32_t off = int32_t(a.num_vertices());
  for (double& x : b.points) x += 10;
  a.points.insert(a.points.end(), b.points.begin(), b.points.end());
  for (int32_t v : b.triangles) a.triangles.push_back(v + off);
  return write_stl_binary(a);
}

// The names of the job's groups; every group must hold elements.
std::vector<std::string> group_names(const MeshJobResult& res) {
  std::vector<std::string> names;
  for (const OutputGroup& g : res.groups) {
    names.push_back(g.name);
    EXPECT_GT(g.elements, 0u) << g.name;
  }
  return names;
}

TEST(PrepareSurface, InsideOutTubeIsReversedAndAnalyzed) {
  SurfaceMesh tube = testing::open_tube(16, 5);
  for (size_t t = 0; t < tube.num_triangles(); ++t) testing::flip_triangle(tube, t);
  auto r = prepare_surface(write_stl_binary(tube));
  ASSERT_TRUE(r.ok()) << r.message();
  const PreparedSurface& s = r.value();
  EXPECT_EQ(s.topology.vertices, tube.num_vertices());
  EXPECT_EQ(s.topology.openings.size(), 2u);
  EXPECT_EQ(s.repair.flipped, tube.num_triangles());
  ASSERT_FALSE(s.warnings.empty());
  EXPECT_NE(s.warnings[0].find("inward"), std::string::npos);
  EXPECT_EQ(s.quality.size(), s.mesh.num_triangles());
  EXPECT_TRUE(check_meshable(s).ok());
}

TEST(PrepareSurface, AllDegenerateIsAnError) {
  TriangleSoup soup;
  std::string stl =
      "solid d\nfacet normal 0 0 0\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
      "vertex 2 0 0\nendloop\nendfacet\nendsolid d\n";
  auto r = prepare_surface(testing::bytes_of(stl));
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.message().find("zero area"), std::string::npos) << r.message();
}

TEST(MeshJob, WithoutRemeshingWritesTheInputAsTheWallGroup) {
  SurfaceMesh tube = testing::open_tube(16, 5);
  for (auto version : {MshVersion::k41, MshVersion::k22}) {
    MeshJobOptions o;
    o.remesh = false;
    o.volume = false;
    o.msh_version = version;
    auto r = run_mesh_job(write_stl_binary(tube), o);
    ASSERT_TRUE(r.ok()) << r.message();
    WriteOptions wo;
    wo.msh_version = version;
    auto files = write_outputs(r.value(), OutputFormat::kMsh, wo);
    ASSERT_TRUE(files.ok()) << files.message();
    const std::string& msh = files.value()[0].bytes;
    EXPECT_EQ(
        msh.rfind(version == MshVersion::k41 ? "$MeshFormat\n4.1 0 8\n" : "$MeshFormat\n2.2 0 8\n",
                  0),
        0u);
    EXPECT_NE(msh.find("2 1 \"wall\""), std::string::npos);
    EXPECT_EQ(r.value().output_surface.num_triangles(), tube.num_triangles());
    ASSERT_EQ(r.value().groups.size(), 1u);
    EXPECT_EQ(r.value().groups[0].name, "wall");
    EXPECT_EQ(r.value().groups[0].elements, tube.num_triangles());
  }
}

TEST(MeshJob, SeveralComponentsAreRefusedUnlessLargestIsKept) {
  auto bytes = two_components_stl();
  auto r = run_mesh_job(bytes);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.message().find("2 connected components"), std::string::npos) << r.message();
  EXPECT_NE(r.message().find("{largest_component_only}"), std::string::npos) << r.message();
  EXPECT_EQ(r.status().remedy().action, "largest_component");

  MeshJobOptions o;
  o.prepare.largest_component_only = true;
  o.remesh = false;
  r = run_mesh_job(bytes, o);
  ASSERT_TRUE(r.ok()) << r.message();
  EXPECT_EQ(r.value().output_surface.num_triangles(), 96u);
}

TEST(MeshJob, RemeshesKeepingTopologyAndWritesEveryTriangleAsWall) {
  const SurfaceMesh phantom = testing::noisy_bifurcation(0.1);
  MeshJobOptions o;
  ASSERT_TRUE(set_option_text(o, "size", "0.15").ok());
  o.volume = false;
  auto r = run_mesh_job(write_stl_binary(phantom), o);
  ASSERT_TRUE(r.ok()) << r.message();
  const MeshJobResult& res = r.value();
  EXPECT_TRUE(res.remeshed);
  EXPECT_GT(res.remesh_stats.patches, 1u);
  EXPECT_EQ(res.output_topology.openings.size(), 3u);
  EXPECT_EQ(res.output_topology.genus, 0);
  EXPECT_EQ(res.output_topology.nonmanifold_edges, 0u);
  ASSERT_EQ(res.groups.size(), 1u);
  EXPECT_EQ(res.groups[0].elements, res.output_surface.num_triangles());
  EXPECT_GT(res.output_quality_stats.min, 0.55);
  EXPECT_GT(res.output_quality_stats.mean, 0.97);
  // Fidelity: output vertices on the input, no self-intersection, and the
  // input within a fraction of h of the output (a smooth phantom).
  EXPECT_LE(res.fidelity.max_vertex_offset, 1e-9);
  EXPECT_EQ(res.fidelity.self_intersections, 0u);
  EXPECT_GT(res.fidelity.max_input_gap, 0.0);
  EXPECT_LT(res.fidelity.max_input_gap, 0.5);
}

TEST(MeshJob, FidelityOptionPinsTheWallOntoFarInputVerticesOrNot) {
  MeshJobOptions o;
  EXPECT_FALSE(set_option_text(o, "fidelity", "-0.1").ok());
  EXPECT_FALSE(set_option_text(o, "fidelity", "2").ok());
  EXPECT_FALSE(set_option_text(o, "fidelity", "x").ok());
  ASSERT_TRUE(set_option_text(o, "fidelity", "0.2").ok());
  EXPECT_EQ(o.remesh_options.fidelity, 0.2);
  EXPECT_GT(o.remesh_options.fidelity_rounds, 0);
  EXPECT_GT(o.remesh_options.fidelity_size_rounds, 0);
  ASSERT_TRUE(set_option_text(o, "fidelity", "0").ok());
  EXPECT_EQ(o.remesh_options.fidelity_rounds, 0);
  EXPECT_EQ(o.remesh_options.fidelity_size_rounds, 0);
  // A mildly noisy phantom at a size that leaves some of its bumps off the
  // wall: pinned by default, not with 0.
  const std::vector<uint8_t> stl =
      write_stl_binary(testing::phantom(PhantomKind::kBifurcation, true, 0.1, 0.1));
  size_t far[2], pinned[2];
  for (int off = 0; off < 2; ++off) {
    MeshJobOptions j;
    ASSERT_TRUE(set_option_text(j, "size", "0.3").ok());
    if (off) {
      ASSERT_TRUE(set_option_text(j, "fidelity", "0").ok());
    }
    j.volume = false;
    auto r = run_mesh_job(stl, j);
    ASSERT_TRUE(r.ok()) << r.message();
    far[off] = r.value().fidelity.input_gap_vertices;
    pinned[off] = r.value().remesh_stats.fidelity_pinned;
    EXPECT_EQ(r.value().output_topology.openings.size(), 3u);
    EXPECT_LE(r.value().fidelity.max_vertex_offset, 1e-9);
  }
  EXPECT_GT(pinned[0], 0u);
  EXPECT_EQ(pinned[1], 0u);
  EXPECT_GT(far[1], 0u);
  EXPECT_LT(far[0], far[1]);
}

TEST(MeshJob, MeshesTheLumenWithNamedPlanarCaps) {
  // The bifurcation phantom: 3 openings, so inlet, outlet_1, outlet_2; the
  // volume is checked (positive, conforming, bounded by wall + caps) and
  // fills exactly the capped surface.
  const SurfaceMesh phantom = testing::noisy_bifurcation(0.1);
  MeshJobOptions o;
  ASSERT_TRUE(set_option_text(o, "size", "0.2").ok());
  o.verify = true;
  auto r = run_mesh_job(write_stl_binary(phantom), o);
  ASSERT_TRUE(r.ok()) << r.message();
  const MeshJobResult& res = r.value();
  EXPECT_EQ(group_names(res),
            (std::vector<std::string>{"wall", "inlet", "outlet_1", "outlet_2", "lumen"}));
  auto check = check_volume_mesh(res.volume);
  ASSERT_TRUE(check.ok()) << check.message();
  // The lumen (layer + core) fills the wall closed by planar caps.
  auto lumen = cap_openings(res.output_surface, {});
  ASSERT_TRUE(lumen.ok()) << lumen.message();
  const double expected = enclosed_volume(lumen.value().mesh);
  EXPECT_NEAR(check.value().volume, expected, 1e-9 * expected);
  EXPECT_GT(res.tet_quality_stats.min, 0.0);
  // The inlet is the largest opening; caps are planar.
  ASSERT_EQ(res.capped.caps.size(), 3u);
  EXPECT_GE(res.capped.caps[0].area, res.capped.caps[1].area);
  const double tol = 1e-9 * bounding_box(res.capped.mesh.points).diagonal();
  for (size_t t = 0; t < res.volume.num_triangles(); ++t) {
    const int32_t tag = res.volume.triangle_tag[t];
    if (tag == 0) continue;
    const CapInfo& cap = res.capped.caps[size_t(tag - 1)];
    for (int k = 0; k < 3; ++k) {
      const double* x = &res.volume.points[3 * size_t(res.volume.triangles[3 * t + size_t(k)])];
      double d = 0;
      for (int c = 0; c < 3; ++c) d += (x[c] - cap.centroid[size_t(c)]) * cap.normal[size_t(c)];
      ASSERT_LE(std::abs(d), tol) << cap.name;
    }
  }
  // --inlet picks another opening: the inlet is then at that opening.
  ASSERT_TRUE(set_option_text(o, "inlet", "3").ok());
  auto r3 = run_mesh_job(write_stl_binary(phantom), o);
  ASSERT_TRUE(r3.ok()) << r3.message();
  const auto& in3 = r3.value().surface.topology.openings[2].centroid;
  const auto& inlet3 = r3.value().capped.caps[0].centroid;
  EXPECT_EQ(r3.value().capped.caps[0].name, "inlet");
  EXPECT_LT(std::hypot(in3[0] - inlet3[0], in3[1] - inlet3[1], in3[2] - inlet3[2]),
            0.5 * r3.value().surface.topology.openings[2].radius);
  ASSERT_TRUE(set_option_text(o, "inlet", "4").ok());
  auto r4 = run_mesh_job(write_stl_binary(phantom), o);
  ASSERT_FALSE(r4.ok());
  EXPECT_EQ(r4.status().kind(), ErrorKind::kBadOption) << r4.message();
  EXPECT_EQ(r4.status().option(), "inlet");
  EXPECT_EQ(phrase_error(r4.status(), kFaceCli),
            "--inlet must be between 1 and the number of openings (3)");
}

TEST(MeshJob, GrowsTheViscousLayerAndTheVesselWall) {
  // The bifurcation phantom with 4 viscous layers (default) and a vessel
  // wall of 0.1 R in 2 layers: named groups, a conforming mesh whose lumen
  // fills the capped wall, every layer present, ring caps in the cap planes.
  const SurfaceMesh phantom = testing::phantom(PhantomKind::kBifurcation, true, 0.1);
  MeshJobOptions o;
  ASSERT_TRUE(set_option_text(o, "size", "0.2").ok());
  ASSERT_TRUE(set_option_text(o, "wall_thickness", "0.1").ok());
  ASSERT_TRUE(set_option_text(o, "wall_layers", "2").ok());
  o.tag_layer = true;
  o.verify = true;
  auto r = run_mesh_job(write_stl_binary(phantom), o);
  ASSERT_TRUE(r.ok()) << r.message();
  const MeshJobResult& res = r.value();
  EXPECT_EQ(group_names(res),
            (std::vector<std::string>{"wall", "inlet", "outlet_1", "outlet_2", "outer_wall",
                                      "wall_inlet", "wall_outlet_1", "wall_outlet_2", "lumen",
                                      "boundary_layer", "vessel_wall"}));
  // Layer tets: 3 per prism, 4 viscous and 2 wall layers over every wall
  // triangle (the front may have a few more triangles from Steiner points).
  const size_t nt = res.output_surface.num_triangles();
  size_t part[3] = {0, 0, 0};
  for (uint8_t p : res.tet_part) ++part[p];
  EXPECT_GE(part[1], 3 * 4 * nt);
  EXPECT_GE(part[2], 3 * 2 * nt);
  EXPECT_GT(part[0], 0u);
  EXPECT_GE(res.volume_stats.boundary_layer.thickness_within_10pct, 0.95);
  EXPECT_GE(res.volume_stats.vessel_wall.thickness_within_10pct, 0.95);
  EXPECT_GE(res.core_quality_stats.min, 0.2);
  // Volumes: lumen + layer = the capped wall's; the vessel wall outside it.
  double lumen = 0, shell = 0;
  for (size_t t = 0; t < res.volume.num_tets(); ++t)
    (res.tet_part[t] == 2 ? shell : lumen) += testing::mesh_tet_volume6(res.volume, t) / 6;
  auto capped = cap_openings(res.output_surface, {});
  ASSERT_TRUE(capped.ok());
  const double expected = enclosed_volume(capped.value().mesh);
  EXPECT_NEAR(lumen, expected, 1e-9 * expected);
  EXPECT_GT(shell, 0.1 * expected);  // a wall of 0.1 R around a tube of R: ~21% of the lumen
  EXPECT_LT(shell, 0.4 * expected);
  // Prisms kept: the same lumen, prisms and ring quads instead of split tets.
  o.keep_prisms = true;
  auto kept = run_mesh_job(write_stl_binary(phantom), o);
  ASSERT_TRUE(kept.ok()) << kept.message();
  const VolumeMesh& km = kept.value().volume;
  EXPECT_GE(km.num_prisms(), 6 * nt);  // 4 + 2 layers over every wall triangle
  EXPECT_GT(km.num_quads(), 0u);
  auto kept_check = check_volume_mesh(km);
  ASSERT_TRUE(kept_check.ok()) << kept_check.message();
  EXPECT_NEAR(kept_check.value().volume, lumen + shell, 1e-9 * (lumen + shell));
  // The groups written count the prisms and quads.
  size_t written = 0;
  for (const OutputGroup& g : kept.value().groups) written += g.elements;
  EXPECT_EQ(written, km.num_tets() + km.num_prisms() + km.num_triangles() + km.num_quads());
  o.keep_prisms = false;
  // Without layers: no layer part, and --layers 0 is accepted.
  ASSERT_TRUE(set_option_text(o, "layers", "0").ok());
  ASSERT_TRUE(set_option_text(o, "wall_layers", "0").ok());
  auto plain = run_mesh_job(write_stl_binary(phantom), o);
  ASSERT_TRUE(plain.ok()) << plain.message();
  for (uint8_t p : plain.value().tet_part) ASSERT_EQ(p, 0);
  // Bad values are refused with the option's name.
  for (const auto& [name, value] :
       std::vector<std::pair<std::string, std::string>>{{"layers", "-1"},
                                                        {"layers", "1.5"},
                                                        {"layer_thickness", "1"},
                                                        {"growth", "0.5"},
                                                        {"wall_thickness", "0"},
                                                        {"first_layer", "-0.1"}}) {
    const Status st = set_option_text(o, name, value);
    EXPECT_FALSE(st.ok()) << name << " " << value;
    EXPECT_EQ(st.kind(), ErrorKind::kBadOption);
    EXPECT_EQ(st.option(), name);
  }
}

TEST(MeshJob, NonManifoldIsRefusedWithALocation) {
  SurfaceMesh m = testing::tetrahedron();
  m.points.insert(m.points.end(), {0.5, -1, 0.5});
  m.triangles.insert(m.triangles.end(), {0, 1, 4});
  // {repair} auto removes the fin; off, the surface is refused.
  MeshJobOptions o;
  ASSERT_TRUE(set_option_text(o, "repair", "off").ok());
  auto r = run_mesh_job(write_stl_binary(m), o);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.message().find("1 non-manifold edges"), std::string::npos) << r.message();
  EXPECT_NE(r.message().find("(0.5, 0, 0)"), std::string::npos) << r.message();
  EXPECT_NE(r.message().find("split them into manifold sheets with {repair} auto"),
            std::string::npos)
      << r.message();
}

TEST(MeshJob, ProgressIsMonotoneAndCancelStops) {
  std::vector<double> seen;
  auto bytes = write_stl_binary(testing::open_tube(16, 5));
  auto r = run_mesh_job(bytes, {}, [&](double f, std::string_view) {
    seen.push_back(f);
    return true;
  });
  ASSERT_TRUE(r.ok());
  ASSERT_GE(seen.size(), 4u);
  for (size_t i = 1; i < seen.size(); ++i) EXPECT_GE(seen[i], seen[i - 1]);
  EXPECT_EQ(seen.back(), 1.0);

  int calls = 0;
  r = run_mesh_job(bytes, {}, [&](double, std::string_view) { return ++calls < 3; });
  ASSERT_FALSE(r.ok());
  EXPECT_TRUE(r.cancelled());
}

TEST(ReportJson, HasTheDocumentedKeys) {
  auto r = run_mesh_job(write_stl_binary(testing::open_tube(16, 5)));
  ASSERT_TRUE(r.ok());
  std::string a = analysis_json(r.value().surface);
  for (const char* key :
       {"\"vertices\":96", "\"triangles\":160", "\"components\":1",
        "\"openings\":[{\"source\":\"file\",\"shape\":null,\"label\":-1,\"extension\":0,"
        "\"name\":\"inlet\"",
        "\"genus\":0", "\"nonmanifold_edges\":0", "\"quality\":{\"min\":", "\"closed\":false",
        "\"format\":\"binary STL\"", "\"caps_removed\":0", "\"holes\":[]",
        // A tube of radius 1, 4 long: a 10 mm vessel in cm, or a 1 mm one
        // in mm, 5 mm long (unusual).
        "\"units\":{\"unit\":\"cm\",\"guessed\":true,\"certain\":false",
        "\"confidence\":\"likely\",\"alternative\":\"mm\",\"measures\":{\"largest_radius\":",
        "\"enclosed_share\":"})
    EXPECT_NE(a.find(key), std::string::npos) << key << " in " << a;
  EXPECT_EQ(testing::count_of(a, "\"radius\":"), 2u);
  std::string m = mesh_report_json(r.value());
  for (const char* key :
       {"\"element_budget\":{\"max_elements\":15000000,\"coarsened\":false}",
        "\"remesh\":{\"patches\":", "\"seam_points\":", "\"genus\":0",
        "\"caps\":[{\"name\":\"inlet\"", "\"volume\":{\"vertices\":", "\"tetrahedra\":",
        "\"groups\":[{\"dim\":2,\"tag\":1,\"name\":\"wall\",\"elements\":",
        "{\"dim\":3,\"tag\":4,\"name\":\"lumen\"",
        "\"input_gap_vertices\":", "\"pinned_vertices\":", "\"pinning_rounds\":",
        "\"pinning_reverted\":", "\"size_rounds\":", "\"local_rounds\":", "\"fidelity\":"})
    EXPECT_NE(m.find(key), std::string::npos) << key << " in " << m;
}

}  // namespace
}  // namespace vm

namespace vm {
namespace {

TEST(MeshJob, ACappedModelGetsItsCapsBackAsNamedOpenings) {
  const std::vector<uint8_t> bytes = write_stl_binary(testing::flat_capped_bifurcation(0.12));
  MeshJobOptions o;
  ASSERT_TRUE(set_option_text(o, "size", "0.3").ok());
  ASSERT_TRUE(set_option_text(o, "layers", "2").ok());
  ASSERT_TRUE(set_option_text(o, "name", "2=left").ok());
  auto r = run_mesh_job(bytes, o);
  ASSERT_TRUE(r.ok()) << r.message();
  EXPECT_EQ(r.value().surface.caps_removed, 3u);
  ASSERT_EQ(r.value().surface.topology.openings.size(), 3u);
  for (const OpeningSource& s : r.value().surface.opening_sources)
    EXPECT_EQ(s.kind, OpeningSource::kCap);
  EXPECT_EQ(r.value().opening_names, (std::vector<std::string>{"inlet", "left", "outlet_1"}));
  std::vector<std::string> groups;
  for (const OutputGroup& g : r.value().groups) groups.push_back(g.name);
  std::sort(groups.begin(), groups.end());
  EXPECT_EQ(groups, (std::vector<std::string>{"inlet", "left", "lumen", "outlet_1", "wall"}));
  // The caps' names follow the openings they close: the `left` cap is the
  // one nearest opening 2.
  const auto& opening = r.value().surface.topology.openings[1].centroid;
  for (const CapInfo& c : r.value().capped.caps) {
    const double d = std::hypot(c.centroid[0] - opening[0], c.centroid[1] - opening[1],
                                c.centroid[2] - opening[2]);
    if (c.name == "left")
      EXPECT_LT(d, r.value().surface.topology.openings[1].radius);
    else
      EXPECT_GT(d, r.value().surface.topology.openings[1].radius);
  }
  // Kept caps with clip off: a closed wall, no opening group.
  ASSERT_TRUE(set_option_text(o, "keep_caps", "").ok());
  ASSERT_TRUE(set_option_text(o, "clip", "off").ok());
  o.opening_names.clear();
  auto kept = run_mesh_job(bytes, o);
  ASSERT_TRUE(kept.ok()) << kept.message();
  EXPECT_EQ(kept.value().surface.topology.openings.size(), 0u);
  EXPECT_EQ(kept.value().groups.size(), 2u);  // wall, lumen
}

}  // namespace
}  // namespace vm

namespace vm {
namespace {

TEST(MeshJob, SizesBeyondTheElementBudgetAreRefusedBeforeMeshing) {
  const std::vector<uint8_t> stl = write_stl_binary(testing::open_tube(24, 8, 1.0, 4.0));
  struct Case {
    const char* option;
    const char* value;
    const char* blamed;
    const char* what;
  };
  // Checked before remeshing, named by the estimate that needs the larger
  // elements: a uniform or core size's tetrahedra first; a field's
  // triangles and tetrahedra from its sizes.
  for (const Case& c : {Case{"size", "1e-30", "size", "tetrahedra in the lumen"},
                        Case{"surface_only", "", "size", "triangles on the wall"},
                        Case{"per_circumference", "1e7", "per_circumference", "tetrahedra"},
                        Case{"core_size", "1e-4", "core_size", "tetrahedra in the lumen"}}) {
    MeshJobOptions o;
    if (c.option == std::string("surface_only")) {
      ASSERT_TRUE(set_option_text(o, "size", "1e-30").ok());
    }
    ASSERT_TRUE(set_option_text(o, c.option, c.value).ok());
    int calls = 0;
    auto r = run_mesh_job(stl, o, [&](double f, std::string_view) { return ++calls, f < 0.5; });
    ASSERT_FALSE(r.ok()) << c.option;
    EXPECT_EQ(r.status().kind(), ErrorKind::kBadOption) << r.message();
    EXPECT_EQ(r.status().option(), c.blamed);
    EXPECT_NE(r.message().find(c.what), std::string::npos) << r.message();
    EXPECT_NE(phrase_error(r.status(), kFaceCli).find("(--max-elements 15000000)"),
              std::string::npos);
  }
  // A smaller budget refuses what the default allows.
  MeshJobOptions o;
  ASSERT_TRUE(set_option_text(o, "size", "0.2").ok());
  EXPECT_TRUE(run_mesh_job(stl, o).ok());
  ASSERT_TRUE(set_option_text(o, "max_elements", "1000").ok());
  EXPECT_EQ(run_mesh_job(stl, o).status().option(), "size");
}

TEST(MeshJob, AWallThatLosesTheVesselsVolumeIsRefusedNamingTheSizeToUse) {
  // A tube of radius 1: 4 edges a circumference lose a third of its volume.
  const std::vector<uint8_t> stl = write_stl_binary(testing::open_tube(48, 32, 1.0, 4.0));
  MeshJobOptions o;
  o.volume = false;
  ASSERT_TRUE(set_option_text(o, "per_circumference", "5").ok());
  auto coarse = run_mesh_job(stl, o);
  ASSERT_FALSE(coarse.ok());
  EXPECT_EQ(coarse.status().kind(), ErrorKind::kBadOption);
  EXPECT_EQ(coarse.status().option(), "per_circumference");
  const std::string cli = phrase_error(coarse.status(), kFaceCli);
  EXPECT_NE(cli.find("--per-circumference 5 makes a wall that encloses"), std::string::npos) << cli;
  EXPECT_NE(cli.find("less volume than the input"), std::string::npos) << cli;
  EXPECT_NE(cli.find("(or accept the change with --max-volume-change"), std::string::npos) << cli;
  // The size it names is fine.
  const size_t at = cli.find("use --per-circumference ");
  ASSERT_NE(at, std::string::npos) << cli;
  const std::string suggested = cli.substr(at + 24, cli.find(' ', at + 24) - (at + 24));
  ASSERT_TRUE(set_option_text(o, "per_circumference", suggested).ok());
  auto fine = run_mesh_job(stl, o);
  ASSERT_TRUE(fine.ok()) << suggested << ": " << fine.message();
  EXPECT_LT(std::abs(fine.value().fidelity.volume_change), 0.05);
  // The default loses about 1.6%, reported; a larger allowance accepts the
  // coarse size, whose loss is then reported.
  MeshJobOptions d;
  d.volume = false;
  auto by_default = run_mesh_job(stl, d);
  ASSERT_TRUE(by_default.ok()) << by_default.message();
  EXPECT_NEAR(by_default.value().fidelity.volume_change, -0.016, 0.01);
  EXPECT_NEAR(by_default.value().fidelity.input_volume, std::numbers::pi * 4, 0.02 * 4);
  ASSERT_TRUE(set_option_text(o, "per_circumference", "5").ok());
  ASSERT_TRUE(set_option_text(o, "max_volume_change", "0.6").ok());
  auto accepted = run_mesh_job(stl, o);
  ASSERT_TRUE(accepted.ok()) << accepted.message();
  EXPECT_LT(accepted.value().fidelity.volume_change, -0.05);
}

TEST(MeshJob, LayersTheUserMayNotHaveMeantAreSaid) {
  // A tube of radius 1 meshed at h 0.5: the vessel wall asked for by its
  // layers alone, and a first layer far thinner than the wall's edges.
  const std::vector<uint8_t> stl = write_stl_binary(testing::open_tube(32, 16, 1.0, 4.0));
  const auto warnings_of = [&](std::vector<std::pair<std::string, std::string>> set) {
    MeshJobOptions o;
    EXPECT_TRUE(set_option_text(o, "size", "0.5").ok());
    for (const auto& [id, text] : set) EXPECT_TRUE(set_option_text(o, id, text).ok()) << id;
    auto r = run_mesh_job(stl, o);
    EXPECT_TRUE(r.ok()) << r.message();
    std::string all;
    for (const std::string& w : r.ok() ? r.value().warnings : std::vector<std::string>{})
      all += phrase_options(w, kFaceCli) + "\n";
    return all;
  };
  const std::string alone = warnings_of({{"wall_layers", "2"}});
  EXPECT_NE(alone.find("a vessel wall of 2 layers, 0.1 R thick (the default --wall-thickness)"),
            std::string::npos)
      << alone;
  EXPECT_EQ(warnings_of({{"wall_layers", "2"}, {"wall_thickness", "0.1"}}).find("vessel wall"),
            std::string::npos);
  const std::string thin = warnings_of({{"first_layer", "1e-6"}});
  EXPECT_NE(thin.find("--first-layer 1e-06 is"), std::string::npos) << thin;
  EXPECT_NE(thin.find("nearly flat"), std::string::npos) << thin;
  EXPECT_EQ(warnings_of({{"first_layer", "0.02"}}).find("nearly flat"), std::string::npos);
}

}  // namespace
}  // namespace vm

namespace vm {
namespace {

// The job on `bytes` with `o`: it succeeds, with the groups `names` (each
// holding elements) and a volume that passes check_volume_mesh.
Result<MeshJobResult> run_checked(const std::vector<uint8_t>& bytes, const MeshJobOptions& o,
                                  const std::vector<std::string>& names) {
  auto r = run_mesh_job(bytes, o);
  EXPECT_TRUE(r.ok()) << r.message();
  if (!r.ok()) return r;
  EXPECT_EQ(group_names(r.value()), names);
  const auto check = check_volume_mesh(r.value().volume);
  EXPECT_TRUE(check.ok()) << check.message();
  return r;
}

TEST(MeshJob, APatchByTheFallbackIsWarnedWithItsPlaceAndListedInTheReport) {
  // The fallback forced on the patch at a wall point: the job still gives a
  // valid volume with every group, warns naming the place and the quality,
  // and the report lists the patch.
  const SurfaceMesh phantom = testing::noisy_bifurcation(0.15);
  MeshJobOptions o;
  ASSERT_TRUE(set_option_text(o, "size", "0.25").ok());
  o.verify = true;
  o.remesh_options.fallback_at = {{phantom.points[30], phantom.points[31], phantom.points[32]}};
  auto r =
      run_checked(write_stl_binary(phantom), o, {"wall", "inlet", "outlet_1", "outlet_2", "lumen"});
  ASSERT_TRUE(r.ok());
  const MeshJobResult& res = r.value();
  EXPECT_EQ(res.fidelity.self_intersections, 0u);
  ASSERT_EQ(res.remesh_stats.fallback_patches.size(), 1u);
  const FallbackPatch& f = res.remesh_stats.fallback_patches[0];
  EXPECT_GT(f.triangles, 0u);
  EXPECT_GT(f.quality_min, 0.0);
  std::string warnings;
  for (const std::string& w : res.warnings) warnings += w + "\n";
  EXPECT_NE(warnings.find("could not be meshed through its map"), std::string::npos) << warnings;
  EXPECT_NE(warnings.find("near " + point_text(f.place) + " " +
                          std::string(unit_symbol(res.surface.unit.unit))),
            std::string::npos)
      << warnings;
  EXPECT_NE(warnings.find("gamma_k min " + number_text(f.quality_min, 3)), std::string::npos)
      << warnings;
  const std::string json = mesh_report_json(res);
  EXPECT_NE(json.find("\"fallback_patches\":[{\"place\":["), std::string::npos) << json;
  EXPECT_NE(json.find("\"input_triangles\":" + std::to_string(f.input_triangles)),
            std::string::npos);
  EXPECT_NE(json.find("\"triangles\":" + std::to_string(f.triangles) + ",\"quality\":{\"min\":"),
            std::string::npos)
      << json;
  // Without it nothing is listed.
  o.remesh_options.fallback_at.clear();
  o.volume = false;
  auto plain = run_mesh_job(write_stl_binary(phantom), o);
  ASSERT_TRUE(plain.ok()) << plain.message();
  EXPECT_TRUE(plain.value().remesh_stats.fallback_patches.empty());
  EXPECT_NE(mesh_report_json(plain.value()).find("\"fallback_patches\":[]"), std::string::npos);
}

TEST(MeshJob, AModelWithManyLabelledFacesAndTinyCapsMeshesWithDefaults) {
  // A SimVascular-like capped model (outlets_phantom.h): 186 labelled
  // faces, 20 caps of 6 triangles on tiny branches. At default options
  // every cap becomes an opening, and the job gives a checked volume with
  // a wall, an inlet and 21 outlets.
  PhantomOptions po;
  po.kind = PhantomKind::kOutlets;
  PhantomTruth truth;
  const SurfaceMesh model = testing::phantom(po, &truth);
  auto vtp = write_surface_vtp(model, truth.face_labels);
  ASSERT_TRUE(vtp.ok()) << vtp.message();
  MeshJobOptions o;
  o.verify = true;
  std::vector<std::string> groups = {"wall", "inlet"};
  for (size_t k = 1; k < truth.opening_centers.size(); ++k)
    groups.push_back("outlet_" + std::to_string(k));
  groups.push_back("lumen");
  auto r = run_checked(testing::bytes_of(vtp.value()), o, groups);
  ASSERT_TRUE(r.ok());
  const MeshJobResult& res = r.value();
  EXPECT_EQ(res.surface.label_array, "ModelFaceID");
  EXPECT_EQ(res.surface.caps_removed, truth.opening_centers.size());
  ASSERT_EQ(res.surface.topology.openings.size(), truth.opening_centers.size());
  size_t tiny = 0;
  for (const Opening& op : res.surface.topology.openings) tiny += op.loop.size() == 6;
  EXPECT_EQ(tiny, size_t(kOutletsBranches));
  EXPECT_GT(res.tet_quality_stats.min, 0.0);
  EXPECT_EQ(res.fidelity.self_intersections, 0u);
}

/// Capped and closed models that users' files are like: each meshes with
/// the default options into a valid mesh with a wall, an inlet and outlets.
struct DefaultCase {
  const char* name;
  PhantomOptions phantom;
  size_t openings;
};

class MeshesWithDefaultOptions : public ::testing::TestWithParam<DefaultCase> {};

TEST_P(MeshesWithDefaultOptions, IntoAValidMeshWithAWallAnInletAndOutlets) {
  const DefaultCase& c = GetParam();
  MeshJobOptions o;
  o.verify = true;
  auto r = run_mesh_job(write_stl_binary(testing::phantom(c.phantom)), o);
  ASSERT_TRUE(r.ok()) << r.message();
  const MeshJobResult& res = r.value();
  std::vector<std::string> expected = {"wall", "inlet"};
  for (size_t k = 1; k < c.openings; ++k) expected.push_back("outlet_" + std::to_string(k));
  expected.push_back("lumen");
  EXPECT_EQ(group_names(res), expected);
  auto check = check_volume_mesh(res.volume);
  ASSERT_TRUE(check.ok()) << check.message();
  EXPECT_GT(res.tet_quality_stats.min, 0.0);
  // The inlet is the largest opening.
  for (size_t k = 1; k < res.capped.caps.size(); ++k)
    EXPECT_GE(res.capped.caps[0].area, res.capped.caps[k].area);
}

PhantomOptions default_case(PhantomKind kind, double noise, bool closed,
                            PhantomCapShape shape = PhantomCapShape::kFlat) {
  PhantomOptions o;
  o.kind = kind;
  o.voxel = 0.15;
  o.noise = noise;
  o.open_ends = !closed;
  o.flat_caps = !closed;
  o.cap_shape = shape;
  return o;
}

INSTANTIATE_TEST_SUITE_P(
    CappedAndClosed, MeshesWithDefaultOptions,
    ::testing::Values(
        DefaultCase{"domed_caps",
                    default_case(PhantomKind::kBifurcation, 0.1, false, PhantomCapShape::kDome), 3},
        DefaultCase{"fan_caps",
                    default_case(PhantomKind::kBifurcation, 0.3, false, PhantomCapShape::kFan), 3},
        DefaultCase{"closed_tree_with_a_short_wide_root",
                    default_case(PhantomKind::kRoot, 0.3, true), 5}),
    [](const auto& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace vm
