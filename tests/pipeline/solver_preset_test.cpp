#include "core/pipeline/solver_preset.h"

#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

#include "core/io/stl.h"
#include "core/pipeline/report_json.h"
#include "tests/support/test_meshes.h"

namespace vm {
namespace {

using Given = std::vector<std::pair<const OptionSpec*, OptionValue>>;

/// Option values as a user gives them: (id, text) pairs, parsed by the
/// table (a flag's text is ignored).
Given given(std::initializer_list<std::pair<const char*, const char*>> items) {
  Given out;
  for (const auto& [id, text] : items) {
    const OptionSpec* spec = find_option(id);
    EXPECT_NE(spec, nullptr) << id;
    auto v = parse_option_text(*spec, text);
    EXPECT_TRUE(v.ok()) << id << ": " << v.message();
    out.emplace_back(spec, v.value());
  }
  return out;
}

const PresetSetting* setting(const MeshJobOptions& o, std::string_view id) {
  for (const PresetSetting& s : o.preset.settings)
    if (s.id == id) return &s;
  return nullptr;
}

TEST(SolverPreset, OpenFoamKeepsPrismsWritesMsh22InMetres) {
  MeshJobOptions o;
  ASSERT_TRUE(apply_options(o, given({{"solver", "openfoam"}})).ok());
  EXPECT_EQ(o.solver, Solver::kOpenFoam);
  EXPECT_TRUE(o.keep_prisms);
  EXPECT_EQ(o.msh_version, MshVersion::k22);
  EXPECT_EQ(o.output_units, LengthUnit::kM);
  // The native case, unless the output's name says otherwise.
  EXPECT_EQ(resolve_output_format(o, std::nullopt), OutputFormat::kFoam);
  for (const char* id : {"prisms", "msh_version", "output_units", "format"}) {
    ASSERT_NE(setting(o, id), nullptr) << id;
    EXPECT_TRUE(setting(o, id)->from_preset) << id;
  }
  EXPECT_EQ(resolve_output_format(o, OutputFormat::kMsh), OutputFormat::kMsh);
  EXPECT_FALSE(setting(o, "format")->from_preset);
  EXPECT_EQ(setting(o, "msh_version")->value, "2.2");
  EXPECT_EQ(setting(o, "output_units")->value, "m");
  EXPECT_NE(preset_summary(o.preset).find("openfoam: prisms true, msh_version 2.2"),
            std::string::npos)
      << preset_summary(o.preset);
}

TEST(SolverPreset, AnExplicitOptionWinsWhereverItIsGiven) {
  // Before or after the preset on the command line: the user's value wins.
  for (bool first : {true, false}) {
    MeshJobOptions o;
    Given g = first
                  ? given({{"msh_version", "4.1"}, {"output_units", "mm"}, {"solver", "openfoam"}})
                  : given({{"solver", "openfoam"}, {"msh_version", "4.1"}, {"output_units", "mm"}});
    ASSERT_TRUE(apply_options(o, g).ok());
    EXPECT_EQ(o.msh_version, MshVersion::k41);
    EXPECT_EQ(o.output_units, LengthUnit::kMm);
    EXPECT_TRUE(o.keep_prisms);  // not given: the preset's
    EXPECT_FALSE(setting(o, "msh_version")->from_preset);
    EXPECT_EQ(setting(o, "msh_version")->value, "4.1");
    EXPECT_FALSE(setting(o, "output_units")->from_preset);
    EXPECT_TRUE(setting(o, "prisms")->from_preset);
    EXPECT_NE(preset_summary(o.preset).find("(yours)"), std::string::npos);
  }
  // JS can say prisms: false under openfoam; the CLI's --prisms under fenics.
  MeshJobOptions foam;
  OptionValue off;
  off.flag = false;
  Given g = given({{"solver", "openfoam"}});
  g.emplace_back(find_option("prisms"), off);
  ASSERT_TRUE(apply_options(foam, g).ok());
  EXPECT_FALSE(foam.keep_prisms);
  MeshJobOptions fenics;
  ASSERT_TRUE(apply_options(fenics, given({{"solver", "fenics"}, {"prisms", ""}})).ok());
  EXPECT_TRUE(fenics.keep_prisms);
  EXPECT_FALSE(setting(fenics, "prisms")->from_preset);
}

TEST(SolverPreset, FormatFromOptionThenNameThenPreset) {
  MeshJobOptions svfsi;
  ASSERT_TRUE(apply_options(svfsi, given({{"solver", "svfsi"}})).ok());
  EXPECT_FALSE(svfsi.keep_prisms);
  EXPECT_EQ(resolve_output_format(svfsi, std::nullopt), OutputFormat::kMeshComplete);
  EXPECT_TRUE(setting(svfsi, "format")->from_preset);
  // An output named .msh is MSH: the name wins over the preset.
  EXPECT_EQ(resolve_output_format(svfsi, OutputFormat::kMsh), OutputFormat::kMsh);
  EXPECT_FALSE(setting(svfsi, "format")->from_preset);
  EXPECT_EQ(setting(svfsi, "format")->value, "msh");
  // {format} wins over the name.
  MeshJobOptions vtu;
  ASSERT_TRUE(apply_options(vtu, given({{"solver", "svfsi"}, {"format", "vtu"}})).ok());
  EXPECT_EQ(resolve_output_format(vtu, OutputFormat::kMsh), OutputFormat::kVtu);
  // Without a preset: MSH, and nothing recorded.
  MeshJobOptions plain;
  ASSERT_TRUE(apply_options(plain, given({{"size", "1"}})).ok());
  EXPECT_EQ(resolve_output_format(plain, std::nullopt), OutputFormat::kMsh);
  EXPECT_TRUE(plain.preset.solver.empty());
  EXPECT_EQ(preset_summary(plain.preset), "");
}

TEST(SolverPreset, EveryChoiceOfTheOptionHasAPreset) {
  const OptionSpec* spec = find_option("solver");
  ASSERT_NE(spec, nullptr);
  ASSERT_EQ(spec->choices.size(), solver_presets().size());
  for (std::string_view name : spec->choices) {
    const SolverPreset* p = find_solver_preset(name);
    ASSERT_NE(p, nullptr) << name;
    EXPECT_EQ(find_solver_preset(p->solver), p);
  }
  EXPECT_NE(solver_presets_json().find("\"name\":\"openfoam\""), std::string::npos);
}

TEST(SolverPreset, YPlusOptionsAreCheckedTogether) {
  MeshJobOptions o;
  auto both = apply_options(
      o, given({{"first_layer_yplus", "1"}, {"inlet_velocity", "0.5"}, {"first_layer", "0.01"}}));
  ASSERT_FALSE(both.ok());
  EXPECT_EQ(both.option(), "first_layer_yplus");
  EXPECT_NE(phrase_error(both, kFaceCli).find("--first-layer both set"), std::string::npos)
      << phrase_error(both, kFaceCli);
  o = {};
  auto no_velocity = apply_options(o, given({{"first_layer_yplus", "1"}}));
  ASSERT_FALSE(no_velocity.ok());
  EXPECT_NE(phrase_error(no_velocity, kFaceJs).find("inletVelocity"), std::string::npos);
  o = {};
  auto alone = apply_options(o, given({{"density", "1000"}}));
  ASSERT_FALSE(alone.ok());
  EXPECT_EQ(alone.option(), "density");
  MeshJobOptions ok;
  ASSERT_TRUE(apply_options(ok, given({{"first_layer_yplus", "2"},
                                       {"inlet_velocity", "0.4"},
                                       {"viscosity", "0.004"}}))
                  .ok());
  EXPECT_EQ(ok.yplus.yplus, 2);
  EXPECT_EQ(ok.yplus.velocity, 0.4);
  EXPECT_EQ(ok.yplus.density, 1060);  // blood's, by default
  EXPECT_EQ(ok.yplus.viscosity, 0.004);
}

/// An open tube of radius 1 mm, 4 mm long, meshed with `items`.
Result<MeshJobResult> mesh_tube(std::initializer_list<std::pair<const char*, const char*>> items) {
  MeshJobOptions o;
  if (Status st = apply_options(o, given(items)); !st.ok()) return st;
  resolve_output_format(o, std::nullopt);
  return run_mesh_job(write_stl_binary(testing::open_tube(24, 8, 1.0, 4.0)), o);
}

TEST(SolverPreset, FenicsGetsTetrahedraOpenFoamPrismsAndTheReportSaysSo) {
  auto fenics =
      mesh_tube({{"size", "0.4"}, {"layers", "2"}, {"units", "mm"}, {"solver", "fenics"}});
  ASSERT_TRUE(fenics.ok()) << fenics.message();
  EXPECT_EQ(fenics.value().volume.num_prisms(), 0u);
  EXPECT_GT(fenics.value().volume.num_tets(), 0u);
  auto foam =
      mesh_tube({{"size", "0.4"}, {"layers", "2"}, {"units", "mm"}, {"solver", "openfoam"}});
  ASSERT_TRUE(foam.ok()) << foam.message();
  EXPECT_GT(foam.value().volume.num_prisms(), 0u);
  const std::string report = mesh_report_json(foam.value());
  EXPECT_NE(report.find("\"preset\":{\"solver\":\"openfoam\""), std::string::npos) << report;
  EXPECT_NE(report.find("{\"option\":\"--output-units\",\"value\":\"m\",\"from\":\"preset\"}"),
            std::string::npos)
      << report;
}

TEST(SolverPreset, YPlusSetsTheFirstLayerInTheModelsUnit) {
  // Radius 1 mm: the inlet's diameter is 2 mm (a little less: a polygon).
  auto r = mesh_tube({{"size", "0.4"},
                      {"layers", "3"},
                      {"growth", "1.2"},
                      {"units", "mm"},
                      {"first_layer_yplus", "1"},
                      {"inlet_velocity", "0.5"}});
  ASSERT_TRUE(r.ok()) << r.message();
  ASSERT_TRUE(r.value().first_layer_yplus.has_value());
  const FirstLayerFromYPlus& y = *r.value().first_layer_yplus;
  EXPECT_EQ(y.inlet, "inlet");
  EXPECT_NEAR(y.inlet_diameter, 2.0, 0.05);
  const YPlusHeight want = first_layer_height_for_yplus(y.target, y.inlet_diameter * 1e-3);
  EXPECT_DOUBLE_EQ(y.estimate.height, want.height);
  EXPECT_DOUBLE_EQ(y.height, want.height * 1e3);  // metres to mm
  EXPECT_GT(y.height, 0.01);
  EXPECT_LT(y.height, 1.0);
  const std::string report = mesh_report_json(r.value());
  EXPECT_NE(report.find("\"first_layer_yplus\":{\"yplus\":1"), std::string::npos) << report;
  // No boundary layer to size: refused before the job starts, naming the
  // option; and by the job itself when its options were filled in by hand.
  MeshJobOptions o;
  EXPECT_EQ(apply_options(
                o, given({{"first_layer_yplus", "1"}, {"inlet_velocity", "0.5"}, {"layers", "0"}}))
                .option(),
            "first_layer_yplus");
  o = {};
  o.yplus.yplus = 1;
  o.yplus.velocity = 0.5;
  o.viscous.layers = 0;
  auto none = run_mesh_job(write_stl_binary(testing::open_tube(24, 8, 1.0, 4.0)), o);
  ASSERT_FALSE(none.ok());
  EXPECT_EQ(none.status().option(), "first_layer_yplus");
}

}  // namespace
}  // namespace vm
