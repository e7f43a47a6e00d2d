// Volume mesh checks (docs/ARCHITECTURE.md, stage 7), in phases: element
// positivity; every element face and surface face grouped by vertex set
// (group_faces), so the uses of a face are together; conformity and
// boundary matching on each group, by the orientation parity of its uses.
#include "core/mesh/volume_check.h"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "core/geom/predicates.h"
#include "core/mesh/face_groups.h"
#include "core/mesh/prism_split.h"
#include "core/util/parallel.h"

namespace vm {
namespace {

/// Orientation parity of the cyclic polygon f (3 or 4 ids): 0 if the cycle
/// read from its smallest id goes towards the smaller of that id's two
/// neighbors.
int parity(const int32_t* f, int n) {
  const int first = int(std::min_element(f, f + n) - f);
  const int32_t next = f[(first + 1) % n], prev = f[(first + n - 1) % n];
  return next < prev ? 0 : 1;
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

  // Phase 2: every face use, grouped by vertex set: the elements' faces
  // (outward) first, then the surface's (volume_mesh_faces).
  for (size_t t = 0; t < m.num_triangles(); ++t)
    if (!in_range(&m.triangles[3 * t], 3))
      return R::Error("surface triangle " + std::to_string(t) + " has a bad vertex");
  for (size_t q = 0; q < m.num_quads(); ++q)
    if (!in_range(&m.quads[4 * q], 4))
      return R::Error("surface quad " + std::to_string(q) + " has a bad vertex");
  const std::vector<int32_t> faces = volume_mesh_faces(m);
  const FaceGroups groups = group_faces(faces.data(), faces.size() / 4, m.num_vertices());
  const size_t ne = 4 * m.num_tets() + 5 * m.num_prisms();  // the elements' faces
  auto size_of = [&](size_t f) { return faces[4 * f + 3] == kNoFourthVertex ? 3 : 4; };
  auto parity_of = [&](size_t f) { return parity(&faces[4 * f], size_of(f)); };
  auto region_of = [&](size_t f) {
    const size_t e = face_element(f, m.num_tets());
    if (e < m.num_tets()) return m.tet_region.empty() ? 0 : m.tet_region[e];
    return m.prism_region.empty() ? 0 : m.prism_region[e - m.num_tets()];
  };

  // Phase 3: the uses of each face.
  for (size_t g = 0; g < groups.num_groups(); ++g) {
    const size_t n = groups.size(g);
    size_t elements = 0;  // the group's elements' faces, first in it
    while (elements < n && groups.face(g, elements) < ne) ++elements;
    const size_t triangles = n - elements;
    const size_t a = groups.face(g, 0), b = n > 1 ? groups.face(g, 1) : a;
    const auto at = [&] {
      return "face at " + where(m, *std::min_element(&faces[4 * a], &faces[4 * a] + size_of(a)));
    };
    if (elements > 2)
      return R::Error("non-conforming mesh: " + at() + " has " + std::to_string(elements) +
                      " elements");
    if (triangles > 1) return R::Error("duplicate surface triangle: " + at());
    if (elements == 2) {
      if (parity_of(a) == parity_of(b)) return R::Error("two elements overlap across the " + at());
      if (triangles == 1 && region_of(a) == region_of(b))
        return R::Error("surface triangle inside one region: " + at());
    } else if (elements == 1) {
      ++c.boundary_faces;
      if (triangles == 0) return R::Error("boundary " + at() + " is not a surface triangle");
      if (parity_of(b) != parity_of(a))
        return R::Error("surface triangle oriented inward: " + at());
    } else {
      return R::Error("surface triangle not on any element: " + at());
    }
  }
  return c;
}

}  // namespace vm
