// STL reader and writer. Binary layout: 80-byte header, uint32 triangle
// count, then per triangle 12 little-endian float32 (normal, 3 corners) and a
// uint16 attribute. ASCII: solid / facet normal / outer loop / 3 x vertex /
// endloop / endfacet / endsolid.
#include "core/io/stl.h"

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <string_view>

namespace vm {
namespace {

constexpr size_t kHeaderBytes = 84;
constexpr size_t kTriangleBytes = 50;

uint32_t read_u32(const uint8_t* p) {
  return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
}

float read_f32(const uint8_t* p) {
  uint32_t u = read_u32(p);
  float f;
  std::memcpy(&f, &u, 4);
  return f;
}

std::string trim(std::string_view s) {
  size_t b = 0, e = s.size();
  while (b < e && (s[b] == ' ' || s[b] == '\0' || s[b] == '\t')) ++b;
  while (e > b && (s[e - 1] == ' ' || s[e - 1] == '\0' || s[e - 1] == '\t' || s[e - 1] == '\r' ||
                   s[e - 1] == '\n'))
    --e;
  return std::string(s.substr(b, e - b));
}

std::string fmt_count(size_t n) { return std::to_string(n); }

Status check_finite(const std::vector<float>& coords, size_t first) {
  for (size_t i = first; i < coords.size(); ++i) {
    if (!std::isfinite(coords[i])) {
      return Status::Error("triangle " + fmt_count(i / 9 + 1) + " has a non-finite coordinate (" +
                           (std::isnan(coords[i]) ? "NaN" : "Inf") + "): the file is corrupt");
    }
  }
  return Status::Ok();
}

// ---- ASCII -----------------------------------------------------------------

class AsciiCursor {
 public:
  explicit AsciiCursor(std::span<const uint8_t> bytes)
      : p_(reinterpret_cast<const char*>(bytes.data())), end_(p_ + bytes.size()) {}

  /// Next whitespace-separated token; empty at end of input.
  std::string_view next() {
    while (p_ < end_ && is_space(*p_)) {
      if (*p_ == '\n') ++line_;
      ++p_;
    }
    const char* b = p_;
    while (p_ < end_ && !is_space(*p_)) ++p_;
    return std::string_view(b, p_ - b);
  }
  /// Rest of the current line (for solid names).
  std::string_view rest_of_line() {
    const char* b = p_;
    while (p_ < end_ && *p_ != '\n') ++p_;
    return std::string_view(b, p_ - b);
  }
  size_t line() const { return line_; }

