// STL reader and writer. Binary layout: 80-byte header, uint32 triangle
// count, then per triangle 12 little-endian float32 (normal, 3 corners) and a
// uint16 attribute. ASCII: solid / facet normal / outer loop / 3 x vertex /
// endloop / endfacet / endsolid.
#include "core/io/stl.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string_view>

#include "core/io/float_bits.h"
#include "core/io/text_scan.h"
#include "core/util/index_hash_table.h"
#include "core/util/parallel.h"

namespace vm {
namespace {

constexpr size_t kHeaderBytes = 84;
constexpr size_t kTriangleBytes = 50;

std::string trim(std::string_view s) {
  size_t b = 0, e = s.size();
  while (b < e && (s[b] == ' ' || s[b] == '\0' || s[b] == '\t')) ++b;
  while (e > b && (s[e - 1] == ' ' || s[e - 1] == '\0' || s[e - 1] == '\t' || s[e - 1] == '\r' ||
                   s[e - 1] == '\n'))
    --e;
  return std::string(s.substr(b, e - b));
}

std::string fmt_count(size_t n) { return std::to_string(n); }

/// Message for a NaN or infinite coordinate of triangle t (0-based).
std::string non_finite_text(size_t t, double x) {
  return "triangle " + fmt_count(t + 1) + " has a non-finite coordinate (" +
         (std::isnan(x) ? "NaN" : "Inf") + "): the file is corrupt";
}

// ---- ASCII -----------------------------------------------------------------

uint64_t double_bits(double x) {
  if (x == 0.0) x = 0.0;  // -0 and +0 are the same point
  uint64_t u;
  std::memcpy(&u, &x, 8);
  return u;
}

/// The distinct corner positions of an ASCII STL in order of first
/// appearance: corners whose three doubles are bit-identical (-0 as +0)
/// get one index. Appends to `points` (3 doubles a point). An open-addressing
/// table of point indices (load <= 1/2, grown by doubling) behind a small
/// cache of recently seen corners: a vertex recurs in about six triangles,
/// usually close together in the file.
class CornerIndex {
 public:
  explicit CornerIndex(std::vector<double>& points) : points_(points) {
    slots_.assign(1 << 12, -1);
    recent_.assign(kRecent, Recent{{0, 0, 0}, -1});
  }

  /// The index of point p (3 doubles), added if new; -1 when there would be
  /// more than 2^31 - 1 points.
  int32_t add(const double* p) {
    const uint64_t h = hash_of(p);
    Recent& r = recent_[h >> (64 - kRecentBits)];
    if (r.id >= 0 && r.p[0] == p[0] && r.p[1] == p[1] && r.p[2] == p[2]) return r.id;
    size_t j = h & (slots_.size() - 1);
    while (slots_[j] >= 0) {
      if (same(size_t(slots_[j]), p)) return remember(r, p, slots_[j]);
      j = (j + 1) & (slots_.size() - 1);
    }
    const size_t id = points_.size() / 3;
    if (id >= size_t(std::numeric_limits<int32_t>::max())) return -1;
    slots_[j] = int32_t(id);
    points_.insert(points_.end(), p, p + 3);
    if (2 * (id + 1) > slots_.size()) grow();
    return remember(r, p, int32_t(id));
  }

 private:
  static constexpr int kRecentBits = 12;
  static constexpr size_t kRecent = size_t(1) << kRecentBits;

  /// A recently seen point with its coordinates, so that a hit reads no
  /// other memory.
  struct Recent {
    double p[3];
    int32_t id;  // -1: empty
  };

  static int32_t remember(Recent& r, const double* p, int32_t id) {
    r = Recent{{p[0], p[1], p[2]}, id};
    return id;
  }

  /// Whether stored point i equals p (-0 equals +0).
  bool same(size_t i, const double* p) const {
    const double* q = &points_[3 * i];
    return q[0] == p[0] && q[1] == p[1] && q[2] == p[2];
  }

