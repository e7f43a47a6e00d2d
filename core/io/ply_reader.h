// PLY (Stanford polygon file format) surface reader.
#pragma once

#include <cstdint>
#include <span>

#include "core/io/read_surface.h"
#include "core/io/surface_file.h"
#include "core/util/result.h"

namespace vm {

/// Reads a PLY file in format ascii 1.0, binary_little_endian 1.0 or
/// binary_big_endian 1.0: element `vertex` (properties x, y, z of any scalar
/// type; other properties skipped) and element `face` (a list property
/// `vertex_indices` or `vertex_index`, fanned from its first vertex; faces
/// of fewer than 3 vertices skipped with a warning). Other elements and
/// properties, list properties included, are skipped. An integer face
/// property named as in kFaceLabelArrays, or `label`, gives face_labels.
/// Errors: malformed header (with its line), unknown type, missing x/y/z or
/// vertex_indices, truncated data or counts larger than the data (with the
/// element and its number), face indices past the vertices (face number,
/// index, vertex count), non-finite coordinates. Allocations are bounded by
/// the bytes present and options.max_triangles.
Result<SurfaceFile> read_ply(std::span<const uint8_t> bytes,
                             const SurfaceReadOptions& options = {});

}  // namespace vm
