// Lumen and vessel-wall assembly (Marchandise et al., section 2.2), in
// phases: the recovery's Steiner points on the core's boundary become new
// layer columns; points are numbered (inner layer, outer layer, core);
// elements and regions; surfaces and their names.
#include "core/layers/layered_volume.h"

#include <algorithm>

#include "core/layers/layer_assembly.h"
#include "core/layers/refine_layers.h"

namespace vm {
namespace {

/// The tag of the cap closing layer opening `op` (the cap whose rim holds
/// op's first rim vertex), or -1.
int32_t cap_tag_of(const CappedSurface& caps, const LayerOpening& op) {
  for (const CapInfo& c : caps.caps)
    if (std::find(c.rim.begin(), c.rim.end(), op.rim[0]) != c.rim.end()) return c.tag;
  return -1;
}

}  // namespace

Result<LayeredVolume> assemble_layered_volume(const LayerMesh* inner, const LayerMesh* outer,
                                              const CappedSurface& caps,
                                              const RecoveredVolume& recovered,
                                              const VolumeMesh& core, bool tag_layer,
                                              bool keep_prisms) {
  LayeredVolume out;
  const VolumeMesh& rec = recovered.mesh;
  const LayerMesh* base = inner ? inner : outer;  // whose columns the core's boundary sits on
  const size_t nv = base ? base->wall_vertices : 0;

  // Phase 1: the core's boundary triangles on the wall/front (tag 0) as
  // column ids; Steiner points there become new columns nv + j.
  std::vector<int32_t> column(rec.num_vertices(), -1), tri, parent;
  std::vector<double> new_points;
  LayerMesh in, ou;
  if (base) {
    for (size_t v = 0; v < nv; ++v) column[v] = int32_t(v);
    for (size_t t = 0; t < rec.num_triangles(); ++t) {
      if (rec.triangle_tag[t] != 0) continue;
      for (int k = 0; k < 3; ++k) {
        const int32_t i = rec.triangles[3 * t + size_t(k)];
        if (column[size_t(i)] < 0) {
          column[size_t(i)] = int32_t(nv + new_points.size() / 3);
          new_points.insert(new_points.end(), &rec.points[3 * size_t(i)],
                            &rec.points[3 * size_t(i)] + 3);
        }
        tri.push_back(column[size_t(i)]);
      }
      parent.push_back(recovered.triangle_parent[t]);
    }
    out.front_steiner_points = new_points.size() / 3;
    if (inner) in = *inner;
    if (outer) ou = *outer;
    if (!new_points.empty()) {
      if (inner) {
        auto refined = refine_layer_columns(*inner, tri, parent, new_points, inner->layers);
        if (!refined.ok()) return refined.status();
        in = std::move(refined).value();
      }
      if (outer) {
        // The outer layer follows the (refined) wall: inner's layer 0.
        std::vector<double> wall_points =
            inner ? std::vector<double>(in.points.begin() + long(3 * nv),
                                        in.points.begin() + long(3 * in.wall_vertices))
                  : new_points;
        auto refined = refine_layer_columns(*outer, tri, parent, wall_points, 0);
        if (!refined.ok()) return refined.status();
        ou = std::move(refined).value();
      }
    }
  }

  // Phase 2: points. Inner layer (all its layers), then the outer layer
  // beyond its wall (its wall is the inner layer's layer 0), then the core's
  // points not on the front.
  VolumeMesh& m = out.mesh;
  const size_t nv2 = inner ? in.wall_vertices : outer ? ou.wall_vertices : 0;
  if (inner) {
    m.points = in.points;
  } else if (outer) {
    m.points.assign(ou.points.begin(), ou.points.begin() + long(3 * nv2));
  }
  const int32_t top = inner ? in.layer_vertex(0, in.layers) : 0;  // front column c = top + c
  const int32_t shift = int32_t(m.num_vertices()) - int32_t(nv2);
  auto outer_id = [&](int32_t id) { return id < int32_t(nv2) ? id : id + shift; };
  if (outer) m.points.insert(m.points.end(), ou.points.begin() + long(3 * nv2), ou.points.end());
  std::vector<int32_t> core_id(core.num_vertices());
  for (size_t i = 0; i < core.num_vertices(); ++i) {
    if (i < column.size() && column[i] >= 0) {
      core_id[i] = top + column[i];
      // The recovery's exact coordinates (equal up to the columns' rounding).
      std::copy(&core.points[3 * i], &core.points[3 * i] + 3, &m.points[3 * size_t(core_id[i])]);
    } else {
      core_id[i] = int32_t(m.num_vertices());
      m.points.insert(m.points.end(), &core.points[3 * i], &core.points[3 * i] + 3);
    }
  }

  // Phase 3: elements and regions.
  const int32_t inner_region = tag_layer ? kRegionBoundaryLayer : kRegionLumen;
  if (inner && keep_prisms) {
    m.prisms = in.prisms;
    m.prism_region.assign(m.num_prisms(), inner_region);
  } else if (inner) {
    m.tets = prisms_to_tets(in.prisms);
    m.tet_region.assign(m.num_tets(), inner_region);
  }
  out.core_first = m.num_tets();
  out.core_count = core.num_tets();
  for (int32_t v : core.tets) m.tets.push_back(core_id[size_t(v)]);
  m.tet_region.resize(m.num_tets(), kRegionLumen);
  if (outer) {
    std::vector<int32_t> prisms = ou.prisms;
    for (int32_t& v : prisms) v = outer_id(v);
    if (keep_prisms) {
      m.prisms.insert(m.prisms.end(), prisms.begin(), prisms.end());
      m.prism_region.resize(m.num_prisms(), kRegionVesselWall);
    } else {
      const std::vector<int32_t> tets = prisms_to_tets(prisms);
      m.tets.insert(m.tets.end(), tets.begin(), tets.end());
      m.tet_region.resize(m.num_tets(), kRegionVesselWall);
    }
  }
  out.region_names = {"lumen", tag_layer && inner ? "boundary_layer" : "",
                      outer ? "vessel_wall" : ""};

  // Phase 4: surfaces. Tags: 0 wall, 1..k the caps (as `caps`), then
  // outer_wall, then wall_<cap> in cap order.
  const int32_t ncaps = int32_t(caps.caps.size());
  const int32_t outer_wall = ncaps + 1;
  out.surface_names = {"wall"};
  for (const CapInfo& c : caps.caps) out.surface_names.push_back(c.name);
  if (outer) {
    out.surface_names.push_back("outer_wall");
    for (const CapInfo& c : caps.caps) out.surface_names.push_back("wall_" + c.name);
  }
  if (inner) {
    for (int32_t v : in.front) m.triangles.push_back(v - top);  // the wall: layer 0
    m.triangle_tag.resize(m.num_triangles(), 0);
  }
  for (size_t t = 0; t < rec.num_triangles(); ++t) {
    if (inner && rec.triangle_tag[t] == 0) continue;  // the front: inside the lumen
    for (int k = 0; k < 3; ++k)
      m.triangles.push_back(core_id[size_t(rec.triangles[3 * t + size_t(k)])]);
    m.triangle_tag.push_back(rec.triangle_tag[t]);
  }
  out.ring_first = m.num_triangles();
  const LayerMesh* ringed[2] = {inner ? &in : nullptr, outer ? &ou : nullptr};
  for (int side = 0; side < 2; ++side) {
    const LayerMesh* layer = ringed[side];
    if (!layer) continue;
    for (size_t o = 0; o < layer->openings.size(); ++o) {
      const int32_t cap = cap_tag_of(caps, layer->openings[o]);
      if (cap < 0) return Status::Internal("a layer opening has no cap");
      std::vector<int32_t> ring = keep_prisms ? ring_quads(*layer, o) : ring_triangles(*layer, o);
      if (side == 1)
        for (int32_t& v : ring) v = outer_id(v);
      const int32_t tag = side == 0 ? cap : outer_wall + cap;
      if (keep_prisms) {
        m.quads.insert(m.quads.end(), ring.begin(), ring.end());
        m.quad_tag.insert(m.quad_tag.end(), ring.size() / 4, tag);
      } else {
        m.triangles.insert(m.triangles.end(), ring.begin(), ring.end());
        m.triangle_tag.insert(m.triangle_tag.end(), ring.size() / 3, tag);
      }
    }
  }
  out.ring_end = m.num_triangles();
  if (outer) {
    for (int32_t v : ou.front) m.triangles.push_back(outer_id(v));
    m.triangle_tag.resize(m.num_triangles(), outer_wall);
  }
  return out;
}

}  // namespace vm
