// Re-surfacing where a surface crosses itself (resurface_crossings.h).
#include "core/prepare/resurface_crossings.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "core/mesh/adjacency.h"
#include "core/mesh/boundary_loops.h"
#include "core/mesh/bridge_loops.h"
#include "core/mesh/marching_cubes.h"
#include "core/mesh/repair.h"
#include "core/mesh/self_intersection.h"
#include "core/mesh/surface_distance.h"
#include "core/mesh/topology.h"
#include "core/mesh/winding_number.h"
#include "core/util/parallel.h"

namespace vm {

size_t ResurfaceReport::resolved() const {
  return size_t(std::count_if(places.begin(), places.end(),
                              [](const ResurfacedPlace& p) { return p.resolved; }));
}

namespace {

struct Box {
  Vec3 lo{}, hi{};
  bool contains(const Vec3& p) const {
    for (int k = 0; k < 3; ++k)
      if (p[size_t(k)] < lo[size_t(k)] || p[size_t(k)] > hi[size_t(k)]) return false;
    return true;
  }
  Box grown(double by) const {
    Box b = *this;
    for (int k = 0; k < 3; ++k) b.lo[size_t(k)] -= by, b.hi[size_t(k)] += by;
    return b;
  }
};

Box triangle_box(const SurfaceMesh& m, size_t t) {
  Box b{at(m.points, m.triangles[3 * t]), at(m.points, m.triangles[3 * t])};
  for (int c = 1; c < 3; ++c) {
    const Vec3 p = at(m.points, m.triangles[3 * t + size_t(c)]);
    for (int k = 0; k < 3; ++k)
      b.lo[size_t(k)] = std::min(b.lo[size_t(k)], p[size_t(k)]),
      b.hi[size_t(k)] = std::max(b.hi[size_t(k)], p[size_t(k)]);
  }
  return b;
}

bool overlap(const Box& a, const Box& b) {
  return boxes_overlap(a.lo.data(), a.hi.data(), b.lo.data(), b.hi.data());
}

/// One place: crossing triangles linked by their pairs or shared vertices.
struct Place {
  std::vector<int32_t> triangles;
  size_t pairs = 0;
  Vec3 where{};
  Box box;
};

// ---- Phase 1: the places, largest first.
std::vector<Place> find_places(const SurfaceMesh& mesh,
                               const std::vector<std::array<int32_t, 2>>& pairs) {
  std::vector<int32_t> parent(mesh.num_triangles(), -1);  // -1: not crossing
  auto find = [&](int32_t x) {
    while (parent[size_t(x)] != x) x = parent[size_t(x)] = parent[size_t(parent[size_t(x)])];
    return x;
  };
  auto join = [&](int32_t a, int32_t b) {
    a = find(a), b = find(b);
    if (a != b) parent[size_t(std::max(a, b))] = std::min(a, b);
  };
  for (const auto& p : pairs)
    for (int32_t t : p)
      if (parent[size_t(t)] < 0) parent[size_t(t)] = t;
  for (const auto& p : pairs) join(p[0], p[1]);
  std::vector<int32_t> first_at_vertex(mesh.num_vertices(), -1);
  for (size_t t = 0; t < parent.size(); ++t) {
    if (parent[t] < 0) continue;
    for (int k = 0; k < 3; ++k) {
      int32_t& first = first_at_vertex[size_t(mesh.triangles[3 * t + size_t(k)])];
      if (first < 0)
        first = int32_t(t);
      else
        join(first, int32_t(t));
    }
  }
  std::vector<int32_t> place_of(mesh.num_triangles(), -1);
  std::vector<Place> places;
  for (size_t t = 0; t < parent.size(); ++t) {
    if (parent[t] < 0) continue;
    const int32_t root = find(int32_t(t));
    if (place_of[size_t(root)] < 0) {
      place_of[size_t(root)] = int32_t(places.size());
      places.emplace_back();
      places.back().box = triangle_box(mesh, t);
    }
    Place& p = places[size_t(place_of[size_t(root)])];
    p.triangles.push_back(int32_t(t));
    const Box b = triangle_box(mesh, t);
    for (int k = 0; k < 3; ++k)
      p.box.lo[size_t(k)] = std::min(p.box.lo[size_t(k)], b.lo[size_t(k)]),
      p.box.hi[size_t(k)] = std::max(p.box.hi[size_t(k)], b.hi[size_t(k)]);
  }
  for (const auto& pr : pairs) ++places[size_t(place_of[size_t(find(pr[0]))])].pairs;
  for (Place& p : places) {
    // The crossing triangle nearest the middle of the box.
    const Vec3 mid = 0.5 * (p.box.lo + p.box.hi);
    double best = -1;
    for (int32_t t : p.triangles) {
      const int32_t* c = &mesh.triangles[3 * size_t(t)];
      const Vec3 q =
          (1.0 / 3) * (at(mesh.points, c[0]) + at(mesh.points, c[1]) + at(mesh.points, c[2]));
      const double d = dot(q - mid, q - mid);
      if (best < 0 || d < best) best = d, p.where = q;
    }
  }
  std::stable_sort(places.begin(), places.end(),
                   [](const Place& a, const Place& b) { return a.pairs > b.pairs; });
  return places;
}

/// The median edge length of the triangles overlapping `box` (0: none).
double median_edge_in(const SurfaceMesh& mesh, const Box& box) {
  std::vector<double> edges;
  for (size_t t = 0; t < mesh.num_triangles(); ++t) {
    if (!overlap(triangle_box(mesh, t), box)) continue;
    for (int k = 0; k < 3; ++k)
      edges.push_back(norm(at(mesh.points, mesh.triangles[3 * t + size_t(k)]) -
                           at(mesh.points, mesh.triangles[3 * t + size_t((k + 1) % 3)])));
  }
  if (edges.empty()) return 0;
  std::nth_element(edges.begin(), edges.begin() + long(edges.size() / 2), edges.end());
  return edges[edges.size() / 2];
}

/// +1 if the surface encloses a positive volume as oriented, else -1.
double orientation_sign(const SurfaceMesh& mesh) {
  double v = 0;
  for (size_t t = 0; t < mesh.num_triangles(); ++t) {
    const int32_t* c = &mesh.triangles[3 * t];
    const Vec3 a = at(mesh.points, c[0]), b = at(mesh.points, c[1]), d = at(mesh.points, c[2]);
    v += dot(a, cross(b, d));
  }
  return v >= 0 ? 1.0 : -1.0;
}

/// What the surface is everywhere the boxes look: its box tree and its
/// winding number tree, built once per state of the mesh.
struct Field {
  const SurfaceMesh& mesh;
  TriangleBvh bvh;
  WindingNumberTree winding;
  double sign = 1;
  explicit Field(const SurfaceMesh& m)
      : mesh(m),
        bvh(build_triangle_bvh(m)),
        winding(build_winding_number_tree(m)),
        sign(orientation_sign(m)) {}
};

// ---- Phase 2-3: the union's boundary inside the grid.
SurfaceMesh union_boundary(const Field& f, const GridSpec& grid) {
  const double v = grid.spacing;
  return marching_cubes(grid, [&](int k, float* plane) {
    parallel_for(size_t(grid.ny), 1, [&](size_t j0, size_t j1) {
      for (size_t j = j0; j < j1; ++j)
        for (int i = 0; i < grid.nx; ++i) {
          const double q[3] = {grid.origin[0] + v * i, grid.origin[1] + v * double(j),
                               grid.origin[2] + v * k};
          const double d = closest_surface_point(f.mesh, f.bvh, q).distance / v;
          const bool inside = f.sign * winding_number(f.mesh, f.winding, q) >= 0.5;
          const double mag = std::max(d, 1e-3);
          plane[size_t(i) + size_t(grid.nx) * j] = float(inside ? -mag : mag);
        }
    });
  });
}

/// Triangles of closed components of `piece` smaller than `min_triangles`
/// removed (bubbles of the level set, not the union's boundary).
void drop_small_closed(SurfaceMesh& piece, size_t min_triangles) {
  const TriangleAdjacency adj = build_adjacency(piece);
  const TopologyReport t = analyze_topology(piece, adj);
  if (t.components <= 1) return;
  std::vector<uint8_t> open(size_t(t.components), 0);
  for (size_t h = 0; h < adj.opposite.size(); ++h)
    if (adj.opposite[h] == TriangleAdjacency::kBoundary)
      open[size_t(t.triangle_component[h / 3])] = 1;
  std::vector<uint8_t> remove(piece.num_triangles(), 0);
  bool any = false;
  for (size_t tr = 0; tr < remove.size(); ++tr) {
    const size_t c = size_t(t.triangle_component[tr]);
    remove[tr] = !open[c] && t.component_triangles[c] < min_triangles;
    any |= remove[tr] != 0;
  }
  if (any) remove_triangles(piece, remove);
}

double loop_radius(const SurfaceMesh& mesh, const std::vector<int32_t>& loop) {
  return describe_loop(mesh, loop).radius;
}

/// Whether some triangle of `triangles` (3 ids each) has the directed edge
/// u -> v.
bool strip_has_edge(const std::vector<int32_t>& triangles, int32_t u, int32_t v) {
  for (size_t t = 0; t < triangles.size(); t += 3)
    for (int k = 0; k < 3; ++k)
      if (triangles[t + size_t(k)] == u && triangles[t + size_t((k + 1) % 3)] == v) return true;
  return false;
}

/// One try: the surface with the part in `box` replaced, or why not.
struct Attempt {
  SurfaceMesh mesh;
  std::vector<int32_t> labels;
  size_t removed = 0, added = 0;
  bool ok = false;
  bool near_opening = false;
  std::string why;
};

Attempt try_box(const SurfaceMesh& mesh, const std::vector<int32_t>* labels, const Field& field,
                const std::vector<std::vector<int32_t>>& openings, Box box, double voxel) {
  Attempt out;
  // The grid: box corners on grid points.
  GridSpec grid;
  int n[3];
  for (int k = 0; k < 3; ++k) {
    n[k] = std::max(2, int(std::ceil((box.hi[size_t(k)] - box.lo[size_t(k)]) / voxel))) + 1;
    box.hi[size_t(k)] = box.lo[size_t(k)] + voxel * (n[k] - 1);
    grid.origin[k] = box.lo[size_t(k)];
  }
  grid.nx = n[0], grid.ny = n[1], grid.nz = n[2];
  grid.spacing = voxel;
  // An opening in the box: the union is not defined across it.
  for (const std::vector<int32_t>& loop : openings) {
    bool inside = false;
    for (int32_t v : loop) inside |= box.contains(at(mesh.points, v));
    if (inside && loop_radius(mesh, loop) > 2 * voxel) {
      out.near_opening = true;
      out.why = "an opening of the surface lies in the box";
      return out;
    }
  }
  SurfaceMesh piece = union_boundary(field, grid);
  drop_small_closed(piece, 64);
  if (field.sign < 0)  // the file's surface faces inward: so does the piece
    for (size_t t = 0; t < piece.num_triangles(); ++t)
      std::swap(piece.triangles[3 * t + 1], piece.triangles[3 * t + 2]);
  if (piece.num_triangles() == 0) {
    out.why = "nothing of the union's boundary in the box";
    return out;
  }
  // Phase 4: the triangles touching the box go; their loops meet the piece's.
  std::vector<uint8_t> remove(mesh.num_triangles(), 0);
  for (size_t t = 0; t < remove.size(); ++t) remove[t] = overlap(triangle_box(mesh, t), box);
  SurfaceMesh removed_part;
  std::vector<int32_t> removed_labels;
  for (size_t t = 0; t < remove.size(); ++t) {
    if (!remove[t]) continue;
    ++out.removed;
    for (int k = 0; k < 3; ++k) {
      removed_part.triangles.push_back(int32_t(removed_part.points.size() / 3));
      const Vec3 p = at(mesh.points, mesh.triangles[3 * t + size_t(k)]);
      removed_part.points.insert(removed_part.points.end(), p.begin(), p.end());
    }
    if (labels) removed_labels.push_back((*labels)[t]);
  }
  std::vector<uint8_t> touched(mesh.num_vertices(), 0);  // vertices of removed triangles
  for (size_t t = 0; t < remove.size(); ++t)
    if (remove[t])
      for (int k = 0; k < 3; ++k) touched[size_t(mesh.triangles[3 * t + size_t(k)])] = 1;
  out.mesh = mesh;
  if (labels) out.labels = *labels;
  const std::vector<int32_t> remap =
      remove_triangles(out.mesh, remove, labels ? &out.labels : nullptr);
  std::vector<uint8_t> touched_now(out.mesh.num_vertices(), 0);
  for (size_t v = 0; v < remap.size(); ++v)
    if (remap[v] >= 0 && touched[v]) touched_now[size_t(remap[v])] = 1;
  const TriangleAdjacency kept_adj = build_adjacency(out.mesh);
  std::vector<std::vector<int32_t>> kept_loops;
  for (std::vector<int32_t>& loop : boundary_loops(out.mesh, kept_adj)) {
    const bool fresh = std::any_of(loop.begin(), loop.end(),
                                   [&](int32_t v) { return touched_now[size_t(v)] != 0; });
    if (fresh) kept_loops.push_back(std::move(loop));
  }
  const TriangleAdjacency piece_adj = build_adjacency(piece);
  std::vector<std::vector<int32_t>> piece_loops = boundary_loops(piece, piece_adj);
  if (piece_loops.size() != kept_loops.size()) {
    out.why = "the new piece meets the box in " + std::to_string(piece_loops.size()) +
              " loops, the surface left around it in " + std::to_string(kept_loops.size());
    return out;
  }
  // The piece's points after the kept surface's.
  const int32_t base = int32_t(out.mesh.num_vertices());
  const size_t first_new = out.mesh.num_triangles();
  out.mesh.points.insert(out.mesh.points.end(), piece.points.begin(), piece.points.end());
  for (int32_t v : piece.triangles) out.mesh.triangles.push_back(base + v);
  for (auto& loop : piece_loops)
    for (int32_t& v : loop) v += base;
  // Pair each kept loop with the piece loop nearest it (mean distance of
  // its vertices to the other's nearest vertex), one to one.
  auto mean_distance = [&](const std::vector<int32_t>& a, const std::vector<int32_t>& b) {
    double sum = 0;
    for (int32_t u : a) {
      double best = std::numeric_limits<double>::infinity();
      for (int32_t w : b)
        best = std::min(best, norm(at(out.mesh.points, u) - at(out.mesh.points, w)));
      sum += best;
    }
    return sum / double(a.size());
  };
  std::vector<int32_t> partner(kept_loops.size(), -1);
  std::vector<uint8_t> taken(piece_loops.size(), 0);
  for (size_t i = 0; i < kept_loops.size(); ++i) {
    double best = std::numeric_limits<double>::infinity();
    for (size_t j = 0; j < piece_loops.size(); ++j) {
      const double d = mean_distance(kept_loops[i], piece_loops[j]);
      if (d < best) best = d, partner[i] = int32_t(j);
    }
    if (partner[i] < 0 || taken[size_t(partner[i])]) {
      out.why = "the loops around the box do not pair one to one";
      return out;
    }
    taken[size_t(partner[i])] = 1;
  }
  for (size_t i = 0; i < kept_loops.size(); ++i) {
    std::vector<int32_t> b = piece_loops[size_t(partner[i])];
    if (loops_agreement(out.mesh.points, kept_loops[i], b) < 0) std::reverse(b.begin(), b.end());
    std::vector<int32_t> strip = bridge_loops(out.mesh.points, kept_loops[i], b);
    // The strip faces the way of the surface it continues: the kept loop
    // runs along its triangles' edges (boundary_loops), so the strip runs
    // along them the other way.
    const std::vector<int32_t>& a = kept_loops[i];
    if (strip_has_edge(strip, a[0], a[1]))
      for (size_t t = 0; t < strip.size(); t += 3) std::swap(strip[t + 1], strip[t + 2]);
    out.mesh.triangles.insert(out.mesh.triangles.end(), strip.begin(), strip.end());
  }
  out.added = out.mesh.num_triangles() - first_new;
  // Phase 5: the new triangles make a closed, non-crossing sheet with the
  // rest: every edge of a new triangle has two triangles, none crosses.
  const TriangleAdjacency adj = build_adjacency(out.mesh);
  for (size_t h = 3 * first_new; h < adj.opposite.size(); ++h)
    if (adj.opposite[h] < 0) {
      out.why = "the sewn surface has an edge with one or more than two triangles";
      return out;
    }
  std::vector<uint8_t> fresh(out.mesh.num_triangles(), 0);
  std::fill(fresh.begin() + long(first_new), fresh.end(), 1);
  const SelfIntersectionReport crossing = find_self_intersections_of(out.mesh, fresh, 1);
  if (crossing.pairs > 0) {
    out.why = std::to_string(crossing.pairs) + " pairs of triangles still cross";
    return out;
  }
  if (labels) {
    const TriangleBvh bvh = build_triangle_bvh(removed_part);
    for (size_t t = first_new; t < out.mesh.num_triangles(); ++t) {
      const int32_t* c = &out.mesh.triangles[3 * t];
      const Vec3 q = (1.0 / 3) * (at(out.mesh.points, c[0]) + at(out.mesh.points, c[1]) +
                                  at(out.mesh.points, c[2]));
      const SurfacePoint s = closest_surface_point(removed_part, bvh, q.data());
      out.labels.push_back(s.triangle >= 0 ? removed_labels[size_t(s.triangle)] : -1);
    }
  }
  out.ok = true;
  return out;
}

/// Per triangle, whether it lies in a piece (triangles linked by shared
/// vertices) with less than `fraction` of the triangles: a stray fragment
/// that the speck removal drops, not to be re-surfaced with the wall.
std::vector<uint8_t> in_small_piece(const SurfaceMesh& mesh, double fraction) {
  std::vector<int32_t> parent(mesh.num_vertices());
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int32_t x) {
    while (parent[size_t(x)] != x) x = parent[size_t(x)] = parent[size_t(parent[size_t(x)])];
    return x;
  };
  for (size_t t = 0; t < mesh.num_triangles(); ++t)
    for (int k = 1; k < 3; ++k) {
      const int32_t a = find(mesh.triangles[3 * t]), b = find(mesh.triangles[3 * t + size_t(k)]);
      if (a != b) parent[size_t(std::max(a, b))] = std::min(a, b);
    }
  std::vector<size_t> count(mesh.num_vertices(), 0);
  for (size_t t = 0; t < mesh.num_triangles(); ++t) ++count[size_t(find(mesh.triangles[3 * t]))];
  std::vector<uint8_t> small(mesh.num_triangles());
  for (size_t t = 0; t < small.size(); ++t)
    small[t] = double(count[size_t(find(mesh.triangles[3 * t]))]) <
               fraction * double(mesh.num_triangles());
  return small;
}

}  // namespace

