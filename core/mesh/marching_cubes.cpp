// Marching cubes (Lorensen and Cline 1987). The 256-case table is derived
// here rather than transcribed: on each cube face the crossing edges are
// linked in pairs (keeping inside corners apart on ambiguous faces); every
// crossing edge then has two links, so the links form cycles; each cycle is
// fan-triangulated and oriented so that its normal points away from the
// inside corners.
#include "core/mesh/marching_cubes.h"

#include <array>
#include <cmath>
#include <vector>

namespace vm {
namespace {

// Corner c of the unit cube: bit 0 = x, bit 1 = y, bit 2 = z.
constexpr int kEdge[12][2] = {{0, 1}, {2, 3}, {4, 5}, {6, 7},   // along x
                              {0, 2}, {1, 3}, {4, 6}, {5, 7},   // along y
                              {0, 4}, {1, 5}, {2, 6}, {3, 7}};  // along z
// Faces as 4 corners in cyclic order.
constexpr int kFace[6][4] = {{0, 2, 6, 4}, {1, 3, 7, 5}, {0, 1, 5, 4},
                             {2, 3, 7, 6}, {0, 1, 3, 2}, {4, 5, 7, 6}};

int edge_between(int a, int b) {
  for (int e = 0; e < 12; ++e)
    if ((kEdge[e][0] == a && kEdge[e][1] == b) || (kEdge[e][0] == b && kEdge[e][1] == a)) return e;
  return -1;
}

struct CaseTable {
  // Per configuration: triangles as edge triples, -1 terminated (at most 12).
  std::array<std::array<int8_t, 37>, 256> tris;

  CaseTable() {
    for (int config = 0; config < 256; ++config) build(config);
  }

