// Welding a triangle soup: phase 1 merges bit-identical corners through a
// hash table; phase 2 merges distinct points closer than the tolerance with
// a hashed grid of cells much larger than the tolerance (so most points look
// at one cell) and a union-find, keeping the first-seen point as the
// representative.
#include "core/mesh/weld.h"

#include <cmath>
#include <cstring>

#include "core/util/index_hash_table.h"

namespace vm {
namespace {

uint32_t float_bits(float f) {
  if (f == 0.0f) f = 0.0f;  // -0 and +0 are the same point
  uint32_t u;
  std::memcpy(&u, &f, 4);
  return u;
}

uint64_t hash3(uint64_t a, uint64_t b, uint64_t c) {
  return (a * 0x9E3779B97F4A7C15ULL) ^ (b * 0xC2B2AE3D27D4EB4FULL) ^
         (c * 0x165667B19E3779F9ULL);
}

int32_t find_root(std::vector<int32_t>& parent, int32_t i) {
  while (parent[i] != i) {
    parent[i] = parent[parent[i]];
    i = parent[i];
  }
  return i;
}

// Phase 2: returns for each unique point the index of its representative
// (the smallest index among the points merged with it, transitively).
std::vector<int32_t> merge_close_points(const std::vector<double>& pts,
                                        double tol, size_t* merged) {
  size_t n = pts.size() / 3;
  std::vector<int32_t> parent(n);
  for (size_t i = 0; i < n; ++i) parent[i] = int32_t(i);
  *merged = 0;
  if (tol <= 0 || n == 0) return parent;
  const double cell = 64 * tol;
  auto cell_of = [&](double x) { return int64_t(std::floor(x / cell)); };
  // Cell -> linked list of points in it.
  IndexHashTable cells(n);
  std::vector<int32_t> next(n, -1);
  std::vector<int64_t> key(3 * n);
  for (size_t i = 0; i < n; ++i) {
    for (int k = 0; k < 3; ++k) key[3 * i + k] = cell_of(pts[3 * i + k]);
  }
  auto same_cell = [&](size_t a, size_t b) {
    return key[3 * a] == key[3 * b] && key[3 * a + 1] == key[3 * b + 1] &&
           key[3 * a + 2] == key[3 * b + 2];
  };
  auto cell_hash = [&](int64_t x, int64_t y, int64_t z) {
    return hash3(uint64_t(x), uint64_t(y), uint64_t(z));
  };
  for (size_t i = 0; i < n; ++i) {
    int32_t h = cells.find_or_insert(
        cell_hash(key[3 * i], key[3 * i + 1], key[3 * i + 2]), int32_t(i),
        [&](int32_t s) { return same_cell(size_t(s), i); });
    if (h != int32_t(i)) {
      next[i] = next[h];
      next[h] = int32_t(i);
    }
  }
  const double tol2 = tol * tol;
  for (size_t i = 0; i < n; ++i) {
    const double* p = &pts[3 * i];
    // Cells within tol of p along each axis: at most 2 per axis.
    int64_t lo[3], hi[3];
    for (int k = 0; k < 3; ++k) {
      lo[k] = cell_of(p[k] - tol);
      hi[k] = cell_of(p[k] + tol);
    }
    for (int64_t x = lo[0]; x <= hi[0]; ++x)
      for (int64_t y = lo[1]; y <= hi[1]; ++y)
        for (int64_t z = lo[2]; z <= hi[2]; ++z) {
          uint64_t h = cell_hash(x, y, z);
          cells.for_each_with_hash(h, [&](int32_t s) {
            if (key[3 * s] != x || key[3 * s + 1] != y || key[3 * s + 2] != z)
              return;
            for (int32_t j = s; j >= 0; j = next[j]) {
              if (size_t(j) <= i) continue;  // each pair once
              const double* q = &pts[3 * j];
              double d2 = (p[0] - q[0]) * (p[0] - q[0]) +
                          (p[1] - q[1]) * (p[1] - q[1]) +
                          (p[2] - q[2]) * (p[2] - q[2]);
              if (d2 <= tol2) {
                int32_t ri = find_root(parent, int32_t(i));
                int32_t rj = find_root(parent, j);
                if (ri != rj) {
                  if (ri < rj) parent[rj] = ri; else parent[ri] = rj;
                  ++*merged;
                }
              }
            }
          });
        }
  }
  for (size_t i = 0; i < n; ++i) parent[i] = find_root(parent, int32_t(i));
  return parent;
}

}  // namespace

SurfaceMesh weld(const TriangleSoup& soup, const WeldOptions& options,
                 WeldStats* stats) {
  const size_t corners = soup.coords.size() / 3;
  const float* c = soup.coords.data();
  // Phase 1: exact duplicates.
  IndexHashTable table(corners / 4 + 16);
  std::vector<int32_t> corner_to_unique(corners);
  std::vector<int32_t> unique_corner;  // first corner of each unique point
  unique_corner.reserve(corners / 5 + 16);
  for (size_t i = 0; i < corners; ++i) {
    const float* p = c + 3 * i;
    uint64_t h = hash3(float_bits(p[0]), float_bits(p[1]), float_bits(p[2]));
    int32_t candidate = int32_t(unique_corner.size());
    int32_t found = table.find_or_insert(h, candidate, [&](int32_t u) {
      const float* q = c + 3 * size_t(unique_corner[u]);
      return float_bits(q[0]) == float_bits(p[0]) &&
             float_bits(q[1]) == float_bits(p[1]) &&
             float_bits(q[2]) == float_bits(p[2]);
    });
    if (found == candidate) unique_corner.push_back(int32_t(i));
    corner_to_unique[i] = found;
  }
  std::vector<double> pts(3 * unique_corner.size());
  for (size_t u = 0; u < unique_corner.size(); ++u)
    for (int k = 0; k < 3; ++k)
      pts[3 * u + k] = c[3 * size_t(unique_corner[u]) + k];

  // Phase 2: near duplicates.
  double tol = options.relative_tolerance * bounding_box(pts).diagonal();
  size_t merged = 0;
  std::vector<int32_t> rep = merge_close_points(pts, tol, &merged);

  SurfaceMesh mesh;
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
  for (size_t i = 0; i < corners; ++i)
    mesh.triangles[i] = new_index[corner_to_unique[i]];
  if (stats) {
    stats->corners = corners;
    stats->exact_unique = rep.size();
    stats->merged_by_tolerance = merged;
  }
  return mesh;
}

}  // namespace vm
