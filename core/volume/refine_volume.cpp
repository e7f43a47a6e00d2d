// Edge-based volume refinement (Marot, Pellerin and Remacle 2019, section
// 4; front-like order after Frey, Borouchaki and George 1998); see
// refine_volume.h.
//
// Phases: (1) checks: sizes, options, the region closed by constrained
// faces; (2) the first layer: over each boundary face the apex of the
// regular tetrahedron of its size, in BRIO order, each candidate tested
// as below; (3) the queue: the first layer, then the region's vertices,
// each part along a Hilbert curve; (4) for each queued vertex v, its edges
// (v, w) in the current mesh, longest first (metric length, ties by
// vertex id): an edge of metric length >= split_length gets one candidate
// (the metric midpoint when shorter than kFarLength, else one unit of h
// from v). A candidate is rejected when it lies outside the region,
// closer than min_spacing * h to a vertex of v's star, of the tetrahedron
// containing it or of that tetrahedron's neighbors, closer than
// boundary_spacing * h to a constrained face of those tetrahedra, or
// closer than min_spacing * h to a vertex of its cavity (checked by the
// kernel before it changes anything); else it is inserted at once
// (constrained cavity) and queued. Metric lengths use h linear along the
// edge between its ends.
//
// Phases 2 and 4 run in rounds (HXT's parallel insertion, section 4 of the
// same paper): the round's items (first-layer points, queued vertices) are
// cut into slabs of equal count along one axis, and each slab works
// through its items (and the vertices it inserts, in phase 4) at the same
// time as the others, in the kernel's partitioned mode
// (Delaunay3D::begin_partitions): it only walks and replaces tetrahedra
// whose vertices are all in its slab. An item that needs more is deferred
// to the next round, whose slabs cut along the next axis; the last round
// is sequential. A slab's vertices are budgeted (3 per front item); when
// one spends its budget with work left, another round follows with the
// budget doubled (a core much finer than the wall, where each front vertex
// fills a larger volume, would otherwise leave most of it to the
// sequential round). Slabs, budgets and order depend only on the data, so
// the mesh is the same with any number of threads. In phase 2 the mesh is
// still the boundary triangulation, whose long tetrahedra cross the cuts:
// a point whose cavity reaches one waits (about 6% on the aortic arch with
// two slabs).
#include "core/volume/refine_volume.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <string>
#include <thread>

#include "core/geom/closest_point.h"
#include "core/geom/hilbert_sort.h"
#include "core/util/parallel.h"
#include "core/util/portable_math.h"
#include "core/volume/slabs.h"
#include "core/volume/tet_topology.h"

namespace vm {
namespace {

// Edges at least this long (units of h) get a point one unit from their
// end instead of their midpoint.
constexpr double kFarLength = 2.5;

// A slab's first budget of new vertices per front item in a round (a
// first-layer item gives at most one).
constexpr int64_t kFrontPerItem = 3;

inline double dist2(const double* a, const double* b) {
  const double x = a[0] - b[0], y = a[1] - b[1], z = a[2] - b[2];
  return x * x + y * y + z * z;
}

// Metric length of a segment of length L with h linear from ha to hb.
inline double metric_length(double L, double ha, double hb) {
  const double d = hb - ha;
  if (std::fabs(d) <= 1e-9 * ha) return L / ha;
  return L * pm::log(hb / ha) / d;
}

// An edge (v, w) of the vertex being processed: its length, its metric
// length and a tetrahedron holding it.
struct Edge {
  double L, ell;
  int32_t w, tet;
};

// One slab's state in a round.
struct SlabWork {
  RefineStats st;
  std::vector<int32_t> items;     // the round's work in order (phase 4 appends new vertices)
  std::vector<int32_t> deferred;  // items for the next round
  std::vector<int32_t> fresh;     // phase 2: the vertices inserted
  int32_t budget = INT32_MAX;     // vertices it may insert
  int32_t inserted = 0;
  bool out_of_budget = false;  // it stopped at its budget with work left
  std::vector<int32_t> star, nbs, nb_tet;
  std::vector<Edge> edges;  // front_item(): v's edges, longest first
  std::vector<uint32_t> seen;
  uint32_t stamp = 0;
};

inline void add_stats(RefineStats& to, const RefineStats& s) {
  to.vertices_processed += s.vertices_processed;
  to.candidates += s.candidates;
  to.size_evaluations += s.size_evaluations;
  to.inserted += s.inserted;
  to.rejected_spacing += s.rejected_spacing;
  to.rejected_boundary += s.rejected_boundary;
  to.rejected_outside += s.rejected_outside;
  to.rejected_kernel += s.rejected_kernel;
  to.deferred += s.deferred;
  to.generations = std::max(to.generations, s.generations);
}

// Result of try_insert() besides a new vertex id.
constexpr int32_t kRejected = -1, kDeferred = -2;

class Refiner {
 public:
  Refiner(Delaunay3D& kernel, const VolumeSizeField& field, std::vector<double>& vertex_h,
          const RefineOptions& o)
      : kernel_(kernel),
        field_(field),
        vertex_h_(vertex_h),
        o_(o),
        tag_(o.region_tag),
        g_(field.gradation()),
        min_h_(field.min_size()),
        n_initial_(kernel.num_vertices()) {}

