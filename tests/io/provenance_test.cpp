#include "core/io/provenance.h"

#include <gtest/gtest.h>

#include <string_view>

namespace vm {
namespace {

std::span<const uint8_t> bytes_of(std::string_view s) {
  return {reinterpret_cast<const uint8_t*>(s.data()), s.size()};
}

TEST(Provenance, InputHashIsXxh128Canonical) {
  // Reference values: `printf ... | xxhsum -H2` (xxHash 0.8.1).
  EXPECT_EQ(input_hash({}), "xxh128:99aa06d3014798d86001c324468d497f");
  EXPECT_EQ(input_hash(bytes_of("abc")), "xxh128:06b05ab6733a618578af5f94892f3950");
  EXPECT_EQ(input_hash(bytes_of("vesselmesh")), "xxh128:36b62fef90ed1e9289259b5ed713689f");
}

TEST(Provenance, InputHashIsStableAndTellsInputsApart) {
  std::string big(100000, 'a');
  const std::string h = input_hash(bytes_of(big));
  EXPECT_EQ(h.size(), 7u + 32u);
  EXPECT_EQ(h.rfind("xxh128:", 0), 0u);
  EXPECT_EQ(input_hash(bytes_of(big)), h);
  big[51234] = 'b';
  EXPECT_NE(input_hash(bytes_of(big)), h);
  big[51234] = 'a';
  big.push_back('\0');
  EXPECT_NE(input_hash(bytes_of(big)), h);
}

TEST(Provenance, TextIsOneLineWithoutDoubleDashes) {
  EXPECT_EQ(provenance_text("0.1.0", "xxh128:00", "--layers 4 --prisms"),
            "vesselmesh 0.1.0; input xxh128:00; options: -layers 4 -prisms");
  EXPECT_EQ(provenance_text("0.1.0", "xxh128:00", ""), "vesselmesh 0.1.0; input xxh128:00");
  const std::string t = provenance_text("0.1.0", "xxh128:00", "a\nb\r\tc ---- d");
  EXPECT_EQ(t, "vesselmesh 0.1.0; input xxh128:00; options: a b  c - d");
  EXPECT_EQ(t.find('\n'), std::string::npos);
}

}  // namespace
}  // namespace vm
