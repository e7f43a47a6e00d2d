// Detection and smoothing of voxel staircases (smooth_surface.h): Taubin's
// lambda|mu filter (SIGGRAPH 1995) with a volume constraint after each pass
// (Desbrun et al., SIGGRAPH 1999) and displacements clamped to half a voxel.
#include "core/prepare/smooth_surface.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "core/geom/vec3.h"
#include "core/mesh/boundary_loops.h"
#include "core/util/parallel.h"
#include "core/util/portable_math.h"
#include "core/util/radix_sort.h"

namespace vm {

const char* smoothing_mode_name(Smoothing::Mode mode) {
  return mode == Smoothing::Mode::kOff      ? "off"
         : mode == Smoothing::Mode::kPasses ? "passes"
                                            : "auto";
}

namespace {

const double* point(const SurfaceMesh& m, int32_t v) { return &m.points[3 * size_t(v)]; }

/// Area vector (b - a) x (c - a) / 2 of triangle t.
Vec3 area_vector(const SurfaceMesh& m, size_t t) {
  const double* a = point(m, m.triangles[3 * t]);
  const double* b = point(m, m.triangles[3 * t + 1]);
  const double* c = point(m, m.triangles[3 * t + 2]);
  const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double w[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  return {0.5 * (u[1] * w[2] - u[2] * w[1]), 0.5 * (u[2] * w[0] - u[0] * w[2]),
          0.5 * (u[0] * w[1] - u[1] * w[0])};
}

/// Chunk of the loops over triangles or vertices (parallel.h).
constexpr size_t kGrain = size_t(1) << 16;
/// Vertices whose coordinates measure the lattice, at most.
constexpr size_t kLatticeSample = 1'000'000;

double cos_degrees(double degrees) { return pm::cos(degrees * std::numbers::pi / 180); }

/// The step of the lattice that most of the sorted values lie on: the
/// median gap between the values shared by at least 3 (closer than `merge`
/// are equal; values off the lattice, such as the vertices of a cut, are
/// seldom shared), refined by a least-squares fit of value = origin + m step
/// over the lattice numbers m. 0 when fewer than 3 values are shared.
/// `origin` gets the phase.
double lattice_step(const std::vector<double>& sorted, double merge, double& origin) {
  std::vector<double> distinct;
  for (size_t i = 0; i < sorted.size();) {
    size_t j = i + 1;
    while (j < sorted.size() && sorted[j] - sorted[j - 1] <= merge) ++j;
    if (j - i >= 3) distinct.push_back(sorted[i]);
    i = j;
  }
  if (distinct.size() < 3) return 0;
  std::vector<double> gaps;
  for (size_t i = 1; i < distinct.size(); ++i) gaps.push_back(distinct[i] - distinct[i - 1]);
  std::nth_element(gaps.begin(), gaps.begin() + long(gaps.size() / 2), gaps.end());
  const double guess = gaps[gaps.size() / 2];
  origin = distinct[0];
  if (!(guess > 0)) return 0;
  // Fit, then fit again without the values more than a tenth of a step off.
  double step = guess;
  for (int round = 0; round < 2; ++round) {
    double n = 0, sm = 0, sx = 0, smm = 0, smx = 0;
    for (double x : distinct) {
      const double u = (x - origin) / step, m = std::round(u);
      if (round > 0 && std::fabs(u - m) > 0.1) continue;
      n += 1, sm += m, sx += x, smm += m * m, smx += m * x;
    }
    const double det = n * smm - sm * sm;
    const double fit = det > 0 ? (n * smx - sm * sx) / det : 0;
    if (!(fit > 0.5 * step && fit < 2 * step)) break;
    step = fit;
    origin = (sx - step * sm) / n;
  }
  return step;
}

/// The grid directions of a voxel of sides `spacing` (> 0): the normals of
/// the planes through the middles of grid edges, (c0 / s0, c1 / s1, c2 /
/// s2) normalized for c in {-1, 0, 1}^3, one of each opposite pair: 13.
std::vector<Vec3> grid_directions(const std::array<double, 3>& spacing) {
  std::vector<Vec3> directions;
  for (int code = 0; code < 27; ++code) {
    const int c[3] = {code % 3 - 1, code / 3 % 3 - 1, code / 9 - 1};  // each -1, 0 or 1
    const int first = c[0] != 0 ? c[0] : c[1] != 0 ? c[1] : c[2];
    if (first != 1) continue;  // one of each opposite pair, no zero vector
    Vec3 d = {c[0] / spacing[0], c[1] / spacing[1], c[2] / spacing[2]};
    const double len = norm(d);
    for (double& x : d) x /= len;
    directions.push_back(d);
  }
  return directions;
}

}  // namespace

StaircaseReport detect_staircase(const SurfaceMesh& mesh, const StaircaseOptions& options,
                                 const TriangleNormals* known) {
  StaircaseReport r;
  const size_t nt = mesh.num_triangles();
  if (nt == 0) return r;
  TriangleNormals own;
  const TriangleNormals& tn = known ? *known : (own = triangle_normals(mesh));
  const std::vector<Vec3>& normals = tn.normal;
  const std::vector<double>& areas = tn.area;
  const double total_area = tn.total_area;
  if (!(total_area > 0)) return r;
  const BoundingBox box = bounding_box(mesh.points);
  const double merge = 1e-6 * box.diagonal();
  const size_t nv = mesh.num_vertices();

  // Share of the area facing grid directions: the axes, the face diagonals
  // and the body diagonals of the voxel (of a cube until it is measured).
  auto direction_fraction = [&](const std::array<double, 3>& spacing) {
    const std::vector<Vec3> directions = grid_directions(spacing);
    const double direction_cos = cos_degrees(options.direction_tolerance_degrees);
    const double on_grid = parallel_sum<double>(nt, kGrain, [&](size_t begin, size_t end) {
      double sum = 0;
      for (size_t t = begin; t < end; ++t)
        for (const Vec3& d : directions)
          if (std::fabs(dot(normals[t], d)) >= direction_cos) {
            sum += areas[t];
            break;
          }
      return sum;
    });
    return on_grid / total_area;
  };

  // The lattice of the vertices along each axis: marching cubes on a binary
  // mask puts every vertex in the middle of a grid edge, so its coordinates
  // are on the lattice of half voxels.
  // On surfaces of over a million vertices the lattice is measured on every
  // k-th vertex (a voxel plane holds thousands of vertices; the sorts of
  // all coordinates would be most of the test's time).
  std::array<double, 3> half{}, origin{};
  const size_t stride = (nv + kLatticeSample - 1) / kLatticeSample;
  std::vector<double> values((nv + stride - 1) / stride);
  for (int k = 0; k < 3; ++k) {
    for (size_t i = 0; i < values.size(); ++i) values[i] = mesh.points[3 * i * stride + size_t(k)];
    radix_sort(values);
    half[size_t(k)] = lattice_step(values, merge, origin[size_t(k)]);
    if (!(half[size_t(k)] > 0)) {  // no lattice: not a staircase
      r.direction_fraction = direction_fraction({1, 1, 1});
      return r;
    }
  }
  // Vertices on the lattice, and edges spanning two half steps along an axis
  // (edge middles of opposite grid edges: the lattice is of half voxels)
  // rather than one at most (voxel corners: the lattice is of voxels).
  const size_t on_lattice = parallel_sum<size_t>(nv, kGrain, [&](size_t begin, size_t end) {
    size_t count = 0;
    for (size_t v = begin; v < end; ++v) {
      bool on = true;
      for (int k = 0; k < 3 && on; ++k) {
        const double u = (mesh.points[3 * v + size_t(k)] - origin[size_t(k)]) / half[size_t(k)];
        on = std::fabs(u - std::round(u)) <= 0.5 * options.lattice_tolerance;
      }
      count += on;
    }
    return count;
  });
  r.lattice_fraction = nv ? double(on_lattice) / double(nv) : 0;
  const size_t edges = mesh.triangles.size();
  const size_t double_steps =
      parallel_sum<size_t>(edges, 3 * kGrain, [&](size_t begin, size_t end) {
        size_t count = 0;
        for (size_t h = begin; h < end; ++h) {
          const double* a = point(mesh, mesh.triangles[h]);
          const double* b = point(mesh, mesh.triangles[h - h % 3 + (h % 3 + 1) % 3]);
          double steps = 0;
          for (int k = 0; k < 3; ++k)
            steps = std::max(steps, std::fabs(b[k] - a[k]) / half[size_t(k)]);
          count += std::fabs(steps - 2) < options.lattice_tolerance;
        }
        return count;
      });
  const bool midpoints = double(double_steps) >= 0.05 * double(edges);
  for (int k = 0; k < 3; ++k) r.spacing[size_t(k)] = (midpoints ? 2 : 1) * half[size_t(k)];
  r.voxel = std::max({r.spacing[0], r.spacing[1], r.spacing[2]});

  // Terraces: planes of facets facing an axis (counted).
  const double terrace_cos = cos_degrees(options.terrace_tolerance_degrees);
  for (int k = 0; k < 3; ++k) {
    values.clear();
    for (size_t t = 0; t < nt; ++t)
      if (std::fabs(normals[t][size_t(k)]) >= terrace_cos)
        values.push_back(point(mesh, mesh.triangles[3 * t])[k]);
    radix_sort(values);
    for (size_t i = 0; i < values.size(); ++i)
      r.terraces += i == 0 || values[i] - values[i - 1] > merge;
  }

  r.direction_fraction = direction_fraction(r.spacing);
  r.staircase = r.direction_fraction >= options.min_direction_fraction &&
                r.lattice_fraction >= options.min_lattice_fraction &&
                r.terraces >= options.min_terraces;
  if (!r.staircase) {  // no voxel: the lattice found is chance
    r.spacing = {};
    r.voxel = 0;
  }
  return r;
}

double median_edge_length(const SurfaceMesh& mesh) {
  std::vector<double> lengths;
  lengths.reserve(mesh.triangles.size());
  for (size_t h = 0; h < mesh.triangles.size(); ++h) {
    const size_t next = h - h % 3 + (h % 3 + 1) % 3;
    const double* a = point(mesh, mesh.triangles[h]);
    const double* b = point(mesh, mesh.triangles[next]);
    lengths.push_back(pm::hypot(b[0] - a[0], b[1] - a[1], b[2] - a[2]));
  }
  if (lengths.empty()) return 0;
  std::nth_element(lengths.begin(), lengths.begin() + long(lengths.size() / 2), lengths.end());
  return lengths[lengths.size() / 2];
}

int staircase_passes(const SurfaceMesh& mesh, double voxel) {
  const double edge = median_edge_length(mesh);
  if (!(edge > 0) || !(voxel > 0)) return 10;
  const double reach = 2 * voxel / edge;  // edges across two voxels
  return int(std::clamp(std::ceil(6 * reach * reach), 10.0, 200.0));
}

namespace {

/// Vertex neighbors (CSR), each once, each ring sorted by index.
VertexRings sorted_vertex_rings(const SurfaceMesh& mesh, const TriangleAdjacency& adj) {
  VertexRings r = vertex_rings(mesh, adj);
  for (size_t v = 0; v + 1 < r.offsets.size(); ++v)
    std::sort(r.ids.begin() + r.offsets[v], r.ids.begin() + r.offsets[v + 1]);
  return r;
}

/// How a vertex may move: freely, along its loop (an opening's rim or a
/// flat region's) in the loop's plane, in its flat region's plane, or not.
enum : uint8_t { kFree = 0, kAlongLoop = 1, kInPlane = 2, kFixed = 3 };

/// A plane vertices are held in.
struct Plane {
  Vec3 point{}, normal{};  ///< normal: unit
};

/// Per vertex: how it may move, its plane (index into `planes`) and, along
/// a loop, its two neighbors on the loop.
struct Constraints {
  std::vector<uint8_t> kind;
  std::vector<int32_t> plane;
  std::vector<std::array<int32_t, 2>> loop;
  std::vector<Plane> planes;

