// The working triangulation of the 2D meshers: triangles with neighbor and
// constraint links inside a large enclosing triangle, with Lawson point
// insertion, edge flips, Sloan segment recovery and region classification.
// Internal to mesh2d/ (constrained_delaunay.cpp, delaunay_refinement.cpp);
// the algorithms are described at the top of constrained_delaunay.cpp.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <deque>
#include <utility>
#include <vector>

#include "core/geom/predicates.h"
#include "core/mesh2d/constrained_delaunay.h"
#include "core/util/result.h"

namespace vm::detail {

struct Tri {
  std::array<int32_t, 3> v;  // counterclockwise
  std::array<int32_t, 3> n;  // n[k]: neighbor across the edge opposite v[k]
  std::array<uint8_t, 3> c;  // c[k]: that edge is a constraint
  uint8_t in = 0;            // inside the domain (after classify_regions)
};

inline int next3(int k) { return k == 2 ? 0 : k + 1; }
inline int prev3(int k) { return k == 0 ? 2 : k - 1; }

class Triangulation {
 public:
  explicit Triangulation(std::vector<double> pts) : p_(std::move(pts)) {}

  const double* pt(int32_t v) const { return &p_[2 * size_t(v)]; }
  size_t num_points() const { return p_.size() / 2; }

  /// Adds the enclosing triangle (vertices appended to the point list).
  void init_super(double cx, double cy, double size) {
    super_ = int32_t(num_points());
    const double pts[3][2] = {
        {cx - 20 * size, cy - 20 * size}, {cx + 20 * size, cy - 20 * size}, {cx, cy + 20 * size}};
    for (auto& q : pts) p_.insert(p_.end(), {q[0], q[1]});
    tris_.push_back({{super_, super_ + 1, super_ + 2}, {-1, -1, -1}, {0, 0, 0}, 0});
    vtri_.assign(num_points(), -1);
    for (int k = 0; k < 3; ++k) vtri_[super_ + k] = 0;
  }

  bool is_super(int32_t v) const { return v >= super_ && v < super_ + 3; }

  /// Inserts point v; returns v, or the vertex it coincides with.
  int32_t insert(int32_t v) {
    int32_t t = locate(pt(v));
    Tri& T = tris_[t];
    int zero = -1, zeros = 0;
    for (int k = 0; k < 3; ++k) {
      if (orient2d(pt(T.v[next3(k)]), pt(T.v[prev3(k)]), pt(v)) == 0) {
        zero = k;
        ++zeros;
      }
    }
    if (zeros >= 2) {  // on a vertex: the one shared by the two zero edges
      for (int k = 0; k < 3; ++k)
        if (pt(T.v[k])[0] == pt(v)[0] && pt(T.v[k])[1] == pt(v)[1]) return T.v[k];
    }
    if (zeros == 1)
      split_edge(t, zero, v);
    else
      split_triangle(t, v);
    legalize();
    return v;
  }

  /// Makes segment (a, b) an edge, splitting it at collinear vertices.
  /// Returns false if it crosses an existing constraint.
  bool recover(int32_t a, int32_t b) {
    std::vector<std::pair<int32_t, int32_t>> todo = {{a, b}};
    while (!todo.empty()) {
      auto [s, e] = todo.back();
      todo.pop_back();
      if (s == e) continue;
      int32_t t, k;
      if (find_edge(s, e, t, k)) {
        mark_constraint(t, k);
        continue;
      }
      // Walk from s toward e collecting the crossed edges.
      std::deque<std::pair<int32_t, int32_t>> crossing;  // vertex pairs
      int32_t on_segment = -1;
      if (!crossed_edges(s, e, crossing, on_segment)) return false;
      if (on_segment >= 0) {  // a vertex lies on the segment: split there
        todo.push_back({on_segment, e});
        todo.push_back({s, on_segment});
        continue;
      }
      // Sloan: flip crossing edges of convex quads until none crosses.
      size_t stall = 0;
      while (!crossing.empty()) {
        auto [u, w] = crossing.front();
        crossing.pop_front();
        int32_t tt, kk;
        if (!find_edge(u, w, tt, kk)) continue;
        const Tri& T = tris_[tt];
        int32_t x = T.v[kk];
        int jj = opposite_index(T.n[kk], tt);
        if (jj < 0) return false;
        int32_t y = tris_[T.n[kk]].v[jj];
        // Convex quad x, u, y, w (strictly): the flip is valid.
        if (orient2d(pt(x), pt(y), pt(u)) * orient2d(pt(x), pt(y), pt(w)) < 0 &&
            orient2d(pt(u), pt(w), pt(x)) * orient2d(pt(u), pt(w), pt(y)) < 0) {
          flip(tt, kk);
          stall = 0;
          // The new edge (x, y) may still cross the segment.
          if (x != s && x != e && y != s && y != e && crosses(s, e, x, y))
            crossing.push_back({x, y});
        } else {
          crossing.push_back({u, w});
          if (++stall > 4 * crossing.size() + 16) return false;
        }
      }
      if (!find_edge(s, e, t, k)) return false;
      mark_constraint(t, k);
    }
    return true;
  }

