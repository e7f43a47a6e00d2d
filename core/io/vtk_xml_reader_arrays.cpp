// Phase 2 of the VTK XML PolyData reader (vtk_xml_reader.h), after "VTK
// File Formats" (VTK User's Guide, chapter 19, XML file formats) and
// vtkXMLDataParser: the values of one DataArray. An ascii array is
// whitespace-separated numbers; a binary one (inline base64, or in the
// appended section after its '_' marker, raw bytes or base64, at the
// array's `offset`) is a header word of `header_type` (UInt32/UInt64)
// giving its byte count, then the bytes; when compressed
// (vtkZLibDataCompressor) the header is [number of blocks, uncompressed
// block size, uncompressed size of the last block (0: full), compressed
// size of each block] and the blocks follow, each a zlib stream; words and
// values are in the file's `byte_order`, of one of the ten numeric types.
// Every allocation is bounded by the bytes present or
// max_decompressed_bytes.
#include <algorithm>
#include <bit>
#include <cstring>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/io/base64.h"
#include "core/io/float_bits.h"
#include "core/io/inflate.h"
#include "core/io/text_scan.h"
#include "core/io/value_type.h"
#include "core/io/vtk_xml_reader_internal.h"

namespace vm {
namespace vtk_xml_detail {
namespace {

static_assert(std::endian::native == std::endian::little, "little-endian hosts only");

// Reads value i of a native-endian array of type t as a double / an int64
// (false for UInt64 values beyond int64 and for float types).
double value_as_double(const uint8_t* p, const ValueType& t) {
  switch (t.size) {
    case 1:
      return t.kind == ValueKind::kSigned ? double(int8_t(*p)) : double(*p);
    case 2: {
      uint16_t u;
      std::memcpy(&u, p, 2);
      return t.kind == ValueKind::kSigned ? double(int16_t(u)) : double(u);
    }
    case 4: {
      uint32_t u;
      std::memcpy(&u, p, 4);
      if (t.kind == ValueKind::kFloat) return double(float_from_bits(u));
      return t.kind == ValueKind::kSigned ? double(int32_t(u)) : double(u);
    }
    default: {
      uint64_t u;
      std::memcpy(&u, p, 8);
      if (t.kind == ValueKind::kFloat) return double_from_bits(u);
      return t.kind == ValueKind::kSigned ? double(int64_t(u)) : double(u);
    }
  }
}

bool value_as_int(const uint8_t* p, const ValueType& t, int64_t& out) {
  switch (t.size) {
    case 1:
      out = t.kind == ValueKind::kSigned ? int64_t(int8_t(*p)) : int64_t(*p);
      return true;
    case 2: {
      uint16_t u;
      std::memcpy(&u, p, 2);
      out = t.kind == ValueKind::kSigned ? int64_t(int16_t(u)) : int64_t(u);
      return true;
    }
    case 4: {
      uint32_t u;
      std::memcpy(&u, p, 4);
      out = t.kind == ValueKind::kSigned ? int64_t(int32_t(u)) : int64_t(u);
      return true;
    }
    default: {
      uint64_t u;
      std::memcpy(&u, p, 8);
      if (t.kind == ValueKind::kUnsigned && u > uint64_t(std::numeric_limits<int64_t>::max()))
        return false;
      out = int64_t(u);
      return true;
    }
  }
}

}  // namespace

// ---- phase 2: decode arrays -----------------------------------------------------

Result<const ValueType*> Reader::type_of(const ArrayRef& a) {
  const ValueType* t = find_value_type(kTypes, a.type);
  if (!t) {
    return Status::Error("array " + a.where + " has data type " + quoted(a.type) +
                         ", which is not a VTK XML numeric type (Int8, UInt8, Int16, UInt16, "
                         "Int32, UInt32, Int64, UInt64, Float32, Float64)");
  }
  return t;
}

namespace {

// Where the bytes of a binary array come from: the raw appended section, or
// base64 text (inline or appended).
class ByteSource {
 public:
  // Raw bytes file[begin, end).
  ByteSource(std::span<const uint8_t> file, size_t begin, size_t end, const std::string& where)
      : file_(file), pos_(begin), end_(end), where_(where) {}
  // Base64 text[begin, end), text[0] being at byte `origin` of the file.
  ByteSource(std::string_view text, size_t begin, size_t end, size_t origin,
             const std::string& where)
      : end_(origin + end), b64_(Base64Stream(text, begin, end, origin)), where_(where) {}

  size_t max_remaining() const { return b64_ ? b64_->max_remaining() : end_ - pos_; }

  // The next n bytes: a view into the file (raw) or into `scratch` (base64).
  Result<std::span<const uint8_t>> read(size_t n, std::vector<uint8_t>& scratch) {
    if (n > max_remaining()) return too_short(n);
    if (b64_) {
      scratch.clear();
      Status st = b64_->read(n, scratch);
      if (!st.ok()) return Status::Error("array " + where_ + ": " + st.message());
      return std::span<const uint8_t>(scratch);
    }
    std::span<const uint8_t> s = file_.subspan(pos_, n);
    pos_ += n;
    return s;
  }

