// Legacy VTK reader, after "VTK File Formats" (VTK User's Guide, simple
// legacy formats) and vtkDataReader / vtkPolyDataReader: a header of three
// lines, then keyword sections. In BINARY files the values of a section
// follow its keyword line as big-endian binary (then a newline); metadata
// blocks (METADATA ... empty line, VTK >= 8) are text in both forms.
// Cells are kept as offsets (n + 1) + connectivity whatever their layout in
// the file; the surface is assembled once the whole file is read.
#include "core/io/vtk_legacy_reader.h"

#include <algorithm>
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

namespace vm {
namespace {

std::string num(uint64_t n) { return std::to_string(n); }

std::string upper(std::string_view s) {
  std::string u(s);
  for (char& c : u)
    if (c >= 'a' && c <= 'z') c = char(c - 'a' + 'A');
  return u;
}

enum class Kind { kSigned, kUnsigned, kFloat, kBit };

struct LegacyType {
  std::string_view name;
  size_t size;  // bytes in BINARY (bit: packed, see value_bytes)
  Kind kind;
};

// vtkIdType is written as 32-bit int by vtkDataWriter.
constexpr LegacyType kTypes[] = {{"bit", 0, Kind::kBit},
                                 {"unsigned_char", 1, Kind::kUnsigned},
                                 {"char", 1, Kind::kSigned},
                                 {"signed_char", 1, Kind::kSigned},
                                 {"unsigned_short", 2, Kind::kUnsigned},
                                 {"short", 2, Kind::kSigned},
                                 {"unsigned_int", 4, Kind::kUnsigned},
                                 {"int", 4, Kind::kSigned},
                                 {"unsigned_long", 8, Kind::kUnsigned},
                                 {"long", 8, Kind::kSigned},
                                 {"vtktypeuint64", 8, Kind::kUnsigned},
                                 {"vtktypeint64", 8, Kind::kSigned},
                                 {"vtkidtype", 4, Kind::kSigned},
                                 {"float", 4, Kind::kFloat},
                                 {"double", 8, Kind::kFloat}};

const LegacyType* find_type(std::string_view name) {
  std::string lower(name);
  for (char& c : lower)
    if (c >= 'A' && c <= 'Z') c = char(c - 'A' + 'a');
  for (const LegacyType& t : kTypes)
    if (t.name == lower) return &t;
  return nullptr;
}

// Cells as offsets (n + 1 entries, starting at 0) into a connectivity list.
struct Cells {
  std::vector<int64_t> offsets{0};
  std::vector<int64_t> connectivity;
  size_t count() const { return offsets.size() - 1; }
};

// What an integer cell array candidate for labels holds.
struct LabelCandidate {
  std::string name;
  int rank = -1;
  std::vector<int64_t> values;
};

class Reader {
 public:
  Reader(std::span<const uint8_t> bytes, const SurfaceReadOptions& options)
      : cur_(bytes), options_(options) {}

  Result<SurfaceFile> read();

 private:
  // "legacy VTK, line N: what" (ASCII) or "legacy VTK, byte N: what".
  Status fail(const std::string& what) {
    return Status::Error("legacy VTK, " +
                         (binary_ ? "byte " + num(cur_.pos()) : "line " + num(cur_.line())) + ": " +
                         what);
  }
  Result<uint64_t> count_token(const char* what);
  Result<const LegacyType*> type_token(const std::string& context);
  // Reads `count` values of type t: as doubles, as int64 (integers only), or
  // skipped when both outputs are null.
  Status values(uint64_t count, const LegacyType& t, const std::string& what,
                std::vector<double>* doubles, std::vector<int64_t>* ints);
  Status read_points();
  Status read_cells(const std::string& keyword, Cells& cells);
  Status read_cell_types();
  Status skip_metadata();
  Status read_attribute(const std::string& keyword, bool& stop);
  Status read_field(bool cell_mode, uint64_t expected_tuples);
  void consider_label(const std::string& name, const LegacyType& t, uint64_t components,
                      std::vector<int64_t>&& values);
  Status assemble(SurfaceFile& file);