  /// Flips unconstrained non-Delaunay edges until none is left.
  void make_delaunay() {
    for (int32_t t = 0; t < int32_t(tris_.size()); ++t)
      for (int k = 0; k < 3; ++k) stack_.push_back({t, k});
    legalize();
  }

  /// Marks each triangle inside the domain (odd number of constraints
  /// crossed from the enclosing triangle) or outside.
  void classify_regions() {
    std::vector<int> depth(tris_.size(), -1);
    std::vector<int32_t> layer, next_layer;
    for (int32_t t = 0; t < int32_t(tris_.size()); ++t)
      if (has_super_vertex(t)) {
        depth[t] = 0;
        layer.push_back(t);
      }
    for (int d = 0; !layer.empty(); ++d) {
      // Spread within the layer across unconstrained edges, collect the
      // triangles across constraints for the next layer.
      for (size_t i = 0; i < layer.size(); ++i) {
        const Tri& T = tris_[layer[i]];
        for (int k = 0; k < 3; ++k) {
          int32_t u = T.n[k];
          if (u < 0 || depth[u] >= 0) continue;
          if (T.c[k]) {
            next_layer.push_back(u);
          } else {
            depth[u] = d;
            layer.push_back(u);
          }
        }
      }
      layer.clear();
      for (int32_t u : next_layer)
        if (depth[u] < 0) {
          depth[u] = d + 1;
          layer.push_back(u);
        }
      next_layer.clear();
    }
    for (size_t t = 0; t < tris_.size(); ++t) tris_[t].in = depth[t] % 2 == 1;
  }

  /// Vertex triples of the inside triangles (classify_regions first).
  std::vector<int32_t> inside_triangles() const {
    std::vector<int32_t> out;
    for (int32_t t = 0; t < int32_t(tris_.size()); ++t)
      if (tris_[t].in && !has_super_vertex(t))
        out.insert(out.end(), tris_[t].v.begin(), tris_[t].v.end());
    return out;
  }

  bool has_super_vertex(int32_t t) const {
    const Tri& T = tris_[t];
    return is_super(T.v[0]) || is_super(T.v[1]) || is_super(T.v[2]);
  }

  size_t num_triangles() const { return tris_.size(); }
  const Tri& tri(int32_t t) const { return tris_[t]; }

  /// Appends a point (not yet inserted); returns its index.
  int32_t add_point(double x, double y) {
    p_.insert(p_.end(), {x, y});
    vtri_.push_back(-1);
    return int32_t(num_points() - 1);
  }

  /// The triangle containing q (walk from the last located one).
  int32_t find_triangle(const double* q) { return locate(q); }

  const std::vector<double>& points() const { return p_; }

  /// While set, every triangle created or changed is appended to `log`.
  void set_touched_log(std::vector<int32_t>* log) { touched_ = log; }

  std::vector<int32_t> all_real_triangles() const {
    std::vector<int32_t> out;
    for (const Tri& T : tris_)
      if (!is_super(T.v[0]) && !is_super(T.v[1]) && !is_super(T.v[2]))
        out.insert(out.end(), T.v.begin(), T.v.end());
    return out;
  }

 private:
  void set(int32_t t, const Tri& T) {
    if (touched_) touched_->push_back(t);
    tris_[t] = T;
    for (int32_t v : T.v) vtri_[v] = t;
  }

  int opposite_index(int32_t t, int32_t neighbor) const {
    for (int k = 0; k < 3; ++k)
      if (tris_[t].n[k] == neighbor) return k;
    return -1;
  }

  void relink(int32_t t, int32_t from, int32_t to) {
    if (t < 0) return;
    for (int k = 0; k < 3; ++k)
      if (tris_[t].n[k] == from) tris_[t].n[k] = to;
  }

