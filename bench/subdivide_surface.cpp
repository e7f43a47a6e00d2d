// Generator of large inputs for the scale benchmarks: a surface subdivided
// without changing its shape, so that it is a real vessel with many more
// triangles (e.g. aortic-arch.stl, 41,176 triangles: three 1-to-4 splits and
// a centroid split give 7.9M triangles, a 395 MB binary STL).
//
// usage: subdivide_surface IN.stl OUT.stl [--four N] [--centroid] [--until T]
//   --four N: N rounds of the 1-to-4 split (edge midpoints); default 3
//   --centroid: then split every triangle at its centroid into 3 (long,
//     thin triangles as a fine segmentation has); default on, --no-centroid
//     turns it off
//   --until T: the centroid split only on the first triangles, until the
//     surface has T triangles (e.g. --four 4 --until 25000000 on the arch:
//     a 25M-triangle surface, the readers' limit)
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <unordered_map>
#include <vector>

#include "core/io/stl.h"
#include "core/mesh/weld.h"

namespace {

using vm::SurfaceMesh;

/// One round of the 1-to-4 split: every edge gets its midpoint, every
/// triangle (a, b, c) becomes (a, ab, ca), (ab, b, bc), (ca, bc, c), (ab, bc,
/// ca). Orientation is kept.
SurfaceMesh split_four(const SurfaceMesh& m) {
  SurfaceMesh out;
  out.points = m.points;
  std::unordered_map<uint64_t, int32_t> midpoint;
  midpoint.reserve(m.triangles.size() * 2);
  auto mid = [&](int32_t a, int32_t b) {
    const uint64_t key = a < b ? (uint64_t(uint32_t(a)) << 32) | uint32_t(b)
                               : (uint64_t(uint32_t(b)) << 32) | uint32_t(a);
    auto [it, added] = midpoint.try_emplace(key, int32_t(out.points.size() / 3));
    if (added)
      for (int k = 0; k < 3; ++k)
        out.points.push_back(0.5 * (m.points[3 * size_t(a) + k] + m.points[3 * size_t(b) + k]));
    return it->second;
  };
  out.triangles.reserve(4 * m.triangles.size());
  for (size_t t = 0; t < m.num_triangles(); ++t) {
    const int32_t a = m.triangles[3 * t], b = m.triangles[3 * t + 1], c = m.triangles[3 * t + 2];
    const int32_t ab = mid(a, b), bc = mid(b, c), ca = mid(c, a);
    for (int32_t v : {a, ab, ca, ab, b, bc, ca, bc, c, ab, bc, ca}) out.triangles.push_back(v);
  }
  return out;
}

/// Every triangle (a, b, c) becomes (a, b, g), (b, c, g), (c, a, g) with g
/// its centroid, in order, while the surface has fewer than `until`
/// triangles; the rest stay as they are.
SurfaceMesh split_centroid(const SurfaceMesh& m, size_t until) {
  SurfaceMesh out;
  out.points = m.points;
  out.triangles.reserve(3 * m.triangles.size());
  size_t count = m.num_triangles();
  for (size_t t = 0; t < m.num_triangles(); ++t) {
    const int32_t v[3] = {m.triangles[3 * t], m.triangles[3 * t + 1], m.triangles[3 * t + 2]};
    if (count + 2 > until) {
      out.triangles.insert(out.triangles.end(), v, v + 3);
      continue;
    }
    count += 2;
    const int32_t g = int32_t(out.points.size() / 3);
    for (int k = 0; k < 3; ++k)
      out.points.push_back((m.points[3 * size_t(v[0]) + k] + m.points[3 * size_t(v[1]) + k] +
                            m.points[3 * size_t(v[2]) + k]) /
                           3);
    for (int i = 0; i < 3; ++i)
      for (int32_t w : {v[i], v[(i + 1) % 3], g}) out.triangles.push_back(w);
  }
  return out;
}

int usage() {
  std::fprintf(stderr,
               "usage: subdivide_surface IN.stl OUT.stl [--four N] [--no-centroid] [--until T]\n");
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) return usage();
  int four = 3;
  bool centroid = true;
  size_t until = SIZE_MAX;
  for (int i = 3; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--four") && i + 1 < argc) {
      four = std::atoi(argv[++i]);
      if (four < 0 || four > 6) return usage();
    } else if (!std::strcmp(argv[i], "--no-centroid")) {
      centroid = false;
    } else if (!std::strcmp(argv[i], "--centroid")) {
      centroid = true;
    } else if (!std::strcmp(argv[i], "--until") && i + 1 < argc) {
      until = size_t(std::atoll(argv[++i]));
    } else {
      return usage();
    }
  }
  std::ifstream in(argv[1], std::ios::binary);
  if (!in) {
    std::fprintf(stderr, "subdivide_surface: cannot open %s\n", argv[1]);
    return 1;
  }
  const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)), {});
  auto soup = vm::read_stl(bytes);
  if (!soup.ok()) {
    std::fprintf(stderr, "subdivide_surface: %s: %s\n", argv[1], soup.message().c_str());
    return 1;
  }
  vm::WeldOptions exact;
  exact.relative_tolerance = 0;
  SurfaceMesh m = vm::weld(soup.value(), exact);  // binary or ASCII
  for (int r = 0; r < four; ++r) m = split_four(m);
  if (centroid) m = split_centroid(m, until);
  const std::vector<uint8_t> out = vm::write_stl_binary(m, "subdivide_surface");
  std::ofstream os(argv[2], std::ios::binary);
  os.write(reinterpret_cast<const char*>(out.data()), std::streamsize(out.size()));
  if (!os) {
    std::fprintf(stderr, "subdivide_surface: cannot write %s\n", argv[2]);
    return 1;
  }
  std::printf("wrote %s: %zu triangles, %zu vertices\n", argv[2], m.num_triangles(),
              m.num_vertices());
  return 0;
}
