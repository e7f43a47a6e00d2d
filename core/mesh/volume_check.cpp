// Volume mesh checks (docs/ARCHITECTURE.md, stage 7), in phases: element
// positivity; every element face listed with its orientation parity and
// sorted, so the uses of a face are adjacent; conformity and boundary
// matching on the sorted list; the surface triangles matched against the
// boundary faces.
#include "core/mesh/volume_check.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "core/geom/predicates.h"
#include "core/mesh/prism_split.h"
#include "core/util/parallel.h"

namespace vm {
namespace {

/// One use of a face by an element (or by a surface triangle): its sorted
/// vertices (a 4th of -1 for triangles), the orientation parity of the use,
/// and who uses it (element index, or -1 - t for surface triangle t).
struct FaceUse {
  std::array<int32_t, 4> key;
  uint8_t parity;
  int32_t region;
  int64_t owner;
};

/// Sorted key and parity of the cyclic polygon f (3 or 4 ids): parity 0 if
/// the cycle read from its smallest id goes towards the smaller of that
/// id's two neighbors.
FaceUse make_use(const int32_t* f, int n, int32_t region, int64_t owner) {
  FaceUse u{{-1, -1, -1, -1}, 0, region, owner};
  const int first = int(std::min_element(f, f + n) - f);
  const int32_t next = f[(first + 1) % n], prev = f[(first + n - 1) % n];
  u.parity = next < prev ? 0 : 1;
  std::copy(f, f + n, u.key.begin());
  std::sort(u.key.begin(), u.key.begin() + n);
  return u;
}

bool indices_in_range(const int32_t* v, int n, const VolumeMesh& m) {
  for (int k = 0; k < n; ++k)
    if (v[k] < 0 || size_t(v[k]) >= m.num_vertices()) return false;
  return true;
}

std::string where(const VolumeMesh& m, int32_t v) {
  const double* p = &m.points[3 * size_t(v)];
  char text[96];
  std::snprintf(text, sizeof text, "(%g, %g, %g)", p[0], p[1], p[2]);
  return text;
}

}  // namespace

Result<VolumeCheck> check_volume_orientation(const VolumeMesh& m) {
  using R = Result<VolumeCheck>;
  VolumeCheck c;
  auto in_range = [&](const int32_t* v, int n) { return indices_in_range(v, n, m); };
  // Phase 1: positivity (prisms by their split).
  c.min_volume6 = 1e300;
  // Its volume into min_volume6 and volume; whether it is positive.
  auto positive = [&](const int32_t* t, double& min_volume6, double& volume) {
    const double* a = &m.points[3 * size_t(t[0])];
    const double* b = &m.points[3 * size_t(t[1])];
    const double* cc = &m.points[3 * size_t(t[2])];
    const double* d = &m.points[3 * size_t(t[3])];
    const double v6 = tet_volume6(a, b, cc, d);
    min_volume6 = std::min(min_volume6, v6);
    volume += v6 / 6;
    return orient3d(a, b, cc, d) < 0;  // exact: positive orientation
  };
  // The tetrahedra on the threads, by chunks: each chunk's smallest
  // volume, its volume (added in chunk order) and its first bad one.
  struct Chunk {
    double min_volume6 = 1e300, volume = 0;
    size_t bad = SIZE_MAX;
    bool bad_index = false;
  };
  constexpr size_t kGrain = 16384;
  std::vector<Chunk> chunks((m.num_tets() + kGrain - 1) / kGrain);
  parallel_for(m.num_tets(), kGrain, [&](size_t begin, size_t end) {
    Chunk& k = chunks[begin / kGrain];
    for (size_t e = begin; e < end; ++e) {
      const int32_t* t = &m.tets[4 * e];
      k.bad_index = !in_range(t, 4);
      if (k.bad_index || !positive(t, k.min_volume6, k.volume)) {
        k.bad = e;
        break;
      }
    }
  });
  for (const Chunk& k : chunks) {
    if (k.bad != SIZE_MAX) {
      if (k.bad_index)
        return R::Error("tetrahedron " + std::to_string(k.bad) + " has a bad vertex");
      return R::Error("tetrahedron " + std::to_string(k.bad) + " at " +
                      where(m, m.tets[4 * k.bad]) + " is inverted or flat");
    }
    c.min_volume6 = std::min(c.min_volume6, k.min_volume6);
    c.volume += k.volume;
  }
  for (size_t e = 0; e < m.num_prisms(); ++e) {
    const int32_t* p = &m.prisms[6 * e];
    if (!in_range(p, 6)) return R::Error("prism " + std::to_string(e) + " has a bad vertex");
    for (const auto& t : split_prism(p))
      if (!positive(t.data(), c.min_volume6, c.volume))
        return R::Error("prism " + std::to_string(e) + " at " + where(m, p[0]) +
                        " is inverted or flat");
  }
  if (m.num_tets() + m.num_prisms() == 0) c.min_volume6 = 0;
  return c;
}

Result<VolumeCheck> check_volume_mesh(const VolumeMesh& m) {
  using R = Result<VolumeCheck>;
  // Phase 1: positivity and indices.
  auto oriented = check_volume_orientation(m);
  if (!oriented.ok()) return oriented;
  VolumeCheck c = oriented.value();
  auto in_range = [&](const int32_t* v, int n) { return indices_in_range(v, n, m); };

  // Phase 2: every face use, outward orientation.
  std::vector<FaceUse> uses;
  uses.reserve(4 * m.num_tets() + 5 * m.num_prisms() + m.num_triangles() + m.num_quads());
  for (size_t e = 0; e < m.num_tets(); ++e) {
    const int32_t* t = &m.tets[4 * e];
    const int32_t region = m.tet_region.empty() ? 0 : m.tet_region[e];
    for (const auto& f : kFaceOut) {
      const int32_t g[3] = {t[f[0]], t[f[1]], t[f[2]]};
      uses.push_back(make_use(g, 3, region, int64_t(e)));
    }
  }
  for (size_t e = 0; e < m.num_prisms(); ++e) {
    const int32_t* p = &m.prisms[6 * e];
    const int32_t region = m.prism_region.empty() ? 0 : m.prism_region[e];
    const int64_t owner = int64_t(m.num_tets() + e);
    const int32_t bottom[3] = {p[0], p[2], p[1]}, top[3] = {p[3], p[4], p[5]};
    const int32_t q0[4] = {p[0], p[1], p[4], p[3]}, q1[4] = {p[1], p[2], p[5], p[4]},
                  q2[4] = {p[2], p[0], p[3], p[5]};
    uses.push_back(make_use(bottom, 3, region, owner));
    uses.push_back(make_use(top, 3, region, owner));
    for (const int32_t* q : {q0, q1, q2}) uses.push_back(make_use(q, 4, region, owner));
  }
  for (size_t t = 0; t < m.num_triangles(); ++t) {
    const int32_t* f = &m.triangles[3 * t];
    if (!in_range(f, 3))
      return R::Error("surface triangle " + std::to_string(t) + " has a bad vertex");
    uses.push_back(make_use(f, 3, -1, -1 - int64_t(t)));
  }
  for (size_t q = 0; q < m.num_quads(); ++q) {
    const int32_t* f = &m.quads[4 * q];
    if (!in_range(f, 4)) return R::Error("surface quad " + std::to_string(q) + " has a bad vertex");
    uses.push_back(make_use(f, 4, -1, -1 - int64_t(m.num_triangles() + q)));
  }
  std::sort(uses.begin(), uses.end(), [](const FaceUse& a, const FaceUse& b) {
    return a.key != b.key ? a.key < b.key : a.owner > b.owner;  // elements first
  });

  // Phase 3: the uses of each face.
  for (size_t i = 0; i < uses.size();) {
    size_t j = i;
    size_t elements = 0, triangles = 0;
    while (j < uses.size() && uses[j].key == uses[i].key) {
      (uses[j].owner >= 0 ? elements : triangles) += 1;
      ++j;
    }
    const FaceUse& a = uses[i];
    const std::string at = "face at " + where(m, a.key[0]);
    if (elements > 2)
      return R::Error("non-conforming mesh: " + at + " has " + std::to_string(elements) +
                      " elements");
    if (triangles > 1) return R::Error("duplicate surface triangle: " + at);
    if (elements == 2) {
      if (uses[i].parity == uses[i + 1].parity)
        return R::Error("two elements overlap across the " + at);
      if (triangles == 1 && uses[i].region == uses[i + 1].region)
        return R::Error("surface triangle inside one region: " + at);
    } else if (elements == 1) {
      ++c.boundary_faces;
      if (triangles == 0) return R::Error("boundary " + at + " is not a surface triangle");
      if (uses[i + 1].parity != a.parity)
        return R::Error("surface triangle oriented inward: " + at);
    } else {
      return R::Error("surface triangle not on any element: " + at);
    }
    i = j;
  }
  return c;
}

}  // namespace vm
