// STL input and output (binary and ASCII).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "core/mesh/surface_mesh.h"
#include "core/mesh/triangle_soup.h"
#include "core/util/result.h"

namespace vm {

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
