// Boundary recovery (George, Hecht, Saltel 1991; Si 2015; flips after
// Shewchuk 2002). Phases:
//   0. validate the surface (closed, manifold, oriented outward);
//   1. Delaunay tetrahedralization of its vertices;
//   2. rounds of: missing edges by flips (walk from an endpoint, flip the
//      first crossed face (2-3) or remove the first crossed edge), missing
//      faces by flips (remove the edges piercing the triangle), present
//      faces constrained; then, once per edge still missing, flips along
//      the whole segment (each crossed face flipped 2-3, or one of its edges
//      removed; each crossed edge removed); then Steiner points on the edges
//      still missing (and on the longest edge of faces still missing) at their midpoints
//      or on concentric shells around input vertices (Ruppert 1995), the
//      surface triangles on a split edge being split in two, inserted
//      without crossing the faces already recovered;
//   3. if the rounds stall, the same with Steiner points only in a fresh
//      Delaunay tetrahedralization (conforming Delaunay, which flips cannot
//      disturb);
//   4. flood fill from the ghost tetrahedra, stopping at the surface, to
//      tell the inside from the outside; output.
#include "core/volume/boundary_recovery.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <utility>

#include "core/geom/predicates.h"
#include "core/util/parallel.h"
#include "core/util/portable_math.h"
#include "core/util/radix_sort.h"
#include "core/volume/tet_topology.h"

namespace vm {
namespace {

using Tri = std::array<int32_t, 3>;

// Edges or faces looked up per chunk of the parallel queries.
constexpr size_t kQueryGrain = 4096;
// Crossings followed along a missing edge.
constexpr int kMaxWalk = 256;

uint64_t edge_key(int32_t a, int32_t b) {
  if (a > b) std::swap(a, b);
  return (uint64_t(uint32_t(a)) << 32) | uint32_t(b);
}

int sgn(double x) { return (x > 0) - (x < 0); }

// The surface being recovered: its triangles as split so far, each with the
// input triangle it came from, and the triangles on each edge.
struct Surface {
  std::vector<Tri> tri;
  std::vector<int32_t> parent;
  std::unordered_map<uint64_t, std::array<int32_t, 2>> edges;

