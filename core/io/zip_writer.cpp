// ZIP writer: per file a local header and the (deflated or stored) data,
// then one central directory record per file and the end-of-central-
// directory record (PKWARE APPNOTE.TXT sections 4.3.7, 4.3.12, 4.3.16).
// Compression and CRC-32 by zlib.
#include "core/io/zip_writer.h"

#include <zlib.h>

#include <cstdint>
#include <set>
#include <string_view>

namespace vm {
namespace {

constexpr uint32_t kLocalHeader = 0x04034b50;
constexpr uint32_t kCentralHeader = 0x02014b50;
constexpr uint32_t kEndRecord = 0x06054b50;
constexpr uint16_t kVersion20 = 20;     // 2.0: deflate, folders
constexpr uint16_t kUtf8Flag = 0x0800;  // general purpose bit 11: UTF-8 names
constexpr uint16_t kStored = 0, kDeflated = 8;
constexpr uint16_t kDosDate1980 = (0 << 9) | (1 << 5) | 1;  // 1980-01-01
constexpr uint16_t kDosTime0 = 0;
// Sizes and offsets are 32-bit without ZIP64, and 0xffffffff means "see the
// ZIP64 record" to readers: everything must stay below it.
constexpr uint64_t kLimit = 0xffffffffULL;
constexpr size_t kMaxEntries = 0xfffe;

void put16(std::string& out, uint16_t v) {
  out.push_back(char(v & 0xff));
  out.push_back(char(v >> 8));
}

void put32(std::string& out, uint32_t v) {
  for (int k = 0; k < 4; ++k) out.push_back(char((v >> (8 * k)) & 0xff));
}

uint32_t crc_of(std::string_view data) {
  uLong crc = crc32(0L, Z_NULL, 0);
  const auto* p = reinterpret_cast<const Bytef*>(data.data());
  size_t left = data.size();
  while (left > 0) {  // crc32 takes a uInt length
    const uInt n = left > (1u << 30) ? (1u << 30) : uInt(left);
    crc = crc32(crc, p, n);
    p += n;
    left -= n;
  }
  return uint32_t(crc);
}

/// Raw DEFLATE (no zlib header: windowBits -15) of `data`, which is below
/// 4 GiB. Empty when zlib fails (the entry is then stored).
std::string deflate_raw(std::string_view data) {
  z_stream zs{};
  if (deflateInit2(&zs, 6, Z_DEFLATED, -15, 8, Z_DEFAULT_STRATEGY) != Z_OK) return {};
  std::string out(deflateBound(&zs, uLong(data.size())), '\0');
  zs.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(data.data()));
  zs.avail_in = uInt(data.size());
  zs.next_out = reinterpret_cast<Bytef*>(out.data());
  zs.avail_out = uInt(out.size());
  const int rc = deflate(&zs, Z_FINISH);
  const size_t written = size_t(zs.total_out);
  deflateEnd(&zs);
  if (rc != Z_STREAM_END) return {};
  out.resize(written);
  return out;
}

Status check_path(const std::string& path) {
  auto bad = [&](const char* why) {
    return Status::Error("cannot put \"" + path + "\" in a ZIP archive: " + why);
  };
  if (path.empty()) return bad("empty path");
  if (path.size() > 0xffff) return bad("path longer than 65535 bytes");
  if (path.front() == '/') return bad("absolute path");
  if (path.find('\\') != std::string::npos) return bad("backslash in the path");
  size_t begin = 0;
  while (begin <= path.size()) {
    size_t end = path.find('/', begin);
    if (end == std::string::npos) end = path.size();
    const std::string_view part(path.data() + begin, end - begin);
    if (part.empty() || part == "." || part == "..")
      return bad("empty, \".\" or \"..\" path component");
    begin = end + 1;
  }
  return Status::Ok();
}

struct Entry {
  uint32_t crc = 0, compressed = 0, size = 0, offset = 0;
  uint16_t method = kStored;
};

// The fields local and central headers share, from "version needed" to the
// name length (APPNOTE 4.3.7 / 4.3.12 after "version made by").
void put_common(std::string& out, const Entry& e, const std::string& path) {
  put16(out, kVersion20);
  put16(out, kUtf8Flag);
  put16(out, e.method);
  put16(out, kDosTime0);
  put16(out, kDosDate1980);
  put32(out, e.crc);
  put32(out, e.compressed);
  put32(out, e.size);
  put16(out, uint16_t(path.size()));
}

}  // namespace

Result<std::string> write_zip(const std::vector<OutputFile>& files) {
  using R = Result<std::string>;
  if (files.size() > kMaxEntries)
    return R::Error("too many files for a ZIP archive without ZIP64: " +
                    std::to_string(files.size()));
  std::set<std::string_view> seen;
  for (const OutputFile& f : files) {
    Status s = check_path(f.path);
    if (!s.ok()) return s;
    if (!seen.insert(f.path).second) return R::Error("file \"" + f.path + "\" given twice");
    if (uint64_t(f.bytes.size()) >= kLimit)
      return R::Error("file \"" + f.path + "\" is too large for a ZIP archive (4 GiB or more)");
  }

  std::string out;
  std::vector<Entry> entries(files.size());
  for (size_t i = 0; i < files.size(); ++i) {
    const OutputFile& f = files[i];
    Entry& e = entries[i];
    e.crc = crc_of(f.bytes);
    e.size = uint32_t(f.bytes.size());
    std::string packed = deflate_raw(f.bytes);
    const bool deflated = !packed.empty() && packed.size() < f.bytes.size();
    e.method = deflated ? kDeflated : kStored;
    const std::string_view data = deflated ? std::string_view(packed) : std::string_view(f.bytes);
    e.compressed = uint32_t(data.size());
    const uint64_t end = uint64_t(out.size()) + 30 + f.path.size() + data.size();
    if (end >= kLimit) return R::Error("the ZIP archive would reach 4 GiB (no ZIP64)");
    e.offset = uint32_t(out.size());
    put32(out, kLocalHeader);
    put_common(out, e, f.path);
    put16(out, 0);  // extra field length
    out += f.path;
    out += data;
  }

  const uint64_t directory_offset = out.size();
  for (size_t i = 0; i < files.size(); ++i) {
    const Entry& e = entries[i];
    put32(out, kCentralHeader);
    put16(out, kVersion20);  // made by: MS-DOS host (attributes unused), 2.0
    put_common(out, e, files[i].path);
    put16(out, 0);  // extra field length
    put16(out, 0);  // comment length
    put16(out, 0);  // disk number start
    put16(out, 0);  // internal attributes
    put32(out, 0);  // external attributes
    put32(out, e.offset);
    out += files[i].path;
  }
  const uint64_t directory_size = out.size() - directory_offset;
  if (uint64_t(out.size()) + 22 >= kLimit)
    return R::Error("the ZIP archive would reach 4 GiB (no ZIP64)");
  put32(out, kEndRecord);
  put16(out, 0);  // this disk
  put16(out, 0);  // disk of the central directory
  put16(out, uint16_t(files.size()));
  put16(out, uint16_t(files.size()));
  put32(out, uint32_t(directory_size));
  put32(out, uint32_t(directory_offset));
  put16(out, 0);  // comment length
  return out;
}

}  // namespace vm
