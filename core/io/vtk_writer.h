// VTK XML writers (VTK file formats, "XML File Formats": UnstructuredGrid
// .vtu and PolyData .vtp) with binary appended raw data: the volume mesh and
// its boundary faces as svFSI, SimVascular, ParaView and meshio read them.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "core/mesh/surface_mesh.h"
#include "core/mesh/volume_mesh.h"
#include "core/util/result.h"

namespace vm {

struct VtkWriteOptions {
  /// Compress every array with zlib in VTK's block layout
  /// (compressor="vtkZLibDataCompressor", 32 KiB blocks); else raw.
  bool zlib = false;
  /// Written as an XML comment right after the XML declaration (e.g. the
  /// provenance); may hold several lines. Empty: no comment. "--" inside is
  /// written "- -" (XML forbids it in comments).
  std::string comment;
};

/// VTK cell type codes used here (vtkCellType.h).
enum class VtkCellType : uint8_t { kTriangle = 5, kQuad = 9, kTetra = 10, kWedge = 13 };

/// The VTK wedge of a VolumeMesh prism p (Gmsh order: bottom 0-1-2
/// counterclockwise seen from the top 3-4-5): VTK wants the first
/// triangle's right-hand normal pointing away from the second, so both
/// triangles are reversed: (p0, p2, p1, p3, p5, p4). Tetrahedra need no
/// change: VTK's tetra, like VolumeMesh's, has ((b-a)x(c-a)).(d-a) > 0.
inline void vtk_wedge_nodes(const int32_t* p, int32_t* out) {
  out[0] = p[0];
  out[1] = p[2];
  out[2] = p[1];
  out[3] = p[3];
  out[4] = p[5];
  out[5] = p[4];
}

/// The volume `mesh` as a VTK XML UnstructuredGrid (header_type UInt64,
/// little endian, all arrays in one `<AppendedData encoding="raw">`).
/// Points: all of mesh.points, Float64 x 3. Cells: the tetrahedra (VTK_TETRA,
/// node order unchanged) then the prisms (VTK_WEDGE, vtk_wedge_nodes);
/// connectivity Int32, offsets Int64, types UInt8. Cell data: ModelRegionID
/// (Int32, region tag + 1), GlobalElementID (Int32, 1-based cell number in
/// this order); point data: GlobalNodeID (Int32, 1-based point number).
/// The mesh's triangles and quads are not written. Errors: a vertex index
/// out of range, region arrays whose size is neither 0 (all region 0) nor
/// one per element, a negative region tag.
Result<std::string> write_vtu(const VolumeMesh& mesh, const VtkWriteOptions& options = {});

/// A surface of polygons for write_vtp: views of points (and their global
/// ids) shared with a volume mesh, and the cells of this surface.
struct VtpSurface {
  /// 3 doubles per point, indexed by triangles and quads. Points no cell
  /// uses are dropped from the file (the others keep their order).
  std::span<const double> points;
  /// 3 point indices per triangle, 4 per quad (a cycle); written as polys,
  /// the triangles first.
  std::vector<int32_t> triangles, quads;
  /// ModelFaceID (Int32) per cell: per triangle, then per quad. Required.
  std::vector<int32_t> face_ids;
  /// Optional (empty: no array): GlobalNodeID (Int32) per point of
  /// `points` (kept with the points they belong to, so a surface keeps its
  /// volume's numbering), and GlobalElementID (Int32) per cell (triangles,
  /// then quads).
  std::span<const int32_t> global_node_ids;
  std::vector<int32_t> global_element_ids;
  /// Optional named point data (Float64, one value per point of `points`,
  /// kept with the points they belong to), e.g. {"radius", R} (a name must
  /// be a plain word: letters, digits, '_').
  std::vector<std::pair<std::string, std::span<const double>>> point_scalars;

  size_t num_cells() const { return triangles.size() / 3 + quads.size() / 4; }
};

/// The surface `s` as a VTK XML PolyData (same encoding as write_vtu): the
/// used points (Float64 x 3), polys (connectivity Int32, offsets Int64),
/// cell data ModelFaceID and, when given, GlobalElementID, point data
/// GlobalNodeID and the point scalars when given. Errors: array sizes inconsistent (partial
/// cells, a face id or global id count that is not one per cell or per
/// point), a point index out of range.
Result<std::string> write_vtp(const VtpSurface& s, const VtkWriteOptions& options = {});

/// A triangle surface as a VTK XML PolyData with one ModelFaceID per
/// triangle (`face_ids`; empty: all 1), as SimVascular writes its models.
/// Errors: those of write_vtp (face ids not one per triangle).
Result<std::string> write_surface_vtp(const SurfaceMesh& mesh, std::span<const int32_t> face_ids,
                                      const VtkWriteOptions& options = {});

}  // namespace vm
