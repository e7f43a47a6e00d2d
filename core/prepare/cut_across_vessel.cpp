// A cut across a vessel at a place the user points to (method: header).
#include "core/prepare/cut_across_vessel.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "core/geom/vec3.h"
#include "core/mesh/level_loops.h"
#include "core/prepare/recognize_caps.h"
#include "core/prepare/vessel_ends.h"
#include "core/util/portable_math.h"

namespace vm {
namespace {

/// A tube's normals have no component along its axis: the smallest
/// eigenvalue of sum(n n^T) is near 0 against the middle one (about 0.1 on
/// noisy or tapering vessels, about 1 on a sphere).
constexpr double kMaxBulge = 0.3;

/// Area-weighted vertex normals (3 doubles per vertex, not normalized: the
/// weight is the sum of the incident triangles' areas).
std::vector<Vec3> vertex_normals(const SurfaceMesh& m) {
  std::vector<Vec3> n(m.num_vertices(), Vec3{0, 0, 0});
  for (size_t t = 0; t < m.num_triangles(); ++t) {
    const int32_t* c = &m.triangles[3 * t];
    const Vec3 a = at(m.points, c[0]), b = at(m.points, c[1]), d = at(m.points, c[2]);
    const Vec3 area2 = cross(b - a, d - a);  // twice the vector area
    for (int k = 0; k < 3; ++k) n[size_t(c[k])] = n[size_t(c[k])] + 0.5 * area2;
  }
  return n;
}

/// Phase 2: the connected surface within `radius` of `centre`, grown over
/// the triangles from those of vertex `seed`, as the axis of the normals
/// there: the unit direction least represented among them (smallest
/// eigenvalue of sum(n n^T)), with the ratio of the middle eigenvalue to the
/// largest (near 0: the normals do not spread round a vessel yet).
struct AxisFit {
  Vec3 axis{};
  double spread = 0;
  /// Smallest over middle eigenvalue: near 0 on a tube (no normal along
  /// its axis), near 1 on a bulge.
  double bulge = 1;
};
AxisFit fit_axis(const SurfaceMesh& m, const TriangleAdjacency& adj,
                 const std::vector<Vec3>& normals, int32_t seed, const Vec3& centre, double radius,
                 std::vector<uint8_t>& seen) {
  std::vector<int32_t> queue, visited;
  const double r2 = radius * radius;
  auto inside = [&](int32_t v) {
    const Vec3 d = at(m.points, v) - centre;
    return dot(d, d) <= r2;
  };
  queue.push_back(seed);
  seen[size_t(seed)] = 1;
  Eigen::Matrix3d M = Eigen::Matrix3d::Zero();
  for (size_t i = 0; i < queue.size(); ++i) {
    const int32_t v = queue[i];
    const Vec3& n = normals[size_t(v)];
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c)
        M(r, c) += n[size_t(r)] * n[size_t(c)] / std::max(norm(n), 1e-300);
    for (int32_t s = adj.star_offsets[size_t(v)]; s < adj.star_offsets[size_t(v) + 1]; ++s) {
      const int32_t t = adj.star[size_t(s)];
      for (int k = 0; k < 3; ++k) {
        const int32_t w = m.triangles[3 * size_t(t) + size_t(k)];
        if (!seen[size_t(w)] && inside(w)) {
          seen[size_t(w)] = 1;
          queue.push_back(w);
        }
      }
    }
  }
  for (int32_t v : queue) seen[size_t(v)] = 0;
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(M);
  const Eigen::Vector3d e = eig.eigenvalues();  // increasing
  const Eigen::Vector3d a = eig.eigenvectors().col(0);
  return {{a(0), a(1), a(2)}, e(2) > 0 ? e(1) / e(2) : 0, e(1) > 0 ? e(0) / e(1) : 1};
}

/// Phase 3: the closed loop of the section through p normal to a that
/// passes nearest p, with its shape; false when there is none.
bool section_through(const SurfaceMesh& m, const TriangleAdjacency& adj, const Vec3& p,
                     const Vec3& a, std::vector<double>& field, CurveShape& shape) {
  for (size_t v = 0; v < m.num_vertices(); ++v) field[v] = dot(at(m.points, int32_t(v)) - p, a);
  const std::vector<LevelLoop> loops = level_loops(m, adj, field, 0.0);
  double best = 1e300;
  for (const LevelLoop& loop : loops) {
    if (!loop.closed || loop.size() < 3) continue;
    const double d = distance_to_polygon(loop.points, p);
    if (d < best) {
      best = d;
      shape = curve_shape(loop.points);
    }
  }
  return best < 1e300;
}

/// The closed loop of the section through q normal to a that winds around
/// q, the smallest if several; false when there is none.
bool section_around(const SurfaceMesh& m, const TriangleAdjacency& adj, const Vec3& q,
                    const Vec3& a, std::vector<double>& field, CurveShape& shape) {
  for (size_t v = 0; v < m.num_vertices(); ++v) field[v] = dot(at(m.points, int32_t(v)) - q, a);
  double best = 1e300;
  for (const LevelLoop& loop : level_loops(m, adj, field, 0.0)) {
    if (!loop.closed || loop.size() < 3 || winding_number(loop.points, q, a) == 0) continue;
    const CurveShape s = curve_shape(loop.points);
    if (s.radius < best) best = s.radius, shape = s;
  }
  return best < 1e300;
}

double roundness_of(const CurveShape& s) {
  return s.max_distance > 0 ? s.min_distance / s.max_distance : 0;
}

/// Phase 1: the vertex nearest `near`.
int32_t nearest_vertex(const SurfaceMesh& mesh, const Vec3& near) {
  int32_t v0 = 0;
  double best = 1e300;
  for (size_t v = 0; v < mesh.num_vertices(); ++v) {
    const Vec3 d = at(mesh.points, int32_t(v)) - near;
    if (dot(d, d) < best) best = dot(d, d), v0 = int32_t(v);
  }
  return v0;
}

/// Step 5: the cut through `centre` perpendicular to `axis` (the section
/// `shape`), removing the side with less surface.
Result<VesselCut> smaller_side(const SurfaceMesh& mesh, const Vec3& centre, const Vec3& axis,
                               const CurveShape& shape) {
  ClipOptions options;
  options.max_removed_fraction = 1;
  VesselCut cut;
  cut.radius = shape.radius;
  cut.roundness = roundness_of(shape);
  cut.area_removed = 1e300;
  std::string last_error;
  for (double sign : {1.0, -1.0}) {
    const ClipPlane plane{centre, sign * axis};
    Result<ClipResult> r = clip_surface(mesh, {}, std::span(&plane, 1), options);
    if (!r.ok()) {
      last_error = r.status().message();
      continue;
    }
    const double removed = r.value().cuts[0].area_removed;
    if (removed < cut.area_removed) {
      cut.area_removed = removed;
      cut.plane = plane;
    }
  }
  if (cut.area_removed == 1e300) return Status::Error(last_error);
  return cut;
}

/// Whether `p` lies on the end cut off by `plane` (normal toward the end):
/// beyond `behind` radii behind it, within 1.5 radii of its axis.
bool on_end(const Vec3& p, const ClipPlane& plane, double radius, double behind) {
  const Vec3 d = p - plane.point;
  const double along = dot(d, plane.normal);
  return along >= -behind * radius && norm(d - along * plane.normal) <= 1.5 * radius;
}

/// Step 6: the cut of the vessel end that the surface point `p` lies on
/// (a fan's or a dome's: at its rim, recognize_caps.h; else {clip} auto's),
/// or an error when it lies on none.
Result<VesselCut> end_cut(const SurfaceMesh& mesh, const TriangleAdjacency& adj, const Vec3& p) {
  std::optional<ClipPlane> plane;
  for (const RecognizedCap& cap : recognize_caps(mesh, adj, {}, {}).caps)
    if (cap.cut_at_rim && on_end(p, {cap.centroid, cap.normal}, cap.radius, 0.5))
      plane = ClipPlane{cap.centroid, cap.normal};
  if (!plane) {
    double best = 1e300;
    for (const VesselEnd& e : find_vessel_ends(mesh).ends)
      if (on_end(p, e.plane, e.radius, 1) && norm(p - e.tip) < best)
        best = norm(p - e.tip), plane = e.plane;
  }
  if (!plane) return Status::Error("on no vessel end");
  std::vector<double> field(mesh.num_vertices());
  CurveShape shape;
  if (!section_around(mesh, adj, plane->point, plane->normal, field, shape))
    return Status::Error("the end's section is not a closed loop");
  ClipOptions options;
  options.max_removed_fraction = 1;
  Result<ClipResult> r = clip_surface(mesh, {}, std::span(&*plane, 1), options);
  if (!r.ok()) return r.status();
  VesselCut cut;
  cut.plane = *plane;
  cut.radius = shape.radius;
  cut.roundness = roundness_of(shape);
  cut.area_removed = r.value().cuts[0].area_removed;
  return cut;
}

/// Steps 1 to 5.
Result<VesselCut> tube_cut(const SurfaceMesh& mesh, const TriangleAdjacency& adj,
                           const std::array<double, 3>& near) {
  // Phase 1: the nearest vertex.
  const int32_t v0 = nearest_vertex(mesh, near);
  const Vec3 p = at(mesh.points, v0);
  const std::vector<Vec3> normals = vertex_normals(mesh);
  std::vector<uint8_t> seen(mesh.num_vertices(), 0);
  std::vector<double> field(mesh.num_vertices());
  auto refuse = [&](const std::string& why) {
    return Status::Error("cannot cut across the vessel at " + point_text(p) + ": " + why +
                         "; point to a vessel away from branchings and aneurysms, or give the "
                         "plane itself ({clip_plane})");
  };

  // Phase 2, first round: grow the ball from a few local edges until the
  // normals spread round the vessel.
  double edge = 0;
  int edges = 0;
  for (int32_t s = adj.star_offsets[size_t(v0)]; s < adj.star_offsets[size_t(v0) + 1]; ++s)
    for (int k = 0; k < 3; ++k) {
      edge +=
          norm(at(mesh.points, mesh.triangles[3 * size_t(adj.star[size_t(s)]) + size_t(k)]) - p);
      ++edges;
    }
  const Vec3 lo = at(mesh.points, 0);
  double extent = 0;
  for (size_t v = 0; v < mesh.num_vertices(); ++v)
    extent = std::max(extent, norm(at(mesh.points, int32_t(v)) - lo));
  double radius = std::max(4 * edge / std::max(edges, 1), 1e-12 * extent);
  AxisFit fit = fit_axis(mesh, adj, normals, v0, p, radius, seen);
  while (fit.spread < 0.2 && radius < 2 * extent) {
    radius *= 1.5;
    fit = fit_axis(mesh, adj, normals, v0, p, radius, seen);
  }
  if (fit.spread < 0.2) return refuse("the surface there is flat, not a vessel");

  // Phases 3-4: section, then the axis again from a ball about the centre.
  CurveShape shape;
  Vec3 axis = fit.axis;
  for (int round = 0; round < 6; ++round) {
    if (!section_through(mesh, adj, p, axis, field, shape))
      return refuse("the section there is not a closed loop (it reaches an opening)");
    const Vec3 centre = shape.centroid;
    const AxisFit next = fit_axis(mesh, adj, normals, v0, centre, 1.5 * shape.radius, seen);
    fit = next;
    const Vec3 a = dot(next.axis, axis) < 0 ? -1.0 * next.axis : next.axis;
    const bool settled = dot(a, axis) > pm::cos(0.5 * std::numbers::pi / 180);
    axis = a;
    if (settled) break;
  }
  if (!section_through(mesh, adj, p, axis, field, shape))
    return refuse("the section there is not a closed loop (it reaches an opening)");
  if (fit.bulge > kMaxBulge)
    return refuse(
        "the surface there is not a tube (its normals point along the vessel too: a "
        "bulge, an aneurysm or a branching)");
  if (roundness_of(shape) < 0.25)
    return refuse("the section there is not round (from its centre, its nearest point is " +
                  number_text(shape.min_distance) + " and its farthest " +
                  number_text(shape.max_distance) + " away)");

  // Phase 4b: a tube on both sides. The sections half a radius away wind
  // around the axis with about the same radius (not a vessel's rounded end,
  // not across a branching); their centroids lie on the vessel's axis, so
  // the line through them corrects an axis tilted by the normals of a
  // nearby end or bend (a tilted plane cuts a tube in parallel ellipses
  // whose centres still follow the tube).
  for (int round = 0;; ++round) {
    Vec3 centres[2];
    for (int k = 0; k < 2; ++k) {
      const Vec3 q = shape.centroid + ((k ? 0.5 : -0.5) * shape.radius) * axis;
      CurveShape near_shape;
      const bool found = section_around(mesh, adj, q, axis, field, near_shape);
      if (!found || std::abs(near_shape.radius / shape.radius - 1) > 0.35 ||
          norm(near_shape.centroid - q) > 0.5 * shape.radius)
        return refuse("the vessel is no tube there (half a radius along it, at " + point_text(q) +
                      ", its section is " +
                      (found ? "of radius " + number_text(near_shape.radius) + " against " +
                                   number_text(shape.radius) + ", or off the axis"
                             : std::string("missing: the vessel ends")) +
                      ")");
      centres[k] = near_shape.centroid;
    }
    Vec3 along = normalized(centres[1] - centres[0]);
    if (dot(along, axis) < 0) along = -1.0 * along;
    const double cos_tilt = dot(along, axis);
    if (cos_tilt > pm::cos(3 * std::numbers::pi / 180)) break;
    if (round == 3 && cos_tilt > pm::cos(10 * std::numbers::pi / 180)) break;
    if (round == 3)
      return refuse(
          "the vessel's axis there is not found (the sections half a radius away "
          "lean " +
          std::to_string(
              int(std::lround(pm::acos(std::min(1.0, cos_tilt)) * 180 / std::numbers::pi))) +
          " degrees from the cut: a bend, or a vessel's end)");
    axis = along;
    if (!section_through(mesh, adj, p, axis, field, shape))
      return refuse("the section there is not a closed loop (it reaches an opening)");
  }

  // Phase 5: remove the side with less surface.
  Result<VesselCut> cut = smaller_side(mesh, shape.centroid, axis, shape);
  if (!cut.ok()) return refuse(cut.message());
  return cut;
}

}  // namespace

Result<VesselCut> cut_across_vessel(const SurfaceMesh& mesh, const TriangleAdjacency& adj,
                                    const std::array<double, 3>& near) {
  if (mesh.num_triangles() == 0) return Status::Error("cannot cut: the surface is empty");
  Result<VesselCut> cut = tube_cut(mesh, adj, near);
  if (cut.ok()) return cut;
  // Step 6: on a vessel's end, that end's cut.
  Result<VesselCut> end = end_cut(mesh, adj, at(mesh.points, nearest_vertex(mesh, near)));
  return end.ok() ? end : cut;
}

}  // namespace vm
