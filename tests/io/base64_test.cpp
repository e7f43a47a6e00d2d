#include "core/io/base64.h"

#include <gtest/gtest.h>

#include <string>

#include "tests/io/surface_writers.h"

namespace vm {
namespace {

std::string decoded(const std::string& text) {
  auto r = base64_decode(text);
  EXPECT_TRUE(r.ok()) << r.message();
  return r.ok() ? std::string(r.value().begin(), r.value().end()) : std::string();
}

TEST(Base64, DecodesRfc4648Vectors) {
  EXPECT_EQ(decoded(""), "");
  EXPECT_EQ(decoded("Zg=="), "f");
  EXPECT_EQ(decoded("Zm8="), "fo");
  EXPECT_EQ(decoded("Zm9v"), "foo");
  EXPECT_EQ(decoded("Zm9vYg=="), "foob");
  EXPECT_EQ(decoded("Zm9vYmE="), "fooba");
  EXPECT_EQ(decoded("Zm9vYmFy"), "foobar");
}

TEST(Base64, RoundTripsEveryByteValue) {
  testing::Bytes all(256 * 3 + 1);
  for (size_t i = 0; i < all.size(); ++i) all[i] = uint8_t(i * 7 + 3);
  auto r = base64_decode(testing::base64(all));
  ASSERT_TRUE(r.ok()) << r.message();
  EXPECT_EQ(r.value(), all);
}

TEST(Base64, SkipsWhitespaceAndReadsConcatenatedPaddedStrings) {
  EXPECT_EQ(decoded("  Zm9v\nYmFy \r\n"), "foobar");
  // Two independently padded strings (as VTK writes a compressed header and
  // its data): the bytes of both, in order.
  EXPECT_EQ(decoded("Zg==Zm8="), "ffo");
  EXPECT_EQ(decoded("Zm8=Zm9vYg=="), "fofoob");
}

/// The message of a decoding that must fail.
std::string error_of(const std::string& text) {
  auto r = base64_decode(text);
  EXPECT_FALSE(r.ok()) << text;
  return r.ok() ? std::string() : r.message();
}

TEST(Base64, BadCharacterGivesItsPosition) {
  EXPECT_EQ(error_of("Zm9vYm#y"), "bad base64 character '#' at position 6");
  EXPECT_EQ(error_of("Zm9v\x01"), "bad base64 character byte 0x01 at position 4");
}

TEST(Base64, StrictPaddingAndGroups) {
  EXPECT_EQ(error_of("Z==="), "misplaced base64 padding '=' at position 1");
  EXPECT_EQ(error_of("Zg=a"), "base64 character 'a' after padding '=' at position 3");
  EXPECT_NE(error_of("Zm9vYg").find("ends inside a 4-character group"), std::string::npos);
}

TEST(Base64, StreamReadsPiecesAndRefusesMoreThanTheTextHolds) {
  std::string text = "xx Zm9vYmFy";
  Base64Stream s(text, 3, text.size(), 1000);
  std::vector<uint8_t> out;
  ASSERT_TRUE(s.read(2, out).ok());
  ASSERT_TRUE(s.read(3, out).ok());
  EXPECT_EQ(std::string(out.begin(), out.end()), "fooba");
  EXPECT_EQ(s.max_remaining(), 1u);
  Status st = s.read(1000000000, out);
  ASSERT_FALSE(st.ok());
  EXPECT_NE(st.message().find("ends at position 1011"), std::string::npos) << st.message();
  EXPECT_EQ(out.size(), 5u);
}

}  // namespace
}  // namespace vm
