// A capped vessel model with many tiny outlets and many labelled faces, as
// SimVascular exports large models (an exterior of 93 labelled caps and
// 190 wall faces, some caps of 6 triangles): an analytic tube with thin
// side branches of hexagonal section, each closed by a 6-triangle fan,
// every face labelled. Our own construction (no voxels), for the tests of
// models with hundreds of faces and tiny caps.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/mesh/surface_mesh.h"

namespace vm {

struct OutletsPhantom {
  SurfaceMesh mesh;  ///< closed, manifold, outward, welded
  /// One face label per triangle (ModelFaceID, from 1): the main wall in
  /// bands (kOutletsWallFaces), each branch's wall, the two end caps, each
  /// branch's cap.
  std::vector<int32_t> labels;
  /// The caps: centre, radius (of the circle through the rim) and outward
  /// unit normal, the main tube's two ends first.
  std::vector<std::array<double, 3>> cap_centers, cap_normals;
  std::vector<double> cap_radii;
  /// Triangles per cap, same order.
  std::vector<size_t> cap_triangles;
};

/// The side branches and the main wall's labelled faces.
inline constexpr int kOutletsBranches = 20;
inline constexpr int kOutletsWallFaces = 144;

/// The model, scaled by `scale` (the main tube's radius): a tube of radius 1
/// along z from 0 to 12.6 (48 rings of 24 vertices), closed at both ends by
/// 24-triangle fans; kOutletsBranches branches of radius 0.15 and length
/// 0.45 along the tube's normal, spiralling around it, each on a hole of
/// two of the tube's quads and closed by a fan of 6 triangles. Faces: 144
/// wall bands (each ring of quads in thirds), 20 branch walls, 2 end caps,
/// 20 branch caps: 186 labels.
OutletsPhantom make_outlets_phantom(double scale = 1);

}  // namespace vm