  static uint64_t hash_of(const double* p) {
    return IndexHashTable::mix((double_bits(p[0]) * 0x9E3779B97F4A7C15ULL) ^
                               (double_bits(p[1]) * 0xC2B2AE3D27D4EB4FULL) ^
                               (double_bits(p[2]) * 0x165667B19E3779F9ULL));
  }

  void grow() {
    slots_.assign(2 * slots_.size(), -1);
    const size_t mask = slots_.size() - 1;
    for (size_t i = 0; i < points_.size() / 3; ++i) {
      size_t j = hash_of(&points_[3 * i]) & mask;
      while (slots_[j] >= 0) j = (j + 1) & mask;
      slots_[j] = int32_t(i);
    }
  }

  std::vector<double>& points_;
  std::vector<int32_t> slots_;  // point index or -1, power-of-two size
  std::vector<Recent> recent_;  // kRecent slots, by hash
};

bool iequals(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i) {
    char x = a[i], y = b[i];
    if (x >= 'A' && x <= 'Z') x = char(x - 'A' + 'a');
    if (x != y) return false;
  }
  return true;
}

/// Reads an ASCII STL into soup.points / soup.triangles, each coordinate the
/// correctly rounded double of its text.
Result<TriangleSoup> read_ascii(std::span<const uint8_t> bytes, const StlReadOptions& options) {
  TriangleSoup soup;
  soup.ascii = true;
  CornerIndex corners(soup.points);
  TextCursor cur(bytes);
  auto fail = [&](const std::string& what) {
    return Result<TriangleSoup>::Error("ASCII STL, line " + std::to_string(cur.line()) + ": " +
                                       what);
  };
  auto expect = [&](std::string_view word) -> bool { return iequals(cur.next(), word); };
  std::string_view tok = cur.next();
  if (!iequals(tok, "solid")) return fail("expected 'solid'");
  soup.header = trim(cur.rest_of_line());
  int solids = 1;
  while (true) {
    tok = cur.next();
    if (tok.empty()) {
      return fail("unexpected end of file (missing 'endsolid')");
    }
    if (iequals(tok, "endsolid")) {
      cur.rest_of_line();
      tok = cur.next();
      if (tok.empty()) break;
      if (!iequals(tok, "solid")) {
        return fail("unexpected '" + std::string(tok.substr(0, 32)) + "' after 'endsolid'");
      }
      cur.rest_of_line();
      ++solids;
      continue;
    }
    if (!iequals(tok, "facet")) {
      return fail("expected 'facet' or 'endsolid', found '" + std::string(tok.substr(0, 32)) + "'");
    }
    if (!expect("normal")) return fail("expected 'normal' after 'facet'");
    double dummy;
    for (int k = 0; k < 3; ++k) {
      if (!parse_double(cur.next(), dummy)) return fail("bad normal component");
    }
    if (!expect("outer") || !expect("loop")) return fail("expected 'outer loop'");
    for (int v = 0; v < 3; ++v) {
      if (!expect("vertex")) return fail("expected 'vertex'");
      double p[3];
      for (int k = 0; k < 3; ++k) {
        std::string_view t = cur.next();
        if (!parse_double(t, p[k])) {
          return fail("bad vertex coordinate '" + std::string(t.substr(0, 32)) + "'");
        }
        if (!std::isfinite(p[k])) {
          return Result<TriangleSoup>::Error(non_finite_text(soup.triangles.size() / 3, p[k]));
        }
      }
      const int32_t id = corners.add(p);
      if (id < 0) return fail("more than 2^31 distinct vertices");
      soup.triangles.push_back(id);
    }
    if (!expect("endloop")) {
      return fail("expected 'endloop' (facets must have exactly 3 vertices)");
    }
    if (!expect("endfacet")) return fail("expected 'endfacet'");
    if (soup.num_triangles() > options.max_triangles) {
      return Result<TriangleSoup>::Error("file too large: more than " +
                                         fmt_count(options.max_triangles) +
                                         " triangles (the limit of this build)");
    }
  }
  if (solids > 1) {
    soup.warnings.push_back("ASCII STL holds " + std::to_string(solids) +
                            " solids; they were read as one surface");
  }
  return soup;
}

bool is_text_byte(uint8_t c) { return c >= 32 || c == '\n' || c == '\r' || c == '\t'; }

/// Whether the first 512 bytes are all text.
bool looks_like_text(std::span<const uint8_t> bytes) {
  const size_t n = std::min<size_t>(bytes.size(), 512);
  for (size_t i = 0; i < n; ++i)
    if (!is_text_byte(bytes[i])) return false;
  return true;
}

/// Whether the bytes (after an optional UTF-8 byte order mark) read as an
/// ASCII STL: "solid", a name line that may hold any byte but a line end
/// (writers put NUL, form feeds or binary junk in it), then text up to 512
/// bytes on whose first word is "facet" or "endsolid".
bool looks_like_ascii_stl(std::span<const uint8_t> bytes) {
  size_t i = 0;
  while (i < bytes.size() &&
         (bytes[i] == ' ' || bytes[i] == '\t' || bytes[i] == '\r' || bytes[i] == '\n'))
    ++i;
  if (bytes.size() - i < 5 ||
      !iequals(std::string_view(reinterpret_cast<const char*>(bytes.data() + i), 5), "solid")) {
    return false;
  }
  const size_t name_end = std::min<size_t>(bytes.size(), i + 1024);
  while (i < name_end && bytes[i] != '\n' && bytes[i] != '\r') ++i;
  if (i == name_end) return false;
  const size_t end = std::min<size_t>(bytes.size(), i + 512);
  for (size_t k = i; k < end; ++k)
    if (!is_text_byte(bytes[k])) return false;
  TextCursor cur(bytes.subspan(i, end - i));
  const std::string_view first = cur.next();
  return iequals(first, "facet") || iequals(first, "endsolid");
}

}  // namespace