 private:
  static bool is_space(char c) {
    return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v';
  }
  const char* p_;
  const char* end_;
  size_t line_ = 1;
};

// Plain decimals ([-+]digits[.digits][e[-+]digits], at most 19 significant
// digits): mantissa as an integer scaled by an exact power of ten. The
// double result is within an ulp or two of the true value, so the float
// stored is the correctly rounded one except in rare ties. Returns false for
// anything else (inf, nan, hex, long mantissas), which strtod then handles.
bool parse_decimal_fast(std::string_view tok, double& out) {
  static constexpr double kPow10[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                      1e8,  1e9,  1e10, 1e11, 1e12, 1e13, 1e14, 1e15,
                                      1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};
  size_t i = 0, n = tok.size();
  bool negative = false;
  if (i < n && (tok[i] == '-' || tok[i] == '+')) negative = tok[i++] == '-';
  uint64_t mantissa = 0;
  int digits = 0, scale = 0;
  bool any = false;
  for (; i < n && tok[i] >= '0' && tok[i] <= '9'; ++i, any = true) {
    if (mantissa == 0 && tok[i] == '0') continue;
    if (++digits > 19) return false;
    mantissa = mantissa * 10 + uint64_t(tok[i] - '0');
  }
  if (i < n && tok[i] == '.') {
    for (++i; i < n && tok[i] >= '0' && tok[i] <= '9'; ++i, any = true) {
      --scale;
      if (mantissa == 0 && tok[i] == '0') continue;
      if (++digits > 19) return false;
      mantissa = mantissa * 10 + uint64_t(tok[i] - '0');
    }
  }
  if (!any) return false;
  if (i < n && (tok[i] == 'e' || tok[i] == 'E')) {
    ++i;
    bool eneg = false;
    if (i < n && (tok[i] == '-' || tok[i] == '+')) eneg = tok[i++] == '-';
    if (i == n) return false;
    int e = 0;
    for (; i < n && tok[i] >= '0' && tok[i] <= '9'; ++i) {
      if (e > 1000) return false;
      e = e * 10 + (tok[i] - '0');
    }
    scale += eneg ? -e : e;
  }
  if (i != n || scale < -22 || scale > 22) return false;
  double v = double(mantissa);
  v = scale < 0 ? v / kPow10[-scale] : v * kPow10[scale];
  out = negative ? -v : v;
  return true;
}

bool parse_float(std::string_view tok, float& out) {
  double fast;
  if (parse_decimal_fast(tok, fast)) {
    out = static_cast<float>(fast);
    return true;
  }
  char buf[64];
  if (tok.empty() || tok.size() >= sizeof(buf)) return false;
  std::memcpy(buf, tok.data(), tok.size());
  buf[tok.size()] = '\0';
  char* endp = nullptr;
  double v = std::strtod(buf, &endp);
  if (endp != buf + tok.size()) return false;
  out = static_cast<float>(v);
  return true;
}

bool iequals(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i) {
    char x = a[i], y = b[i];
    if (x >= 'A' && x <= 'Z') x = char(x - 'A' + 'a');
    if (x != y) return false;
  }
  return true;
}

Result<TriangleSoup> read_ascii(std::span<const uint8_t> bytes, const StlReadOptions& options) {
  TriangleSoup soup;
  soup.ascii = true;
  AsciiCursor cur(bytes);
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
    float dummy;
    for (int k = 0; k < 3; ++k) {
      if (!parse_float(cur.next(), dummy)) return fail("bad normal component");
    }
    if (!expect("outer") || !expect("loop")) return fail("expected 'outer loop'");
    for (int v = 0; v < 3; ++v) {
      if (!expect("vertex")) return fail("expected 'vertex'");
      for (int k = 0; k < 3; ++k) {
        float x;
        std::string_view t = cur.next();
        if (!parse_float(t, x)) {
          return fail("bad vertex coordinate '" + std::string(t.substr(0, 32)) + "'");
        }
        soup.coords.push_back(x);
      }
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

bool looks_like_text(std::span<const uint8_t> bytes) {
  size_t n = std::min<size_t>(bytes.size(), 512);
  for (size_t i = 0; i < n; ++i) {
    uint8_t c = bytes[i];
    if (c == 0 || (c < 32 && c != '\n' && c != '\r' && c != '\t')) return false;
  }
  return true;
}

bool starts_with_solid(std::span<const uint8_t> bytes) {
  size_t i = 0;
  while (i < bytes.size() &&
         (bytes[i] == ' ' || bytes[i] == '\t' || bytes[i] == '\r' || bytes[i] == '\n'))
    ++i;
  return bytes.size() - i >= 5 &&
         iequals(std::string_view(reinterpret_cast<const char*>(bytes.data() + i), 5), "solid");
}

}  // namespace

Result<TriangleSoup> read_stl(std::span<const uint8_t> bytes, const StlReadOptions& options) {
  if (bytes.empty()) return Result<TriangleSoup>::Error("empty file");
  bool binary_law = false;
  uint64_t count = 0;
  if (bytes.size() >= kHeaderBytes) {
    count = read_u32(bytes.data() + 80);
    binary_law = kHeaderBytes + kTriangleBytes * count == bytes.size();
  }
  bool text = looks_like_text(bytes);
  if (!binary_law && text) {
    if (!starts_with_solid(bytes)) {
      return Result<TriangleSoup>::Error("not an STL file: text that does not start with 'solid'");
    }
    Result<TriangleSoup> r = read_ascii(bytes, options);
    if (!r.ok()) return r;
    if (r.value().num_triangles() == 0) {
      return Result<TriangleSoup>::Error("ASCII STL contains no facet");
    }
    Status finite = check_finite(r.value().coords, 0);
    if (!finite.ok()) return finite;
    return r;
  }
  if (bytes.size() < kHeaderBytes) {
    return Result<TriangleSoup>::Error("not an STL file: " + fmt_count(bytes.size()) +
                                       " bytes is shorter than a binary STL header (84 bytes)");
  }
  if (count > options.max_triangles) {
    return Result<TriangleSoup>::Error("file too large: the header announces " + fmt_count(count) +
                                       " triangles, the limit of this build is " +
                                       fmt_count(options.max_triangles));
  }
  uint64_t need = kHeaderBytes + kTriangleBytes * count;
  TriangleSoup soup;
  if (bytes.size() < need) {
    uint64_t have = (bytes.size() - kHeaderBytes) / kTriangleBytes;
    return Result<TriangleSoup>::Error("truncated binary STL: the header announces " +
                                       fmt_count(count) + " triangles (" + fmt_count(need) +
                                       " bytes) but the file has " + fmt_count(bytes.size()) +
                                       " bytes (room for " + fmt_count(have) + " triangles)");
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
  const uint8_t* p = bytes.data() + kHeaderBytes;
  float* out = soup.coords.data();
  for (uint64_t t = 0; t < count; ++t, p += kTriangleBytes, out += 9) {
    for (int k = 0; k < 9; ++k) out[k] = read_f32(p + 12 + 4 * k);
  }
  Status finite = check_finite(soup.coords, 0);
  if (!finite.ok()) return finite;
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
