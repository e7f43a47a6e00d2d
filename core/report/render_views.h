// Pictures of a mesh without a GPU, for the methods report of the CLI: a
// small z-buffered software rasterizer (flat Lambert shading, orthographic
// views) and a PNG encoder (zlib). Our own design.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/pipeline/mesh_job.h"
#include "core/report/methods_report.h"

namespace vm {

/// An 8-bit RGB raster, rows top to bottom: rgb has 3 width height bytes.
struct RgbImage {
  int width = 0, height = 0;
  std::vector<uint8_t> rgb;
};

/// The cut's fill colours (RGB) per part, as MeshJobResult::tet_part
/// numbers them: 0 the core, 1 the viscous layer, 2 the vessel wall.
inline constexpr uint8_t kReportPartColours[3][3] = {
    {206, 222, 240}, {242, 166, 60}, {176, 64, 110}};

/// The PNG file of `image` (colour type 2, 8 bits, zlib-compressed IDAT).
std::string encode_png(const RgbImage& image);

/// The report's three views of a meshed result, `width` x `height` pixels
/// each: the wall mesh (shaded, its edges drawn), a cut through the volume
/// by the plane through the lumen's centre across its longest extent (the
/// cut tetrahedra's faces on the plane, core and layers in two colours),
/// and a close-up of that cut where it meets the wall (the boundary layer).
/// A surface-only result gets the wall view alone.
std::vector<ReportImage> render_report_views(const MeshJobResult& result, int width = 800,
                                             int height = 600);

}  // namespace vm