  // The error for data that ends before `needed` more bytes.
  Status too_short(uint64_t needed) const {
    if (b64_) {
      return Status::Error("array " + where_ + " is cut short: its base64 data ends at byte " +
                           num(end_) + " with at most " + num(max_remaining()) +
                           " bytes left, but " + num(needed) + " more are needed");
    }
    return Status::Error("the appended data ends at byte " + num(end_) + " but array " + where_ +
                         " needs bytes up to " + num(uint64_t(pos_) + needed));
  }

 private:
  std::span<const uint8_t> file_;
  size_t pos_ = 0, end_ = 0;
  std::optional<Base64Stream> b64_;
  std::string where_;
};

}  // namespace

Result<std::vector<uint8_t>> Reader::binary_bytes(const ArrayRef& a, const ValueType& t,
                                                  std::optional<uint64_t> expected_values) {
  std::optional<ByteSource> src;
  if (a.format == ArrayFormat::kBinary) {
    src.emplace(a.text, 0, a.text.size(), a.text_origin, a.where);
  } else {
    if (!has_appended_) {
      return Status::Error("array " + a.where +
                           " is appended but the file has no <AppendedData> section");
    }
    if (a.offset > appended_end_ - appended_begin_) {
      return Status::Error("array " + a.where + " starts at appended offset " + num(a.offset) +
                           " but the appended data has only " +
                           num(appended_end_ - appended_begin_) + " " +
                           (appended_base64_ ? "characters" : "bytes"));
    }
    size_t begin = appended_begin_ + size_t(a.offset);
    if (appended_base64_)
      src.emplace(text_, begin, appended_end_, 0, a.where);
    else
      src.emplace(bytes_, begin, appended_end_, a.where);
  }
  std::vector<uint8_t> scratch;
  auto word = [&](std::span<const uint8_t> s, size_t i) {
    uint64_t v = 0;
    for (size_t k = 0; k < header_size_; ++k) {
      size_t byte = big_endian_ ? header_size_ - 1 - k : k;
      v |= uint64_t(s[i * header_size_ + byte]) << (8 * k);
    }
    return v;
  };
  std::optional<uint64_t> expected_bytes;
  if (expected_values) {
    if (*expected_values > std::numeric_limits<uint64_t>::max() / t.size) {
      return Status::Error("array " + a.where + ": the header declares an impossible size");
    }
    expected_bytes = *expected_values * t.size;
  }
  auto size_mismatch = [&](uint64_t have) {
    return Status::Error("array " + a.where + " holds " + num(have) + " bytes but the header " +
                         "declares " + num(*expected_values) + " values of " + num(t.size) +
                         " bytes (" + num(*expected_bytes) + " bytes)");
  };
  std::vector<uint8_t> out;
  if (!zlib_) {
    Result<std::span<const uint8_t>> h = src->read(header_size_, scratch);
    if (!h.ok()) return h.status();
    uint64_t nbytes = word(h.value(), 0);
    if (expected_bytes && nbytes != *expected_bytes) return size_mismatch(nbytes);
    if (nbytes % t.size != 0) {
      return Status::Error("array " + a.where + " holds " + num(nbytes) +
                           " bytes, not a whole number of " + std::string(t.name) + " values");
    }
    if (nbytes > src->max_remaining()) return src->too_short(nbytes);
    Result<std::span<const uint8_t>> d = src->read(size_t(nbytes), scratch);
    if (!d.ok()) return d.status();
    out.assign(d.value().begin(), d.value().end());
  } else {
    Result<std::span<const uint8_t>> h = src->read(3 * header_size_, scratch);
    if (!h.ok()) return h.status();
    const uint64_t nblocks = word(h.value(), 0), block = word(h.value(), 1),
                   last = word(h.value(), 2);
    if (nblocks > src->max_remaining() / header_size_) {
      return src->too_short(nblocks * header_size_);
    }
    Result<std::span<const uint8_t>> sizes_span =
        src->read(size_t(nblocks) * header_size_, scratch);
    if (!sizes_span.ok()) return sizes_span.status();
    std::vector<uint64_t> csize(nblocks);
    uint64_t csum = 0;  // <= max_remaining()
    for (uint64_t b = 0; b < nblocks; ++b) {
      csize[b] = word(sizes_span.value(), b);
      if (csize[b] > src->max_remaining() - csum) return src->too_short(csum + csize[b]);
      csum += csize[b];
    }
    uint64_t total = 0;
    if (nblocks > 0) {
      if (block == 0 || last > block) {
        return Status::Error("array " + a.where + ": bad compression header (block size " +
                             num(block) + ", last block " + num(last) + ")");
      }
      if (nblocks - 1 > (std::numeric_limits<uint64_t>::max() - block) / block) {
        return Status::Error("array " + a.where +
                             ": the compression header declares an "
                             "impossible size");
      }
      total = (nblocks - 1) * block + (last == 0 ? block : last);
    }
    if (expected_bytes && total != *expected_bytes) return size_mismatch(total);
    if (total % t.size != 0) {
      return Status::Error("array " + a.where + " decompresses to " + num(total) +
                           " bytes, not a whole number of " + std::string(t.name) + " values");
    }
    if (total > options_.max_decompressed_bytes - decompressed_total_) {
      return Status::Error("array " + a.where + ": decompressed data exceeds the limit of " +
                           num(options_.max_decompressed_bytes) + " bytes (compression ratio " +
                           "over " + num(total / std::max<uint64_t>(csum, 1)) + "): refused");
    }
    for (uint64_t b = 0; b < nblocks; ++b) {
      uint64_t usize = (b + 1 == nblocks && last != 0) ? last : block;
      // deflate cannot do better than about 1032:1.
      if (usize / 1032 > csize[b] + 1) {
        return Status::Error("array " + a.where + ", zlib block " + num(b + 1) + " of " +
                             num(nblocks) + ": " + num(csize[b]) +
                             " compressed bytes cannot hold " + num(usize) +
                             " bytes: the header lies");
      }
    }
    decompressed_total_ += total;
    out.resize(size_t(total));
    size_t at = 0;
    for (uint64_t b = 0; b < nblocks; ++b) {
      size_t usize = size_t((b + 1 == nblocks && last != 0) ? last : block);
      Result<std::span<const uint8_t>> c = src->read(size_t(csize[b]), scratch);
      if (!c.ok()) return c.status();
      Status st = inflate_zlib_exact(c.value(), std::span<uint8_t>(out.data() + at, usize));
      if (!st.ok()) {
        return Status::Error("array " + a.where + ", zlib block " + num(b + 1) + " of " +
                             num(nblocks) + ": " + st.message());
      }
      at += usize;
    }
  }
  if (big_endian_ && t.size > 1) {
    for (size_t i = 0; i + t.size <= out.size(); i += t.size)
      std::reverse(out.begin() + long(i), out.begin() + long(i + t.size));
  }
  return out;
}

template <typename T>
Status Reader::ascii_values(const ArrayRef& a, std::optional<uint64_t> expected,
                            bool (*parse)(std::string_view, T&), const char* what,
                            std::vector<T>& values) {
  std::vector<std::string_view> tokens;
  size_t i = 0, n = a.text.size();
  while (true) {
    while (i < n && is_text_space(a.text[i])) ++i;
    if (i >= n) break;
    size_t b = i;
    while (i < n && !is_text_space(a.text[i])) ++i;
    tokens.push_back(a.text.substr(b, i - b));
  }
  if (expected && tokens.size() != *expected) {
    return Status::Error("ascii array " + a.where + " has " + num(tokens.size()) +
                         " values but the header declares " + num(*expected));
  }
  values.resize(tokens.size());
  for (size_t k = 0; k < tokens.size(); ++k) {
    if (!parse(tokens[k], values[k])) {
      return Status::Error("ascii array " + a.where + ": value " + num(k + 1) + " " +
                           quoted(tokens[k]) + " is not " + what);
    }
  }
  return Status::Ok();
}

template <typename T>
Result<std::vector<T>> Reader::values(const ArrayRef& a, const ValueType& t,
                                      std::optional<uint64_t> expected,
                                      bool (*parse)(std::string_view, T&), const char* what,
                                      bool (*from_bytes)(const uint8_t*, const ValueType&, T&)) {
  std::vector<T> v;
  if (a.format == ArrayFormat::kAscii) {
    Status st = ascii_values(a, expected, parse, what, v);
    if (!st.ok()) return st;
    return v;
  }
  Result<std::vector<uint8_t>> b = binary_bytes(a, t, expected);
  if (!b.ok()) return b.status();
  const size_t size = t.size, count = b.value().size() / size;
  v.resize(count);
  for (size_t i = 0; i < count; ++i) {
    if (!from_bytes(&b.value()[i * size], t, v[i])) {
      return Status::Error("array " + a.where + ": value " + num(i + 1) +
                           " is too large for an index");
    }
  }
  return v;
}

Result<std::vector<double>> Reader::doubles(const ArrayRef& a, std::optional<uint64_t> expected) {
  Result<const ValueType*> t = type_of(a);
  if (!t.ok()) return t.status();
  return values<double>(a, *t.value(), expected, parse_double, "a number",
                        [](const uint8_t* p, const ValueType& type, double& out) {
                          out = value_as_double(p, type);
                          return true;
                        });
}

Result<std::vector<int64_t>> Reader::ints(const ArrayRef& a, std::optional<uint64_t> expected) {
  Result<const ValueType*> t = type_of(a);
  if (!t.ok()) return t.status();
  if (t.value()->kind == ValueKind::kFloat) {
    return Status::Error("array " + a.where + " has type " + a.type +
                         ", but it must hold integers");
  }
  return values<int64_t>(a, *t.value(), expected, parse_int64, "an integer", value_as_int);
}

}  // namespace vtk_xml_detail
}  // namespace vm
