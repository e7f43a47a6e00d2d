// Command-line arguments through the option table (args.h).
#include "cli/args.h"

#include <algorithm>

namespace vm::cli {
namespace {

constexpr std::pair<OptionCommand, const char*> kCommands[] = {
    {kCommandInfo, "info"}, {kCommandMesh, "mesh"}, {kCommandPhantom, "phantom"}};

constexpr const char* kGroups[] = {"input",  "size",     "volume", "layers",
                                   "output", "advanced", "phantom"};

std::string flag_text(const OptionSpec& s) {
  std::string t = "--" + std::string(s.cli);
  if (s.type != OptionType::kFlag) {
    t += " ";
    if (s.per_opening == PerOpening::kRequired) t += "K=";
    if (s.per_opening == PerOpening::kOptional) t += "[K=]";
    t += s.metavar;
  }
  return t;
}

/// `text` starting at `column`, wrapped at `width` columns, continuation
/// lines indented by `indent`.
std::string wrap(const std::string& text, size_t column, size_t indent, size_t width) {
  std::string out;
  size_t i = 0;
  while (i < text.size()) {
    size_t end = text.find(' ', i);
    if (end == std::string::npos) end = text.size();
    const size_t length = end - i;
    if (i > 0 && column + 1 + length > width) {
      out += "\n" + std::string(indent, ' ');
      column = indent;
    } else if (i > 0) {
      out += ' ';
      ++column;
    }
    out.append(text, i, length);
    column += length;
    i = end + 1;
  }
  return out;
}

std::string describe(const OptionSpec& s) {
  std::string d(s.type == OptionType::kFlag && s.default_on ? s.off_doc : s.doc);
  if (!s.default_text.empty()) d += "; default " + std::string(s.default_text);
  if (s.repeatable) d += "; repeatable";
  for (std::string_view a : s.cli_aliases) d += "; also --" + std::string(a) + " (its older name)";
  return d;
}

}  // namespace

const OptionValue* Args::get(std::string_view id) const {
  for (auto it = values.rbegin(); it != values.rend(); ++it)
    if (it->first->id == id) return &it->second;
  return nullptr;
}

Args parse_args(int argc, char** argv, int first, OptionCommand command) {
  Args a;
  for (int i = first; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg.size() < 2 || arg[0] != '-') {
      a.positional.push_back(arg);
      continue;
    }
    std::string name = arg, value;
    bool has_value = false;
    if (const size_t eq = arg.find('='); eq != std::string::npos) {
      name = arg.substr(0, eq);
      value = arg.substr(eq + 1);
      has_value = true;
    }
    const OptionSpec* spec = nullptr;
    if (name == "-o")
      spec = find_cli_option("output", command);
    else if (name.rfind("--", 0) == 0)
      spec = find_cli_option(std::string_view(name).substr(2), command);
    if (!spec) {
      a.error = "unknown option '" + name + "'";
      return a;
    }
    if (!spec->repeatable && a.get(spec->id)) {
      a.error = "option '" + name + "' is given more than once";
      return a;
    }
    if (spec->type == OptionType::kFlag) {
      if (has_value) {
        a.error = "option '" + name + "' takes no value";
        return a;
      }
    } else if (!has_value) {
      if (i + 1 >= argc) {
        a.error = "option '" + name + "' needs a value";
        return a;
      }
      value = argv[++i];
    }
    Result<OptionValue> v = parse_option_text(*spec, value);
    if (!v.ok()) {
      a.error = phrase_error(v.status(), kFaceCli);
      return a;
    }
    a.values.emplace_back(spec, std::move(v).value());
  }
  return a;
}

std::string apply_all(const Args& args, MeshJobOptions& options) {
  Status st = apply_options(options, args.values);  // the solver preset first
  return st.ok() ? "" : phrase_error(st, kFaceCli);
}

std::string apply_all(const Args& args, PhantomOptions& options) {
  for (const auto& [spec, value] : args.values) {
    if (!(spec->commands & kCommandPhantom)) continue;
    Status st = apply_option(options, *spec, value);
    if (!st.ok()) return phrase_error(st, kFaceCli);
  }
  return "";
}

std::string options_help() {
  std::string out;
  for (const auto& [command, command_name] : kCommands) {
    out += "\n" + std::string(command_name) + " options:\n";
    for (const char* group : kGroups) {
      bool header = false;
      for (const OptionSpec& s : option_table()) {
        if (!(s.commands & command) || !(s.faces & kFaceCli) || s.group != group) continue;
        if (!header && command != kCommandPhantom) out += "  " + std::string(group) + ":\n";
        header = true;
        std::string line = "    " + flag_text(s);
        if (line.size() < 30)
          line += std::string(30 - line.size(), ' ');
        else
          line += "\n" + std::string(30, ' ');
        out += line + wrap(describe(s), 30, 30, 79) + "\n";
      }
    }
  }
  return out;
}

namespace {

/// A Markdown table cell: a '|' (in "auto|off", say) would end the cell.
std::string cell(const std::string& text) {
  std::string out;
  for (char c : text) out += c == '|' ? std::string("\\|") : std::string(1, c);
  return out;
}

}  // namespace

std::string options_markdown() {
  std::string out;
  for (const auto& [command, command_name] : kCommands) {
    out += "\n`" + std::string(command_name) + "`";
    out += command == kCommandInfo   ? " (JS `analyze()`)"
           : command == kCommandMesh ? " (JS `mesh()`)"
                                     : " (JS `makePhantom()`)";
    out += ":\n\n| CLI | JS | value | default | what |\n|---|---|---|---|---|\n";
    for (const char* group : kGroups)
      for (const OptionSpec& s : option_table()) {
        if (!(s.commands & command) || s.group != group) continue;
        std::string cli = (s.faces & kFaceCli) ? "`" + flag_text(s) + "`" : "";
        if (s.id == "output") cli = "`-o`, " + cli;
        for (std::string_view a : s.cli_aliases) cli += " (or `--" + std::string(a) + "`)";
        const std::string js = (s.faces & kFaceJs) ? "`" + std::string(s.js) + "`" : "";
        const std::string value = s.type == OptionType::kFlag ? "flag" : std::string(s.needs);
        std::string def(s.default_text);
        if (s.type == OptionType::kFlag) def = s.default_on ? "on" : "off";
        out += "| " + cell(cli) + " | " + cell(js) + " | " + cell(value) + " | " + cell(def) +
               " | " + cell(std::string(s.doc) + (s.repeatable ? "; repeatable" : "")) + " |\n";
      }
  }
  return out;
}

}  // namespace vm::cli
