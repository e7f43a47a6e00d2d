// Decompression through zlib's inflate(): windowBits 15 reads the zlib
// format, 16 + 15 the gzip format (RFC 1950 / 1952). The output buffer grows
// by doubling, never past the caller's limit + 1 byte (the extra byte
// detects a stream that would go on), or past the prefix's length when only a
// prefix is asked for.
#include "core/io/inflate.h"

#include <zlib.h>

#include <algorithm>
#include <cstdio>
#include <limits>

namespace vm {
namespace {

constexpr size_t kMaxChunk = size_t(1) << 30;  // zlib's avail_in/out are 32-bit

std::string zlib_error(const z_stream& z, int code, const char* what, size_t consumed) {
  std::string reason = z.msg ? z.msg : (code == Z_MEM_ERROR ? "out of memory" : "corrupt data");
  return std::string("bad ") + what + " data: " + reason + " (at compressed byte " +
         std::to_string(consumed) + ")";
}

std::string limit_error(size_t limit, size_t consumed) {
  size_t ratio = limit / std::max<size_t>(consumed, 1);
  return "decompressed data exceeds the limit of " + std::to_string(limit) +
         " bytes (compression ratio over " + std::to_string(ratio) + "): refused";
}

// Runs inflate over `in` with the given windowBits. For gzip, members are
// read until the input ends or does not start another member. With `prefix`,
// inflate stops once max_output bytes are out and returns them (no limit
// error).
Result<std::vector<uint8_t>> run_inflate(std::span<const uint8_t> in, size_t max_output, bool gzip,
                                         std::vector<std::string>* warnings, bool prefix = false) {
  const char* what = gzip ? "gzip" : "zlib";
  z_stream z{};
  if (inflateInit2(&z, gzip ? 16 + MAX_WBITS : MAX_WBITS) != Z_OK) {
    return Result<std::vector<uint8_t>>::Error(std::string("cannot start ") + what +
                                               " decompression (out of memory)");
  }
  struct Guard {
    z_stream* z;
    ~Guard() { inflateEnd(z); }
  } guard{&z};
  const size_t cap_limit =
      prefix || max_output == std::numeric_limits<size_t>::max() ? max_output : max_output + 1;
  std::vector<uint8_t> out;
  out.resize(std::min(cap_limit, std::max<size_t>(size_t(1) << 16, 4 * in.size())));
  size_t in_pos = 0, out_pos = 0;
  while (true) {
    if (out_pos == out.size()) {
      if (prefix && out.size() >= cap_limit) break;
      if (out.size() >= cap_limit)
        return Result<std::vector<uint8_t>>::Error(limit_error(max_output, in_pos));
      out.resize(std::min(cap_limit, out.size() > cap_limit / 2 ? cap_limit : 2 * out.size()));
    }
    size_t in_chunk = std::min(in.size() - in_pos, kMaxChunk);
    size_t out_chunk = std::min(out.size() - out_pos, kMaxChunk);
    z.next_in = const_cast<Bytef*>(in.data() + in_pos);
    z.avail_in = uInt(in_chunk);
    z.next_out = out.data() + out_pos;
    z.avail_out = uInt(out_chunk);
    int code = inflate(&z, Z_NO_FLUSH);
    in_pos += in_chunk - z.avail_in;
    out_pos += out_chunk - z.avail_out;
    if (out_pos > max_output) {
      return Result<std::vector<uint8_t>>::Error(limit_error(max_output, in_pos));
    }
    if (code == Z_STREAM_END) {
      if (!gzip) break;
      // Another gzip member follows?
      if (in.size() - in_pos >= 2 && in[in_pos] == 0x1f && in[in_pos + 1] == 0x8b) {
        inflateReset(&z);
        continue;
      }
      if (in_pos < in.size() && warnings) {
        warnings->push_back(std::to_string(in.size() - in_pos) +
                            " bytes after the end of the gzip data were ignored");
      }
      break;
    }
    if (code == Z_BUF_ERROR || (code == Z_OK && in_pos == in.size() && z.avail_out > 0)) {
      if (in_pos == in.size()) {
        return Result<std::vector<uint8_t>>::Error(
            std::string(what) + " data ends before the end of the compressed stream (after " +
            std::to_string(in.size()) + " bytes): the file is truncated");
      }
      continue;  // no room for output: grow and go on
    }
    if (code != Z_OK) {
      return Result<std::vector<uint8_t>>::Error(zlib_error(z, code, what, in_pos));
    }
  }
  out.resize(out_pos);
  out.shrink_to_fit();
  return out;
}

}  // namespace

Result<std::vector<uint8_t>> inflate_zlib(std::span<const uint8_t> in, size_t max_output) {
  return run_inflate(in, max_output, false, nullptr);
}

Result<std::vector<uint8_t>> inflate_gzip(std::span<const uint8_t> in, size_t max_output,
                                          std::vector<std::string>* warnings) {
  return run_inflate(in, max_output, true, warnings);
}

Result<std::vector<uint8_t>> inflate_gzip_prefix(std::span<const uint8_t> in, size_t n) {
  return run_inflate(in, n, true, nullptr, true);
}

Status inflate_zlib_exact(std::span<const uint8_t> in, std::span<uint8_t> out) {
  z_stream z{};
  if (inflateInit2(&z, MAX_WBITS) != Z_OK) {
    return Status::Error("cannot start zlib decompression (out of memory)");
  }
  struct Guard {
    z_stream* z;
    ~Guard() { inflateEnd(z); }
  } guard{&z};
  size_t in_pos = 0, out_pos = 0;
  uint8_t spare[1];
  while (true) {
    size_t in_chunk = std::min(in.size() - in_pos, kMaxChunk);
    bool full = out_pos == out.size();
    size_t out_chunk = full ? 1 : std::min(out.size() - out_pos, kMaxChunk);
    z.next_in = const_cast<Bytef*>(in.data() + in_pos);
    z.avail_in = uInt(in_chunk);
    z.next_out = full ? spare : out.data() + out_pos;
    z.avail_out = uInt(out_chunk);
    int code = inflate(&z, Z_NO_FLUSH);
    in_pos += in_chunk - z.avail_in;
    size_t produced = out_chunk - z.avail_out;
    if (full && produced > 0) {
      return Status::Error("zlib data decompresses to more than the " + std::to_string(out.size()) +
                           " bytes its header announces");
    }
    out_pos += full ? 0 : produced;
    if (code == Z_STREAM_END) break;
    if (code == Z_BUF_ERROR || (code == Z_OK && in_pos == in.size() && produced == 0)) {
      if (in_pos == in.size()) {
        return Status::Error("zlib data ends before the end of the compressed stream (" +
                             std::to_string(out_pos) + " of " + std::to_string(out.size()) +
                             " bytes decompressed)");
      }
      continue;
    }
    if (code != Z_OK) return Status::Error(zlib_error(z, code, "zlib", in_pos));
  }
  if (out_pos != out.size()) {
    return Status::Error("zlib data decompresses to " + std::to_string(out_pos) +
                         " bytes but its header announces " + std::to_string(out.size()));
  }
  return Status::Ok();
}

}  // namespace vm