Result<TriangleSoup> read_stl(std::span<const uint8_t> bytes, const StlReadOptions& options) {
  if (bytes.empty()) return Result<TriangleSoup>::Error("empty file");
  bool binary_law = false;
  uint64_t count = 0;
  if (bytes.size() >= kHeaderBytes) {
    count = load_u32le(bytes.data() + 80);
    binary_law = kHeaderBytes + kTriangleBytes * count == bytes.size();
  }
  if (bytes.size() >= 3 && bytes[0] == 0xEF && bytes[1] == 0xBB && bytes[2] == 0xBF &&
      !binary_law) {
    bytes = bytes.subspan(3);  // a UTF-8 byte order mark before "solid"
  }
  if (!binary_law && looks_like_ascii_stl(bytes)) {
    Result<TriangleSoup> r = read_ascii(bytes, options);
    if (!r.ok()) return r;
    if (r.value().num_triangles() == 0) {
      return Result<TriangleSoup>::Error("ASCII STL contains no facet");
    }
    return r;
  }
  if (bytes.size() < kHeaderBytes) {
    return Result<TriangleSoup>::Error("not an STL file: " + fmt_count(bytes.size()) +
                                       " bytes is shorter than a binary STL header (84 bytes)");
  }
  uint64_t need = kHeaderBytes + kTriangleBytes * count;
  TriangleSoup soup;
  if (bytes.size() < need && !looks_like_text(bytes)) {
    uint64_t have = (bytes.size() - kHeaderBytes) / kTriangleBytes;
    return Result<TriangleSoup>::Error("truncated binary STL: the header announces " +
                                       fmt_count(count) + " triangles (" + fmt_count(need) +
                                       " bytes) but the file has " + fmt_count(bytes.size()) +
                                       " bytes (room for " + fmt_count(have) + " triangles)");
  }
  if (bytes.size() < need) {
    return Result<TriangleSoup>::Error(
        "not an STL file: text that is not an ASCII STL ('solid NAME', then 'facet normal' "
        "lines; it starts with '" +
        printable_prefix(bytes, 24) + "')");
  }
  if (count > options.max_triangles) {
    return Result<TriangleSoup>::Error("file too large: the header announces " + fmt_count(count) +
                                       " triangles, the limit of this build is " +
                                       fmt_count(options.max_triangles));
  }
  if (count == 0) {
    return Result<TriangleSoup>::Error("binary STL contains no triangle");
  }
  if (bytes.size() > need) {
    soup.warnings.push_back("binary STL has " + fmt_count(bytes.size() - need) +
                            " bytes after its " + fmt_count(count) +
                            " triangles; they were ignored");
  }
  soup.header = trim(std::string_view(reinterpret_cast<const char*>(bytes.data()), 80));
  soup.coords.resize(9 * count);
  // Coordinates with all exponent bits set (Inf, NaN), counted.
  const size_t non_finite =
      parallel_sum<size_t>(size_t(count), size_t(1) << 16, [&](size_t begin, size_t end) {
        size_t n = 0;
        for (size_t t = begin; t < end; ++t) {
          const uint8_t* p = bytes.data() + kHeaderBytes + kTriangleBytes * t + 12;
          float* out = soup.coords.data() + 9 * t;
          for (int k = 0; k < 9; ++k) {
            const uint32_t u = load_u32le(p + 4 * k);
            n += (u & 0x7F800000u) == 0x7F800000u;
            out[k] = float_from_bits(u);
          }
        }
        return n;
      });
  if (non_finite) {
    for (size_t i = 0; i < soup.coords.size(); ++i)
      if (!std::isfinite(soup.coords[i]))
        return Status::Error(non_finite_text(i / 9, soup.coords[i]));
  }
  return soup;
}

