// Input hash by xxHash's XXH3 128-bit variant (Debian libxxhash-dev, used
// header-only: the header is copied into the build tree by CMakeLists.txt).
#include "core/io/provenance.h"

#define XXH_INLINE_ALL
#include "xxhash.h"

namespace vm {
namespace {

// Appends `text` with control characters as spaces and '-' runs as one '-'.
void append_one_line(std::string& out, std::string_view text) {
  for (char c : text) {
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = ' ';
    if (c == '-' && !out.empty() && out.back() == '-') continue;
    out.push_back(c);
  }
}

}  // namespace

std::string input_hash(std::span<const uint8_t> bytes) {
  const XXH128_hash_t h = XXH3_128bits(bytes.data(), bytes.size());
  XXH128_canonical_t canonical;
  XXH128_canonicalFromHash(&canonical, h);
  static constexpr char kHex[] = "0123456789abcdef";
  std::string out = "xxh128:";
  for (unsigned char b : canonical.digest) {
    out.push_back(kHex[b >> 4]);
    out.push_back(kHex[b & 15]);
  }
  return out;
}

std::string provenance_text(std::string_view version, std::string_view input_hash,
                            std::string_view options) {
  std::string out;
  append_one_line(out, "vesselmesh ");
  append_one_line(out, version);
  append_one_line(out, "; input ");
  append_one_line(out, input_hash);
  if (!options.empty()) {
    append_one_line(out, "; options: ");
    append_one_line(out, options);
  }
  return out;
}

}  // namespace vm