  void build(int config) {
    auto inside = [&](int c) { return (config >> c) & 1; };
    // Links between crossing edges, two per crossing edge.
    std::array<std::array<int, 2>, 12> link;
    for (auto& l : link) l = {-1, -1};
    auto add_link = [&](int a, int b) {
      link[a][link[a][0] < 0 ? 0 : 1] = b;
      link[b][link[b][0] < 0 ? 0 : 1] = a;
    };
    for (const auto& f : kFace) {
      int crossing[4], n = 0;
      for (int k = 0; k < 4; ++k) {
        int a = f[k], b = f[(k + 1) % 4];
        if (inside(a) != inside(b)) crossing[n++] = k;
      }
      if (n == 2) {
        add_link(edge_between(f[crossing[0]], f[(crossing[0] + 1) % 4]),
                 edge_between(f[crossing[1]], f[(crossing[1] + 1) % 4]));
      } else if (n == 4) {
        // Inside corners on a diagonal: cut each inside corner off, i.e. link
        // the two face edges that meet at it.
        for (int k = 0; k < 4; ++k) {
          if (!inside(f[k])) continue;
          int prev = edge_between(f[(k + 3) % 4], f[k]);
          int next = edge_between(f[k], f[(k + 1) % 4]);
          add_link(prev, next);
        }
      }
    }
    // Walk the cycles, fan-triangulate, orient.
    std::array<bool, 12> used{};
    int out = 0;
    for (int e0 = 0; e0 < 12; ++e0) {
      if (used[e0] || link[e0][0] < 0) continue;
      std::vector<int> cycle;
      int prev = -1, cur = e0;
      while (!used[cur]) {
        used[cur] = true;
        cycle.push_back(cur);
        int next = link[cur][0] != prev ? link[cur][0] : link[cur][1];
        prev = cur;
        cur = next;
      }
      // Orientation: the cycle's vector area (edge midpoints) must point
      // from the inside corners to the outside ones.
      double area[3] = {0, 0, 0}, flow[3] = {0, 0, 0};
      auto mid = [](int e, double* p) {
        for (int k = 0; k < 3; ++k)
          p[k] = 0.5 * (((kEdge[e][0] >> k) & 1) + ((kEdge[e][1] >> k) & 1));
      };
      for (size_t i = 0; i < cycle.size(); ++i) {
        double p[3], q[3];
        mid(cycle[i], p);
        mid(cycle[(i + 1) % cycle.size()], q);
        area[0] += p[1] * q[2] - p[2] * q[1];
        area[1] += p[2] * q[0] - p[0] * q[2];
        area[2] += p[0] * q[1] - p[1] * q[0];
        int a = kEdge[cycle[i]][0], b = kEdge[cycle[i]][1];
        int in = inside(a) ? a : b, ou = inside(a) ? b : a;
        for (int k = 0; k < 3; ++k) flow[k] += ((ou >> k) & 1) - ((in >> k) & 1);
      }
      bool reverse = area[0] * flow[0] + area[1] * flow[1] + area[2] * flow[2] < 0;
      for (size_t i = 1; i + 1 < cycle.size(); ++i) {
        int a = cycle[0], b = cycle[i], c = cycle[i + 1];
        if (reverse) std::swap(b, c);
        tris[config][out++] = int8_t(a);
        tris[config][out++] = int8_t(b);
        tris[config][out++] = int8_t(c);
      }
    }
    tris[config][out] = -1;
  }
};

const CaseTable& case_table() {
  static const CaseTable table;
  return table;
}

}  // namespace

SurfaceMesh marching_cubes(const GridSpec& g, const PlaneFn& plane_values) {
  SurfaceMesh mesh;
  if (g.nx < 2 || g.ny < 2 || g.nz < 2) return mesh;
  const CaseTable& table = case_table();
  const size_t plane = size_t(g.nx) * size_t(g.ny);
  constexpr float kEps = 1e-6f;
  std::vector<float> lo(plane), hi(plane);
  auto load = [&](int k, std::vector<float>& v) {
    plane_values(k, v.data());
    for (float& x : v)
      if (std::fabs(x) < kEps) x = kEps;
  };
  // Vertex ids of the edges: x- and y-edges of the lower and upper planes,
  // z-edges between them.
  std::vector<int32_t> xlo(plane, -1), ylo(plane, -1), xhi(plane, -1), yhi(plane, -1),
      zmid(plane, -1);
  auto point = [&](int i, int j, int k, int axis, float v0, float v1) {
    double t = double(v0) / (double(v0) - double(v1));
    double p[3] = {double(i), double(j), double(k)};
    p[axis] += t;
    for (int a = 0; a < 3; ++a) mesh.points.push_back(g.origin[a] + g.spacing * p[a]);
    return int32_t(mesh.num_vertices() - 1);
  };
  load(0, lo);
  for (int k = 0; k + 1 < g.nz; ++k) {
    load(k + 1, hi);
    std::fill(xhi.begin(), xhi.end(), -1);
    std::fill(yhi.begin(), yhi.end(), -1);
    std::fill(zmid.begin(), zmid.end(), -1);
    auto value = [&](int i, int j, int dk) {
      return (dk ? hi : lo)[size_t(i) + size_t(g.nx) * size_t(j)];
    };
    // Vertex on cube edge e of cube (i, j, k), created on first use.
    auto edge_vertex = [&](int i, int j, int e) -> int32_t {
      // Edges run from their lower corner a along +axis.
      int a = kEdge[e][0];
      int ai = i + (a & 1), aj = j + ((a >> 1) & 1), ak = (a >> 2) & 1;
      int axis = e < 4 ? 0 : e < 8 ? 1 : 2;
      size_t idx = size_t(ai) + size_t(g.nx) * size_t(aj);
      std::vector<int32_t>& ids = axis == 2   ? zmid
                                  : axis == 0 ? (ak ? xhi : xlo)
                                              : (ak ? yhi : ylo);
      if (ids[idx] < 0) {
        float v0 = value(ai, aj, ak);
        int bi = ai + (axis == 0), bj = aj + (axis == 1), bk = ak + (axis == 2);
        ids[idx] = point(ai, aj, k + ak, axis, v0, value(bi, bj, bk));
      }
      return ids[idx];
    };
    for (int j = 0; j + 1 < g.ny; ++j) {
      for (int i = 0; i + 1 < g.nx; ++i) {
        int config = 0;
        for (int c = 0; c < 8; ++c)
          if (value(i + (c & 1), j + ((c >> 1) & 1), (c >> 2) & 1) < 0) config |= 1 << c;
        if (config == 0 || config == 255) continue;
        const auto& t = table.tris[config];
        for (int n = 0; t[n] >= 0; n += 3) {
          int32_t a = edge_vertex(i, j, t[n]), b = edge_vertex(i, j, t[n + 1]),
                  c = edge_vertex(i, j, t[n + 2]);
          mesh.triangles.insert(mesh.triangles.end(), {a, b, c});
        }
      }
    }
    lo.swap(hi);
    xlo.swap(xhi);
    ylo.swap(yhi);
  }
  return mesh;
}

}  // namespace vm
