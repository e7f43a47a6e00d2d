// Planar caps (Marchandise et al., section 2; planar mesher of section 3) in
// phases: (1) openings of the wall and checks of its orientation; (2) per
// opening, least-squares plane of the rim, plane frame, rim in plane
// coordinates, simple-polygon check, area; (3) order by area and names;
// (4) rims moved onto their planes; (5) per cap, frontal-Delaunay mesh of the
// rim polygon with the blended rim size, optimization, checks that the rim
// is shared edge for edge, map back; (6) outward orientation of the result;
// (7) wall triangles flipped by the projection.
#include "core/surface/cap_openings.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <sstream>

#include "core/geom/predicates.h"
#include "core/geom/vec3.h"
#include "core/mesh/adjacency.h"
#include "core/mesh/boundary_loops.h"
#include "core/mesh/enclosed_volume.h"
#include "core/mesh2d/frontal_delaunay.h"
#include "core/mesh2d/optimize2d.h"
#include "core/quality/triangle_quality.h"
#include "core/util/portable_math.h"

namespace vm {
namespace {

Vec3 point(const std::vector<double>& pts, int32_t v) { return at(pts, v); }
Vec3 sub(const Vec3& a, const Vec3& b) { return a - b; }

Vec3 triangle_normal(const std::vector<double>& pts, const int32_t* v) {
  const Vec3 a = point(pts, v[0]);
  return cross(sub(point(pts, v[1]), a), sub(point(pts, v[2]), a));
}

std::string describe(const Vec3& c, size_t rim) {
  std::ostringstream s;
  s.precision(6);
  s << "the opening at (" << c[0] << ", " << c[1] << ", " << c[2] << ") with " << rim
    << " rim vertices";
  return s.str();
}

// One opening between the phases.
struct Opening {
  std::vector<int32_t> loop;  // wall vertex ids, wall half-edge order
  Vec3 origin{}, normal{}, e1{}, e2{};
  std::vector<double> uv;  // rim in plane coordinates, 2 per rim vertex
  double area = 0;         // of the rim polygon
  double max_projection = 0;
};

// Phase 2a: the rim plane (fit_opening_plane, public below).
Status fit_plane(const std::vector<double>& pts, Opening& op) {
  Result<OpeningPlane> plane = fit_opening_plane(pts, op.loop);
  if (!plane.ok()) return plane.status();
  OpeningPlane& p = plane.value();
  op.origin = p.origin;
  op.normal = p.normal;
  op.e1 = p.e1;
  op.e2 = p.e2;
  op.uv = std::move(p.uv);
  op.max_projection = p.max_projection;
  return Status::Ok();
}

int sgn(double x) { return (x > 0) - (x < 0); }

bool on_collinear_segment(const double* p, const double* q, const double* r) {
  for (int k = 0; k < 2; ++k)
    if (r[k] < std::min(p[k], q[k]) || r[k] > std::max(p[k], q[k])) return false;
  return true;
}

bool segments_meet(const double* p, const double* q, const double* r, const double* s) {
  const int o1 = sgn(orient2d(p, q, r)), o2 = sgn(orient2d(p, q, s));
  const int o3 = sgn(orient2d(r, s, p)), o4 = sgn(orient2d(r, s, q));
  if (o1 * o2 < 0 && o3 * o4 < 0) return true;
  return (o1 == 0 && on_collinear_segment(p, q, r)) || (o2 == 0 && on_collinear_segment(p, q, s)) ||
         (o3 == 0 && on_collinear_segment(r, s, p)) || (o4 == 0 && on_collinear_segment(r, s, q));
}

// Phase 2b: the rim polygon in plane coordinates must be simple: no
// repeated point, no fold between consecutive edges, no two other edges
// meeting (exact orient2d). Sweep over the edges sorted by their smallest u.
Status check_simple(const Opening& op) {
  const size_t n = op.loop.size();
  const double* uv = op.uv.data();
  auto P = [&](size_t i) { return uv + 2 * (i % n); };
  auto fail = [&](const std::string& what) {
    return Status::Error(describe(op.origin, n) + ": its rim projected onto the fitted plane " +
                         what + " (largest projection distance " +
                         std::to_string(op.max_projection) +
                         "); the opening is too far from planar to cap");
  };
  for (size_t i = 0; i < n; ++i) {
    const double *a = P(i + n - 1), *b = P(i), *c = P(i + 1);
    if (b[0] == c[0] && b[1] == c[1]) return fail("has two coincident vertices");
    if (orient2d(a, b, c) == 0 && (a[0] - b[0]) * (c[0] - b[0]) + (a[1] - b[1]) * (c[1] - b[1]) > 0)
      return fail("folds back on itself");
  }
  std::vector<size_t> order(n);
  std::iota(order.begin(), order.end(), size_t(0));
  auto umin = [&](size_t i) { return std::min(P(i)[0], P(i + 1)[0]); };
  auto umax = [&](size_t i) { return std::max(P(i)[0], P(i + 1)[0]); };
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return umin(a) < umin(b); });
  for (size_t x = 0; x < n; ++x) {
    const size_t i = order[x];
    for (size_t y = x + 1; y < n && umin(order[y]) <= umax(i); ++y) {
      const size_t j = order[y];
      if ((i + 1) % n == j || (j + 1) % n == i) continue;  // consecutive: checked above
      if (segments_meet(P(i), P(i + 1), P(j), P(j + 1)))
        return fail("intersects itself (rim edges " + std::to_string(i) + " and " +
                    std::to_string(j) + ")");
    }
  }
  double twice = 0;
  for (size_t i = 0; i < n; ++i) twice += P(i)[0] * P(i + 1)[1] - P(i + 1)[0] * P(i)[1];
  // Loop order winds clockwise around the outward normal.
  if (!(twice < 0)) return fail("winds the wrong way around its outward normal");
  return Status::Ok();
}