  void link(int32_t a, int32_t b, int32_t t) {
    auto& e = edges.try_emplace(edge_key(a, b), std::array<int32_t, 2>{-1, -1}).first->second;
    (e[0] < 0 ? e[0] : e[1]) = t;
  }
  void unlink(int32_t a, int32_t b, int32_t t) {
    auto it = edges.find(edge_key(a, b));
    if (it == edges.end()) return;
    auto& e = it->second;
    if (e[0] == t) e[0] = e[1], e[1] = -1;
    if (e[1] == t) e[1] = -1;
    if (e[0] < 0) edges.erase(it);
  }
  int32_t add(const Tri& v, int32_t par) {
    const int32_t t = int32_t(tri.size());
    tri.push_back(v);
    parent.push_back(par);
    for (int k = 0; k < 3; ++k) link(v[size_t(k)], v[size_t((k + 1) % 3)], t);
    return t;
  }
  void set(int32_t t, const Tri& v) {
    for (int k = 0; k < 3; ++k) unlink(tri[size_t(t)][size_t(k)], tri[size_t(t)][(k + 1) % 3], t);
    tri[size_t(t)] = v;
    for (int k = 0; k < 3; ++k) link(v[size_t(k)], v[size_t((k + 1) % 3)], t);
  }
  /// Splits both triangles on edge (a, b) at vertex m, keeping orientation.
  void split_edge(int32_t a, int32_t b, int32_t m) {
    auto it = edges.find(edge_key(a, b));
    if (it == edges.end()) return;
    const std::array<int32_t, 2> on = it->second;
    for (int32_t t : on) {
      if (t < 0) continue;
      Tri v = tri[size_t(t)];
      int r = 0;  // rotate so that (v[0], v[1]) is the edge
      while (!((v[0] == a && v[1] == b) || (v[0] == b && v[1] == a))) {
        std::rotate(v.begin(), v.begin() + 1, v.end());
        if (++r > 3) return;
      }
      set(t, {v[0], m, v[2]});
      add({m, v[1], v[2]}, parent[size_t(t)]);
    }
  }
};

// Phase 0.
Status validate(const std::vector<double>& points, const std::vector<int32_t>& triangles,
                const std::vector<int32_t>& tags) {
  if (points.size() % 3 != 0) return Status::Error("points: size not a multiple of 3");
  if (triangles.size() % 3 != 0) return Status::Error("triangles: size not a multiple of 3");
  const size_t nt = triangles.size() / 3, nv = points.size() / 3;
  if (tags.size() != nt) return Status::Error("tags: one per triangle expected");
  if (nt < 4) return Status::Error("surface: fewer than 4 triangles cannot be closed");
  for (double x : points)
    if (!std::isfinite(x)) return Status::Error("points: non-finite coordinate");
  // Six times the enclosed volume, summed about the first point rather than
  // the origin: about the origin the terms of a model far from it (1e5 away)
  // are ~1e15 times its own and their rounding drowns the volume.
  const double o[3] = {points[0], points[1], points[2]};
  double volume6 = 0;
  for (size_t t = 0; t < nt; ++t) {
    const int32_t* v = &triangles[3 * t];
    for (int k = 0; k < 3; ++k)
      if (v[k] < 0 || size_t(v[k]) >= nv)
        return Status::Error("triangle " + std::to_string(t) + ": vertex index out of range");
    if (v[0] == v[1] || v[1] == v[2] || v[2] == v[0])
      return Status::Error("triangle " + std::to_string(t) + ": repeated vertex");
    const double* a = &points[3 * size_t(v[0])];
    const double* b = &points[3 * size_t(v[1])];
    const double* c = &points[3 * size_t(v[2])];
    const double a2[2] = {a[2], a[0]}, b2[2] = {b[2], b[0]}, c2[2] = {c[2], c[0]};
    if (orient2d(a, b, c) == 0 && orient2d(a + 1, b + 1, c + 1) == 0 && orient2d(a2, b2, c2) == 0)
      return Status::Error("triangle " + std::to_string(t) + ": degenerate (collinear corners)");
    const double p[3] = {a[0] - o[0], a[1] - o[1], a[2] - o[2]};
    const double q[3] = {b[0] - o[0], b[1] - o[1], b[2] - o[2]};
    const double r[3] = {c[0] - o[0], c[1] - o[1], c[2] - o[2]};
    volume6 += p[0] * (q[1] * r[2] - q[2] * r[1]) - p[1] * (q[0] * r[2] - q[2] * r[0]) +
               p[2] * (q[0] * r[1] - q[1] * r[0]);
  }
  // Closed and manifold: each directed edge (a, b) once, and (b, a) too,
  // i.e. the sorted keys a << 32 | b have no repeat and equal the sorted
  // keys b << 32 | a. Else the first such edge in triangle order is named.
  auto key = [](int32_t a, int32_t b) { return (uint64_t(uint32_t(a)) << 32) | uint32_t(b); };
  std::vector<uint64_t> directed(3 * nt), reversed(3 * nt);
  for (size_t i = 0; i < 3 * nt; ++i) {
    const int32_t a = triangles[i], b = triangles[i - i % 3 + (i + 1) % 3];
    directed[i] = key(a, b);
    reversed[i] = key(b, a);
  }
  radix_sort(directed);
  radix_sort(reversed);
  if (directed != reversed ||
      std::adjacent_find(directed.begin(), directed.end()) != directed.end()) {
    std::unordered_map<uint64_t, int> seen;
    for (size_t i = 0; i < 3 * nt; ++i) {
      const int32_t a = triangles[i], b = triangles[i - i % 3 + (i + 1) % 3];
      if (++seen[key(a, b)] > 1)
        return Status::Error("surface: edge (" + std::to_string(a) + ", " + std::to_string(b) +
                             ") is non-manifold or inconsistently oriented");
    }
    for (size_t i = 0; i < 3 * nt; ++i) {
      const int32_t a = triangles[i], b = triangles[i - i % 3 + (i + 1) % 3];
      if (!seen.count(key(b, a)))
        return Status::Error("surface: not closed (edge " + std::to_string(a) + ", " +
                             std::to_string(b) + " has one triangle)");
    }
  }
  if (!(volume6 > 0))
    return Status::Error(
        "surface: encloses no volume or is oriented inward (normals must point "
        "outward)");
  return Status::Ok();
}

struct Crossing {
  bool face = true;  // else an edge (x, y)
  int32_t tet = -1;
  int k = -1;  // the crossed face of tet
  int32_t x = -1, y = -1;
};

class Recovery {
 public:
  Recovery(Delaunay3D d, Surface s, const RecoveryOptions& o, bool flips, int64_t max_steiner,
           const std::vector<int32_t>& tags)
      : d_(std::move(d)),
        s_(std::move(s)),
        o_(o),
        flips_(flips),
        max_steiner_(max_steiner),
        num_input_(int32_t(d_.num_vertices())),
        input_(s_.tri),
        tags_(&tags) {}

