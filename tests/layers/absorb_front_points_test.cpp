#include "core/layers/absorb_front_points.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <string>
#include <vector>

#include "core/layers/extrude_layers.h"
#include "core/layers/layer_assembly.h"
#include "core/mesh/volume_check.h"
#include "tests/support/test_meshes.h"

namespace vm {
namespace {

// The layer's front refined as boundary recovery refines it: edges split
// one after another (both triangles on an edge split in two), in column ids
// (new point j is nv + j), with the front triangle each piece lies in.
struct Refined {
  std::vector<int32_t> triangles, parent;
  std::vector<double> new_points;
  size_t nv = 0;

  explicit Refined(const LayerMesh& m) : nv(m.wall_vertices) {
    const int32_t top = m.layer_vertex(0, m.layers);
    for (int32_t v : m.front) triangles.push_back(v - top);
    for (size_t t = 0; t < m.wall_triangles; ++t) parent.push_back(int32_t(t));
  }
  const double* point(const LayerMesh& m, int32_t c) const {
    return size_t(c) < nv ? &m.points[3 * size_t(m.layer_vertex(c, m.layers))]
                          : &new_points[3 * (size_t(c) - nv)];
  }
  // Splits edge (a, b) at its midpoint; returns the new column.
  int32_t split(const LayerMesh& m, int32_t a, int32_t b) {
    const int32_t mid = int32_t(nv + new_points.size() / 3);
    for (int k = 0; k < 3; ++k) new_points.push_back(0.5 * (point(m, a)[k] + point(m, b)[k]));
    const size_t n = triangles.size() / 3;
    for (size_t t = 0; t < n; ++t) {
      std::array<int32_t, 3> v = {triangles[3 * t], triangles[3 * t + 1], triangles[3 * t + 2]};
      for (int r = 0; r < 3; ++r) {
        if ((v[0] == a && v[1] == b) || (v[0] == b && v[1] == a)) {
          triangles[3 * t] = v[0], triangles[3 * t + 1] = mid, triangles[3 * t + 2] = v[2];
          triangles.insert(triangles.end(), {mid, v[1], v[2]});
          parent.push_back(parent[t]);
          break;
        }
        std::rotate(v.begin(), v.begin() + 1, v.end());
      }
    }
    return mid;
  }
  // How many triangles use edge (a, b).
  int uses(int32_t a, int32_t b) const {
    int n = 0;
    for (size_t t = 0; t < triangles.size(); t += 3)
      for (int k = 0; k < 3; ++k) {
        const int32_t x = triangles[t + size_t(k)], y = triangles[t + size_t((k + 1) % 3)];
        n += (x == a && y == b) || (x == b && y == a);
      }
    return n;
  }
};

// The layer region with the top slice's tetrahedra: m's prisms split,
// those replaced left out, the absorbed tetrahedra (new points after m's);
// boundary: the wall (tag 0), the refined front (1), the rings (2 + o)
// with their faces replaced (layer_volume's tags and orientations).
VolumeMesh absorbed_volume(const LayerMesh& m, const Refined& r, const AbsorbedFront& a) {
  VolumeMesh vol = layer_volume(m, true);
  const int32_t n_points = int32_t(m.num_vertices());
  auto id = [&](int32_t v) { return v >= 0 ? v : n_points + (-1 - v); };
  vol.points.insert(vol.points.end(), r.new_points.begin(), r.new_points.end());
  std::vector<int32_t> tets;
  for (size_t p = 0; p < m.num_prisms(); ++p)
    if (!std::binary_search(a.replaced_prisms.begin(), a.replaced_prisms.end(), int32_t(p)))
      tets.insert(tets.end(), vol.tets.begin() + long(12 * p),
                  vol.tets.begin() + long(12 * p + 12));
  for (int32_t v : a.tets) tets.push_back(id(v));
  vol.tets = tets;
  vol.tet_region.assign(vol.num_tets(), 0);
  std::vector<int32_t> tris, tags;
  const int32_t top = m.layer_vertex(0, m.layers);
  for (size_t t = 0; t < vol.num_triangles(); ++t) {
    const int32_t* v = &vol.triangles[3 * t];
    if (vol.triangle_tag[t] == 1) continue;  // the front: replaced below
    if (vol.triangle_tag[t] >= 2) {
      bool replaced = false;
      for (size_t q = 0; q < a.ring_opening.size(); ++q) {
        const int32_t* quad = &a.ring_quads[4 * q];
        replaced |= std::all_of(
            v, v + 3, [&](int32_t x) { return std::find(quad, quad + 4, x) != quad + 4; });
      }
      if (replaced) continue;
    }
    tris.insert(tris.end(), v, v + 3);
    tags.push_back(vol.triangle_tag[t]);
  }
  for (size_t t = 0; t < r.triangles.size(); t += 3) {
    for (int k : {0, 2, 1}) {  // out of the layer region: into the core
      const int32_t c = r.triangles[t + size_t(k)];
      tris.push_back(size_t(c) < r.nv ? top + c : n_points + c - int32_t(r.nv));
    }
    tags.push_back(1);
  }
  for (size_t q = 0; q < a.ring_opening.size(); ++q)
    for (int32_t i = 3 * a.ring_first[q]; i < 3 * a.ring_first[q + 1]; ++i) {
      tris.push_back(id(a.ring_triangles[size_t(i)]));
      if (i % 3 == 2) tags.push_back(2 + a.ring_opening[q]);
    }
  vol.triangles = tris;
  vol.triangle_tag = tags;
  return vol;
}

// Absorbs r into m and checks the layer region: valid, conforming, its
// boundary the wall + refined front + rings, the same volume, and only
// top-slice prisms replaced.
void check_absorbed(const LayerMesh& m, const Refined& r, const std::string& name) {
  SCOPED_TRACE(name);
  auto a = absorb_front_points(m, r.triangles, r.parent, r.new_points);
  ASSERT_TRUE(a.ok()) << a.message();
  const AbsorbedFront& f = a.value();
  EXPECT_FALSE(f.replaced_prisms.empty());
  EXPECT_TRUE(std::is_sorted(f.replaced_prisms.begin(), f.replaced_prisms.end()));
  for (int32_t p : f.replaced_prisms)
    EXPECT_GE(size_t(p), size_t(m.layers - 1) * m.wall_triangles) << "not in the top slice";
  const auto before = check_volume_mesh(layer_volume(m, true));
  ASSERT_TRUE(before.ok()) << before.message();
  const auto after = check_volume_mesh(absorbed_volume(m, r, f));
  ASSERT_TRUE(after.ok()) << after.message();
  EXPECT_NEAR(after.value().volume, before.value().volume, 1e-12 * before.value().volume);
}

LayerMesh tube_layer() {
  const SurfaceMesh wall = testing::open_tube(24, 10, 1.0, 2.0);
  auto r = extrude_layers(wall, std::vector<double>(wall.num_vertices(), 1.0), LayerSpec{});
  EXPECT_TRUE(r.ok()) << r.message();
  return r.ok() ? std::move(r).value() : LayerMesh{};
}

TEST(AbsorbFrontPoints, SplitEdgesStayInTheTopSlice) {
  const LayerMesh m = tube_layer();
  ASSERT_GT(m.num_prisms(), 0u);
  const int32_t top = m.layer_vertex(0, m.layers);
  // An inner edge (two triangles on it) and a rim edge (one).
  int32_t inner[2] = {-1, -1}, rim[2] = {-1, -1};
  const Refined plain(m);
  for (size_t t = 0; t < m.wall_triangles; ++t)
    for (int k = 0; k < 3; ++k) {
      const int32_t a = m.front[3 * t + size_t(k)] - top;
      const int32_t b = m.front[3 * t + size_t((k + 1) % 3)] - top;
      int32_t* e = plain.uses(a, b) == 2 ? inner : rim;
      if (e[0] < 0) e[0] = a, e[1] = b;
    }
  ASSERT_GE(inner[0], 0);
  ASSERT_GE(rim[0], 0);
  {
    Refined r(m);
    r.split(m, inner[0], inner[1]);
    check_absorbed(m, r, "an inner edge");
  }
  {
    Refined r(m);
    r.split(m, rim[0], rim[1]);
    check_absorbed(m, r, "a rim edge");
    auto a = absorb_front_points(m, r.triangles, r.parent, r.new_points);
    ASSERT_TRUE(a.ok());
    EXPECT_EQ(a.value().ring_opening.size(), 1u);  // its ring face changes
  }
  {
    // A second point on a piece's inner edge: inside the front triangle.
    Refined r(m);
    const int32_t mid = r.split(m, inner[0], inner[1]);
    int32_t apex = -1;
    for (size_t t = 0; t < r.triangles.size() && apex < 0; t += 3)
      for (int k = 0; k < 3; ++k)
        if (r.triangles[t + size_t(k)] == mid) {
          apex = r.triangles[t + size_t((k + 2) % 3)];
          if (apex == inner[0] || apex == inner[1]) apex = r.triangles[t + size_t((k + 1) % 3)];
          break;
        }
    ASSERT_GE(apex, 0);
    r.split(m, mid, apex);
    check_absorbed(m, r, "a point inside a front triangle");
  }
  {
    // Every edge of the front split once.
    Refined r(m);
    std::vector<std::array<int32_t, 2>> edges;
    for (size_t t = 0; t < m.wall_triangles; ++t)
      for (int k = 0; k < 3; ++k) {
        const int32_t a = m.front[3 * t + size_t(k)] - top;
        const int32_t b = m.front[3 * t + size_t((k + 1) % 3)] - top;
        if (a < b || plain.uses(a, b) == 1) edges.push_back({a, b});
      }
    for (const auto& [a, b] : edges) r.split(m, a, b);
    check_absorbed(m, r, "every edge");
  }
}

TEST(AbsorbFrontPoints, Errors) {
  const LayerMesh m = tube_layer();
  Refined r(m);
  r.split(m, r.triangles[0], r.triangles[1]);
  // A piece given to another parent: the pieces do not tile their parents.
  std::vector<int32_t> parent = r.parent;
  parent.back() = parent.back() == 0 ? 1 : 0;
  EXPECT_FALSE(absorb_front_points(m, r.triangles, parent, r.new_points).ok());
  EXPECT_FALSE(absorb_front_points(m, r.triangles, {0}, r.new_points).ok());
  std::vector<int32_t> bad = r.triangles;
  bad[0] = int32_t(m.wall_vertices + r.new_points.size());  // out of range
  EXPECT_FALSE(absorb_front_points(m, bad, r.parent, r.new_points).ok());
  LayerMesh outward = m;
  outward.outward = true;
  EXPECT_FALSE(absorb_front_points(outward, r.triangles, r.parent, r.new_points).ok());
  // A new point pulled off its front triangle, out beyond the wall:
  // the top slice's tetrahedra are not all positive.
  std::vector<double> far = r.new_points;
  for (size_t i = 0; i < far.size(); i += 3) far[i] *= 1.5, far[i + 1] *= 1.5;
  auto off = absorb_front_points(m, r.triangles, r.parent, far);
  ASSERT_FALSE(off.ok());
  EXPECT_NE(off.message().find("not positive"), std::string::npos) << off.message();
}

}  // namespace
}  // namespace vm
