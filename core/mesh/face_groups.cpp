// Faces grouped by vertex set (face_groups.h), in phases: bucket sizes by
// each face's smallest vertex; every face's index scattered into its bucket
// in input order (a stable counting sort); each bucket's faces read as
// 16-byte records of their other vertices and index, sorted, and written
// back, equal runs as groups. Only 4 bytes a face besides the input.
#include "core/mesh/face_groups.h"

#include <algorithm>

namespace vm {
namespace {

/// A face in its smallest vertex's bucket: hi = its 2nd and 3rd smallest
/// vertices, lo = its 4th plus 1 (0 for a triangle) and its index. Ordering
/// by (hi, lo) orders by sorted vertex list, then by index.
struct BucketFace {
  uint64_t hi, lo;
};

bool operator<(const BucketFace& a, const BucketFace& b) {
  return a.hi != b.hi ? a.hi < b.hi : a.lo < b.lo;
}

/// Whether a and b have the same vertices (their indices aside).
bool same_vertices(const BucketFace& a, const BucketFace& b) {
  return a.hi == b.hi && (a.lo >> 32) == (b.lo >> 32);
}

/// The smallest vertex of face f (4 slots, a triangle's 4th kNoFourthVertex).
size_t smallest(const int32_t* f) {
  // As unsigned values kNoFourthVertex is the largest.
  return std::min(std::min(uint32_t(f[0]), uint32_t(f[1])),
                  std::min(uint32_t(f[2]), uint32_t(f[3])));
}

void order2(uint32_t& a, uint32_t& b) {
  const uint32_t lo = std::min(a, b), hi = std::max(a, b);
  a = lo;
  b = hi;
}

/// Face i of `faces` in its smallest vertex's bucket.
BucketFace bucket_face(const int32_t* faces, uint32_t i) {
  // As unsigned values kNoFourthVertex is the largest: it stays last.
  uint32_t v[4];
  for (int k = 0; k < 4; ++k) v[k] = uint32_t(faces[4 * size_t(i) + size_t(k)]);
  order2(v[0], v[1]);  // a sorting network for four
  order2(v[2], v[3]);
  order2(v[0], v[2]);
  order2(v[1], v[3]);
  order2(v[1], v[2]);
  return {uint64_t(v[1]) << 32 | v[2], uint64_t(v[3] + 1) << 32 | i};
}

/// Buckets of at most this many faces are sorted by insertion.
constexpr ptrdiff_t kInsertionSortMax = 24;

void sort_bucket(BucketFace* begin, BucketFace* end) {
  if (end - begin > kInsertionSortMax) {
    std::sort(begin, end);
    return;
  }
  for (BucketFace* i = begin + 1; i < end; ++i) {
    const BucketFace x = *i;
    BucketFace* j = i;
    for (; j > begin && x < j[-1]; --j) *j = j[-1];
    *j = x;
  }
}

}  // namespace

FaceGroups group_faces(const int32_t* faces, size_t num_faces, size_t num_vertices) {
  FaceGroups g;
  // Phase 1: bucket sizes (each face goes to its smallest vertex).
  std::vector<uint32_t> start(num_vertices + 1, 0);
  for (size_t i = 0; i < num_faces; ++i) ++start[smallest(&faces[4 * i]) + 1];
  for (size_t v = 0; v < num_vertices; ++v) start[v + 1] += start[v];
  // Phase 2: the faces' indices scattered into their buckets, in input order.
  g.order.resize(num_faces);
  {
    std::vector<uint32_t> fill(start.begin(), start.end() - 1);
    for (size_t i = 0; i < num_faces; ++i) g.order[fill[smallest(&faces[4 * i])]++] = uint32_t(i);
  }
  // Phase 3: each bucket sorted by its faces' other vertices; runs of equal
  // faces are the groups.
  g.group_start.reserve(num_faces / 2 + num_faces / 8 + 2);
  std::vector<BucketFace> bucket;
  for (size_t v = 0; v < num_vertices; ++v) {
    const uint32_t begin = start[v], end = start[v + 1];
    if (begin == end) continue;
    bucket.resize(end - begin);
    for (size_t j = begin; j < end; ++j) {
      // The faces are read in no order: each one 16 faces ahead is fetched.
      if (j + 16 < num_faces) __builtin_prefetch(&faces[4 * size_t(g.order[j + 16])]);
      bucket[j - begin] = bucket_face(faces, g.order[j]);
    }
    sort_bucket(bucket.data(), bucket.data() + bucket.size());
    for (size_t k = 0; k < bucket.size(); ++k) {
      if (k > 0 && !same_vertices(bucket[k - 1], bucket[k]))
        g.group_start.push_back(begin + uint32_t(k));
      g.order[begin + k] = uint32_t(bucket[k].lo);
    }
    g.group_start.push_back(end);
  }
  return g;
}

std::vector<int32_t> volume_mesh_faces(const VolumeMesh& mesh) {
  static constexpr int kPrismFaceOut[5][4] = {
      {0, 2, 1, -1}, {3, 4, 5, -1}, {0, 1, 4, 3}, {1, 2, 5, 4}, {2, 0, 3, 5}};
  const size_t nt = mesh.num_tets(), np = mesh.num_prisms();
  const size_t ntri = mesh.num_triangles(), nq = mesh.num_quads();
  std::vector<int32_t> faces(4 * (4 * nt + 5 * np + ntri + nq));
  int32_t* f = faces.data();
  for (size_t e = 0; e < nt; ++e) {
    const int32_t* t = &mesh.tets[4 * e];
    for (const auto& k : kFaceOut) {
      *f++ = t[k[0]];
      *f++ = t[k[1]];
      *f++ = t[k[2]];
      *f++ = kNoFourthVertex;
    }
  }
  for (size_t e = 0; e < np; ++e) {
    const int32_t* p = &mesh.prisms[6 * e];
    for (const auto& k : kPrismFaceOut)
      for (int s = 0; s < 4; ++s) *f++ = k[s] < 0 ? kNoFourthVertex : p[k[s]];
  }
  for (size_t e = 0; e < ntri; ++e) {
    const int32_t* t = &mesh.triangles[3 * e];
    *f++ = t[0];
    *f++ = t[1];
    *f++ = t[2];
    *f++ = kNoFourthVertex;
  }
  std::copy(mesh.quads.begin(), mesh.quads.begin() + long(4 * nq), f);
  return faces;
}

}  // namespace vm
