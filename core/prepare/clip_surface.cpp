// Clipping a surface by planes, each removing the part beyond the section
// loop around its point (clip_surface.h).
#include "core/prepare/clip_surface.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "core/geom/vec3.h"
#include "core/mesh/adjacency.h"
#include "core/mesh/level_loops.h"
#include "core/mesh/topology.h"

namespace vm {
namespace {

std::string point_text(const Vec3& p) {
  char buf[96];
  std::snprintf(buf, sizeof(buf), "(%.6g, %.6g, %.6g)", p[0], p[1], p[2]);
  return buf;
}

/// The surface being cut, with what travels with its triangles and vertices.
struct State {
  SurfaceMesh mesh;
  std::vector<int32_t> labels;
  std::vector<int32_t> cut_of_vertex;
  std::vector<int32_t> input_vertex;
};

double triangle_area(const SurfaceMesh& m, size_t t) {
  const int32_t* c = &m.triangles[3 * t];
  const Vec3 n = triangle_cross(&m.points[3 * size_t(c[0])], &m.points[3 * size_t(c[1])],
                                &m.points[3 * size_t(c[2])]);
  return 0.5 * v3::norm(n.data());
}

/// Shape quality of a triangle for choosing a quad's diagonal: area over the
/// sum of squared edge lengths (0 when flat).
double triangle_shape(const double* a, const double* b, const double* c) {
  const Vec3 n = triangle_cross(a, b, c);
  double e[3], s = 0;
  v3::sub(b, a, e), s += v3::dot(e, e);
  v3::sub(c, b, e), s += v3::dot(e, e);
  v3::sub(a, c, e), s += v3::dot(e, e);
  return s > 0 ? v3::norm(n.data()) / s : 0;
}

/// Keeps the triangles with keep[t] != 0 (and the vertices they use).
void compact(State& s, const std::vector<uint8_t>& keep) {
  const size_t nv = s.mesh.num_vertices();
  std::vector<int32_t> remap(nv, -1);
  std::vector<int32_t> tris;
  std::vector<int32_t> labels;
  for (size_t t = 0; t < s.mesh.num_triangles(); ++t) {
    if (!keep[t]) continue;
    for (int k = 0; k < 3; ++k) {
      const int32_t v = s.mesh.triangles[3 * t + size_t(k)];
      remap[size_t(v)] = 0;
      tris.push_back(v);
    }
    if (!s.labels.empty()) labels.push_back(s.labels[t]);
  }
  SurfaceMesh out;
  std::vector<int32_t> cut_of, input;
  for (size_t v = 0; v < nv; ++v) {
    if (remap[v] < 0) continue;
    remap[v] = int32_t(out.num_vertices());
    out.points.insert(out.points.end(), &s.mesh.points[3 * v], &s.mesh.points[3 * v + 3]);
    cut_of.push_back(s.cut_of_vertex[v]);
    input.push_back(s.input_vertex[v]);
  }
  for (int32_t& v : tris) v = remap[size_t(v)];
  out.triangles = std::move(tris);
  s.mesh = std::move(out);
  if (!s.labels.empty()) s.labels = std::move(labels);
  s.cut_of_vertex = std::move(cut_of);
  s.input_vertex = std::move(input);
}

/// One plane's cut of the current surface.
class PlaneCut {
 public:
  PlaneCut(State& s, const ClipPlane& plane, int index, const ClipOptions& o)
      : s_(s), plane_(plane), index_(index), o_(o) {}

  Status run(ClipCut& report);

 private:
  void signed_distances();
  bool snap_keeps_triangles(int32_t v) const;
  Status choose_loop(LevelLoop& chosen) const;
  /// The loop's point ids (a vertex at the plane is its own point, others
  /// get new ids from `next_id`); returns a vertex the loop passes twice, or
  /// -1.
  int32_t point_ids(const LevelLoop& loop, std::vector<int32_t>& ids) const;
  bool above(int32_t v) const { return dz_[size_t(v)] > 0; }