  // Stochastic visibility walk (Devillers, Pion, Teillaud 2002).
  int32_t locate(const double* q) {
    int32_t t = last_ >= 0 && last_ < int32_t(tris_.size()) ? last_ : 0;
    for (size_t steps = 0; steps < 4 * tris_.size() + 64; ++steps) {
      const Tri& T = tris_[t];
      int start = int(rng_() % 3);
      int32_t go = -1;
      for (int i = 0; i < 3 && go < 0; ++i) {
        int k = (start + i) % 3;
        if (orient2d(pt(T.v[next3(k)]), pt(T.v[prev3(k)]), q) < 0) go = T.n[k];
      }
      if (go < 0) return last_ = t;
      t = go;
    }
    // Fallback (never expected): scan.
    for (int32_t s = 0; s < int32_t(tris_.size()); ++s) {
      const Tri& T = tris_[s];
      bool inside = true;
      for (int k = 0; k < 3 && inside; ++k)
        inside = orient2d(pt(T.v[next3(k)]), pt(T.v[prev3(k)]), q) >= 0;
      if (inside) return last_ = s;
    }
    return last_ = 0;
  }

  void split_triangle(int32_t t, int32_t p) {
    const Tri T = tris_[t];
    const int32_t t1 = int32_t(tris_.size()), t2 = t1 + 1;
    tris_.resize(tris_.size() + 2);
    set(t, {{p, T.v[1], T.v[2]}, {T.n[0], t1, t2}, {T.c[0], 0, 0}, T.in});
    set(t1, {{p, T.v[2], T.v[0]}, {T.n[1], t2, t}, {T.c[1], 0, 0}, T.in});
    set(t2, {{p, T.v[0], T.v[1]}, {T.n[2], t, t1}, {T.c[2], 0, 0}, T.in});
    relink(T.n[1], t, t1);
    relink(T.n[2], t, t2);
    stack_.insert(stack_.end(), {{t, 0}, {t1, 0}, {t2, 0}});
  }

  // p lies on the edge opposite vertex k of t.
  void split_edge(int32_t t, int k, int32_t p) {
    const Tri T = tris_[t];
    const int32_t a = T.v[k], b = T.v[next3(k)], c = T.v[prev3(k)];
    const int32_t u = T.n[k];
    const uint8_t cbc = T.c[k];
    const int32_t Nb = T.n[next3(k)], Nc = T.n[prev3(k)];
    const uint8_t cNb = T.c[next3(k)], cNc = T.c[prev3(k)];
    const int32_t t1 = int32_t(tris_.size());
    tris_.resize(tris_.size() + 1);
    if (u < 0) {  // hull edge (only possible on the enclosing triangle)
      set(t, {{a, b, p}, {-1, t1, Nc}, {cbc, 0, cNc}, T.in});
      set(t1, {{a, p, c}, {-1, Nb, t}, {cbc, cNb, 0}, T.in});
      relink(Nb, t, t1);
      stack_.insert(stack_.end(), {{t, 2}, {t1, 1}});
      return;
    }
    const Tri U = tris_[u];
    const int j = opposite_index(u, t);
    if (j < 0) return;  // broken adjacency: cannot happen
    const int32_t d = U.v[j];
    const int32_t Mc = U.n[next3(j)], Mb = U.n[prev3(j)];  // opposite c, b in u
    const uint8_t cMc = U.c[next3(j)], cMb = U.c[prev3(j)];
    const int32_t u1 = int32_t(tris_.size());
    tris_.resize(tris_.size() + 1);
    set(t, {{a, b, p}, {u1, t1, Nc}, {cbc, 0, cNc}, T.in});
    set(t1, {{a, p, c}, {u, Nb, t}, {cbc, cNb, 0}, T.in});
    set(u, {{d, c, p}, {t1, u1, Mb}, {cbc, 0, cMb}, U.in});
    set(u1, {{d, p, b}, {t, Mc, u}, {cbc, cMc, 0}, U.in});
    relink(Nb, t, t1);
    relink(Mc, u, u1);
    stack_.insert(stack_.end(), {{t, 2}, {t1, 1}, {u, 2}, {u1, 1}});
  }

  // Flips the edge opposite vertex k of t (the quad must be convex).
  void flip(int32_t t, int k) {
    const Tri T = tris_[t];
    const int32_t u = T.n[k];
    const Tri U = tris_[u];
    const int j = opposite_index(u, t);
    if (j < 0) return;  // broken adjacency: cannot happen
    const int32_t P = T.v[k], A = T.v[next3(k)], B = T.v[prev3(k)], Q = U.v[j];
    const int32_t N1 = T.n[next3(k)], N2 = T.n[prev3(k)];  // opposite A, B in t
    const uint8_t c1 = T.c[next3(k)], c2 = T.c[prev3(k)];
    const int32_t M1 = U.n[next3(j)], M2 = U.n[prev3(j)];  // opposite B, A in u
    const uint8_t d1 = U.c[next3(j)], d2 = U.c[prev3(j)];
    // An unconstrained edge never separates regions: both share T.in.
    set(t, {{P, A, Q}, {M1, u, N2}, {d1, 0, c2}, T.in});
    set(u, {{Q, B, P}, {N1, t, M2}, {c1, 0, d2}, T.in});
    relink(N1, t, u);
    relink(M1, u, t);
  }