  explicit Constraints(size_t nv) : kind(nv, kFree), plane(nv, -1), loop(nv, {-1, -1}) {}

  /// Vertex v gets `k`; a vertex that already had a constraint is fixed.
  void set(int32_t v, uint8_t k, int32_t plane_id, std::array<int32_t, 2> neighbors = {-1, -1}) {
    const size_t i = size_t(v);
    if (kind[i] != kFree) {
      kind[i] = kFixed;
      return;
    }
    kind[i] = k;
    plane[i] = plane_id;
    loop[i] = neighbors;
  }
};

/// Whether every vertex of `vertices` is within `tolerance` of the plane.
bool within_plane(const SurfaceMesh& m, const std::vector<int32_t>& vertices, const Plane& p,
                  double tolerance) {
  for (int32_t v : vertices) {
    const double* x = point(m, v);
    double d = 0;
    for (int k = 0; k < 3; ++k) d += (x[k] - p.point[size_t(k)]) * p.normal[size_t(k)];
    if (std::fabs(d) > tolerance) return false;
  }
  return true;
}

/// Openings: a planar boundary loop slides along itself in its plane (so the
/// opening stays where it was), another stays fixed. Returns the loops.
std::vector<std::vector<int32_t>> hold_openings(const SurfaceMesh& mesh,
                                                const TriangleAdjacency& adj, double tolerance,
                                                Constraints& c) {
  std::vector<std::vector<int32_t>> loops = boundary_loops(mesh, adj);
  for (const std::vector<int32_t>& loop : loops) {
    const size_t n = loop.size();
    Plane p;
    for (int32_t v : loop)
      for (int k = 0; k < 3; ++k) p.point[size_t(k)] += point(mesh, v)[k] / double(n);
    for (size_t i = 0; i < n; ++i) {  // Newell's normal
      const double* a = point(mesh, loop[i]);
      const double* b = point(mesh, loop[(i + 1) % n]);
      for (int k = 0; k < 3; ++k) {
        const int k1 = (k + 1) % 3, k2 = (k + 2) % 3;
        p.normal[size_t(k)] += (a[k1] - b[k1]) * (a[k2] + b[k2]);
      }
    }
    const double len = norm(p.normal);
    if (len > 0)
      for (double& x : p.normal) x /= len;
    const bool planar = len > 0 && n >= 3 && within_plane(mesh, loop, p, tolerance);
    const int32_t id = int32_t(c.planes.size());
    c.planes.push_back(p);
    for (size_t i = 0; i < n; ++i) {
      if (planar)
        c.set(loop[i], kAlongLoop, id, {loop[(i + n - 1) % n], loop[(i + 1) % n]});
      else
        c.kind[size_t(loop[i])] = kFixed;
    }
  }
  return loops;
}

/// Flat regions (planar caps): triangles grown across edges from a seed
/// while their normals stay within `angle_cos` of the seed's, not facing a
/// direction of `grid` (a staircase's terraces are smoothed), of area at
/// least `min_area`, every vertex within `tolerance` of the region's plane.
/// Their inner vertices move in the plane, their rims along themselves in
/// the plane, so caps stay flat with their sharp rims. Returns the number of
/// regions held.
size_t hold_flat_regions(const SurfaceMesh& mesh, const TriangleAdjacency& adj,
                         const std::vector<Vec3>& grid, double angle_cos, double min_area,
                         double tolerance, Constraints& c) {
  const size_t nt = mesh.num_triangles();
  std::vector<Vec3> normals(nt);
  std::vector<double> areas(nt);
  for (size_t t = 0; t < nt; ++t) {
    Vec3 a = area_vector(mesh, t);
    areas[t] = norm(a);
    if (areas[t] > 0)
      for (double& x : a) x /= areas[t];
    normals[t] = a;
  }
  const double grid_cos = pm::cos(2 * std::numbers::pi / 180);
  std::vector<uint8_t> taken(nt, 0);
  for (size_t t = 0; t < nt; ++t) {
    bool terrace = false;
    for (const Vec3& d : grid) terrace = terrace || std::fabs(dot(normals[t], d)) >= grid_cos;
    if (terrace || !(areas[t] > 0)) taken[t] = 1;
  }
  std::vector<int32_t> region, stack;
  std::vector<uint8_t> in_region(nt, 0);
  size_t held = 0;
  for (size_t seed = 0; seed < nt; ++seed) {
    if (taken[seed]) continue;
    region.assign(1, int32_t(seed));
    stack.assign(1, int32_t(seed));
    taken[seed] = 1;
    while (!stack.empty()) {
      const int32_t t = stack.back();
      stack.pop_back();
      for (int k = 0; k < 3; ++k) {
        const int32_t o = adj.opposite[3 * size_t(t) + size_t(k)];
        if (o < 0 || taken[size_t(o / 3)]) continue;
        if (dot(normals[size_t(o / 3)], normals[seed]) < angle_cos) continue;
        taken[size_t(o / 3)] = 1;
        region.push_back(o / 3);
        stack.push_back(o / 3);
      }
    }
    Plane p;
    double area = 0;
    std::vector<int32_t> vertices;
    for (int32_t t : region) {
      const double a = areas[size_t(t)];
      area += a;
      for (int k = 0; k < 3; ++k) {
        p.normal[size_t(k)] += a * normals[size_t(t)][size_t(k)];
        const int32_t v = mesh.triangles[3 * size_t(t) + size_t(k)];
        vertices.push_back(v);
        for (int i = 0; i < 3; ++i) p.point[size_t(i)] += a / 3 * point(mesh, v)[i];
      }
    }
    if (area < min_area) continue;
    for (double& x : p.point) x /= area;
    const double len = norm(p.normal);
    if (!(len > 0)) continue;
    for (double& x : p.normal) x /= len;
    std::sort(vertices.begin(), vertices.end());
    vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
    if (!within_plane(mesh, vertices, p, tolerance)) continue;
    // The rim: half-edges of the region whose other side is not in it.
    for (int32_t t : region) in_region[size_t(t)] = 1;
    std::vector<std::pair<int32_t, int32_t>> rim;  // (from, to)
    for (int32_t t : region)
      for (int k = 0; k < 3; ++k) {
        const int32_t h = 3 * t + k, o = adj.opposite[size_t(h)];
        if (o >= 0 && in_region[size_t(o / 3)]) continue;
        rim.push_back({half_edge_from(mesh, h), half_edge_to(mesh, h)});
      }
    for (int32_t t : region) in_region[size_t(t)] = 0;
    std::vector<std::pair<int32_t, int32_t>> back;  // (to, from)
    for (const auto& [from, to] : rim) back.push_back({to, from});
    std::sort(rim.begin(), rim.end());
    std::sort(back.begin(), back.end());
    const int32_t id = int32_t(c.planes.size());
    c.planes.push_back(p);
    ++held;
    std::vector<int32_t> rim_vertices;
    for (size_t i = 0; i < rim.size(); ++i) {
      const int32_t v = rim[i].first;
      rim_vertices.push_back(v);
      // One half-edge out of v and one into it, else v is a pinch: fixed.
      const auto into =
          std::equal_range(back.begin(), back.end(), std::pair{v, INT32_MIN},
                           [](const auto& a, const auto& b) { return a.first < b.first; });
      const bool single = (i + 1 == rim.size() || rim[i + 1].first != v) &&
                          (i == 0 || rim[i - 1].first != v) && into.second - into.first == 1;
      if (!single) {
        c.kind[size_t(v)] = kFixed;
        continue;
      }
      c.set(v, kAlongLoop, id, {into.first->second, rim[i].second});
    }
    std::sort(rim_vertices.begin(), rim_vertices.end());
    for (int32_t v : vertices)
      if (!std::binary_search(rim_vertices.begin(), rim_vertices.end(), v)) c.set(v, kInPlane, id);
  }
  return held;
}

/// Volume enclosed by the mesh with each opening's loop closed by a fan
/// from its centroid (reversed: the loops run along the triangles' boundary
/// half-edges), relative to origin o.
double closed_volume(const SurfaceMesh& m, const std::vector<std::vector<int32_t>>& loops,
                     const Vec3& o) {
  auto det = [&](const double* a, const double* b, const double* c) {
    const double p[3] = {a[0] - o[0], a[1] - o[1], a[2] - o[2]};
    const double q[3] = {b[0] - o[0], b[1] - o[1], b[2] - o[2]};
    const double r[3] = {c[0] - o[0], c[1] - o[1], c[2] - o[2]};
    return p[0] * (q[1] * r[2] - q[2] * r[1]) + p[1] * (q[2] * r[0] - q[0] * r[2]) +
           p[2] * (q[0] * r[1] - q[1] * r[0]);
  };
  double sum = 0;
  for (size_t t = 0; t < m.num_triangles(); ++t)
    sum += det(point(m, m.triangles[3 * t]), point(m, m.triangles[3 * t + 1]),
               point(m, m.triangles[3 * t + 2]));
  for (const std::vector<int32_t>& loop : loops) {
    Vec3 c{};
    for (int32_t v : loop)
      for (int k = 0; k < 3; ++k) c[size_t(k)] += point(m, v)[k] / double(loop.size());
    for (size_t i = 0; i < loop.size(); ++i)
      sum += det(point(m, loop[(i + 1) % loop.size()]), point(m, loop[i]), c.data());
  }
  return sum / 6;
}

}  // namespace

SmoothReport smooth_surface(SurfaceMesh& mesh, const TriangleAdjacency& adj,
                            const SmoothOptions& options) {
  SmoothReport report;
  const size_t nv = mesh.num_vertices();
  const Vec3& radii = options.max_displacement;
  if (!(radii[0] > 0 && radii[1] > 0 && radii[2] > 0) || options.passes <= 0) return report;
  const std::vector<double> input = mesh.points;
  const VertexRings nb = sorted_vertex_rings(mesh, adj);
  const double tolerance = options.planar_tolerance * std::min({radii[0], radii[1], radii[2]});

  Constraints c(nv);
  const std::vector<std::vector<int32_t>> loops = hold_openings(mesh, adj, tolerance, c);
  if (options.flat_min_area > 0) {
    const bool staircase = options.grid[0] > 0 && options.grid[1] > 0 && options.grid[2] > 0;
    report.flat_regions = hold_flat_regions(
        mesh, adj, staircase ? grid_directions(options.grid) : std::vector<Vec3>{},
        cos_degrees(options.flat_angle_degrees), options.flat_min_area, tolerance, c);
  }
  for (uint8_t k : c.kind) {
    report.held_vertices += k == kAlongLoop || k == kInPlane;
    report.fixed_vertices += k == kFixed;
  }

  const BoundingBox box = bounding_box(mesh.points);
  const Vec3 o = {0.5 * (box.min[0] + box.max[0]), 0.5 * (box.min[1] + box.max[1]),
                  0.5 * (box.min[2] + box.max[2])};
  report.volume_before = closed_volume(mesh, loops, o);
  report.volume_after = report.volume_before;

  // Keeps vertex v within the ellipsoid around its input position (a
  // vertex held in a plane stays in it: its input position is in it).
  auto clamp = [&](size_t v) {
    double* p = &mesh.points[3 * v];
    const double* q = &input[3 * v];
    double e = 0;
    for (int k = 0; k < 3; ++k) {
      const double d = (p[k] - q[k]) / radii[size_t(k)];
      e += d * d;
    }
    if (e > 1) {
      const double f = 1 / std::sqrt(e);
      for (int k = 0; k < 3; ++k) p[k] = q[k] + f * (p[k] - q[k]);
    }
  };

  // One Laplacian step: umbrella vectors of all vertices from the current
  // positions (along the loop for loop vertices), projected into the plane
  // of held vertices, then applied with `factor`.
  std::vector<double> delta(3 * nv);
  auto laplacian_step = [&](double factor) {
    for (size_t v = 0; v < nv; ++v) {
      double* d = &delta[3 * v];
      d[0] = d[1] = d[2] = 0;
      const uint8_t kind = c.kind[v];
      if (kind == kFixed) continue;
      const double* p = &mesh.points[3 * v];
      if (kind == kAlongLoop) {
        const double* a = point(mesh, c.loop[v][0]);
        const double* b = point(mesh, c.loop[v][1]);
        for (int k = 0; k < 3; ++k) d[k] = 0.5 * (a[k] + b[k]) - p[k];
      } else {
        const int32_t begin = nb.offsets[v], end = nb.offsets[v + 1];
        if (begin == end) continue;
        for (int32_t i = begin; i < end; ++i)
          for (int k = 0; k < 3; ++k) d[k] += point(mesh, nb.ids[size_t(i)])[k];
        for (int k = 0; k < 3; ++k) d[k] = d[k] / double(end - begin) - p[k];
      }
      if (kind != kFree) {
        const Vec3& n = c.planes[size_t(c.plane[v])].normal;
        const double along = d[0] * n[0] + d[1] * n[1] + d[2] * n[2];
        for (int k = 0; k < 3; ++k) d[k] -= along * n[size_t(k)];
      }
    }
    for (size_t v = 0; v < nv; ++v) {
      if (c.kind[v] == kFixed) continue;
      for (int k = 0; k < 3; ++k)
        mesh.points[3 * v + size_t(k)] += factor * delta[3 * v + size_t(k)];
      clamp(v);
    }
  };

  // Restores the enclosed volume by a uniform offset of the free vertices
  // along their (area-weighted) normals, a few times since the clamp may
  // hold some back.
  std::vector<Vec3> vertex_normals(nv);
  auto restore_volume = [&]() {
    for (int round = 0; round < 3; ++round) {
      const double now = closed_volume(mesh, loops, o);
      if (std::fabs(report.volume_before - now) <= 1e-9 * std::fabs(report.volume_before)) return;
      std::fill(vertex_normals.begin(), vertex_normals.end(), Vec3{});
      for (size_t t = 0; t < mesh.num_triangles(); ++t) {
        const Vec3 a = area_vector(mesh, t);
        for (int i = 0; i < 3; ++i)
          for (int k = 0; k < 3; ++k)
            vertex_normals[size_t(mesh.triangles[3 * t + size_t(i)])][size_t(k)] +=
                a[size_t(k)] / 3;
      }
      // Moving free vertex v by f along its unit normal changes the volume
      // by about f |n_v| (its share of the area): f = dV / sum |n_v|.
      double moving_area = 0;
      for (size_t v = 0; v < nv; ++v)
        if (c.kind[v] == kFree) moving_area += norm(vertex_normals[v]);
      if (!(moving_area > 0)) return;
      const double f = (report.volume_before - now) / moving_area;
      for (size_t v = 0; v < nv; ++v) {
        const double len = norm(vertex_normals[v]);
        if (c.kind[v] != kFree || !(len > 0)) continue;
        for (int k = 0; k < 3; ++k)
          mesh.points[3 * v + size_t(k)] += f * vertex_normals[v][size_t(k)] / len;
        clamp(v);
      }
    }
  };

  for (int pass = 0; pass < options.passes; ++pass) {
    laplacian_step(options.lambda);
    laplacian_step(options.mu);
    if (options.keep_volume) restore_volume();
  }
  report.passes = options.passes;
  report.volume_after = closed_volume(mesh, loops, o);
  for (size_t v = 0; v < nv; ++v) {
    double d2 = 0, e = 0;
    for (int k = 0; k < 3; ++k) {
      const double d = mesh.points[3 * v + size_t(k)] - input[3 * v + size_t(k)];
      d2 += d * d;
      e += (d / radii[size_t(k)]) * (d / radii[size_t(k)]);
    }
    report.max_displacement = std::max(report.max_displacement, std::sqrt(d2));
    report.max_displacement_ratio = std::max(report.max_displacement_ratio, std::sqrt(e));
  }
  return report;
}

}  // namespace vm
