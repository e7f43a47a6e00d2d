// Planar caps of a capped vessel model (recognize_caps.h).
#include "core/prepare/recognize_caps.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <queue>
#include <tuple>

#include "core/geom/vec3.h"
#include "core/mesh/chord_radius.h"
#include "core/mesh/edge_geodesics.h"
#include "core/util/portable_math.h"

namespace vm {
namespace {

const double* point(const SurfaceMesh& m, int32_t v) { return &m.points[3 * size_t(v)]; }

double angle_cos(double degrees) { return pm::cos(degrees * std::numbers::pi / 180); }

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::nth_element(v.begin(), v.begin() + long(v.size() / 2), v.end());
  return v[v.size() / 2];
}

/// Phase 2's view of one candidate region.
struct Region {
  std::vector<int32_t> triangles;
  std::vector<int32_t> rim_half_edges;  ///< half-edges of region triangles across the rim
  Vec3 normal{}, centroid{};
  double area = 0;
};

/// Shared data of the tests.
struct Context {
  const SurfaceMesh& mesh;
  const TriangleAdjacency& adj;
  const std::vector<Vec3>& normals;
  const std::vector<double>& areas;
  const CapRecognitionOptions& options;
  double total_area = 0;
  /// Per vertex, -1 outside a geodesic search (looks_like_a_vessel_end's
  /// buffer, allocated once).
  std::vector<double>& distance;
};

/// Fills rim, area and mean normal; false when the region touches an
/// opening or a non-manifold edge. The centroid is left to planar().
bool describe(const Context& ctx, const std::vector<uint8_t>& in_region, Region& r) {
  r.rim_half_edges.clear();
  Vec3 weighted{};
  r.area = 0;
  r.centroid = {};
  for (int32_t t : r.triangles) {
    const double a = ctx.areas[size_t(t)];
    r.area += a;
    for (int k = 0; k < 3; ++k) {
      weighted[size_t(k)] += a * ctx.normals[size_t(t)][size_t(k)];
      const int32_t h = 3 * t + k;
      const int32_t o = ctx.adj.opposite[size_t(h)];
      if (o < 0) return false;  // an opening or a non-manifold edge
      if (!in_region[size_t(o / 3)]) r.rim_half_edges.push_back(h);
    }
  }
  if (r.area <= 0) return false;
  const double len = v3::norm(weighted.data());
  if (len <= 0) return false;
  for (int k = 0; k < 3; ++k) r.normal[size_t(k)] = weighted[size_t(k)] / len;
  return true;
}

/// The region's vertices, rim vertices and Euler characteristic.
struct RegionTopology {
  std::vector<int32_t> vertices, rim_vertices;
  long euler = 0;
  int rim_loops = 0;
};

RegionTopology region_topology(const Context& ctx, const Region& r) {
  const SurfaceMesh& m = ctx.mesh;
  RegionTopology topo;
  for (int32_t t : r.triangles)
    for (int c = 0; c < 3; ++c) topo.vertices.push_back(m.triangles[3 * size_t(t) + c]);
  std::sort(topo.vertices.begin(), topo.vertices.end());
  topo.vertices.erase(std::unique(topo.vertices.begin(), topo.vertices.end()), topo.vertices.end());
  // Edges: interior ones are counted twice among the half-edges.
  const size_t half_edges = 3 * r.triangles.size();
  const size_t edges = (half_edges + r.rim_half_edges.size()) / 2;
  topo.euler = long(topo.vertices.size()) - long(edges) + long(r.triangles.size());
  // Rim loops: follow rim half-edges from vertex to vertex.
  std::vector<std::pair<int32_t, int32_t>> next;  // from -> to
  for (int32_t h : r.rim_half_edges) next.emplace_back(half_edge_from(m, h), half_edge_to(m, h));
  std::sort(next.begin(), next.end());
  for (auto& e : next) topo.rim_vertices.push_back(e.first);
  // A vertex with two outgoing rim edges: the rim touches itself.
  for (size_t i = 1; i < next.size(); ++i)
    if (next[i].first == next[i - 1].first) {
      topo.rim_loops = -1;
      return topo;
    }
  std::vector<uint8_t> seen(next.size(), 0);
  for (size_t i = 0; i < next.size(); ++i) {
    if (seen[i]) continue;
    ++topo.rim_loops;
    size_t j = i;
    while (!seen[j]) {
      seen[j] = 1;
      auto it = std::lower_bound(next.begin(), next.end(), std::pair{next[j].second, INT32_MIN});
      if (it == next.end() || it->first != next[j].second) {
        topo.rim_loops = -1;
        return topo;
      }
      j = size_t(it - next.begin());
    }
  }
  return topo;
}

/// Whether every triangle of the region faces within the planar angle of
/// its mean normal and every corner lies within the planar distance of its
/// plane (tested before the region's topology, which most candidates of a
/// curved wall never need). Fills the centroid (area-weighted) once the
/// normals pass.
bool planar(const Context& ctx, Region& r) {
  const CapRecognitionOptions& o = ctx.options;
  const double cos_limit = angle_cos(o.planar_angle_degrees);
  for (int32_t t : r.triangles)
    if (ctx.areas[size_t(t)] > 0 &&
        v3::dot(ctx.normals[size_t(t)].data(), r.normal.data()) < cos_limit)
      return false;
  for (int32_t t : r.triangles) {
    const double a = ctx.areas[size_t(t)];
    for (int k = 0; k < 3; ++k)
      for (int c = 0; c < 3; ++c)
        r.centroid[size_t(k)] += a / 3 * point(ctx.mesh, ctx.mesh.triangles[3 * size_t(t) + c])[k];
  }
  for (double& x : r.centroid) x /= r.area;
  const double limit = o.planar_distance * std::sqrt(r.area / std::numbers::pi);
  for (int32_t t : r.triangles)
    for (int k = 0; k < 3; ++k) {
      double d[3];
      v3::sub(point(ctx.mesh, ctx.mesh.triangles[3 * size_t(t) + size_t(k)]), r.centroid.data(), d);
      if (std::abs(v3::dot(d, r.normal.data())) > limit) return false;
    }
  return true;
}

/// Why a planar region is not a cap-sized disk, or "" when it is one.
std::string disk_problem(const Context& ctx, const Region& r, const RegionTopology& topo) {
  const CapRecognitionOptions& o = ctx.options;
  if (r.area > o.max_area_fraction * ctx.total_area) return "too large a share of the surface";
  if (topo.rim_loops != 1 || topo.euler != 1) return "not a disk";
  if (int(topo.rim_vertices.size()) < o.min_rim_vertices) return "too small";
  return "";
}

/// Whether every rim edge of the region turns the normal by more than the
/// rim angle.
bool sharp_rim(const Context& ctx, const Region& r) {
  const double sharp = angle_cos(ctx.options.rim_angle_degrees);
  for (int32_t h : r.rim_half_edges) {
    const size_t other = size_t(ctx.adj.opposite[size_t(h)] / 3);
    if (v3::dot(ctx.normals[size_t(h / 3)].data(), ctx.normals[other].data()) > sharp) return false;
  }
  return true;
}

/// Whether the wall meets the region's plane (r.normal) at a mean angle of
/// at least the wall angle and, within one rim radius of the rim, goes
/// straight back from it like a vessel of the rim's radius about its axis
/// (the line through r.centroid along r.normal).
bool wall_goes_back_like_a_vessel(const Context& ctx, const std::vector<uint8_t>& in_region,
                                  const Region& r, const RegionTopology& topo) {
  const SurfaceMesh& m = ctx.mesh;
  const CapRecognitionOptions& o = ctx.options;
  // The mean angle of the wall to the cap plane.
  double sin_sum = 0;
  for (int32_t h : r.rim_half_edges) {
    const size_t other = size_t(ctx.adj.opposite[size_t(h)] / 3);
    const double c = v3::dot(ctx.normals[other].data(), r.normal.data());
    sin_sum += std::sqrt(std::max(0.0, 1 - c * c));
  }
  const double mean_angle =
      pm::asin(std::min(1.0, sin_sum / double(r.rim_half_edges.size()))) * 180 / std::numbers::pi;
  if (mean_angle < o.wall_angle_degrees) return false;
  // The rim's mean radius about the centroid.
  double rim_radius = 0;
  for (int32_t v : topo.rim_vertices) {
    double d[3];
    v3::sub(point(m, v), r.centroid.data(), d);
    rim_radius += v3::norm(d);
  }
  rim_radius /= double(topo.rim_vertices.size());
  // Geodesic distances from the rim over the wall, up to one rim radius
  // (in the context's buffer, reset to -1 where it was written).
  std::vector<double>& dist = ctx.distance;
  std::vector<int32_t> reached;
  using Item = std::pair<double, int32_t>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
  for (int32_t v : topo.rim_vertices) dist[size_t(v)] = 0, queue.push({0, v}), reached.push_back(v);
  std::vector<double> rate, radius_ratio;
  while (!queue.empty()) {
    auto [d, v] = queue.top();
    queue.pop();
    if (d > dist[size_t(v)]) continue;
    if (d > 0.25 * rim_radius) {
      double p[3];
      v3::sub(point(m, v), r.centroid.data(), p);
      const double depth = -v3::dot(p, r.normal.data());
      for (int k = 0; k < 3; ++k) p[k] += depth * r.normal[size_t(k)];
      rate.push_back(depth / d);
      radius_ratio.push_back(v3::norm(p) / rim_radius);
    }
    for (int32_t i = ctx.adj.star_offsets[size_t(v)]; i < ctx.adj.star_offsets[size_t(v) + 1];
         ++i) {
      const int32_t t = ctx.adj.star[size_t(i)];
      if (in_region[size_t(t)]) continue;
      for (int c = 0; c < 3; ++c) {
        const int32_t w = m.triangles[3 * size_t(t) + size_t(c)];
        double e[3];
        v3::sub(point(m, w), point(m, v), e);
        const double dw = d + v3::norm(e);
        if (dw <= rim_radius && (dist[size_t(w)] < 0 || dw < dist[size_t(w)])) {
          if (dist[size_t(w)] < 0) reached.push_back(w);
          dist[size_t(w)] = dw;
          queue.push({dw, w});
        }
      }
    }
  }
  for (int32_t v : reached) dist[size_t(v)] = -1;
  if (rate.size() < 3) return false;
  const double ratio = median(radius_ratio);
  return median(rate) >= o.min_depth_rate && ratio >= o.min_radius_ratio &&
         ratio <= o.max_radius_ratio;
}

/// Shape tests of an unlabelled planar candidate: sharp rim, wall at a right
/// angle going straight back like a vessel of the cap's radius.
bool looks_like_a_vessel_end(const Context& ctx, const std::vector<uint8_t>& in_region,
                             const Region& r, const RegionTopology& topo) {
  return sharp_rim(ctx, r) && wall_goes_back_like_a_vessel(ctx, in_region, r, topo);
}

/// Adds to the region the parts of the surface it encloses: the connected
/// parts of the rest (across manifold edges) next to its rim that are
/// smaller than half its area. in_region is set for the triangles added.
/// False when none was added.
bool take_islands(const Context& ctx, std::vector<uint8_t>& in_region, Region& r) {
  std::vector<int32_t> part;
  std::vector<int32_t> seen;
  bool added = false;
  for (int32_t h : r.rim_half_edges) {
    const int32_t seed = ctx.adj.opposite[size_t(h)] / 3;
    if (in_region[size_t(seed)]) continue;  // taken, or seen in an earlier part
    part.assign(1, seed);
    in_region[size_t(seed)] = 2;
    double area = ctx.areas[size_t(seed)];
    bool small = true;
    for (size_t i = 0; i < part.size() && small; ++i)
      for (int k = 0; k < 3; ++k) {
        const int32_t o = ctx.adj.opposite[3 * size_t(part[i]) + size_t(k)];
        if (o < 0) {
          small = false;  // an opening: no island
          break;
        }
        if (in_region[size_t(o / 3)]) continue;
        in_region[size_t(o / 3)] = 2;
        part.push_back(o / 3);
        area += ctx.areas[size_t(o / 3)];
        if (area >= 0.5 * r.area) small = false;
      }
    seen.insert(seen.end(), part.begin(), part.end());
    if (!small) continue;
    for (int32_t t : part) in_region[size_t(t)] = 1, r.triangles.push_back(t);
    added = true;
  }
  for (int32_t t : seen)
    if (in_region[size_t(t)] == 2) in_region[size_t(t)] = 0;
  return added;
}

/// Triangle normals with the noise of a segmentation's wall smoothed and
/// creases kept: a pass of bilateral normal filtering (Zheng, Fu, Au and
/// Tai, "Bilateral normal filtering for mesh denoising", IEEE TVCG 2011)
/// over the triangles sharing a vertex, weighted by area and by
/// exp(-((1 - n.m) / (1 - cos 0.9 a))^2), a the crease angle: a neighbour
/// turned by the crease angle weighs e^-1.5, by half of it e^-0.09 (a
/// second pass lost more domes' rims than it found on the phantoms).
/// Needles keep their normal and give none.
std::vector<Vec3> bilateral_normals(const Context& ctx, const std::vector<uint8_t>& needle,
                                    double crease_degrees) {
  const SurfaceMesh& m = ctx.mesh;
  const std::vector<Vec3>& n = ctx.normals;
  const double scale = 1 - angle_cos(0.9 * crease_degrees);
  std::vector<Vec3> out = n;
  std::vector<int32_t> near;
  for (size_t t = 0; t < n.size(); ++t) {
    if (needle[t]) continue;
    near.clear();
    for (int k = 0; k < 3; ++k) {
      const int32_t v = m.triangles[3 * t + size_t(k)];
      for (int32_t i = ctx.adj.star_offsets[size_t(v)]; i < ctx.adj.star_offsets[size_t(v) + 1];
           ++i)
        near.push_back(ctx.adj.star[size_t(i)]);
    }
    std::sort(near.begin(), near.end());
    near.erase(std::unique(near.begin(), near.end()), near.end());
    Vec3 sum{};
    for (int32_t s : near) {
      if (needle[size_t(s)]) continue;
      const double x = (1 - dot(n[t], n[size_t(s)])) / scale;
      sum = sum + (ctx.areas[size_t(s)] * std::exp(-x * x)) * n[size_t(s)];
    }
    if (norm(sum) > 0) out[t] = normalized(sum);
  }
  return out;
}

/// Whether triangle t (of area `area`) is a needle: of height under 0.002%
/// of its longest edge (two nearly coincident corners), its normal the
/// direction of that tiny offset rather than the surface's.
bool needle(const SurfaceMesh& m, size_t t, double area) {
  double longest = 0;
  for (int k = 0; k < 3; ++k)
    longest = std::max(longest, norm(at(m.points, m.triangles[3 * t + size_t(k)]) -
                                     at(m.points, m.triangles[3 * t + (k + 1) % 3])));
  return area < 1e-5 * longest * longest;
}

/// Phase 2b's tests of a region bounded by creases (the file comment): a
/// round rim near its best-fit plane, the region beyond it and facing out
/// of it, the wall going back from it like a vessel. Sets r's plane to the
/// rim's and fills `cap` (all but its triangles and label) when it is one.
bool shaped_cap(const Context& ctx, const std::vector<uint8_t>& in_region, Region& r,
                const RegionTopology& topo, RecognizedCap& cap) {
  const CapRecognitionOptions& o = ctx.options;
  auto p = [&](int32_t v) { return at(ctx.mesh.points, v); };
  // The rim's plane: the mean of its vertices and the unit normal of its
  // vector area (its half-edges run along the region's outward orientation).
  Vec3 c{};
  for (int32_t v : topo.rim_vertices) c = c + (1.0 / double(topo.rim_vertices.size())) * p(v);
  Vec3 area2{};
  for (int32_t h : r.rim_half_edges)
    area2 = area2 + cross(p(half_edge_from(ctx.mesh, h)) - c, p(half_edge_to(ctx.mesh, h)) - c);
  const double len = norm(area2);
  if (!(len > 0)) return false;
  const Vec3 n = (1 / len) * area2;
  const double R = std::sqrt(0.5 * len / std::numbers::pi);
  const double tolerance = o.rim_planar_distance * R;
  // A round rim near its plane.
  double nearest = 1e300, farthest = 0;
  for (int32_t v : topo.rim_vertices) {
    const Vec3 d = p(v) - c;
    const double h = dot(d, n);
    if (std::abs(h) > tolerance) return false;
    const double lateral = norm(d - h * n);
    nearest = std::min(nearest, lateral);
    farthest = std::max(farthest, lateral);
  }
  if (nearest < 0.5 * farthest) return false;
  // The cap over the rim's disk, beyond its plane, facing out of it.
  double height = 0;
  for (int32_t v : topo.vertices) {
    const Vec3 d = p(v) - c;
    const double h = dot(d, n);
    if (h < -tolerance || h > o.max_height * R || norm(d - h * n) > farthest + tolerance)
      return false;
    height = std::max(height, h);
  }
  double facing_away = 0;
  for (int32_t t : r.triangles)
    if (dot(ctx.normals[size_t(t)], n) < o.min_facing) facing_away += ctx.areas[size_t(t)];
  if (facing_away > 0.05 * r.area) return false;
  // The wall, as for a planar cap, about the rim's plane.
  r.normal = n;
  r.centroid = c;
  if (!wall_goes_back_like_a_vessel(ctx, in_region, r, topo)) return false;
  cap.area = r.area;
  cap.radius = R;
  cap.centroid = c;
  cap.normal = n;
  cap.height = height;
  cap.cut_at_rim = true;
  // One vertex inside the rim (or none): a fan; more: a dome, or planar
  // when it bulges by less than the planar distance (a flat cap whose
  // normals or rim failed phase 2's tests; 5% of its radius at least).
  cap.shape = topo.vertices.size() <= topo.rim_vertices.size() + 1 ? CapShape::kFan
              : height <= std::max(0.05, o.planar_distance) * R    ? CapShape::kPlanar
                                                                   : CapShape::kDome;
  return true;
}

/// Connected parts of the triangles with in_set != 0, joined across manifold
/// edges (half-edge h of t, opposite triangle s) that pass
/// `joins(seed, t, s, h)`; those of at least
/// `min_size` triangles (grown in one reused buffer: most parts of a curved
/// wall are single triangles).
template <class Joins>
std::vector<std::vector<int32_t>> grow_regions(const Context& ctx,
                                               const std::vector<uint8_t>& in_set, size_t min_size,
                                               Joins joins) {
  std::vector<std::vector<int32_t>> regions;
  std::vector<uint8_t> done(in_set.size(), 0);
  std::vector<int32_t> region;
  for (size_t seed = 0; seed < in_set.size(); ++seed) {
    if (!in_set[seed] || done[seed]) continue;
    region.assign(1, int32_t(seed));
    done[seed] = 1;
    for (size_t i = 0; i < region.size(); ++i) {
      const int32_t t = region[i];
      for (int k = 0; k < 3; ++k) {
        const int32_t o = ctx.adj.opposite[size_t(3 * t + k)];
        if (o < 0) continue;
        const int32_t s = o / 3;
        if (!in_set[size_t(s)] || done[size_t(s)] || !joins(int32_t(seed), t, s, 3 * t + k))
          continue;
        done[size_t(s)] = 1;
        region.push_back(s);
      }
    }
    if (region.size() >= min_size) regions.push_back(region);
  }
  return regions;
}

std::string label_text(int32_t label, std::span<const std::pair<int32_t, std::string>> names) {
  for (const auto& [l, n] : names)
    if (l == label && !n.empty()) return "face " + std::to_string(label) + " (" + n + ")";
  return "face " + std::to_string(label);
}

}  // namespace

