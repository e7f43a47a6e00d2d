// Reading any surface file the tool supports, the reader chosen by the bytes
// (never by the file name): binary or ASCII STL, VTK XML PolyData (.vtp),
// legacy VTK (.vtk), Wavefront OBJ, PLY, and any of them gzip-compressed.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include "core/io/surface_file.h"
#include "core/util/result.h"

namespace vm {

struct SurfaceReadOptions {
  /// Files with more triangles are refused ("too large") before any
  /// allocation proportional to the claimed size (see StlReadOptions).
  size_t max_triangles = 25'000'000;
  /// Limit of gzip/zlib output (the whole decompressed file, and the sum of
  /// the compressed arrays of a VTK XML file): a "zip bomb" is refused.
  size_t max_decompressed_bytes = size_t(2) << 30;
  /// Larger files are refused before they are read (check_surface_size):
  /// 25M triangles of ASCII STL take about 7 GiB.
  uint64_t max_file_bytes = uint64_t(8) << 30;
};

/// Whether a file of `file_size` bytes whose first bytes are `prefix` (at
/// least 84 when the file has them) is within the limits of `options`,
/// judged before the file is read: its size against max_file_bytes, and a
/// binary STL header's triangle count against max_triangles. Formats whose
/// counts come later are checked by their readers, before any allocation
/// proportional to a count.
Status check_surface_size(std::span<const uint8_t> prefix, uint64_t file_size,
                          const SurfaceReadOptions& options = {});

/// Reads a surface file held in memory. The format is sniffed from the
/// content: "<?xml" or "<VTKFile" (VTK XML PolyData), "# vtk DataFile"
/// (legacy VTK), a "ply" line (PLY), "solid" or the binary STL size law (STL,
/// see read_stl), lines of OBJ statements (v, vn, vt, f, g, o, #, mtllib,
/// usemtl, s, ...). Anything else: "not a surface file this tool reads
/// (binary or ASCII STL, VTK XML PolyData .vtp, legacy VTK .vtk, Wavefront
/// .obj, PLY; any of them gzip-compressed): it starts with '...'". Gzip magic
/// (1f 8b): the first 64 KiB are decompressed and sniffed, and refused there
/// when they are another gzip stream, a binary STL header over max_triangles
/// or of no format above ("its first 65536 decompressed bytes are not the
/// start of a surface file..."); only then is the whole decompressed (within
/// max_decompressed_bytes) and sniffed. Errors of a recognised format are
/// that reader's, prefixed "gzip-compressed file: " when it was compressed.
Result<SurfaceFile> read_surface(std::span<const uint8_t> bytes,
                                 const SurfaceReadOptions& options = {});

}  // namespace vm