// Phase 5a: the cap's size field in plane coordinates (see cap_openings.h).
class CapSize {
 public:
  CapSize(const Opening& op, const std::vector<double>& vertex_size, double blend)
      : uv_(op.uv), blend_(blend) {
    const size_t n = op.loop.size();
    edge_.resize(n);
    target_.resize(n);
    for (size_t i = 0; i < n; ++i) {
      const size_t j = (i + 1) % n, h = (i + n - 1) % n;
      edge_[i] = 0.5 * (pm::hypot(uv_[2 * j] - uv_[2 * i], uv_[2 * j + 1] - uv_[2 * i + 1]) +
                        pm::hypot(uv_[2 * h] - uv_[2 * i], uv_[2 * h + 1] - uv_[2 * i + 1]));
      target_[i] = vertex_size.empty() ? edge_[i] : vertex_size[size_t(op.loop[i])];
    }
  }

  double operator()(double u, double v) const {
    double sw = 0, se = 0, st = 0, d2min = std::numeric_limits<double>::infinity();
    for (size_t i = 0; i < edge_.size(); ++i) {
      const double du = u - uv_[2 * i], dv = v - uv_[2 * i + 1], d2 = du * du + dv * dv;
      if (d2 == 0) return edge_[i];
      const double w = edge_[i] / d2;
      sw += w;
      se += w * edge_[i];
      st += w * target_[i];
      d2min = std::min(d2min, d2);
    }
    const double h_rim = se / sw, h_target = st / sw;
    const double s = std::min(1.0, std::sqrt(d2min) / (blend_ * h_rim));
    const double beta = s * s * (3 - 2 * s);
    return (1 - beta) * h_rim + beta * h_target;
  }

 private:
  const std::vector<double>& uv_;
  double blend_;
  std::vector<double> edge_, target_;
};

}  // namespace