ResurfaceReport resurface_crossings(SurfaceMesh& mesh, std::vector<int32_t>* labels,
                                    const ResurfaceOptions& options) {
  ResurfaceReport report;
  if (labels && labels->size() != mesh.num_triangles()) labels = nullptr;
  std::vector<Box> given_up;  // boxes of places left as they were
  bool changed = true;        // since the pairs were last found
  for (int round = 0; round < 32; ++round) {
    SelfIntersectionReport found = find_self_intersections(mesh, 4'000'000);
    report.left = std::move(found.examples);
    changed = false;
    if (round == 0) report.pairs = found.pairs;
    if (found.pairs == 0) break;
    // Pairs with a stray fragment are left to the speck removal.
    const std::vector<uint8_t> small = in_small_piece(mesh, 0.01);
    std::vector<std::array<int32_t, 2>> pairs;
    for (const auto& p : report.left)
      if (!small[size_t(p[0])] && !small[size_t(p[1])]) pairs.push_back(p);
    if (pairs.empty()) break;
    std::vector<Place> places = find_places(mesh, pairs);
    auto fresh = std::find_if(places.begin(), places.end(), [&](const Place& p) {
      return std::none_of(given_up.begin(), given_up.end(),
                          [&](const Box& b) { return b.contains(p.where); });
    });
    if (fresh == places.end()) break;
    const Place& place = *fresh;
    ResurfacedPlace done;
    done.where = place.where;
    done.pairs = place.pairs;
    const double edge = median_edge_in(mesh, place.box);
    double voxel = options.voxel_edges * edge;
    const Field field(mesh);
    const TriangleAdjacency adj = build_adjacency(mesh);
    const std::vector<std::vector<int32_t>> openings = boundary_loops(mesh, adj);
    double margin = options.margin_voxels * voxel;
    Box box = place.box.grown(margin);
    for (int attempt = 0; attempt < options.tries && voxel > 0; ++attempt) {
      const Vec3 extent = box.hi - box.lo;
      const double longest = std::max({extent[0], extent[1], extent[2]});
      const double v = std::max(voxel, longest / (options.max_cells - 1));
      Attempt a = try_box(mesh, labels, field, openings, box, v);
      done.box_min = box.lo, done.box_max = box.hi, done.voxel = v;
      done.why = a.why;
      done.near_opening = a.near_opening;
      if (a.ok) {
        mesh = std::move(a.mesh);
        if (labels) *labels = std::move(a.labels);
        done.resolved = true;
        changed = true;
        done.triangles_removed = a.removed;
        done.triangles_added = a.added;
        done.why.clear();
        break;
      }
      if (a.near_opening) break;
      margin *= 2;
      box = place.box.grown(margin);
    }
    if (!done.resolved) given_up.push_back(place.box.grown(margin));
    report.places.push_back(done);
  }
  if (changed) report.left = find_self_intersections(mesh, 4'000'000).examples;
  return report;
}

}  // namespace vm