  Status run(RefineStats& st, const ProgressFn& progress);

 private:
  enum class Phase { kFirstLayer, kFront };
  /// Works through `items` on the whole triangulation (no slabs), the
  /// inserted vertices into `fresh` (phase 2).
  Status sequential(Phase phase, std::vector<int32_t> items, RefineStats& st,
                    const ProgressFn& progress, std::vector<int32_t>* fresh);
  /// Phases 2 and 4: the slab rounds, then sequential() for what is left.
  Status slab_rounds(Phase phase, std::vector<int32_t> items, RefineStats& st,
                     const ProgressFn& progress, std::vector<int32_t>* fresh);
  /// Where item `i` of the phase lies.
  const double* item_point(Phase phase, int32_t i) const {
    return phase == Phase::kFirstLayer ? &apex_[3 * size_t(i)] : kernel_.point(i);
  }
  void work(Phase phase, int part, SlabWork& S, const ProgressFn& progress, bool caller);
  /// One item of phase 2 or 4 (part -1: out of a slab round); false when
  /// it must wait for the next round.
  bool first_layer_item(int part, SlabWork& S, int32_t i);
  bool front_item(int part, SlabWork& S, int32_t v);
  int32_t try_insert(int part, SlabWork& S, const double* p, double hp, double hspacing,
                     int32_t hint, int32_t generation);
  /// A tetrahedron of part `part` among t and `around`, or -1.
  int32_t own_hint(int part, int32_t t, const std::vector<int32_t>& around) const;

