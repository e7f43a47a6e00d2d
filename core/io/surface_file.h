// A surface as a file gives it, before welding and repair: the common result
// of every surface reader (STL, VTK XML PolyData, legacy VTK, OBJ, PLY, any of
// them gzip-compressed). The reader is chosen by the bytes, not by the file
// name (read_surface.h).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "core/mesh/triangle_soup.h"

namespace vm {

/// One surface file's contents. Exactly one of `soup.coords` (binary STL:
/// unwelded corner triples, float as in the file) and `points`/`triangles`
/// (every other format, ASCII STL included: the file's own indexed points,
/// as doubles) is non-empty.
struct SurfaceFile {
  /// STL only: `ascii` and `header`; binary STL: `coords`, 9 floats per
  /// triangle (see triangle_soup.h). Its `points`/`triangles` are always
  /// empty (an ASCII STL's are moved to the fields below).
  TriangleSoup soup;
  /// Indexed formats: 3 doubles per point (x y z), 3 point indices per
  /// triangle, in the file's orientation. Polygons are split into triangles
  /// by a fan from their first point, triangle strips into their triangles
  /// (alternate ones reversed so that all keep the strip's orientation).
  std::vector<double> points;
  std::vector<int32_t> triangles;
  /// Per triangle (same order as `triangles`, or as the soup's triangles),
  /// the face label of the polygon it came from, read from an integer cell
  /// array (VTK: `ModelFaceID`, else `CapID`, `CellEntityIds`, `FaceID`,
  /// `RegionId`, in this order of preference; OBJ: the group `g`/`o` number,
  /// counting from 1 in order of appearance). Empty when the file has none.
  std::vector<int32_t> face_labels;
  /// Name of the array the labels came from ("ModelFaceID", "CellEntityIds",
  /// "obj groups", ...); empty without labels.
  std::string label_array;
  /// The name of a label where the file gives one (OBJ group names; VTK
  /// field data naming faces), label -> name.
  std::vector<std::pair<int32_t, std::string>> face_names;
  /// What was read, for messages and reports: "binary STL", "ASCII STL",
  /// "VTK XML PolyData (appended raw, zlib)", "legacy VTK (binary)",
  /// "Wavefront OBJ", "PLY (binary big endian)", prefixed "gzip, " when the
  /// file was gzip-compressed.
  std::string format;
  /// Short id of the format: "stl", "vtp", "vtk", "obj", "ply".
  std::string format_id;
  bool gzip = false;  ///< the bytes were gzip-compressed
  /// Tolerated oddities (unsupported cells skipped, trailing bytes...).
  std::vector<std::string> warnings;

  size_t num_triangles() const {
    return soup.coords.empty() ? triangles.size() / 3 : soup.num_triangles();
  }
};

}  // namespace vm
