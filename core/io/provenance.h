// Provenance of an output: a hash of the input's bytes and a one-line text
// (version, input hash, options) written into every output file, so that a
// mesh can be traced back to what made it.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>

namespace vm {

/// "xxh128:" followed by the 32 lowercase hex digits of XXH3_128bits(bytes)
/// in xxHash's canonical (big-endian) form, the digits `xxh128sum` prints.
std::string input_hash(std::span<const uint8_t> bytes);

/// "vesselmesh <version>; input <input_hash>; options: <options>" on one
/// line: control characters (newlines, tabs) become spaces and runs of '-'
/// become a single '-' (so "--layers 4" reads "-layers 4"), which keeps the
/// text valid inside an XML comment and one line in any header. `options`
/// is free text (e.g. the command line's options); when empty the
/// "; options: ..." part is omitted.
std::string provenance_text(std::string_view version, std::string_view input_hash,
                            std::string_view options);

}  // namespace vm