  Delaunay3D& kernel_;
  const VolumeSizeField& field_;
  std::vector<double>& vertex_h_;
  const RefineOptions& o_;
  const int32_t tag_;
  const double g_, min_h_;
  const size_t n_initial_;           // the kernel's vertices before refinement
  std::vector<int32_t> generation_;  // per vertex: depth in the front
  // Phase 2: per boundary face the apex, its size and the face's vertices.
  std::vector<double> apex_, apex_h_;
  std::vector<int32_t> apex_face_;  // 3 per apex
  // This round's slab of each vertex (kNoPart out of a round).
  std::vector<uint8_t> vpart_;
  std::vector<SlabWork> slabs_;
  // Progress (read on the calling thread only) and cancellation.
  std::atomic<int64_t> done_{0}, queued_{0};
  std::atomic<bool> cancelled_{false};
  double last_fraction_ = 0;
};

int32_t Refiner::own_hint(int part, int32_t t, const std::vector<int32_t>& around) const {
  if (t >= 0 && kernel_.in_part(part, t)) return t;
  for (int32_t u : around)
    if (!kernel_.is_ghost(u) && kernel_.in_part(part, u)) return u;
  return -1;
}

int32_t Refiner::try_insert(int part, SlabWork& S, const double* p, double hp, double hspacing,
                            int32_t hint, int32_t generation) {
  RefineStats& st = S.st;
  const double r2 = o_.min_spacing * o_.min_spacing * hspacing * hspacing;
  const double b2 = o_.boundary_spacing * o_.boundary_spacing * hp * hp;
  const Delaunay3D::Location loc = kernel_.locate_in(part, p, hint);
  if (loc.type == Delaunay3D::LocationType::kForeign) return kDeferred;
  if (kernel_.is_ghost(loc.tet) || kernel_.tag(loc.tet) != tag_) {
    ++st.rejected_outside;
    return kRejected;
  }
  if (loc.type == Delaunay3D::LocationType::kOnVertex) {
    ++st.rejected_spacing;
    return kRejected;
  }
  // The tetrahedron containing p and its neighbors: their vertices and
  // constrained faces.
  bool close = false, near_boundary = false;
  auto check_tet = [&](int32_t t) {
    const int32_t* tv = kernel_.tet(t);
    for (int k = 0; k < 4; ++k) {
      if (tv[k] != Delaunay3D::kInfinite) {
        if (dist2(p, kernel_.point(tv[k])) < r2) close = true;
      }
      if (!kernel_.is_constrained(t, k)) continue;
      const int* f = kFaceOut[k];
      if (tv[f[0]] < 0 || tv[f[1]] < 0 || tv[f[2]] < 0) continue;
      double q[3];
      if (closest_point_on_triangle(p, kernel_.point(tv[f[0]]), kernel_.point(tv[f[1]]),
                                    kernel_.point(tv[f[2]]), q) < b2)
        near_boundary = true;
    }
  };
  check_tet(loc.tet);
  for (int k = 0; k < 4; ++k) {
    const int32_t u = kernel_.neighbor(loc.tet, k) >> 2;
    if (!kernel_.is_ghost(u)) check_tet(u);
  }
  if (close) {
    ++st.rejected_spacing;
    return kRejected;
  }
  if (near_boundary) {
    ++st.rejected_boundary;
    return kRejected;
  }
  // Last, every vertex p would be joined to (its cavity's: after flips
  // or clipped cavities the tetrahedra around p miss some neighbors).
  const Delaunay3D::InsertResult ins =
      kernel_.insert_in(part, p, loc.tet, o_.min_spacing * hspacing);
  if (ins.status == Delaunay3D::InsertStatus::kForeign) return kDeferred;
  if (ins.status == Delaunay3D::InsertStatus::kTooClose) {
    ++st.rejected_spacing;
    return kRejected;
  }
  if (ins.status != Delaunay3D::InsertStatus::kInserted) {
    ++st.rejected_kernel;
    return kRejected;
  }
  const size_t v = size_t(ins.vertex);
  if (v >= vertex_h_.size()) {  // sequential: the kernel appended it
    vertex_h_.resize(v + 1);
    generation_.resize(v + 1);
  }
  vertex_h_[v] = hp;
  generation_[v] = generation;
  st.generations = std::max(st.generations, generation);
  ++st.inserted;
  ++S.inserted;
  return ins.vertex;
}

bool Refiner::first_layer_item(int part, SlabWork& S, int32_t i) {
  // The walk starts from a tetrahedron of a vertex of the face; in a slab
  // round, of one of the slab's (another slab rewrites its own vertices'
  // tetrahedra, never these), else the item waits.
  int32_t a = apex_face_[3 * size_t(i)];
  for (int k = 1; k < 3 && part >= 0 && vpart_[size_t(a)] != part; ++k)
    a = apex_face_[3 * size_t(i) + size_t(k)];
  if (part >= 0 && vpart_[size_t(a)] != part) return false;
  int32_t hint = kernel_.vertex_tet(a);
  if (part >= 0 && !kernel_.in_part(part, hint)) {
    kernel_.tets_around_vertex_in(part, a, S.star);
    hint = own_hint(part, -1, S.star);
    if (hint < 0) return false;
  }
  const double* p = &apex_[3 * size_t(i)];
  const double hf = apex_h_[size_t(i)];
  ++S.st.candidates;
  ++S.st.size_evaluations;
  const double hp = field_.eval(p, hf + g_ * hf, o_.size_tolerance);
  const int32_t v = try_insert(part, S, p, hp, std::min(hp, hf), hint, 1);
  if (v == kDeferred) return false;
  if (v >= 0) S.fresh.push_back(v);
  return true;
}

bool Refiner::front_item(int part, SlabWork& S, int32_t v) {
  RefineStats& st = S.st;
  ++st.vertices_processed;
  kernel_.tets_around_vertex_in(part, v, S.star);
  // Neighbors of v (each once, with a tetrahedron of the edge).
  if (S.seen.size() < kernel_.num_vertices()) S.seen.resize(kernel_.num_vertices(), 0);
  if (++S.stamp == 0) std::fill(S.seen.begin(), S.seen.end(), 0), S.stamp = 1;
  std::vector<int32_t>& nbs = S.nbs;
  nbs.clear();
  S.nb_tet.clear();
  // An inserted vertex's star lies in the region (cavities never cross a
  // constrained face): only the initial vertices' stars need the test.
  const bool initial = size_t(v) < n_initial_;
  for (int32_t t : S.star) {
    if (initial && (kernel_.is_ghost(t) || kernel_.tag(t) != tag_)) continue;
    for (int k = 0; k < 4; ++k) {
      const int32_t w = kernel_.tet(t)[k];
      if (w == v || S.seen[size_t(w)] == S.stamp) continue;
      S.seen[size_t(w)] = S.stamp;
      nbs.push_back(w);
      S.nb_tet.push_back(t);
    }
  }
  const size_t n_nbs = nbs.size();
  // Copies: sequential insertions reallocate the kernel's point array.
  const double xv[3] = {kernel_.point(v)[0], kernel_.point(v)[1], kernel_.point(v)[2]};
  const double hv = vertex_h_[size_t(v)];
  // Longest edge first (ties by vertex id): the kernel's order of the
  // star (the vertices' slots in its tetrahedra) is no good order, and the
  // mesh's quality depended on it.
  S.edges.clear();
  for (size_t i = 0; i < n_nbs; ++i) {
    const double L = std::sqrt(dist2(xv, kernel_.point(nbs[i])));
    S.edges.push_back({L, metric_length(L, hv, vertex_h_[size_t(nbs[i])]), nbs[i], S.nb_tet[i]});
  }
  std::sort(S.edges.begin(), S.edges.end(), [](const Edge& a, const Edge& b) {
    return a.ell != b.ell ? a.ell > b.ell : a.w < b.w;
  });
  for (size_t i = 0; i < n_nbs; ++i) nbs[i] = S.edges[i].w, S.nb_tet[i] = S.edges[i].tet;
  const double split = o_.split_length;
  bool deferred = false;
  for (size_t i = 0; i < n_nbs; ++i) {
    const int32_t w = nbs[i];
    const double* xw = kernel_.point(w);
    const double hw = vertex_h_[size_t(w)];
    const double L = S.edges[i].L, ell = S.edges[i].ell;
    if (ell < split) continue;
    // Distance d of the candidate from v along the edge.
    double d;
    if (ell < kFarLength) {
      const double dh = hw - hv;
      d = std::fabs(dh) <= 1e-9 * hv ? 0.5 * L : L * (std::sqrt(hv * hw) - hv) / dh;
    } else {
      const double gam = std::clamp((hw - hv) / L, -g_, g_);
      d = std::fabs(gam) < 1e-12 ? hv : hv * pm::expm1(gam) / gam;
    }
    const double s = d / L;
    const double p[3] = {xv[0] + s * (xw[0] - xv[0]), xv[1] + s * (xw[1] - xv[1]),
                         xv[2] + s * (xw[2] - xv[2])};
    ++st.candidates;
    // Cheap rejection first: h >= its Lipschitz lower bound from v and w,
    // against v's neighbors (and the points just inserted around v).
    const double lo = std::max({hv - g_ * d, hw - g_ * (L - d), min_h_});
    const double lo2 = o_.min_spacing * o_.min_spacing * lo * lo;
    bool close = dist2(p, xv) < lo2;
    for (size_t j = 0; j < nbs.size() && !close; ++j) close = dist2(p, kernel_.point(nbs[j])) < lo2;
    if (close) {
      ++st.rejected_spacing;
      continue;
    }
    // h is g-Lipschitz and vertex_h holds its values (or upper bounds of
    // them): every neighbor gives an upper bound.
    double ub = std::min(hv + g_ * d, hw + g_ * (L - d));
    for (size_t j = 0; j < nbs.size(); ++j) {
      const double hj = vertex_h_[size_t(nbs[j])];
      if (hj < ub) ub = std::min(ub, hj + g_ * std::sqrt(dist2(p, kernel_.point(nbs[j]))));
    }
    ++st.size_evaluations;
    const double hp = field_.eval(p, ub, o_.size_tolerance);
    const double r2 = o_.min_spacing * o_.min_spacing * hp * hp;
    for (size_t j = 0; j < nbs.size() && !close; ++j) close = dist2(p, kernel_.point(nbs[j])) < r2;
    if (close) {
      ++st.rejected_spacing;
      continue;
    }
    const int32_t hint = own_hint(part, S.nb_tet[i], S.star);
    const int32_t nv =
        hint < 0 ? kDeferred : try_insert(part, S, p, hp, hp, hint, generation_[size_t(v)] + 1);
    if (nv == kDeferred) deferred = true;
    if (nv < 0) continue;
    S.items.push_back(nv);
    queued_.fetch_add(1, std::memory_order_relaxed);
    nbs.push_back(nv);  // checked by the next candidates around v
  }
  return !deferred;
}

void Refiner::work(Phase phase, int part, SlabWork& S, const ProgressFn& progress, bool caller) {
  S.deferred.clear();
  S.fresh.clear();
  S.inserted = 0;
  S.out_of_budget = false;
  for (size_t k = 0; k < S.items.size(); ++k) {
    if ((k & 1023) == 0) {
      if (caller && progress) {
        const double f = double(done_.load(std::memory_order_relaxed)) /
                         double(queued_.load(std::memory_order_relaxed) + 1);
        if (phase == Phase::kFront) last_fraction_ = std::max(last_fraction_, std::min(f, 1.0));
        if (!report_progress(progress, last_fraction_, "refine volume"))
          cancelled_.store(true, std::memory_order_relaxed);
      }
      if (cancelled_.load(std::memory_order_relaxed)) return;
    }
    done_.fetch_add(1, std::memory_order_relaxed);
    const int32_t item = S.items[k];
    if (S.inserted >= S.budget) {  // the rest waits for the next round
      S.deferred.insert(S.deferred.end(), S.items.begin() + ptrdiff_t(k), S.items.end());
      S.out_of_budget = true;
      break;
    }
    if (!(phase == Phase::kFirstLayer ? first_layer_item(part, S, item)
                                      : front_item(part, S, item)))
      S.deferred.push_back(item);
  }
  S.st.deferred += int64_t(S.deferred.size());
}

Status Refiner::sequential(Phase phase, std::vector<int32_t> items, RefineStats& st,
                           const ProgressFn& progress, std::vector<int32_t>* fresh) {
  if (st.inserted >= o_.max_points) {
    st.hit_max_points = !items.empty();
    return Status::Ok();
  }
  SlabWork& S = slabs_.emplace_back();
  S.items = std::move(items);
  S.budget = int32_t(std::min<int64_t>(o_.max_points - st.inserted, INT32_MAX));
  S.st = RefineStats{};
  work(phase, -1, S, progress, true);
  if (cancelled_) return Status::Cancelled();
  if (S.inserted >= S.budget && !S.deferred.empty()) st.hit_max_points = true;
  add_stats(st, S.st);
  st.sequential_inserted += S.st.inserted;
  if (fresh) fresh->insert(fresh->end(), S.fresh.begin(), S.fresh.end());
  slabs_.pop_back();
  return Status::Ok();
}

Status Refiner::slab_rounds(Phase phase, std::vector<int32_t> items, RefineStats& st,
                            const ProgressFn& progress, std::vector<int32_t>* fresh) {
  const int parts = o_.parts;
  if (phase == Phase::kFront) {
    done_ = 0;  // the progress fraction counts the front's work only
    queued_ = int64_t(items.size());
  }
  // Vertex budget per item: a front vertex gives a few new ones (the
  // front grows into the volume), a first-layer item at most one. A round
  // in which a slab spent its budget with work left (a core much finer
  // than the wall: each front vertex fills a larger volume) adds a round,
  // with the budget doubled, up to o_.budget_rounds of them.
  int64_t per_item = phase == Phase::kFirstLayer ? 1 : kFrontPerItem;
  int budget_rounds = 0;
  for (int round = 0; round < o_.rounds + budget_rounds && parts > 1 &&
                      items.size() >= size_t(std::max(o_.min_slab_items, 1)) * size_t(parts);
       ++round) {
    if (st.inserted >= o_.max_points) break;
    const int64_t room = o_.max_points - st.inserted;
    // Slabs of equal item count along axis round % 3.
    const int axis = round % 3;
    std::vector<double> xs(items.size());
    for (size_t i = 0; i < items.size(); ++i) xs[i] = item_point(phase, items[i])[axis];
    const Slabs slabs = equal_count_slabs(xs, axis, size_t(parts));
    auto slab_of = [&](const double* x) { return slabs.of(x); };
    const size_t n0 = kernel_.num_vertices();
    vpart_.assign(n0, Delaunay3D::kNoPart);
    for (size_t v = 0; v < n0; ++v)
      if (kernel_.vertex_tet(int32_t(v)) >= 0)
        vpart_[v] = uint8_t(slab_of(kernel_.point(int32_t(v))));
    slabs_.resize(size_t(parts));
    for (SlabWork& S : slabs_) S.items.clear(), S.st = RefineStats{};
    for (int32_t v : items) slabs_[size_t(slab_of(item_point(phase, v)))].items.push_back(v);
    // Budgets: per_item vertices an item, and fresh tetrahedra for them (a
    // new vertex makes about 6.7), within max_points. A doubled budget
    // stays within the slab's share of the vertices so far (the mesh at
    // most doubles in a round, so do its arrays).
    const int64_t tets_per_vertex = phase == Phase::kFirstLayer ? 5 : 7;
    std::vector<Delaunay3D::PartBudget> budgets(static_cast<size_t>(parts));
    int64_t total = 0;
    for (int j = 0; j < parts; ++j) {
      const int64_t n = int64_t(slabs_[size_t(j)].items.size());
      const int64_t share = int64_t(n0) * n / int64_t(items.size());
      const int64_t wanted = std::min(per_item * n, std::max(kFrontPerItem * n, share)) + 256;
      budgets[size_t(j)].vertices = int32_t(std::min<int64_t>(wanted, room));
      total += budgets[size_t(j)].vertices;
    }
    for (int j = 0; j < parts; ++j) {
      Delaunay3D::PartBudget& b = budgets[size_t(j)];
      if (total > room) b.vertices = int32_t(int64_t(b.vertices) * room / total);
      slabs_[size_t(j)].budget = b.vertices;
      b.tets = int32_t(tets_per_vertex * b.vertices + 4096);
    }
    kernel_.begin_partitions(vpart_, budgets);
    vertex_h_.resize(kernel_.num_vertices());
    generation_.resize(kernel_.num_vertices());
    const std::thread::id caller = std::this_thread::get_id();
    parallel_for(size_t(parts), 1, [&](size_t begin, size_t end) {
      const bool on_caller = std::this_thread::get_id() == caller;
      for (size_t j = begin; j < end; ++j) work(phase, int(j), slabs_[j], progress, on_caller);
    });
    // Back to consecutive vertex ids.
    const std::vector<int32_t> remap = kernel_.end_partitions();
    for (size_t k = 0; k < remap.size(); ++k) {
      if (remap[k] < 0) continue;
      vertex_h_[size_t(remap[k])] = vertex_h_[n0 + k];
      generation_[size_t(remap[k])] = generation_[n0 + k];
    }
    vertex_h_.resize(kernel_.num_vertices());
    generation_.resize(kernel_.num_vertices());
    vpart_.clear();
    ++st.rounds;
    if (cancelled_) return Status::Cancelled();
    items.clear();
    auto current = [&](int32_t v) { return size_t(v) >= n0 ? remap[size_t(v) - n0] : v; };
    if (budget_rounds < o_.budget_rounds &&
        std::any_of(slabs_.begin(), slabs_.end(),
                    [](const SlabWork& S) { return S.out_of_budget; })) {
      ++budget_rounds;
      per_item *= 2;
    }
    for (SlabWork& S : slabs_) {
      for (int32_t v : S.deferred) items.push_back(phase == Phase::kFront ? current(v) : v);
      if (fresh)
        for (int32_t v : S.fresh) fresh->push_back(current(v));
      add_stats(st, S.st);
    }
  }
  // The last round: sequential, the whole triangulation.
  return sequential(phase, std::move(items), st, progress, fresh);
}

Status Refiner::run(RefineStats& st, const ProgressFn& progress) {
  const auto t0 = std::chrono::steady_clock::now();
  // Phase 1: checks.
  if (vertex_h_.size() != kernel_.num_vertices())
    return Status::Error("refine: one size per kernel vertex expected");
  for (double h : vertex_h_)
    if (!(h > 0) || !std::isfinite(h)) return Status::Error("refine: sizes must be finite and > 0");
  if (!(o_.split_length > 1) || !(o_.min_spacing > 0) || !(o_.min_spacing < o_.split_length) ||
      !(o_.boundary_spacing >= 0) || !(o_.parts >= 1 && o_.parts <= 64) || !(o_.rounds >= 0) ||
      !(o_.budget_rounds >= 0))
    return Status::Error(
        "refine: options need split_length > 1, 0 < min_spacing < split_length, "
        "boundary_spacing >= 0, 1 <= parts <= 64, rounds >= 0, budget_rounds >= 0");
  const int32_t cap = int32_t(kernel_.tet_capacity());
  std::vector<uint8_t> in_region(kernel_.num_vertices(), 0);
  for (int32_t t = 0; t < cap; ++t) {
    if (!kernel_.is_live(t) || kernel_.is_ghost(t) || kernel_.tag(t) != tag_) continue;
    for (int k = 0; k < 4; ++k) {
      in_region[size_t(kernel_.tet(t)[k])] = 1;
      const int32_t u = kernel_.neighbor(t, k) >> 2;
      if ((kernel_.is_ghost(u) || kernel_.tag(u) != tag_) && !kernel_.is_constrained(t, k))
        return Status::Error(
            "refine: the region is not closed by constrained faces (a face to the outside is "
            "not constrained)");
    }
  }
  generation_.assign(kernel_.num_vertices(), 0);

  // Phase 2: the first layer: the apex of the regular tetrahedron on each
  // boundary face (height sqrt(2/3) h inward from its centroid), in BRIO
  // order: the first points are spread over the whole surface and break
  // the long tetrahedra of the boundary-only triangulation everywhere at
  // once; points inserted along a curve would keep re-creating long
  // tetrahedra to the far side (cavities 3x larger).
  std::vector<int32_t> queue;
  if (o_.first_layer) {
    const double height = std::sqrt(2.0 / 3.0);
    for (int32_t t = 0; t < cap; ++t) {
      if (!kernel_.is_live(t) || kernel_.is_ghost(t) || kernel_.tag(t) != tag_) continue;
      for (int k = 0; k < 4; ++k) {
        const int32_t u = kernel_.neighbor(t, k) >> 2;
        if (!kernel_.is_ghost(u) && kernel_.tag(u) == tag_) continue;
        // The face counterclockwise seen from outside the region.
        const int32_t* tv = kernel_.tet(t);
        const int32_t a = tv[kFaceOut[k][0]], b = tv[kFaceOut[k][1]], c = tv[kFaceOut[k][2]];
        const double *pa = kernel_.point(a), *pb = kernel_.point(b), *pc = kernel_.point(c);
        double e1[3], e2[3];
        for (int j = 0; j < 3; ++j) e1[j] = pb[j] - pa[j], e2[j] = pc[j] - pa[j];
        // Outward normal.
        const double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                             e1[0] * e2[1] - e1[1] * e2[0]};
        const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        if (!(len > 0)) continue;
        const double hf = (vertex_h_[size_t(a)] + vertex_h_[size_t(b)] + vertex_h_[size_t(c)]) / 3;
        for (int j = 0; j < 3; ++j)
          apex_.push_back((pa[j] + pb[j] + pc[j]) / 3 - height * hf * n[j] / len);
        apex_h_.push_back(hf);
        apex_face_.insert(apex_face_.end(), {a, b, c});
      }
    }
    Status s = slab_rounds(Phase::kFirstLayer, brio_hilbert_order(apex_), st, progress, &queue);
    if (!s.ok()) return s;
    hilbert_sort(kernel_.points(), queue.data(), int64_t(queue.size()));
  }
  st.first_layer = st.inserted;
  st.first_layer_rounds = st.rounds;
  st.first_layer_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  // Phase 3: the queue: the first layer, then the region's vertices along a
  // Hilbert curve.
  {
    const size_t first = queue.size();
    for (size_t v = 0; v < in_region.size(); ++v)
      if (in_region[v]) queue.push_back(int32_t(v));
    hilbert_sort(kernel_.points(), queue.data() + first, int64_t(queue.size() - first));
  }
  // Phase 4: edges of each queued vertex, new vertices queued after.
  Status s = slab_rounds(Phase::kFront, std::move(queue), st, progress, nullptr);
  if (!s.ok()) return s;
  st.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return Status::Ok();
}

}  // namespace

Status refine_volume(Delaunay3D& kernel, const VolumeSizeField& field,
                     std::vector<double>& vertex_h, const RefineOptions& options,
                     RefineStats* stats, const ProgressFn& progress) {
  RefineStats st;
  Refiner refiner(kernel, field, vertex_h, options);
  Status s = refiner.run(st, progress);
  if (!s.ok()) return s;
  if (stats) *stats = st;
  return Status::Ok();
}

}  // namespace vm
