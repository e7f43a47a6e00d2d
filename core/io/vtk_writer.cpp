// VTK XML UnstructuredGrid / PolyData writer ("VTK File Formats", XML
// section): the XML header lists every array with its offset into one
// appended raw block; each array there is a UInt64 byte count followed by
// the little-endian values, or, with zlib, VTK's compressed block layout
// (UInt64 header: block count, block size, size of the last partial block
// or 0, each block's compressed size; then the blocks, each zlib's
// compress2, at its fastest level, of up to 32 KiB of the values).
#include "core/io/vtk_writer.h"

#include <zlib.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>
#include <string_view>

namespace vm {
namespace {

static_assert(std::endian::native == std::endian::little,
              "the VTK writer copies values as little-endian bytes");

constexpr size_t kBlockBytes = 32768;  // vtkZLibDataCompressor's default block
/// zlib's fastest level: on a mesh's arrays (the bifurcation's 243,000
/// tetrahedra, 9.3 MB raw) it packs as tightly as the default level 6
/// (0.29 against 0.30 of the raw bytes) in a quarter of the time.
constexpr int kLevel = Z_BEST_SPEED;

void put_u64(std::string& out, uint64_t v) {
  char b[8];
  std::memcpy(b, &v, 8);
  out.append(b, 8);
}

/// One raw array of the appended data: its byte count, then its bytes.
void append_raw(std::string& out, const void* data, size_t bytes) {
  put_u64(out, bytes);
  if (bytes > 0) out.append(static_cast<const char*>(data), bytes);
}

/// The appended data block of zlib-compressed arrays, added one after the
/// other.
class Compressed {
 public:
  /// Appends `bytes` bytes at `data` as one array; returns its offset.
  uint64_t add(const void* data, size_t bytes) {
    const uint64_t offset = out_.size();
    const auto* p = static_cast<const char*>(data);
    const size_t blocks = (bytes + kBlockBytes - 1) / kBlockBytes;
    put_u64(out_, blocks);
    put_u64(out_, kBlockBytes);
    put_u64(out_, bytes % kBlockBytes);
    const size_t sizes_at = out_.size();
    out_.append(8 * blocks, '\0');
    std::string packed(compressBound(kBlockBytes), '\0');
    for (size_t b = 0; b < blocks; ++b) {
      const size_t n = std::min(kBlockBytes, bytes - b * kBlockBytes);
      uLongf packed_size = uLongf(packed.size());
      if (compress2(reinterpret_cast<Bytef*>(packed.data()), &packed_size,
                    reinterpret_cast<const Bytef*>(p + b * kBlockBytes), uLong(n),
                    kLevel) != Z_OK) {
        failed_ = true;
        packed_size = 0;
      }
      const uint64_t size = packed_size;
      std::memcpy(&out_[sizes_at + 8 * b], &size, 8);
      out_.append(packed.data(), packed_size);
    }
    return offset;
  }
  bool failed() const { return failed_; }
  const std::string& bytes() const { return out_; }

