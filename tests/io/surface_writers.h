// Writers of every surface format the readers accept, for generating test
// inputs in the tests themselves (no external files): VTK XML PolyData in
// each encoding, legacy VTK, OBJ, PLY, and zlib/gzip compression through
// the zlib library.
#pragma once

#include <zlib.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <type_traits>
#include <vector>

#include "core/mesh/surface_mesh.h"

namespace vm::testing {

using Bytes = std::vector<uint8_t>;

inline Bytes to_bytes(const std::string& s) { return Bytes(s.begin(), s.end()); }

inline std::string to_string(const Bytes& b) { return std::string(b.begin(), b.end()); }

inline std::string fmt17(double x) {
  char buf[40];
  std::snprintf(buf, sizeof(buf), "%.17g", x);
  return buf;
}

/// Standard base64 with padding.
inline std::string base64(const Bytes& b) {
  static const char* d = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string s;
  for (size_t i = 0; i < b.size(); i += 3) {
    uint32_t v = uint32_t(b[i]) << 16;
    if (i + 1 < b.size()) v |= uint32_t(b[i + 1]) << 8;
    if (i + 2 < b.size()) v |= b[i + 2];
    s += d[v >> 18 & 63];
    s += d[v >> 12 & 63];
    s += i + 1 < b.size() ? d[v >> 6 & 63] : '=';
    s += i + 2 < b.size() ? d[v & 63] : '=';
  }
  return s;
}

/// zlib stream of `b` (compress2, level 6).
inline Bytes zlib_compress(const Bytes& b) {
  uLongf n = compressBound(uLong(b.size()));
  Bytes out(n);
  if (compress2(out.data(), &n, b.data(), uLong(b.size()), 6) != Z_OK) return {};
  out.resize(n);
  return out;
}

/// gzip member of `b` (deflateInit2 with windowBits 16 + 15).
inline Bytes gzip(const Bytes& b) {
  z_stream z{};
  deflateInit2(&z, 6, Z_DEFLATED, 16 + 15, 8, Z_DEFAULT_STRATEGY);
  Bytes out(deflateBound(&z, uLong(b.size())) + 64);
  z.next_in = const_cast<Bytef*>(b.data());
  z.avail_in = uInt(b.size());
  z.next_out = out.data();
  z.avail_out = uInt(out.size());
  deflate(&z, Z_FINISH);
  out.resize(z.total_out);
  deflateEnd(&z);
  return out;
}

/// gzip member of `n` zero bytes (n a multiple of 1 MiB), deflated at level 9
/// from one 1 MiB buffer: about 1 KiB a MiB.
inline Bytes gzip_zeros(size_t n) {
  z_stream z{};
  deflateInit2(&z, 9, Z_DEFLATED, 16 + 15, 9, Z_DEFAULT_STRATEGY);
  Bytes zeros(1 << 20, 0), out(1 << 20), gz;
  for (size_t mb = 0, count = n >> 20; mb < count; ++mb) {
    z.next_in = zeros.data();
    z.avail_in = uInt(zeros.size());
    const int flush = mb + 1 == count ? Z_FINISH : Z_NO_FLUSH;
    do {
      z.next_out = out.data();
      z.avail_out = uInt(out.size());
      deflate(&z, flush);
      gz.insert(gz.end(), out.begin(), out.end() - z.avail_out);
    } while (z.avail_out == 0);
  }
  deflateEnd(&z);
  return gz;
}

/// Points, polygons, strips, per-cell labels: the content of a test file.
/// Cells are lists of point indices; labels (when not empty) hold one value
/// per cell in VTK order: verts, lines, polys, strips.
struct CellMesh {
  std::vector<double> points;
  std::vector<std::vector<int64_t>> verts, lines, polys, strips;
  std::vector<int32_t> labels;
};

/// Quads of open_tube(n, m)'s layout (ring j, index i -> j * n + i), one
/// quad (a, b, d, c) per tube quad: fanned from a they give exactly the
/// tube's triangles (a, b, d), (a, d, c).
inline std::vector<std::vector<int64_t>> tube_quads(int n, int m) {
  std::vector<std::vector<int64_t>> q;
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < n; ++i) {
      int64_t a = j * n + i, b = j * n + (i + 1) % n, c = a + n, d = b + n;
      q.push_back({a, b, d, c});
    }
  return q;
}

