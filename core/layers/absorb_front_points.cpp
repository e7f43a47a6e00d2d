// Absorbing the core's points on the layer front in its top slice (see
// absorb_front_points.h; our own method). Phases: the pieces of each split
// front triangle and their boundary, side by side; the cone of tetrahedra
// of each split prism; the rim faces that change; the exact check.
#include "core/layers/absorb_front_points.h"

#include <algorithm>
#include <array>
#include <string>
#include <utility>

#include "core/geom/predicates.h"

namespace vm {
namespace {

// A split front triangle: its corners (column ids, front orientation) and,
// per side i (corner i to corner i + 1), the new points on it in that
// order (column ids >= nv).
struct SplitTriangle {
  std::array<int32_t, 3> corner{};
  std::array<std::vector<int32_t>, 3> side;
};

// Phase 1 for one parent: the boundary of its pieces (3 column ids each)
// walked from corner 0, cut at the corners. False when the pieces are not
// one disc with the corners on its boundary, in order, and only new points
// between them.
bool split_sides(const std::vector<std::array<int32_t, 3>>& pieces, size_t nv, SplitTriangle& s) {
  std::vector<std::pair<int32_t, int32_t>> edges, boundary;
  for (const auto& p : pieces)
    for (int k = 0; k < 3; ++k) edges.push_back({p[size_t(k)], p[size_t((k + 1) % 3)]});
  for (const auto& [a, b] : edges)
    if (std::find(edges.begin(), edges.end(), std::pair{b, a}) == edges.end())
      boundary.push_back({a, b});
  int32_t v = s.corner[0];
  size_t side = 0;
  for (size_t step = 0; step < boundary.size(); ++step) {
    auto it = std::find_if(boundary.begin(), boundary.end(),
                           [&](const std::pair<int32_t, int32_t>& e) { return e.first == v; });
    if (it == boundary.end()) return false;
    v = it->second;
    if (side < 3 && v == s.corner[(side + 1) % 3]) {
      ++side;
    } else if (side < 3 && size_t(v) >= nv) {
      s.side[side].push_back(v);
    } else {
      return false;
    }
  }
  return side == 3 && v == s.corner[0];
}

// The polygon of a side face (front corner u, the new points on the side,
// front corner w, then w and u on layer N - 1), oriented out of the prism,
// cut as a fan from its smallest id (a layer N - 1 point): 3 ids a
// triangle, oriented like the polygon.
std::vector<int32_t> side_fan(const std::vector<int32_t>& polygon) {
  const size_t n = polygon.size();
  const size_t f = size_t(std::min_element(polygon.begin(), polygon.end(),
                                           [](int32_t a, int32_t b) {
                                             // New points (negative ids) are never the smallest.
                                             if ((a < 0) != (b < 0)) return a >= 0;
                                             return a < b;
                                           }) -
                          polygon.begin());
  std::vector<int32_t> tris;
  for (size_t j = 1; j + 1 < n; ++j)
    tris.insert(tris.end(), {polygon[f], polygon[(f + j) % n], polygon[(f + j + 1) % n]});
  return tris;
}

}  // namespace

Result<AbsorbedFront> absorb_front_points(const LayerMesh& m, const std::vector<int32_t>& triangles,
                                          const std::vector<int32_t>& parent,
                                          const std::vector<double>& new_points) {
  using R = Result<AbsorbedFront>;
  const size_t nv = m.wall_vertices, nt = m.wall_triangles, n_new = new_points.size() / 3;
  const size_t nt2 = triangles.size() / 3;
  if (m.outward || m.layers < 1) return R::Error("absorb front points: an inward layer is needed");
  if (triangles.size() % 3 != 0 || new_points.size() % 3 != 0 || parent.size() != nt2)
    return R::Error("absorb front points: sizes of triangles, parents and new points do not match");
  for (int32_t v : triangles)
    if (v < 0 || size_t(v) >= nv + n_new)
      return R::Error("absorb front points: a column id is out of range");
  for (int32_t p : parent)
    if (p < 0 || size_t(p) >= nt) return R::Error("absorb front points: a parent is out of range");
  const int n = m.layers;
  const int32_t top = m.layer_vertex(0, n);
  auto top_id = [&](int32_t c) {
    return size_t(c) < nv ? m.layer_vertex(c, n) : -1 - (c - int32_t(nv));
  };
  auto below_id = [&](int32_t c) { return m.layer_vertex(c, n - 1); };
  auto point = [&](int32_t id) {
    return id >= 0 ? &m.points[3 * size_t(id)] : &new_points[3 * size_t(-1 - id)];
  };

  // Phase 1: the pieces of each parent (counting sort, in triangle order),
  // and the split parents' sides.
  std::vector<int32_t> first(nt + 1, 0), order(nt2);
  for (int32_t p : parent) ++first[size_t(p) + 1];
  for (size_t t = 0; t < nt; ++t) first[t + 1] += first[t];
  {
    std::vector<int32_t> fill(first.begin(), first.end() - 1);
    for (size_t t = 0; t < nt2; ++t) order[size_t(fill[size_t(parent[t])]++)] = int32_t(t);
  }
  AbsorbedFront out;
  std::vector<std::array<int32_t, 3>> pieces;
  for (size_t t = 0; t < nt; ++t) {
    pieces.clear();
    bool has_new = false;
    for (int32_t i = first[t]; i < first[t + 1]; ++i) {
      const int32_t* v = &triangles[3 * size_t(order[size_t(i)])];
      pieces.push_back({v[0], v[1], v[2]});
      for (int k = 0; k < 3; ++k) has_new |= size_t(v[k]) >= nv;
    }
    if (!has_new) continue;
    SplitTriangle s;
    for (int k = 0; k < 3; ++k) s.corner[size_t(k)] = m.front[3 * t + size_t(k)] - top;
    if (!split_sides(pieces, nv, s))
      return R::Error("absorb front points: the pieces of front triangle " + std::to_string(t) +
                      " do not tile it");
    out.replaced_prisms.push_back(int32_t(size_t(n - 1) * nt + t));
    // Phase 2: the cone from the smallest bottom corner: over the front's
    // pieces (oriented out of the vessel, toward the apex), and over the
    // side opposite the apex (the fan's triangles point out of the prism).
    const size_t a = size_t(std::min_element(s.corner.begin(), s.corner.end()) - s.corner.begin());
    const int32_t apex = below_id(s.corner[a]);
    for (const auto& p : pieces)
      out.tets.insert(out.tets.end(), {top_id(p[0]), top_id(p[1]), top_id(p[2]), apex});
    for (size_t i = 0; i < 3; ++i) {
      const int32_t u = s.corner[i], w = s.corner[(i + 1) % 3];
      std::vector<int32_t> polygon = {top_id(u)};
      for (int32_t c : s.side[i]) polygon.push_back(top_id(c));
      polygon.insert(polygon.end(), {top_id(w), below_id(w), below_id(u)});
      const std::vector<int32_t> fan = side_fan(polygon);
      if (i == (a + 1) % 3)
        for (size_t f = 0; f < fan.size(); f += 3)
          out.tets.insert(out.tets.end(), {fan[f], fan[f + 2], fan[f + 1], apex});
      // Phase 3: a side on an opening's rim with new points is a ring face.
      if (s.side[i].empty()) continue;
      for (size_t o = 0; o < m.openings.size(); ++o) {
        const std::vector<int32_t>& rim = m.openings[o].rim;
        const size_t r = rim.size();
        const auto iu = std::find(rim.begin(), rim.end(), u);
        if (iu == rim.end()) continue;
        const size_t k = size_t(iu - rim.begin());
        if (rim[(k + 1) % r] != w && rim[(k + r - 1) % r] != w) break;
        out.ring_quads.insert(out.ring_quads.end(),
                              {below_id(u), below_id(w), top_id(w), top_id(u)});
        out.ring_opening.push_back(int32_t(o));
        out.ring_triangles.insert(out.ring_triangles.end(), fan.begin(), fan.end());
        out.ring_first.push_back(int32_t(out.ring_triangles.size() / 3));
        break;
      }
    }
  }

  // Phase 4: every tetrahedron strictly positive (exact).
  for (size_t t = 0; t < out.tets.size(); t += 4) {
    const int32_t* v = &out.tets[t];
    if (!(orient3d(point(v[0]), point(v[1]), point(v[2]), point(v[3])) < 0)) {
      const double* q = point(v[3]);
      return R::Error("absorb front points: a tetrahedron of the top slice near (" +
                      std::to_string(q[0]) + ", " + std::to_string(q[1]) + ", " +
                      std::to_string(q[2]) + ") is not positive");
    }
  }
  return out;
}

}  // namespace vm
