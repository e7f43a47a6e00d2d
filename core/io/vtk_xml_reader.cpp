// VTK XML PolyData reader, after "VTK File Formats" (VTK User's Guide,
// chapter 19, XML file formats) and vtkXMLDataParser:
// - the XML part is read tag by tag (xml_scanner.h) up to <AppendedData>;
//   the appended section after its '_' marker is raw bytes or base64 text,
//   addressed by each DataArray's `offset`;
// - a binary array (inline base64 or appended) is a header word of
//   `header_type` (UInt32/UInt64) giving its byte count, then the bytes; when
//   compressed (vtkZLibDataCompressor) the header is [number of blocks,
//   uncompressed block size, uncompressed size of the last block (0: full),
//   compressed size of each block] and the blocks follow, each a zlib
//   stream; words and values are in the file's `byte_order`;
// - Polys and Strips are `connectivity` plus `offsets` (the end of each
//   cell; an array of n + 1 beginnings starting at 0 is accepted too);
//   cell data is ordered verts, lines, polys, strips.
// Phases: scan the XML into array references, then decode the arrays each
// piece needs and assemble points, triangles and labels.
#include "core/io/vtk_xml_reader.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <deque>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/io/base64.h"
#include "core/io/cells_to_triangles.h"
#include "core/io/float_bits.h"
#include "core/io/inflate.h"
#include "core/io/text_scan.h"
#include "core/io/value_type.h"
#include "core/io/xml_scanner.h"

namespace vm {
namespace {

static_assert(std::endian::native == std::endian::little, "little-endian hosts only");

std::string num(uint64_t n) { return std::to_string(n); }

// ---- data types -------------------------------------------------------------

constexpr ValueType kTypes[] = {
    {"Int8", 1, ValueKind::kSigned},   {"UInt8", 1, ValueKind::kUnsigned},
    {"Int16", 2, ValueKind::kSigned},  {"UInt16", 2, ValueKind::kUnsigned},
    {"Int32", 4, ValueKind::kSigned},  {"UInt32", 4, ValueKind::kUnsigned},
    {"Int64", 8, ValueKind::kSigned},  {"UInt64", 8, ValueKind::kUnsigned},
    {"Float32", 4, ValueKind::kFloat}, {"Float64", 8, ValueKind::kFloat}};

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

bool parse_u64(std::string_view s, uint64_t& out) {
  while (!s.empty() && is_text_space(s.front())) s.remove_prefix(1);
  while (!s.empty() && is_text_space(s.back())) s.remove_suffix(1);
  int64_t v;
  if (!parse_int64(s, v) || v < 0) return false;
  out = uint64_t(v);
  return true;
}

// ---- scanned structure ------------------------------------------------------

enum class ArrayFormat { kAscii, kBinary, kAppended };

struct ArrayRef {
  std::string name;   // Name attribute, unescaped
  std::string type;   // type attribute as written
  std::string where;  // for messages: "'Points' (piece 1)"
  uint64_t components = 1;
  ArrayFormat format = ArrayFormat::kAscii;
  uint64_t offset = 0;     // appended: offset after the '_' marker
  std::string_view text;   // inline content (ascii numbers or base64)
  size_t text_origin = 0;  // file offset of text[0] (for messages)
  size_t tag_pos = 0;      // file offset of the <DataArray tag
};

struct CellRefs {
  std::optional<ArrayRef> connectivity, offsets;
};

struct PieceRefs {
  uint64_t points = 0, verts = 0, lines = 0, strips = 0, polys = 0;
  std::optional<ArrayRef> points_array;
  CellRefs polys_arrays, strips_arrays;
  std::vector<ArrayRef> cell_data;
  size_t tag_pos = 0;
};

class Reader {
 public:
  Reader(std::span<const uint8_t> bytes, const SurfaceReadOptions& options)
      : bytes_(bytes),
        text_(reinterpret_cast<const char*>(bytes.data()), bytes.size()),
        options_(options) {}

  Result<SurfaceFile> read();

 private:
  Status scan();
  Status scan_data_array(XmlScanner& scanner, const XmlTag& tag, const std::string& section,
                         size_t piece_index, ArrayRef& out);
  Status read_piece(const PieceRefs& piece, size_t index, SurfaceFile& file);

