// The option table and the conversions around it (option_table.h).
#include "core/pipeline/option_table.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <deque>

#include "core/io/text_scan.h"
#include "core/pipeline/option_rows.h"
#include "core/util/json_writer.h"

namespace vm {
namespace {

using T = OptionType;
using option_rows::shortest_text;

constexpr double kInf = 1e308;

bool is_upper(char c) { return c >= 'A' && c <= 'Z'; }

/// camelCase to words joined by `sep` in lower case: ("coreSize", '-')
/// gives "core-size".
std::string joined_lower(std::string_view key, char sep) {
  std::string out;
  for (char c : key) {
    if (is_upper(c)) {
      out += sep;
      out += char(c - 'A' + 'a');
    } else {
      out += c;
    }
  }
  return out;
}

/// A repeatable option whose key is a plural takes one value a CLI flag:
/// its flag and id are the singular ("names": --name, "clipPlanes":
/// --clip-plane).
std::string_view singular(const OptionSpec& s) {
  return s.repeatable && s.key.ends_with('s') ? s.key.substr(0, s.key.size() - 1) : s.key;
}

/// The rows, joined in help order, with their derived names and defaults.
struct Table {
  std::vector<OptionSpec> specs;
  std::deque<std::string> texts;  ///< the derived strings the specs view

  std::string_view keep(std::string text) { return texts.emplace_back(std::move(text)); }

