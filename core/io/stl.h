// STL input and output (binary and ASCII).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "core/mesh/surface_mesh.h"
#include "core/util/result.h"

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

struct StlReadOptions {
  /// Inputs with more triangles are refused with a "too large" error, before
  /// any allocation proportional to the claimed size. 25M triangles is ~2 GB
  /// of working memory downstream, about the ceiling of a browser tab.
  size_t max_triangles = 25'000'000;
};

/// Parses an STL file held in memory. Detects binary vs ASCII by the binary
/// size law (84 + 50 n bytes), not by the "solid" prefix (binary files often
/// start with "solid" too). Errors: empty input, truncated binary, count in
/// header disagreeing with the size, malformed ASCII (with line number),
/// NaN/Inf coordinates (with triangle index), too many triangles.
Result<TriangleSoup> read_stl(std::span<const uint8_t> bytes, const StlReadOptions& options = {});

/// Serializes a surface as binary STL (normals computed from the triangles).
std::vector<uint8_t> write_stl_binary(const SurfaceMesh& mesh,
                                      const std::string& header = "vesselmesh");

}  // namespace vm