  // Decoded values of an array; `expected` values when known.
  Result<std::vector<double>> doubles(const ArrayRef& a, std::optional<uint64_t> expected);
  Result<std::vector<int64_t>> ints(const ArrayRef& a, std::optional<uint64_t> expected);
  // The native-endian bytes of a binary (base64 or appended) array.
  Result<std::vector<uint8_t>> binary_bytes(const ArrayRef& a, const ValueType& t,
                                            std::optional<uint64_t> expected_values);
  Result<const ValueType*> type_of(const ArrayRef& a);
  // The values of an ascii array, each token read by `parse` (parse_double or
  // parse_int64); `what` names a value in the error for a token it rejects.
  template <typename T>
  Status ascii_values(const ArrayRef& a, std::optional<uint64_t> expected,
                      bool (*parse)(std::string_view, T&), const char* what,
                      std::vector<T>& values);
  // The values of array `a` of type `t`: an ascii array's by ascii_values, a
  // binary array's each converted by `from_bytes` (value_as_double or
  // value_as_int; false: the value is too large for an index).
  template <typename T>
  Result<std::vector<T>> values(const ArrayRef& a, const ValueType& t,
                                std::optional<uint64_t> expected,
                                bool (*parse)(std::string_view, T&), const char* what,
                                bool (*from_bytes)(const uint8_t*, const ValueType&, T&));

  std::span<const uint8_t> bytes_;
  std::string_view text_;
  const SurfaceReadOptions& options_;

