// Format sniffing: the reader is chosen by the first bytes of the content
// (magic numbers and keywords of each format), never by a file name, so a
// misnamed file is still read and bytes of no known format get a message
// listing what is supported instead of a misleading STL error.
#include "core/io/read_surface.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <string_view>

#include "core/geom/vec3.h"
#include "core/io/float_bits.h"
#include "core/io/inflate.h"
#include "core/io/obj_reader.h"
#include "core/io/ply_reader.h"
#include "core/io/stl.h"
#include "core/io/text_scan.h"
#include "core/io/vtk_legacy_reader.h"
#include "core/io/vtk_xml_reader.h"

namespace vm {
namespace {

constexpr const char* kSupported =
    "binary or ASCII STL, VTK XML PolyData .vtp, legacy VTK .vtk, Wavefront .obj, PLY; any of "
    "them gzip-compressed";

enum class Format { kVtkXml, kVtkLegacy, kPly, kStl, kObj, kUnknown };

/// How much of a file's start sniff_start reads (looks_like_obj's 64 KiB).
constexpr size_t kSniffBytes = 65536;

std::string_view as_text(std::span<const uint8_t> b) {
  return std::string_view(reinterpret_cast<const char*>(b.data()), b.size());
}

bool istarts_with(std::string_view s, std::string_view prefix) {
  if (s.size() < prefix.size()) return false;
  for (size_t i = 0; i < prefix.size(); ++i) {
    char a = s[i], b = prefix[i];
    if (a >= 'A' && a <= 'Z') a = char(a - 'A' + 'a');
    if (b >= 'A' && b <= 'Z') b = char(b - 'A' + 'a');
    if (a != b) return false;
  }
  return true;
}

// The text after an optional UTF-8 byte order mark and leading whitespace.
std::string_view content_start(std::span<const uint8_t> bytes) {
  std::string_view s = as_text(bytes);
  if (s.starts_with("\xEF\xBB\xBF")) s.remove_prefix(3);
  while (!s.empty() && is_text_space(s.front())) s.remove_prefix(1);
  return s;
}

// A binary STL that does not match the size law (truncated, or with bytes
// after its triangles): binary content, a positive count, and triangles
// whose normals are zero or unit vectors and whose corners are finite, as
// STL writers make them (random bytes almost never pass).
bool looks_like_binary_stl(std::span<const uint8_t> b) {
  if (b.size() < 84 + 50) return false;
  uint32_t count = load_u32le(b.data() + 80);
  if (count == 0) return false;
  size_t check = std::min<size_t>(std::min<size_t>((b.size() - 84) / 50, count), 8);
  for (size_t t = 0; t < check; ++t) {
    const uint8_t* p = b.data() + 84 + 50 * t;
    double n2 = 0;
    for (int k = 0; k < 12; ++k) {
      float x = load_f32le(p + 4 * k);
      if (!std::isfinite(x) || std::fabs(x) > 1e30f) return false;
      if (k < 3) n2 += double(x) * x;
    }
    if (n2 != 0 && std::fabs(n2 - 1) > 1e-3) return false;
  }
  return true;
}

bool is_obj_keyword(std::string_view w) {
  static constexpr std::string_view kKeywords[] = {"v", "vn",     "vt",     "vp", "f", "g",
                                                   "o", "mtllib", "usemtl", "s",  "l", "p"};
  for (std::string_view k : kKeywords)
    if (w == k) return true;
  return false;
}

// Text whose first statements (up to 5 lines that are neither empty nor
// comments, within the first 64 KiB) are all OBJ keywords.
bool looks_like_obj(std::span<const uint8_t> b) {
  std::string_view s = as_text(b.first(std::min<size_t>(b.size(), kSniffBytes)));
  if (s.starts_with("\xEF\xBB\xBF")) s.remove_prefix(3);
  for (char c : s) {
    unsigned char u = static_cast<unsigned char>(c);
    if (u == 0 || (u < 32 && !is_text_space(c))) return false;
  }
  int statements = 0;
  size_t pos = 0;
  while (pos < s.size() && statements < 5) {
    size_t e = s.find('\n', pos);
    bool last = e == std::string_view::npos;
    std::string_view line = s.substr(pos, last ? std::string_view::npos : e - pos);
    pos = last ? s.size() : e + 1;
    size_t i = 0;
    while (i < line.size() && is_text_space(line[i])) ++i;
    if (i == line.size() || line[i] == '#') continue;
    size_t j = i;
    while (j < line.size() && !is_text_space(line[j])) ++j;
    if (!is_obj_keyword(line.substr(i, j - i))) return false;
    ++statements;
  }
  return statements > 0;
}

// The format by the start of the content, the binary STL size law aside: no
// more than the first kSniffBytes are read, and no more than the first 16
// after the whitespace content_start skips, except by looks_like_binary_stl
// (the first 484).
Format sniff_start(std::span<const uint8_t> bytes) {
  std::string_view s = content_start(bytes);
  if (s.starts_with("<?xml") || s.starts_with("<VTKFile")) return Format::kVtkXml;
  if (istarts_with(s, "# vtk DataFile")) return Format::kVtkLegacy;
  if (s.starts_with("ply") && s.size() > 3 && (s[3] == '\n' || s[3] == '\r')) return Format::kPly;
  if (istarts_with(s, "solid")) return Format::kStl;
  if (looks_like_binary_stl(bytes)) return Format::kStl;
  if (looks_like_obj(bytes)) return Format::kObj;
  return Format::kUnknown;
}

Format sniff(std::span<const uint8_t> bytes) {
  // The binary STL size law first: its 80-byte header is free text (it may
  // start like another format), and text never satisfies the law (bytes
  // 80-83 of text read as a count above 0x09090909, a file of gigabytes).
  if (bytes.size() >= 84 && 84 + 50 * uint64_t(load_u32le(bytes.data() + 80)) == bytes.size())
    return Format::kStl;
  return sniff_start(bytes);
}

std::string hint(std::span<const uint8_t> b) {
  std::string_view s = as_text(b);
  if (s.starts_with("\x89PNG")) return " (a PNG image)";
  if (s.starts_with("\xFF\xD8\xFF")) return " (a JPEG image)";
  if (s.starts_with("%PDF")) return " (a PDF document)";
  if (s.starts_with("PK\x03\x04")) return " (a ZIP archive: extract the surface file from it)";
  if (s.size() >= 132 && s.substr(128, 4) == "DICM") {
    return " (a DICOM image: segment it and export the surface first)";
  }
  const size_t zeros = s.find_first_not_of('\0');
  if (zeros == std::string_view::npos) return " (all zero bytes)";
  if (zeros >= 16) return " (its first " + std::to_string(zeros) + " bytes are zero)";
  return "";
}

// The first bytes, quoted, and what they are when known.
std::string quoted_start(std::span<const uint8_t> bytes) {
  std::string s = "'";  // appended, not "'" + ...: GCC 12 warns falsely on that (-Wrestrict)
  s += printable_prefix(bytes, 16);
  s += "'";
  s += hint(bytes);
  return s;
}

bool is_gzip(std::span<const uint8_t> b) { return b.size() >= 2 && b[0] == 0x1f && b[1] == 0x8b; }

const char* const kGzipPrefix = "gzip-compressed file: ";
const char* const kCompressedTwice =
    "it holds another gzip stream (compressed twice): decompress it once first";

/// Refuses a gzip file from the first kSniffBytes of its content when the
/// whole content would be refused anyway, so that a large stream of no
/// surface format is not inflated whole: another gzip stream, bytes of no
/// format sniff() knows (the binary STL size law ruled out by the header's
/// count: below the prefix's length or above max_decompressed_bytes), a binary
/// STL header announcing more than max_triangles. Ok when the whole content
/// must be read to tell (shorter than kSniffBytes, nearly all whitespace),
/// and when that part cannot be inflated (the whole inflate then says why).
Status sniff_gzip_start(std::span<const uint8_t> gz, const SurfaceReadOptions& options) {
  Result<std::vector<uint8_t>> head = inflate_gzip_prefix(gz, kSniffBytes);
  if (!head.ok()) return Status::Ok();
  const std::vector<uint8_t>& b = head.value();
  if (is_gzip(b)) return Status::Error(std::string(kGzipPrefix) + kCompressedTwice);
  if (b.size() < kSniffBytes || content_start(b).size() < 16) return Status::Ok();
  const Format format = sniff_start(b);
  const uint64_t count = load_u32le(b.data() + 80);
  if (format == Format::kStl && !istarts_with(content_start(b), "solid") &&
      count > options.max_triangles) {
    return Status::Error(std::string(kGzipPrefix) +
                         "file too large: the binary STL header announces " +
                         std::to_string(count) + " triangles, the limit of this build is " +
                         std::to_string(options.max_triangles));
  }
  const uint64_t law_size = 84 + 50 * count;
  if (format != Format::kUnknown ||
      (law_size >= b.size() && law_size <= options.max_decompressed_bytes)) {
    return Status::Ok();
  }
  return Status::Error(std::string(kGzipPrefix) + "its first " + std::to_string(b.size()) +
                       " decompressed bytes are not the start of a surface file this tool reads (" +
                       kSupported + "): they " +
                       (as_text(b).find_first_not_of('\0') == std::string_view::npos
                            ? std::string("are all zero bytes")
                            : "start with " + quoted_start(b)) +
                       "; the rest was not decompressed. Open the surface file itself (a "
                       "download or export that failed can leave such a file)");
}

Result<SurfaceFile> read_stl_file(std::span<const uint8_t> bytes,
                                  const SurfaceReadOptions& options) {
  StlReadOptions o;
  o.max_triangles = options.max_triangles;
  Result<TriangleSoup> soup = read_stl(bytes, o);
  if (!soup.ok()) return soup.status();
  SurfaceFile file;
  file.soup = std::move(soup.value());
  // An ASCII STL's indexed doubles go where every indexed format's go; the
  // soup keeps its `ascii` flag and header, without coordinates.
  file.points = std::move(file.soup.points);
  file.triangles = std::move(file.soup.triangles);
  file.soup.points = {};
  file.soup.triangles = {};
  file.warnings = file.soup.warnings;
  file.format = file.soup.ascii ? "ASCII STL" : "binary STL";
  file.format_id = "stl";
  return file;
}

Result<SurfaceFile> read_sniffed(std::span<const uint8_t> bytes,
                                 const SurfaceReadOptions& options) {
  switch (sniff(bytes)) {
    case Format::kVtkXml:
      return read_vtk_xml(bytes, options);
    case Format::kVtkLegacy:
      return read_vtk_legacy(bytes, options);
    case Format::kPly:
      return read_ply(bytes, options);
    case Format::kStl:
      return read_stl_file(bytes, options);
    case Format::kObj:
      return read_obj(bytes, options);
    case Format::kUnknown:
      break;
  }
  return Status::Error(std::string("not a surface file this tool reads (") + kSupported +
                       "): it starts with " + quoted_start(bytes));
}

/// Whether the bytes start with a UTF-16 byte order mark (FF FE: little
/// endian, FE FF: big endian).
bool is_utf16(std::span<const uint8_t> b) {
  return b.size() >= 2 && ((b[0] == 0xFF && b[1] == 0xFE) || (b[0] == 0xFE && b[1] == 0xFF));
}

/// UTF-16 text (after its byte order mark) as one byte a character: ASCII
/// as is, anything else '?' (the formats' keywords and numbers are ASCII).
std::vector<uint8_t> utf16_to_ascii(std::span<const uint8_t> b) {
  const bool little = b[0] == 0xFF;
  std::vector<uint8_t> out;
  out.reserve(b.size() / 2);
  for (size_t i = 2; i + 1 < b.size(); i += 2) {
    const unsigned unit = little ? b[i] | (b[i + 1] << 8) : (b[i] << 8) | b[i + 1];
    out.push_back(unit < 128 ? uint8_t(unit) : uint8_t('?'));
  }
  return out;
}

}  // namespace

Status check_surface_size(std::span<const uint8_t> prefix, uint64_t file_size,
                          const SurfaceReadOptions& options) {
  const auto gib = [](uint64_t n) { return number_text(double(n) / double(uint64_t(1) << 30), 3); };
  if (file_size > options.max_file_bytes) {
    return Status::Error("file too large: " + gib(file_size) + " GiB, the limit of this build is " +
                         gib(options.max_file_bytes) + " GiB");
  }
  if (prefix.size() >= 84 && !is_gzip(prefix)) {
    const uint64_t count = load_u32le(prefix.data() + 80);
    if (84 + 50 * count == file_size && count > options.max_triangles) {
      return Status::Error("file too large: the binary STL header announces " +
                           std::to_string(count) + " triangles, the limit of this build is " +
                           std::to_string(options.max_triangles));
    }
  }
  return Status::Ok();
}

Result<SurfaceFile> read_surface(std::span<const uint8_t> bytes,
                                 const SurfaceReadOptions& options) {
  if (bytes.empty()) return Status::Error("empty file");
  if (is_utf16(bytes)) {
    const std::vector<uint8_t> text = utf16_to_ascii(bytes);
    Result<SurfaceFile> r = read_surface(text, options);
    if (!r.ok()) return Status::Error("UTF-16 text file: " + r.message());
    r.value().warnings.push_back("the file is UTF-16 text; it was read as ASCII");
    return r;
  }
  if (!is_gzip(bytes)) return read_sniffed(bytes, options);
  const std::string prefix = kGzipPrefix;
  if (Status start = sniff_gzip_start(bytes, options); !start.ok()) return start;
  std::vector<std::string> gzip_warnings;
  Result<std::vector<uint8_t>> inner =
      inflate_gzip(bytes, options.max_decompressed_bytes, &gzip_warnings);
  if (!inner.ok()) return Status::Error(prefix + inner.message());
  if (inner.value().empty()) return Status::Error(prefix + "it holds an empty file");
  if (is_gzip(inner.value())) {
    return Status::Error(prefix + kCompressedTwice);
  }
  Result<SurfaceFile> r = read_sniffed(inner.value(), options);
  if (!r.ok()) return Status::Error(prefix + r.message());
  SurfaceFile& file = r.value();
  file.gzip = true;
  file.format = "gzip, " + file.format;
  file.warnings.insert(file.warnings.end(), gzip_warnings.begin(), gzip_warnings.end());
  return r;
}

}  // namespace vm
