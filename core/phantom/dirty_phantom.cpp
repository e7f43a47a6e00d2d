// Segmentation defects on a clean phantom: holes, touching holes, a fin,
// duplicates, a flipped patch, a zero-area band (see dirty_phantom.h).
#include "core/phantom/dirty_phantom.h"

#include <algorithm>
#include <set>
#include <utility>
#include <vector>

#include "core/geom/vec3.h"
#include "core/mesh/adjacency.h"
#include "core/mesh/boundary_loops.h"
#include "core/mesh/repair.h"

namespace vm {
namespace {

uint64_t mix(uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

}  // namespace

DirtTruth add_segmentation_defects(SurfaceMesh& mesh, uint32_t seed, int holes) {
  DirtTruth truth;
  holes = std::clamp(holes, 5, 50);
  const TriangleAdjacency adj = build_adjacency(mesh);
  auto& tri = mesh.triangles;
  const size_t nv = mesh.num_vertices(), nt = mesh.num_triangles();
  if (nt == 0) return truth;
  // Median edge length, and the vertices on openings.
  std::vector<double> lengths;
  std::vector<Vec3> rim;
  for (size_t h = 0; h < 3 * nt; ++h) {
    const Vec3 a = at(mesh.points, half_edge_from(mesh, int32_t(h)));
    const Vec3 b = at(mesh.points, half_edge_to(mesh, int32_t(h)));
    lengths.push_back(norm(b - a));
    if (adj.opposite[h] == TriangleAdjacency::kBoundary) rim.push_back(a);
  }
  std::nth_element(lengths.begin(), lengths.begin() + long(lengths.size() / 2), lengths.end());
  const double h = lengths[lengths.size() / 2];
  auto star = [&](int32_t v) {
    return std::vector<int32_t>(adj.star.begin() + adj.star_offsets[size_t(v)],
                                adj.star.begin() + adj.star_offsets[size_t(v) + 1]);
  };
  auto link = [&](int32_t v) {
    std::set<int32_t> out;
    for (int32_t t : star(v))
      for (int k = 0; k < 3; ++k)
        if (tri[3 * size_t(t) + size_t(k)] != v) out.insert(tri[3 * size_t(t) + size_t(k)]);
    return out;
  };
  // A site: an interior vertex of valence >= 4 whose 1-ring is a disk with
  // no chord (exactly as many edges among its link as link vertices), far
  // from the openings and from the other sites.
  std::vector<int32_t> order(nv);
  for (size_t v = 0; v < nv; ++v) order[v] = int32_t(v);
  std::sort(order.begin(), order.end(), [&](int32_t a, int32_t b) {
    return mix(uint64_t(seed) << 32 ^ uint64_t(a)) < mix(uint64_t(seed) << 32 ^ uint64_t(b));
  });
  std::vector<int32_t> sites;
  const size_t wanted = size_t(holes) + 5;
  for (int32_t v : order) {
    if (sites.size() == wanted) break;
    const Vec3 p = at(mesh.points, v);
    const std::vector<int32_t> s = star(v);
    const std::set<int32_t> l = link(v);
    if (s.size() < 4 || l.size() != s.size()) continue;
    bool ok = true;
    for (const Vec3& q : rim) ok = ok && norm(q - p) > 5 * h;
    for (int32_t w : sites) ok = ok && norm(at(mesh.points, w) - p) > 6 * h;
    if (!ok) continue;
    std::set<std::pair<int32_t, int32_t>> edges;
    for (int32_t a : l)
      for (int32_t t : star(a))
        for (int k = 0; k < 3; ++k) {
          const int32_t x = tri[3 * size_t(t) + size_t(k)],
                        y = tri[3 * size_t(t) + size_t(k + 1) % 3];
          if (l.count(x) && l.count(y)) edges.insert({std::min(x, y), std::max(x, y)});
        }
    if (edges.size() != l.size()) continue;
    sites.push_back(v);
  }
  if (sites.size() < 10) return truth;  // too small a mesh for defects
  const size_t hole_sites = sites.size() - 5;
  std::vector<uint8_t> remove(nt, 0);
  // Holes: the 1-ring of each hole site.
  for (size_t i = 0; i < hole_sites; ++i)
    for (int32_t t : star(sites[i])) remove[size_t(t)] = 1;
  truth.holes = int(hole_sites);
  // Two holes touching at one vertex: two triangles of its star that share
  // only that vertex.
  {
    const int32_t v = sites[hole_sites];
    const std::vector<int32_t> s = star(v);
    auto shares_edge = [&](int32_t a, int32_t b) {
      int common = 0;
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
          common += tri[3 * size_t(a) + size_t(i)] == tri[3 * size_t(b) + size_t(j)];
      return common >= 2;
    };
    for (size_t j = 1; j < s.size(); ++j)
      if (!shares_edge(s[0], s[j])) {
        remove[size_t(s[0])] = remove[size_t(s[j])] = 1;
        truth.holes += 2;
        truth.bowtie_vertices = 1;
        break;
      }
  }
  // A fin on the first edge of a triangle at the fin site, standing out.
  {
    const int32_t t = star(sites[hole_sites + 1])[0];
    const int32_t a = tri[3 * size_t(t)], b = tri[3 * size_t(t) + 1], c = tri[3 * size_t(t) + 2];
    const Vec3 pa = at(mesh.points, a), pb = at(mesh.points, b), pc = at(mesh.points, c);
    const Vec3 n = normalized(cross(pb - pa, pc - pa));
    const Vec3 p = 0.5 * (pa + pb) + (0.5 * norm(pb - pa)) * n;
    const int32_t q = int32_t(mesh.num_vertices());
    mesh.points.insert(mesh.points.end(), p.begin(), p.end());
    tri.insert(tri.end(), {b, a, q});
    truth.fins = 1;
  }
  // A flipped patch: the 2-ring of the flip site.
  {
    std::set<int32_t> patch;
    const int32_t v = sites[hole_sites + 2];
    for (int32_t w : link(v))
      for (int32_t t : star(w)) patch.insert(t);
    for (int32_t t : patch) std::swap(tri[3 * size_t(t) + 1], tri[3 * size_t(t) + 2]);
    truth.flipped = int(patch.size());
  }
  // Duplicates: the star of the duplicate site, every other one reversed.
  {
    const std::vector<int32_t> s = star(sites[hole_sites + 3]);
    for (size_t i = 0; i < s.size() && i < 6; ++i) {
      const int32_t t = s[i];
      std::array<int32_t, 3> d{tri[3 * size_t(t)], tri[3 * size_t(t) + 1], tri[3 * size_t(t) + 2]};
      if (i % 2) std::swap(d[1], d[2]);
      tri.insert(tri.end(), d.begin(), d.end());
      ++truth.duplicates;
    }
  }
  // A zero-area band around the band site: its 1-ring takes coincident
  // copies of the rim vertices, joined to the rim by zero-area triangles.
  {
    const int32_t v = sites[hole_sites + 4];
    std::vector<std::pair<int32_t, int32_t>> copies;  // rim vertex -> copy
    auto copy_of = [&](int32_t a) {
      for (auto [x, y] : copies)
        if (x == a) return y;
      const int32_t y = int32_t(mesh.num_vertices());
      const Vec3 p = at(mesh.points, a);
      mesh.points.insert(mesh.points.end(), p.begin(), p.end());
      copies.emplace_back(a, y);
      return y;
    };
    for (int32_t t : star(v)) {
      int k = 0;
      while (tri[3 * size_t(t) + size_t(k)] != v) ++k;
      const int32_t a = tri[3 * size_t(t) + size_t(k + 1) % 3],
                    b = tri[3 * size_t(t) + size_t(k + 2) % 3];
      const int32_t a2 = copy_of(a), b2 = copy_of(b);
      tri[3 * size_t(t) + size_t(k + 1) % 3] = a2;
      tri[3 * size_t(t) + size_t(k + 2) % 3] = b2;
      tri.insert(tri.end(), {a, b, b2, a, b2, a2});
      truth.band_triangles += 2;
    }
  }
  remove.resize(mesh.num_triangles(), 0);
  remove_triangles(mesh, remove);
  return truth;
}

std::vector<DamagedEnd> add_damaged_ends(SurfaceMesh& mesh, uint32_t seed) {
  std::vector<DamagedEnd> out;
  const TriangleAdjacency adj = build_adjacency(mesh);
  const std::vector<std::vector<int32_t>> loops = boundary_loops(mesh, adj);
  auto& tri = mesh.triangles;
  // Per vertex, a triangle using it (for the rim triangles' third corners).
  std::vector<int32_t> some_triangle(mesh.num_vertices(), -1);
  for (size_t t = 0; t < mesh.num_triangles(); ++t)
    for (int k = 0; k < 3; ++k) some_triangle[size_t(tri[3 * t + size_t(k)])] = int32_t(t);
  std::vector<uint8_t> on_rim(mesh.num_vertices(), 0);
  for (const auto& loop : loops)
    for (int32_t v : loop) on_rim[size_t(v)] = 1;
  std::vector<uint8_t> remove(mesh.num_triangles(), 0);
  for (const std::vector<int32_t>& loop : loops) {
    const size_t n = loop.size();
    if (n < 16) continue;
    DamagedEnd d;
    Vec3 c{0, 0, 0}, normal{0, 0, 0};
    double h = 0;
    for (size_t i = 0; i < n; ++i) {
      const Vec3 a = at(mesh.points, loop[i]), b = at(mesh.points, loop[(i + 1) % n]);
      c = c + (1.0 / double(n)) * a;
      normal = normal + cross(a, b);  // Newell: twice the loop's vector area
      h += norm(b - a) / double(n);
    }
    d.radius = std::sqrt(0.5 * norm(normal) / 3.141592653589793);
    Vec3 axis = normalized(normal);
    // Out of the vessel: away from the rim triangles' third corners.
    const int32_t t0 = some_triangle[size_t(loop[0])];
    Vec3 inner{0, 0, 0};
    for (int k = 0; k < 3; ++k)
      inner = inner + (1.0 / 3) * at(mesh.points, tri[3 * size_t(t0) + size_t(k)]);
    if (dot(inner - c, axis) > 0) axis = -1.0 * axis;
    d.center = c;
    d.axis = axis;
    const size_t shift = size_t(mix(seed + n) % n);
    auto L = [&](size_t i) { return loop[(i + shift) % n]; };
    // The fold: four rim vertices pushed a third of the radius in along
    // the vessel, so that their triangles turn over onto the next rings.
    auto radial_at = [&](const Vec3& x) {
      const Vec3 r = x - c;
      return normalized(r - dot(r, axis) * axis);
    };
    for (size_t i = 1; i <= 4; ++i) {
      const int32_t v = L(i);
      const Vec3 x = at(mesh.points, v);
      put(mesh.points, v, x - (0.3 * d.radius) * axis + (0.05 * d.radius) * radial_at(x));
    }
    // A flap on a rim edge: two triangles, out of the wall and back in
    // through it a third of a radius in.
    {
      const int32_t a = L(n / 4), b = L(n / 4 + 1);
      const Vec3 mid = 0.5 * (at(mesh.points, a) + at(mesh.points, b));
      const Vec3 radial = radial_at(mid);
      const Vec3 p = mid - (0.1 * d.radius) * axis + (0.1 * d.radius) * radial;
      const Vec3 q = mid - (0.3 * d.radius) * axis - (0.1 * d.radius) * radial;
      const int32_t ip = int32_t(mesh.num_vertices()), iq = ip + 1;
      mesh.points.insert(mesh.points.end(), p.begin(), p.end());
      mesh.points.insert(mesh.points.end(), q.begin(), q.end());
      tri.insert(tri.end(), {b, a, ip, a, iq, ip});
    }
    // A tiny loop: a triangle one ring in, next to the rim, removed.
    for (size_t t = 0; t < remove.size(); ++t) {
      const int32_t* v = &tri[3 * t];
      bool touches = false, rim = false;
      for (int k = 0; k < 3; ++k) {
        rim |= on_rim[size_t(v[k])] != 0;
        touches |= norm(at(mesh.points, v[k]) - at(mesh.points, L(n / 2))) < 2.5 * h;
      }
      if (touches && !rim) {
        remove[t] = 1;
        break;
      }
    }
    // A twisted band between rim edges (k, k+1) and (k+4, k+5): it runs
    // along the first against its rim triangle, along the second with it.
    {
      const size_t k = 3 * n / 4;
      tri.insert(tri.end(), {L(k + 1), L(k), L(k + 4), L(k + 1), L(k + 4), L(k + 5)});
    }
    d.depth = 0.3 * d.radius + 2 * h;
    out.push_back(d);
  }
  remove.resize(mesh.num_triangles(), 0);
  remove_triangles(mesh, remove);
  return out;
}

}  // namespace vm
