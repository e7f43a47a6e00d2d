// Welding a triangle soup: phase 1 merges bit-identical corners through a
// hash table laid out by spatial cell (see weld_exact); phase 2 merges
// distinct points closer than the tolerance with a grid of cells much larger
// than the tolerance (so most points look at one cell), bucketed by a radix
// sort of the cells' hashes, and a union-find keeping the first-seen point
// as the representative.
#include "core/mesh/weld.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>

#include "core/util/index_hash_table.h"
#include "core/util/parallel.h"
#include "core/util/radix_sort.h"

namespace vm {
namespace {

uint32_t float_bits(float f) {
  if (f == 0.0f) f = 0.0f;  // -0 and +0 are the same point
  uint32_t u;
  std::memcpy(&u, &f, 4);
  return u;
}

uint64_t hash3(uint64_t a, uint64_t b, uint64_t c) {
  return (a * 0x9E3779B97F4A7C15ULL) ^ (b * 0xC2B2AE3D27D4EB4FULL) ^ (c * 0x165667B19E3779F9ULL);
}

int32_t find_root(std::vector<int32_t>& parent, int32_t i) {
  while (parent[i] != i) {
    parent[i] = parent[parent[i]];
    i = parent[i];
  }
  return i;
}

// floor() as an integer without a libm call. Values beyond +-2^62 (a model
// placed absurdly far from the origin for its size) are clamped: they then
// share cells, which costs time but stays correct.
int64_t floor_to_int(double x) {
  constexpr double kLimit = 4.6e18;
  x = std::clamp(x, -kLimit, kLimit);
  int64_t i = int64_t(x);
  return i - (double(i) > x);
}

// A cell size holding a few dozen surface points: four times the median
// edge length of a sample of triangles; 0 when it cannot be estimated.
double locality_cell_size(const TriangleSoup& soup) {
  const size_t nt = soup.num_triangles();
  if (nt < 64) return 0.0;
  std::vector<double> lengths;
  const size_t step = std::max<size_t>(1, nt / 2048);
  for (size_t t = 0; t < nt; t += step) {
    const float* p = &soup.coords[9 * t];
    double d = 0;
    for (int k = 0; k < 3; ++k) d += double(p[3 + k] - p[k]) * double(p[3 + k] - p[k]);
    lengths.push_back(std::sqrt(d));
  }
  std::nth_element(lengths.begin(), lengths.begin() + lengths.size() / 2, lengths.end());
  double median = lengths[lengths.size() / 2];
  return std::isfinite(median) && median > 0 ? 4 * median : 0.0;
}

// Merges bit-identical corners. Table slots hold only the id of a unique
// point (keys are compared in `keys`), so the table is 4 bytes a slot. With
// cell > 0 a point's probe starts in a block of 64 slots chosen by its
// spatial cell, so that corners close in the file (which are close in space)
// probe nearby memory instead of missing the cache on every new point.
// Returns false (and must be re-run with cell = 0) if probes grow long, which
// happens only when the cell estimate is far off (very uneven sampling).
bool weld_exact(const float* c, size_t corners, double cell, std::vector<int32_t>& corner_to_unique,
                std::vector<int32_t>& unique_corner) {
  constexpr size_t kBlock = 64;
  constexpr size_t kMaxProbe = 1024;
  unique_corner.clear();
  unique_corner.reserve(corners / 5 + 16);
  std::vector<uint32_t> keys;  // 3 per unique point: float bits of x, y, z
  keys.reserve(3 * (corners / 5 + 16));
  size_t cap = std::bit_ceil(corners / 2 + 2 * kBlock);
  std::vector<int32_t> table(cap, -1);
  const double inv_cell = cell > 0 ? 1.0 / cell : 0.0;
  auto start_slot = [&](const float* p, uint32_t x, uint32_t y, uint32_t z) {
    uint64_t fine = IndexHashTable::mix(hash3(x, y, z));
    if (cell <= 0) return size_t(fine >> 16) & (cap - 1);
    uint64_t block = IndexHashTable::mix(hash3(uint64_t(floor_to_int(p[0] * inv_cell)),
                                               uint64_t(floor_to_int(p[1] * inv_cell)),
                                               uint64_t(floor_to_int(p[2] * inv_cell))));
    return size_t(block * kBlock + (fine & (kBlock - 1))) & (cap - 1);
  };
  bool long_probe = false;
  auto probe = [&](size_t j, uint32_t x, uint32_t y, uint32_t z) {
    size_t steps = 0;
    while (table[j] >= 0) {
      const uint32_t* k = &keys[3 * size_t(table[j])];
      if (k[0] == x && k[1] == y && k[2] == z) break;
      j = (j + 1) & (cap - 1);
      if (++steps > kMaxProbe) long_probe = true;
    }
    return j;
  };
  // Recently seen corners first: each vertex recurs in about six triangles
  // that are usually close in the file.
  struct Recent {
    uint32_t x, y, z;
    int32_t id;  // -1: empty
  };
  constexpr size_t kRecent = 1 << 12;
  std::vector<Recent> recent(kRecent, Recent{0, 0, 0, -1});
  for (size_t i = 0; i < corners; ++i) {
    const float* p = c + 3 * i;
    uint32_t x = float_bits(p[0]), y = float_bits(p[1]), z = float_bits(p[2]);
    Recent& r = recent[(x * 0x9E3779B1u ^ y * 0x85EBCA77u ^ z * 0xC2B2AE3Du) >> 20];
    if (r.id >= 0 && r.x == x && r.y == y && r.z == z) {
      corner_to_unique[i] = r.id;
      continue;
    }
    size_t j = probe(start_slot(p, x, y, z), x, y, z);
    if (long_probe && cell > 0) return false;
    if (table[j] < 0) {
      table[j] = int32_t(unique_corner.size());
      unique_corner.push_back(int32_t(i));
      keys.insert(keys.end(), {x, y, z});
      if (2 * unique_corner.size() > cap) {  // keep the load factor <= 1/2
        cap *= 2;
        table.assign(cap, -1);
        for (size_t u = 0; u < unique_corner.size(); ++u) {
          const uint32_t* k = &keys[3 * u];
          const float* q = c + 3 * size_t(unique_corner[u]);
          table[probe(start_slot(q, k[0], k[1], k[2]), k[0], k[1], k[2])] = int32_t(u);
        }
        j = probe(start_slot(p, x, y, z), x, y, z);
      }
    }
    corner_to_unique[i] = table[j];
    r = Recent{x, y, z, table[j]};
  }
  return true;
}

// Phase 2: returns for each unique point the index of its representative
// (the smallest index among the points merged with it, transitively).
// `pts`: n points, 3 doubles each. Points are bucketed in cells of side
// `cell` (>= 2 tol, so a point's tol-neighbourhood spans at most 2 cells an
// axis) by sorting keys (cell hash above, point index below): the points
// of a cell are then contiguous, found by binary search, with no scattered
// hash-table access per point. Hash collisions only put two cells in one
// run; every pair is still tested by its cells.
// Cells hold about one point each; should one hold more than kMaxRun
// (points packed far closer than the median edge), the cells shrink to
// `fallback_cell`, so that no run's pairs grow quadratic past what that
// size allows.
std::vector<int32_t> merge_close_points(const std::vector<double>& pts, double tol, double cell,
                                        double fallback_cell, size_t* merged) {
  constexpr size_t kMaxRun = 256;
  const size_t n = pts.size() / 3;
  std::vector<int32_t> parent(n);
  for (size_t i = 0; i < n; ++i) parent[i] = int32_t(i);
  *merged = 0;
  if (!(tol > 0) || n == 0) return parent;
  double inv_cell = 0;
  auto cell_of = [&](double x) { return floor_to_int(x * inv_cell); };
  // Key bits, high to low: the cell's hash, whether the point lies within
  // tol of its cell's faces, the point's index. The loop below reads the
  // coordinates of a point only when it shares its run or lies near a face
  // (a few in a hundred): the sorted order is random in memory.
  const int index_bits = std::max(1, int(std::bit_width(n)));
  const uint64_t index_mask = (uint64_t(1) << index_bits) - 1;
  const uint64_t near_face = uint64_t(1) << index_bits;
  const uint64_t low_mask = (near_face << 1) - 1;
  auto cell_key = [&](int64_t x, int64_t y, int64_t z) {
    return IndexHashTable::mix(hash3(uint64_t(x), uint64_t(y), uint64_t(z))) & ~low_mask;
  };
  // The cells within tol of p along each axis (at most 2 per axis).
  auto reach = [&](const double* p, int64_t lo[3], int64_t hi[3]) {
    for (int k = 0; k < 3; ++k) {
      lo[k] = cell_of(p[k] - tol);
      hi[k] = cell_of(p[k] + tol);
    }
    return lo[0] != hi[0] || lo[1] != hi[1] || lo[2] != hi[2];
  };
  std::vector<uint64_t> sorted(n);
  auto bucket = [&](double side) {
    inv_cell = 1.0 / std::max(side, 2 * tol);
    parallel_for(n, 1 << 16, [&](size_t begin, size_t end) {
      for (size_t i = begin; i < end; ++i) {
        const double* p = &pts[3 * i];
        int64_t lo[3], hi[3];
        sorted[i] = cell_key(cell_of(p[0]), cell_of(p[1]), cell_of(p[2])) |
                    (reach(p, lo, hi) ? near_face : 0) | i;
      }
    });
    // Sorted by cell hash only: a run keeps its points in index order.
    radix_sort(sorted, index_bits + 1);
    size_t longest = 0;
    for (size_t a = 0, b = 0; a < n; a = b) {
      while (b < n && (sorted[b] & ~low_mask) == (sorted[a] & ~low_mask)) ++b;
      longest = std::max(longest, b - a);
    }
    return longest;
  };
  if (bucket(cell) > kMaxRun && fallback_cell < cell) bucket(fallback_cell);
  auto in_cell = [&](size_t a, int64_t x, int64_t y, int64_t z) {
    return cell_of(pts[3 * a]) == x && cell_of(pts[3 * a + 1]) == y && cell_of(pts[3 * a + 2]) == z;
  };
  const double tol2 = tol * tol;
  auto unite_if_close = [&](size_t i, size_t j) {
    const double* p = &pts[3 * i];
    const double* q = &pts[3 * j];
    const double d2 = (p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
                      (p[2] - q[2]) * (p[2] - q[2]);
    if (d2 > tol2) return;
    const int32_t ri = find_root(parent, int32_t(i));
    const int32_t rj = find_root(parent, int32_t(j));
    if (ri == rj) return;
    parent[size_t(std::max(ri, rj))] = std::min(ri, rj);
    ++*merged;
  };
  for (size_t a = 0; a < n;) {
    const uint64_t run_key = sorted[a] & ~low_mask;
    size_t end = a + 1;
    while (end < n && (sorted[end] & ~low_mask) == run_key) ++end;
    for (size_t b = a; b < end; ++b) {
      const bool shared = end - a > 1, near = (sorted[b] & near_face) != 0;
      if (!shared && !near) continue;  // alone in its cell, far from its faces
      const size_t i = size_t(sorted[b] & index_mask);
      const double* p = &pts[3 * i];
      const int64_t own[3] = {cell_of(p[0]), cell_of(p[1]), cell_of(p[2])};
      // The later points of its own run (each pair once).
      for (size_t c = b + 1; c < end; ++c) {
        const size_t j = size_t(sorted[c] & index_mask);
        if (in_cell(j, own[0], own[1], own[2])) unite_if_close(i, j);
      }
      if (!near) continue;
      int64_t lo[3], hi[3];
      reach(p, lo, hi);
      for (int64_t x = lo[0]; x <= hi[0]; ++x)
        for (int64_t y = lo[1]; y <= hi[1]; ++y)
          for (int64_t z = lo[2]; z <= hi[2]; ++z) {
            if (x == own[0] && y == own[1] && z == own[2]) continue;
            // The points j > i of that cell (j sees i likewise).
            const uint64_t key = cell_key(x, y, z);
            for (auto it = std::lower_bound(sorted.begin(), sorted.end(), key);
                 it != sorted.end() && (*it & ~low_mask) == key; ++it) {
              const size_t j = size_t(*it & index_mask);
              if (j > i && in_cell(j, x, y, z)) unite_if_close(i, j);
            }
          }
    }
    a = end;
  }
  for (size_t i = 0; i < n; ++i) parent[i] = find_root(parent, int32_t(i));
  return parent;
}

// Phases 2 and 3, shared by both weld() overloads: merges the distinct
// points `pts` closer than the tolerance and builds the mesh whose corner i
// is unique point corner_to_unique[i].
SurfaceMesh merge_and_index(std::vector<double> pts, std::vector<int32_t> corner_to_unique,
                            const WeldOptions& options, WeldStats* stats) {
  const size_t corners = corner_to_unique.size();
  double tol = options.relative_tolerance * bounding_box(pts).diagonal();
  // No far point may inflate the tolerance past the mesh's own scale: at
  // most a small fraction of the median edge (of at most about 3M edges,
  // every k-th triangle's, on larger meshes).
  double median_edge = 0;
  {
    std::vector<double> edges2;  // squared lengths; freed here
    const size_t triangles = corners / 3;
    const size_t step = std::max<size_t>(1, triangles / 1'000'000);
    edges2.reserve(3 * (triangles / step + 1));
    for (size_t c = 0; c + 2 < corners; c += 3 * step)
      for (size_t k = 0; k < 3; ++k) {
        const double* a = &pts[3 * size_t(corner_to_unique[c + k])];
        const double* b = &pts[3 * size_t(corner_to_unique[c + (k + 1) % 3])];
        const double d2 = (a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                          (a[2] - b[2]) * (a[2] - b[2]);
        if (d2 > 0) edges2.push_back(d2);
      }
    if (!edges2.empty()) {
      std::nth_element(edges2.begin(), edges2.begin() + long(edges2.size() / 2), edges2.end());
      median_edge = std::sqrt(edges2[edges2.size() / 2]);
      tol = std::min(tol, options.edge_fraction * median_edge);
    }
  }
  size_t merged = 0;
  // Cells of a tenth of an edge hold about one point each, and few points lie
  // within tol of their faces.
  std::vector<int32_t> rep =
      merge_close_points(pts, tol, std::max(64 * tol, 0.1 * median_edge), 64 * tol, &merged);

  SurfaceMesh mesh;
  if (stats) {
    stats->corners = corners;
    stats->exact_unique = rep.size();
    stats->merged_by_tolerance = merged;
  }
  if (merged == 0) {  // the usual case: the distinct points are the vertices
    mesh.points = std::move(pts);
    mesh.triangles = std::move(corner_to_unique);
    return mesh;
  }
  std::vector<int32_t> new_index(rep.size(), -1);
  int32_t next_vertex = 0;
  for (size_t u = 0; u < rep.size(); ++u) {
    if (rep[u] == int32_t(u)) new_index[u] = next_vertex++;
  }
  for (size_t u = 0; u < rep.size(); ++u) new_index[u] = new_index[rep[u]];
  mesh.points.resize(3 * size_t(next_vertex));
  for (size_t u = 0; u < rep.size(); ++u) {
    if (rep[u] != int32_t(u)) continue;
    for (int k = 0; k < 3; ++k) mesh.points[3 * new_index[u] + k] = pts[3 * u + k];
  }
  mesh.triangles.resize(corners);
  for (size_t i = 0; i < corners; ++i) mesh.triangles[i] = new_index[corner_to_unique[i]];
  return mesh;
}

// Phase 1 of the soup weld: the distinct points (3 doubles each) and each
// corner's index among them.
std::vector<double> distinct_corners(const TriangleSoup& soup,
                                     std::vector<int32_t>& corner_to_unique) {
  const size_t corners = soup.coords.size() / 3;
  const float* c = soup.coords.data();
  corner_to_unique.resize(corners);
  std::vector<int32_t> unique_corner;  // first corner of each unique point
  if (!weld_exact(c, corners, locality_cell_size(soup), corner_to_unique, unique_corner))
    weld_exact(c, corners, 0.0, corner_to_unique, unique_corner);
  std::vector<double> pts(3 * unique_corner.size());
  for (size_t u = 0; u < unique_corner.size(); ++u)
    for (int k = 0; k < 3; ++k) pts[3 * u + k] = c[3 * size_t(unique_corner[u]) + k];
  return pts;
}

}  // namespace

SurfaceMesh weld(const TriangleSoup& soup, const WeldOptions& options, WeldStats* stats) {
  if (soup.coords.empty() && !soup.triangles.empty())  // an ASCII STL: indexed doubles
    return weld(soup.points, soup.triangles, options, stats);
  std::vector<int32_t> corner_to_unique;
  std::vector<double> pts = distinct_corners(soup, corner_to_unique);
  return merge_and_index(std::move(pts), std::move(corner_to_unique), options, stats);
}

SurfaceMesh weld(TriangleSoup&& soup, const WeldOptions& options, WeldStats* stats) {
  if (soup.coords.empty() && !soup.triangles.empty()) {
    SurfaceMesh mesh = weld(soup.points, soup.triangles, options, stats);
    soup.points = {};
    soup.triangles = {};
    return mesh;
  }
  std::vector<int32_t> corner_to_unique;
  std::vector<double> pts = distinct_corners(soup, corner_to_unique);
  soup.coords = {};
  return merge_and_index(std::move(pts), std::move(corner_to_unique), options, stats);
}

SurfaceMesh weld(const std::vector<double>& points, const std::vector<int32_t>& triangles,
                 const WeldOptions& options, WeldStats* stats) {
  const size_t corners = triangles.size();
  // Points in order of first use by a corner (unused points are dropped).
  std::vector<int32_t> first_use(points.size() / 3, -1);
  std::vector<int32_t> used;
  for (size_t i = 0; i < corners; ++i) {
    int32_t p = triangles[i];
    if (first_use[p] < 0) {
      first_use[p] = int32_t(used.size());
      used.push_back(p);
    }
  }
  // Phase 1: exact duplicates among the used points (-0 equals +0).
  auto bits = [](double x) {
    if (x == 0.0) x = 0.0;
    uint64_t u;
    std::memcpy(&u, &x, 8);
    return u;
  };
  IndexHashTable table(used.size());
  std::vector<double> pts;
  pts.reserve(3 * used.size());
  std::vector<int32_t> used_to_unique(used.size());
  for (size_t u = 0; u < used.size(); ++u) {
    const double* p = &points[3 * size_t(used[u])];
    int32_t candidate = int32_t(pts.size() / 3);
    int32_t found =
        table.find_or_insert(hash3(bits(p[0]), bits(p[1]), bits(p[2])), candidate, [&](int32_t s) {
          const double* q = &pts[3 * size_t(s)];
          return q[0] == p[0] && q[1] == p[1] && q[2] == p[2];
        });
    if (found == candidate) pts.insert(pts.end(), p, p + 3);
    used_to_unique[u] = found;
  }
  std::vector<int32_t> corner_to_unique(corners);
  for (size_t i = 0; i < corners; ++i)
    corner_to_unique[i] = used_to_unique[size_t(first_use[triangles[i]])];
  return merge_and_index(std::move(pts), std::move(corner_to_unique), options, stats);
}

}  // namespace vm
