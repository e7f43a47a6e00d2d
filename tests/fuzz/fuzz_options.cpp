// libFuzzer target: the option table's parsing, as the CLI and the JS API
// use it (the JS wrapper hands the core the same texts). The first byte
// picks an option of the table, the rest is its text. Parsing returns a
// value or an error with a message; a parsed value passes its own checks,
// applies without crashing, and prints as a text that parses back to the
// same text.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

#include "core/pipeline/option_table.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  const auto& table = vm::option_table();
  const vm::OptionSpec& spec = table[data[0] % table.size()];
  const std::string_view text(reinterpret_cast<const char*>(data + 1), size - 1);
  vm::Result<vm::OptionValue> v = vm::parse_option_text(spec, text);
  if (!v.ok()) {
    if (v.message().empty()) std::abort();
    (void)vm::phrase_error(v.status(), vm::kFaceCli);
    return 0;
  }
  if (!vm::check_option_value(spec, v.value()).ok()) std::abort();
  vm::MeshJobOptions mesh;
  vm::PhantomOptions phantom;
  (void)vm::apply_option(mesh, spec, v.value());
  (void)vm::apply_option(phantom, spec, v.value());
  const std::string canonical = vm::option_value_text(spec, v.value());
  if (spec.type == vm::OptionType::kFlag) return 0;
  vm::Result<vm::OptionValue> again = vm::parse_option_text(spec, canonical);
  if (!again.ok() || vm::option_value_text(spec, again.value()) != canonical) {
    std::fprintf(stderr, "option %s: '%s' does not read back\n", std::string(spec.id).c_str(),
                 canonical.c_str());
    std::abort();
  }
  return 0;
}