  /// Phase 2 (or 3 without flips). Error when stalled or degenerate.
  Status run() {
    const int64_t max_rounds = 4 * max_steiner_ + 64;
    for (int64_t round = 0; round < max_rounds; ++round) {
      // Only the triangles not known to be constrained faces are looked at:
      // flips and constrained insertions never remove a constrained face;
      // a split makes its pieces pending; an unconstrained insertion
      // (rescan_) makes every triangle pending again.
      if (rescan_) {
        done_.assign(s_.tri.size(), 0);
        rescan_ = false;
      }
      done_.resize(s_.tri.size(), 0);
      std::vector<int32_t> pending;
      for (int32_t t = 0; t < int32_t(s_.tri.size()); ++t)
        if (!done_[size_t(t)]) pending.push_back(t);
      // 2a: edges by flips.
      std::vector<std::pair<int32_t, int32_t>> missing_edges;
      collect_missing_edges(pending, missing_edges);
      if (flips_)
        for (auto [a, b] : missing_edges) recover_edge_by_flips(a, b);
      // 2b: faces by flips; present faces constrained (found on the
      // threads, then marked in order).
      std::vector<int32_t> missing_faces;
      std::vector<std::pair<int32_t, int>> faces(pending.size());
      parallel_for(pending.size(), kQueryGrain, [&](size_t begin, size_t end) {
        Delaunay3D::AroundScratch scratch;
        for (size_t i = begin; i < end; ++i) {
          const Tri& v = s_.tri[size_t(pending[i])];
          faces[i].first = d_.find_face(v[0], v[1], v[2], &faces[i].second, scratch);
        }
      });
      for (size_t i = 0; i < pending.size(); ++i) {
        const auto [tet, k] = faces[i];
        if (tet < 0) {
          missing_faces.push_back(pending[i]);
          continue;
        }
        if (!d_.is_constrained(tet, k)) d_.set_constrained(tet, k, true);
        done_[size_t(pending[i])] = 1;
      }
      if (flips_) {
        std::vector<int32_t> still;
        for (int32_t t : missing_faces)
          if (edges_present(t) && recover_face_by_flips(t) && constrain_face(t))
            done_[size_t(t)] = 1;
          else
            still.push_back(t);
        missing_faces.swap(still);
      }
      if (missing_faces.empty()) {
        if (rescan_) continue;  // a last unconstrained insertion: check all
        return Status::Ok();
      }
      // 2c: Steiner points: missing edges at their midpoints, then faces
      // whose edges are all present at the midpoint of their longest edge.
      collect_missing_edges(missing_faces, missing_edges);
      if (missing_edges.empty()) {
        for (int32_t t : missing_faces) {
          const Tri& v = s_.tri[size_t(t)];
          if (d_.find_face(v[0], v[1], v[2], nullptr) >= 0) continue;
          auto [a, b] = longest_edge(t);
          Status st = split(a, b);
          if (!st.ok()) return st;
        }
      }
      for (auto [a, b] : missing_edges) {
        if (!s_.edges.count(edge_key(a, b))) continue;  // already split this round
        // Flips along the whole segment first, once per edge (they may
        // undo each other's work, and a Steiner point ends that).
        if (flips_ && tried_along_.insert(edge_key(a, b)).second && recover_edge_along(a, b)) {
          ++recovered_along_;
          continue;
        }
        if (flips_ && flip_surface_edge(a, b)) continue;
        Status st = split(a, b);
        if (!st.ok()) return st;
      }
    }
    return Status::Error("boundary recovery: no progress after many rounds");
  }

  Delaunay3D& kernel() { return d_; }
  Surface& surface() { return s_; }
  int64_t steiner() const { return steiner_; }
  int64_t recovered_along() const { return recovered_along_; }
  int64_t surface_flips() const { return surface_flips_; }
  const std::vector<int32_t>& flipped_edges() const { return flipped_edges_; }
  /// The input triangles after the surface flips.
  const std::vector<Tri>& input() const { return input_; }

