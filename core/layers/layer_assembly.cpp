// Ring faces, prism split, front surface and the standalone layer volume
// (see layer_assembly.h; Marchandise et al., section 2.2).
#include "core/layers/layer_assembly.h"

#include <algorithm>

#include "core/mesh/prism_split.h"

namespace vm {

std::vector<int32_t> ring_quads_of_columns(const std::vector<int32_t>& columns, int layers,
                                           bool outward) {
  const size_t c = size_t(layers) + 1, n = columns.size() / c;
  std::vector<int32_t> quads;
  quads.reserve(4 * n * size_t(layers));
  for (size_t i = 0; i < n; ++i) {
    const int32_t* a = &columns[c * i];
    const int32_t* b = &columns[c * ((i + 1) % n)];
    // a -> b runs clockwise around the normal; the columns go inward of
    // the rim (inward layers) or outward of it.
    for (size_t k = 0; k + 1 < c; ++k) {
      if (outward)
        quads.insert(quads.end(), {a[k], b[k], b[k + 1], a[k + 1]});
      else
        quads.insert(quads.end(), {a[k], a[k + 1], b[k + 1], b[k]});
    }
  }
  return quads;
}

std::vector<int32_t> split_quads(const std::vector<int32_t>& quads) {
  std::vector<int32_t> tris;
  tris.reserve(quads.size() / 4 * 6);
  for (size_t q = 0; q + 4 <= quads.size(); q += 4) {
    const int32_t* v = &quads[q];
    const size_t i = size_t(std::min_element(v, v + 4) - v);
    const int32_t a = v[i], b = v[(i + 1) % 4], c = v[(i + 2) % 4], d = v[(i + 3) % 4];
    tris.insert(tris.end(), {a, b, c, a, c, d});
  }
  return tris;
}

std::vector<int32_t> ring_quads(const LayerMesh& m, size_t o) {
  return ring_quads_of_columns(m.openings[o].columns, m.layers, m.outward);
}

std::vector<int32_t> ring_triangles(const LayerMesh& m, size_t o) {
  return split_quads(ring_quads(m, o));
}

std::vector<int32_t> prisms_to_tets(const std::vector<int32_t>& prisms) {
  std::vector<int32_t> tets;
  tets.reserve(prisms.size() * 2);
  for (size_t p = 0; p + 6 <= prisms.size(); p += 6)
    for (const auto& t : split_prism(&prisms[p])) tets.insert(tets.end(), t.begin(), t.end());
  return tets;
}

SurfaceMesh front_surface(const LayerMesh& m) {
  SurfaceMesh s;
  const size_t nv = m.wall_vertices;
  const int32_t top = m.layer_vertex(0, m.layers);
  s.points.assign(m.points.begin() + std::ptrdiff_t(3 * size_t(top)),
                  m.points.begin() + std::ptrdiff_t(3 * (size_t(top) + nv)));
  s.triangles = m.front;
  for (int32_t& v : s.triangles) v -= top;
  return s;
}

VolumeMesh layer_volume(const LayerMesh& m, bool split) {
  VolumeMesh vol;
  vol.points = m.points;
  if (split) {
    vol.tets = prisms_to_tets(m.prisms);
    vol.tet_region.assign(vol.num_tets(), 0);
  } else {
    vol.prisms = m.prisms;
    vol.prism_region.assign(vol.num_prisms(), 0);
  }
  // Inward, the region lies inside the wall and outside the front;
  // outward, the reverse: the surface it lies outside of is reversed.
  const int32_t top = m.layer_vertex(0, m.layers);
  for (int pass = 0; pass < 2; ++pass)
    for (size_t t = 0; t < m.wall_triangles; ++t) {
      const int32_t* f = &m.front[3 * t];
      const int32_t shift = pass == 0 ? top : 0;
      const int32_t a = f[0] - shift, b = f[1] - shift, c = f[2] - shift;
      const bool reversed = (pass == 0) == m.outward;
      vol.triangles.insert(vol.triangles.end(), {a, reversed ? c : b, reversed ? b : c});
      vol.triangle_tag.push_back(pass);
    }
  if (split)
    for (size_t o = 0; o < m.openings.size(); ++o) {
      const std::vector<int32_t> ring = ring_triangles(m, o);
      vol.triangles.insert(vol.triangles.end(), ring.begin(), ring.end());
      vol.triangle_tag.insert(vol.triangle_tag.end(), ring.size() / 3, int32_t(2 + o));
    }
  return vol;
}

}  // namespace vm
