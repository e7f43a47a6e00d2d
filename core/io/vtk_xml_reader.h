// VTK XML PolyData (.vtp) reader.
#pragma once

#include <cstdint>
#include <span>

#include "core/io/read_surface.h"
#include "core/io/surface_file.h"
#include "core/util/result.h"

namespace vm {

/// Reads a VTK XML PolyData file (<VTKFile type="PolyData">): every array
/// format (ascii, inline base64 "binary", appended raw or base64), header
/// types UInt32/UInt64, vtkZLibDataCompressor or no compression, little or
/// big endian, any of the ten numeric data types, several Pieces
/// (concatenated). Output (SurfaceFile): points (3 doubles each) and
/// triangles from Polys (fanned from their first point; cells of fewer than
/// 3 points skipped) and Strips (split, see cells_to_triangles.h); Verts and
/// Lines are ignored with a warning. The first integer cell array named as
/// in kFaceLabelArrays gives face_labels, one per triangle (the label of
/// the cell it came from). Errors name the array, piece, cell or point and
/// byte position: data cut short, bad base64, bad zlib block, sizes that
/// disagree with the header, indices out of range, unknown data types,
/// missing Points, non-finite coordinates. Every allocation is bounded by
/// the bytes present, options.max_triangles or
/// options.max_decompressed_bytes.
Result<SurfaceFile> read_vtk_xml(std::span<const uint8_t> bytes,
                                 const SurfaceReadOptions& options = {});

}  // namespace vm
