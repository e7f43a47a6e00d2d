// build()'s rounds of slabs and the partitioned insertion of Delaunay3D,
// after Marot, Pellerin and Remacle ("One machine, one minute, three
// billion tetrahedra", IJNME 117, 2019, section 4: parallel insertion in
// partitions with ownership): past its first points, build() inserts in
// rounds of slabs of equal point count, each slab at the same time on its
// own thread, only in its own tetrahedra; a point whose walk or cavity
// leaves its slab waits for the next round, with slabs across another
// axis, and the rest is inserted sequentially. Points mostly on a surface
// stay sequential. See delaunay3d.h (DelaunayBuildOptions,
// begin_partitions()).
//
// Phases of build_insertions(): (2a) sequential up to parts *
// min_part_points points, (2b) rounds of slabs, (2c) what is left,
// sequentially.
#include <algorithm>
#include <cmath>

#include "core/util/parallel.h"
#include "core/volume/delaunay3d.h"
#include "core/volume/delaunay3d_internal.h"
#include "core/volume/slabs.h"

namespace vm {

// ---------------------------------------------------------------- building

void Delaunay3D::build_insertions(const BuildOptions& o, const int32_t first[4]) {
  const int32_t n = int32_t(num_vertices());
  auto is_first = [&](int32_t v) { return v == first[1] || v == first[2] || v == first[3]; };
  // Phase 2a: sequential, each walk starting where the previous insertion
  // ended, up to parts * min_part_points vertices (all of them with one
  // part or few points).
  const int64_t start = int64_t(o.parts) * o.min_part_points;
  int32_t v = 1;
  auto insert_up_to = [&](int32_t end) {
    for (; v < end; ++v)
      if (!is_first(v)) build_insert(v);
  };
  insert_up_to(o.parts < 2 || int64_t(n) < 2 * start ? n : int32_t(start));
  // Points mostly on a surface (the hull has more than one face per 16
  // vertices so far) stay sequential: a slab cuts their long tetrahedra,
  // and points on the hull need ghosts, which no part owns.
  if (v < n) {
    int64_t hull_faces = 0;
    for (int32_t t = 0; t < int32_t(tet_capacity()); ++t) hull_faces += is_live(t) && is_ghost(t);
    if (16 * hull_faces > int64_t(v)) return insert_up_to(n);
    // Room for the fresh slots the rounds leave unused (7 per point tried,
    // the points left over from a round tried again, 4096 per part), so
    // that no round moves the arrays.
    int rounds = o.retry_rounds + 1;
    for (int64_t m = v; m < n; m *= 2) ++rounds;
    topo_.reserve(size_t(n) * 8 + size_t(rounds) * size_t(o.parts) * 4096 + 16);
  }
  // Phase 2b: rounds of slabs, each adding at most as many points as there
  // are vertices, with the ones left over from the round before; slabs
  // across x, y, z in turn. Rounds with no new points retry those left.
  std::vector<int32_t> items, left;
  int retries = 0;
  for (int round = 0; v < n || (!left.empty() && retries < o.retry_rounds); ++round) {
    if (v == n) ++retries;
    // The new points first (in order, each walk short), then those left.
    const int32_t end = int32_t(std::min<int64_t>(n, 2 * int64_t(v)));
    items.clear();
    for (; v < end; ++v)
      if (!is_first(v)) items.push_back(v);
    items.insert(items.end(), left.begin(), left.end());
    build_round(o.parts, round % 3, v, items);
    left.swap(items);
    ++seq_.stats.build_rounds;
    if (left.size() < size_t(o.min_part_points) && v == n) break;
  }
  // Phase 2c: what is left, sequentially.
  for (int32_t u : left) build_insert(u);
}

void Delaunay3D::build_insert(int32_t v) {
  const InsertResult r = insert_vertex(seq_, v, -1, false);
  if (r.status == InsertStatus::kDuplicate) dup_[size_t(v)] = r.vertex;
}

void Delaunay3D::build_round(int parts, int axis, int32_t nv, std::vector<int32_t>& items) {
  if (items.empty()) return;
  // Slabs of equal point count across `axis`; a vertex is in the slab its
  // coordinate falls in.
  std::vector<double> xs(items.size());
  for (size_t i = 0; i < items.size(); ++i) xs[i] = point(items[i])[axis];
  const Slabs slabs = equal_count_slabs(xs, axis, size_t(parts));
  std::vector<uint8_t> vertex_part(static_cast<size_t>(nv));
  parallel_for(size_t(nv), size_t(1) << 16, [&](size_t begin, size_t end) {
    for (size_t u = begin; u < end; ++u) vertex_part[u] = uint8_t(slabs.of(point(int32_t(u))));
  });
  std::vector<std::vector<int32_t>> lists(static_cast<size_t>(parts)), left(lists.size()),
      outside(lists.size());
  for (int32_t u : items) lists[vertex_part[size_t(u)]].push_back(u);
  // Fresh slots: a new vertex takes about 6.7 more tetrahedra than it frees.
  std::vector<PartBudget> budgets(lists.size());
  for (int j = 0; j < parts; ++j)
    budgets[size_t(j)].tets = int32_t(7 * lists[size_t(j)].size() + 4096);
  begin_partitions(std::move(vertex_part), budgets);
  // Each slab's first tetrahedron: the sequential walk to its first points,
  // until one lands in a tetrahedron of the slab (none: the slab waits;
  // points outside the hull, or near another slab, do not).
  std::vector<int32_t> start(lists.size(), -1);
  for (int j = 0; j < parts; ++j)
    for (size_t i = 0; i < std::min<size_t>(lists[size_t(j)].size(), 64) && start[size_t(j)] < 0;
         ++i) {
      const int32_t t = walk(seq_, point(lists[size_t(j)][i]), -1, o3_bound_);
      if (owns(parts_[size_t(j)], t)) start[size_t(j)] = t;
      seq_.last = t;
    }
  parallel_for(size_t(parts), 1, [&](size_t begin, size_t end) {
    for (size_t j = begin; j < end; ++j) {
      Worker& w = parts_[j];
      int32_t hint = start[j];
      for (int32_t u : lists[j]) {
        if (hint < 0 || w.gen > 0xf0000000u) {
          left[j].push_back(u);
          continue;
        }
        w.beyond_hull = false;
        const InsertResult r = insert_vertex(w, u, hint, false);
        if (r.status == InsertStatus::kInserted)
          hint = w.last;
        else if (r.status == InsertStatus::kDuplicate)
          dup_[size_t(u)] = r.vertex;
        else
          (w.beyond_hull ? outside : left)[j].push_back(u);
      }
    }
  });
  for (int j = parts - 1; j >= 0; --j)
    if (parts_[size_t(j)].last >= 0) seq_.last = parts_[size_t(j)].last;
  end_partitions();
  // Points outside the hull now (no part owns a ghost), so that the next
  // rounds see the whole hull.
  items.clear();
  for (const std::vector<int32_t>& l : outside) items.insert(items.end(), l.begin(), l.end());
  std::sort(items.begin(), items.end());
  for (int32_t u : items) build_insert(u);
  items.clear();
  for (const std::vector<int32_t>& l : left) items.insert(items.end(), l.begin(), l.end());
  std::sort(items.begin(), items.end());
}

// ---------------------------------------------------------------- partitions

void Delaunay3D::begin_partitions(std::vector<uint8_t> vertex_part,
                                  const std::vector<PartBudget>& budgets) {
  const size_t n0 = num_vertices();
  size_t nv = 0, nt = 0;
  for (const PartBudget& b : budgets) nv += size_t(b.vertices), nt += size_t(b.tets);
  round_vertices_ = int64_t(n0);
  part_ = std::move(vertex_part);
  part_.resize(n0 + nv, kNoPart);
  pts_.resize(3 * (n0 + nv));
  dup_.resize(n0 + nv, -1);
  topo_.vertex_tet.resize(n0 + nv, -1);
  // Fresh slots for the parts, left uninitialized: a part fills those it
  // takes (its star), on its own thread, and end_partitions() frees the
  // others, so no slot is read unwritten.
  const size_t cap0 = topo_.capacity();
  topo_.tets.resize(cap0 + nt);
  topo_.constrained.resize(cap0 + nt);
  if (topo_.tagged) topo_.tags.resize(cap0 + nt);
  topo_.stamp.resize(cap0 + nt);
  // Visit marks: part i uses gen + 2 i + k * 2 parts (k >= 1), above every
  // mark used so far and distinct between the parts.
  if (topo_.gen > 0x7fffffffu) {
    std::fill(topo_.stamp.begin(), topo_.stamp.end(), 0u);
    topo_.gen = 0;
  }
  parts_.resize(budgets.size());
  int32_t vnext = int32_t(n0), tnext = int32_t(cap0);
  for (size_t i = 0; i < budgets.size(); ++i) {
    Worker& w = parts_[i];
    w.part = int(i);
    w.last = -1;
    w.rng = 0x2545f4914f6cdd1dull ^ (0x9e3779b97f4a7c15ull * (i + 1));
    w.stats = Stats{};
    w.gen = topo_.gen + 2 * uint32_t(i);
    w.gen_step = 2 * uint32_t(budgets.size());
    w.free_slots.clear();
    w.slot_next = tnext;
    w.slot_end = tnext += budgets[i].tets;
    w.vertex_begin = w.vertex_next = vnext;
    w.vertex_end = vnext += budgets[i].vertices;
    std::fill(part_.begin() + w.vertex_begin, part_.begin() + w.vertex_end, uint8_t(i));
  }
}

Delaunay3D::InsertResult Delaunay3D::insert_in(int part, const double* p, int32_t hint,
                                               double min_distance) {
  if (part < 0) return insert(p, hint, true, min_distance);
  if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
    return {InsertStatus::kInvalid, -1};
  if (!in_box(p)) return {InsertStatus::kOutsideHull, -1};  // the hull is inside the box
  Worker& w = parts_[size_t(part)];
  if (w.vertex_next >= w.vertex_end || w.gen > 0xf0000000u) return {InsertStatus::kForeign, -1};
  const int32_t v = w.vertex_next;
  std::copy(p, p + 3, &pts_[3 * size_t(v)]);
  const InsertResult r = insert_vertex(w, v, hint, true, min_distance);
  if (r.status == InsertStatus::kInserted) ++w.vertex_next;
  return r;
}

bool Delaunay3D::in_part(int part, int32_t t) const {
  return part < 0 || owns(parts_[size_t(part)], t);
}

std::vector<int32_t> Delaunay3D::end_partitions() {
  // The fresh slots no part took, never written: free slots.
  for (const Worker& w : parts_)
    for (int32_t t = w.slot_next; t < w.slot_end; ++t) {
      topo_.tets[size_t(t)] = {{kFree, kFree, kFree, kFree}, {-1, -1, -1, -1}};
      topo_.constrained[size_t(t)] = 0;
      if (topo_.tagged) topo_.tags[size_t(t)] = 0;
      topo_.stamp[size_t(t)] = 0;
    }
  const int32_t n0 = int32_t(round_vertices_);
  std::vector<int32_t> remap(num_vertices() - size_t(n0), -1);
  int32_t next = n0;
  for (const Worker& w : parts_)
    for (int32_t v = w.vertex_begin; v < w.vertex_next; ++v) remap[size_t(v - n0)] = next++;
  // Vertices move down (remap[k] <= n0 + k), in ascending order.
  for (size_t k = 0; k < remap.size(); ++k) {
    const int32_t d = remap[k];
    if (d < 0) continue;
    const size_t src = size_t(n0) + k;
    std::copy(&pts_[3 * src], &pts_[3 * src] + 3, &pts_[3 * size_t(d)]);
    topo_.vertex_tet[size_t(d)] = topo_.vertex_tet[src];
  }
  pts_.resize(3 * size_t(next));
  dup_.resize(size_t(next));
  topo_.vertex_tet.resize(size_t(next));
  if (!remap.empty())  // (a build's rounds add no vertices)
    for (TetTopology::Rec& r : topo_.tets) {
      if (r.v[0] == kFree) continue;
      for (int32_t& v : r.v)
        if (v >= n0) v = remap[size_t(v - n0)];
    }
  for (Worker& w : parts_) {
    topo_.free_slots.insert(topo_.free_slots.end(), w.free_slots.begin(), w.free_slots.end());
    for (int32_t t = w.slot_end - 1; t >= w.slot_next; --t) topo_.free_slots.push_back(t);
    topo_.gen = std::max(topo_.gen, w.gen);
    Stats& s = seq_.stats;
    s.walk_steps += w.stats.walk_steps;
    s.cavity_tets += w.stats.cavity_tets;
    s.boundary_faces += w.stats.boundary_faces;
    s.checked_cavities += w.stats.checked_cavities;
    s.shrunk_cavities += w.stats.shrunk_cavities;
    w.free_slots.clear();
  }
  part_.clear();
  round_vertices_ = 0;
  return remap;
}

}  // namespace vm