 private:
  const double* P(int32_t v) const { return d_.point(v); }

  // The edges of triangles `tris` that are not edges of the mesh, sorted,
  // each once.
  void collect_missing_edges(const std::vector<int32_t>& tris,
                             std::vector<std::pair<int32_t, int32_t>>& out) const {
    out.clear();
    for (int32_t t : tris)
      for (int k = 0; k < 3; ++k) {
        int32_t a = s_.tri[size_t(t)][size_t(k)], b = s_.tri[size_t(t)][(k + 1) % 3];
        if (a > b) std::swap(a, b);
        out.push_back({a, b});
      }
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    std::vector<uint8_t> present(out.size());
    parallel_for(out.size(), kQueryGrain, [&](size_t begin, size_t end) {
      Delaunay3D::AroundScratch scratch;
      for (size_t i = begin; i < end; ++i)
        present[i] = d_.find_edge(out[i].first, out[i].second, scratch) >= 0;
    });
    size_t kept = 0;
    for (size_t i = 0; i < out.size(); ++i)
      if (!present[i]) out[kept++] = out[i];
    out.resize(kept);
  }

  bool edges_present(int32_t t) const {
    const Tri& v = s_.tri[size_t(t)];
    for (int k = 0; k < 3; ++k)
      if (d_.find_edge(v[size_t(k)], v[(k + 1) % 3]) < 0) return false;
    return true;
  }

  /// Marks surface triangle t constrained if it is a face; false if not.
  bool constrain_face(int32_t t) {
    const Tri& v = s_.tri[size_t(t)];
    int k = -1;
    const int32_t tet = d_.find_face(v[0], v[1], v[2], &k);
    if (tet < 0) return false;
    if (!d_.is_constrained(tet, k)) d_.set_constrained(tet, k, true);
    return true;
  }

  void unconstrain_face(const Tri& v) {
    int k = -1;
    const int32_t tet = d_.find_face(v[0], v[1], v[2], &k);
    if (tet >= 0 && d_.is_constrained(tet, k)) d_.set_constrained(tet, k, false);
  }

  std::pair<int32_t, int32_t> longest_edge(int32_t t) const {
    const Tri& v = s_.tri[size_t(t)];
    double best = -1;
    std::pair<int32_t, int32_t> e;
    for (int k = 0; k < 3; ++k) {
      const int32_t a = v[size_t(k)], b = v[(k + 1) % 3];
      double l = 0;
      for (int c = 0; c < 3; ++c) l += (P(a)[c] - P(b)[c]) * (P(a)[c] - P(b)[c]);
      if (l > best) best = l, e = {std::min(a, b), std::max(a, b)};
    }
    return e;
  }

  // The first face or edge crossed by the open segment a -> b. Returns 1 if
  // (a, b) is an edge, 0 with `c` set, -1 if the segment runs through a
  // vertex (or nothing was found).
  int first_crossing(int32_t a, int32_t b, Crossing& c) {
    d_.tets_around_vertex(a, around_);
    for (int32_t t : around_) {
      if (d_.is_ghost(t)) continue;
      const int32_t* v = d_.tet(t);
      int sa = -1;
      for (int s = 0; s < 4; ++s) {
        if (v[s] == b) return 1;
        if (v[s] == a) sa = s;
      }
      const int32_t x = v[kFaceOut[sa][0]], y = v[kFaceOut[sa][1]], z = v[kFaceOut[sa][2]];
      if (orient3d(P(x), P(y), P(z), P(b)) >= 0) continue;  // b not beyond the face
      const int r = line_through_face(a, b, t, sa, c);
      if (r < 0) continue;
      return r == 0 ? 0 : -1;
    }
    return -1;
  }

  // Whether line (a, b) passes through face k of tet t: -1 not, 1 through
  // a vertex of it; 0 through its interior or an edge, `c` then set.
  int line_through_face(int32_t a, int32_t b, int32_t t, int k, Crossing& c) const {
    const int32_t* v = d_.tet(t);
    const int32_t x = v[kFaceOut[k][0]], y = v[kFaceOut[k][1]], z = v[kFaceOut[k][2]];
    const int s1 = sgn(orient3d(P(a), P(b), P(x), P(y)));
    const int s2 = sgn(orient3d(P(a), P(b), P(y), P(z)));
    const int s3 = sgn(orient3d(P(a), P(b), P(z), P(x)));
    if ((s1 < 0 || s2 < 0 || s3 < 0) && (s1 > 0 || s2 > 0 || s3 > 0)) return -1;
    const int zeros = (s1 == 0) + (s2 == 0) + (s3 == 0);
    if (zeros >= 2) return 1;
    c = Crossing{};
    c.tet = t;
    c.k = k;
    c.face = zeros == 0;
    if (zeros == 1) {
      c.x = s1 == 0 ? x : s2 == 0 ? y : z;
      c.y = s1 == 0 ? y : s2 == 0 ? z : x;
    }
    return 0;
  }

