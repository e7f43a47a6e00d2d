// Lumen and vessel-wall assembly (Marchandise et al., section 2.2), in
// phases: the recovery's Steiner points on the core's boundary stay in the
// viscous layer's top slice, or become new layer columns; points are
// numbered (inner layer, outer layer, core);
// elements and regions; surfaces and their names.
#include "core/layers/layered_volume.h"

#include <algorithm>
#include <optional>
#include <utility>

#include "core/layers/absorb_front_points.h"
#include "core/layers/flip_wall_edges.h"
#include "core/layers/layer_assembly.h"
#include "core/layers/refine_layers.h"
#include "core/layers/slide_wall_points.h"

namespace vm {
namespace {

/// The tag of the cap closing layer opening `op` (the cap whose rim holds
/// op's first rim vertex), or -1.
int32_t cap_tag_of(const CappedSurface& caps, const LayerOpening& op) {
  for (const CapInfo& c : caps.caps)
    if (std::find(c.rim.begin(), c.rim.end(), op.rim[0]) != c.rim.end()) return c.tag;
  return -1;
}

/// The edge (a, b) on which vertex v of a refined triangulation lies: the
/// triangles `tris` (3 ids each; with `tags`, only those tagged 0) using v
/// have exactly two parents, triangles of `parent_tris` (3 ids each, minus
/// `shift`), and these share the edge (a, b). Else (-1, -1).
std::pair<int32_t, int32_t> shared_edge(const std::vector<int32_t>& parent_tris, int32_t shift,
                                        const std::vector<int32_t>& tris,
                                        const std::vector<int32_t>& parent, int32_t v,
                                        const std::vector<int32_t>* tags = nullptr) {
  int32_t p[2] = {-1, -1};
  for (size_t t = 0; t < tris.size() / 3; ++t) {
    if ((tags && (*tags)[t] != 0) ||
        std::find(&tris[3 * t], &tris[3 * t] + 3, v) == &tris[3 * t] + 3)
      continue;
    const int32_t q = parent[t];
    if (q == p[0] || q == p[1]) continue;
    if (p[1] >= 0) return {-1, -1};  // a third parent
    (p[0] < 0 ? p[0] : p[1]) = q;
  }
  if (p[1] < 0) return {-1, -1};
  const int32_t* x = &parent_tris[3 * size_t(p[0])];
  const int32_t* y = &parent_tris[3 * size_t(p[1])];
  std::vector<int32_t> common;
  for (int i = 0; i < 3; ++i)
    if (std::find(y, y + 3, x[i]) != y + 3) common.push_back(x[i] - shift);
  if (common.size() != 2) return {-1, -1};
  return {common[0], common[1]};
}

/// Ring triangles `ring` (3 ids each) of opening `o` with the top-slice
/// faces `a` changes replaced: those whose corners are all corners of one of
/// its quads of `o` are left out, and its triangles there appended (ids
/// through `id`).
template <class Id>
void replace_ring_faces(const AbsorbedFront& a, int32_t o, const Id& id,
                        std::vector<int32_t>& ring) {
  std::vector<int32_t> kept;
  for (size_t t = 0; t < ring.size(); t += 3) {
    bool replaced = false;
    for (size_t q = 0; q < a.ring_opening.size() && !replaced; ++q) {
      if (a.ring_opening[q] != o) continue;
      const int32_t* quad = &a.ring_quads[4 * q];
      replaced = std::all_of(&ring[t], &ring[t] + 3,
                             [&](int32_t v) { return std::find(quad, quad + 4, v) != quad + 4; });
    }
    if (!replaced) kept.insert(kept.end(), &ring[t], &ring[t] + 3);
  }
  for (size_t q = 0; q < a.ring_opening.size(); ++q) {
    if (a.ring_opening[q] != o) continue;
    for (int32_t i = 3 * a.ring_first[q]; i < 3 * a.ring_first[q + 1]; ++i)
      kept.push_back(id(a.ring_triangles[size_t(i)]));
  }
  ring.swap(kept);
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
  std::vector<int32_t> column(rec.num_vertices(), -1), tri, parent, new_vertex, wall_steiner;
  std::vector<double> new_points;
  LayerMesh in, ou;
  std::vector<int32_t> wall_tris;  // the base layer's wall triangles, as the recovery flipped them
  std::optional<AbsorbedFront> absorbed;
  if (base) {
    for (size_t v = 0; v < nv; ++v) column[v] = int32_t(v);
    for (size_t t = 0; t < rec.num_triangles(); ++t) {
      if (rec.triangle_tag[t] != 0) continue;
      for (int k = 0; k < 3; ++k) {
        const int32_t i = rec.triangles[3 * t + size_t(k)];
        if (column[size_t(i)] < 0) {
          column[size_t(i)] = int32_t(nv + new_points.size() / 3);
          new_vertex.push_back(i);
          new_points.insert(new_points.end(), &rec.points[3 * size_t(i)],
                            &rec.points[3 * size_t(i)] + 3);
        }
        tri.push_back(column[size_t(i)]);
      }
      parent.push_back(recovered.triangle_parent[t]);
    }
    out.front_steiner_points = new_points.size() / 3;
    // The wall edges the recovery flipped (wall_flip_rule) flip in the
    // layers' columns.
    const size_t nt = base->wall_triangles;
    wall_tris.assign(recovered.input_triangles.begin(),
                     recovered.input_triangles.begin() + long(3 * nt));
    const bool flipped =
        !std::equal(wall_tris.begin(), wall_tris.end(), caps.mesh.triangles.begin());
    if (inner) in = flipped ? retriangulate_layer(*inner, wall_tris) : *inner;
    if (outer) ou = flipped ? retriangulate_layer(*outer, wall_tris) : *outer;
    // Points on the viscous layer's front stay in its top slice when its
    // tetrahedra there are valid: the wall keeps its triangles.
    if (inner && !keep_prisms && !new_points.empty()) {
      auto a = absorb_front_points(in, tri, parent, new_points);
      if (a.ok()) {
        absorbed = std::move(a).value();
        out.absorbed_steiner_points = new_points.size() / 3;
        for (int32_t i : new_vertex) column[size_t(i)] = -1;  // core points
      }
    }
    if (!new_points.empty() && !absorbed) {
      if (inner) {
        auto refined = refine_layer_columns(in, tri, parent, new_points, inner->layers);
        if (!refined.ok()) return refined.status();
        in = std::move(refined).value();
      }
      if (outer) {
        // The outer layer follows the (refined) wall: inner's layer 0.
        std::vector<double> wall_points =
            inner ? std::vector<double>(in.points.begin() + long(3 * nv),
                                        in.points.begin() + long(3 * in.wall_vertices))
                  : new_points;
        auto refined = refine_layer_columns(ou, tri, parent, wall_points, 0);
        if (!refined.ok()) return refined.status();
        ou = std::move(refined).value();
      }
      out.wall_steiner_points = new_points.size() / 3;
    }
  } else {
    // No layer: the recovery's points on the wall (tag 0) are the core's.
    for (size_t t = 0; t < rec.num_triangles(); ++t)
      for (int k = 0; k < 3 && rec.triangle_tag[t] == 0; ++k)
        if (size_t(rec.triangles[3 * t + size_t(k)]) >= caps.mesh.num_vertices())
          wall_steiner.push_back(rec.triangles[3 * t + size_t(k)]);
    std::sort(wall_steiner.begin(), wall_steiner.end());
    wall_steiner.erase(std::unique(wall_steiner.begin(), wall_steiner.end()), wall_steiner.end());
    out.wall_steiner_points = wall_steiner.size();
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

  // An id of the absorbed front's (absorb_front_points.h) in the mesh.
  auto absorbed_id = [&](int32_t v) {
    return v >= 0 ? v : core_id[size_t(new_vertex[size_t(-1 - v)])];
  };

  // Phase 3: elements and regions.
  const int32_t inner_region = tag_layer ? kRegionBoundaryLayer : kRegionLumen;
  if (inner && keep_prisms) {
    m.prisms = in.prisms;
    m.prism_region.assign(m.num_prisms(), inner_region);
  } else if (inner && absorbed) {
    // The prisms the top slice's tetrahedra replace are left out.
    std::vector<int32_t> kept;
    kept.reserve(in.prisms.size());
    size_t r = 0;
    for (size_t p = 0; p < in.num_prisms(); ++p) {
      if (r < absorbed->replaced_prisms.size() && size_t(absorbed->replaced_prisms[r]) == p) {
        ++r;
        continue;
      }
      kept.insert(kept.end(), &in.prisms[6 * p], &in.prisms[6 * p] + 6);
    }
    m.tets = prisms_to_tets(kept);
    for (int32_t v : absorbed->tets) m.tets.push_back(absorbed_id(v));
    m.tet_region.assign(m.num_tets(), inner_region);
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
      if (side == 0 && absorbed) replace_ring_faces(*absorbed, int32_t(o), absorbed_id, ring);
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
  // Phase 5: wall points of the recovery (columns carried to the wall, or
  // on a wall without layers) slide along their edges.
  std::vector<WallPointColumn> slide;
  std::vector<int32_t> wall_ids;  // those points in m
  if (base && !absorbed) {
    for (size_t j = 0; j < new_vertex.size(); ++j) {
      const int32_t c = int32_t(nv + j);
      wall_ids.push_back(c);  // layer 0 of column c, inner or outer
      const auto [a, b] = shared_edge(wall_tris, 0, tri, parent, c);
      if (a < 0) continue;
      WallPointColumn col;
      if (inner)
        for (int k = 0; k <= in.layers; ++k)
          col.points.insert(col.points.end(),
                            {in.layer_vertex(c, k), in.layer_vertex(a, k), in.layer_vertex(b, k)});
      if (outer)
        for (int k = inner ? 1 : 0; k <= ou.layers; ++k)
          col.points.insert(col.points.end(),
                            {outer_id(ou.layer_vertex(c, k)), outer_id(ou.layer_vertex(a, k)),
                             outer_id(ou.layer_vertex(b, k))});
      slide.push_back(std::move(col));
    }
  } else if (!base) {
    for (int32_t i : wall_steiner) {
      wall_ids.push_back(core_id[size_t(i)]);
      const auto [a, b] = shared_edge(recovered.input_triangles, 0, rec.triangles,
                                      recovered.triangle_parent, i, &rec.triangle_tag);
      if (a >= 0) slide.push_back({{core_id[size_t(i)], core_id[size_t(a)], core_id[size_t(b)]}});
    }
  }
  if (!slide.empty()) out.reoptimized_steiner_points = slide_wall_points(m, slide, 0).moved;
  for (int32_t v : wall_ids)
    out.wall_steiner_places.insert(out.wall_steiner_places.end(), &m.points[3 * size_t(v)],
                                   &m.points[3 * size_t(v)] + 3);
  return out;
}

}  // namespace vm
