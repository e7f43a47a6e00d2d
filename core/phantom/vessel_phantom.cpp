// Synthetic segmentation-like vessels: an implicit model (sphere sweeps along
// smooth centerlines, branches joined by a smooth minimum, an optional bulb)
// sampled on a voxel grid with optional value noise, optionally thresholded
// to a binary mask (the raw staircase of an unsmoothed segmentation),
// extracted by marching cubes (marching_cubes.h) and cut open by planes
// across the vessel ends, so the result has the staircase, oversampling and
// slivers of real segmentation output.
#include "core/phantom/vessel_phantom.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/geom/vec3.h"
#include "core/mesh/adjacency.h"
#include "core/mesh/boundary_loops.h"
#include "core/mesh/marching_cubes.h"
#include "core/mesh/topology.h"
#include "core/phantom/dirty_phantom.h"
#include "core/phantom/outlets_phantom.h"
#include "core/util/portable_math.h"

namespace vm {
namespace {

Vec3 lerp(const Vec3& a, const Vec3& b, double t) {
  return {a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), a[2] + t * (b[2] - a[2])};
}
Vec3 sub(const Vec3& a, const Vec3& b) { return a - b; }
Vec3 unit(const Vec3& a) {
  double n = std::sqrt(dot(a, a));
  return {a[0] / n, a[1] / n, a[2] / n};
}

/// A vessel branch: a polyline centerline with a radius per point.
struct Branch {
  std::vector<Vec3> points;
  std::vector<double> radii;
};

/// Catmull-Rom spline through `ctrl` sampled with `n` points per span, radius
/// from `radius(s)` with s in [0, 1] along the samples.
template <class RadiusFn>
Branch spline_branch(const std::vector<Vec3>& ctrl, int n, RadiusFn radius) {
  Branch b;
  const size_t spans = ctrl.size() - 1;
  for (size_t s = 0; s < spans; ++s) {
    const Vec3& p0 = ctrl[s == 0 ? 0 : s - 1];
    const Vec3& p1 = ctrl[s];
    const Vec3& p2 = ctrl[s + 1];
    const Vec3& p3 = ctrl[std::min(s + 2, spans)];
    for (int i = 0; i < n || (s + 1 == spans && i == n); ++i) {
      double t = double(i) / n, t2 = t * t, t3 = t2 * t;
      Vec3 p;
      for (int k = 0; k < 3; ++k)
        p[k] = 0.5 * (2 * p1[k] + (-p0[k] + p2[k]) * t +
                      (2 * p0[k] - 5 * p1[k] + 4 * p2[k] - p3[k]) * t2 +
                      (-p0[k] + 3 * p1[k] - 3 * p2[k] + p3[k]) * t3);
      b.points.push_back(p);
    }
  }
  for (size_t i = 0; i < b.points.size(); ++i)
    b.radii.push_back(radius(double(i) / double(b.points.size() - 1)));
  return b;
}

/// A plane cutting one vessel end; the part on the +normal side near `center`
/// is removed.
struct EndCut {
  Vec3 center, normal;
  double radius;
};

struct Model {
  std::vector<Branch> branches;
  bool has_bulb = false;
  Vec3 bulb_center{};
  double bulb_radius = 0;
  std::vector<EndCut> cuts;  ///< used when open_ends
  std::vector<EndCut> ends;  ///< the rounded free ends: tip, outward direction, radius
  /// Per branch: its last point is a junction (other branches start there),
  /// so that end is not free. Branch 0's start is always free.
  std::vector<bool> joined_end;
  int genus = 0;
  /// Each branch its own surface (not joined by the smooth minimum).
  bool separate_shells = false;
};

/// The cut across the end of `b` at sample `i`, facing away from sample j.
EndCut cut_at(const Branch& b, size_t i, size_t j) {
  return {b.points[i], unit(sub(b.points[i], b.points[j])), b.radii[i]};
}

/// Adds to `m` a branch from `start` along `dir` (unit) of length `len` and
/// radius `r` (tapering by 6%), gently bent toward `side`, and below it
/// `depth` levels of asymmetric splits: the two children leave at 32 and 42
/// degrees in the plane of `dir` and `side`, with radii by Murray's law (the
/// cubes of the children's radii sum to the parent's), 0.78 of its length,
/// and their own split planes turned a quarter turn about their axes.
void grow_tree(Model& m, const Vec3& start, const Vec3& dir, const Vec3& side, double r, double len,
               int depth) {
  auto at = [&](double t, double bend) {
    return Vec3{start[0] + t * len * dir[0] + bend * side[0],
                start[1] + t * len * dir[1] + bend * side[1],
                start[2] + t * len * dir[2] + bend * side[2]};
  };
  m.branches.push_back(spline_branch({at(0, 0), at(0.5, 0.08 * len), at(1, 0)}, 24,
                                     [r](double s) { return r * (1.0 - 0.06 * s); }));
  m.joined_end.push_back(depth > 0);
  if (depth == 0) return;
  const Vec3 end = at(1, 0);
  const double rr = 0.94 * r;
  // Murray's law with a 0.6:0.4 flow split: r_i = rr * share_i^(1/3).
  const double shares[2] = {0.6, 0.4};
  const double angles[2] = {32.0, -42.0};
  for (int c = 0; c < 2; ++c) {
    const double a = angles[c] * std::numbers::pi / 180;
    const Vec3 d = unit({pm::cos(a) * dir[0] + pm::sin(a) * side[0],
                         pm::cos(a) * dir[1] + pm::sin(a) * side[1],
                         pm::cos(a) * dir[2] + pm::sin(a) * side[2]});
    const Vec3 turned = unit(cross(d, side));
    grow_tree(m, end, d, turned, rr * pm::cbrt(shares[c]), 0.78 * len, depth - 1);
  }
}

Model build_model(PhantomKind kind) {
  Model m;
  const int n = 24;
  switch (kind) {
    case PhantomKind::kTube: {
      m.branches.push_back(spline_branch(
          {{0, 0, -5}, {0.8, 0.3, -2}, {-0.4, 0.2, 1}, {0.5, -0.5, 4}, {0.2, 0, 6.5}}, n,
          [](double s) { return 1.0 + 0.18 * pm::sin(2 * std::numbers::pi * s); }));
      break;
    }
    case PhantomKind::kBifurcation:
    case PhantomKind::kAneurysm: {
      m.branches.push_back(spline_branch({{0, 0, -6}, {0.2, 0.1, -3}, {0, 0, 0}}, n,
                                         [](double s) { return 1.0 - 0.05 * s; }));
      m.branches.push_back(
          spline_branch({{0, 0, 0}, {0.9, 0.1, 1.6}, {2.3, 0.3, 3.6}, {3.2, 0.2, 6}}, n,
                        [](double s) { return 0.78 - 0.08 * s; }));
      m.branches.push_back(
          spline_branch({{0, 0, 0}, {-0.8, -0.1, 1.7}, {-1.8, -0.4, 3.8}, {-2.2, -0.3, 6.2}}, n,
                        [](double s) { return 0.66 - 0.06 * s; }));
      if (kind == PhantomKind::kAneurysm) {
        m.has_bulb = true;
        m.bulb_center = {0.15, 1.05, 1.6};
        m.bulb_radius = 0.95;
      }
      break;
    }
    case PhantomKind::kTree: {
      // A trunk splitting three times (8 leaves) with two side branches off
      // the trunk: 17 branches, 11 free ends.
      grow_tree(m, {0, 0, -6}, {0, 0, 1}, {1, 0, 0}, 1.0, 6.0, 3);
      const Branch trunk = m.branches[0];
      const double side_at[2] = {0.35, 0.65};
      const Vec3 side_dir[2] = {unit({-0.2, 0.85, 0.5}), unit({-0.3, -0.8, 0.5})};
      for (int k = 0; k < 2; ++k) {
        const Vec3& p = trunk.points[size_t(side_at[k] * double(trunk.points.size() - 1))];
        const Vec3 q = {p[0] + 3.2 * side_dir[k][0], p[1] + 3.2 * side_dir[k][1],
                        p[2] + 3.2 * side_dir[k][2]};
        m.branches.push_back(
            spline_branch({p, lerp(p, q, 0.5), q}, n, [](double s) { return 0.5 - 0.04 * s; }));
        m.joined_end.push_back(false);
      }
      break;
    }
    case PhantomKind::kCrossing: {
      // A vessel along z and one crossing it at 50 degrees, their axes 1.3
      // apart: with radii 1 and 0.8 they overlap by half a radius.
      m.branches.push_back(
          spline_branch({{0, 0, -5}, {0.1, 0, 0}, {0, 0, 5}}, n, [](double) { return 1.0; }));
      m.branches.push_back(spline_branch({{-4.2, 1.3, -3.5}, {0, 1.3, 0}, {4.2, 1.3, 3.5}}, n,
                                         [](double) { return 0.8; }));
      m.separate_shells = true;
      for (const Branch& b : m.branches) {
        const size_t last = b.points.size() - 1, in = std::max<size_t>(1, b.points.size() / 12);
        m.cuts.push_back(cut_at(b, in, in + 1));
        m.cuts.push_back(cut_at(b, last - in, last - in - 1));
        m.ends.push_back(cut_at(b, 0, 1));
        m.ends.push_back(cut_at(b, last, last - 1));
      }
      return m;
    }
    case PhantomKind::kRoot: {
      // A short, wide root (1.5 of its radii long to the branching) and two
      // branches leaving it at 40 degrees, each splitting once more.
      m.branches.push_back(spline_branch({{0, 0, -1.4}, {0.05, 0, -0.7}, {0, 0, 0}}, n,
                                         [](double s) { return 1.7 - 0.05 * s; }));
      m.joined_end.push_back(true);
      const double a = 70 * std::numbers::pi / 180;
      grow_tree(m, {0, 0, 0}, {pm::sin(a), 0, pm::cos(a)}, {0, 1, 0}, 1.1, 6.0, 1);
      grow_tree(m, {0, 0, 0}, {-pm::sin(a), 0, pm::cos(a)}, {0, 1, 0}, 1.0, 6.0, 1);
      break;
    }
    case PhantomKind::kTorus: {
      std::vector<Vec3> ring;
      for (int i = 0; i <= 8; ++i) {
        double a = 2 * std::numbers::pi * i / 8;
        ring.push_back({3.2 * pm::cos(a), 2.6 * pm::sin(a), 0.4 * pm::sin(2 * a)});
      }
      // Close the loop: repeat the first span's neighbors for the spline.
      ring.push_back(ring[1]);
      Branch b = spline_branch(
          ring, n, [](double s) { return 0.8 + 0.12 * pm::cos(2 * std::numbers::pi * s * 9 / 8); });
      // Keep one full turn (8 spans).
      size_t keep = size_t(8 * n + 1);
      b.points.resize(keep);
      b.radii.resize(keep);
      m.branches.push_back(b);
      m.genus = 1;
      return m;
    }
    case PhantomKind::kOutlets:  // analytic (make_outlets_phantom)
      break;
  }
  // Free ends: cut a twelfth of the way in. A single tube has two; in a
  // bifurcation or a tree the parents end and the children start at the
  // junctions.
  if (kind == PhantomKind::kBifurcation || kind == PhantomKind::kAneurysm)
    m.joined_end = {true, false, false};
  m.joined_end.resize(m.branches.size(), false);
  for (size_t bi = 0; bi < m.branches.size(); ++bi) {
    const Branch& b = m.branches[bi];
    size_t last = b.points.size() - 1, in = std::max<size_t>(1, b.points.size() / 12);
    bool free_start = bi == 0;
    bool free_end = !m.joined_end[bi];
    if (free_start) m.cuts.push_back(cut_at(b, in, in + 1));
    if (free_end) m.cuts.push_back(cut_at(b, last - in, last - in - 1));
    if (free_start) m.ends.push_back(cut_at(b, 0, 1));
    if (free_end) m.ends.push_back(cut_at(b, last, last - 1));
  }
  return m;
}

double smooth_min(double a, double b, double k) {
  double h = std::max(k - std::fabs(a - b), 0.0) / k;
  return std::min(a, b) - h * h * k * 0.25;
}

uint64_t splitmix64(uint64_t x) {
  x += 0x9E3779B97F4A7C15ULL;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ULL;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBULL;
  return x ^ (x >> 31);
}

/// Field of one branch over plane z = zk: distance to the polyline minus the
/// interpolated radius, computed only in the xy boxes of the segments that
/// reach the plane (elsewhere `far`).
void branch_plane(const Branch& b, const GridSpec& g, double zk, float far, float* out) {
  std::fill(out, out + size_t(g.nx) * size_t(g.ny), far);
  const double band = far;
  for (size_t s = 0; s + 1 < b.points.size(); ++s) {
    const Vec3 &p = b.points[s], &q = b.points[s + 1];
    double rmax = std::max(b.radii[s], b.radii[s + 1]) + band;
    if (zk < std::min(p[2], q[2]) - rmax || zk > std::max(p[2], q[2]) + rmax) continue;
    int i0 = std::max(0, int(std::floor((std::min(p[0], q[0]) - rmax - g.origin[0]) / g.spacing)));
    int i1 =
        std::min(g.nx - 1, int(std::ceil((std::max(p[0], q[0]) + rmax - g.origin[0]) / g.spacing)));
    int j0 = std::max(0, int(std::floor((std::min(p[1], q[1]) - rmax - g.origin[1]) / g.spacing)));
    int j1 =
        std::min(g.ny - 1, int(std::ceil((std::max(p[1], q[1]) + rmax - g.origin[1]) / g.spacing)));
    Vec3 d = sub(q, p);
    double len2 = dot(d, d);
    for (int j = j0; j <= j1; ++j) {
      for (int i = i0; i <= i1; ++i) {
        Vec3 x = {g.origin[0] + g.spacing * i, g.origin[1] + g.spacing * j, zk};
        Vec3 w = sub(x, p);
        double t = len2 > 0 ? std::clamp(dot(w, d) / len2, 0.0, 1.0) : 0.0;
        Vec3 c = lerp(p, q, t);
        Vec3 e = sub(x, c);
        double v = std::sqrt(dot(e, e)) - (b.radii[s] + t * (b.radii[s + 1] - b.radii[s]));
        float& o = out[size_t(i) + size_t(g.nx) * size_t(j)];
        o = std::min(o, float(v));
      }
    }
  }
}

/// Removes the part of `mesh` beyond the plane of `cut`, within 3 radii of
/// its center, splitting the crossing triangles (new vertices exactly on the
/// plane, shared between neighbors).
void clip(SurfaceMesh& mesh, const EndCut& cut) {
  const size_t nv = mesh.num_vertices();
  std::vector<double> dist(nv);
  const double reach2 = 9 * cut.radius * cut.radius;
  for (size_t v = 0; v < nv; ++v) {
    Vec3 p = {mesh.points[3 * v], mesh.points[3 * v + 1], mesh.points[3 * v + 2]};
    Vec3 r = sub(p, cut.center);
    double d = dot(r, cut.normal);
    double lateral2 = dot(r, r) - d * d;
    // Outside the reach of this cut everything is kept.
    dist[v] = lateral2 > reach2 || std::fabs(d) > 3 * cut.radius ? -1.0 : d;
  }
  std::vector<std::pair<uint64_t, int32_t>> cache;  // edge -> vertex on plane
  auto on_plane = [&](int32_t a, int32_t b) -> int32_t {
    uint64_t key = uint64_t(std::min(a, b)) << 32 | uint64_t(std::max(a, b));
    for (auto& [k, v] : cache)
      if (k == key) return v;
    double t = dist[a] / (dist[a] - dist[b]);
    for (int k = 0; k < 3; ++k)
      mesh.points.push_back(mesh.points[3 * a + k] +
                            t * (mesh.points[3 * b + k] - mesh.points[3 * a + k]));
    int32_t id = int32_t(mesh.num_vertices() - 1);
    cache.push_back({key, id});
    return id;
  };
  std::vector<int32_t> out;
  out.reserve(mesh.triangles.size());
  for (size_t t = 0; t < mesh.num_triangles(); ++t) {
    const int32_t* v = &mesh.triangles[3 * t];
    bool beyond[3];
    int n_beyond = 0;
    for (int k = 0; k < 3; ++k) n_beyond += beyond[k] = dist[v[k]] > 0;
    if (n_beyond == 0) {
      out.insert(out.end(), v, v + 3);
      continue;
    }
    if (n_beyond == 3) continue;
    std::vector<int32_t> poly;
    for (int k = 0; k < 3; ++k) {
      int32_t a = v[k], b = v[(k + 1) % 3];
      if (!beyond[k]) poly.push_back(a);
      if (beyond[k] != beyond[(k + 1) % 3]) {
        // The kept end may lie on the plane itself: reuse it.
        int32_t kept = beyond[k] ? b : a, gone = beyond[k] ? a : b;
        int32_t p = dist[kept] == 0 ? kept : on_plane(kept, gone);
        if (poly.empty() || poly.back() != p) poly.push_back(p);
      }
    }
    if (poly.size() > 1 && poly.front() == poly.back()) poly.pop_back();
    for (size_t i = 1; i + 1 < poly.size(); ++i)
      out.insert(out.end(), {poly[0], poly[i], poly[i + 1]});
  }
  mesh.triangles.swap(out);
}

/// Keeps the largest connected component (clipping may leave noise specks).
void keep_largest_component(SurfaceMesh& mesh) {
  TopologyReport r = analyze_topology(mesh);
  if (r.components > 0) mesh = extract_component(mesh, r, 0);
}

/// Closes every boundary loop by a cap of `shape`, outward oriented (each
/// triangle next to the rim runs against the loop's boundary half-edge): a
/// fan from the loop's centroid (flat), from an apex lifted 0.1 radius off
/// it (fan), or rings of a paraboloid rising 0.3, 0.6 or 1 radius (dome, in
/// turn from loop to loop) up to its apex, each ring taking every m-th rim
/// vertex's direction (m about the rim's radius over the ring's), so that
/// its triangles keep the rim's size.
/// Returns a face label per triangle: 1 the wall, 2, 3, ... each cap.
std::vector<int32_t> close_ends(SurfaceMesh& mesh, PhantomCapShape shape) {
  const TriangleAdjacency adj = build_adjacency(mesh);
  const std::vector<std::vector<int32_t>> loops = boundary_loops(mesh, adj);
  std::vector<int32_t> labels(mesh.num_triangles(), 1);
  for (size_t l = 0; l < loops.size(); ++l) {
    const std::vector<int32_t>& loop = loops[l];
    const size_t n = loop.size();
    auto p = [&](size_t i) { return at(mesh.points, loop[i % n]); };
    Vec3 c = {0, 0, 0};
    for (size_t i = 0; i < n; ++i) c = c + (1.0 / double(n)) * p(i);
    // The fan's outward normal (twice its vector area), the loop's
    // equivalent radius and mean edge.
    Vec3 area2 = {0, 0, 0};
    double edge = 0;
    for (size_t i = 0; i < n; ++i) {
      area2 = area2 + cross(p(i) - p(i + 1), c - p(i + 1));
      edge += norm(p(i + 1) - p(i)) / double(n);
    }
    const double radius = std::sqrt(0.5 * norm(area2) / std::numbers::pi);
    const Vec3 normal = normalized(area2);
    constexpr double kDomeHeights[3] = {0.3, 0.6, 1.0};
    const double height = shape == PhantomCapShape::kFan    ? 0.1
                          : shape == PhantomCapShape::kDome ? kDomeHeights[l % 3]
                                                            : 0.0;
    const int rings = shape == PhantomCapShape::kDome
                          ? std::max(3, int(std::lround(radius / std::max(edge, 1e-12))))
                          : 1;
    // A ring: its vertices and the rim index each one's direction comes from.
    std::vector<int32_t> outer = loop;
    std::vector<size_t> outer_at(n);
    for (size_t i = 0; i < n; ++i) outer_at[i] = i;
    for (int k = 1; k < rings; ++k) {
      const double r = 1 - double(k) / rings;
      const size_t step = std::clamp<size_t>(size_t(std::lround(1 / r)), 1, n / 3);
      std::vector<int32_t> inner;
      std::vector<size_t> inner_at;
      for (size_t i = 0; i < n; i += step) {
        const Vec3 q = c + r * (p(i) - c) + (height * radius * (1 - r * r)) * normal;
        inner.push_back(int32_t(mesh.num_vertices()));
        inner_at.push_back(i);
        mesh.points.insert(mesh.points.end(), q.begin(), q.end());
      }
      // Stitch the two rings in the order of their rim indices.
      const size_t na = outer.size(), nb = inner.size();
      auto param = [&](const std::vector<size_t>& ring_at, size_t j) {
        return j >= ring_at.size() ? double(n) : double(ring_at[j]);
      };
      for (size_t a = 0, b = 0; a < na || b < nb;) {
        if (b == nb || (a < na && param(outer_at, a + 1) <= param(inner_at, b + 1))) {
          mesh.triangles.insert(mesh.triangles.end(),
                                {outer[(a + 1) % na], outer[a % na], inner[b % nb]});
          ++a;
        } else {
          mesh.triangles.insert(mesh.triangles.end(),
                                {outer[a % na], inner[b % nb], inner[(b + 1) % nb]});
          ++b;
        }
      }
      outer = std::move(inner);
      outer_at = std::move(inner_at);
    }
    const Vec3 apex = c + (height * radius) * normal;
    const int32_t centre = int32_t(mesh.num_vertices());
    mesh.points.insert(mesh.points.end(), apex.begin(), apex.end());
    for (size_t i = 0; i < outer.size(); ++i)
      mesh.triangles.insert(mesh.triangles.end(),
                            {outer[(i + 1) % outer.size()], outer[i], centre});
    labels.resize(mesh.num_triangles(), int32_t(l + 2));
  }
  return labels;
}

}  // namespace