  // Lawson: pops (t, k) and flips the edge opposite v[k] when the vertex
  // across it lies strictly inside t's circumcircle.
  void legalize() {
    while (!stack_.empty()) {
      auto [t, k] = stack_.back();
      stack_.pop_back();
      const Tri& T = tris_[t];
      int32_t u = T.n[k];
      if (u < 0 || T.c[k]) continue;
      int j = opposite_index(u, t);
      if (j < 0) continue;
      int32_t q = tris_[u].v[j];
      if (incircle(pt(T.v[0]), pt(T.v[1]), pt(T.v[2]), pt(q)) <= 0) continue;
      flip(t, k);
      // The two outer edges of the new triangles may now be illegal.
      stack_.insert(stack_.end(), {{t, 0}, {t, 2}, {u, 0}, {u, 2}});
    }
  }

  // Finds the triangle t with edge (a, b) (either direction) opposite v[k].
  bool find_edge(int32_t a, int32_t b, int32_t& t, int32_t& k) const {
    int32_t start = vtri_[a];
    int32_t cur = start;
    // Rotate around a; a is interior (enclosing triangle), so the loop closes.
    for (size_t guard = 0; guard < tris_.size() + 1; ++guard) {
      const Tri& T = tris_[cur];
      int ia = -1;
      for (int i = 0; i < 3; ++i)
        if (T.v[i] == a) ia = i;
      if (ia < 0) return false;
      if (T.v[next3(ia)] == b) {
        t = cur;
        k = prev3(ia);
        return true;
      }
      if (T.v[prev3(ia)] == b) {
        t = cur;
        k = next3(ia);
        return true;
      }
      int32_t nx = T.n[next3(ia)];  // across edge (v[prev], a)
      if (nx < 0 || nx == start) return false;
      cur = nx;
    }
    return false;
  }

  void mark_constraint(int32_t t, int32_t k) {
    tris_[t].c[k] = 1;
    int32_t u = tris_[t].n[k];
    if (u >= 0) tris_[u].c[opposite_index(u, t)] = 1;
  }

  // Do segments (s, e) and (x, y) cross at a point interior to both?
  bool crosses(int32_t s, int32_t e, int32_t x, int32_t y) const {
    double o1 = orient2d(pt(s), pt(e), pt(x)), o2 = orient2d(pt(s), pt(e), pt(y));
    double o3 = orient2d(pt(x), pt(y), pt(s)), o4 = orient2d(pt(x), pt(y), pt(e));
    return o1 * o2 < 0 && o3 * o4 < 0;
  }

  // Edges crossed by segment (s, e), walking from s. Sets on_segment to a
  // vertex lying strictly inside the segment if one is met first. Returns
  // false if a crossed edge is a constraint (crossing segments).
  bool crossed_edges(int32_t s, int32_t e, std::deque<std::pair<int32_t, int32_t>>& out,
                     int32_t& on_segment) const {
    // The triangle around s whose opposite edge the segment passes through.
    int32_t start = vtri_[s], cur = start, t = -1, k = -1;
    for (size_t guard = 0; guard < tris_.size() + 1; ++guard) {
      const Tri& T = tris_[cur];
      int is = 0;
      while (T.v[is] != s) ++is;
      int32_t l = T.v[next3(is)], r = T.v[prev3(is)];
      double ol = orient2d(pt(s), pt(e), pt(l)), or_ = orient2d(pt(s), pt(e), pt(r));
      if (ol == 0 && dot_ahead(s, e, l)) {
        on_segment = l;
        return true;
      }
      if (or_ == 0 && dot_ahead(s, e, r)) {
        on_segment = r;
        return true;
      }
      if (ol < 0 && or_ > 0) {
        t = cur;
        k = is;
        break;
      }
      cur = T.n[next3(is)];
      if (cur < 0 || cur == start) return false;
    }
    if (t < 0) return false;
    // Cross triangles until e.
    for (size_t guard = 0; guard < tris_.size() + 1; ++guard) {
      const Tri& T = tris_[t];
      int32_t a = T.v[next3(k)], b = T.v[prev3(k)];
      if (T.c[k]) return false;
      out.push_back({a, b});
      int32_t u = T.n[k];
      const Tri& U = tris_[u];
      int j = opposite_index(u, t);
      if (j < 0) return false;
      int32_t w = U.v[j];
      if (w == e) return true;
      double ow = orient2d(pt(s), pt(e), pt(w));
      if (ow == 0) {
        on_segment = w;
        out.clear();
        return true;
      }
      // Leave u = (w, b, a) by the edge joining a right vertex to a left one:
      // a is right of s->e and b left, so w left means edge (a, w), opposite
      // b; w right means edge (w, b), opposite a.
      t = u;
      k = ow > 0 ? index_of(U, b) : index_of(U, a);
    }
    return false;
  }