  TextCursor cur_;
  const SurfaceReadOptions& options_;
  bool binary_ = false;
  bool unstructured_ = false;
  bool have_points_ = false;
  std::vector<double> points_;
  Cells verts_, lines_, polys_, strips_, ug_cells_;
  std::vector<int64_t> ug_types_;
  bool have_cells_ = false;
  // Attribute section: 0 none, 1 CELL_DATA, 2 POINT_DATA.
  int attribute_mode_ = 0;
  uint64_t attribute_count_ = 0;
  std::optional<LabelCandidate> label_;
  std::vector<std::string> warnings_;
};

Result<uint64_t> Reader::count_token(const char* what) {
  std::string_view t = cur_.next();
  int64_t v;
  if (!parse_int64(t, v) || v < 0) {
    return fail(std::string("expected ") + what + ", found " +
                (t.empty() ? std::string("the end of the file") : quoted(t)));
  }
  return uint64_t(v);
}

Result<const LegacyType*> Reader::type_token(const std::string& context) {
  std::string_view t = cur_.next();
  const LegacyType* type = find_type(t);
  if (!type) {
    return fail(context + " has data type " + quoted(t) +
                ", which is not a legacy VTK type (bit, unsigned_char, char, unsigned_short, "
                "short, unsigned_int, int, unsigned_long, long, vtktypeint64, vtktypeuint64, "
                "vtkIdType, float, double)");
  }
  return type;
}

Status Reader::values(uint64_t count, const LegacyType& t, const std::string& what,
                      std::vector<double>* doubles, std::vector<int64_t>* ints) {
  if (ints && t.kind == Kind::kFloat) {
    return fail(what + " has type " + std::string(t.name) + " but must hold integers");
  }
  if (binary_) {
    cur_.skip_line_end();
    uint64_t nbytes = t.kind == Kind::kBit ? count / 8 + (count % 8 != 0) : count;
    if (t.kind != Kind::kBit && count > cur_.remaining() / t.size) {
      return fail(what + ": the file ends at byte " + num(cur_.size()) + " but " + num(count) +
                  " values of " + num(t.size) + " bytes are announced (the data is cut short or " +
                  "the count is wrong)");
    }
    if (t.kind != Kind::kBit) nbytes = count * t.size;
    if (nbytes > cur_.remaining()) {
      return fail(what + ": the file ends at byte " + num(cur_.size()) + " but " + num(nbytes) +
                  " bytes of data are announced");
    }
    const uint8_t* p = cur_.data_at_pos();
    if (t.kind == Kind::kBit) {
      if (ints) {
        ints->resize(count);
        for (uint64_t i = 0; i < count; ++i) (*ints)[i] = (p[i / 8] >> (7 - i % 8)) & 1;
      }
      if (doubles) {
        doubles->resize(count);
        for (uint64_t i = 0; i < count; ++i) (*doubles)[i] = (p[i / 8] >> (7 - i % 8)) & 1;
      }
      cur_.skip(size_t(nbytes));
      return Status::Ok();
    }
    if (doubles) doubles->resize(count);
    if (ints) ints->resize(count);
    for (uint64_t i = 0; i < count && (doubles || ints); ++i, p += t.size) {
      uint64_t u = 0;
      for (size_t k = 0; k < t.size; ++k) u = u << 8 | p[k];  // big-endian
      if (t.kind == Kind::kFloat) {
        (*doubles)[i] = t.size == 4 ? double(float_from_bits(uint32_t(u))) : double_from_bits(u);
        continue;
      }
      int64_t v;
      if (t.kind == Kind::kSigned) {
        int shift = int(64 - 8 * t.size);
        v = int64_t(u << shift) >> shift;  // sign-extend
      } else {
        if (u > uint64_t(std::numeric_limits<int64_t>::max())) {
          return fail(what + ": value " + num(i + 1) + " is too large");
        }
        v = int64_t(u);
      }
      if (ints) (*ints)[i] = v;
      if (doubles) (*doubles)[i] = double(v);
    }
    cur_.skip(size_t(nbytes));
    return Status::Ok();
  }
  // ASCII: each value takes at least 2 bytes (a digit and a separator).
  if (count > cur_.remaining() / 2 + 1) {
    return fail(what + ": " + num(count) + " values are announced but the file has only " +
                num(cur_.remaining()) + " bytes left");
  }
  if (doubles) doubles->resize(count);
  if (ints) ints->resize(count);
  for (uint64_t i = 0; i < count; ++i) {
    std::string_view tok = cur_.next();
    if (tok.empty()) {
      return fail(what + ": the file ends after " + num(i) + " of " + num(count) + " values");
    }
    if (!doubles && !ints) continue;
    if (t.kind == Kind::kFloat || !ints) {
      double v;
      if (!parse_double(tok, v)) {
        return fail(what + ": value " + num(i + 1) + " " + quoted(tok) + " is not a number");
      }
      if (doubles) (*doubles)[i] = v;
    } else {
      int64_t v;
      if (!parse_int64(tok, v)) {
        return fail(what + ": value " + num(i + 1) + " " + quoted(tok) + " is not an integer");
      }
      (*ints)[i] = v;
      if (doubles) (*doubles)[i] = double(v);
    }
  }
  return Status::Ok();
}

Status Reader::read_points() {
  Result<uint64_t> n = count_token("the number of points after POINTS");
  if (!n.ok()) return n.status();
  if (n.value() > uint64_t(std::numeric_limits<int32_t>::max())) {
    return fail("file too large: " + num(n.value()) + " points");
  }
  Result<const LegacyType*> t = type_token("POINTS");
  if (!t.ok()) return t.status();
  Status st = values(3 * n.value(), *t.value(), "POINTS", &points_, nullptr);
  if (!st.ok()) return st;
  for (size_t i = 0; i < points_.size(); ++i) {
    if (!std::isfinite(points_[i])) {
      return Status::Error("legacy VTK: point " + num(i / 3) + " has a non-finite coordinate (" +
                           (std::isnan(points_[i]) ? "NaN" : "Inf") + "): the file is corrupt");
    }
  }
  have_points_ = true;
  return Status::Ok();
}

Status Reader::read_cells(const std::string& keyword, Cells& cells) {
  Result<uint64_t> a = count_token(("the number of cells after " + keyword).c_str());
  if (!a.ok()) return a.status();
  Result<uint64_t> b = count_token(("the size after " + keyword).c_str());
  if (!b.ok()) return b.status();
  cells = Cells{};
  if (upper(cur_.peek()) == "OFFSETS") {
    // VTK 5.1 layout: a = offsets count (cells + 1), b = connectivity size.
    cur_.next();
    Result<const LegacyType*> t = type_token(keyword + " OFFSETS");
    if (!t.ok()) return t.status();
    Status st = values(a.value(), *t.value(), keyword + " OFFSETS", nullptr, &cells.offsets);
    if (!st.ok()) return st;
    if (cur_.at_end() || upper(cur_.next()) != "CONNECTIVITY") {
      return fail(keyword + ": CONNECTIVITY expected after the OFFSETS");
    }
    t = type_token(keyword + " CONNECTIVITY");
    if (!t.ok()) return t.status();
    st = values(b.value(), *t.value(), keyword + " CONNECTIVITY", nullptr, &cells.connectivity);
    if (!st.ok()) return st;
    if (cells.offsets.empty()) cells.offsets.push_back(0);
    if (cells.offsets[0] != 0) return fail(keyword + ": the first offset is not 0");
    for (size_t i = 1; i < cells.offsets.size(); ++i) {
      if (cells.offsets[i] < cells.offsets[i - 1] ||
          cells.offsets[i] > int64_t(cells.connectivity.size())) {
        return fail(keyword + ": offsets out of range: cell " + num(i - 1) + " ends at " +
                    std::to_string(cells.offsets[i]) + " but the connectivity has " +
                    num(cells.connectivity.size()) + " entries");
      }
    }
    if (cells.offsets.back() != int64_t(cells.connectivity.size())) {
      warnings_.push_back("the last " +
                          num(cells.connectivity.size() - uint64_t(cells.offsets.back())) +
                          " entries of the " + keyword + " connectivity belong to no cell");
    }
    return Status::Ok();
  }
  // Classic layout: b integers, each cell its point count then its points.
  std::vector<int64_t> raw;
  const LegacyType* int_type = find_type("int");
  Status st = values(b.value(), *int_type, keyword, nullptr, &raw);
  if (!st.ok()) return st;
  if (a.value() > raw.size()) {
    return fail(keyword + " declares " + num(a.value()) + " cells in " + num(b.value()) +
                " values: impossible");
  }
  cells.offsets.reserve(a.value() + 1);
  cells.connectivity.reserve(raw.size() - a.value());
  size_t i = 0;
  for (uint64_t c = 0; c < a.value(); ++c) {
    if (i >= raw.size()) {
      return fail(keyword + " declares " + num(a.value()) + " cells but its " + num(b.value()) +
                  " values hold only " + num(c));
    }
    int64_t n = raw[i++];
    if (n < 0 || uint64_t(n) > raw.size() - i) {
      return fail(keyword + ": cell " + num(c) + " announces " + std::to_string(n) +
                  " points but only " + num(raw.size() - i) + " values are left");
    }
    cells.connectivity.insert(cells.connectivity.end(), raw.begin() + long(i),
                              raw.begin() + long(i + size_t(n)));
    i += size_t(n);
    cells.offsets.push_back(int64_t(cells.connectivity.size()));
  }
  if (i != raw.size()) {
    return fail(keyword + " declares " + num(a.value()) + " cells in " + num(b.value()) +
                " values but the cells use " + num(i));
  }
  return Status::Ok();
}

Status Reader::read_cell_types() {
  Result<uint64_t> n = count_token("the number of cells after CELL_TYPES");
  if (!n.ok()) return n.status();
  if (n.value() != ug_cells_.count()) {
    return fail("CELL_TYPES declares " + num(n.value()) + " cells but CELLS has " +
                num(ug_cells_.count()));
  }
  return values(n.value(), *find_type("int"), "CELL_TYPES", nullptr, &ug_types_);
}

Status Reader::skip_metadata() {
  // Text lines up to an empty line.
  cur_.rest_of_line();
  while (cur_.remaining() > 0) {
    std::string_view line = cur_.rest_of_line();
    if (std::all_of(line.begin(), line.end(), is_text_space)) break;
  }
  return Status::Ok();
}

void Reader::consider_label(const std::string& name, const LegacyType& t, uint64_t components,
                            std::vector<int64_t>&& values) {
  int rank = face_label_rank(name);
  if (rank < 0) return;
  if (t.kind == Kind::kFloat || components != 1) {
    warnings_.push_back("cell array '" + name + "' (" + std::string(t.name) + ", " +
                        num(components) + " components) is not used as face labels");
    return;
  }
  if (label_ && label_->rank <= rank) return;
  label_ = LabelCandidate{name, rank, std::move(values)};
}

Status Reader::read_field(bool cell_mode, uint64_t expected_tuples) {
  cur_.next();  // the field's name
  Result<uint64_t> k = count_token("the number of arrays of a FIELD");
  if (!k.ok()) return k.status();
  for (uint64_t a = 0; a < k.value(); ++a) {
    std::string name(cur_.next());
    if (name.empty()) return fail("the file ends inside a FIELD");
    if (name == "NULL_ARRAY") continue;
    Result<uint64_t> comps = count_token(("the components of FIELD array '" + name + "'").c_str());
    if (!comps.ok()) return comps.status();
    Result<uint64_t> tuples = count_token(("the tuples of FIELD array '" + name + "'").c_str());
    if (!tuples.ok()) return tuples.status();
    std::string_view type_name = cur_.peek();
    if (type_name == "string" || type_name == "utf8_string" || type_name == "variant") {
      return fail("FIELD array '" + name + "' has type " + std::string(type_name) +
                  ", which this reader does not skip");
    }
    Result<const LegacyType*> t = type_token("FIELD array '" + name + "'");
    if (!t.ok()) return t.status();
    if (comps.value() > 0 && tuples.value() > std::numeric_limits<uint64_t>::max() / comps.value())
      return fail("FIELD array '" + name + "' is impossibly large");
    const uint64_t count = comps.value() * tuples.value();
    bool wanted = cell_mode && face_label_rank(name) >= 0 && t.value()->kind != Kind::kFloat &&
                  comps.value() == 1;
    if (wanted && tuples.value() != expected_tuples) {
      return fail("cell array '" + name + "' has " + num(tuples.value()) +
                  " values but CELL_DATA declares " + num(expected_tuples));
    }
    std::vector<int64_t> v;
    Status st =
        values(count, *t.value(), "FIELD array '" + name + "'", nullptr, wanted ? &v : nullptr);
    if (!st.ok()) return st;
    if (cell_mode && face_label_rank(name) >= 0)
      consider_label(name, *t.value(), comps.value(), std::move(v));
    if (upper(cur_.peek()) == "METADATA") {
      cur_.next();
      skip_metadata();
    }
  }
  return Status::Ok();
}

// One attribute of CELL_DATA / POINT_DATA. Sets `stop` for a keyword that
// is not an attribute (the caller handles it).
Status Reader::read_attribute(const std::string& kw, bool& stop) {
  stop = false;
  const bool cell = attribute_mode_ == 1;
  const uint64_t n = attribute_count_;
  auto tuples = [&](uint64_t per) -> Result<uint64_t> {
    if (per > 0 && n > std::numeric_limits<uint64_t>::max() / per)
      return fail(kw + " is impossibly large");
    return n * per;
  };
  if (kw == "SCALARS") {
    std::string name(cur_.next());
    Result<const LegacyType*> t = type_token("SCALARS '" + name + "'");
    if (!t.ok()) return t.status();
    // Optional component count, on the same line.
    uint64_t comps = 1;
    std::string_view next = cur_.peek();
    int64_t c;
    if (parse_int64(next, c) && upper(next) != "LOOKUP_TABLE") {
      if (c < 1 || c > 4)
        return fail("SCALARS '" + name + "' has " + std::string(next) +
                    " components (1 to 4 allowed)");
      cur_.next();
      comps = uint64_t(c);
    }
    if (upper(cur_.peek()) == "LOOKUP_TABLE") {
      cur_.next();
      cur_.next();  // table name
    }
    bool wanted =
        cell && face_label_rank(name) >= 0 && t.value()->kind != Kind::kFloat && comps == 1;
    Result<uint64_t> count = tuples(comps);
    if (!count.ok()) return count.status();
    std::vector<int64_t> v;
    Status st =
        values(count.value(), *t.value(), "SCALARS '" + name + "'", nullptr, wanted ? &v : nullptr);
    if (!st.ok()) return st;
    if (cell) consider_label(name, *t.value(), comps, std::move(v));
  } else if (kw == "COLOR_SCALARS") {
    std::string name(cur_.next());
    Result<uint64_t> comps = count_token("the components of COLOR_SCALARS");
    if (!comps.ok()) return comps.status();
    Result<uint64_t> count = tuples(comps.value());
    if (!count.ok()) return count.status();
    // Binary: unsigned char; ASCII: floats in [0, 1].
    Status st = values(count.value(), *find_type(binary_ ? "unsigned_char" : "float"),
                       "COLOR_SCALARS '" + name + "'", nullptr, nullptr);
    if (!st.ok()) return st;
  } else if (kw == "LOOKUP_TABLE") {
    std::string name(cur_.next());
    Result<uint64_t> size = count_token("the size of LOOKUP_TABLE");
    if (!size.ok()) return size.status();
    if (size.value() > std::numeric_limits<uint64_t>::max() / 4)
      return fail("LOOKUP_TABLE is impossibly large");
    Status st = values(4 * size.value(), *find_type(binary_ ? "unsigned_char" : "float"),
                       "LOOKUP_TABLE '" + name + "'", nullptr, nullptr);
    if (!st.ok()) return st;
  } else if (kw == "VECTORS" || kw == "NORMALS" || kw == "TENSORS" || kw == "TENSORS6" ||
             kw == "GLOBAL_IDS" || kw == "PEDIGREE_IDS" || kw == "TEXTURE_COORDINATES") {
    std::string name(cur_.next());
    uint64_t per = kw == "TENSORS"                      ? 9
                   : kw == "TENSORS6"                   ? 6
                   : kw == "VECTORS" || kw == "NORMALS" ? 3
                                                        : 1;
    if (kw == "TEXTURE_COORDINATES") {
      Result<uint64_t> dim = count_token("the dimension of TEXTURE_COORDINATES");
      if (!dim.ok()) return dim.status();
      per = dim.value();
    }
    Result<const LegacyType*> t = type_token(kw + " '" + name + "'");
    if (!t.ok()) return t.status();
    Result<uint64_t> count = tuples(per);
    if (!count.ok()) return count.status();
    Status st = values(count.value(), *t.value(), kw + " '" + name + "'", nullptr, nullptr);
    if (!st.ok()) return st;
  } else if (kw == "FIELD") {
    Status st = read_field(cell, n);
    if (!st.ok()) return st;
  } else {
    stop = true;
    return Status::Ok();
  }
  if (upper(cur_.peek()) == "METADATA") {
    cur_.next();
    skip_metadata();
  }
  return Status::Ok();
}

Status Reader::assemble(SurfaceFile& file) {
  const uint64_t np = points_.size() / 3;
  file.points = std::move(points_);
  struct Block {
    const Cells* cells;
    bool strips;
    uint64_t label_base;
    const char* name;
  };
  std::vector<Block> blocks;
  uint64_t total_cells = 0;
  if (unstructured_) {
    if (ug_types_.size() != ug_cells_.count()) {
      return Status::Error("legacy VTK: the unstructured grid has CELLS but no CELL_TYPES");
    }
    blocks.push_back({&ug_cells_, false, 0, "CELLS"});
    total_cells = ug_cells_.count();
  } else {
    total_cells = verts_.count() + lines_.count() + polys_.count() + strips_.count();
    blocks.push_back({&polys_, false, verts_.count() + lines_.count(), "POLYGONS"});
    blocks.push_back(
        {&strips_, true, verts_.count() + lines_.count() + polys_.count(), "TRIANGLE_STRIPS"});
    if (verts_.count() + lines_.count() > 0) {
      file.warnings.push_back("the file has " + num(verts_.count()) + " vertex cells and " +
                              num(lines_.count()) +
                              " line cells; they were ignored (only polygons and strips make "
                              "the surface)");
    }
  }
  const std::vector<int64_t>* labels = nullptr;
  if (label_) {
    if (label_->values.size() != total_cells) {
      return Status::Error("legacy VTK: cell array '" + label_->name + "' has " +
                           num(label_->values.size()) + " values but the file has " +
                           num(total_cells) + " cells");
    }
    labels = &label_->values;
    for (int64_t v : *labels) {
      if (v < std::numeric_limits<int32_t>::min() || v > std::numeric_limits<int32_t>::max()) {
        file.warnings.push_back("cell array '" + label_->name +
                                "' has values beyond 32 bits: not used as face labels");
        labels = nullptr;
        break;
      }
    }
    if (labels) file.label_array = label_->name;
  }
  // Count triangles (and validate indices) before allocating.
  uint64_t ntri = 0;
  size_t skipped_small = 0, skipped_other = 0, dropped = 0;
  for (const Block& b : blocks) {
    for (size_t c = 0; c < b.cells->count(); ++c) {
      int64_t begin = b.cells->offsets[c], end = b.cells->offsets[c + 1];
      for (int64_t k = begin; k < end; ++k) {
        int64_t id = b.cells->connectivity[size_t(k)];
        if (id < 0 || uint64_t(id) >= np) {
          return Status::Error("legacy VTK: " + std::string(b.name) + " cell " + num(c) +
                               " refers to point " + std::to_string(id) + " but there are " +
                               num(np) + " points");
        }
      }
      ntri += polygon_triangles(size_t(end - begin));
    }
  }
  if (ntri > options_.max_triangles) {
    return Status::Error("file too large: more than " + num(options_.max_triangles) +
                         " triangles (the limit of this build)");
  }
  file.triangles.reserve(3 * ntri);
  if (labels) file.face_labels.reserve(ntri);
  for (const Block& b : blocks) {
    for (size_t c = 0; c < b.cells->count(); ++c) {
      int64_t begin = b.cells->offsets[c], end = b.cells->offsets[c + 1];
      const int64_t* ids = b.cells->connectivity.data() + begin;
      size_t n = size_t(end - begin);
      bool strip = b.strips;
      if (unstructured_) {
        int64_t type = ug_types_[c];
        // 5 triangle, 6 triangle strip, 7 polygon, 9 quad.
        if (type == 6) {
          strip = true;
        } else if (type != 5 && type != 7 && type != 9) {
          ++skipped_other;
          continue;
        }
      }
      if (n < 3) {
        ++skipped_small;
        continue;
      }
      size_t before = file.triangles.size();
      if (strip)
        dropped += append_strip(ids, n, file.triangles);
      else
        append_fan(ids, n, file.triangles);
      if (labels) {
        file.face_labels.insert(file.face_labels.end(), (file.triangles.size() - before) / 3,
                                int32_t((*labels)[size_t(b.label_base + c)]));
      }
    }
  }
  if (skipped_other > 0) {
    file.warnings.push_back(num(skipped_other) +
                            " cells that are not surface cells (vertices, lines, volume cells) "
                            "were ignored");
  }
  if (skipped_small > 0) {
    file.warnings.push_back(num(skipped_small) + " cells with fewer than 3 points were skipped");
  }
  if (dropped > 0) {
    file.warnings.push_back(num(dropped) +
                            " degenerate strip triangles (a repeated point) were skipped");
  }
  if (file.triangles.empty()) {
    return Status::Error(unstructured_ && skipped_other > 0
                             ? "legacy VTK unstructured grid without surface cells (it holds " +
                                   num(skipped_other) +
                                   " volume or line cells): extract its surface first"
                             : "legacy VTK file without any polygon or triangle strip");
  }
  return Status::Ok();
}

Result<SurfaceFile> Reader::read() {
  std::string_view first = cur_.rest_of_line();
  if (first.find("vtk") == std::string_view::npos) {
    return Status::Error("legacy VTK: the first line is not '# vtk DataFile Version x.y'");
  }
  cur_.rest_of_line();  // title
  std::string mode = upper(cur_.next());
  if (mode == "BINARY") {
    binary_ = true;
  } else if (mode != "ASCII") {
    return fail("expected ASCII or BINARY on the third line, found " + quoted(mode));
  }
  {
    std::string kw = upper(cur_.next());
    if (kw != "DATASET") return fail("expected DATASET, found " + quoted(kw));
    std::string type = upper(cur_.next());
    if (type == "UNSTRUCTURED_GRID") {
      unstructured_ = true;
    } else if (type != "POLYDATA") {
      return fail("DATASET " + type +
                  ": only POLYDATA surfaces (and unstructured grids of surface cells) are read");
    }
  }
  while (!cur_.at_end()) {
    size_t at = cur_.pos();
    std::string kw = upper(cur_.next());
    Status st;
    if (kw == "POINTS") {
      st = read_points();
    } else if (kw == "METADATA") {
      st = skip_metadata();
    } else if (!unstructured_ &&
               (kw == "POLYGONS" || kw == "TRIANGLE_STRIPS" || kw == "VERTICES" || kw == "LINES")) {
      Cells& c = kw == "POLYGONS"          ? polys_
                 : kw == "TRIANGLE_STRIPS" ? strips_
                 : kw == "VERTICES"        ? verts_
                                           : lines_;
      st = read_cells(kw, c);
      have_cells_ = true;
    } else if (unstructured_ && kw == "CELLS") {
      st = read_cells(kw, ug_cells_);
      have_cells_ = true;
    } else if (unstructured_ && kw == "CELL_TYPES") {
      st = read_cell_types();
    } else if (kw == "CELL_DATA" || kw == "POINT_DATA") {
      Result<uint64_t> n = count_token(("the count after " + kw).c_str());
      if (!n.ok()) return n.status();
      attribute_mode_ = kw == "CELL_DATA" ? 1 : 2;
      attribute_count_ = n.value();
      if (attribute_mode_ == 1) {
        uint64_t cells = unstructured_
                             ? ug_cells_.count()
                             : verts_.count() + lines_.count() + polys_.count() + strips_.count();
        if (n.value() != cells) {
          return fail("CELL_DATA declares " + num(n.value()) + " values but the file has " +
                      num(cells) + " cells");
        }
      }
    } else if (kw == "FIELD" && attribute_mode_ == 0) {
      st = read_field(false, 0);
    } else if (attribute_mode_ != 0) {
      bool stop = false;
      st = read_attribute(kw, stop);
      if (st.ok() && stop) {
        if (have_points_ && have_cells_) {
          warnings_.push_back("the rest of the file from byte " + num(at) + " (" + quoted(kw) +
                              ") was not read: not needed for the surface");
          break;
        }
        return fail("unknown keyword " + quoted(kw));
      }
    } else {
      if (have_points_ && have_cells_) {
        warnings_.push_back("the rest of the file from byte " + num(at) + " (" + quoted(kw) +
                            ") was not read: not needed for the surface");
        break;
      }
      return fail("unknown keyword " + quoted(kw));
    }
    if (!st.ok()) return st;
  }
  if (!have_points_) return Status::Error("legacy VTK file without POINTS");
  SurfaceFile file;
  Status st = assemble(file);
  if (!st.ok()) return st;
  file.warnings.insert(file.warnings.begin(), warnings_.begin(), warnings_.end());
  file.format = binary_ ? "legacy VTK (binary)" : "legacy VTK (ASCII)";
  file.format_id = "vtk";
  return file;
}

}  // namespace

Result<SurfaceFile> read_vtk_legacy(std::span<const uint8_t> bytes,
                                    const SurfaceReadOptions& options) {
  Reader reader(bytes, options);
  return reader.read();
}

}  // namespace vm
