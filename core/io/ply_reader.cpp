// PLY reader after Greg Turk's description of the format ("The PLY Polygon
// File Format", 1994) and the rply/tinyply conventions for type names
// (char/int8 ... double/float64). The header is text lines up to
// end_header; the elements follow in header order, as whitespace-separated
// numbers (ascii) or packed values (binary, little or big endian). Faces are
// kept as offsets + indices and validated once every element is read.
#include "core/io/ply_reader.h"

#include <cmath>
#include <cstring>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/io/cells_to_triangles.h"
#include "core/io/float_bits.h"
#include "core/io/text_scan.h"
#include "core/io/value_type.h"

namespace vm {
namespace {

std::string num(uint64_t n) { return std::to_string(n); }

constexpr ValueType kTypes[] = {
    {"char", 1, ValueKind::kSigned},     {"int8", 1, ValueKind::kSigned},
    {"uchar", 1, ValueKind::kUnsigned},  {"uint8", 1, ValueKind::kUnsigned},
    {"short", 2, ValueKind::kSigned},    {"int16", 2, ValueKind::kSigned},
    {"ushort", 2, ValueKind::kUnsigned}, {"uint16", 2, ValueKind::kUnsigned},
    {"int", 4, ValueKind::kSigned},      {"int32", 4, ValueKind::kSigned},
    {"uint", 4, ValueKind::kUnsigned},   {"uint32", 4, ValueKind::kUnsigned},
    {"float", 4, ValueKind::kFloat},     {"float32", 4, ValueKind::kFloat},
    {"double", 8, ValueKind::kFloat},    {"float64", 8, ValueKind::kFloat},
    {"int64", 8, ValueKind::kSigned},    {"uint64", 8, ValueKind::kUnsigned}};

struct Property {
  std::string name;
  const ValueType* type = nullptr;        // value type (list: item type)
  const ValueType* count_type = nullptr;  // list only
  bool is_list() const { return count_type != nullptr; }
};

struct Element {
  std::string name;
  uint64_t count = 0;
  std::vector<Property> properties;
  size_t header_line = 0;
};

enum class Format { kAscii, kLittle, kBig };

// Label preference: kFaceLabelArrays, then "label".
int label_rank(std::string_view name) {
  int r = face_label_rank(name);
  if (r >= 0) return r;
  return name == "label" ? int(kFaceLabelArrays.size()) : -1;
}

class Reader {
 public:
  Reader(std::span<const uint8_t> bytes, const SurfaceReadOptions& options)
      : cur_(bytes), options_(options) {}
  Result<SurfaceFile> read();

 private:
  Status parse_header();
  Status read_element(const Element& e);
  // One value of a scalar type at the cursor: as a double and, for integer
  // types, as an int64.
  Status value(const ValueType& t, const Element& e, uint64_t index, double& d, int64_t& i);