 private:
  bool failed_ = false;
  std::string out_;
};

/// One DataArray: its header attributes and a view of its values (which
/// must outlive assemble()).
struct ArrayRef {
  const char* type;  ///< "Int32", "Float64", ...
  const char* name;  ///< nullptr: no Name attribute (the points)
  int components;
  const void* data;
  size_t bytes;
  uint64_t offset = 0;  ///< set by assemble()
};

template <class T>
ArrayRef array_ref(const char* type, const char* name, int components,
                   const std::vector<T>& values) {
  return {type, name, components, values.data(), values.size() * sizeof(T)};
}

/// An element of the piece holding arrays: PointData, CellData, Points...
struct Section {
  const char* tag;
  std::vector<ArrayRef> arrays;
};

/// `text` as valid UTF-8 (a byte that starts no well-formed sequence becomes
/// '?'), control characters other than newline as spaces, and a space
/// between two '-' (XML comments must not hold "--").
std::string comment_text(std::string_view text) {
  std::string out;
  const auto* s = reinterpret_cast<const unsigned char*>(text.data());
  const size_t n = text.size();
  for (size_t i = 0; i < n;) {
    const unsigned char c = s[i];
    if (c < 0x80) {
      char ch = char(c);
      if ((c < 0x20 && c != '\n') || c == 0x7f) ch = ' ';
      if (ch == '-' && !out.empty() && out.back() == '-') out.push_back(' ');
      out.push_back(ch);
      ++i;
      continue;
    }
    // Length and the allowed range of the second byte (no overlong forms,
    // no surrogates, nothing above U+10FFFF).
    size_t len = 0;
    unsigned char lo = 0x80, hi = 0xbf;
    if (c >= 0xc2 && c <= 0xdf) {
      len = 2;
    } else if (c >= 0xe0 && c <= 0xef) {
      len = 3;
      if (c == 0xe0) lo = 0xa0;
      if (c == 0xed) hi = 0x9f;
    } else if (c >= 0xf0 && c <= 0xf4) {
      len = 4;
      if (c == 0xf0) lo = 0x90;
      if (c == 0xf4) hi = 0x8f;
    }
    bool ok = len > 0 && i + len <= n && s[i + 1] >= lo && s[i + 1] <= hi;
    for (size_t k = 2; ok && k < len; ++k) ok = s[i + k] >= 0x80 && s[i + k] <= 0xbf;
    if (!ok) {
      out.push_back('?');
      ++i;
      continue;
    }
    out.append(text.substr(i, len));
    i += len;
  }
  return out;
}

/// The whole file: declaration, comment, VTKFile, the dataset element with
/// one Piece (attributes `piece`), its sections, the appended data. The
/// arrays are appended in the reverse of their order in the header: meshio
/// (5.x-7.0) maps raw appended arrays back to their tags by searching the
/// header for offset="i" while it rewrites the offsets of the tags already
/// seen, and takes a rewritten tag for a later one whose offset it happens
/// to equal; with the later tags first in the data, the tag it searches for
/// comes before every rewritten one and is found first. Raw arrays are
/// copied once, straight into the file's text. Errors: zlib failed.
Result<std::string> assemble(const VtkWriteOptions& options, const char* type,
                             const std::string& piece, std::vector<Section> sections) {
  std::vector<ArrayRef*> order;  // the appended data's order
  for (auto s = sections.rbegin(); s != sections.rend(); ++s)
    for (auto a = s->arrays.rbegin(); a != s->arrays.rend(); ++a) order.push_back(&*a);
  Compressed compressed;
  uint64_t raw_bytes = 0;
  for (ArrayRef* a : order) {
    if (options.zlib) {
      a->offset = compressed.add(a->data, a->bytes);
    } else {
      a->offset = raw_bytes;
      raw_bytes += 8 + a->bytes;
    }
  }
  if (compressed.failed()) return Result<std::string>::Error(std::string(type) + ": zlib failed");
  std::string x = "<?xml version=\"1.0\"?>\n";
  if (!options.comment.empty()) x += "<!-- " + comment_text(options.comment) + " -->\n";
  x += "<VTKFile type=\"";
  x += type;
  x += "\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\"";
  if (options.zlib) x += " compressor=\"vtkZLibDataCompressor\"";
  x += ">\n  <";
  x += type;
  x += ">\n    <Piece " + piece + ">\n";
  for (const Section& s : sections) {
    x += "      <";
    x += s.tag;
    x += ">\n";
    for (const ArrayRef& a : s.arrays) {
      x += "        <DataArray type=\"";
      x += a.type;
      x += '"';
      if (a.name) {
        x += " Name=\"";
        x += a.name;
        x += '"';
      }
      if (a.components != 1) x += " NumberOfComponents=\"" + std::to_string(a.components) + '"';
      x += " format=\"appended\" offset=\"" + std::to_string(a.offset) + "\"/>\n";
    }
    x += "      </";
    x += s.tag;
    x += ">\n";
  }
  x += "    </Piece>\n  </";
  x += type;
  x += ">\n  <AppendedData encoding=\"raw\">\n   _";
  static constexpr std::string_view kTail = "\n  </AppendedData>\n</VTKFile>\n";
  if (options.zlib) {
    x.reserve(x.size() + compressed.bytes().size() + kTail.size());
    x += compressed.bytes();
  } else {
    x.reserve(x.size() + raw_bytes + kTail.size());
    for (const ArrayRef* a : order) append_raw(x, a->data, a->bytes);
  }
  x += kTail;
  return x;
}

bool in_range(const std::vector<int32_t>& v, size_t n) {
  for (int32_t i : v)
    if (i < 0 || size_t(i) >= n) return false;
  return true;
}

/// Cumulative cell sizes: the offsets array of a run of `count` cells of
/// `size` nodes, appended to `offsets`.
void add_offsets(std::vector<int64_t>& offsets, size_t count, int size) {
  int64_t at = offsets.empty() ? 0 : offsets.back();
  for (size_t i = 0; i < count; ++i) offsets.push_back(at += size);
}

std::vector<int32_t> one_based(size_t n) {
  std::vector<int32_t> ids(n);
  for (size_t i = 0; i < n; ++i) ids[i] = int32_t(i + 1);
  return ids;
}

}  // namespace

Result<std::string> write_vtu(const VolumeMesh& mesh, const VtkWriteOptions& options) {
  using R = Result<std::string>;
  const size_t np = mesh.num_vertices(), nt = mesh.num_tets(), npr = mesh.num_prisms();
  const size_t nc = nt + npr;
  if (mesh.points.size() % 3 || mesh.tets.size() % 4 || mesh.prisms.size() % 6)
    return R::Error("VTU: point or element array with a partial entry");
  if (!in_range(mesh.tets, np) || !in_range(mesh.prisms, np))
    return R::Error("VTU: an element refers to a vertex out of range");
  if (!(mesh.tet_region.empty() || mesh.tet_region.size() == nt) ||
      !(mesh.prism_region.empty() || mesh.prism_region.size() == npr))
    return R::Error("VTU: region tags are not one per element");
  if (np > size_t(INT32_MAX) || nc > size_t(INT32_MAX))
    return R::Error("VTU: too many points or cells for Int32 ids");

  // Tetrahedra as they are, then the wedges (without prisms, no copy).
  std::vector<int32_t> with_wedges;
  if (npr > 0) {
    with_wedges.reserve(mesh.tets.size() + mesh.prisms.size());
    with_wedges.insert(with_wedges.end(), mesh.tets.begin(), mesh.tets.end());
    for (size_t p = 0; p < npr; ++p) {
      int32_t w[6];
      vtk_wedge_nodes(&mesh.prisms[6 * p], w);
      with_wedges.insert(with_wedges.end(), w, w + 6);
    }
  }
  const std::vector<int32_t>& connectivity = npr > 0 ? with_wedges : mesh.tets;
  std::vector<int64_t> offsets;
  offsets.reserve(nc);
  add_offsets(offsets, nt, 4);
  add_offsets(offsets, npr, 6);
  std::vector<uint8_t> types(nt, uint8_t(VtkCellType::kTetra));
  types.resize(nc, uint8_t(VtkCellType::kWedge));
  std::vector<int32_t> region(nc, 0);
  std::copy(mesh.tet_region.begin(), mesh.tet_region.end(), region.begin());
  std::copy(mesh.prism_region.begin(), mesh.prism_region.end(), region.begin() + nt);
  for (int32_t& r : region) {
    if (r < 0 || r == INT32_MAX) return R::Error("VTU: region tag out of range");
    ++r;  // ModelRegionID counts from 1
  }

  const std::vector<int32_t> node_ids = one_based(np), element_ids = one_based(nc);
  std::vector<Section> sections;
  sections.push_back({"PointData", {array_ref("Int32", "GlobalNodeID", 1, node_ids)}});
  sections.push_back({"CellData",
                      {array_ref("Int32", "ModelRegionID", 1, region),
                       array_ref("Int32", "GlobalElementID", 1, element_ids)}});
  sections.push_back({"Points", {array_ref("Float64", nullptr, 3, mesh.points)}});
  sections.push_back(
      {"Cells",
       {array_ref("Int32", "connectivity", 1, connectivity),
        array_ref("Int64", "offsets", 1, offsets), array_ref("UInt8", "types", 1, types)}});
  const std::string piece =
      "NumberOfPoints=\"" + std::to_string(np) + "\" NumberOfCells=\"" + std::to_string(nc) + '"';
  return assemble(options, "UnstructuredGrid", piece, std::move(sections));
}

Result<std::string> write_vtp(const VtpSurface& s, const VtkWriteOptions& options) {
  using R = Result<std::string>;
  const size_t n = s.points.size() / 3, nc = s.num_cells();
  if (s.points.size() % 3 || s.triangles.size() % 3 || s.quads.size() % 4)
    return R::Error("VTP: point or cell array with a partial entry");
  if (s.face_ids.size() != nc) return R::Error("VTP: face ids are not one per cell");
  if (!s.global_node_ids.empty() && s.global_node_ids.size() != n)
    return R::Error("VTP: global node ids are not one per point");
  if (!s.global_element_ids.empty() && s.global_element_ids.size() != nc)
    return R::Error("VTP: global element ids are not one per cell");
  for (const auto& [name, values] : s.point_scalars) {
    if (values.size() != n) return R::Error("VTP: point data '" + name + "' is not one per point");
    if (name.empty() ||
        name.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                               "0123456789_") != std::string::npos)
      return R::Error("VTP: point data name '" + name + "' is not a plain word");
  }
  if (!in_range(s.triangles, n) || !in_range(s.quads, n))
    return R::Error("VTP: a cell refers to a point out of range");
  if (nc > size_t(INT32_MAX)) return R::Error("VTP: too many cells");

