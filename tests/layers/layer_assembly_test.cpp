// The caller's assembly of a layered volume, end to end: viscous layer
// inward, vessel wall outward, the front capped and filled with tetrahedra
// (cap_openings.h, boundary_recovery.h), everything merged into one VolumeMesh with
// the output groups and checked by check_volume_mesh (exact positivity,
// conformity, boundary = surface triangles).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>
#include <vector>

#include "core/layers/extrude_layers.h"
#include "core/layers/refine_layers.h"
#include "core/mesh/chord_radius.h"
#include "core/mesh/enclosed_volume.h"
#include "core/mesh/volume_check.h"
#include "core/phantom/vessel_phantom.h"
#include "core/surface/cap_openings.h"
#include "core/surface/remesh_surface.h"
#include "core/volume/boundary_recovery.h"
#include "tests/support/phantoms.h"
#include "tests/support/remesh_options.h"
#include "tests/support/test_meshes.h"
#include "tests/support/tet_volume.h"

namespace vm {
namespace {

// Surface tags of the assembled mesh.
constexpr int32_t kWall = 0;            // lumen | vessel wall (or the boundary)
constexpr int32_t kCapBase = 1;         // inlet, outlet_1.. (inner cap + inward ring)
constexpr int32_t kOuterWall = 100;     // outer_wall
constexpr int32_t kWallRingBase = 200;  // wall_inlet, wall_outlet_k
constexpr int32_t kLumen = 0, kVesselWall = 1;

struct Assembly {
  VolumeMesh mesh;
  size_t steiner_points = 0;
  size_t front_steiner_points = 0;          // of which on the front (absorbed by the layers)
  double front_rim_move = 0;                // largest move of a front rim point by the front's caps
  std::vector<int32_t> cap_tag_of_opening;  // per wall opening: its cap's tag
};

// The cap of `caps` whose rim is wall opening `op` (same wall vertex ids).
int32_t cap_tag_of(const CappedSurface& caps, const LayerOpening& op) {
  for (const CapInfo& c : caps.caps)
    if (std::find(c.rim.begin(), c.rim.end(), op.rim[0]) != c.rim.end()) return c.tag;
  return -1;
}

// Inward layer `in_layer` (required) and outward layer `out_layer`
// (optional, same wall) merged: lumen = split prisms of the inward layer +
// tetrahedra filling its capped front; vessel wall = split prisms of the
// outward layer. Steiner points the recovery puts on the front are absorbed
// by refining both layers' columns (refine_layers.h).
Assembly assemble(const LayerMesh& in_layer, const LayerMesh* out_layer) {
  Assembly a;
  const size_t nv = in_layer.wall_vertices, nt = in_layer.wall_triangles;
  const int n = in_layer.layers;

  // The front closed by planar caps, filled with tetrahedra.
  const SurfaceMesh front = front_surface(in_layer);
  auto capped = cap_openings(front, {});
  EXPECT_TRUE(capped.ok()) << capped.message();
  if (!capped.ok()) return a;
  const CappedSurface& cf = capped.value();
  auto recovered = recover_boundary(cf.mesh.points, cf.mesh.triangles, cf.triangle_tag);
  EXPECT_TRUE(recovered.ok()) << recovered.message();
  if (!recovered.ok()) return a;
  const RecoveredVolume& rec = recovered.value();
  a.steiner_points = size_t(rec.steiner_points);

  // The recovered front (tag 0) as columns: the front's own vertices, then
  // Steiner points on it as new columns.
  std::vector<int32_t> column(rec.mesh.num_vertices(), -1), tri, par;
  std::vector<double> new_points;
  for (size_t v = 0; v < nv; ++v) column[v] = int32_t(v);
  for (size_t t = 0; t < rec.mesh.num_triangles(); ++t) {
    if (rec.mesh.triangle_tag[t] != 0) continue;
    for (int k = 0; k < 3; ++k) {
      const int32_t i = rec.mesh.triangles[3 * t + size_t(k)];
      if (column[size_t(i)] < 0) {
        column[size_t(i)] = int32_t(nv + new_points.size() / 3);
        new_points.insert(new_points.end(), &rec.mesh.points[3 * size_t(i)],
                          &rec.mesh.points[3 * size_t(i)] + 3);
      }
      tri.push_back(column[size_t(i)]);
    }
    EXPECT_LT(size_t(rec.triangle_parent[t]), nt);
    par.push_back(rec.triangle_parent[t]);
  }
  a.front_steiner_points = new_points.size() / 3;
  LayerMesh in = in_layer, out;
  if (out_layer) out = *out_layer;
  if (!new_points.empty()) {
    auto refined = refine_layer_columns(in_layer, tri, par, new_points, n);
    EXPECT_TRUE(refined.ok()) << refined.message();
    if (!refined.ok()) return a;
    in = std::move(refined).value();
    if (out_layer) {
      // The outward layer follows the refined wall exactly.
      std::vector<double> wall_points(in.points.begin() + long(3 * nv),
                                      in.points.begin() + long(3 * in.wall_vertices));
      auto refined_out = refine_layer_columns(*out_layer, tri, par, wall_points, 0);
      EXPECT_TRUE(refined_out.ok()) << refined_out.message();
      if (!refined_out.ok()) return a;
      out = std::move(refined_out).value();
    }
  }
  const size_t nv2 = in.wall_vertices;
  const int32_t top = in.layer_vertex(0, n);

  VolumeMesh& vol = a.mesh;
  vol.points = in.points;
  // Outward layer's new points appended (an increasing renumbering, so the
  // prism splits are unchanged).
  auto out_id = [&](int32_t id) {
    return id < int32_t(nv2) ? id : int32_t(in.num_vertices()) + (id - int32_t(nv2));
  };
  if (out_layer)
    vol.points.insert(vol.points.end(), out.points.begin() + long(3 * nv2), out.points.end());
  // Front points as the recovery has them (the caps moved the rim points
  // onto their re-fitted planes by rounding only), then the core's others.
  for (size_t i = 0; i < rec.mesh.num_vertices(); ++i) {
    if (column[i] < 0) continue;
    for (int k = 0; k < 3; ++k) {
      double& x = vol.points[3 * size_t(top + column[i]) + size_t(k)];
      a.front_rim_move =
          std::max(a.front_rim_move, std::abs(x - rec.mesh.points[3 * i + size_t(k)]));
      x = rec.mesh.points[3 * i + size_t(k)];
    }
  }
  std::vector<int32_t> core_id(rec.mesh.num_vertices());
  for (size_t i = 0; i < rec.mesh.num_vertices(); ++i) {
    if (column[i] >= 0) {
      core_id[i] = top + column[i];
    } else {
      core_id[i] = int32_t(vol.num_vertices());
      vol.points.insert(vol.points.end(), &rec.mesh.points[3 * i], &rec.mesh.points[3 * i] + 3);
    }
  }

  // Lumen: the viscous layer's prisms split, then the core.
  vol.tets = prisms_to_tets(in.prisms);
  for (int32_t v : rec.mesh.tets) vol.tets.push_back(core_id[size_t(v)]);
  vol.tet_region.assign(vol.num_tets(), kLumen);
  // Vessel wall.
  if (out_layer) {
    std::vector<int32_t> prisms = out.prisms;
    for (int32_t& v : prisms) v = out_id(v);
    const std::vector<int32_t> tets = prisms_to_tets(prisms);
    vol.tets.insert(vol.tets.end(), tets.begin(), tets.end());
    vol.tet_region.resize(vol.num_tets(), kVesselWall);
  }

  // Surfaces: wall (boundary, or the lumen | vessel-wall interface).
  for (int32_t v : in.front) vol.triangles.push_back(v - top);
  vol.triangle_tag.resize(vol.num_triangles(), kWall);
  // Inner caps (the front's caps, their tags) and the inward rings.
  for (size_t t = 0; t < rec.mesh.num_triangles(); ++t) {
    if (rec.mesh.triangle_tag[t] == 0) continue;  // the front: inside the lumen
    for (int k = 0; k < 3; ++k)
      vol.triangles.push_back(core_id[size_t(rec.mesh.triangles[3 * t + size_t(k)])]);
    vol.triangle_tag.push_back(kCapBase - 1 + rec.mesh.triangle_tag[t]);
  }
  for (size_t o = 0; o < in.openings.size(); ++o) {
    const int32_t tag = cap_tag_of(cf, in.openings[o]);
    a.cap_tag_of_opening.push_back(tag);
    const std::vector<int32_t> ring = ring_triangles(in, o);
    vol.triangles.insert(vol.triangles.end(), ring.begin(), ring.end());
    vol.triangle_tag.insert(vol.triangle_tag.end(), ring.size() / 3, kCapBase - 1 + tag);
  }
  if (out_layer) {
    for (int32_t v : out.front) vol.triangles.push_back(out_id(v));
    vol.triangle_tag.resize(vol.num_triangles(), kOuterWall);
    for (size_t o = 0; o < out.openings.size(); ++o) {
      std::vector<int32_t> ring = ring_triangles(out, o);
      for (int32_t& v : ring) v = out_id(v);
      vol.triangles.insert(vol.triangles.end(), ring.begin(), ring.end());
      vol.triangle_tag.insert(vol.triangle_tag.end(), ring.size() / 3,
                              kWallRingBase + a.cap_tag_of_opening[o]);
    }
  }
  return a;
}

// Checks the assembled mesh: valid, its volume the capped wall's (plus the
// vessel wall's shell), every cap group planar.
void check_assembly(const SurfaceMesh& wall, const LayerMesh& in, const LayerMesh* out,
                    const std::string& name) {
  SCOPED_TRACE(name);
  const Assembly a = assemble(in, out);
  ASSERT_GT(a.mesh.num_tets(), 0u);
  const double diag = bounding_box(a.mesh.points).diagonal();
  EXPECT_LE(a.front_rim_move, 1e-12 * diag);
  const auto check = check_volume_mesh(a.mesh);
  ASSERT_TRUE(check.ok()) << check.message();
  // The lumen's volume is the capped wall's.
  auto capped_wall = cap_openings(wall, {});
  ASSERT_TRUE(capped_wall.ok());
  double lumen = 0, shell = 0;
  for (size_t t = 0; t < a.mesh.num_tets(); ++t)
    (a.mesh.tet_region[t] == kLumen ? lumen : shell) += testing::mesh_tet_volume6(a.mesh, t) / 6;
  const double expected = enclosed_volume(capped_wall.value().mesh);
  EXPECT_NEAR(lumen, expected, 1e-9 * expected);
  // Each cap group (inner cap + ring; wall ring) lies in its opening's plane.
  for (size_t o = 0; o < in.openings.size(); ++o) {
    const LayerOpening& op = in.openings[o];
    double worst = 0;
    size_t count = 0;
    for (size_t t = 0; t < a.mesh.num_triangles(); ++t) {
      const int32_t tag = a.mesh.triangle_tag[t];
      if (tag != kCapBase - 1 + a.cap_tag_of_opening[o] &&
          tag != kWallRingBase + a.cap_tag_of_opening[o])
        continue;
      ++count;
      for (int k = 0; k < 3; ++k) {
        const double* p = &a.mesh.points[3 * size_t(a.mesh.triangles[3 * t + size_t(k)])];
        double s = 0;
        for (int d = 0; d < 3; ++d) s += (p[d] - op.origin[d]) * op.normal[d];
        worst = std::max(worst, std::abs(s));
      }
    }
    EXPECT_GT(count, 0u);
    EXPECT_LE(worst, 1e-9 * diag) << "opening " << o;
  }
  std::cout << "[ info ] " << name << ": " << a.mesh.num_tets() << " tetrahedra (lumen volume "
            << lumen << ", vessel wall " << shell << "), " << a.mesh.num_triangles()
            << " boundary/interface triangles, valid; " << a.steiner_points << " Steiner points, "
            << a.front_steiner_points << " on the front\n";
}

TEST(LayerAssembly, TubeLumenAndVesselWall) {
  const SurfaceMesh wall = testing::open_tube(32, 20, 1.0, 3.0);
  const std::vector<double> radius(wall.num_vertices(), 1.0);
  LayerSpec in_spec, out_spec;
  out_spec.outward = true;
  out_spec.thickness_fraction = 0.1;
  auto in = extrude_layers(wall, radius, in_spec);
  auto out = extrude_layers(wall, radius, out_spec);
  ASSERT_TRUE(in.ok() && out.ok());
  // Both share the wall points bitwise.
  for (size_t i = 0; i < wall.points.size(); ++i)
    ASSERT_EQ(in.value().points[i], out.value().points[i]);
  check_assembly(wall, in.value(), nullptr, "tube, viscous layer");
  check_assembly(wall, in.value(), &out.value(), "tube, viscous layer + vessel wall");
}

TEST(LayerAssembly, BifurcationPhantomLumenAndVesselWall) {
  auto remeshed = remesh_surface(testing::noisy_bifurcation(0.15), testing::uniform_remesh(0.2));
  ASSERT_TRUE(remeshed.ok()) << remeshed.message();
  const SurfaceMesh& wall = remeshed.value().mesh;
  const std::vector<double> radius = chord_radius(wall);
  LayerSpec in_spec, out_spec;
  out_spec.outward = true;
  out_spec.thickness_fraction = 0.1;
  auto in = extrude_layers(wall, radius, in_spec);
  auto out = extrude_layers(wall, radius, out_spec);
  ASSERT_TRUE(in.ok()) << in.message();
  ASSERT_TRUE(out.ok()) << out.message();
  check_assembly(wall, in.value(), &out.value(), "bifurcation, viscous layer + vessel wall");
}

}  // namespace
}  // namespace vm