  // The faces and edges segment a -> b crosses, in order from a (a walk
  // through the tetrahedra it passes): the walk stops after an edge, at a
  // vertex, or at b.
  void crossings(int32_t a, int32_t b, std::vector<Crossing>& out) {
    out.clear();
    Crossing c;
    if (first_crossing(a, b, c) != 0) return;
    for (int step = 0; step < kMaxWalk; ++step) {
      out.push_back(c);
      if (!c.face) return;
      const int32_t link = d_.neighbor(c.tet, c.k), u = link >> 2;
      const int entry = link & 3;
      if (d_.is_ghost(u) || d_.tet(u)[entry] == b) return;
      int found = -1;
      for (int k = 0; k < 4 && found < 0; ++k)
        if (k != entry) found = line_through_face(a, b, u, k, c);
      if (found != 0) return;
    }
  }

  bool apply(const Crossing& c) {
    if (c.face) return d_.flip23(c.tet, c.k).ok();
    if (s_.edges.count(edge_key(c.x, c.y))) return false;  // a surface edge stays
    return d_.remove_edge(c.tet, c.x, c.y).ok();
  }

  // A crossing removed otherwise when its own flip is invalid: an edge of
  // a crossed face (not a surface edge) by edge removal.
  bool apply_or_remove_edge(const Crossing& c) {
    if (apply(c)) return true;
    if (!c.face) return false;
    const int32_t* v = d_.tet(c.tet);
    const int32_t f[3] = {v[kFaceOut[c.k][0]], v[kFaceOut[c.k][1]], v[kFaceOut[c.k][2]]};
    for (int i = 0; i < 3; ++i) {
      const int32_t x = f[i], y = f[(i + 1) % 3];
      if (!s_.edges.count(edge_key(x, y)) && d_.remove_edge(c.tet, x, y).ok()) return true;
    }
    return false;
  }

  // Before a Steiner point: flips anywhere along the segment, in order
  // from a, each crossed face by its 2-3 flip or the removal of one of its
  // edges, each crossed edge by its removal.
  bool recover_edge_along(int32_t a, int32_t b) {
    for (int it = 0; it < 4 * o_.max_flips_per_item; ++it) {
      crossings(a, b, walk_);
      if (walk_.empty()) return d_.find_edge(a, b) >= 0;
      bool flipped = false;
      for (const Crossing& c : walk_)
        if ((flipped = apply_or_remove_edge(c))) break;
      if (!flipped) return false;
    }
    return d_.find_edge(a, b) >= 0;
  }

  bool recover_edge_by_flips(int32_t a, int32_t b) {
    for (int it = 0; it < o_.max_flips_per_item; ++it) {
      Crossing c;
      int r = first_crossing(a, b, c);
      if (r == 1) return true;
      if (r < 0) return false;
      if (apply(c)) continue;
      r = first_crossing(b, a, c);
      if (r == 1) return true;
      if (r < 0 || !apply(c)) return false;
    }
    return d_.find_edge(a, b) >= 0;
  }

  // Edges (x, y) of the rings around the triangle's edges that pierce its
  // interior are removed (3-2 flip or edge removal) until the face appears.
  bool recover_face_by_flips(int32_t t) {
    const Tri v = s_.tri[size_t(t)];
    for (int it = 0; it < o_.max_flips_per_item; ++it) {
      if (d_.find_face(v[0], v[1], v[2], nullptr) >= 0) return true;
      bool progress = false;
      for (int k = 0; k < 3 && !progress; ++k) {
        const int32_t a = v[size_t(k)], b = v[(k + 1) % 3];
        const int32_t e = d_.find_edge(a, b);
        if (e < 0) return false;
        d_.edge_ring(e, a, b, ring_tets_, ring_);
        const size_t n = ring_.size();
        for (size_t i = 0; i < n && !progress; ++i) {
          const int32_t x = ring_[i], y = ring_[(i + 1) % n];
          if (x < 0 || y < 0 || !pierces(v, x, y)) continue;
          if (s_.edges.count(edge_key(x, y))) continue;
          const int32_t et = d_.find_edge(x, y);
          progress = et >= 0 && d_.remove_edge(et, x, y).ok();
        }
      }
      if (!progress) return false;
    }
    return d_.find_face(v[0], v[1], v[2], nullptr) >= 0;
  }