Result<SurfaceMesh> make_vessel_phantom(const PhantomOptions& o, PhantomTruth* truth) {
  if (!(o.voxel > 0) || !std::isfinite(o.voxel))
    return Result<SurfaceMesh>::Error("phantom voxel size must be a positive number");
  if (!(o.scale > 0) || !std::isfinite(o.scale))
    return Result<SurfaceMesh>::Error("phantom scale must be a positive number");
  if (!(o.noise >= 0) || o.noise > 2)
    return Result<SurfaceMesh>::Error("phantom noise must be between 0 and 2 voxels");
  if (o.kind == PhantomKind::kOutlets) {
    OutletsPhantom p = make_outlets_phantom(o.scale);
    if (truth) {
      *truth = PhantomTruth{};
      truth->opening_radii = p.cap_radii;
      truth->opening_centers = p.cap_centers;
      truth->face_labels = std::move(p.labels);
    }
    return std::move(p.mesh);
  }
  Model m = build_model(o.kind);
  // Grid around the model, with 3 voxels of margin.
  Vec3 lo = {1e30, 1e30, 1e30}, hi = {-1e30, -1e30, -1e30};
  for (const Branch& b : m.branches)
    for (size_t i = 0; i < b.points.size(); ++i)
      for (int k = 0; k < 3; ++k) {
        lo[k] = std::min(lo[k], b.points[i][k] - b.radii[i]);
        hi[k] = std::max(hi[k], b.points[i][k] + b.radii[i]);
      }
  if (m.has_bulb)
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], m.bulb_center[k] - m.bulb_radius);
      hi[k] = std::max(hi[k], m.bulb_center[k] + m.bulb_radius);
    }
  GridSpec g;
  g.spacing = o.voxel;
  double n[3];
  for (int k = 0; k < 3; ++k) {
    g.origin[k] = lo[k] - 3 * o.voxel;
    n[k] = std::ceil((hi[k] - lo[k]) / o.voxel) + 7;
  }
  if (n[0] * n[1] * n[2] > 2e8)
    return Result<SurfaceMesh>::Error("phantom grid too large (" +
                                      std::to_string(size_t(n[0] * n[1] * n[2])) +
                                      " voxels, limit 200M): use a larger voxel size");
  g.nx = int(n[0]), g.ny = int(n[1]), g.nz = int(n[2]);

  const float far = float(4 * o.voxel + 0.5);
  const double k_blend = 0.35;
  std::vector<std::vector<float>> branch(m.branches.size(),
                                         std::vector<float>(size_t(g.nx) * size_t(g.ny)));
  auto plane_fn = [&](int k, float* out) {
    double z = g.origin[2] + g.spacing * k;
    for (size_t b = 0; b < m.branches.size(); ++b)
      branch_plane(m.branches[b], g, z, far, branch[b].data());
    const size_t np = size_t(g.nx) * size_t(g.ny);
    for (size_t i = 0; i < np; ++i) {
      double v = branch[0][i];
      for (size_t b = 1; b < m.branches.size(); ++b) v = smooth_min(v, branch[b][i], k_blend);
      out[i] = float(v);
    }
    if (m.has_bulb) {
      for (int j = 0; j < g.ny; ++j)
        for (int i = 0; i < g.nx; ++i) {
          Vec3 x = {g.origin[0] + g.spacing * i, g.origin[1] + g.spacing * j, z};
          Vec3 d = sub(x, m.bulb_center);
          double s = std::sqrt(dot(d, d)) - m.bulb_radius;
          float& v = out[size_t(i) + size_t(g.nx) * size_t(j)];
          v = float(smooth_min(v, s, 0.3));
        }
    }
    if (o.noise > 0) {
      for (size_t i = 0; i < np; ++i) {
        uint64_t h = splitmix64((uint64_t(o.seed) << 40) ^ (uint64_t(k) * np + i));
        double u = double(h >> 11) * (1.0 / 9007199254740992.0);  // [0, 1)
        out[i] += float(o.noise * o.voxel * (2 * u - 1));
      }
    }
    // A binary mask: inside -1, outside +1 (each crossing at its edge's middle).
    if (o.binary)
      for (size_t i = 0; i < np; ++i) out[i] = out[i] < 0 ? -1.0f : 1.0f;
  };
  const bool open = o.open_ends && !m.cuts.empty();
  SurfaceMesh mesh;
  if (m.separate_shells) {
    // Each branch alone, cut at its own ends, then all put together.
    Model all = std::move(m);
    for (size_t b = 0; b < all.branches.size(); ++b) {
      m.branches = {all.branches[b]};
      SurfaceMesh shell = marching_cubes(g, plane_fn);
      if (open)
        for (size_t c = 2 * b; c < 2 * b + 2; ++c) clip(shell, all.cuts[c]);
      keep_largest_component(shell);
      const int32_t base = int32_t(mesh.num_vertices());
      mesh.points.insert(mesh.points.end(), shell.points.begin(), shell.points.end());
      for (int32_t v : shell.triangles) mesh.triangles.push_back(base + v);
    }
    m = std::move(all);
  } else {
    mesh = marching_cubes(g, plane_fn);
    if (open)
      for (const EndCut& c : m.cuts) clip(mesh, c);
    keep_largest_component(mesh);
  }
  // Flat caps are labelled as SimVascular labels its faces; fans and domes,
  // as capping tools leave them, are not.
  std::vector<int32_t> labels;
  if (open && o.flat_caps) labels = close_ends(mesh, o.cap_shape);
  if (o.cap_shape != PhantomCapShape::kFlat) labels.clear();
  const DirtTruth dirt = o.dirty ? add_segmentation_defects(mesh, o.seed) : DirtTruth{};
  if (o.dirty) labels.clear();
  if (open && !o.flat_caps && o.damaged_ends) add_damaged_ends(mesh, o.seed);
  for (double& x : mesh.points) x *= o.scale;
  if (truth) {
    truth->genus = m.genus;
    truth->holes = dirt.holes;
    truth->openings = open && !o.flat_caps ? int(m.cuts.size()) : 0;
    truth->face_labels = std::move(labels);
    truth->opening_radii.clear();
    truth->opening_centers.clear();
    truth->end_tips.clear();
    truth->end_directions.clear();
    truth->end_radii.clear();
    for (const EndCut& e : m.ends) {
      const Vec3 tip = {e.center[0] + e.radius * e.normal[0], e.center[1] + e.radius * e.normal[1],
                        e.center[2] + e.radius * e.normal[2]};
      truth->end_tips.push_back({tip[0] * o.scale, tip[1] * o.scale, tip[2] * o.scale});
      truth->end_directions.push_back(e.normal);
      truth->end_radii.push_back(e.radius * o.scale);
    }
    if (open)
      for (const EndCut& c : m.cuts) {
        truth->opening_radii.push_back(c.radius * o.scale);
        truth->opening_centers.push_back(
            {c.center[0] * o.scale, c.center[1] * o.scale, c.center[2] * o.scale});
      }
  }
  if (mesh.num_triangles() == 0)
    return Result<SurfaceMesh>::Error("phantom is empty: voxel size too large for the model");
  return mesh;
}

}  // namespace vm
