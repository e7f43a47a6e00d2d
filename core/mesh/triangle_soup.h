// A triangle soup: a surface as an STL file stores it, before welding. The
// STL reader (core/io/stl.h) makes it, weld() (weld.h) turns it into an
// indexed SurfaceMesh; it lives here, beside the mesh types, so that the
// mesh module needs nothing from io.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace vm {

/// An STL as read, before welding. Binary: an unwelded soup, every triangle
/// with its own three float corners, as the file stores them. ASCII: every
/// coordinate as the double its text gives (correctly rounded; full
/// precision, so that a model far from the origin keeps its detail), indexed:
/// only corners whose three numbers are bit-identical (-0 as +0) share a
/// point. Exactly one of `coords` and `points`/`triangles` is non-empty;
/// weld the first with weld(soup), the second with weld(points, triangles)
/// (weld.h; weld(soup) reads `coords` only).
struct TriangleSoup {
  /// Binary STL: 9 * num_triangles() floats (x y z of corners a, b, c).
  std::vector<float> coords;
  /// ASCII STL: 3 doubles (x y z) per distinct corner position, in order of
  /// first appearance in the file.
  std::vector<double> points;
  /// ASCII STL: 3 indices into `points` per triangle (corners a, b, c).
  std::vector<int32_t> triangles;
  bool ascii = false;  ///< true when read from an ASCII STL
  std::string header;  ///< binary header (80 bytes, trimmed) or ASCII solid name
  /// Tolerated oddities (e.g. trailing bytes after a binary STL).
  std::vector<std::string> warnings;
  size_t num_triangles() const { return coords.empty() ? triangles.size() / 3 : coords.size() / 9; }
};

}  // namespace vm
