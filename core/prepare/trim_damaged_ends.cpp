// Trimming damaged vessel ends back to a clean cross-section
// (trim_damaged_ends.h).
#include "core/prepare/trim_damaged_ends.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <deque>

#include "core/mesh/adjacency.h"
#include "core/mesh/boundary_loops.h"
#include "core/mesh/repair.h"
#include "core/mesh/topology.h"

namespace vm {
namespace {

Vec3 centroid(const SurfaceMesh& m, size_t t) {
  const int32_t* c = &m.triangles[3 * t];
  return (1.0 / 3) * (at(m.points, c[0]) + at(m.points, c[1]) + at(m.points, c[2]));
}

// ---- Phase 1: triangles whose orientation contradicts their neighbours'.

/// Propagates an orientation across the edges of exactly two triangles,
/// from the triangle farthest (in steps) from any free or non-manifold edge
/// of each component; marks both triangles of an edge where the
/// propagation contradicts itself.
std::vector<uint8_t> misoriented_triangles(const SurfaceMesh& mesh, const TriangleAdjacency& adj) {
  const size_t nt = mesh.num_triangles();
  // Steps from the border (free or non-manifold edges).
  std::vector<int32_t> depth(nt, -1);
  std::deque<int32_t> queue;
  for (size_t t = 0; t < nt; ++t)
    for (int k = 0; k < 3; ++k)
      if (adj.opposite[3 * t + size_t(k)] < 0 && depth[t] < 0)
        depth[t] = 0, queue.push_back(int32_t(t));
  while (!queue.empty()) {
    const int32_t t = queue.front();
    queue.pop_front();
    for (int k = 0; k < 3; ++k) {
      const int32_t o = adj.opposite[3 * size_t(t) + size_t(k)];
      if (o >= 0 && depth[size_t(o / 3)] < 0) {
        depth[size_t(o / 3)] = depth[size_t(t)] + 1;
        queue.push_back(o / 3);
      }
    }
  }
  std::vector<int32_t> by_depth(nt);
  for (size_t t = 0; t < nt; ++t) by_depth[t] = int32_t(t);
  std::stable_sort(by_depth.begin(), by_depth.end(),
                   [&](int32_t a, int32_t b) { return depth[size_t(a)] > depth[size_t(b)]; });
  std::vector<int8_t> flip(nt, -1);  // -1: not reached
  std::vector<uint8_t> bad(nt, 0);
  for (int32_t seed : by_depth) {
    if (flip[size_t(seed)] >= 0) continue;
    flip[size_t(seed)] = 0;
    queue.push_back(seed);
    while (!queue.empty()) {
      const int32_t t = queue.front();
      queue.pop_front();
      for (int k = 0; k < 3; ++k) {
        const int32_t h = 3 * t + k, o = adj.opposite[size_t(h)];
        if (o < 0) continue;
        // Consistent when the two triangles run along the edge both ways.
        const bool opposite_ways = half_edge_from(mesh, h) == half_edge_to(mesh, o);
        const int8_t want = int8_t(flip[size_t(t)] ^ (opposite_ways ? 0 : 1));
        const size_t u = size_t(o / 3);
        if (flip[u] < 0) {
          flip[u] = want;
          queue.push_back(int32_t(u));
        } else if (flip[u] != want) {
          bad[size_t(t)] = bad[u] = 1;
        }
      }
    }
  }
  return bad;
}

/// The unit direction least represented among the normals of `triangles`
/// (area-weighted): a tube's axis. Zero when there are none.
Vec3 axis_of_normals(const SurfaceMesh& mesh, const std::vector<int32_t>& triangles) {
  Eigen::Matrix3d m = Eigen::Matrix3d::Zero();
  for (int32_t t : triangles) {
    const int32_t* c = &mesh.triangles[3 * size_t(t)];
    const Vec3 n = triangle_cross(&mesh.points[3 * size_t(c[0])], &mesh.points[3 * size_t(c[1])],
                                  &mesh.points[3 * size_t(c[2])]);
    const double a = norm(n);
    if (!(a > 0)) continue;
    const Eigen::Vector3d u(n[0] / a, n[1] / a, n[2] / a);
    m += 0.5 * a * u * u.transpose();
  }
  if (m.trace() == 0) return {0, 0, 0};
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(m);
  const Eigen::Vector3d v = eig.eigenvectors().col(0);
  return {v[0], v[1], v[2]};
}

struct EndState {
  Opening loop;
  std::vector<int32_t> near;  ///< triangles within reach of the loop's centroid
};

}  // namespace

std::vector<TrimmedEnd> trim_damaged_ends(SurfaceMesh& mesh, std::vector<int32_t>* labels,
                                          const std::vector<std::array<int32_t, 2>>& crossing_pairs,
                                          const TrimOptions& options) {
  std::vector<TrimmedEnd> out;
  const size_t nt = mesh.num_triangles();
  if (labels && labels->size() != nt) labels = nullptr;
  const TriangleAdjacency adj = build_adjacency(mesh);
  // Phase 1: the damage.
  std::vector<uint8_t> crossing(nt, 0), nonmanifold(nt, 0), tiny(nt, 0);
  for (const auto& p : crossing_pairs) crossing[size_t(p[0])] = crossing[size_t(p[1])] = 1;
  for (size_t h = 0; h < adj.opposite.size(); ++h)
    if (adj.opposite[h] == TriangleAdjacency::kNonManifold) nonmanifold[h / 3] = 1;
  const std::vector<uint8_t> misoriented = misoriented_triangles(mesh, adj);
  std::vector<Opening> loops;
  for (std::vector<int32_t>& loop : boundary_loops(mesh, adj))
    if (loop.size() >= 3) loops.push_back(describe_loop(mesh, std::move(loop)));
  std::sort(loops.begin(), loops.end(),
            [](const Opening& a, const Opening& b) { return a.radius > b.radius; });
  // A loop far smaller than an opening it lies beside is part of that end's
  // damage; the others are openings (a small hole elsewhere is the hole
  // filling's).
  std::vector<Opening> openings;
  std::vector<uint8_t> on_tiny_loop(mesh.num_vertices(), 0);
  for (const Opening& l : loops) {
    const bool beside = std::any_of(openings.begin(), openings.end(), [&](const Opening& o) {
      return l.radius < options.tiny_fraction * o.radius &&
             norm(Vec3(l.centroid) - Vec3(o.centroid)) < 2.5 * o.radius;
    });
    if (!beside) {
      openings.push_back(l);
      continue;
    }
    for (int32_t v : l.loop) on_tiny_loop[size_t(v)] = 1;
  }
  for (size_t t = 0; t < nt; ++t)
    for (int k = 0; k < 3; ++k) tiny[t] |= on_tiny_loop[size_t(mesh.triangles[3 * t + size_t(k)])];

  std::vector<uint8_t> remove(nt, 0);
  for (const Opening& o : openings) {
    const Vec3 c = o.centroid;
    const double R = o.radius;
    if (!(R > 0)) continue;
    // Phase 2: the damage at this end, its triangles within 2 radii.
    std::vector<int32_t> near, damaged;
    for (size_t t = 0; t < nt; ++t) {
      bool close = false;
      for (int k = 0; k < 3 && !close; ++k)
        close = norm(at(mesh.points, mesh.triangles[3 * t + size_t(k)]) - c) < 2 * R;
      if (!close) continue;
      near.push_back(int32_t(t));
      if (crossing[t] || misoriented[t] || nonmanifold[t] || tiny[t]) damaged.push_back(int32_t(t));
    }
    const bool serious = std::any_of(damaged.begin(), damaged.end(), [&](int32_t t) {
      return crossing[size_t(t)] || misoriented[size_t(t)];
    });
    if (!serious) continue;
    TrimmedEnd end;
    end.where = c;
    end.radius = R;
    for (int32_t t : damaged) {
      end.crossing += crossing[size_t(t)];
      end.nonmanifold += nonmanifold[size_t(t)];
      end.misoriented += misoriented[size_t(t)];
      end.tiny_loops += tiny[size_t(t)];
    }
    // The axis: the loop's normal, out of the vessel (away from the wall
    // near it), then from the clean wall's normals behind the damage.
    Vec3 axis = normalized(Vec3(o.normal));
    Vec3 mean{0, 0, 0};
    for (int32_t t : near) mean = mean + (1.0 / double(near.size())) * centroid(mesh, size_t(t));
    if (dot(mean - c, axis) > 0) axis = -1.0 * axis;
    std::vector<double> edges;
    for (int32_t t : near)
      for (int k = 0; k < 3; ++k)
        edges.push_back(norm(at(mesh.points, mesh.triangles[3 * size_t(t) + size_t(k)]) -
                             at(mesh.points, mesh.triangles[3 * size_t(t) + size_t((k + 1) % 3)])));
    std::nth_element(edges.begin(), edges.begin() + long(edges.size() / 2), edges.end());
    const double h = edges[edges.size() / 2];
    auto depth_of = [&](const Vec3& p) { return dot(c - p, axis); };
    auto damage_depth = [&] {
      double d = 0;
      for (int32_t t : damaged)
        for (int k = 0; k < 3; ++k)
          d = std::max(d, depth_of(at(mesh.points, mesh.triangles[3 * size_t(t) + size_t(k)])));
      return d;
    };
    for (int round = 0; round < 2; ++round) {
      const double d0 = damage_depth();
      std::vector<int32_t> wall;
      for (size_t t = 0; t < nt; ++t) {
        if (crossing[t] || misoriented[t] || nonmanifold[t] || tiny[t]) continue;
        const Vec3 q = centroid(mesh, t);
        const double d = depth_of(q);
        const Vec3 off = (c - q) - d * axis;
        if (d >= d0 && d <= d0 + 1.5 * R && norm(off) < 1.5 * R) wall.push_back(int32_t(t));
      }
      Vec3 fitted = axis_of_normals(mesh, wall);
      if (dot(fitted, axis) < 0) fitted = -1.0 * fitted;
      if (dot(fitted, axis) > std::cos(45 * 3.141592653589793 / 180)) axis = normalized(fitted);
    }
    const double margin = std::max(options.margin_radii * R, options.margin_edges * h);
    end.depth = damage_depth() + margin;
    end.plane.point = c - end.depth * axis;
    end.plane.normal = axis;
    if (end.depth > options.max_depth * R) {
      out.push_back(end);
      continue;
    }
    // Phase 4: what lies wholly beyond half the margin short of the cut,
    // connected to the end through such triangles, goes.
    const double beyond = end.depth - 0.5 * margin;
    auto wholly_beyond = [&](size_t t) {
      for (int k = 0; k < 3; ++k) {
        const Vec3 p = at(mesh.points, mesh.triangles[3 * t + size_t(k)]);
        const double d = depth_of(p);
        if (!(d < beyond) || norm((c - p) - d * axis) > 3 * R) return false;
      }
      return true;
    };
    std::vector<uint8_t> at_vertex(mesh.num_vertices(), 0);  // reached vertices
    for (int32_t v : o.loop) at_vertex[size_t(v)] = 1;
    for (int32_t t : damaged)
      if (wholly_beyond(size_t(t)))
        for (int k = 0; k < 3; ++k)
          at_vertex[size_t(mesh.triangles[3 * size_t(t) + size_t(k)])] = 1;
    std::vector<int32_t> candidates;
    for (size_t t = 0; t < nt; ++t)
      if (!remove[t] && wholly_beyond(t)) candidates.push_back(int32_t(t));
    std::vector<int32_t> taken;
    std::vector<uint8_t> in(nt, 0);
    for (bool grew = true; grew;) {
      grew = false;
      for (int32_t t : candidates) {
        if (in[size_t(t)]) continue;
        const int32_t* v = &mesh.triangles[3 * size_t(t)];
        if (!(at_vertex[size_t(v[0])] || at_vertex[size_t(v[1])] || at_vertex[size_t(v[2])]))
          continue;
        in[size_t(t)] = 1;
        taken.push_back(t);
        for (int k = 0; k < 3; ++k) at_vertex[size_t(v[k])] = 1;
        grew = true;
      }
    }
    if (double(taken.size()) > options.max_removed_fraction * double(nt)) {
      out.push_back(end);
      continue;
    }
    for (int32_t t : taken) remove[size_t(t)] = 1;
    end.triangles_removed = taken.size();
    end.trimmed = true;
    out.push_back(end);
  }
  if (std::any_of(remove.begin(), remove.end(), [](uint8_t r) { return r != 0; }))
    remove_triangles(mesh, remove, labels);
  return out;
}

}  // namespace vm