/// One triangle strip per ring of open_tube(n, m): c0 a0 c1 a1 ... c0 a0,
/// whose triangles are again exactly the tube's (a, d, c), (a, b, d).
inline std::vector<std::vector<int64_t>> tube_strips(int n, int m) {
  std::vector<std::vector<int64_t>> s;
  for (int j = 0; j < m; ++j) {
    std::vector<int64_t> strip;
    for (int i = 0; i <= n; ++i) {
      strip.push_back(int64_t((j + 1) * n + i % n));
      strip.push_back(int64_t(j * n + i % n));
    }
    s.push_back(strip);
  }
  return s;
}

inline CellMesh cells_of(const SurfaceMesh& m) {
  CellMesh c;
  c.points = m.points;
  for (size_t t = 0; t < m.num_triangles(); ++t)
    c.polys.push_back({m.triangles[3 * t], m.triangles[3 * t + 1], m.triangles[3 * t + 2]});
  return c;
}

// ---- VTK XML PolyData ----------------------------------------------------------

struct VtpStyle {
  enum Encoding { kAscii, kBinary, kAppendedRaw, kAppendedBase64 };
  Encoding encoding = kAscii;
  bool uint64_header = false;
  bool zlib = false;
  size_t block_size = 32768;
  bool big_endian = false;
  bool float64_points = true;
  bool int64_ids = true;
  /// Offsets as n + 1 beginnings starting at 0 instead of n ends.
  bool offsets_with_zero = false;
  /// Inline binary, no compression: header and data base64-encoded
  /// separately (as older VTK did) instead of together.
  bool separate_header_base64 = false;
  std::string label_name = "ModelFaceID";
};

class VtpWriter {
 public:
  explicit VtpWriter(const VtpStyle& s) : s_(s) {}

  /// Values as bytes in the file's byte order.
  template <class T>
  Bytes raw(const std::vector<T>& v) const {
    Bytes b(v.size() * sizeof(T));
    if (!v.empty()) std::memcpy(b.data(), v.data(), b.size());
    if (s_.big_endian)
      for (size_t i = 0; i < b.size(); i += sizeof(T))
        std::reverse(b.begin() + long(i), b.begin() + long(i + sizeof(T)));
    return b;
  }
  Bytes word(uint64_t v) const {
    if (s_.uint64_header) return raw(std::vector<uint64_t>{v});
    return raw(std::vector<uint32_t>{uint32_t(v)});
  }
  /// Header + data of a binary array, as the file holds it before any base64:
  /// two parts (header, data) so that base64 can encode them separately.
  std::pair<Bytes, Bytes> block(const Bytes& data) const {
    Bytes header, body;
    if (!s_.zlib) {
      header = word(data.size());
      body = data;
      return {header, body};
    }
    size_t nblocks = (data.size() + s_.block_size - 1) / s_.block_size;
    size_t last = data.size() % s_.block_size;
    std::vector<Bytes> comp;
    for (size_t b = 0; b < nblocks; ++b) {
      size_t from = b * s_.block_size, n = std::min(s_.block_size, data.size() - from);
      comp.push_back(
          zlib_compress(Bytes(data.begin() + long(from), data.begin() + long(from + n))));
    }
    auto append = [](Bytes& a, const Bytes& b) { a.insert(a.end(), b.begin(), b.end()); };
    append(header, word(nblocks));
    append(header, word(s_.block_size));
    append(header, word(last));
    for (const Bytes& c : comp) append(header, word(c.size()));
    for (const Bytes& c : comp) append(body, c);
    return {header, body};
  }