  static int index_of(const Tri& T, int32_t v) {
    for (int i = 0; i < 3; ++i)
      if (T.v[i] == v) return i;
    return -1;
  }

  // Is v (collinear with s, e) strictly between s and e?
  bool dot_ahead(int32_t s, int32_t e, int32_t v) const {
    double dx = pt(e)[0] - pt(s)[0], dy = pt(e)[1] - pt(s)[1];
    double t = (pt(v)[0] - pt(s)[0]) * dx + (pt(v)[1] - pt(s)[1]) * dy;
    return t > 0 && t < dx * dx + dy * dy;
  }

  std::vector<double> p_;
  std::vector<Tri> tris_;
  std::vector<int32_t> vtri_;
  std::vector<std::pair<int32_t, int>> stack_;
  std::vector<int32_t>* touched_ = nullptr;
  int32_t super_ = 0;
  int32_t last_ = -1;
  uint64_t state_ = 0x9E3779B97F4A7C15ULL;
  uint64_t rng_() {
    state_ ^= state_ << 13;
    state_ ^= state_ >> 7;
    state_ ^= state_ << 17;
    return state_;
  }
};

/// Circle through three points (center cx, cy; squared radius r2).
struct Circle {
  double cx, cy, r2;
};

/// Circumcircle of a non-degenerate triangle (infinite for a flat one).
inline Circle circumcircle(const double* a, const double* b, const double* c) {
  double bx = b[0] - a[0], by = b[1] - a[1], cx = c[0] - a[0], cy = c[1] - a[1];
  double d = 2 * (bx * cy - by * cx);
  double b2 = bx * bx + by * by, c2 = cx * cx + cy * cy;
  double ux = (cy * b2 - by * c2) / d, uy = (bx * c2 - cx * b2) / d;
  return {a[0] + ux, a[1] + uy, ux * ux + uy * uy};
}

/// Does q lie on or inside the diametral circle of a constrained edge of
/// triangle s or of its neighbors?
inline bool encroaches(const Triangulation& tr, int32_t s, const double* q) {
  int32_t around[4] = {s, tr.tri(s).n[0], tr.tri(s).n[1], tr.tri(s).n[2]};
  for (int32_t t : around) {
    if (t < 0) continue;
    const auto& T = tr.tri(t);
    for (int k = 0; k < 3; ++k) {
      if (!T.c[k]) continue;
      const double *a = tr.pt(T.v[(k + 1) % 3]), *b = tr.pt(T.v[(k + 2) % 3]);
      if ((q[0] - a[0]) * (q[0] - b[0]) + (q[1] - a[1]) * (q[1] - b[1]) <= 0) return true;
    }
  }
  return false;
}

/// The output of a mesher: the input points (same indices), then the
/// inserted ones (which follow the enclosing triangle's three in `tr`), and
/// the inside triangles.
inline Mesh2D extract_mesh(const Triangulation& tr, const std::vector<double>& points) {
  Mesh2D out;
  out.points = points;
  const size_t n_input = points.size() / 2;
  std::vector<int32_t> remap(tr.num_points(), -1);
  for (size_t i = 0; i < n_input; ++i) remap[i] = int32_t(i);
  for (size_t i = n_input + 3; i < tr.num_points(); ++i) {
    remap[i] = int32_t(out.points.size() / 2);
    out.points.insert(out.points.end(), {tr.pt(int32_t(i))[0], tr.pt(int32_t(i))[1]});
  }
  for (int32_t v : tr.inside_triangles()) out.triangles.push_back(remap[v]);
  return out;
}

/// Builds the constrained Delaunay triangulation of `points` and `segments`
/// into `tr` and classifies its regions (constrained_delaunay.cpp). On
/// success `alias[i]` is the vertex point i was merged into (itself unless a
/// duplicate).
Status build_constrained(const std::vector<double>& points, const std::vector<int32_t>& segments,
                         Triangulation& tr, std::vector<int32_t>& alias);

}  // namespace vm::detail
