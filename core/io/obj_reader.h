// Wavefront OBJ surface reader.
#pragma once

#include <cstdint>
#include <span>

#include "core/io/read_surface.h"
#include "core/io/surface_file.h"
#include "core/util/result.h"

namespace vm {

/// Reads the polygonal part of a Wavefront OBJ file: `v x y z [w ...]`
/// vertices and `f` faces whose corners are `a`, `a/b`, `a//c` or `a/b/c`
/// (a: 1-based vertex index, or negative: relative to the last vertex read);
/// polygons are fanned from their first corner, faces of fewer than 3
/// corners skipped with a warning. `g` and `o` start a named group: when the
/// file has any, each triangle's face label is its group's number (1, 2, ...
/// in order of first use by a face) and face_names gives the names
/// (label_array "obj groups"). vn, vt, vp, usemtl, mtllib, s, l, p and
/// comments are ignored; other statements too, with a warning. Errors give
/// the line: index 0, an index out of range (with the index and the vertex
/// count), non-numeric values, non-finite coordinates, no face at all.
Result<SurfaceFile> read_obj(std::span<const uint8_t> bytes,
                             const SurfaceReadOptions& options = {});

}  // namespace vm
