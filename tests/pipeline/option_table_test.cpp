#include "core/pipeline/option_table.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <map>
#include <set>
#include <string>
#include <vector>

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

/// camelCase `key` as lower-case words joined by `sep`.
std::string words(std::string_view key, char sep) {
  std::string out;
  for (char c : key) {
    if (c >= 'A' && c <= 'Z') {
      out += sep;
      out += char(c - 'A' + 'a');
    } else {
      out += c;
    }
  }
  return out;
}

// The CLI flag, the JS key, the id and the page's control id all come from
// the row's one key, by one rule each.
TEST(OptionTable, EveryNameComesFromTheKey) {
  for (const OptionSpec& s : option_table()) {
    std::string_view one = s.key;
    if (s.repeatable && one.ends_with('s')) one.remove_suffix(1);
    EXPECT_EQ(s.id, words(one, '_')) << s.key;
    const std::string flag = words(one, '-');
    EXPECT_EQ(s.cli, s.type == OptionType::kFlag && s.default_on ? "no-" + flag : flag) << s.key;
    EXPECT_EQ(s.js, (s.faces & kFaceJs) ? s.key : std::string_view()) << s.key;
    EXPECT_EQ(control_id(s), words(s.key, '-')) << s.key;
    for (std::string_view alias : s.cli_aliases)
      for (OptionCommand c : {kCommandInfo, kCommandMesh, kCommandPhantom})
        if (s.commands & c) {
          EXPECT_EQ(find_cli_option(alias, c), &s) << alias;
        }
  }
  // The older names users' scripts have.
  EXPECT_EQ(find_cli_option("for", kCommandMesh), find_option("solver"));
  EXPECT_EQ(find_cli_option("closed", kCommandPhantom), find_option("open_ends"));
  EXPECT_EQ(find_cli_option("largest-component", kCommandInfo),
            find_option("largest_component_only"));
}

/// Every row's reading of `options` (or of the phantom's), by id.
std::map<std::string_view, std::string> reads(const MeshJobOptions& m, const PhantomOptions& p) {
  std::map<std::string_view, std::string> out;
  for (const OptionSpec& s : option_table()) {
    if (s.read) out[s.id] = s.read(m);
    if (s.read_phantom) out[s.id] = s.read_phantom(p);
  }
  return out;
}

// The table's defaults are MeshJobOptions{} (and PhantomOptions{}): each is
// read from the struct, and giving it changes nothing in a default job.
TEST(OptionTable, DefaultsAreTheStructs) {
  const auto defaults = reads(MeshJobOptions{}, PhantomOptions{});
  for (const OptionSpec& s : option_table()) {
    const bool job = s.commands & (kCommandInfo | kCommandMesh);
    // Every option but the CLI's own (paths, printing) is set and read
    // through its row.
    if (job && (s.faces & kFaceJs)) {
      EXPECT_TRUE(s.set && s.read) << s.id;
    }
    if (s.commands & kCommandPhantom) {
      EXPECT_TRUE(s.set_phantom && s.read_phantom) << s.id;
    }
    if (!s.read && !s.read_phantom) continue;
    const std::string text = defaults.at(s.id);
    if (s.type == OptionType::kFlag) {
      EXPECT_EQ(text, s.default_on ? "true" : "false") << s.id;
      continue;
    }
    EXPECT_EQ(s.default_text, text) << s.id;
    if (text.empty()) continue;  // unset: decided from the surface
    auto v = parse_option_text(s, text);
    ASSERT_TRUE(v.ok()) << s.id << ": the default " << text << " is refused: " << v.message();
    MeshJobOptions m;
    PhantomOptions p;
    Status st = s.set ? apply_option(m, s, v.value()) : apply_option(p, s, v.value());
    ASSERT_TRUE(st.ok()) << s.id << ": " << st.message();
    EXPECT_EQ(reads(m, p), defaults)
        << "giving " << s.id << " its default " << text << " changed the job's options";
  }
}

// What a row sets, it reads back: every choice, and a value in range.
TEST(OptionTable, WhatIsSetIsRead) {
  for (const OptionSpec& s : option_table()) {
    if (!s.read && !s.read_phantom) continue;
    std::vector<std::string> texts;
    if (s.type == OptionType::kChoice)
      texts.assign(s.choices.begin(), s.choices.end());
    else if (s.type == OptionType::kNumber || s.type == OptionType::kInteger)
      texts.push_back(valid_text(s));
    for (const std::string& text : texts) {
      auto v = parse_option_text(s, text);
      ASSERT_TRUE(v.ok()) << s.id << " " << text;
      MeshJobOptions m;
      PhantomOptions p;
      ASSERT_TRUE((s.set ? apply_option(m, s, v.value()) : apply_option(p, s, v.value())).ok());
      const std::string back = s.read ? s.read(m) : s.read_phantom(p);
      // A value that leaves the job as by default may read as unset (the
      // inlet 1, the largest opening; 0 wall layers, no wall).
      if (back.empty() && reads(m, p) == reads(MeshJobOptions{}, PhantomOptions{})) continue;
      EXPECT_EQ(back, option_value_text(s, v.value())) << s.id << " " << text;
    }
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