  /// A DataArray element; for appended arrays its data goes to appended_.
  template <class T>
  std::string array(const std::string& type, const std::string& name, int components,
                    const std::vector<T>& v) {
    std::string head =
        "<DataArray type=\"" + type + "\" Name=\"" + name + "\"" +
        (components > 1 ? " NumberOfComponents=\"" + std::to_string(components) + "\""
                        : std::string());
    if (s_.encoding == VtpStyle::kAscii) {
      std::string text;
      for (const T& x : v)
        text += (std::is_floating_point_v<T> ? fmt17(double(x)) : std::to_string(x)) + " ";
      return head + " format=\"ascii\">\n" + text + "\n</DataArray>\n";
    }
    auto [header, body] = block(raw(v));
    if (s_.encoding == VtpStyle::kBinary) {
      std::string text;
      if (s_.zlib || s_.separate_header_base64) {
        text = base64(header) + base64(body);
      } else {
        Bytes all = header;
        all.insert(all.end(), body.begin(), body.end());
        text = base64(all);
      }
      return head + " format=\"binary\">\n" + text + "\n</DataArray>\n";
    }
    size_t offset = appended_.size();
    if (s_.encoding == VtpStyle::kAppendedRaw) {
      appended_ += to_string(header) + to_string(body);
    } else if (s_.zlib) {
      appended_ += base64(header) + base64(body);
    } else {
      Bytes all = header;
      all.insert(all.end(), body.begin(), body.end());
      appended_ += base64(all);
    }
    return head + " format=\"appended\" offset=\"" + std::to_string(offset) + "\"/>\n";
  }

  std::string ids(const std::string& name, const std::vector<int64_t>& v) {
    if (s_.int64_ids) return array("Int64", name, 1, v);
    return array("Int32", name, 1, std::vector<int32_t>(v.begin(), v.end()));
  }

  std::string cells(const std::string& tag, const std::vector<std::vector<int64_t>>& c) {
    std::vector<int64_t> conn, off;
    if (s_.offsets_with_zero) off.push_back(0);
    for (const auto& cell : c) {
      conn.insert(conn.end(), cell.begin(), cell.end());
      off.push_back(int64_t(conn.size()));
    }
    std::string s = "<" + tag + ">\n";
    s += ids("connectivity", conn);  // in this order in the appended data
    s += ids("offsets", off);
    return s + "</" + tag + ">\n";
  }

  std::string piece(const CellMesh& m) {
    std::string p = "<Piece NumberOfPoints=\"" + std::to_string(m.points.size() / 3) +
                    "\" NumberOfVerts=\"" + std::to_string(m.verts.size()) + "\" NumberOfLines=\"" +
                    std::to_string(m.lines.size()) + "\" NumberOfStrips=\"" +
                    std::to_string(m.strips.size()) + "\" NumberOfPolys=\"" +
                    std::to_string(m.polys.size()) + "\">\n";
    p += "<PointData>\n</PointData>\n<CellData>\n";
    if (!m.labels.empty()) p += array("Int32", s_.label_name, 1, m.labels);
    p += "</CellData>\n<Points>\n";
    if (s_.float64_points)
      p += array("Float64", "Points", 3, m.points);
    else
      p += array("Float32", "Points", 3, std::vector<float>(m.points.begin(), m.points.end()));
    p += "</Points>\n";
    p += cells("Verts", m.verts);
    p += cells("Lines", m.lines);
    p += cells("Strips", m.strips);
    p += cells("Polys", m.polys);
    return p + "</Piece>\n";
  }

  std::string file(const std::vector<CellMesh>& pieces) {
    appended_.clear();
    std::string body;
    for (const CellMesh& m : pieces) body += piece(m);
    std::string x =
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"" +
        std::string(s_.big_endian ? "BigEndian" : "LittleEndian") + "\" header_type=\"" +
        (s_.uint64_header ? "UInt64" : "UInt32") + "\"" +
        (s_.zlib ? " compressor=\"vtkZLibDataCompressor\"" : "") + ">\n<PolyData>\n" + body +
        "</PolyData>\n";
    if (s_.encoding == VtpStyle::kAppendedRaw || s_.encoding == VtpStyle::kAppendedBase64) {
      x += std::string("<AppendedData encoding=\"") +
           (s_.encoding == VtpStyle::kAppendedRaw ? "raw" : "base64") + "\">\n   _" + appended_ +
           "\n</AppendedData>\n";
    }
    return x + "</VTKFile>\n";
  }

 private:
  VtpStyle s_;
  std::string appended_;
};

