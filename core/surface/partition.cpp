// Patch partition by recursive principal-axis bisection, checked by the map
// itself (Marchandise et al., section 2.1). Phases per candidate piece:
// connected components, disk test (Euler characteristic, boundary loops,
// pinched vertices), map and crowding test, and if anything fails a
// bisection with a straightened cut. The pieces of one bisection depth are
// processed on the threads (partition_for_maps says how the result stays
// the sequential one).
#include "core/surface/partition.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "core/mesh/boundary_loops.h"
#include "core/util/parallel.h"

namespace vm {
namespace {

struct Piece {
  std::vector<int32_t> tris;  // input triangle ids
  int depth = 0;
};

// The owner array is shared by the pieces of a level, which run at the same
// time: a piece writes only its own triangles' entries (with ids from its
// own range) and reads its neighbors', which another piece may be writing;
// what it reads there is never one of its ids either way, so the result
// does not depend on the timing. Relaxed atomic accesses keep those reads
// defined.
inline int64_t owner_of(const std::vector<int64_t>& owner, int32_t t) {
  return __atomic_load_n(&owner[size_t(t)], __ATOMIC_RELAXED);
}
inline void set_owner(std::vector<int64_t>& owner, int32_t t, int64_t id) {
  __atomic_store_n(&owner[size_t(t)], id, __ATOMIC_RELAXED);
}

/// Copies the triangles `tris` of `m` with compact local vertex numbers.
MappedPatch extract(const SurfaceMesh& m, const std::vector<int32_t>& tris,
                    std::vector<int32_t>& local) {
  MappedPatch p;
  p.triangle_of = tris;
  p.mesh.triangles.reserve(3 * tris.size());
  for (int32_t t : tris)
    for (int c = 0; c < 3; ++c) {
      int32_t v = m.triangles[3 * size_t(t) + c];
      if (local[size_t(v)] < 0) {
        local[size_t(v)] = int32_t(p.vertex_of.size());
        p.vertex_of.push_back(v);
        p.mesh.points.insert(p.mesh.points.end(), &m.points[3 * size_t(v)],
                             &m.points[3 * size_t(v)] + 3);
      }
      p.mesh.triangles.push_back(local[size_t(v)]);
    }
  for (int32_t v : p.vertex_of) local[size_t(v)] = -1;
  return p;
}

/// True if `p` is a topological disk without pinched vertices.
bool is_disk(const SurfaceMesh& p) {
  TriangleAdjacency adj = build_adjacency(p);
  if (adj.num_nonmanifold_edges > 0) return false;
  std::vector<int> boundary_degree(p.num_vertices(), 0);
  for (size_t h = 0; h < adj.opposite.size(); ++h)
    if (adj.opposite[h] == TriangleAdjacency::kBoundary) {
      if (++boundary_degree[size_t(half_edge_from(p, int32_t(h)))] > 2) return false;
      if (++boundary_degree[size_t(half_edge_to(p, int32_t(h)))] > 2) return false;
    }
  const long chi = long(p.num_vertices()) - long(adj.num_edges) + long(p.num_triangles());
  return chi == 1 && boundary_loops(p, adj).size() == 1;
}

/// Splits `tris` (all with owner[t] == id) in two by the principal-axis
/// median plane, then moves teeth across the cut; marks side 1 in owner as
/// id + 1.
void bisect(const SurfaceMesh& m, const TriangleAdjacency& adj, const std::vector<int32_t>& tris,
            std::vector<int64_t>& owner, int64_t id, std::vector<int32_t> out[2]) {
  const size_t n = tris.size();
  std::vector<double> c(3 * n), w(n);
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  double total = 0;
  for (size_t i = 0; i < n; ++i) {
    const int32_t* v = &m.triangles[3 * size_t(tris[i])];
    Eigen::Vector3d p[3];
    for (int k = 0; k < 3; ++k) p[k] = Eigen::Vector3d(&m.points[3 * size_t(v[k])]);
    Eigen::Vector3d ctr = (p[0] + p[1] + p[2]) / 3;
    w[i] = 0.5 * (p[1] - p[0]).cross(p[2] - p[0]).norm() + 1e-300;
    for (int k = 0; k < 3; ++k) c[3 * i + k] = ctr[k];
    mean += w[i] * ctr;
    total += w[i];
  }
  mean /= total;
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (size_t i = 0; i < n; ++i) {
    Eigen::Vector3d d = Eigen::Vector3d(&c[3 * i]) - mean;
    cov += w[i] * d * d.transpose();
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
  Eigen::Vector3d axis = eig.eigenvectors().col(2);
  // Area-weighted median of the projections.
  std::vector<std::pair<double, size_t>> proj(n);
  for (size_t i = 0; i < n; ++i) proj[i] = {axis.dot(Eigen::Vector3d(&c[3 * i])), i};
  std::sort(proj.begin(), proj.end());
  double acc = 0;
  std::vector<uint8_t> side(n, 0);
  for (auto& [x, i] : proj) {
    side[i] = acc >= 0.5 * total;
    acc += w[i];
  }
  // Straighten: a triangle with at least two neighbors (in the piece) on
  // the other side changes side; a few passes.
  for (size_t i = 0; i < n; ++i) set_owner(owner, tris[i], id + side[i]);
  for (int pass = 0; pass < 4; ++pass) {
    bool changed = false;
    for (size_t i = 0; i < n; ++i) {
      const int32_t t = tris[i];
      int other = 0;
      for (int k = 0; k < 3; ++k) {
        int32_t o = adj.opposite[3 * size_t(t) + k];
        if (o < 0) continue;
        const int64_t s = owner_of(owner, o / 3);
        if ((s == id || s == id + 1) && s != owner_of(owner, t)) ++other;
      }
      if (other >= 2) {
        set_owner(owner, t, owner_of(owner, t) == id ? id + 1 : id);
        changed = true;
      }
    }
    if (!changed) break;
  }
  // Fragments: a piece of one side cut off from that side's largest piece
  // joins the other side (so no patch is a sliver left by the cut).
  for (int side = 0; side < 2; ++side) {
    const int64_t mine = id + side, other = id + 1 - side;
    std::vector<uint8_t> seen(n, 0);
    std::vector<std::vector<size_t>> pieces;
    for (size_t i = 0; i < n; ++i) {
      if (seen[i] || owner_of(owner, tris[i]) != mine) continue;
      pieces.push_back({i});
      seen[i] = 1;
      auto& piece = pieces.back();
      for (size_t j = 0; j < piece.size(); ++j) {
        const int32_t t = tris[piece[j]];
        for (int k = 0; k < 3; ++k) {
          int32_t o = adj.opposite[3 * size_t(t) + k];
          if (o < 0 || owner_of(owner, o / 3) != mine) continue;
          auto it = std::lower_bound(tris.begin(), tris.end(), o / 3);
          const size_t idx = size_t(it - tris.begin());
          if (!seen[idx]) {
            seen[idx] = 1;
            piece.push_back(idx);
          }
        }
      }
    }
    if (pieces.size() < 2) continue;
    size_t largest = 0;
    for (size_t i = 1; i < pieces.size(); ++i)
      if (pieces[i].size() > pieces[largest].size()) largest = i;
    for (size_t i = 0; i < pieces.size(); ++i)
      if (i != largest)
        for (size_t idx : pieces[i]) set_owner(owner, tris[idx], other);
  }
  for (int32_t t : tris) out[owner_of(owner, t) - id].push_back(t);
  if (!out[0].empty() && !out[1].empty()) return;
  // Too few triangles for a plane to cut (a coarse input): the first half
  // of a breadth-first order from the triangle lowest along the axis.
  out[0].clear();
  out[1].clear();
  for (int32_t t : tris) set_owner(owner, t, id + 1);
  std::vector<int32_t> order = {tris[proj.front().second]};
  set_owner(owner, order[0], id);
  for (size_t i = 0; i < order.size() && order.size() < n / 2; ++i)
    for (int k = 0; k < 3 && order.size() < n / 2; ++k) {
      const int32_t o = adj.opposite[3 * size_t(order[i]) + k];
      if (o >= 0 && owner_of(owner, o / 3) == id + 1) {
        set_owner(owner, o / 3, id);
        order.push_back(o / 3);
      }
    }
  for (int32_t t : tris) out[owner_of(owner, t) - id].push_back(t);
}

/// Edge-connected components of `tris` (all with owner[t] == id).
std::vector<std::vector<int32_t>> components(const TriangleAdjacency& adj,
                                             const std::vector<int32_t>& tris,
                                             std::vector<int64_t>& owner, int64_t id,
                                             int64_t& next_id) {
  std::vector<std::vector<int32_t>> out;
  for (int32_t seed : tris) {
    if (owner_of(owner, seed) != id) continue;
    std::vector<int32_t> comp = {seed};
    const int64_t cid = next_id++;
    set_owner(owner, seed, cid);
    for (size_t i = 0; i < comp.size(); ++i)
      for (int k = 0; k < 3; ++k) {
        int32_t o = adj.opposite[3 * size_t(comp[i]) + k];
        if (o >= 0 && owner_of(owner, o / 3) == id) {
          set_owner(owner, o / 3, cid);
          comp.push_back(o / 3);
        }
      }
    out.push_back(std::move(comp));
  }
  return out;
}

}  // namespace

std::vector<double> conformal_factors(const SurfaceMesh& m, const std::vector<double>& uv) {
  std::vector<double> f(m.num_triangles());
  for (size_t t = 0; t < m.num_triangles(); ++t) {
    const int32_t* v = &m.triangles[3 * t];
    Eigen::Vector3d a(&m.points[3 * size_t(v[0])]), b(&m.points[3 * size_t(v[1])]),
        c(&m.points[3 * size_t(v[2])]);
    double a3 = (b - a).cross(c - a).norm();
    const double *pa = &uv[2 * size_t(v[0])], *pb = &uv[2 * size_t(v[1])],
                 *pc = &uv[2 * size_t(v[2])];
    double a2 = (pb[0] - pa[0]) * (pc[1] - pa[1]) - (pb[1] - pa[1]) * (pc[0] - pa[0]);
    f[t] = a3 > 0 ? std::sqrt(std::max(a2, 0.0) / a3) : 0;
  }
  return f;
}

double conformal_factor_ratio(const SurfaceMesh& m, const std::vector<double>& uv) {
  std::vector<double> f = conformal_factors(m, uv);
  if (f.empty()) return 1;
  size_t lo = f.size() * 2 / 100, hi = std::min(f.size() - 1, f.size() * 98 / 100);
  std::nth_element(f.begin(), f.begin() + long(lo), f.end());
  double flo = f[lo];
  std::nth_element(f.begin(), f.begin() + long(hi), f.end());
  double fhi = f[hi];
  return flo > 0 ? fhi / flo : 1e300;
}

Result<std::vector<MappedPatch>> partition_for_maps(const SurfaceMesh& mesh,
                                                    const TriangleAdjacency& adj,
                                                    const PatchMapFn& map,
                                                    const PartitionOptions& options,
                                                    PartitionStats* stats) {
  // The pieces form a tree: each is split into its components, which are
  // accepted as patches or bisected into two child pieces. The pieces of
  // one depth are independent and run on the threads (the owner array is
  // shared as owner_of() says; each piece takes ids from its own range,
  // above every id used before). The patches come in the depth-first order
  // a stack of pieces gives (a piece's patches, then its children, the
  // last pushed first), and so does the first error: the same result on
  // any number of threads.
  struct Node {
    Piece piece;
    int64_t first_id = 0;
    std::vector<MappedPatch> accepted;
    std::vector<Piece> pushed;     // the child pieces, in push order
    std::vector<size_t> children;  // their nodes
    Status error = Status::Ok();
    PartitionStats stats;
  };
  const size_t nt = mesh.num_triangles();
  std::vector<Node> nodes(1);
  nodes[0].piece.tris.resize(nt);
  for (size_t t = 0; t < nt; ++t) nodes[0].piece.tris[t] = int32_t(t);
  std::vector<int64_t> owner(nt, 0);
  auto process = [&](Node& node) {
    thread_local std::vector<int32_t> local;
    if (local.size() < mesh.num_vertices()) local.assign(mesh.num_vertices(), -1);
    const Piece& piece = node.piece;
    int64_t ids = node.first_id;
    const int64_t id = ids++;
    for (int32_t t : piece.tris) set_owner(owner, t, id);
    for (auto& comp : components(adj, piece.tris, owner, id, ids)) {
      bool accept = false;
      MappedPatch p = extract(mesh, comp, local);
      bool small_enough = comp.size() <= options.max_patch_triangles;
      if (!options.size_limit.empty())
        for (int32_t t : comp)
          if (options.size_limit[size_t(t)] > 0 &&
              comp.size() >= size_t(options.size_limit[size_t(t)]))
            small_enough = false;
      const bool disk = small_enough && is_disk(p.mesh);
      if (disk) {
        auto uv = map(p.mesh);
        if (uv.ok()) {
          p.map = std::move(uv).value();
          p.factor_ratio =
              p.map.flipped_triangles ? 1e300 : conformal_factor_ratio(p.mesh, p.map.uv);
          accept = p.factor_ratio <= options.max_factor_ratio || comp.size() < 8;
          if (!accept) ++node.stats.rejected_maps;
        } else if (comp.size() < 8) {
          // No map, and too small to split: remeshed without one.
          p.unmappable = "its map failed: " + uv.message();
          accept = true;
        } else {
          ++node.stats.rejected_maps;  // no map: split further
        }
      }
      if (accept) {
        node.accepted.push_back(std::move(p));
        continue;
      }
      if (piece.depth + 1 > options.max_depth && (disk || is_disk(p.mesh))) {
        p.unmappable = "its map still folds or crowds after " + std::to_string(options.max_depth) +
                       " bisections";
        node.accepted.push_back(std::move(p));
        continue;
      }
      if (piece.depth + 1 > options.max_depth) {
        node.error =
            Status::Error("could not split the surface into parametrizable patches (depth " +
                          std::to_string(options.max_depth) + " reached)");
        return;
      }
      std::vector<int32_t> halves[2];
      std::sort(comp.begin(), comp.end());
      bisect(mesh, adj, comp, owner, ids, halves);
      ids += 2;
      ++node.stats.bisections;
      for (auto& h : halves)
        if (!h.empty()) node.pushed.push_back({std::move(h), piece.depth + 1});
    }
  };
  // Depth by depth. A piece uses at most 1 + 3 * (its triangles) ids: its
  // own, one per component and two per bisection.
  int64_t next_id = 1;
  for (size_t begin = 0, end = 1; begin < end; begin = end, end = nodes.size()) {
    for (size_t i = begin; i < end; ++i) {
      nodes[i].first_id = next_id;
      next_id += 1 + 3 * int64_t(nodes[i].piece.tris.size());
    }
    parallel_for(end - begin, 1, [&](size_t b, size_t e) {
      for (size_t i = b; i < e; ++i) process(nodes[begin + i]);
    });
    for (size_t i = begin; i < end; ++i) {
      std::vector<int32_t>().swap(nodes[i].piece.tris);  // done with: free it
      if (!nodes[i].error.ok()) continue;
      std::vector<Piece> pushed = std::move(nodes[i].pushed);
      for (Piece& child : pushed) {
        nodes[i].children.push_back(nodes.size());
        nodes.emplace_back().piece = std::move(child);
      }
    }
  }
  // The stack's order.
  std::vector<MappedPatch> done;
  PartitionStats local_stats;
  std::vector<size_t> stack = {0};
  while (!stack.empty()) {
    Node& node = nodes[stack.back()];
    stack.pop_back();
    if (!node.error.ok()) return node.error;
    for (MappedPatch& p : node.accepted) done.push_back(std::move(p));
    local_stats.bisections += node.stats.bisections;
    local_stats.rejected_maps += node.stats.rejected_maps;
    stack.insert(stack.end(), node.children.begin(), node.children.end());
  }
  if (stats) *stats = local_stats;
  return done;
}

}  // namespace vm
