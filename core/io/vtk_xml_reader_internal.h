// What the two files of the VTK XML PolyData reader (vtk_xml_reader.h)
// share: the array references the XML scan finds and the reader's state.
// vtk_xml_reader.cpp scans the XML (phase 1) and assembles the pieces
// (phase 3); vtk_xml_reader_arrays.cpp decodes the arrays (phase 2: ascii
// numbers, base64 or raw bytes, zlib blocks, byte order, data types). Not
// part of the API.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/io/read_surface.h"
#include "core/io/surface_file.h"
#include "core/io/value_type.h"
#include "core/io/xml_scanner.h"
#include "core/util/result.h"

namespace vm {
namespace vtk_xml_detail {

/// The ten numeric data types of VTK XML.
inline constexpr ValueType kTypes[] = {
    {"Int8", 1, ValueKind::kSigned},   {"UInt8", 1, ValueKind::kUnsigned},
    {"Int16", 2, ValueKind::kSigned},  {"UInt16", 2, ValueKind::kUnsigned},
    {"Int32", 4, ValueKind::kSigned},  {"UInt32", 4, ValueKind::kUnsigned},
    {"Int64", 8, ValueKind::kSigned},  {"UInt64", 8, ValueKind::kUnsigned},
    {"Float32", 4, ValueKind::kFloat}, {"Float64", 8, ValueKind::kFloat}};

/// n in decimal.
inline std::string num(uint64_t n) { return std::to_string(n); }

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

}  // namespace vtk_xml_detail
}  // namespace vm