inline std::string vtp(const CellMesh& m, const VtpStyle& s = {}) {
  VtpWriter w(s);
  return w.file({m});
}

// ---- legacy VTK ---------------------------------------------------------------------

struct VtkStyle {
  bool binary = false;
  bool layout51 = false;      ///< OFFSETS / CONNECTIVITY (vtktypeint64)
  bool field_labels = false;  ///< labels as a FIELD array instead of SCALARS
  bool metadata = false;      ///< METADATA blocks after the arrays
  std::string label_name = "ModelFaceID";
};

inline std::string vtk_legacy(const CellMesh& m, const VtkStyle& s = {}) {
  std::string out = std::string("# vtk DataFile Version ") + (s.layout51 ? "5.1" : "3.0") +
                    "\ntest surface\n" + (s.binary ? "BINARY" : "ASCII") + "\nDATASET POLYDATA\n";
  auto be = [](auto v) {
    std::string b(sizeof(v), '\0');
    std::memcpy(b.data(), &v, sizeof(v));
    std::reverse(b.begin(), b.end());
    return b;
  };
  const size_t np = m.points.size() / 3;
  out += "POINTS " + std::to_string(np) + " double\n";
  for (size_t i = 0; i < m.points.size(); ++i)
    out += s.binary ? be(m.points[i]) : fmt17(m.points[i]) + (i % 3 == 2 ? "\n" : " ");
  if (s.binary) out += "\n";
  if (s.metadata) out += "METADATA\nINFORMATION 0\n\n";
  auto cells = [&](const std::string& kw, const std::vector<std::vector<int64_t>>& c) {
    if (c.empty()) return;
    size_t total = 0;
    for (const auto& cell : c) total += cell.size();
    if (s.layout51) {
      out += kw + " " + std::to_string(c.size() + 1) + " " + std::to_string(total) + "\n";
      out += "OFFSETS vtktypeint64\n";
      int64_t at = 0;
      out += s.binary ? be(at) : "0 ";
      for (const auto& cell : c) {
        at += int64_t(cell.size());
        out += s.binary ? be(at) : std::to_string(at) + " ";
      }
      out += "\nCONNECTIVITY vtktypeint64\n";
      for (const auto& cell : c)
        for (int64_t id : cell) out += s.binary ? be(id) : std::to_string(id) + " ";
      out += "\n";
      return;
    }
    out += kw + " " + std::to_string(c.size()) + " " + std::to_string(total + c.size()) + "\n";
    for (const auto& cell : c) {
      out += s.binary ? be(int32_t(cell.size())) : std::to_string(cell.size());
      for (int64_t id : cell) {
        if (!s.binary) out += ' ';
        out += s.binary ? be(int32_t(id)) : std::to_string(id);
      }
      if (!s.binary) out += "\n";
    }
    if (s.binary) out += "\n";
  };
  cells("VERTICES", m.verts);
  cells("LINES", m.lines);
  cells("POLYGONS", m.polys);
  cells("TRIANGLE_STRIPS", m.strips);
  const size_t ncells = m.verts.size() + m.lines.size() + m.polys.size() + m.strips.size();
  // Point data first (skipped by the reader), then the cell labels.
  out += "POINT_DATA " + std::to_string(np) + "\nNORMALS normals float\n";
  for (size_t i = 0; i < 3 * np; ++i) out += s.binary ? be(float(0.5)) : "0.5 ";
  out += "\n";
  if (!m.labels.empty()) {
    out += "CELL_DATA " + std::to_string(ncells) + "\n";
    out += "SCALARS Quality float 1\nLOOKUP_TABLE default\n";
    for (size_t i = 0; i < ncells; ++i) out += s.binary ? be(float(i)) : std::to_string(i) + " ";
    out += "\n";
    if (s.field_labels) {
      out += "FIELD FieldData 2\nOther 2 " + std::to_string(ncells) + " double\n";
      for (size_t i = 0; i < 2 * ncells; ++i) out += s.binary ? be(double(i)) : "1.5 ";
      out += "\n";
      if (s.metadata)
        out += "METADATA\nINFORMATION 1\nNAME L2_NORM_RANGE LOCATION vtkDataArray\nDATA 2 0 1\n\n";
      out += s.label_name + " 1 " + std::to_string(ncells) + " int\n";
    } else {
      out += "SCALARS " + s.label_name + " int 1\nLOOKUP_TABLE default\n";
    }
    for (int32_t l : m.labels) out += s.binary ? be(l) : std::to_string(l) + " ";
    out += "\n";
  }
  return out;
}