  // The used points, in their order.
  std::vector<int32_t> new_index(n, -1);
  for (int32_t v : s.triangles) new_index[v] = 0;
  for (int32_t v : s.quads) new_index[v] = 0;
  std::vector<double> points;
  std::vector<int32_t> node_ids;
  std::vector<std::vector<double>> scalars(s.point_scalars.size());
  int32_t used = 0;
  for (size_t v = 0; v < n; ++v) {
    if (new_index[v] < 0) continue;
    new_index[v] = used++;
    points.insert(points.end(), &s.points[3 * v], &s.points[3 * v] + 3);
    if (!s.global_node_ids.empty()) node_ids.push_back(s.global_node_ids[v]);
    for (size_t k = 0; k < scalars.size(); ++k) scalars[k].push_back(s.point_scalars[k].second[v]);
  }
  std::vector<int32_t> connectivity;
  connectivity.reserve(s.triangles.size() + s.quads.size());
  for (int32_t v : s.triangles) connectivity.push_back(new_index[v]);
  for (int32_t v : s.quads) connectivity.push_back(new_index[v]);
  std::vector<int64_t> offsets;
  offsets.reserve(nc);
  add_offsets(offsets, s.triangles.size() / 3, 3);
  add_offsets(offsets, s.quads.size() / 4, 4);

