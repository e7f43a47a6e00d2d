// Splitting polygon and triangle-strip cells into triangles, and the face
// label arrays the readers recognise. Shared by the VTK XML, legacy VTK, OBJ
// and PLY readers.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string_view>
#include <utility>
#include <vector>

namespace vm {

/// Integer cell arrays read as face labels, in order of preference: the
/// first of these names present in a file wins (SimVascular/VMTK, meshio,
/// generic). PLY also accepts a face property named "label" (last).
inline constexpr std::array<std::string_view, 5> kFaceLabelArrays = {
    "ModelFaceID", "CapID", "CellEntityIds", "FaceID", "RegionId"};

/// Rank of `name` in kFaceLabelArrays (0 = preferred), -1 if absent.
inline int face_label_rank(std::string_view name) {
  for (size_t i = 0; i < kFaceLabelArrays.size(); ++i)
    if (kFaceLabelArrays[i] == name) return int(i);
  return -1;
}

/// Triangles of a polygon of n points (fan from the first point): n - 2,
/// 0 when n < 3.
inline size_t polygon_triangles(size_t n) { return n < 3 ? 0 : n - 2; }

/// Appends the fan (ids[0], ids[k], ids[k+1]), k = 1..n-2, of a polygon.
/// Precondition: every id fits in int32 (checked by the caller).
template <class Index>
void append_fan(const Index* ids, size_t n, std::vector<int32_t>& triangles) {
  for (size_t k = 1; k + 1 < n; ++k) {
    triangles.push_back(int32_t(ids[0]));
    triangles.push_back(int32_t(ids[k]));
    triangles.push_back(int32_t(ids[k + 1]));
  }
}

/// Appends the triangles of a triangle strip of n points: triangle i is
/// (ids[i], ids[i+1], ids[i+2]) for even i and (ids[i+1], ids[i], ids[i+2])
/// for odd i (as vtkTriangleStrip decomposes), so all keep the strip's
/// orientation. Triangles with a repeated point (strip turns) are dropped;
/// returns how many were. Precondition: ids fit in int32.
template <class Index>
size_t append_strip(const Index* ids, size_t n, std::vector<int32_t>& triangles) {
  size_t dropped = 0;
  for (size_t i = 0; i + 2 < n; ++i) {
    int32_t a = int32_t(ids[i]), b = int32_t(ids[i + 1]), c = int32_t(ids[i + 2]);
    if (a == b || b == c || a == c) {
      ++dropped;
      continue;
    }
    if (i % 2) std::swap(a, b);
    triangles.push_back(a);
    triangles.push_back(b);
    triangles.push_back(c);
  }
  return dropped;
}

}  // namespace vm
