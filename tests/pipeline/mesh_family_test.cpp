#include "core/pipeline/mesh_family.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "core/io/stl.h"
#include "core/pipeline/option_table.h"
#include "tests/support/expect_has.h"
#include "tests/support/phantoms.h"

namespace vm {
namespace {

TEST(MeshFamily, MemberOptionsDivideEverySizeByTheRatioPower) {
  MeshJobOptions o;
  ASSERT_TRUE(set_option_text(o, "family", "3").ok());
  ASSERT_TRUE(set_option_text(o, "ratio", "1.5").ok());
  ASSERT_TRUE(set_option_text(o, "size", "0.4").ok());
  ASSERT_TRUE(set_option_text(o, "core_size", "0.6").ok());
  ASSERT_TRUE(set_option_text(o, "refine", "0,0,0,1,0.2").ok());
  ASSERT_TRUE(set_option_text(o, "size_min", "0.1").ok());
  const MeshJobOptions m0 = family_member_options(o, 0);
  EXPECT_EQ(m0.family, 1);
  EXPECT_EQ(m0.remesh_options.size.size, 0.4);
  EXPECT_EQ(m0.viscous.layers, 4);
  const MeshJobOptions m2 = family_member_options(o, 2);
  EXPECT_EQ(m2.family, 1);
  EXPECT_DOUBLE_EQ(m2.remesh_options.size.size, 0.4 / 2.25);
  EXPECT_DOUBLE_EQ(m2.core_size, 0.6 / 2.25);
  EXPECT_DOUBLE_EQ(m2.remesh_options.size.size_min, 0.1 / 2.25);
  ASSERT_EQ(m2.remesh_options.size.spheres.size(), 1u);
  EXPECT_DOUBLE_EQ(m2.remesh_options.size.spheres[0].size, 0.2 / 2.25);
  EXPECT_EQ(m2.remesh_options.size.spheres[0].radius, 1.0);  // where, not how fine
  EXPECT_DOUBLE_EQ(m2.remesh_options.size.gradation, o.remesh_options.size.gradation / 2.25);
  EXPECT_DOUBLE_EQ(m2.gradation_divisor, 2.25);
  EXPECT_TRUE(m2.size_given);  // refused over the budget, never coarsened alone
  // Refined layers: 4 -> 9, the first layer (0.05 R) divided by 2.25
  // exactly, the total thickness the same here (9 = 4 x 2.25).
  EXPECT_EQ(m2.viscous.layers, 9);
  EXPECT_DOUBLE_EQ(m2.viscous.thickness_fraction / 9, 0.2 / 4 / 2.25);
  const MeshJobOptions m1 = family_member_options(o, 1);  // 4 x 1.5 = 6
  EXPECT_EQ(m1.viscous.layers, 6);
  EXPECT_DOUBLE_EQ(m1.viscous.thickness_fraction / 6, 0.2 / 4 / 1.5);
}

TEST(MeshFamily, PerCircumferenceGrowsAndLayersRefineOrStayFixed) {
  MeshJobOptions o;
  ASSERT_TRUE(set_option_text(o, "family", "3").ok());
  ASSERT_TRUE(set_option_text(o, "first_layer", "0.02").ok());
  ASSERT_TRUE(set_option_text(o, "growth", "1.2").ok());
  // The default 20 per circumference, coarsened to 16 by the budget.
  const MeshJobOptions m1 = family_member_options(o, 1, 16);
  EXPECT_DOUBLE_EQ(m1.remesh_options.size.per_circumference, 16 * 1.4);
  EXPECT_DOUBLE_EQ(m1.viscous.first_height, 0.02 / 1.4);
  EXPECT_EQ(m1.viscous.layers, 6);
  // The same total layer: g^4 = g1^6.
  EXPECT_NEAR(std::pow(m1.viscous.growth, 6), std::pow(1.2, 4), 1e-9);
  ASSERT_TRUE(set_option_text(o, "family_layers", "fixed").ok());
  const MeshJobOptions f2 = family_member_options(o, 2);
  EXPECT_EQ(f2.viscous.layers, 4);
  EXPECT_EQ(f2.viscous.first_height, 0.02);
  EXPECT_EQ(f2.viscous.growth, 1.2);
  EXPECT_DOUBLE_EQ(f2.remesh_options.size.per_circumference, 20 * 1.96);
  // Out of range.
  EXPECT_FALSE(set_option_text(o, "family", "0").ok());
  EXPECT_FALSE(set_option_text(o, "family", "7").ok());
  EXPECT_FALSE(set_option_text(o, "ratio", "1").ok());
  EXPECT_FALSE(set_option_text(o, "family_layers", "more").ok());
}

TEST(MeshFamily, ThreeMembersOfOneSurfaceRefineByTheRatio) {
  const std::vector<uint8_t> stl =
      write_stl_binary(testing::phantom(PhantomKind::kBifurcation, true, 0.2));
  MeshJobOptions o;
  ASSERT_TRUE(set_option_text(o, "family", "3").ok());
  ASSERT_TRUE(set_option_text(o, "per_circumference", "10").ok());
  ASSERT_TRUE(set_option_text(o, "layers", "2").ok());
  std::vector<std::vector<std::string>> names;
  std::vector<int> order;
  auto fam = run_mesh_family(stl, o, [&](int k, const MeshJobOptions& m, const MeshJobResult& r) {
    order.push_back(k);
    EXPECT_EQ(m.viscous.layers, k == 0 ? 2 : k == 1 ? 3 : 4);
    std::vector<std::string> n;
    for (const OutputGroup& g : r.groups) n.push_back(g.name);
    names.push_back(n);
    return Status::Ok();
  });
  ASSERT_TRUE(fam.ok()) << fam.message();
  EXPECT_EQ(order, (std::vector<int>{0, 1, 2}));
  ASSERT_EQ(names.size(), 3u);
  EXPECT_EQ(names[0], names[1]);
  EXPECT_EQ(names[0], names[2]);
  const MeshFamily& f = fam.value();
  ASSERT_EQ(f.rows.size(), 3u);
  EXPECT_EQ(f.unit, "cm");  // the phantom's radii of about 1 look like an aorta in cm
  for (int k = 0; k < 3; ++k) {
    const FamilyMember& m = f.rows[size_t(k)];
    EXPECT_EQ(m.index, k);
    EXPECT_GT(m.cells, 0u);
    EXPECT_GE(m.core_quality.min, 0.25) << k;
    EXPECT_GT(m.layer_thickness, 0);
    EXPECT_GT(m.first_layer_height, 0);
    EXPECT_LT(m.first_layer_height, m.layer_thickness);
    // The same lumen, resolved better.
    EXPECT_NEAR(m.lumen_volume, f.rows[0].lumen_volume, 0.05 * f.rows[0].lumen_volume);
    if (k > 0) {
      EXPECT_NEAR(m.ratio, 1.4, 0.14) << k;  // within 10 % of r
      EXPECT_NEAR(m.h * m.ratio, f.rows[size_t(k) - 1].h, 1e-12);
      // The first layer refined by r (its height measured from the layer's
      // volume, not asked).
      EXPECT_NEAR(f.rows[size_t(k) - 1].first_layer_height / m.first_layer_height, 1.4, 0.14) << k;
    }
  }
  // Written in metres: the table's lengths are the files'.
  MeshJobOptions m = o;
  m.family = 2;
  ASSERT_TRUE(set_option_text(m, "output_units", "m").ok());
  auto metres = run_mesh_family(stl, m, {});
  ASSERT_TRUE(metres.ok()) << metres.message();
  EXPECT_EQ(metres.value().unit, "m");
  EXPECT_NEAR(metres.value().rows[1].h, f.rows[1].h / 100, 1e-9 * f.rows[1].h);
  EXPECT_NEAR(metres.value().rows[1].lumen_volume, f.rows[1].lumen_volume / 1e6,
              1e-9 * f.rows[1].lumen_volume);
  EXPECT_EQ(metres.value().rows[1].ratio, f.rows[1].ratio);
  const std::string csv = family_csv(f);
  EXPECT_EQ(testing::count_of(csv, "\n"), 4u);
  EXPECT_EQ(csv.rfind("member,file,scale,nodes,", 0), 0u);
  const std::string json = family_json(f);
  EXPECT_EQ(testing::count_of(json, "\"member\":"), 3u);
  EXPECT_NE(json.find("\"layers\":\"refine\""), std::string::npos);
}

TEST(MeshFamily, SurfaceOnlyIsRefusedAndAMemberErrorSaysWhichMember) {
  const std::vector<uint8_t> stl =
      write_stl_binary(testing::phantom(PhantomKind::kBifurcation, true, 0.2));
  MeshJobOptions o;
  ASSERT_TRUE(set_option_text(o, "family", "2").ok());
  o.volume = false;
  auto r = run_mesh_family(stl, o, {});
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().kind(), ErrorKind::kBadOption);
  // A budget the first member fits and the second does not.
  MeshJobOptions b;
  ASSERT_TRUE(set_option_text(b, "family", "2").ok());
  ASSERT_TRUE(set_option_text(b, "ratio", "2").ok());
  ASSERT_TRUE(set_option_text(b, "per_circumference", "10").ok());
  ASSERT_TRUE(set_option_text(b, "layers", "0").ok());
  MeshJobOptions one = b;
  one.family = 1;
  auto single = run_mesh_job(stl, one);
  ASSERT_TRUE(single.ok()) << single.message();
  b.max_elements = double(single.value().volume.num_tets()) * 2;  // the second needs ~8 times
  int written = 0;
  auto over = run_mesh_family(stl, b, [&](int, const MeshJobOptions&, const MeshJobResult&) {
    ++written;
    return Status::Ok();
  });
  ASSERT_FALSE(over.ok());
  EXPECT_EQ(written, 1);
  EXPECT_NE(over.message().find("family member 2 of 2 (sizes / 2)"), std::string::npos)
      << over.message();
}

}  // namespace
}  // namespace vm