const char* cap_shape_name(CapShape shape) {
  switch (shape) {
    case CapShape::kLabelled:
      return "labelled";
    case CapShape::kFan:
      return "fan";
    case CapShape::kDome:
      return "dome";
    case CapShape::kPlanar:
      break;
  }
  return "planar";
}

CapRecognition recognize_caps(const SurfaceMesh& mesh, const TriangleAdjacency& adj,
                              std::span<const int32_t> labels,
                              std::span<const std::pair<int32_t, std::string>> label_names,
                              const CapRecognitionOptions& options, const TriangleNormals* known) {
  CapRecognition out;
  const size_t nt = mesh.num_triangles();
  TriangleNormals own;
  const TriangleNormals& tn = known ? *known : (own = triangle_normals(mesh));
  const std::vector<Vec3>& normals = tn.normal;
  std::vector<double> distance(mesh.num_vertices(), -1);
  Context ctx{mesh, adj, normals, tn.area, options, tn.total_area, distance};
  // Labels tell faces apart only when there are two or more (a file with
  // one group for the whole surface says nothing about caps).
  const bool labelled =
      labels.size() == nt && nt > 0 &&
      std::any_of(labels.begin(), labels.end(), [&](int32_t l) { return l != labels[0]; });

  // Phase 1: candidates.
  std::vector<std::vector<int32_t>> candidates;
  const std::vector<uint8_t> all(nt, 1);
  if (labelled) {
    candidates = grow_regions(ctx, all, 1, [&](int32_t, int32_t t, int32_t s, int32_t) {
      return labels[size_t(t)] == labels[size_t(s)];
    });
  } else {
    const double flat = angle_cos(options.planar_angle_degrees);
    // A single triangle is no cap of an unlabelled surface.
    candidates = grow_regions(ctx, all, 2, [&](int32_t seed, int32_t, int32_t s, int32_t) {
      return v3::dot(normals[size_t(seed)].data(), normals[size_t(s)].data()) >= flat;
    });
  }

  // Phase 2: tests.
  std::vector<uint8_t> in_region(nt, 0);
  std::vector<int32_t> owner(mesh.num_vertices(), -1);
  std::vector<std::vector<int32_t>> kept_vertices, kept_rims;
  for (auto& triangles : candidates) {
    Region r;
    r.triangles = std::move(triangles);
    for (int32_t t : r.triangles) in_region[size_t(t)] = 1;
    const int32_t label = labelled ? labels[size_t(r.triangles[0])] : -1;
    bool ok = describe(ctx, in_region, r);
    RegionTopology topo;
    std::string problem;
    if (ok && !planar(ctx, r)) {
      problem = "not planar";
      ok = false;
    }
    if (ok) {
      topo = region_topology(ctx, r);
      problem = disk_problem(ctx, r, topo);
      ok = problem.empty() && (labelled || looks_like_a_vessel_end(ctx, in_region, r, topo));
    }
    for (int32_t t : r.triangles) in_region[size_t(t)] = 0;
    // A labelled face that is planar but not a disk is worth a word; walls
    // (not planar) are expected.
    if (labelled && !ok && !problem.empty() && problem != "not planar" &&
        problem != "too large a share of the surface")
      out.notes.push_back(label_text(label, label_names) + " is planar but " + problem +
                          ": kept as wall");
    if (!ok) continue;
    RecognizedCap cap;
    cap.triangles = std::move(r.triangles);
    cap.label = label;
    for (const auto& [l, n] : label_names)
      if (l == label) cap.name = n;
    cap.shape = labelled ? CapShape::kLabelled : CapShape::kPlanar;
    cap.area = r.area;
    cap.radius = std::sqrt(r.area / std::numbers::pi);
    cap.centroid = r.centroid;
    cap.normal = r.normal;
    out.caps.push_back(std::move(cap));
    kept_vertices.push_back(std::move(topo.vertices));
    kept_rims.push_back(std::move(topo.rim_vertices));
  }

  // Phase 2b (unlabelled): caps that are not planar, bounded by creases.
  if (!labelled) {
    std::vector<uint8_t> free(nt, 1);
    for (const RecognizedCap& cap : out.caps)
      for (int32_t t : cap.triangles) free[size_t(t)] = 0;
    // Crease vertices: two triangles of the vertex's star whose normals
    // differ by more than the crease angle. An edge joining two of them
    // bounds the regions: a crease loop (every vertex of a rim loop has
    // triangles of both sides) leaves no gap.
    const double smooth = angle_cos(options.crease_angle_degrees);
    // Needles are left out.
    std::vector<uint8_t> is_needle(nt, 0);
    for (size_t t = 0; t < nt; ++t) is_needle[t] = needle(mesh, t, tn.area[t]);
    const std::vector<Vec3> filtered =
        bilateral_normals(ctx, is_needle, options.crease_angle_degrees);
    // The largest turn between two triangles of each vertex's star.
    std::vector<double> spread(mesh.num_vertices(), 1);  // cosine
    std::vector<int32_t> star;
    for (size_t v = 0; v < mesh.num_vertices(); ++v) {
      star.clear();
      for (int32_t i = adj.star_offsets[v]; i < adj.star_offsets[v + 1]; ++i)
        if (!is_needle[size_t(adj.star[size_t(i)])]) star.push_back(adj.star[size_t(i)]);
      for (size_t i = 0; i < star.size(); ++i)
        for (size_t j = i + 1; j < star.size(); ++j)
          spread[v] =
              std::min(spread[v], dot(filtered[size_t(star[i])], filtered[size_t(star[j])]));
    }
    // Crease vertices: a turn over the crease angle (strong), or over 0.6
    // of it (weak) with at least two neighbours strong or weak, one of them
    // strong, and not more than half (a crease loop's weaker stretch, where
    // the wall leans toward the cap; not a fan's apex, all of whose
    // neighbours are on the rim).
    std::vector<uint8_t> on_crease(mesh.num_vertices(), 0);
    const double weak = angle_cos(0.6 * options.crease_angle_degrees);
    for (size_t v = 0; v < mesh.num_vertices(); ++v)
      on_crease[v] = spread[v] < smooth ? 2 : spread[v] < weak ? 1 : 0;
    const VertexGraph graph = build_vertex_graph(mesh);
    std::vector<uint8_t> weak_crease(mesh.num_vertices(), 0);
    for (size_t v = 0; v < mesh.num_vertices(); ++v) {
      if (on_crease[v] != 1) continue;
      int strong = 0, either = 0;
      const int32_t degree = graph.offsets[v + 1] - graph.offsets[v];
      for (int32_t i = graph.offsets[v]; i < graph.offsets[v + 1]; ++i) {
        const uint8_t c = on_crease[size_t(graph.neighbors[size_t(i)])];
        strong += c == 2;
        either += c > 0;
      }
      weak_crease[v] = strong >= 1 && either >= 2 && 2 * either <= degree;
    }
    for (size_t v = 0; v < mesh.num_vertices(); ++v) on_crease[v] = on_crease[v] == 2;
    for (size_t v = 0; v < mesh.num_vertices(); ++v) on_crease[v] |= weak_crease[v];
    std::vector<std::vector<int32_t>> regions =
        grow_regions(ctx, free, 4, [&](int32_t, int32_t, int32_t, int32_t h) {
          return !(on_crease[size_t(half_edge_from(mesh, h))] &&
                   on_crease[size_t(half_edge_to(mesh, h))]);
        });
    for (auto& triangles : regions) {
      Region r;
      r.triangles = std::move(triangles);
      for (int32_t t : r.triangles) in_region[size_t(t)] = 1;
      RecognizedCap cap;
      RegionTopology topo;
      bool ok = describe(ctx, in_region, r);
      if (ok) {
        topo = region_topology(ctx, r);
        // Islands inside the region (a dome's top where its curvature
        // turns the normal as much as a crease) are part of it.
        if (topo.rim_loops > 1 && take_islands(ctx, in_region, r)) {
          ok = describe(ctx, in_region, r);
          if (ok) topo = region_topology(ctx, r);
        }
        ok = ok && disk_problem(ctx, r, topo).empty() && shaped_cap(ctx, in_region, r, topo, cap);
      }
      for (int32_t t : r.triangles) in_region[size_t(t)] = 0;
      if (!ok) continue;
      cap.triangles = std::move(r.triangles);
      out.caps.push_back(std::move(cap));
      kept_vertices.push_back(std::move(topo.vertices));
      kept_rims.push_back(std::move(topo.rim_vertices));
    }
  }

  // Phase 3: an unlabelled cap much narrower than the lumen across its rim
  // is a flat spot on a vessel's side (noise), not a vessel end. The median
  // half chord from the rim along the inward normals measures the lumen:
  // about the cap's own radius at a real end (the rays cross the vessel
  // behind it), the vessel's radius beside a flat spot.
  std::vector<uint8_t> narrow(out.caps.size(), 0);
  if (!labelled && !out.caps.empty()) {
    std::vector<int32_t> rims;
    for (const std::vector<int32_t>& rim : kept_rims)
      rims.insert(rims.end(), rim.begin(), rim.end());
    const std::vector<double> chord = half_chords(mesh, rims);
    size_t at = 0;
    for (size_t c = 0; c < out.caps.size(); ++c) {
      std::vector<double> measured;
      for (size_t i = 0; i < kept_rims[c].size(); ++i, ++at)
        if (chord[at] > 0) measured.push_back(chord[at]);
      if (!measured.empty() && out.caps[c].radius < options.min_lumen_fraction * median(measured))
        narrow[c] = 1;
    }
  }

  // Phase 4: caps sharing a vertex cannot both become openings.
  std::vector<uint8_t> drop(out.caps.size(), 0);
  for (size_t c = 0; c < out.caps.size(); ++c)
    for (int32_t v : kept_vertices[c]) {
      if (narrow[c]) break;
      if (owner[size_t(v)] >= 0 && owner[size_t(v)] != int32_t(c))
        drop[c] = drop[size_t(owner[size_t(v)])] = 1;
      owner[size_t(v)] = int32_t(c);
    }
  size_t n = 0;
  for (size_t c = 0; c < out.caps.size(); ++c) {
    if (narrow[c]) continue;
    if (drop[c]) {
      out.notes.push_back("a flat end at " + std::to_string(out.caps[c].centroid[0]) + ", " +
                          std::to_string(out.caps[c].centroid[1]) + ", " +
                          std::to_string(out.caps[c].centroid[2]) +
                          " touches another one: both kept as wall");
      continue;
    }
    if (n != c) out.caps[n] = std::move(out.caps[c]);
    ++n;
  }
  out.caps.resize(n);
  return out;
}

}  // namespace vm