  bool big_endian_ = false;
  size_t header_size_ = 4;
  bool zlib_ = false;
  std::vector<PieceRefs> pieces_;
  std::deque<std::string> owned_text_;  // inline text joined from pieces
  bool has_appended_ = false;
  bool appended_base64_ = false;
  size_t appended_begin_ = 0, appended_end_ = 0;
  uint64_t decompressed_total_ = 0;
  size_t skipped_small_cells_ = 0, dropped_strip_triangles_ = 0;
};

// ---- phase 1: scan the XML ------------------------------------------------------

Status Reader::scan_data_array(XmlScanner& scanner, const XmlTag& tag, const std::string& section,
                               size_t piece_index, ArrayRef& a) {
  a.tag_pos = tag.begin;
  if (const std::string_view* v = tag.attribute("Name")) a.name = xml_unescape(*v);
  if (const std::string_view* v = tag.attribute("type")) a.type = std::string(*v);
  std::string shown = a.name.empty() ? section : a.name;
  a.where = "'" + shown + "' of <" + section + ">" +
            (piece_index > 0 ? " (piece " + num(piece_index) + ")" : "");
  if (a.type.empty()) {
    return Status::Error("DataArray " + a.where + " at byte " + num(tag.begin) +
                         " has no type attribute");
  }
  if (const std::string_view* v = tag.attribute("NumberOfComponents")) {
    if (!parse_u64(*v, a.components) || a.components == 0) {
      return Status::Error("DataArray " + a.where + " has a bad NumberOfComponents " + quoted(*v));
    }
  }
  std::string_view format = "ascii";
  if (const std::string_view* v = tag.attribute("format")) format = *v;
  if (format == "ascii") {
    a.format = ArrayFormat::kAscii;
  } else if (format == "binary") {
    a.format = ArrayFormat::kBinary;
  } else if (format == "appended") {
    a.format = ArrayFormat::kAppended;
    const std::string_view* off = tag.attribute("offset");
    if (!off || !parse_u64(*off, a.offset)) {
      return Status::Error("appended DataArray " + a.where + " at byte " + num(tag.begin) +
                           " has no valid offset attribute");
    }
  } else {
    return Status::Error("DataArray " + a.where + " has format " + quoted(format) +
                         " (expected ascii, binary or appended)");
  }
  if (tag.kind == XmlTag::kEmpty) return Status::Ok();
  // Content: the text directly inside <DataArray> (children such as
  // <InformationKey> are skipped with their content).
  std::vector<std::pair<size_t, size_t>> segments;
  size_t text_from = tag.end;
  int depth = 0;
  XmlTag t;
  while (true) {
    Result<bool> more = scanner.next(t);
    if (!more.ok()) return more.status();
    if (!more.value()) {
      return Status::Error("DataArray " + a.where + " at byte " + num(tag.begin) +
                           " is not closed (no </DataArray>)");
    }
    if (depth == 0) {
      std::string_view seg = text_.substr(text_from, t.begin - text_from);
      if (std::any_of(seg.begin(), seg.end(), [](char c) { return !is_text_space(c); }))
        segments.emplace_back(text_from, t.begin - text_from);
    }
    if (t.kind == XmlTag::kStart) {
      ++depth;
    } else if (t.kind == XmlTag::kEnd) {
      if (depth == 0) {
        if (t.name != "DataArray") {
          return Status::Error("malformed XML at byte " + num(t.begin) + ": </" +
                               std::string(t.name) + "> closes <DataArray>");
        }
        break;
      }
      --depth;
    }
    text_from = t.end;
  }
  if (segments.size() == 1) {
    a.text = text_.substr(segments[0].first, segments[0].second);
    a.text_origin = segments[0].first;
  } else if (segments.size() > 1) {
    std::string joined;
    for (auto [b, n] : segments) joined.append(text_.substr(b, n)).push_back('\n');
    owned_text_.push_back(std::move(joined));
    a.text = owned_text_.back();
    a.text_origin = segments[0].first;
  }
  return Status::Ok();
}

Status Reader::scan() {
  XmlScanner scanner(text_);
  XmlTag tag;
  std::vector<std::string> stack;
  bool seen_root = false, seen_polydata = false;
  while (true) {
    Result<bool> more = scanner.next(tag);
    if (!more.ok()) return more.status();
    if (!more.value()) break;
    std::string name(tag.name);
    if (tag.kind == XmlTag::kEnd) {
      if (stack.empty() || stack.back() != name) {
        return Status::Error(
            "malformed XML at byte " + num(tag.begin) + ": </" + name + "> does not close " +
            (stack.empty() ? std::string("any element") : "<" + stack.back() + ">"));
      }
      stack.pop_back();
      continue;
    }
    if (!seen_root) {
      seen_root = true;
      if (name != "VTKFile") {
        return Status::Error("an XML file whose root element is <" + name +
                             ">, not <VTKFile>: not a VTK file");
      }
      const std::string_view* type = tag.attribute("type");
      if (!type || *type != "PolyData") {
        std::string t = type ? std::string(*type) : "";
        std::string ext = t == "UnstructuredGrid"  ? " (.vtu)"
                          : t == "ImageData"       ? " (.vti)"
                          : t == "StructuredGrid"  ? " (.vts)"
                          : t == "RectilinearGrid" ? " (.vtr)"
                                                   : "";
        return Status::Error("VTK XML file of type " + quoted(t) + ext +
                             ": only PolyData (.vtp) surfaces are read");
      }
      if (const std::string_view* v = tag.attribute("byte_order")) {
        if (*v == "BigEndian") {
          big_endian_ = true;
        } else if (*v != "LittleEndian") {
          return Status::Error("VTK XML file with byte_order " + quoted(*v) +
                               " (expected LittleEndian or BigEndian)");
        }
      }
      if (const std::string_view* v = tag.attribute("header_type")) {
        if (*v == "UInt64") {
          header_size_ = 8;
        } else if (*v != "UInt32") {
          return Status::Error("VTK XML file with header_type " + quoted(*v) +
                               " (expected UInt32 or UInt64)");
        }
      }
      if (const std::string_view* v = tag.attribute("compressor")) {
        if (*v == "vtkZLibDataCompressor") {
          zlib_ = true;
        } else if (!v->empty()) {
          return Status::Error("VTK XML file compressed with " + quoted(*v) +
                               ", which this tool does not read: save it with zlib "
                               "compression (vtkZLibDataCompressor) or none");
        }
      }
    } else if (name == "PolyData") {
      seen_polydata = true;
    } else if (name == "Piece") {
      if (stack.empty() || stack.back() != "PolyData") {
        return Status::Error("malformed VTK file: <Piece> at byte " + num(tag.begin) +
                             " is not inside <PolyData>");
      }
      PieceRefs p;
      p.tag_pos = tag.begin;
      struct {
        const char* attr;
        uint64_t* field;
      } counts[] = {{"NumberOfPoints", &p.points},
                    {"NumberOfVerts", &p.verts},
                    {"NumberOfLines", &p.lines},
                    {"NumberOfStrips", &p.strips},
                    {"NumberOfPolys", &p.polys}};
      for (auto& c : counts) {
        if (const std::string_view* v = tag.attribute(c.attr)) {
          if (!parse_u64(*v, *c.field)) {
            return Status::Error("<Piece> at byte " + num(tag.begin) + " has a bad " + c.attr +
                                 " " + quoted(*v));
          }
        }
      }
      pieces_.push_back(std::move(p));
    } else if (name == "DataArray") {
      std::string section = stack.empty() ? "" : stack.back();
      bool in_piece = std::find(stack.begin(), stack.end(), "Piece") != stack.end();
      size_t piece_number = pieces_.size();  // 1-based once in a piece
      ArrayRef a;
      Status st = scan_data_array(scanner, tag, section, in_piece ? piece_number : 0, a);
      if (!st.ok()) return st;
      if (!in_piece) continue;  // FieldData and such: not needed
      PieceRefs& p = pieces_.back();
      if (section == "Points") {
        if (!p.points_array) p.points_array = std::move(a);
      } else if (section == "Polys" || section == "Strips") {
        CellRefs& c = section == "Polys" ? p.polys_arrays : p.strips_arrays;
        if (a.name == "connectivity") c.connectivity = std::move(a);
        if (a.name == "offsets") c.offsets = std::move(a);
      } else if (section == "CellData") {
        p.cell_data.push_back(std::move(a));
      }
      continue;  // the DataArray's closing tag was consumed
    } else if (name == "AppendedData") {
      std::string_view enc = "raw";
      if (const std::string_view* v = tag.attribute("encoding")) enc = *v;
      if (enc == "base64") {
        appended_base64_ = true;
      } else if (enc != "raw") {
        return Status::Error("<AppendedData> has encoding " + quoted(enc) +
                             " (expected raw or base64)");
      }
      size_t p = tag.end;
      while (p < text_.size() && is_text_space(text_[p])) ++p;
      if (p >= text_.size() || text_[p] != '_') {
        return Status::Error("<AppendedData> at byte " + num(tag.begin) +
                             " is not followed by the '_' marker that starts its data");
      }
      has_appended_ = true;
      appended_begin_ = p + 1;
      appended_end_ = text_.size();
      if (appended_base64_) {
        size_t lt = text_.find('<', appended_begin_);
        if (lt != std::string_view::npos) appended_end_ = lt;
      }
      break;  // what follows is data, not XML
    }
    if (tag.kind == XmlTag::kStart) stack.push_back(name);
  }
  if (!seen_root) return Status::Error("an XML file without a root element: not a VTK file");
  if (!seen_polydata) return Status::Error("VTK XML file without a <PolyData> element");
  if (pieces_.empty()) return Status::Error("VTK XML PolyData file without a <Piece>");
  if (pieces_.size() == 1) {
    // One piece: messages need not name it.
    PieceRefs& p = pieces_[0];
    auto plain = [](std::optional<ArrayRef>& a) {
      if (a && a->where.ends_with(" (piece 1)")) a->where.resize(a->where.size() - 10);
    };
    plain(p.points_array);
    plain(p.polys_arrays.connectivity);
    plain(p.polys_arrays.offsets);
    plain(p.strips_arrays.connectivity);
    plain(p.strips_arrays.offsets);
    for (ArrayRef& a : p.cell_data)
      if (a.where.ends_with(" (piece 1)")) a.where.resize(a.where.size() - 10);
  }
  return Status::Ok();
}

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

// ---- phase 3: assemble a piece -------------------------------------------------

Status Reader::read_piece(const PieceRefs& p, size_t index, SurfaceFile& file) {
  const std::string piece = pieces_.size() > 1 ? " (piece " + num(index) + ")" : "";
  const uint64_t base = file.points.size() / 3;
  if (p.points > 0 && !p.points_array) {
    return Status::Error("the file declares " + num(p.points) + " points" + piece +
                         " but has no <Points> array");
  }
  if (p.points_array) {
    if (p.points_array->components != 3) {
      return Status::Error("the Points array" + piece + " has " + num(p.points_array->components) +
                           " components; 3 (x y z) are needed");
    }
    Result<std::vector<double>> pts = doubles(*p.points_array, 3 * p.points);
    if (!pts.ok()) return pts.status();
    for (size_t i = 0; i < pts.value().size(); ++i) {
      if (!std::isfinite(pts.value()[i])) {
        return Status::Error("point " + num(i / 3) + piece + " has a non-finite coordinate (" +
                             (std::isnan(pts.value()[i]) ? "NaN" : "Inf") +
                             "): the file is corrupt");
      }
    }
    // The array's size matched the declared count: the points are really
    // there, so only now can their number be called too large.
    if (p.points > uint64_t(std::numeric_limits<int32_t>::max()) - base) {
      return Status::Error("file too large: " + num(p.points) + " points" + piece);
    }
    file.points.insert(file.points.end(), pts.value().begin(), pts.value().end());
  }
  if (p.verts > 0 || p.lines > 0) {
    file.warnings.push_back("the file has " + num(p.verts) + " vertex cells and " + num(p.lines) +
                            " line cells" + piece +
                            "; they were ignored (only polygons and strips make the surface)");
  }

  // Labels: the preferred integer cell array, one value per cell.
  const ArrayRef* label_ref = nullptr;
  int best = std::numeric_limits<int>::max();
  for (const ArrayRef& a : p.cell_data) {
    int rank = face_label_rank(a.name);
    if (rank < 0 || rank >= best) continue;
    const ValueType* t = find_value_type(kTypes, a.type);
    if (!t || t->kind == ValueKind::kFloat || a.components != 1) {
      file.warnings.push_back("cell array '" + a.name + "' (" + a.type + ", " + num(a.components) +
                              " components) is not used as face labels");
      continue;
    }
    best = rank;
    label_ref = &a;
  }
  if (index > 1 && !file.label_array.empty() &&
      (!label_ref || label_ref->name != file.label_array)) {
    file.warnings.push_back("piece " + num(index) + " has no cell array '" + file.label_array +
                            "': the face labels were dropped");
    file.face_labels.clear();
    file.label_array.clear();
    label_ref = nullptr;
  }
  if (index > 1 && file.label_array.empty()) label_ref = nullptr;
  std::vector<int64_t> cell_labels;
  const uint64_t ncells = p.verts + p.lines + p.polys + p.strips;
  if (label_ref) {
    if (p.verts > ncells || p.lines > ncells || p.polys > ncells) {
      return Status::Error("the cell counts" + piece + " overflow");
    }
    Result<std::vector<int64_t>> l = ints(*label_ref, ncells);
    if (!l.ok()) return l.status();
    for (int64_t v : l.value()) {
      if (v < std::numeric_limits<int32_t>::min() || v > std::numeric_limits<int32_t>::max()) {
        file.warnings.push_back("cell array '" + label_ref->name +
                                "' has values beyond 32 bits: not used as face labels");
        label_ref = nullptr;
        break;
      }
    }
    if (label_ref) {
      cell_labels = std::move(l.value());
      if (index == 1) file.label_array = label_ref->name;
    }
  }

  struct Block {
    const char* name;
    uint64_t count;
    const CellRefs* refs;
    bool strips;
    uint64_t label_base;
  } blocks[] = {{"Polys", p.polys, &p.polys_arrays, false, p.verts + p.lines},
                {"Strips", p.strips, &p.strips_arrays, true, p.verts + p.lines + p.polys}};
  for (const Block& blk : blocks) {
    if (blk.count == 0) continue;
    if (!blk.refs->connectivity || !blk.refs->offsets) {
      return Status::Error("the file declares " + num(blk.count) + " " + blk.name + " cells" +
                           piece + " but <" + blk.name + "> lacks its '" +
                           (blk.refs->connectivity ? "offsets" : "connectivity") + "' array");
    }
    Result<std::vector<int64_t>> off = ints(*blk.refs->offsets, std::nullopt);
    if (!off.ok()) return off.status();
    const std::vector<int64_t>& o = off.value();
    bool with_zero = o.size() == blk.count + 1 && !o.empty() && o[0] == 0;
    if (o.size() != blk.count && !with_zero) {
      return Status::Error("array " + blk.refs->offsets->where + " has " + num(o.size()) +
                           " values but the file declares " + num(blk.count) + " " + blk.name +
                           " cells");
    }
    Result<std::vector<int64_t>> conn = ints(*blk.refs->connectivity, std::nullopt);
    if (!conn.ok()) return conn.status();
    const std::vector<int64_t>& c = conn.value();
    // Validate the offsets and count triangles before allocating them.
    uint64_t new_triangles = 0;
    int64_t prev = 0;
    for (uint64_t k = 0; k < blk.count; ++k) {
      int64_t begin = with_zero ? o[k] : prev, end = with_zero ? o[k + 1] : o[k];
      if (end < begin || end > int64_t(c.size())) {
        return Status::Error(std::string("offsets of <") + blk.name + ">" + piece +
                             " are out of range: cell " + num(k) + " spans entries " +
                             std::to_string(begin) + " to " + std::to_string(end) +
                             " of a connectivity of " + num(c.size()) + " entries");
      }
      new_triangles += polygon_triangles(size_t(end - begin));
      prev = end;
    }
    if (prev < int64_t(c.size())) {
      file.warnings.push_back("the last " + num(c.size() - uint64_t(prev)) + " entries of the " +
                              blk.name + " connectivity" + piece + " belong to no cell");
    }
    if (new_triangles > options_.max_triangles - file.triangles.size() / 3) {
      return Status::Error("file too large: more than " + num(options_.max_triangles) +
                           " triangles (the limit of this build)");
    }
    file.triangles.reserve(file.triangles.size() + 3 * new_triangles);
    if (!cell_labels.empty()) file.face_labels.reserve(file.triangles.capacity() / 3);
    prev = 0;
    std::vector<int64_t> ids;
    for (uint64_t k = 0; k < blk.count; ++k) {
      int64_t begin = with_zero ? o[k] : prev, end = with_zero ? o[k + 1] : o[k];
      prev = end;
      size_t n = size_t(end - begin);
      ids.assign(c.begin() + begin, c.begin() + end);
      for (int64_t& id : ids) {
        if (id < 0 || uint64_t(id) >= p.points) {
          return Status::Error(std::string("<") + blk.name + "> cell " + num(k) + piece +
                               " refers to point " + std::to_string(id) + " but there are " +
                               num(p.points) + " points");
        }
        id += int64_t(base);
      }
      if (n < 3) {
        ++skipped_small_cells_;
        continue;
      }
      size_t before = file.triangles.size();
      if (blk.strips)
        dropped_strip_triangles_ += append_strip(ids.data(), n, file.triangles);
      else
        append_fan(ids.data(), n, file.triangles);
      if (!cell_labels.empty()) {
        int32_t label = int32_t(cell_labels[size_t(blk.label_base + k)]);
        file.face_labels.insert(file.face_labels.end(), (file.triangles.size() - before) / 3,
                                label);
      }
    }
  }
  return Status::Ok();
}

Result<SurfaceFile> Reader::read() {
  Status st = scan();
  if (!st.ok()) return st;
  SurfaceFile file;
  for (size_t i = 0; i < pieces_.size(); ++i) {
    st = read_piece(pieces_[i], i + 1, file);
    if (!st.ok()) return st;
  }
  if (skipped_small_cells_ > 0) {
    file.warnings.push_back(num(skipped_small_cells_) +
                            " cells with fewer than 3 points were skipped");
  }
  if (dropped_strip_triangles_ > 0) {
    file.warnings.push_back(num(dropped_strip_triangles_) +
                            " degenerate strip triangles (a repeated point) were skipped");
  }
  if (file.triangles.empty()) {
    return Status::Error("VTK XML PolyData file without any polygon or triangle strip");
  }
  if (file.face_labels.size() != file.triangles.size() / 3) {
    file.face_labels.clear();
    file.label_array.clear();
  }
  // Describe the format by the Points array of the first piece.
  std::string how = "ascii";
  for (const PieceRefs& p : pieces_) {
    if (!p.points_array) continue;
    how = p.points_array->format == ArrayFormat::kAscii    ? "ascii"
          : p.points_array->format == ArrayFormat::kBinary ? "binary"
          : appended_base64_                               ? "appended base64"
                                                           : "appended raw";
    break;
  }
  if (zlib_ && how != "ascii") how += ", zlib";
  if (big_endian_) how += ", big endian";
  file.format = "VTK XML PolyData (" + how + ")";
  file.format_id = "vtp";
  return file;
}

}  // namespace

Result<SurfaceFile> read_vtk_xml(std::span<const uint8_t> bytes,
                                 const SurfaceReadOptions& options) {
  Reader reader(bytes, options);
  return reader.read();
}

}  // namespace vm