  // Segment (x, y) crosses the interior of triangle v.
  bool pierces(const Tri& v, int32_t x, int32_t y) const {
    const double *a = P(v[0]), *b = P(v[1]), *c = P(v[2]);
    const int ox = sgn(orient3d(a, b, c, P(x))), oy = sgn(orient3d(a, b, c, P(y)));
    if (ox * oy >= 0) return false;
    const int s1 = sgn(orient3d(P(x), P(y), a, b));
    const int s2 = sgn(orient3d(P(x), P(y), b, c));
    const int s3 = sgn(orient3d(P(x), P(y), c, a));
    return s1 != 0 && s1 == s2 && s2 == s3;
  }

  // Where to split surface edge (a, b): the midpoint, except when exactly
  // one endpoint is an input vertex: then at the power-of-two distance from
  // it nearest to half the length (Ruppert's concentric shells, "A Delaunay
  // refinement algorithm for quality 2-dimensional mesh generation", J.
  // Algorithms 18, 1995), so that two edges meeting at a small angle are
  // split at the same distances and do not keep encroaching each other.
  void split_point(int32_t a, int32_t b, double* m) const {
    const bool ia = a < num_input_, ib = b < num_input_;
    double t = 0.5;
    if (ia != ib) {
      double l2 = 0;
      for (int k = 0; k < 3; ++k) l2 += (P(b)[k] - P(a)[k]) * (P(b)[k] - P(a)[k]);
      const double len = std::sqrt(l2);
      const double shell = pm::exp2(std::round(pm::log2(0.5 * len)));
      t = ia ? shell / len : 1 - shell / len;
      if (!(t > 0.25 && t < 0.75)) t = 0.5;
    }
    for (int k = 0; k < 3; ++k) m[k] = P(a)[k] + t * (P(b)[k] - P(a)[k]);
    if (t == 0.5)
      for (int k = 0; k < 3; ++k) m[k] = 0.5 * (P(a)[k] + P(b)[k]);
  }

  // The surface flip of missing edge (a, b) between two whole input
  // triangles of one tag, when the caller allows it: (p, q, c) and
  // (q, p, d) become (c, p, d) and (d, q, c).
  bool flip_surface_edge(int32_t a, int32_t b) {
    if (!o_.may_flip_surface || flipped_.count(edge_key(a, b))) return false;
    const auto it = s_.edges.find(edge_key(a, b));
    if (it == s_.edges.end()) return false;
    const int32_t t1 = it->second[0], t2 = it->second[1];
    const int32_t n_input = int32_t(input_.size());
    if (t1 < 0 || t2 < 0 || t1 >= n_input || t2 >= n_input) return false;
    if (s_.tri[size_t(t1)] != input_[size_t(t1)] || s_.tri[size_t(t2)] != input_[size_t(t2)])
      return false;  // split already
    const int32_t tag = (*tags_)[size_t(t1)];
    if ((*tags_)[size_t(t2)] != tag) return false;
    Tri u = s_.tri[size_t(t1)], w = s_.tri[size_t(t2)];
    for (int r = 0; r < 3 && !((u[0] == a && u[1] == b) || (u[0] == b && u[1] == a)); ++r)
      std::rotate(u.begin(), u.begin() + 1, u.end());
    const int32_t p = u[0], q = u[1], c = u[2];
    for (int r = 0; r < 3 && !(w[0] == q && w[1] == p); ++r)
      std::rotate(w.begin(), w.begin() + 1, w.end());
    const int32_t d = w[2];
    if (w[0] != q || w[1] != p || c == d || s_.edges.count(edge_key(c, d))) return false;
    if (!o_.may_flip_surface(p, q, c, d, tag)) return false;
    s_.set(t1, {c, p, d});
    s_.set(t2, {d, q, c});
    input_[size_t(t1)] = s_.tri[size_t(t1)];
    input_[size_t(t2)] = s_.tri[size_t(t2)];
    for (int32_t t : {t1, t2})
      if (size_t(t) < done_.size()) done_[size_t(t)] = 0;
    flipped_.insert(edge_key(c, d));
    flipped_edges_.insert(flipped_edges_.end(), {c, d});
    ++surface_flips_;
    return true;
  }

