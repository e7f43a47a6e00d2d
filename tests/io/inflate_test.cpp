#include "core/io/inflate.h"

#include <gtest/gtest.h>
#include <zlib.h>

#include <string>

#include "tests/io/surface_writers.h"

namespace vm {
namespace {

using testing::Bytes;

Bytes sample(size_t n) {
  Bytes b(n);
  for (size_t i = 0; i < n; ++i) b[i] = uint8_t((i * i) >> 3);
  return b;
}

TEST(Inflate, ZlibRoundTrip) {
  Bytes data = sample(300000);
  auto r = inflate_zlib(testing::zlib_compress(data), 1 << 20);
  ASSERT_TRUE(r.ok()) << r.message();
  EXPECT_EQ(r.value(), data);
}

TEST(Inflate, GzipSeveralMembers) {
  Bytes a = sample(1000), b = sample(70000);
  Bytes gz = testing::gzip(a);
  Bytes gb = testing::gzip(b);
  gz.insert(gz.end(), gb.begin(), gb.end());
  std::vector<std::string> warnings;
  auto r = inflate_gzip(gz, 1 << 20, &warnings);
  ASSERT_TRUE(r.ok()) << r.message();
  Bytes want = a;
  want.insert(want.end(), b.begin(), b.end());
  EXPECT_EQ(r.value(), want);
  EXPECT_TRUE(warnings.empty());
  // Zero padding after the members is ignored with a note.
  gz.insert(gz.end(), 10, 0);
  r = inflate_gzip(gz, 1 << 20, &warnings);
  ASSERT_TRUE(r.ok()) << r.message();
  EXPECT_EQ(r.value(), want);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_EQ(warnings[0], "10 bytes after the end of the gzip data were ignored");
}

TEST(Inflate, EmptyPayload) {
  auto r = inflate_gzip(testing::gzip({}), 100);
  ASSERT_TRUE(r.ok()) << r.message();
  EXPECT_TRUE(r.value().empty());
}

// 100 MB of zeros compress to about 100 KB: with a 10 MB limit the output
// must be refused, not allocated.
TEST(Inflate, GzipBombIsRefused) {
  const Bytes gz = testing::gzip_zeros(size_t(100) << 20);
  ASSERT_LT(gz.size(), 200000u);
  const size_t limit = 10 << 20;
  auto r = inflate_gzip(gz, limit);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.message().find("decompressed data exceeds the limit of 10485760 bytes "
                             "(compression ratio over "),
            std::string::npos)
      << r.message();
  EXPECT_NE(r.message().find("): refused"), std::string::npos);
  // With room for it, the same data decompresses.
  r = inflate_gzip(gz, 100 << 20);
  ASSERT_TRUE(r.ok()) << r.message();
  EXPECT_EQ(r.value().size(), size_t(100) << 20);
}

TEST(Inflate, GzipPrefix) {
  const Bytes data = sample(300000);
  const Bytes gz = testing::gzip(data);
  auto r = inflate_gzip_prefix(gz, 1000);
  ASSERT_TRUE(r.ok()) << r.message();
  EXPECT_EQ(r.value(), Bytes(data.begin(), data.begin() + 1000));
  // Content shorter than asked for: all of it; nothing asked for: nothing.
  r = inflate_gzip_prefix(testing::gzip(sample(500)), 1000);
  ASSERT_TRUE(r.ok()) << r.message();
  EXPECT_EQ(r.value(), sample(500));
  r = inflate_gzip_prefix(gz, 0);
  ASSERT_TRUE(r.ok()) << r.message();
  EXPECT_TRUE(r.value().empty());
  // Members are read in order.
  Bytes two = testing::gzip(sample(10));
  const Bytes second = testing::gzip(data);
  two.insert(two.end(), second.begin(), second.end());
  r = inflate_gzip_prefix(two, 100);
  ASSERT_TRUE(r.ok()) << r.message();
  Bytes want = sample(10);
  want.insert(want.end(), data.begin(), data.begin() + 90);
  EXPECT_EQ(r.value(), want);
  // Nothing past the prefix is read: a truncated stream, or one with a bad
  // CRC, still gives its start, and a bomb gives its start at once.
  r = inflate_gzip_prefix(Bytes(gz.begin(), gz.begin() + long(gz.size() / 2)), 1000);
  ASSERT_TRUE(r.ok()) << r.message();
  EXPECT_EQ(r.value(), Bytes(data.begin(), data.begin() + 1000));
  Bytes bad = gz;
  bad[bad.size() - 5] ^= 0xff;
  EXPECT_TRUE(inflate_gzip_prefix(bad, 1000).ok());
  r = inflate_gzip_prefix(testing::gzip_zeros(size_t(16) << 20), 65536);
  ASSERT_TRUE(r.ok()) << r.message();
  EXPECT_EQ(r.value(), Bytes(65536, 0));
  // Errors within the prefix are inflate_gzip's.
  bad = gz;
  bad[3] = 0xe0;  // reserved flag bits
  r = inflate_gzip_prefix(bad, 1000);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.message(), inflate_gzip(bad, 1 << 20).message());
}

TEST(Inflate, TruncatedAndCorruptStreams) {
  Bytes gz = testing::gzip(sample(50000));
  auto r = inflate_gzip(Bytes(gz.begin(), gz.begin() + long(gz.size() / 2)), 1 << 20);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.message().find("gzip data ends before the end of the compressed stream"),
            std::string::npos)
      << r.message();
  Bytes bad = gz;
  bad[bad.size() - 5] ^= 0xff;  // CRC
  r = inflate_gzip(bad, 1 << 20);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.message().find("bad gzip data: incorrect data check"), std::string::npos)
      << r.message();
  Bytes z = testing::zlib_compress(sample(1000));
  z[0] = 0x12;
  r = inflate_zlib(z, 1 << 20);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.message().find("bad zlib data: incorrect header check"), std::string::npos)
      << r.message();
}

TEST(Inflate, ExactSizeBlocks) {
  Bytes data = sample(5000);
  Bytes z = testing::zlib_compress(data);
  Bytes out(5000);
  ASSERT_TRUE(inflate_zlib_exact(z, out).ok());
  EXPECT_EQ(out, data);
  Bytes small(4000);
  Status st = inflate_zlib_exact(z, small);
  ASSERT_FALSE(st.ok());
  EXPECT_NE(st.message().find("more than the 4000 bytes"), std::string::npos) << st.message();
  Bytes big(6000);
  st = inflate_zlib_exact(z, big);
  ASSERT_FALSE(st.ok());
  EXPECT_NE(st.message().find("decompresses to 5000 bytes but its header announces 6000"),
            std::string::npos)
      << st.message();
  st = inflate_zlib_exact(Bytes(z.begin(), z.begin() + 20), out);
  ASSERT_FALSE(st.ok());
  EXPECT_NE(st.message().find("ends before the end"), std::string::npos) << st.message();
}

}  // namespace
}  // namespace vm