// Least-squares plane through the rim, weighted by each vertex's share of the
// loop length; normal oriented against the loop's vector area (out of the
// lumen). Fails on a degenerate rim.
Result<OpeningPlane> fit_opening_plane(const std::vector<double>& pts,
                                       const std::vector<int32_t>& loop) {
  using R = Result<OpeningPlane>;
  OpeningPlane op;
  const size_t n = loop.size();
  if (n == 0) return R::Error("an opening has an empty rim");
  std::vector<double> w(n);
  double total = 0;
  Vec3 vector_area{0, 0, 0};
  const Vec3 p0 = point(pts, loop[0]);
  for (size_t i = 0; i < n; ++i) {
    const Vec3 a = point(pts, loop[i]), b = point(pts, loop[(i + 1) % n]);
    const double len = norm(sub(b, a));
    w[i] += 0.5 * len;
    w[(i + 1) % n] += 0.5 * len;
    total += len;
    const Vec3 c = cross(sub(a, p0), sub(b, p0));
    for (int k = 0; k < 3; ++k) vector_area[k] += 0.5 * c[k];
  }
  if (!(total > 0)) return R::Error(describe(p0, n) + " has a rim of zero length");
  Vec3 c{0, 0, 0};
  for (size_t i = 0; i < n; ++i) {
    const Vec3 p = point(pts, loop[i]);
    for (int k = 0; k < 3; ++k) c[k] += w[i] / total * p[k];
  }
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (size_t i = 0; i < n; ++i) {
    const Vec3 d = sub(point(pts, loop[i]), c);
    const Eigen::Vector3d e(d[0], d[1], d[2]);
    cov += (w[i] / total) * e * e.transpose();
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);  // ascending eigenvalues
  const Eigen::Vector3d ev = eig.eigenvectors().col(0);
  // A rim spread along a line has no plane.
  if (!(eig.eigenvalues()(1) > 1e-24 * eig.eigenvalues()(2)) || !(eig.eigenvalues()(2) > 0))
    return R::Error(describe(c, n) + " has collinear rim vertices: no cap plane");
  Vec3 normal{ev(0), ev(1), ev(2)};
  const double nn = norm(normal);
  for (double& x : normal) x /= nn;
  // The wall's boundary half-edges wind clockwise seen from outside.
  if (dot(normal, vector_area) > 0)
    for (double& x : normal) x = -x;
  // Frame: e1 toward the first rim vertex (any in-plane direction will do).
  Vec3 e1{0, 0, 0};
  for (size_t i = 0; i < n && norm(e1) == 0; ++i) {
    const Vec3 d = sub(point(pts, loop[i]), c);
    const double h = dot(d, normal);
    e1 = {d[0] - h * normal[0], d[1] - h * normal[1], d[2] - h * normal[2]};
  }
  const double l1 = norm(e1);
  for (double& x : e1) x /= l1;
  op.origin = c;
  op.normal = normal;
  op.e1 = e1;
  op.e2 = cross(normal, e1);  // e1 x e2 = normal: ccw in the plane faces out
  op.uv.resize(2 * n);
  for (size_t i = 0; i < n; ++i) {
    const Vec3 d = sub(point(pts, loop[i]), c);
    op.max_projection = std::max(op.max_projection, std::abs(dot(d, normal)));
    op.uv[2 * i] = dot(d, op.e1);
    op.uv[2 * i + 1] = dot(d, op.e2);
  }
  return op;
}