  // Steiner point on surface edge (a, b).
  Status split(int32_t a, int32_t b) {
    if (steiner_ >= max_steiner_)
      return Status::Error("boundary recovery: Steiner point limit (" +
                           std::to_string(max_steiner_) + ") reached");
    auto it = s_.edges.find(edge_key(a, b));
    for (int32_t t : it->second)
      if (t >= 0) unconstrain_face(s_.tri[size_t(t)]);
    double m[3];
    split_point(a, b, m);
    int32_t hint = d_.find_edge(a, b);
    if (hint < 0) hint = d_.vertex_tet(a);
    // With flips, the faces recovered so far are kept (the cavity stops at
    // them); without, the triangulation stays Delaunay (conforming).
    auto r = d_.insert(m, hint, flips_);
    // Blocked (not star-shaped within the recovered faces), or just outside
    // the hull (the midpoint of a hull edge, rounded): insert ignoring the
    // constraints; the faces it removes are recovered again.
    if (r.status == Delaunay3D::InsertStatus::kBlocked ||
        r.status == Delaunay3D::InsertStatus::kOutsideHull) {
      r = d_.insert(m, hint, false);
      rescan_ = true;
    }
    if (!flips_) rescan_ = true;  // Delaunay insertions ignore the constraints
    if (r.status == Delaunay3D::InsertStatus::kDuplicate)
      return Status::Error("boundary recovery: vertex " + std::to_string(r.vertex) +
                           " lies on surface edge (" + std::to_string(a) + ", " +
                           std::to_string(b) + ") (degenerate or self-intersecting surface)");
    if (r.status != Delaunay3D::InsertStatus::kInserted)
      return Status::Error("boundary recovery: cannot insert a Steiner point on edge (" +
                           std::to_string(a) + ", " + std::to_string(b) + ") (status " +
                           std::to_string(int(r.status)) + ")");
    auto on = s_.edges.find(edge_key(a, b))->second;
    s_.split_edge(a, b, r.vertex);
    for (int32_t t : on)
      if (t >= 0 && size_t(t) < done_.size()) done_[size_t(t)] = 0;  // new pieces are appended
    ++steiner_;
    return Status::Ok();
  }