  State& s_;
  ClipPlane plane_;
  int index_;
  const ClipOptions& o_;
  TriangleAdjacency adj_;
  std::vector<double> d_;   ///< signed distance of each vertex to the plane
  std::vector<double> dz_;  ///< the same, 0 for vertices moved onto the plane
  std::vector<uint8_t> no_snap_;
};

void PlaneCut::signed_distances() {
  const SurfaceMesh& m = s_.mesh;
  const size_t nv = m.num_vertices();
  d_.resize(nv);
  for (size_t v = 0; v < nv; ++v) {
    double r[3];
    v3::sub(&m.points[3 * v], plane_.point.data(), r);
    d_[v] = v3::dot(r, plane_.normal.data());
  }
  std::vector<double> shortest(nv, 1e300);
  for (size_t t = 0; t < m.num_triangles(); ++t)
    for (int k = 0; k < 3; ++k) {
      const int32_t a = m.triangles[3 * t + size_t(k)], b = m.triangles[3 * t + size_t(k + 1) % 3];
      double e[3];
      v3::sub(&m.points[3 * size_t(a)], &m.points[3 * size_t(b)], e);
      const double len = v3::norm(e);
      shortest[size_t(a)] = std::min(shortest[size_t(a)], len);
      shortest[size_t(b)] = std::min(shortest[size_t(b)], len);
    }
  dz_ = d_;
  for (size_t v = 0; v < nv; ++v) {
    if (d_[v] == 0) continue;
    if (no_snap_[v] || std::abs(d_[v]) > o_.snap_fraction * shortest[v]) continue;
    if (snap_keeps_triangles(int32_t(v))) dz_[v] = 0;
  }
}

/// Whether moving v onto the plane keeps each of its triangles facing the
/// same way with at least a quarter of its area.
bool PlaneCut::snap_keeps_triangles(int32_t v) const {
  const SurfaceMesh& m = s_.mesh;
  Vec3 moved;
  for (int k = 0; k < 3; ++k)
    moved[size_t(k)] =
        m.points[3 * size_t(v) + size_t(k)] - d_[size_t(v)] * plane_.normal[size_t(k)];
  for (int32_t i = adj_.star_offsets[size_t(v)]; i < adj_.star_offsets[size_t(v) + 1]; ++i) {
    const int32_t* c = &m.triangles[3 * size_t(adj_.star[size_t(i)])];
    const double* p[3];
    const double* q[3];
    for (int k = 0; k < 3; ++k) {
      p[k] = &m.points[3 * size_t(c[k])];
      q[k] = c[k] == v ? moved.data() : p[k];
    }
    const Vec3 before = triangle_cross(p[0], p[1], p[2]);
    const Vec3 after = triangle_cross(q[0], q[1], q[2]);
    if (v3::dot(before.data(), after.data()) <= 0.25 * v3::dot(before.data(), before.data()))
      return false;
  }
  return true;
}

Status PlaneCut::choose_loop(LevelLoop& chosen) const {
  std::vector<LevelLoop> loops = level_loops(s_.mesh, adj_, dz_, 0.0);
  const Vec3& q = plane_.point;
  if (loops.empty())
    return Status::Error("the plane at " + point_text(q) + " with normal " +
                         point_text(plane_.normal) +
                         " does not cut the surface: give a point inside the vessel to cut "
                         "({clip_plane})");
  // The innermost closed loop around the point, else the nearest loop.
  long best = -1;
  double best_radius = 1e300;
  for (size_t i = 0; i < loops.size(); ++i) {
    if (!loops[i].closed || loops[i].size() < 3) continue;
    if (winding_number(loops[i].points, q, plane_.normal) == 0) continue;
    const double r = curve_shape(loops[i].points).radius;
    if (r < best_radius) best = long(i), best_radius = r;
  }
  if (best < 0) {
    double best_distance = 1e300;
    for (size_t i = 0; i < loops.size(); ++i) {
      const double dist = distance_to_polygon(loops[i].points, q);
      if (dist < best_distance) best = long(i), best_distance = dist;
    }
    const LevelLoop& near = loops[size_t(best)];
    const CurveShape shape = curve_shape(near.points);
    if (near.closed && best_distance > o_.reach * shape.radius)
      return Status::Error("the plane at " + point_text(q) + " does not cut the surface within " +
                           number_text(o_.reach * shape.radius) +
                           " of that point (its nearest cut, around " + point_text(shape.centroid) +
                           " with radius " + number_text(shape.radius) + ", passes " +
                           number_text(best_distance) +
                           " away): put the point inside the vessel to cut, at the centre of "
                           "its section ({clip_plane})");
  }
  chosen = std::move(loops[size_t(best)]);
  if (!chosen.closed) {
    const Vec3 end = {chosen.points[chosen.points.size() - 3],
                      chosen.points[chosen.points.size() - 2], chosen.points.back()};
    return Status::Error("the cut of the plane at " + point_text(q) +
                         " runs into an opening of the surface near " + point_text(end) +
                         ": move the plane away from the opening or turn it ({clip_plane})");
  }
  return Status::Ok();
}

int32_t PlaneCut::point_ids(const LevelLoop& loop, std::vector<int32_t>& ids) const {
  int32_t next_id = int32_t(s_.mesh.num_vertices());
  ids.resize(loop.size());
  for (size_t i = 0; i < loop.size(); ++i) {
    const int32_t below = loop.edges[i][0];
    ids[i] = dz_[size_t(below)] == 0 ? below : next_id++;
  }
  // A vertex the loop meets twice (not in a row) would pinch the opening.
  std::vector<std::pair<int32_t, size_t>> seen;
  for (size_t i = 0; i < ids.size(); ++i)
    if (ids[i] < int32_t(s_.mesh.num_vertices()) &&
        ids[i] != ids[(i + ids.size() - 1) % ids.size()])
      seen.emplace_back(ids[i], i);
  std::sort(seen.begin(), seen.end());
  for (size_t i = 1; i < seen.size(); ++i)
    if (seen[i].first == seen[i - 1].first) return seen[i].first;
  return -1;
}

Status PlaneCut::run(ClipCut& report) {
  SurfaceMesh& m = s_.mesh;
  const double len = v3::norm(plane_.normal.data());
  if (!(len > 0) || !std::isfinite(len))
    return Status::Error("the plane at " + point_text(plane_.point) +
                         " has no normal: give a nonzero normal ({clip_plane})");
  for (double& x : plane_.normal) x /= len;
  report.plane = plane_;
  adj_ = build_adjacency(m);
  no_snap_.assign(m.num_vertices(), 0);
  const Vec3& n = plane_.normal;

  // Trace and choose the loop; a vertex at the plane that the loop passes
  // twice is left off the plane (moved slightly back if it lies on it).
  LevelLoop loop;
  std::vector<int32_t> ids;
  for (int attempt = 0;; ++attempt) {
    signed_distances();
    if (Status st = choose_loop(loop); !st.ok()) return st;
    const int32_t pinch = point_ids(loop, ids);
    if (pinch < 0) break;
    if (attempt > 64)
      return Status::Internal(
          "the cut at " + point_text(plane_.point) + " keeps touching itself at " +
          point_text({m.points[3 * size_t(pinch)], m.points[3 * size_t(pinch) + 1],
                      m.points[3 * size_t(pinch) + 2]}));
    no_snap_[size_t(pinch)] = 1;
    if (d_[size_t(pinch)] == 0) {
      double shortest = 1e300;
      for (int32_t i = adj_.star_offsets[size_t(pinch)]; i < adj_.star_offsets[size_t(pinch) + 1];
           ++i)
        shortest =
            std::min(shortest, std::sqrt(2 * triangle_area(m, size_t(adj_.star[size_t(i)]))));
      const double back = 0.5 * o_.snap_fraction * shortest;
      for (int k = 0; k < 3; ++k) m.points[3 * size_t(pinch) + size_t(k)] -= back * n[size_t(k)];
    }
  }

  // The two sides: grow the removed side from the loop without crossing it.
  const size_t nt = m.num_triangles();
  std::vector<uint8_t> side(nt, 0);  // 1 crossed by the loop, 2 removed
  for (int32_t t : loop.triangles) side[size_t(t)] = 1;
  std::vector<int32_t> removed;
  std::vector<int32_t> kept_seeds;
  for (int32_t t : loop.triangles)
    for (int k = 0; k < 3; ++k) {
      const int32_t h = 3 * t + k;
      const int32_t a = half_edge_from(m, h), b = half_edge_to(m, h);
      if (above(a) != above(b)) continue;
      const int32_t o = adj_.opposite[size_t(h)];
      if (o < 0 || side[size_t(o / 3)] == 1) continue;
      if (above(a)) {
        if (side[size_t(o / 3)] == 0) side[size_t(o / 3)] = 2, removed.push_back(o / 3);
      } else {
        kept_seeds.push_back(o / 3);
      }
    }
  for (size_t i = 0; i < removed.size(); ++i)
    for (int k = 0; k < 3; ++k) {
      const int32_t o = adj_.opposite[3 * size_t(removed[i]) + size_t(k)];
      if (o >= 0 && side[size_t(o / 3)] == 0) side[size_t(o / 3)] = 2, removed.push_back(o / 3);
    }
  const CurveShape shape = curve_shape(loop.points);
  for (int32_t t : kept_seeds)
    if (side[size_t(t)] == 2)
      return Status::Error("the cut of the plane at " + point_text(plane_.point) + " (around " +
                           point_text(shape.centroid) + ", radius " + number_text(shape.radius) +
                           ") does not divide the surface in two: the vessels beyond it join "
                           "the rest again; cut a vessel end instead ({clip_plane})");

  // Area removed: whole triangles and the far parts of the crossed ones.
  double total_area = 0, removed_area = 0;
  for (size_t t = 0; t < nt; ++t) {
    const double a = triangle_area(m, t);
    total_area += a;
    if (side[t] == 2) removed_area += a;
  }
  double crossed_area = 0;
  for (int32_t t : loop.triangles) crossed_area += triangle_area(m, size_t(t));
  // The crossed triangles' far parts: at most their area; count half of it.
  removed_area += 0.5 * crossed_area;
  if (removed_area > o_.max_removed_fraction * total_area) {
    char pct[16];
    std::snprintf(pct, sizeof(pct), "%.0f%%", 100 * removed_area / total_area);
    return Status::Error("the plane at " + point_text(plane_.point) + " would remove " + pct +
                         " of the surface (the side its normal " + point_text(n) +
                         " points to): turn the normal around to keep that side, or move the "
                         "plane ({clip_plane})");
  }

  // Move the loop's vertices at the plane onto it, add the new vertices.
  const size_t nv = m.num_vertices();
  for (size_t i = 0; i < loop.size(); ++i) {
    const int32_t v = ids[i];
    if (size_t(v) < nv) {
      if (s_.cut_of_vertex[size_t(v)] == index_) continue;  // met again in a row
      for (int k = 0; k < 3; ++k)
        m.points[3 * size_t(v) + size_t(k)] -= d_[size_t(v)] * n[size_t(k)];
      s_.cut_of_vertex[size_t(v)] = index_;
    } else if (size_t(v) == m.num_vertices()) {
      m.points.insert(m.points.end(), &loop.points[3 * i], &loop.points[3 * i + 3]);
      s_.cut_of_vertex.push_back(index_);
      s_.input_vertex.push_back(-1);
    }
  }

  // Split the crossed triangles: keep the part below the plane.
  const size_t n_loop = loop.size();
  std::vector<int32_t> new_triangles;
  std::vector<int32_t> new_labels;
  for (size_t i = 0; i < loop.triangles.size(); ++i) {
    const int32_t t = loop.triangles[i];
    const int32_t* c = &m.triangles[3 * size_t(t)];
    std::array<int32_t, 5> poly{};
    size_t np = 0;
    auto emit = [&](int32_t v) {
      if (np == 0 || poly[np - 1] != v) poly[np++] = v;
    };
    for (int k = 0; k < 3; ++k) {
      const int32_t a = c[k], b = c[(k + 1) % 3];
      if (!above(a)) emit(a);
      if (above(a) != above(b)) {
        const std::array<int32_t, 2> e = above(a) ? std::array{b, a} : std::array{a, b};
        emit(loop.edges[i] == e ? ids[i] : ids[(i + 1) % n_loop]);
      }
    }
    if (np > 1 && poly[np - 1] == poly[0]) --np;
    const int32_t label = s_.labels.empty() ? 0 : s_.labels[size_t(t)];
    auto add = [&](int32_t a, int32_t b, int32_t d) {
      new_triangles.insert(new_triangles.end(), {a, b, d});
      new_labels.push_back(label);
    };
    auto p = [&](int32_t v) { return &m.points[3 * size_t(v)]; };
    if (np == 3) {
      add(poly[0], poly[1], poly[2]);
    } else if (np == 4) {
      const double q02 = std::min(triangle_shape(p(poly[0]), p(poly[1]), p(poly[2])),
                                  triangle_shape(p(poly[0]), p(poly[2]), p(poly[3])));
      const double q13 = std::min(triangle_shape(p(poly[1]), p(poly[2]), p(poly[3])),
                                  triangle_shape(p(poly[1]), p(poly[3]), p(poly[0])));
      if (q02 >= q13) {
        add(poly[0], poly[1], poly[2]);
        add(poly[0], poly[2], poly[3]);
      } else {
        add(poly[1], poly[2], poly[3]);
        add(poly[1], poly[3], poly[0]);
      }
    }
  }
  // No piece may have lost its area (vertices moved onto the plane); the
  // crossed triangles lose what the pieces do not keep.
  double kept_area = 0;
  for (size_t i = 0; i < new_triangles.size(); i += 3) {
    const Vec3 a = triangle_cross(&m.points[3 * size_t(new_triangles[i])],
                                  &m.points[3 * size_t(new_triangles[i + 1])],
                                  &m.points[3 * size_t(new_triangles[i + 2])]);
    if (!(v3::norm(a.data()) > 0))
      return Status::Internal("a zero-area triangle in the cut at " + point_text(plane_.point));
    kept_area += 0.5 * v3::norm(a.data());
  }
  for (size_t i = 0; i < loop.size(); ++i) {
    const int32_t v = ids[i];
    if (size_t(v) >= nv) continue;
    for (int32_t j = adj_.star_offsets[size_t(v)]; j < adj_.star_offsets[size_t(v) + 1]; ++j) {
      const int32_t t = adj_.star[size_t(j)];
      if (side[size_t(t)] == 0 && !(triangle_area(m, size_t(t)) > 0))
        return Status::Internal("a triangle at " + point_text(plane_.point) +
                                " lost its area when its vertex was moved onto the plane");
    }
  }

  std::vector<uint8_t> keep(nt, 1);
  size_t whole = 0;
  for (size_t t = 0; t < nt; ++t)
    if (side[t] != 0) keep[t] = 0, whole += side[t] == 2;
  m.triangles.insert(m.triangles.end(), new_triangles.begin(), new_triangles.end());
  if (!s_.labels.empty()) s_.labels.insert(s_.labels.end(), new_labels.begin(), new_labels.end());
  keep.resize(m.num_triangles(), 1);
  compact(s_, keep);

  // The new loop as it ended up.
  size_t loop_vertices = 0;
  for (size_t v = 0; v < s_.mesh.num_vertices(); ++v)
    loop_vertices += s_.cut_of_vertex[v] == index_;
  report.centroid = shape.centroid;
  report.radius = shape.radius;
  report.perimeter = shape.perimeter;
  report.loop_vertices = loop_vertices;
  report.area_removed = removed_area - 0.5 * crossed_area + (crossed_area - kept_area);
  report.triangles_removed = whole;
  return Status::Ok();
}

}  // namespace

Result<ClipResult> clip_surface(const SurfaceMesh& mesh, std::span<const int32_t> labels,
                                std::span<const ClipPlane> planes, const ClipOptions& options) {
  State s;
  s.mesh = mesh;
  if (labels.size() == mesh.num_triangles()) s.labels.assign(labels.begin(), labels.end());
  s.cut_of_vertex.assign(mesh.num_vertices(), -1);
  s.input_vertex.resize(mesh.num_vertices());
  for (size_t v = 0; v < mesh.num_vertices(); ++v) s.input_vertex[v] = int32_t(v);
  ClipResult result;
  for (size_t i = 0; i < planes.size(); ++i) {
    ClipCut cut;
    PlaneCut one(s, planes[i], int(i), options);
    if (Status st = one.run(cut); !st.ok()) return st;
    result.cuts.push_back(cut);
  }
  // The largest component by area.
  if (!planes.empty() && s.mesh.num_triangles() > 0) {
    const TopologyReport topo = analyze_topology(s.mesh);
    if (topo.components > 1) {
      std::vector<double> area(size_t(topo.components), 0);
      for (size_t t = 0; t < s.mesh.num_triangles(); ++t)
        area[size_t(topo.triangle_component[t])] += triangle_area(s.mesh, t);
      const int32_t largest = int32_t(std::max_element(area.begin(), area.end()) - area.begin());
      std::vector<uint8_t> keep(s.mesh.num_triangles(), 1);
      for (size_t t = 0; t < keep.size(); ++t)
        if (topo.triangle_component[t] != largest) {
          keep[t] = 0;
          ++result.triangles_dropped;
          result.area_dropped += triangle_area(s.mesh, t);
        }
      result.components_dropped = topo.components - 1;
      compact(s, keep);
    }
  }
  result.mesh = std::move(s.mesh);
  result.labels = std::move(s.labels);
  result.cut_of_vertex = std::move(s.cut_of_vertex);
  result.input_vertex = std::move(s.input_vertex);
  return result;
}

}  // namespace vm
