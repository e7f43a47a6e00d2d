// Legacy VTK (.vtk) surface reader.
#pragma once

#include <cstdint>
#include <span>

#include "core/io/read_surface.h"
#include "core/io/surface_file.h"
#include "core/util/result.h"

namespace vm {

/// Reads a legacy VTK file ("# vtk DataFile Version x.y", ASCII or BINARY,
/// binary values big-endian as the format says) holding DATASET POLYDATA:
/// POINTS of any numeric type; POLYGONS and TRIANGLE_STRIPS in the classic
/// layout (n i0 i1 ...) or the 5.1 layout (OFFSETS / CONNECTIVITY arrays);
/// VERTICES and LINES are skipped with a warning. DATASET UNSTRUCTURED_GRID
/// is read too when it holds surface cells (triangles, quads, polygons,
/// strips); its other cells are skipped with a warning. Face labels: a
/// CELL_DATA integer array (SCALARS, or an array of a FIELD) named as in
/// kFaceLabelArrays, one value per cell. Other attributes (POINT_DATA,
/// vectors, normals, lookup tables, metadata blocks) are skipped. Errors
/// give the line (ASCII) or byte offset (BINARY): truncated data, counts
/// that disagree, indices out of range, unknown types or keywords,
/// non-finite coordinates. Allocations are bounded by the bytes present and
/// options.max_triangles.
Result<SurfaceFile> read_vtk_legacy(std::span<const uint8_t> bytes,
                                    const SurfaceReadOptions& options = {});

}  // namespace vm