  std::vector<Section> sections;
  Section point_data{"PointData", {}};
  if (!s.global_node_ids.empty())
    point_data.arrays.push_back(array_ref("Int32", "GlobalNodeID", 1, node_ids));
  for (size_t k = 0; k < scalars.size(); ++k)
    point_data.arrays.push_back(
        array_ref("Float64", s.point_scalars[k].first.c_str(), 1, scalars[k]));
  if (!point_data.arrays.empty()) sections.push_back(std::move(point_data));
  Section cell_data{"CellData", {array_ref("Int32", "ModelFaceID", 1, s.face_ids)}};
  if (!s.global_element_ids.empty())
    cell_data.arrays.push_back(array_ref("Int32", "GlobalElementID", 1, s.global_element_ids));
  sections.push_back(std::move(cell_data));
  sections.push_back({"Points", {array_ref("Float64", nullptr, 3, points)}});
  sections.push_back({"Polys",
                      {array_ref("Int32", "connectivity", 1, connectivity),
                       array_ref("Int64", "offsets", 1, offsets)}});
  const std::string piece = "NumberOfPoints=\"" + std::to_string(used) +
                            "\" NumberOfVerts=\"0\" NumberOfLines=\"0\" NumberOfStrips=\"0\" "
                            "NumberOfPolys=\"" +
                            std::to_string(nc) + '"';
  return assemble(options, "PolyData", piece, std::move(sections));
}

Result<std::string> write_surface_vtp(const SurfaceMesh& mesh, std::span<const int32_t> face_ids,
                                      const VtkWriteOptions& options) {
  VtpSurface s;
  s.points = mesh.points;
  s.triangles = mesh.triangles;
  if (face_ids.empty())
    s.face_ids.assign(mesh.num_triangles(), 1);
  else
    s.face_ids.assign(face_ids.begin(), face_ids.end());
  return write_vtp(s, options);
}

}  // namespace vm
