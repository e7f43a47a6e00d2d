#include "core/io/zip_writer.h"

#include <gtest/gtest.h>
#include <zlib.h>

#include <cstring>
#include <random>

namespace vm {
namespace {

uint32_t u32(const std::string& s, size_t at) {
  const auto* p = reinterpret_cast<const unsigned char*>(s.data() + at);
  return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
}
uint16_t u16(const std::string& s, size_t at) {
  const auto* p = reinterpret_cast<const unsigned char*>(s.data() + at);
  return uint16_t(p[0] | p[1] << 8);
}

std::string inflate_raw(const std::string& packed, size_t size) {
  std::string out(size, '\0');
  z_stream zs{};
  EXPECT_EQ(inflateInit2(&zs, -15), Z_OK);
  zs.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(packed.data()));
  zs.avail_in = uInt(packed.size());
  zs.next_out = reinterpret_cast<Bytef*>(out.data());
  zs.avail_out = uInt(out.size());
  EXPECT_EQ(inflate(&zs, Z_FINISH), Z_STREAM_END);
  EXPECT_EQ(zs.total_out, size);
  inflateEnd(&zs);
  return out;
}

struct ReadEntry {
  std::string name, bytes;
  uint16_t method = 0, flags = 0, date = 0, time = 0;
};

/// Reads an archive the way an unzip tool does: from the end record to the
/// central directory, from there to each local header and its data.
std::vector<ReadEntry> read_zip(const std::string& zip) {
  std::vector<ReadEntry> out;
  EXPECT_GE(zip.size(), 22u);
  const size_t end = zip.size() - 22;  // no archive comment
  EXPECT_EQ(u32(zip, end), 0x06054b50u);
  const uint16_t count = u16(zip, end + 10);
  EXPECT_EQ(u16(zip, end + 8), count);
  const uint32_t dir_size = u32(zip, end + 12), dir_at = u32(zip, end + 16);
  EXPECT_EQ(size_t(dir_at) + dir_size, end);
  size_t p = dir_at;
  for (uint16_t i = 0; i < count; ++i) {
    EXPECT_EQ(u32(zip, p), 0x02014b50u);
    ReadEntry e;
    e.flags = u16(zip, p + 8);
    e.method = u16(zip, p + 10);
    e.time = u16(zip, p + 12);
    e.date = u16(zip, p + 14);
    const uint32_t crc = u32(zip, p + 16), packed = u32(zip, p + 20), size = u32(zip, p + 24);
    const uint16_t name_len = u16(zip, p + 28), extra = u16(zip, p + 30),
                   comment = u16(zip, p + 32);
    const uint32_t local = u32(zip, p + 42);
    e.name = zip.substr(p + 46, name_len);
    p += 46 + name_len + extra + comment;
    // The local header repeats the fields.
    EXPECT_EQ(u32(zip, local), 0x04034b50u);
    EXPECT_EQ(u16(zip, local + 6), e.flags);
    EXPECT_EQ(u16(zip, local + 8), e.method);
    EXPECT_EQ(u32(zip, local + 14), crc);
    EXPECT_EQ(u32(zip, local + 18), packed);
    EXPECT_EQ(u32(zip, local + 22), size);
    EXPECT_EQ(zip.substr(local + 30, u16(zip, local + 26)), e.name);
    const std::string data = zip.substr(local + 30 + name_len + u16(zip, local + 28), packed);
    e.bytes = e.method == 8 ? inflate_raw(data, size) : data;
    EXPECT_EQ(e.bytes.size(), size);
    EXPECT_EQ(crc32(0, reinterpret_cast<const Bytef*>(e.bytes.data()), uInt(e.bytes.size())), crc)
        << e.name;
    out.push_back(std::move(e));
  }
  EXPECT_EQ(p, end);
  return out;
}

std::vector<OutputFile> sample_files() {
  std::string text;
  for (int i = 0; i < 2000; ++i) text += "line " + std::to_string(i % 17) + " of a VTU\n";
  std::string noise(5000, '\0');
  std::mt19937 rng(3);
  for (char& c : noise) c = char(rng() & 0xff);
  return {{"mesh-complete.mesh.vtu", text},
          {"mesh-surfaces/wall.vtp", noise},
          {"mesh-surfaces/empty.vtp", ""},
          {"names.json", "{\"caf\xc3\xa9\": 1}"}};
}

TEST(ZipWriter, EntriesInflateToTheFilesWithTheirCrcs) {
  const auto files = sample_files();
  auto r = write_zip(files);
  ASSERT_TRUE(r.ok()) << r.message();
  auto entries = read_zip(r.value());
  ASSERT_EQ(entries.size(), files.size());
  for (size_t i = 0; i < files.size(); ++i) {
    SCOPED_TRACE(files[i].path);
    EXPECT_EQ(entries[i].name, files[i].path);
    EXPECT_EQ(entries[i].bytes, files[i].bytes);
    EXPECT_EQ(entries[i].flags, 0x0800);  // UTF-8 names
    EXPECT_EQ(entries[i].date, (1 << 5) | 1);
    EXPECT_EQ(entries[i].time, 0);
  }
  EXPECT_EQ(entries[0].method, 8);  // text deflates
  EXPECT_EQ(entries[1].method, 0);  // noise is stored
  EXPECT_EQ(entries[2].method, 0);  // empty
  EXPECT_LT(r.value().size(), files[0].bytes.size());
}

TEST(ZipWriter, SameFilesSameBytes) {
  auto a = write_zip(sample_files()), b = write_zip(sample_files());
  ASSERT_TRUE(a.ok() && b.ok());
  EXPECT_EQ(a.value(), b.value());
}

TEST(ZipWriter, EmptyArchive) {
  auto r = write_zip({});
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r.value().size(), 22u);
  EXPECT_TRUE(read_zip(r.value()).empty());
}

TEST(ZipWriter, RefusesUnsafeOrRepeatedPaths) {
  for (const char* bad : {"", "/etc/x", "a/../b", "..", "a//b", "a\\b", "./a", "dir/"}) {
    auto r = write_zip({{bad, "x"}});
    EXPECT_FALSE(r.ok()) << bad;
  }
  auto r = write_zip({{"a.vtp", "1"}, {"a.vtp", "2"}});
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.message().find("twice"), std::string::npos);
}

}  // namespace
}  // namespace vm