// ---- OBJ and PLY ------------------------------------------------------------------

/// OBJ text: `v` lines, then one group per distinct label (`g name`) with
/// its polygons, corners written as "a/a/a".
inline std::string obj(const CellMesh& m, const std::vector<std::string>& group_names = {}) {
  std::string s = "# test\nmtllib test.mtl\n";
  for (size_t i = 0; i < m.points.size(); i += 3)
    s += "v " + fmt17(m.points[i]) + " " + fmt17(m.points[i + 1]) + " " + fmt17(m.points[i + 2]) +
         "\n";
  s += "vn 0 0 1\nvt 0 0\ns off\n";
  for (size_t c = 0; c < m.polys.size(); ++c) {
    if (!group_names.empty() && !m.labels.empty() && (c == 0 || m.labels[c] != m.labels[c - 1]))
      s.append("g ").append(group_names[size_t(m.labels[c]) - 1]).append("\nusemtl red\n");
    s += "f";
    for (int64_t id : m.polys[c]) s.append(" ").append(std::to_string(id + 1)).append("/1/1");
    s += "\n";
  }
  return s;
}

enum class PlyFormat { kAscii, kLittle, kBig };

/// PLY with extra vertex properties (normals, colour), an extra element
/// before the faces (with a list property), the face list as uchar/int
/// and, when labels are given, an int face property named `label_name`.
inline std::string ply(const CellMesh& m, PlyFormat f, const std::string& label_name = "label") {
  const size_t np = m.points.size() / 3;
  std::string s = std::string("ply\nformat ") +
                  (f == PlyFormat::kAscii    ? "ascii"
                   : f == PlyFormat::kLittle ? "binary_little_endian"
                                             : "binary_big_endian") +
                  " 1.0\ncomment made by a test\n";
  s += "element vertex " + std::to_string(np) +
       "\nproperty float nx\nproperty double x\nproperty double y\nproperty double z\n"
       "property uchar red\nproperty list uchar int extra\n";
  s += "element edge 2\nproperty int vertex1\nproperty list uint8 int32 ids\n";
  s += "element face " + std::to_string(m.polys.size()) +
       "\nproperty uchar flags\nproperty list uchar int vertex_indices\n";
  if (!m.labels.empty()) s += "property int " + label_name + "\n";
  s += "property float quality\nend_header\n";
  auto put = [&](auto v) {
    if (f == PlyFormat::kAscii) {
      if constexpr (std::is_floating_point_v<decltype(v)>)
        s += fmt17(double(v)) + " ";
      else
        s += std::to_string(int64_t(v)) + " ";
      return;
    }
    std::string b(sizeof(v), '\0');
    std::memcpy(b.data(), &v, sizeof(v));
    if (f == PlyFormat::kBig) std::reverse(b.begin(), b.end());
    s += b;
  };
  auto eol = [&] {
    if (f == PlyFormat::kAscii) s += "\n";
  };
  for (size_t i = 0; i < np; ++i) {
    put(float(0.25));
    put(m.points[3 * i]);
    put(m.points[3 * i + 1]);
    put(m.points[3 * i + 2]);
    put(uint8_t(200));
    put(uint8_t(2));
    put(int32_t(7));
    put(int32_t(-8));
    eol();
  }
  for (int e = 0; e < 2; ++e) {
    put(int32_t(e));
    put(uint8_t(3));
    put(int32_t(1));
    put(int32_t(2));
    put(int32_t(3));
    eol();
  }
  for (size_t c = 0; c < m.polys.size(); ++c) {
    put(uint8_t(1));
    put(uint8_t(m.polys[c].size()));
    for (int64_t id : m.polys[c]) put(int32_t(id));
    if (!m.labels.empty()) put(int32_t(m.labels[c]));
    put(float(0.5));
    eol();
  }
  return s;
}

}  // namespace vm::testing