Result<CappedSurface> cap_openings(const SurfaceMesh& wall, const std::vector<double>& vertex_size,
                                   const CapOptions& options) {
  using R = Result<CappedSurface>;
  const size_t nv = wall.num_vertices(), nt = wall.num_triangles();
  if (!vertex_size.empty() && vertex_size.size() != nv)
    return R::Error("caps: " + std::to_string(vertex_size.size()) + " sizes for " +
                    std::to_string(nv) + " wall vertices");
  if (options.inlet_index < 0) return R::Error("caps: inlet_index must be >= 0");
  if (!(options.blend_lengths > 0)) return R::Error("caps: blend_lengths must be > 0");
  for (int32_t v : wall.triangles)
    if (v < 0 || size_t(v) >= nv) return R::Error("caps: a wall triangle index is out of range");

  // Phase 1: openings; the wall must be manifold and consistently oriented.
  const TriangleAdjacency adj = build_adjacency(wall);
  if (Status s = check_manifold_oriented(wall, adj); !s.ok())
    return R::Error("caps: " + s.message());
  CappedSurface out;
  out.mesh = wall;
  out.wall_vertices = nv;
  out.wall_triangles = nt;
  out.triangle_tag.assign(nt, 0);
  std::vector<Opening> ops;
  std::vector<int32_t> opening_of(nv, -1);
  for (auto& loop : boundary_loops(wall, adj)) {
    for (int32_t v : loop) {
      if (opening_of[size_t(v)] >= 0)
        return R::Error("caps: " + describe(point(wall.points, v), loop.size()) +
                        " shares a vertex with another opening");
      opening_of[size_t(v)] = int32_t(ops.size());
    }
    if (loop.size() < 3)
      return R::Error("caps: " + describe(point(wall.points, loop[0]), loop.size()) +
                      " has fewer than 3 rim vertices");
    ops.push_back({});
    ops.back().loop = std::move(loop);
  }
  if (ops.empty()) return out;
  if (size_t(options.inlet_index) >= ops.size())
    return R::Error("caps: inlet_index " + std::to_string(options.inlet_index) +
                    " is out of range (" + std::to_string(ops.size()) + " openings)");
  if (!vertex_size.empty())
    for (const Opening& op : ops)
      for (int32_t v : op.loop)
        if (!(vertex_size[size_t(v)] > 0) || !std::isfinite(vertex_size[size_t(v)]))
          return R::Error("caps: the size at rim vertex " + std::to_string(v) + " is not positive");

  // Phase 2: planes, plane coordinates, simplicity, area.
  for (Opening& op : ops) {
    Status s = fit_plane(wall.points, op);
    if (!s.ok()) return R::Error("caps: " + s.message());
    s = check_simple(op);
    if (!s.ok()) return R::Error("caps: " + s.message());
    const size_t n = op.loop.size();
    double twice = 0;
    for (size_t i = 0; i < n; ++i) {
      const size_t j = (i + 1) % n;
      twice += op.uv[2 * i] * op.uv[2 * j + 1] - op.uv[2 * j] * op.uv[2 * i + 1];
    }
    op.area = -0.5 * twice;
  }

  // Phase 3: order by decreasing area (areas equal to 1e-9 of the largest
  // are ties, broken by the smallest rim vertex id, so the order does not
  // depend on rounding), the chosen inlet first.
  std::vector<size_t> by_area(ops.size());
  std::iota(by_area.begin(), by_area.end(), size_t(0));
  double largest = 0;
  for (const Opening& op : ops) largest = std::max(largest, op.area);
  auto area_key = [&](size_t i) { return std::llround(ops[i].area / (1e-9 * largest)); };
  std::sort(by_area.begin(), by_area.end(), [&](size_t a, size_t b) {
    if (area_key(a) != area_key(b)) return area_key(a) > area_key(b);
    return *std::min_element(ops[a].loop.begin(), ops[a].loop.end()) <
           *std::min_element(ops[b].loop.begin(), ops[b].loop.end());
  });
  std::vector<size_t> tag_order = {by_area[size_t(options.inlet_index)]};
  for (size_t i = 0; i < by_area.size(); ++i)
    if (int(i) != options.inlet_index) tag_order.push_back(by_area[i]);

  // Phase 4: rims onto their planes (the wall keeps the vertices).
  std::vector<Vec3> normal_before;
  std::vector<size_t> rim_triangles;
  for (size_t t = 0; t < nt; ++t)
    for (int k = 0; k < 3; ++k)
      if (opening_of[size_t(wall.triangles[3 * t + size_t(k)])] >= 0) {
        rim_triangles.push_back(t);
        normal_before.push_back(triangle_normal(wall.points, &wall.triangles[3 * t]));
        break;
      }
  for (const Opening& op : ops) {
    OpeningPlane plane;
    plane.origin = op.origin;
    plane.e1 = op.e1;
    plane.e2 = op.e2;
    for (size_t i = 0; i < op.loop.size(); ++i) {
      const Vec3 p = plane.at(op.uv[2 * i], op.uv[2 * i + 1]);
      for (int k = 0; k < 3; ++k) out.mesh.points[3 * size_t(op.loop[i]) + size_t(k)] = p[k];
    }
  }

  // Phase 5: mesh each cap in tag order.
  for (size_t c = 0; c < tag_order.size(); ++c) {
    const Opening& op = ops[tag_order[c]];
    const size_t n = op.loop.size();
    CapInfo info;
    info.tag = int32_t(c + 1);
    info.name = c == 0 ? "inlet" : "outlet_" + std::to_string(c);
    info.area = op.area;
    info.normal = op.normal;
    info.rim = op.loop;
    info.max_projection_distance = op.max_projection;
    std::vector<int32_t> seg;
    seg.reserve(2 * n);
    for (size_t j = 0; j < n; ++j) seg.insert(seg.end(), {int32_t(j), int32_t((j + 1) % n)});
    const CapSize size(op, vertex_size, options.blend_lengths);
    Result<Mesh2D> plane = frontal_delaunay(
        op.uv, seg, [&size](double u, double v) { return size(u, v); }, options.refinement);
    if (!plane.ok())
      return R::Error("caps: meshing " + describe(op.origin, n) + " failed: " + plane.message());
    Mesh2D& m = plane.value();
    if (options.optimize_passes > 0) optimize_mesh2d(m, options.optimize_passes);
    // Rim shared edge for edge: each rim segment is the edge of exactly one
    // cap triangle, traversed against the wall's half-edge (j + 1 -> j).
    std::vector<uint8_t> rim_used(n, 0);
    for (size_t t = 0; t < m.num_triangles(); ++t)
      for (int k = 0; k < 3; ++k) {
        const int32_t a = m.triangles[3 * t + size_t(k)],
                      b = m.triangles[3 * t + size_t(k + 1) % 3];
        if (size_t(a) >= n || size_t(b) >= n) continue;
        bool bad = false;
        if (size_t(b + 1) % n == size_t(a))
          bad = rim_used[size_t(b)]++ > 0;
        else if (size_t(a + 1) % n == size_t(b))
          bad = true;  // a rim segment traversed like the wall: wrong side
        if (bad)
          return R::Error("caps: the mesher did not produce a valid cap on " +
                          describe(op.origin, n));
      }
    if (std::count(rim_used.begin(), rim_used.end(), 1) != std::ptrdiff_t(n))
      return R::Error("caps: the mesher left a rim edge of " + describe(op.origin, n) +
                      " uncovered");
    // Map back: rim points are the wall's, new points appended.
    std::vector<int32_t> id(m.num_vertices(), -1);
    for (size_t j = 0; j < n; ++j) id[j] = op.loop[j];
    for (size_t t = 0; t < m.num_triangles(); ++t)
      for (int k = 0; k < 3; ++k) {
        const size_t v = size_t(m.triangles[3 * t + size_t(k)]);
        if (id[v] >= 0) continue;
        id[v] = int32_t(out.mesh.num_vertices());
        for (int d = 0; d < 3; ++d)
          out.mesh.points.push_back(op.origin[d] + m.points[2 * v] * op.e1[d] +
                                    m.points[2 * v + 1] * op.e2[d]);
        ++info.interior_vertices;
      }
    info.first_triangle = out.mesh.num_triangles();
    info.triangles = m.num_triangles();
    double area = 0, gsum = 0, gmin = 1;
    Vec3 centroid{0, 0, 0};
    for (size_t t = 0; t < m.num_triangles(); ++t) {
      int32_t v[3];
      for (int k = 0; k < 3; ++k) v[k] = id[size_t(m.triangles[3 * t + size_t(k)])];
      out.mesh.triangles.insert(out.mesh.triangles.end(), {v[0], v[1], v[2]});
      out.triangle_tag.push_back(info.tag);
      const double* p[3] = {&out.mesh.points[3 * size_t(v[0])], &out.mesh.points[3 * size_t(v[1])],
                            &out.mesh.points[3 * size_t(v[2])]};
      const double a = 0.5 * norm(triangle_normal(out.mesh.points, v));
      for (int d = 0; d < 3; ++d) centroid[d] += a * (p[0][d] + p[1][d] + p[2][d]) / 3;
      area += a;
      const double g = triangle_gamma(p[0], p[1], p[2]);
      gsum += g;
      gmin = std::min(gmin, g);
    }
    for (int d = 0; d < 3; ++d) info.centroid[d] = area > 0 ? centroid[d] / area : op.origin[d];
    info.quality_min = m.num_triangles() > 0 ? gmin : 0;
    info.quality_mean = m.num_triangles() > 0 ? gsum / double(m.num_triangles()) : 0;
    for (size_t j = 0; j < n; ++j)
      info.perimeter += norm(
          sub(point(out.mesh.points, op.loop[(j + 1) % n]), point(out.mesh.points, op.loop[j])));
    out.caps.push_back(std::move(info));
  }

  // Phase 6: the caps follow the wall's orientation, so an inward-facing
  // wall gives an inward-facing closed surface.
  if (!(enclosed_volume(out.mesh) > 0))
    return R::Error(
        "caps: the capped surface encloses a negative volume: the wall faces inward (orient it "
        "outward first)");

  // Phase 7: wall triangles at the rims that the projection turned over.
  std::vector<size_t> cap_of_opening(ops.size());
  for (size_t c = 0; c < tag_order.size(); ++c) cap_of_opening[tag_order[c]] = c;
  for (size_t i = 0; i < rim_triangles.size(); ++i) {
    const size_t t = rim_triangles[i];
    if (dot(normal_before[i], triangle_normal(out.mesh.points, &wall.triangles[3 * t])) > 0)
      continue;
    for (int k = 0; k < 3; ++k) {
      const int32_t o = opening_of[size_t(wall.triangles[3 * t + size_t(k)])];
      if (o >= 0) {
        ++out.caps[cap_of_opening[size_t(o)]].flipped_wall_triangles;
        break;
      }
    }
  }
  return out;
}

}  // namespace vm