std::vector<uint8_t> write_stl_binary(const SurfaceMesh& mesh, const std::string& header) {
  size_t n = mesh.num_triangles();
  std::vector<uint8_t> out(kHeaderBytes + kTriangleBytes * n, 0);
  // A binary header must not start with "solid" (readers would take it for
  // ASCII).
  std::string h = header.rfind("solid", 0) == 0 ? "_" + header : header;
  std::memcpy(out.data(), h.data(), std::min<size_t>(h.size(), 80));
  auto put_u32 = [&](size_t at, uint32_t v) {
    for (int k = 0; k < 4; ++k) out[at + k] = uint8_t(v >> (8 * k));
  };
  auto put_f32 = [&](size_t at, float f) {
    uint32_t u;
    std::memcpy(&u, &f, 4);
    put_u32(at, u);
  };
  put_u32(80, uint32_t(n));
  for (size_t t = 0; t < n; ++t) {
    const double* a = &mesh.points[3 * mesh.triangles[3 * t]];
    const double* b = &mesh.points[3 * mesh.triangles[3 * t + 1]];
    const double* c = &mesh.points[3 * mesh.triangles[3 * t + 2]];
    double u[3], v[3], nrm[3];
    for (int k = 0; k < 3; ++k) u[k] = b[k] - a[k], v[k] = c[k] - a[k];
    nrm[0] = u[1] * v[2] - u[2] * v[1];
    nrm[1] = u[2] * v[0] - u[0] * v[2];
    nrm[2] = u[0] * v[1] - u[1] * v[0];
    double len = std::sqrt(nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]);
    size_t at = kHeaderBytes + kTriangleBytes * t;
    for (int k = 0; k < 3; ++k) put_f32(at + 4 * k, len > 0 ? nrm[k] / len : 0);
    const double* corners[3] = {a, b, c};
    for (int v2 = 0; v2 < 3; ++v2)
      for (int k = 0; k < 3; ++k) put_f32(at + 12 + 12 * v2 + 4 * k, float(corners[v2][k]));
  }
  return out;
}

}  // namespace vm
