#include "core/pipeline/option_table.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <set>
#include <string>

namespace vm {
namespace {

/// A valid CLI text for `spec` (the low end of its range).
std::string valid_text(const OptionSpec& s) {
  std::string t;
  switch (s.type) {
    case OptionType::kNumber:
      t = std::to_string(s.min_exclusive ? s.min + 0.5 : s.min);
      break;
    case OptionType::kInteger:
      t = std::to_string(int(s.min) + (s.min_exclusive ? 1 : 0));
      break;
    case OptionType::kChoice:
      t = std::string(s.choices.front());
      break;
    case OptionType::kText:  // the default where there is one ("auto" for smooth)
      t.assign(s.default_text.empty() ? std::string_view("a") : s.default_text);
      break;
    case OptionType::kNumbers:
      for (int i = 0; i < s.list_size; ++i)
        t += (i ? "," : "") + std::to_string(std::max(s.min + 1, 1.0));
      break;
    case OptionType::kFlag:
      break;
  }
  return s.per_opening == PerOpening::kRequired ? "1=" + t : t;
}

TEST(OptionTable, NamesAreUniquePerCommandAndComplete) {
  for (OptionCommand c : {kCommandInfo, kCommandMesh, kCommandPhantom}) {
    std::set<std::string_view> ids, clis, jss;
    for (const OptionSpec& s : option_table()) {
      if (!(s.commands & c)) continue;
      EXPECT_TRUE(ids.insert(s.id).second) << s.id;
      if (s.faces & kFaceCli) {
        EXPECT_TRUE(clis.insert(s.cli).second) << s.cli;
      }
      if (s.faces & kFaceJs) {
        EXPECT_TRUE(jss.insert(s.js).second) << s.js;
      }
    }
  }
  for (const OptionSpec& s : option_table()) {
    EXPECT_FALSE(s.doc.empty()) << s.id;
    EXPECT_FALSE(s.group.empty()) << s.id;
    if (s.faces & kFaceJs) {
      EXPECT_FALSE(s.js.empty()) << s.id;
    }
    if (s.type != OptionType::kFlag) {
      EXPECT_FALSE(s.needs.empty()) << s.id;
    }
    if (s.type != OptionType::kFlag) {
      EXPECT_FALSE(s.metavar.empty()) << s.id;
    }
    if (s.type == OptionType::kFlag && s.default_on) {
      EXPECT_FALSE(s.off_doc.empty()) << s.id;
    }
    if (s.type == OptionType::kChoice) {
      EXPECT_FALSE(s.choices.empty()) << s.id;
    }
    EXPECT_EQ(find_option(s.id), &s);
  }
}

TEST(OptionTable, EveryOptionAppliesWithAValidValue) {
  for (const OptionSpec& s : option_table()) {
    OptionValue flag;
    flag.flag = !s.default_on;
    auto v = s.type == OptionType::kFlag ? Result<OptionValue>(flag)
                                         : parse_option_text(s, valid_text(s));
    ASSERT_TRUE(v.ok()) << s.id << ": " << v.message();
    Status st;
    if (s.commands & kCommandPhantom) {
      PhantomOptions p;
      st = apply_option(p, s, v.value());
    } else {
      MeshJobOptions m;
      st = apply_option(m, s, v.value());
    }
    EXPECT_TRUE(st.ok()) << s.id << ": " << st.message();
  }
}

TEST(OptionTable, EveryIntegerFitsAnInt) {
  // Integer options are stored in int (inlet, layers...): a maximum keeps
  // every accepted value representable (the fuzzer found --inlet 1e10).
  for (const OptionSpec& s : option_table()) {
    if (s.type != OptionType::kInteger) continue;
    EXPECT_LE(s.max, 4294967295.0) << s.id;
    if (s.id != "seed") {
      EXPECT_LE(s.max, double(std::numeric_limits<int>::max())) << s.id;
    }
  }
  MeshJobOptions o;
  const Status big = set_option_text(o, "inlet", "1e10");
  EXPECT_EQ(big.kind(), ErrorKind::kBadOption);
}

TEST(OptionTable, ParsesAndChecksRanges) {
  const OptionSpec& layers = *find_option("layers");
  EXPECT_EQ(parse_option_text(layers, "4").value().number, 4);
  for (const char* bad : {"-1", "101", "1.5", "x", "", "4x", "nan", "inf"}) {
    auto r = parse_option_text(layers, bad);
    ASSERT_FALSE(r.ok()) << bad;
    EXPECT_EQ(r.status().kind(), ErrorKind::kBadOption);
    EXPECT_EQ(r.status().option(), "layers");
    EXPECT_EQ(r.message(), "needs a number of layers from 0 (none) to 100");
  }
  const OptionSpec& thickness = *find_option("layer_thickness");
  EXPECT_FALSE(parse_option_text(thickness, "0").ok());  // exclusive bounds
  EXPECT_FALSE(parse_option_text(thickness, "1").ok());
  EXPECT_TRUE(parse_option_text(thickness, "0.5").ok());
  const OptionSpec& version = *find_option("msh_version");
  EXPECT_TRUE(parse_option_text(version, "2.2").ok());
  EXPECT_FALSE(parse_option_text(version, "3").ok());
  // Not per-opening: K=VALUE is not a number.
  EXPECT_FALSE(parse_option_text(*find_option("size"), "1=0.2").ok());
}

TEST(OptionTable, AppliesToTheJobOptions) {
  MeshJobOptions o;
  ASSERT_TRUE(set_option_text(o, "size", "0.25").ok());
  EXPECT_EQ(o.remesh_options.size.mode, SizeMode::kUniform);
  EXPECT_EQ(o.remesh_options.size.size, 0.25);
  ASSERT_TRUE(set_option_text(o, "inlet", "2").ok());
  EXPECT_EQ(o.inlet, 1);
  ASSERT_TRUE(set_option_text(o, "wall_thickness", "0.15").ok());
  EXPECT_EQ(o.vessel.layers, 4);  // a thickness alone turns the wall on
  EXPECT_EQ(o.vessel.thickness_fraction, 0.15);
  ASSERT_TRUE(set_option_text(o, "mesher2d", "adapt").ok());
  EXPECT_EQ(o.remesh_options.patch.mesher, Mesher2D::kAdapt);
  ASSERT_TRUE(set_option_text(o, "fidelity", "0").ok());
  EXPECT_EQ(o.remesh_options.fidelity_rounds, 0);
  EXPECT_EQ(set_option_text(o, "no_such_option", "1").kind(), ErrorKind::kInternal);
}

TEST(OptionTable, EachInterfacePhrasesOptionsInItsOwnWords) {
  const Status st = Status::BadOption("per_circumference", "needs more than {size_min}");
  EXPECT_EQ(phrase_error(st, kFaceCli), "--per-circumference needs more than --size-min");
  EXPECT_EQ(phrase_error(st, kFaceJs), "perCircumference needs more than sizeMin");
  // A flag that defaults to on is named by the CLI flag that turns it off.
  EXPECT_EQ(phrase_options("try {remesh}", kFaceCli), "try --no-remesh");
  // Braces that are not option ids stay.
  EXPECT_EQ(phrase_options("{x} and {", kFaceJs), "{x} and {");
  EXPECT_EQ(phrase_error(Status::Cancelled(), kFaceJs), "cancelled");
}

TEST(OptionTable, JsonListsEveryOption) {
  const std::string json = option_table_json();
  for (const OptionSpec& s : option_table())
    EXPECT_NE(json.find("\"id\":\"" + std::string(s.id) + "\""), std::string::npos) << s.id;
}

}  // namespace
}  // namespace vm
