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
// Phases: scan the XML into array references (this file), then decode the
// arrays each piece needs (vtk_xml_reader_arrays.cpp) and assemble points,
// triangles and labels (this file).
#include "core/io/vtk_xml_reader.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/io/cells_to_triangles.h"
#include "core/io/text_scan.h"
#include "core/io/vtk_xml_reader_internal.h"
#include "core/io/xml_scanner.h"

namespace vm {
namespace vtk_xml_detail {
namespace {

bool parse_u64(std::string_view s, uint64_t& out) {
  while (!s.empty() && is_text_space(s.front())) s.remove_prefix(1);
  while (!s.empty() && is_text_space(s.back())) s.remove_suffix(1);
  int64_t v;
  if (!parse_int64(s, v) || v < 0) return false;
  out = uint64_t(v);
  return true;
}

}  // namespace

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

}  // namespace vtk_xml_detail

Result<SurfaceFile> read_vtk_xml(std::span<const uint8_t> bytes,
                                 const SurfaceReadOptions& options) {
  vtk_xml_detail::Reader reader(bytes, options);
  return reader.read();
}

}  // namespace vm
