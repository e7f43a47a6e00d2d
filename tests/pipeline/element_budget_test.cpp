#include "core/pipeline/element_budget.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <new>
#include <numbers>
#include <string>
#include <string_view>

#include "core/geom/vec3.h"
#include "core/io/stl.h"
#include "core/pipeline/mesh_job.h"
#include "core/pipeline/option_table.h"
#include "core/pipeline/report_json.h"
#include "core/surface/vessel_radius.h"
#include "tests/support/phantoms.h"

namespace vm {
namespace {

/// The bifurcation phantom (parent radius 1) as a file.
std::vector<uint8_t> bifurcation_stl() {
  return write_stl_binary(testing::phantom(PhantomKind::kBifurcation, true, 0.15));
}

/// The budget of the default job with `max_elements`, and its options.
MeshJobOptions with_budget(const char* max_elements) {
  MeshJobOptions o;
  EXPECT_TRUE(set_option_text(o, "max_elements", max_elements).ok());
  return o;
}

/// Whether the size options fit the budget on the prepared surface `s`.
bool fits(const PreparedSurface& s, const MeshJobOptions& o) {
  SizeOptions size = o.remesh_options.size;
  BudgetFit fit;
  return fit_element_budget(s.mesh, s.topology.openings, vessel_radius(s.mesh), element_budget(o),
                            size, fit)
      .ok();
}

/// The refusal `st` of `option` (per_circumference 20 or size 0.05 in `o`)
/// has a `coarser` remedy: a coarser value of the same option, named in the
/// message as the one that fits, and fitting (`o`'s budget and memory) on
/// the prepared surface `s`.
void expect_coarser_fits(const Status& st, const std::string& option, MeshJobOptions o,
                         const PreparedSurface& s) {
  ASSERT_EQ(st.remedy().action, "coarser") << st.message();
  const double coarser = st.remedy().value;
  EXPECT_NE(st.message().find("{" + option + "} " + number_text(coarser) + " fits"),
            std::string::npos)
      << st.message();
  ASSERT_TRUE(set_option_text(o, option, number_text(coarser)).ok());
  EXPECT_TRUE(option == "size" ? coarser > 0.05 : coarser < 20);
  EXPECT_TRUE(fits(s, o)) << option << " " << coarser;
}

TEST(ElementBudget, TheDefaultSizeIsCoarsenedToFitAndSaysSo) {
  const std::vector<uint8_t> stl = bifurcation_stl();
  MeshJobOptions o = with_budget("15000");
  auto r = run_mesh_job(stl, o);
  ASSERT_TRUE(r.ok()) << r.message();
  const BudgetFit& f = r.value().budget;
  ASSERT_TRUE(f.coarsened);
  EXPECT_EQ(f.asked_per_circumference, 20);
  EXPECT_LT(f.per_circumference, 20);
  EXPECT_GE(f.per_circumference, fewest_per_circumference(o.max_volume_change));
  EXPECT_EQ(f.per_circumference, std::floor(f.per_circumference));
  EXPECT_GT(f.asked_elements, 15000);
  EXPECT_LE(f.elements, 15000);
  EXPECT_GE(f.enough, f.asked_elements);
  // Said in a warning with how to ask for the finer mesh, and in the report.
  const std::vector<std::string>& w = r.value().warnings;
  ASSERT_NE(std::find(w.begin(), w.end(), budget_warning(f)), w.end());
  EXPECT_NE(budget_warning(f).find("the default size ({per_circumference} 20) would make about"),
            std::string::npos);
  EXPECT_NE(budget_warning(f).find("ask for the finer mesh with {per_circumference} 20 and "
                                   "{max_elements} "),
            std::string::npos);
  const std::string json = mesh_report_json(r.value());
  EXPECT_NE(json.find("\"element_budget\":{\"max_elements\":15000,\"coarsened\":true,\"counted\":"),
            std::string::npos);
  // The mesh is whole: a lumen, every element in a group.
  EXPECT_GT(r.value().volume.num_tets(), 0u);
  size_t grouped = 0;
  for (const OutputGroup& g : r.value().groups)
    if (g.dim == 3) grouped += g.elements;
  EXPECT_EQ(grouped, r.value().volume.num_tets() + r.value().volume.num_prisms());

  // The finer mesh it names fits the budget it names, and the default fits
  // a budget that large without coarsening.
  auto prepared = prepare_surface(stl);
  ASSERT_TRUE(prepared.ok());
  MeshJobOptions finer = with_budget(std::to_string(long(f.enough)).c_str());
  ASSERT_TRUE(set_option_text(finer, "per_circumference", "20").ok());
  EXPECT_TRUE(fits(prepared.value(), finer));
  EXPECT_FALSE(fits(prepared.value(), [&] {
    MeshJobOptions given = with_budget("15000");
    EXPECT_TRUE(set_option_text(given, "per_circumference", "20").ok());
    return given;
  }()));
}

TEST(ElementBudget, AGivenSizeIsRefusedWithTheSizeThatFits) {
  const std::vector<uint8_t> stl = bifurcation_stl();
  auto prepared = prepare_surface(stl);
  ASSERT_TRUE(prepared.ok());
  for (const auto& [option, value] : std::vector<std::pair<std::string, std::string>>{
           {"per_circumference", "20"}, {"size", "0.05"}}) {
    MeshJobOptions o = with_budget("15000");
    ASSERT_TRUE(set_option_text(o, option, value).ok());
    int calls = 0;
    auto r = run_mesh_job(stl, o, [&](double f, std::string_view) { return ++calls, f < 0.5; });
    ASSERT_FALSE(r.ok()) << option;
    const Status& st = r.status();
    EXPECT_EQ(st.kind(), ErrorKind::kBadOption) << st.message();
    EXPECT_EQ(st.option(), option);
    EXPECT_NE(st.message().find("more than the element budget ({max_elements} 15000)"),
              std::string::npos)
        << st.message();
    expect_coarser_fits(st, option, o, prepared.value());
  }
}

TEST(ElementBudget, MemoryCapsTheTetrahedraBelowTheBudget) {
  const std::vector<uint8_t> stl = bifurcation_stl();
  auto prepared = prepare_surface(stl);
  ASSERT_TRUE(prepared.ok());
  // Memory for 15000 tetrahedra, under the default budget of 15M.
  const double memory = 15000 * kWasmBytesPerTetrahedron;
  EXPECT_DOUBLE_EQ(tetrahedra_in_memory(memory), 15000);
  EXPECT_EQ(tetrahedra_in_memory(0), 0);
  EXPECT_TRUE(tetrahedron_limit(15e6, memory).memory);
  EXPECT_FALSE(tetrahedron_limit(1e4, memory).memory);
  EXPECT_FALSE(tetrahedron_limit(15e6, 0).memory);

  // A given size: refused as the memory's limit, with the size that fits
  // it and no larger budget offered (none would help).
  for (const auto& [option, value] : std::vector<std::pair<std::string, std::string>>{
           {"per_circumference", "20"}, {"size", "0.05"}}) {
    MeshJobOptions o;
    ASSERT_TRUE(set_option_text(o, option, value).ok());
    o.memory_bytes = memory;
    auto r = run_mesh_job(stl, o);
    ASSERT_FALSE(r.ok()) << option;
    const Status& st = r.status();
    EXPECT_EQ(st.kind(), ErrorKind::kBadOption) << st.message();
    EXPECT_EQ(st.option(), option);
    EXPECT_NE(st.message().find("tetrahedra in the lumen, more than fit in " + memory_text(memory)),
              std::string::npos)
        << st.message();
    EXPECT_NE(memory_text(memory).find("about 1.5e+04 tetrahedra at 300 bytes each"),
              std::string::npos)
        << memory_text(memory);
    EXPECT_EQ(st.message().find("max_elements"), std::string::npos) << st.message();
    expect_coarser_fits(st, option, o, prepared.value());
  }

  // The default size: coarsened to fit, said as the memory's limit.
  MeshJobOptions o;
  o.memory_bytes = memory;
  auto r = run_mesh_job(stl, o);
  ASSERT_TRUE(r.ok()) << r.message();
  const BudgetFit& f = r.value().budget;
  ASSERT_TRUE(f.coarsened);
  EXPECT_TRUE(f.memory);
  EXPECT_LE(f.elements, 15000);
  EXPECT_NE(budget_warning(f).find("more than fit in the mesher's memory"), std::string::npos)
      << budget_warning(f);
  EXPECT_EQ(budget_warning(f).find("max_elements"), std::string::npos) << budget_warning(f);
}

TEST(ElementBudget, AFailedAllocationEndsTheJobWithAnError) {
  // An allocation failing in the remeshing (std::bad_alloc thrown from
  // within the job, as operator new throws it).
  bool thrown = false;
  auto r = run_mesh_job(bifurcation_stl(), {}, [&](double, std::string_view stage) {
    if (stage == "partitioning" && !thrown) {
      thrown = true;
      throw std::bad_alloc();
    }
    return true;
  });
  ASSERT_TRUE(thrown);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().kind(), ErrorKind::kBadInput);
  const std::string text = phrase_error(r.status(), kFaceJs);
  EXPECT_EQ(text.rfind("out of memory during \"partitioning\" (", 0), 0u) << text;
  EXPECT_NE(text.find("try a coarser size (a larger size or a smaller perCircumference)"),
            std::string::npos)
      << text;
  // The next job runs.
  EXPECT_TRUE(run_mesh_job(bifurcation_stl(), with_budget("15000")).ok());
}

TEST(ElementBudget, ABudgetTooSmallForTheDefaultIsRefusedNamingIt) {
  auto r = run_mesh_job(bifurcation_stl(), with_budget("1000"));
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().kind(), ErrorKind::kBadOption);
  EXPECT_EQ(r.status().option(), "max_elements");
  EXPECT_NE(
      phrase_error(r.status(), kFaceCli).find("--max-elements 1000 is too small for this model"),
      std::string::npos)
      << r.message();
}

TEST(ElementBudget, TheFewestPerCircumferenceKeepsTheVesselsVolume) {
  // A regular N-gon inscribed in a circle keeps N sin(2 pi / N) / (2 pi) of
  // its area: the fewest N keeps the loss within the allowance, one fewer
  // would not keep it within 0.8 of it.
  auto loss = [](double n) {
    return 1 - n * std::sin(2 * std::numbers::pi / n) / (2 * std::numbers::pi);
  };
  for (double change : {0.01, 0.02, 0.05, 0.2}) {
    const double n = fewest_per_circumference(change);
    EXPECT_LE(loss(n), change) << change;
    EXPECT_GT(loss(n - 1), 0.7 * change) << change;
  }
}

}  // namespace
}  // namespace vm
