// The option table: every user-settable option of vesselmesh, once, with its
// type, range, default, unit and one line of documentation. The CLI parser
// and help, the WebAssembly binding, the JavaScript API's type declarations
// and the option list of docs/options.md are all made from it (or checked
// against it), so they cannot drift apart. See docs/ARCHITECTURE.md, "Options".
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/phantom/vessel_phantom.h"
#include "core/pipeline/mesh_job.h"
#include "core/util/result.h"

namespace vm {

enum class OptionType {
  kNumber,   ///< a finite real number
  kInteger,  ///< a whole number
  kFlag,     ///< on/off (CLI: present or not; JS: a boolean)
  kChoice,   ///< one word of `choices`
  kText,     ///< free text (CLI-only paths, names)
  kNumbers,  ///< `list_size` comma-separated numbers (JS: an array)
};

/// The commands (CLI subcommands, JS API calls) an option applies to.
enum OptionCommand : uint8_t {
  kCommandInfo = 1,     ///< `vesselmesh info`, JS analyze()
  kCommandMesh = 2,     ///< `vesselmesh mesh`, JS mesh()
  kCommandPhantom = 4,  ///< `vesselmesh phantom`, JS makePhantom()
};

/// The interfaces that expose an option.
enum OptionFace : uint8_t { kFaceCli = 1, kFaceJs = 2, kFaceBoth = 3 };

/// Whether an option's value may name one opening ("K=VALUE" on the CLI,
/// `{K: value}` in JS; K numbers the openings as the analysis lists them).
enum class PerOpening : uint8_t {
  kNo,        ///< a plain value
  kOptional,  ///< a plain value for all openings, or K=VALUE for one
  kRequired,  ///< always K=VALUE
};

/// One value of an option, as parsed from text (CLI) or converted from a JS
/// value: the field the type uses, and the opening it names (1-based; 0:
/// all openings, or not per-opening).
struct OptionValue {
  double number = 0;
  bool flag = false;
  std::string text;
  std::vector<double> numbers;
  int opening = 0;
};

/// One option: what a user gives, and where it goes in the job's options.
///
/// Names: a row gives one name, `key`, the JS API's camelCase key. The
/// others are derived from it by option_table() (option_names.h): `id`, the
/// snake_case id used in core messages ("{id}"), reports and provenance;
/// `cli`, the CLI flag without dashes (kebab-case; for a repeatable option
/// whose key is a plural, the singular: one value a flag; for a flag that
/// defaults to on, "no-" and the key: the flag that turns it off); `js`,
/// the key itself where JS takes the option (else empty). The page's
/// control for the option has the id kebab-case(key), which is also its key
/// in a shared link. `cli_aliases` are older CLI names still accepted.
///
/// Values: `set` applies a checked value to the job's options (false: the
/// value is not what the option needs); `read` gives the value in a job's
/// options as option_value_text() writes it ("" = unset, decided later).
/// The default shown to users is read(MeshJobOptions{}): the struct's
/// initialisers are the one source of defaults. `default_text` is given
/// only for an option with no field of its own (CLI paths).
struct OptionSpec {
  std::string_view key;
  OptionType type = OptionType::kNumber;
  uint8_t commands = kCommandMesh;
  uint8_t faces = kFaceBoth;
  /// Help section: "input", "size", "layers", "volume", "output", "advanced",
  /// "phantom".
  std::string_view group;
  std::string_view metavar;  ///< the value's placeholder in help ("H", "N")
  /// Range of a number or integer; exclusive bounds when the flags say so.
  double min = -1e308, max = 1e308;
  bool min_exclusive = false, max_exclusive = false;
  std::span<const std::string_view> choices;  ///< kChoice
  int list_size = 0;                          ///< kNumbers
  bool default_on = false;                    ///< kFlag: its default
  /// The default as shown to users ("20", "0.2", "lscm"; empty: none/unset).
  /// Derived from `read` (or `read_phantom`) when the row has one.
  std::string_view default_text;
  /// What a length is measured in: "length" (the model's unit), "fraction
  /// of R" (the local vessel radius), "degrees", or empty.
  std::string_view unit;
  /// What a valid value is, completing "<option> needs ...".
  std::string_view needs;
  std::string_view doc;  ///< one line
  /// A flag that defaults to on: what its CLI flag (which turns it off) does.
  std::string_view off_doc;
  bool repeatable = false;
  PerOpening per_opening = PerOpening::kNo;
  std::span<const std::string_view> cli_aliases;
  /// An info or mesh option: applies a checked value; false when the value
  /// is not what the option needs (apply_option says `needs`).
  bool (*set)(MeshJobOptions&, const OptionValue&) = nullptr;
  /// The value's text in `options`; "" when unset.
  std::string (*read)(const MeshJobOptions& options) = nullptr;
  /// A phantom option: the same two.
  bool (*set_phantom)(PhantomOptions&, const OptionValue&) = nullptr;
  std::string (*read_phantom)(const PhantomOptions& options) = nullptr;
  /// Derived names (above), filled by option_table().
  std::string_view id, cli, js;
};

/// Whether `name` may name a group (an opening): 1-64 letters, digits, `_`
/// and `-`, starting with a letter (so it is also an OpenFOAM patch name and
/// a file name).
bool valid_group_name(std::string_view name);

/// Every option, in help order, with its derived names and defaults.
std::span<const OptionSpec> option_table();

/// The option with this id, or nullptr.
const OptionSpec* find_option(std::string_view id);
/// The option with this CLI name (without dashes; or one of its older
/// names) taken by `command`, or nullptr.
const OptionSpec* find_cli_option(std::string_view cli, OptionCommand command);
/// The option with this JS key taken by `command`, or nullptr.
const OptionSpec* find_js_option(std::string_view js, OptionCommand command);

/// Parses the CLI text of one value of `spec` ("K=VALUE" for per-opening
/// options); checks type and range. Flags take no text: use a value with
/// `flag` = !spec.default_on.
Result<OptionValue> parse_option_text(const OptionSpec& spec, std::string_view text);

/// Checks a value's type-independent constraints (range, integer, choice,
/// list size, opening number >= 1) against `spec`. Errors are kBadOption.
Status check_option_value(const OptionSpec& spec, const OptionValue& value);

/// Applies a checked value of an info or mesh option (commands kCommandInfo
/// or kCommandMesh) to `options`. Options of other faces only (CLI paths)
/// are ignored. Errors are kBadOption.
Status apply_option(MeshJobOptions& options, const OptionSpec& spec, const OptionValue& value);

/// Applies a checked value of a phantom option.
Status apply_option(PhantomOptions& options, const OptionSpec& spec, const OptionValue& value);

/// Parses `text` for option `id` and applies it (tests, benchmarks, tools):
/// parse_option_text then apply_option. Unknown ids are kInternal errors.
Status set_option_text(MeshJobOptions& options, std::string_view id, std::string_view text);

/// The canonical text of a value ("0.2", "true", "2=aorta", "1,0,0,...").
std::string option_value_text(const OptionSpec& spec, const OptionValue& value);

/// The options a job was given, as provenance: "id=value" separated by
/// spaces, in the order given, the same text whatever the interface
/// (options of one interface only, such as output paths, are left out).
std::string options_provenance(std::span<const std::pair<const OptionSpec*, OptionValue>> values);

/// `message` with every "{id}" of a known option replaced by its name on
/// `face` ("--size" on the CLI, "size" in JS).
std::string phrase_options(std::string_view message, OptionFace face);

/// An error's message in the words of `face`: a kBadOption error becomes
/// "<option name> <message>"; "{id}" references are phrased.
std::string phrase_error(const Status& status, OptionFace face);

/// The id of the page's control for an option, which is also its key in a
/// shared link: kebab-case of its key ("coreSize": "core-size").
std::string control_id(const OptionSpec& spec);

/// The table as JSON (an array of objects with the fields of OptionSpec:
/// id, cli, js, control (control_id; "" for an option JS does not take),
/// cliAliases, type, commands [names], faces [names], group, metavar, min,
/// max, minExclusive, maxExclusive, choices, listSize, defaultOn, default,
/// unit, needs, doc, offDoc, repeatable, perOpening), for the JS side, its type
/// declarations and the docs/options.md check.
std::string option_table_json();

}  // namespace vm