  TextCursor cur_;
  const SurfaceReadOptions& options_;
  Format format_ = Format::kAscii;
  std::vector<Element> elements_;
  bool have_vertex_ = false, have_face_ = false;
  std::vector<double> points_;
  std::vector<int64_t> face_offsets_{0}, face_indices_;
  std::vector<int64_t> face_labels_;
  std::string label_name_;
};

Status Reader::parse_header() {
  auto fail = [&](const std::string& what) {
    return Status::Error("PLY header line " + num(cur_.line() - 1) + ": " + what);
  };
  std::string_view magic = cur_.rest_of_line();
  while (!magic.empty() && is_text_space(magic.back())) magic.remove_suffix(1);
  if (magic != "ply") return Status::Error("PLY: the first line is not 'ply'");
  bool have_format = false;
  while (true) {
    if (cur_.remaining() == 0) {
      return Status::Error("PLY header without end_header (the file ends at line " +
                           num(cur_.line()) + ")");
    }
    std::string_view line = cur_.rest_of_line();
    std::vector<std::string_view> tok;
    for (size_t i = 0; i < line.size();) {
      while (i < line.size() && is_text_space(line[i])) ++i;
      size_t b = i;
      while (i < line.size() && !is_text_space(line[i])) ++i;
      if (i > b) tok.push_back(line.substr(b, i - b));
    }
    if (tok.empty()) continue;
    if (tok[0] == "end_header") break;
    if (tok[0] == "comment" || tok[0] == "obj_info") continue;
    if (tok[0] == "format") {
      if (tok.size() < 3) return fail("format line needs a format and a version");
      if (tok[1] == "ascii") {
        format_ = Format::kAscii;
      } else if (tok[1] == "binary_little_endian") {
        format_ = Format::kLittle;
      } else if (tok[1] == "binary_big_endian") {
        format_ = Format::kBig;
      } else {
        return fail("unknown format " + quoted(tok[1]) +
                    " (ascii, binary_little_endian or binary_big_endian)");
      }
      if (tok[2] != "1.0") return fail("unsupported version " + quoted(tok[2]));
      have_format = true;
    } else if (tok[0] == "element") {
      if (tok.size() != 3) return fail("element line needs a name and a count");
      Element e;
      e.name = std::string(tok[1]);
      int64_t n;
      if (!parse_int64(tok[2], n) || n < 0) return fail("bad element count " + quoted(tok[2]));
      e.count = uint64_t(n);
      e.header_line = cur_.line() - 1;
      elements_.push_back(std::move(e));
    } else if (tok[0] == "property") {
      if (elements_.empty()) return fail("property before any element");
      Property p;
      if (tok.size() >= 2 && tok[1] == "list") {
        if (tok.size() != 5)
          return fail("list property needs a count type, an item type and a name");
        p.count_type = find_value_type(kTypes, tok[2]);
        if (!p.count_type) return fail("unknown property type " + quoted(tok[2]));
        if (p.count_type->kind == ValueKind::kFloat) {
          return fail("list count type " + quoted(tok[2]) + " is not an integer type");
        }
        p.type = find_value_type(kTypes, tok[3]);
        if (!p.type) return fail("unknown property type " + quoted(tok[3]));
        p.name = std::string(tok[4]);
      } else {
        if (tok.size() != 3) return fail("property needs a type and a name");
        p.type = find_value_type(kTypes, tok[1]);
        if (!p.type) return fail("unknown property type " + quoted(tok[1]));
        p.name = std::string(tok[2]);
      }
      elements_.back().properties.push_back(std::move(p));
    } else {
      return fail("unknown header keyword " + quoted(tok[0]));
    }
  }
  if (!have_format) return Status::Error("PLY header without a format line");
  return Status::Ok();
}

Status Reader::value(const ValueType& t, const Element& e, uint64_t index, double& d, int64_t& i) {
  auto cut = [&]() {
    return Status::Error("PLY data ends in element '" + e.name + "' number " + num(index) + " of " +
                         num(e.count) + " (the file is truncated or the header's " +
                         "counts are wrong)");
  };
  if (format_ == Format::kAscii) {
    std::string_view tok = cur_.next();
    if (tok.empty()) return cut();
    if (t.kind == ValueKind::kFloat) {
      if (!parse_double(tok, d)) {
        return Status::Error("PLY line " + num(cur_.line()) + ": " + quoted(tok) +
                             " is not a number (element '" + e.name + "' number " + num(index) +
                             ")");
      }
      i = 0;
      return Status::Ok();
    }
    if (!parse_int64(tok, i)) {
      return Status::Error("PLY line " + num(cur_.line()) + ": " + quoted(tok) +
                           " is not an integer (element '" + e.name + "' number " + num(index) +
                           ")");
    }
    d = double(i);
    return Status::Ok();
  }
  if (cur_.remaining() < t.size) return cut();
  const uint8_t* p = cur_.data_at_pos();
  uint64_t u = 0;
  for (size_t k = 0; k < t.size; ++k) {
    size_t byte = format_ == Format::kBig ? k : t.size - 1 - k;
    u = u << 8 | p[byte];
  }
  cur_.skip(t.size);
  if (t.kind == ValueKind::kFloat) {
    d = t.size == 4 ? double(float_from_bits(uint32_t(u))) : double_from_bits(u);
    i = 0;
  } else if (t.kind == ValueKind::kSigned) {
    int shift = int(64 - 8 * t.size);
    i = int64_t(u << shift) >> shift;
    d = double(i);
  } else {
    i = u > uint64_t(std::numeric_limits<int64_t>::max()) ? -1 : int64_t(u);
    d = double(u);
  }
  return Status::Ok();
}

Status Reader::read_element(const Element& e) {
  if (e.properties.empty() || e.count == 0) return Status::Ok();
  const bool is_vertex = e.name == "vertex" && !have_vertex_;
  const bool is_face = e.name == "face" && !have_face_;
  // Bound the count by the data present before allocating: each element
  // takes at least `min_bytes` (binary) or one token of 2 bytes per property
  // (ascii).
  uint64_t min_bytes = 0;
  for (const Property& p : e.properties)
    min_bytes += p.is_list() ? p.count_type->size : p.type->size;
  if (format_ == Format::kAscii) min_bytes = 2 * e.properties.size();
  // (ascii: the last token needs no separator).
  const uint64_t room =
      format_ == Format::kAscii ? (cur_.remaining() + 1) / min_bytes : cur_.remaining() / min_bytes;
  if (e.count > room) {
    return Status::Error("PLY element '" + e.name + "' (header line " + num(e.header_line) +
                         ") declares " + num(e.count) + " elements of at least " + num(min_bytes) +
                         " bytes but only " + num(cur_.remaining()) +
                         " bytes of data remain (the file is truncated or the count is wrong)");
  }
  int xyz[3] = {-1, -1, -1};
  int list = -1, label = -1, best = std::numeric_limits<int>::max();
  for (size_t k = 0; k < e.properties.size(); ++k) {
    const Property& p = e.properties[k];
    if (is_vertex && !p.is_list()) {
      if (p.name == "x") xyz[0] = int(k);
      if (p.name == "y") xyz[1] = int(k);
      if (p.name == "z") xyz[2] = int(k);
    }
    if (is_face && p.is_list() && (p.name == "vertex_indices" || p.name == "vertex_index") &&
        list < 0) {
      if (p.type->kind == ValueKind::kFloat) {
        return Status::Error("PLY face property '" + p.name + "' has item type " +
                             std::string(p.type->name) + " but must hold integers");
      }
      list = int(k);
    }
    if (is_face && !p.is_list()) {
      int r = label_rank(p.name);
      if (r >= 0 && r < best && p.type->kind != ValueKind::kFloat) {
        best = r;
        label = int(k);
      }
    }
  }
  if (is_vertex) {
    for (int c = 0; c < 3; ++c) {
      if (xyz[c] < 0) {
        return Status::Error(std::string("PLY element 'vertex' has no scalar property '") +
                             "xyz"[c] + "'");
      }
    }
    if (e.count > uint64_t(std::numeric_limits<int32_t>::max())) {
      return Status::Error("file too large: " + num(e.count) + " vertices");
    }
    points_.resize(3 * e.count);
    have_vertex_ = true;
  }
  if (is_face) {
    if (list < 0) {
      return Status::Error("PLY element 'face' has no list property 'vertex_indices'");
    }
    face_offsets_.reserve(e.count + 1);
    if (label >= 0) {
      label_name_ = e.properties[size_t(label)].name;
      face_labels_.reserve(e.count);
    }
    have_face_ = true;
  }
  uint64_t triangles = 0;
  for (uint64_t n = 0; n < e.count; ++n) {
    for (size_t k = 0; k < e.properties.size(); ++k) {
      const Property& p = e.properties[k];
      double d;
      int64_t iv;
      if (!p.is_list()) {
        Status st = value(*p.type, e, n, d, iv);
        if (!st.ok()) return st;
        if (is_vertex) {
          for (int c = 0; c < 3; ++c) {
            if (xyz[c] != int(k)) continue;
            if (!std::isfinite(d)) {
              return Status::Error("PLY vertex " + num(n) + " has a non-finite coordinate (" +
                                   (std::isnan(d) ? "NaN" : "Inf") + ")");
            }
            points_[3 * n + size_t(c)] = d;
          }
        }
        if (is_face && int(k) == label) face_labels_.push_back(iv);
        continue;
      }
      Status st = value(*p.count_type, e, n, d, iv);
      if (!st.ok()) return st;
      if (iv < 0) {
        return Status::Error("PLY element '" + e.name + "' number " + num(n) + ": list '" + p.name +
                             "' has a negative length");
      }
      const uint64_t len = uint64_t(iv);
      // Binary: the items must fit in the bytes left (they may be skipped
      // whole); ascii: one token of at least 2 bytes each but the last.
      const uint64_t room =
          format_ == Format::kAscii ? (cur_.remaining() + 1) / 2 : cur_.remaining() / p.type->size;
      if (len > room) {
        return Status::Error("PLY data ends in element '" + e.name + "' number " + num(n) + " of " +
                             num(e.count) + ": its list '" + p.name + "' announces " + num(len) +
                             " items");
      }
      const bool keep = is_face && int(k) == list;
      if (keep) {
        triangles += polygon_triangles(size_t(len));
        if (triangles > options_.max_triangles) {
          return Status::Error("file too large: more than " + num(options_.max_triangles) +
                               " triangles (the limit of this build)");
        }
      }
      if (!keep && format_ != Format::kAscii) {
        cur_.skip(size_t(len * p.type->size));
        continue;
      }
      for (uint64_t j = 0; j < len; ++j) {
        st = value(*p.type, e, n, d, iv);
        if (!st.ok()) return st;
        if (keep) face_indices_.push_back(iv);
      }
      if (keep) face_offsets_.push_back(int64_t(face_indices_.size()));
    }
  }
  return Status::Ok();
}

Result<SurfaceFile> Reader::read() {
  Status st = parse_header();
  if (!st.ok()) return st;
  // The data starts right after "end_header\n" (consumed by the header).
  bool vertex_declared = false, face_declared = false;
  for (const Element& e : elements_) {
    vertex_declared |= e.name == "vertex";
    face_declared |= e.name == "face";
  }
  if (!vertex_declared) return Status::Error("PLY file without a 'vertex' element");
  if (!face_declared) {
    return Status::Error("PLY file without a 'face' element (a point cloud, not a surface)");
  }
  std::vector<std::string> skipped;
  for (const Element& e : elements_) {
    st = read_element(e);
    if (!st.ok()) return st;
    if (e.name != "vertex" && e.name != "face" && e.count > 0) skipped.push_back(e.name);
  }
  SurfaceFile file;
  const uint64_t nv = points_.size() / 3;
  const size_t nfaces = face_offsets_.size() - 1;
  uint64_t ntri = 0;
  size_t small = 0;
  for (size_t f = 0; f < nfaces; ++f) {
    for (int64_t k = face_offsets_[f]; k < face_offsets_[f + 1]; ++k) {
      int64_t id = face_indices_[size_t(k)];
      if (id < 0 || uint64_t(id) >= nv) {
        return Result<SurfaceFile>::Error("PLY face " + num(f) + " refers to vertex " +
                                          std::to_string(id) + " but there are " + num(nv) +
                                          " vertices");
      }
    }
    size_t n = size_t(face_offsets_[f + 1] - face_offsets_[f]);
    ntri += polygon_triangles(n);
    small += n < 3;
  }
  bool labels = !label_name_.empty() && face_labels_.size() == nfaces;
  for (size_t f = 0; labels && f < nfaces; ++f) {
    if (face_labels_[f] < std::numeric_limits<int32_t>::min() ||
        face_labels_[f] > std::numeric_limits<int32_t>::max()) {
      file.warnings.push_back("face property '" + label_name_ +
                              "' has values beyond 32 bits: not used as face labels");
      labels = false;
    }
  }
  file.points = std::move(points_);
  file.triangles.reserve(3 * ntri);
  if (labels) file.face_labels.reserve(ntri);
  for (size_t f = 0; f < nfaces; ++f) {
    size_t n = size_t(face_offsets_[f + 1] - face_offsets_[f]);
    append_fan(face_indices_.data() + face_offsets_[f], n, file.triangles);
    if (labels) file.face_labels.resize(file.triangles.size() / 3, int32_t(face_labels_[f]));
  }
  if (labels) file.label_array = label_name_;
  if (file.triangles.empty()) {
    return Result<SurfaceFile>::Error("PLY file without any face of 3 or more vertices");
  }
  if (small > 0) {
    file.warnings.push_back(num(small) + " faces with fewer than 3 vertices were skipped");
  }
  if (!skipped.empty()) {
    std::string list;
    for (const std::string& s : skipped) list += (list.empty() ? "'" : ", '") + s + "'";
    file.warnings.push_back("PLY elements " + list + " were ignored");
  }
  if (format_ == Format::kAscii ? !cur_.at_end() : cur_.remaining() > 0) {
    file.warnings.push_back("data after the last PLY element was ignored");
  }
  file.format = format_ == Format::kAscii    ? "PLY (ascii)"
                : format_ == Format::kLittle ? "PLY (binary little endian)"
                                             : "PLY (binary big endian)";
  file.format_id = "ply";
  return file;
}

}  // namespace

Result<SurfaceFile> read_ply(std::span<const uint8_t> bytes, const SurfaceReadOptions& options) {
  Reader reader(bytes, options);
  return reader.read();
}

}  // namespace vm