  Table() {
    for (auto rows : {option_rows::input_and_size(), option_rows::volume_and_layers(),
                      option_rows::output_advanced_phantom()})
      for (OptionSpec s : rows) {
        s.id = keep(joined_lower(singular(s), '_'));
        const std::string flag = joined_lower(singular(s), '-');
        s.cli = keep(s.type == T::kFlag && s.default_on ? "no-" + flag : flag);
        s.js = (s.faces & kFaceJs) ? s.key : std::string_view();
        // The default is the struct's (a flag's is default_on).
        if (s.type != T::kFlag && s.read) s.default_text = keep(s.read(MeshJobOptions{}));
        if (s.type != T::kFlag && s.read_phantom)
          s.default_text = keep(s.read_phantom(PhantomOptions{}));
        specs.push_back(s);
      }
  }
};

const Table& table() {
  static const Table t;
  return t;
}

std::string_view type_name(OptionType t) {
  switch (t) {
    case T::kNumber:
      return "number";
    case T::kInteger:
      return "integer";
    case T::kFlag:
      return "flag";
    case T::kChoice:
      return "choice";
    case T::kText:
      return "text";
    case T::kNumbers:
      return "numbers";
  }
  return "";
}

bool parse_number(std::string_view text, double& out) {
  return parse_double(text, out) && std::isfinite(out);
}

Status needs(const OptionSpec& spec) {
  return Status::BadOption(std::string(spec.id), "needs " + std::string(spec.needs));
}

bool in_range(const OptionSpec& spec, double x) {
  if (spec.min_exclusive ? !(x > spec.min) : !(x >= spec.min)) return false;
  if (spec.max_exclusive ? !(x < spec.max) : !(x <= spec.max)) return false;
  return spec.type != T::kInteger || x == std::floor(x);
}

std::string option_name(const OptionSpec& spec, OptionFace face) {
  return face == kFaceCli ? "--" + std::string(spec.cli) : std::string(spec.js);
}

}  // namespace

std::string option_rows::shortest_text(double x) {
  char buf[32];
  for (int digits = 15; digits <= 17; ++digits) {
    std::snprintf(buf, sizeof buf, "%.*g", digits, x);
    double back = 0;
    if (parse_double(buf, back) && back == x) break;
  }
  return buf;
}

bool valid_group_name(std::string_view name) {
  if (name.empty() || name.size() > 64) return false;
  if (!((name[0] >= 'a' && name[0] <= 'z') || (name[0] >= 'A' && name[0] <= 'Z'))) return false;
  for (char c : name)
    if (!((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
          c == '-'))
      return false;
  return true;
}

std::span<const OptionSpec> option_table() { return table().specs; }

const OptionSpec* find_option(std::string_view id) {
  for (const OptionSpec& s : option_table())
    if (s.id == id) return &s;
  return nullptr;
}

const OptionSpec* find_cli_option(std::string_view cli, OptionCommand command) {
  for (const OptionSpec& s : option_table())
    if ((s.faces & kFaceCli) && (s.commands & command) &&
        (s.cli == cli ||
         std::find(s.cli_aliases.begin(), s.cli_aliases.end(), cli) != s.cli_aliases.end()))
      return &s;
  return nullptr;
}

const OptionSpec* find_js_option(std::string_view js, OptionCommand command) {
  for (const OptionSpec& s : option_table())
    if ((s.faces & kFaceJs) && (s.commands & command) && s.js == js) return &s;
  return nullptr;
}

Status check_option_value(const OptionSpec& spec, const OptionValue& v) {
  if (v.opening < 0 || (v.opening > 0 && spec.per_opening == PerOpening::kNo) ||
      (v.opening == 0 && spec.per_opening == PerOpening::kRequired))
    return Status::BadOption(std::string(spec.id), "needs K=VALUE with K an opening number >= 1");
  switch (spec.type) {
    case T::kNumber:
    case T::kInteger:
      if (!std::isfinite(v.number) || !in_range(spec, v.number)) return needs(spec);
      break;
    case T::kChoice: {
      bool found = false;
      for (std::string_view c : spec.choices) found = found || c == v.text;
      if (!found) return needs(spec);
      break;
    }
    case T::kNumbers:
      if (v.numbers.size() != size_t(spec.list_size)) return needs(spec);
      for (double x : v.numbers)
        if (!std::isfinite(x) || !in_range(spec, x)) return needs(spec);
      break;
    case T::kText:
      if (v.text.empty()) return needs(spec);
      break;
    case T::kFlag:
      break;
  }
  return Status::Ok();
}

Result<OptionValue> parse_option_text(const OptionSpec& spec, std::string_view text) {
  OptionValue v;
  if (spec.per_opening != PerOpening::kNo) {
    const size_t eq = text.find('=');
    double k = 0;
    if (eq != std::string_view::npos && parse_number(text.substr(0, eq), k)) {
      if (k < 1 || k != std::floor(k) || k > 1e6)
        return Status::BadOption(std::string(spec.id),
                                 "needs K=VALUE with K an opening number >= 1");
      v.opening = int(k);
      text = text.substr(eq + 1);
    }
  }
  switch (spec.type) {
    case T::kNumber:
    case T::kInteger:
      if (!parse_number(text, v.number)) return needs(spec);
      break;
    case T::kNumbers: {
      size_t start = 0;
      while (start <= text.size()) {
        size_t comma = text.find(',', start);
        if (comma == std::string_view::npos) comma = text.size();
        double x = 0;
        if (!parse_number(text.substr(start, comma - start), x)) return needs(spec);
        v.numbers.push_back(x);
        start = comma + 1;
      }
      break;
    }
    case T::kChoice:
    case T::kText:
      v.text = std::string(text);
      break;
    case T::kFlag:
      v.flag = !spec.default_on;
      break;
  }
  Status st = check_option_value(spec, v);
  if (!st.ok()) return st;
  return v;
}

Status apply_option(MeshJobOptions& o, const OptionSpec& spec, const OptionValue& v) {
  if (!spec.set) {
    // Options of the CLI alone (paths, printing) are the CLI's business.
    if (spec.faces == kFaceCli && (spec.commands & (kCommandInfo | kCommandMesh)))
      return Status::Ok();
    return Status::Internal("option " + std::string(spec.id) + " is not applied to the job");
  }
  return spec.set(o, v) ? Status::Ok() : needs(spec);
}

Status apply_option(PhantomOptions& o, const OptionSpec& spec, const OptionValue& v) {
  if (!spec.set_phantom)
    return Status::Internal("option " + std::string(spec.id) + " is not a phantom option");
  return spec.set_phantom(o, v) ? Status::Ok() : needs(spec);
}

Status set_option_text(MeshJobOptions& options, std::string_view id, std::string_view text) {
  const OptionSpec* spec = find_option(id);
  if (!spec) return Status::Internal("unknown option id " + std::string(id));
  auto v = parse_option_text(*spec, text);
  if (!v.ok()) return v.status();
  return apply_option(options, *spec, v.value());
}

std::string option_value_text(const OptionSpec& spec, const OptionValue& v) {
  std::string text = v.opening > 0 ? std::to_string(v.opening) + "=" : "";
  switch (spec.type) {
    case T::kNumber:
    case T::kInteger:
      return text + shortest_text(v.number);
    case T::kFlag:
      return text + (v.flag ? "true" : "false");
    case T::kNumbers:
      for (size_t i = 0; i < v.numbers.size(); ++i) {
        if (i) text += ',';
        text += shortest_text(v.numbers[i]);
      }
      return text;
    case T::kChoice:
    case T::kText:
      break;
  }
  return text + v.text;
}

std::string options_provenance(std::span<const std::pair<const OptionSpec*, OptionValue>> values) {
  std::string out;
  for (const auto& [spec, value] : values) {
    // Paths, printing and the thread count change no mesh.
    if (spec->faces == kFaceCli || spec->id == "threads") continue;
    if (!out.empty()) out += " ";
    out += std::string(spec->id) + "=" + option_value_text(*spec, value);
  }
  return out;
}

std::string phrase_options(std::string_view message, OptionFace face) {
  std::string out;
  out.reserve(message.size());
  size_t i = 0;
  while (i < message.size()) {
    if (message[i] == '{') {
      const size_t close = message.find('}', i);
      if (close != std::string_view::npos) {
        if (const OptionSpec* spec = find_option(message.substr(i + 1, close - i - 1))) {
          out += option_name(*spec, face);
          i = close + 1;
          continue;
        }
      }
    }
    out += message[i++];
  }
  return out;
}

std::string phrase_error(const Status& status, OptionFace face) {
  std::string message = phrase_options(status.message(), face);
  if (status.kind() == ErrorKind::kBadOption) {
    if (const OptionSpec* spec = find_option(status.option()))
      return option_name(*spec, face) + " " + message;
  }
  return message;
}

std::string control_id(const OptionSpec& spec) { return joined_lower(spec.key, '-'); }

std::string option_table_json() {
  JsonWriter j;
  j.begin_array();
  for (const OptionSpec& s : option_table()) {
    j.begin_object();
    j.key("id").value(s.id);
    j.key("cli").value(s.cli);
    j.key("js").value(s.js);
    j.key("control").value(s.js.empty() ? std::string() : control_id(s));
    j.key("cliAliases").begin_array();
    for (std::string_view a : s.cli_aliases) j.value(a);
    j.end_array();
    j.key("type").value(type_name(s.type));
    j.key("commands").begin_array();
    for (auto [bit, name] : {std::pair{kCommandInfo, "info"}, std::pair{kCommandMesh, "mesh"},
                             std::pair{kCommandPhantom, "phantom"}})
      if (s.commands & bit) j.value(name);
    j.end_array();
    j.key("faces").begin_array();
    if (s.faces & kFaceCli) j.value("cli");
    if (s.faces & kFaceJs) j.value("js");
    j.end_array();
    j.key("group").value(s.group);
    j.key("metavar").value(s.metavar);
    if (s.min > -kInf) j.key("min").value(s.min);
    if (s.max < kInf) j.key("max").value(s.max);
    j.key("minExclusive").value(s.min_exclusive);
    j.key("maxExclusive").value(s.max_exclusive);
    j.key("choices").begin_array();
    for (std::string_view c : s.choices) j.value(c);
    j.end_array();
    j.key("listSize").value(s.list_size);
    j.key("defaultOn").value(s.default_on);
    j.key("default").value(s.default_text);
    j.key("unit").value(s.unit);
    j.key("needs").value(s.needs);
    j.key("doc").value(s.doc);
    j.key("offDoc").value(s.off_doc);
    j.key("repeatable").value(s.repeatable);
    j.key("perOpening")
        .value(s.per_opening == PerOpening::kNo         ? "no"
               : s.per_opening == PerOpening::kOptional ? "optional"
                                                        : "required");
    j.end_object();
  }
  j.end_array();
  return j.str();
}

}  // namespace vm