  Delaunay3D d_;
  Surface s_;
  RecoveryOptions o_;
  bool flips_;
  int64_t max_steiner_;
  int32_t num_input_;
  int64_t steiner_ = 0;
  std::vector<uint8_t> done_;  // per surface triangle: a constrained face
  bool rescan_ = false;
  std::vector<int32_t> around_, ring_tets_, ring_;
  std::vector<Crossing> walk_;
  std::unordered_set<uint64_t> tried_along_;  // edges whose flips along were tried
  int64_t recovered_along_ = 0;
  std::vector<Tri> input_;                // the input triangles, surface flips applied
  const std::vector<int32_t>* tags_;      // per input triangle
  std::unordered_set<uint64_t> flipped_;  // edges surface flips made
  int64_t surface_flips_ = 0;
  std::vector<int32_t> flipped_edges_;  // the edges surface flips made, in order
};

// Phase 1 for one attempt: the kernel and the surface.
Result<Recovery> start(const std::vector<double>& points, const std::vector<int32_t>& triangles,
                       const std::vector<int32_t>& parents, const std::vector<int32_t>& tags,
                       const RecoveryOptions& options, bool flips, int64_t max_steiner) {
  auto built = Delaunay3D::build(points);
  if (!built.ok()) return Result<Recovery>::Error("boundary recovery: " + built.message());
  for (int32_t v : triangles)
    if (built.value().duplicate_of(v) >= 0)
      return Result<Recovery>::Error("surface: vertices " + std::to_string(v) + " and " +
                                     std::to_string(built.value().duplicate_of(v)) +
                                     " are at the same position");
  Surface s;
  s.edges.reserve(triangles.size());
  for (size_t t = 0; t < triangles.size() / 3; ++t)
    s.add({triangles[3 * t], triangles[3 * t + 1], triangles[3 * t + 2]}, parents[t]);
  return Recovery(std::move(built.value()), std::move(s), options, flips, max_steiner, tags);
}

// Phase 4: inside/outside by a layered flood fill from the ghosts: crossing
// a constrained face increments the depth; odd depth is inside.
Status classify(Delaunay3D& d) {
  const int32_t cap = int32_t(d.tet_capacity());
  std::vector<int32_t> depth(size_t(cap), -1), layer, next;
  for (int32_t t = 0; t < cap; ++t)
    if (d.is_live(t) && d.is_ghost(t)) {
      depth[size_t(t)] = 0;
      layer.push_back(t);
    }
  for (int32_t level = 0; !layer.empty(); ++level) {
    for (size_t i = 0; i < layer.size(); ++i) {
      const int32_t t = layer[i];
      for (int k = 0; k < 4; ++k) {
        const int32_t u = d.neighbor(t, k) >> 2;
        if (depth[size_t(u)] >= 0) continue;
        if (d.is_constrained(t, k)) {
          next.push_back(u);
        } else {
          depth[size_t(u)] = level;
          layer.push_back(u);
        }
      }
    }
    layer.clear();
    for (int32_t u : next)
      if (depth[size_t(u)] < 0) {
        depth[size_t(u)] = level + 1;
        layer.push_back(u);
      }
    next.clear();
  }
  for (int32_t t = 0; t < cap; ++t) {
    if (!d.is_live(t)) continue;
    d.set_tag(t, depth[size_t(t)] % 2 == 1 ? kInsideTag : kOutsideTag);
    for (int k = 0; k < 4; ++k)
      if (d.is_constrained(t, k) &&
          depth[size_t(t)] % 2 == depth[size_t(d.neighbor(t, k) >> 2)] % 2)
        return Status::Error("boundary recovery: a surface face has the same region on both sides");
  }
  return Status::Ok();
}

}  // namespace

Result<RecoveredVolume> recover_boundary(const std::vector<double>& points,
                                         const std::vector<int32_t>& triangles,
                                         const std::vector<int32_t>& tags,
                                         const RecoveryOptions& options) {
  using R = Result<RecoveredVolume>;
  if (Status st = validate(points, triangles, tags); !st.ok()) return R(st);
  const size_t nt = triangles.size() / 3;
  const int64_t max_steiner =
      options.max_steiner_points >= 0 ? options.max_steiner_points : int64_t(nt) + 1000;
  std::vector<int32_t> parents(nt);
  for (size_t t = 0; t < nt; ++t) parents[t] = int32_t(t);

  // Phases 1-2, then 3 if they stall.
  RecoveredVolume out;
  auto attempt = start(points, triangles, parents, tags, options, options.use_flips, max_steiner);
  if (!attempt.ok()) return R(attempt.status());
  Status st = attempt.value().run();
  if (!st.ok() && options.use_flips) {
    auto fresh = start(points, triangles, parents, tags, options, false, max_steiner);
    if (!fresh.ok()) return R(fresh.status());
    attempt = std::move(fresh);
    out.used_fallback = true;
    out.fallback_reason = st.message();
    st = attempt.value().run();
    if (!st.ok()) st = Status::Error(st.message() + " (with flips: " + out.fallback_reason + ")");
  }
  if (!st.ok()) return R(st);
  Recovery& rec = attempt.value();
  Delaunay3D& d = rec.kernel();
  if (Status c = classify(d); !c.ok()) return R(c);

  // Output.
  out.steiner_points = rec.steiner();
  out.edges_recovered_along = rec.recovered_along();
  out.surface_flips = rec.surface_flips();
  out.flipped_edges = rec.flipped_edges();
  for (const Tri& t : rec.input())
    out.input_triangles.insert(out.input_triangles.end(), t.begin(), t.end());
  out.flips = d.stats().flips;
  out.mesh.points = d.points();
  d.for_each_finite_tet([&](int32_t t) {
    if (d.tag(t) != kInsideTag) return;
    out.mesh.tets.insert(out.mesh.tets.end(), d.tet(t), d.tet(t) + 4);
    out.mesh.tet_region.push_back(0);
  });
  const Surface& s = rec.surface();
  for (size_t t = 0; t < s.tri.size(); ++t) {
    out.mesh.triangles.insert(out.mesh.triangles.end(), s.tri[t].begin(), s.tri[t].end());
    out.mesh.triangle_tag.push_back(tags[size_t(s.parent[t])]);
    out.triangle_parent.push_back(s.parent[t]);
  }
  out.kernel = std::move(d);
  return out;
}

}  // namespace vm
