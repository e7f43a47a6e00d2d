// The outlets phantom (outlets_phantom.h): our own construction. The main
// tube is a grid of quads in (angle, height); a branch replaces two
// neighbouring quads (a hole of 6 vertices) by a hexagonal tube along the
// normal, whose rings turn the hole into a regular hexagon, and a fan of 6
// triangles at its end. Every quad is split along the same diagonal, all
// triangles face out.
#include "core/phantom/outlets_phantom.h"

#include <array>
#include <numbers>

#include "core/geom/vec3.h"
#include "core/util/portable_math.h"

namespace vm {
namespace {

constexpr int kAround = 24;  // vertices around the main tube
constexpr int kRings = 49;   // rings of the main tube (48 bands of quads)
constexpr int kBranchRings = 3;
constexpr double kBranchRadius = 0.15, kBranchStep = 0.15;

/// Branch k sits on the quads (i, j) and (i + 1, j), rows 4, 6, ...,
/// columns spiralling around. The columns leave no part of a wall face
/// (a third of a band, 8 quads) of one or two quads: such a part would be
/// flat, and taken for a cap.
std::array<int, 2> branch_site(int k) {
  constexpr int kColumns[] = {0, 3, 6, 7, 8, 11, 14, 15, 16, 19, 22, 23};
  return {kColumns[(5 * k) % 12], 4 + 2 * k};
}

}  // namespace

OutletsPhantom make_outlets_phantom(double scale) {
  OutletsPhantom out;
  SurfaceMesh& m = out.mesh;
  const double step = 2 * std::numbers::pi / kAround;  // angle, and height of a band
  auto add_point = [&](const Vec3& p) {
    m.points.insert(m.points.end(), p.begin(), p.end());
    return int32_t(m.num_vertices() - 1);
  };
  auto add_triangle = [&](int32_t a, int32_t b, int32_t c, int32_t label) {
    m.triangles.insert(m.triangles.end(), {a, b, c});
    out.labels.push_back(label);
  };
  auto add_cap = [&](const Vec3& centre, const Vec3& normal, double radius, size_t triangles) {
    out.cap_centers.push_back(scale * centre);
    out.cap_normals.push_back(normal);
    out.cap_radii.push_back(scale * radius);
    out.cap_triangles.push_back(triangles);
  };
  // The main tube's vertices, ring by ring.
  for (int j = 0; j < kRings; ++j)
    for (int i = 0; i < kAround; ++i) add_point({pm::cos(step * i), pm::sin(step * i), step * j});
  auto grid = [&](int i, int j) { return int32_t(j * kAround + (i % kAround)); };
  std::vector<int> branch_at(size_t(kAround) * (kRings - 1), -1);
  for (int k = 0; k < kOutletsBranches; ++k) {
    const auto [i, j] = branch_site(k);
    branch_at[size_t(j * kAround + i)] = branch_at[size_t(j * kAround + (i + 1) % kAround)] = k;
  }
  // The wall's quads, each band of quads in thirds.
  for (int j = 0; j + 1 < kRings; ++j)
    for (int i = 0; i < kAround; ++i) {
      if (branch_at[size_t(j * kAround + i)] >= 0) continue;
      const int32_t label = 1 + 3 * j + i / (kAround / 3);
      const int32_t a = grid(i, j), b = grid(i + 1, j), c = grid(i + 1, j + 1), d = grid(i, j + 1);
      add_triangle(a, b, c, label);
      add_triangle(a, c, d, label);
    }
  // The end caps: fans, outward (-z at the start, +z at the end).
  const int32_t first_label = kOutletsWallFaces + kOutletsBranches + 1;
  const double length = step * (kRings - 1);
  const int32_t c0 = add_point({0, 0, 0}), c1 = add_point({0, 0, length});
  for (int i = 0; i < kAround; ++i) {
    add_triangle(grid(i + 1, 0), grid(i, 0), c0, first_label);
    add_triangle(grid(i, kRings - 1), grid(i + 1, kRings - 1), c1, first_label + 1);
  }
  add_cap({0, 0, 0}, {0, 0, -1}, 1, kAround);
  add_cap({0, 0, length}, {0, 0, 1}, 1, kAround);
  // The branches: rings of 6 from the hole (counterclockwise about the
  // normal, as the hole's quads ran) out to a regular hexagon, then a fan.
  for (int k = 0; k < kOutletsBranches; ++k) {
    const auto [i, j] = branch_site(k);
    const double angle = step * (i + 1);
    const Vec3 n = {pm::cos(angle), pm::sin(angle), 0}, t = {-n[1], n[0], 0}, up = {0, 0, 1};
    const Vec3 base = {n[0], n[1], step * (j + 0.5)};
    std::vector<std::array<int32_t, 6>> rings = {{grid(i, j), grid(i + 1, j), grid(i + 2, j),
                                                  grid(i + 2, j + 1), grid(i + 1, j + 1),
                                                  grid(i, j + 1)}};
    for (int r = 1; r <= kBranchRings; ++r) {
      std::array<int32_t, 6> ring;
      for (int v = 0; v < 6; ++v) {
        const double phi = std::numbers::pi * (-150.0 + 60.0 * v) / 180.0;
        const Vec3 radial = pm::cos(phi) * t + pm::sin(phi) * up;
        ring[size_t(v)] = add_point(base + (kBranchStep * r) * n + kBranchRadius * radial);
      }
      rings.push_back(ring);
    }
    const int32_t wall_label = kOutletsWallFaces + 1 + k;
    for (size_t r = 0; r + 1 < rings.size(); ++r)
      for (size_t v = 0; v < 6; ++v) {
        const int32_t a = rings[r][v], b = rings[r][(v + 1) % 6], c = rings[r + 1][(v + 1) % 6],
                      d = rings[r + 1][v];
        add_triangle(a, b, c, wall_label);
        add_triangle(a, c, d, wall_label);
      }
    const Vec3 tip = base + (kBranchStep * kBranchRings) * n;
    const int32_t centre = add_point(tip);
    for (size_t v = 0; v < 6; ++v)
      add_triangle(rings.back()[v], rings.back()[(v + 1) % 6], centre, first_label + 2 + k);
    add_cap(tip, n, kBranchRadius, 6);
  }
  for (double& x : m.points) x *= scale;
  return out;
}

}  // namespace vm
