#include "core/volume/tet_topology.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <vector>

#include "core/mesh/volume_mesh.h"
#include "core/volume/tet_mesh.h"
#include "tests/support/volume_inputs.h"

namespace vm {
namespace {

// The octahedron around edge (0, 1) as 4 positive tetrahedra (boundary
// faces unlinked), built by TetMesh::from_arrays.
TetTopology octahedron() { return testing::octahedron_tets(0).topology(); }

TEST(TetTopology, FaceTableIsOrientedAndHelpersAgree) {
  for (int k = 0; k < 4; ++k) {
    // (k, face) is an even permutation: the face is counterclockwise seen
    // from outside when the tetrahedron is positive.
    EXPECT_TRUE(parity_even(k, kFaceOut[k][0], kFaceOut[k][1], kFaceOut[k][2]));
    const int32_t v[4] = {10, 11, 12, 13};
    std::array<int32_t, 3> f = {v[kFaceOut[k][0]], v[kFaceOut[k][1]], v[kFaceOut[k][2]]};
    std::sort(f.begin(), f.end());
    EXPECT_EQ(face_key(v, k), f);
    EXPECT_EQ(slot_of(v, 10 + k), k);
  }
  EXPECT_FALSE(parity_even(1, 0, 2, 3));
}

TEST(TetTopology, EdgeRingStoppingRules) {
  TetTopology m = octahedron();
  ASSERT_TRUE(check_topology(m, 6, false, true).ok());
  EXPECT_FALSE(check_topology(m, 6, false, false).ok());  // boundary faces are unlinked
  std::vector<int32_t> ring_tets, ring;
  ASSERT_TRUE(edge_ring(m, 0, 0, 1, ring_tets, ring));
  EXPECT_EQ(ring_tets.size(), 4u);
  std::vector<int32_t> sorted = ring;
  std::sort(sorted.begin(), sorted.end());
  EXPECT_EQ(sorted, (std::vector<int32_t>{2, 3, 4, 5}));
  EXPECT_FALSE(edge_ring(m, 0, 0, 1, ring_tets, ring, {false, 3}));
  EXPECT_TRUE(edge_ring(m, 0, 0, 1, ring_tets, ring, {false, 4}));
  // A constrained face around the edge stops only when asked to.
  const int32_t e = m.neighbor(0, slot_of(m.tet(0), ring[0]));
  m.constrained[0] |= uint8_t(1u << slot_of(m.tet(0), ring[0]));
  m.constrained[size_t(e >> 2)] |= uint8_t(1u << (e & 3));
  EXPECT_TRUE(check_topology(m, 6, false, true).ok());
  EXPECT_TRUE(edge_ring(m, 0, 0, 1, ring_tets, ring));
  EXPECT_FALSE(edge_ring(m, 0, 0, 1, ring_tets, ring, {true, 64}));
  std::vector<int32_t> star;
  tets_around_vertex(m, 0, star);
  EXPECT_EQ(star.size(), 4u);
  tets_around_vertex(m, 2, star);
  EXPECT_EQ(star.size(), 2u);
}

TEST(TetTopology, ReplaceWithASlotPoolTakesAndFreesOnlyItsSlots) {
  // A 2-3 flip and back, as a worker of a parallel pass does them: new
  // slots only from its pool, freed ones into it, the free list untouched.
  TetTopology m = octahedron();
  std::vector<int32_t> ring_tets, ring, ids;
  ASSERT_TRUE(edge_ring(m, 0, 0, 1, ring_tets, ring));
  const int k = slot_of(m.tet(ring_tets[0]), ring[0]);  // the face shared with the next one
  const int32_t old[2] = {ring_tets[0], m.neighbor(ring_tets[0], k) >> 2};
  std::array<int32_t, 4> two[2], three[3];
  for (int i = 0; i < 2; ++i) std::copy(m.tet(old[i]), m.tet(old[i]) + 4, two[i].begin());
  flip23_tets(m, ring_tets[0], k, three);
  ReplaceScratch scratch;
  std::vector<SlotPool> pools;
  take_slot_pools(m, {4}, pools);  // the free list is empty: no slot
  ASSERT_EQ(pools.size(), 1u);
  EXPECT_EQ(pools[0].room(), 0u);
  const size_t capacity = m.capacity();
  EXPECT_EQ(replace_tets(m, old, 2, three, 3, ids, scratch, &pools[0]), ReplaceError::kNoRoom);
  for (int i = 0; i < 2; ++i) EXPECT_TRUE(std::equal(two[i].begin(), two[i].end(), m.tet(old[i])));
  return_slot_pools(m, pools);
  // One free slot on the list: the pool takes it, the flip uses it.
  const int32_t spare = m.new_slot();
  m.free_slot(spare);
  take_slot_pools(m, {4}, pools);
  EXPECT_EQ(pools[0].room(), 1u);
  EXPECT_TRUE(m.free_slots.empty());
  ASSERT_EQ(replace_tets(m, old, 2, three, 3, ids, scratch, &pools[0]), ReplaceError::kNone);
  EXPECT_EQ(ids, (std::vector<int32_t>{old[0], old[1], spare}));
  EXPECT_EQ(pools[0].room(), 0u);
  EXPECT_TRUE(check_topology(m, 6, false, true).ok())
      << check_topology(m, 6, false, true).message();
  // Back: the slot freed goes to the pool, then to the list on return.
  const std::vector<int32_t> three_ids = ids;
  ASSERT_EQ(replace_tets(m, three_ids.data(), 3, two, 2, ids, scratch, &pools[0]),
            ReplaceError::kNone);
  EXPECT_EQ(pools[0].free, std::vector<int32_t>{spare});
  EXPECT_TRUE(m.free_slots.empty());
  EXPECT_FALSE(m.is_live(spare));
  EXPECT_TRUE(check_topology(m, 6, false, true).ok())
      << check_topology(m, 6, false, true).message();
  return_slot_pools(m, pools);
  EXPECT_TRUE(pools.empty());
  EXPECT_EQ(m.free_slots, std::vector<int32_t>{spare});
  EXPECT_EQ(m.capacity(), capacity + 1);
}

TEST(TetTopology, ReplaceKeepsLinksOrChangesNothing) {
  TetTopology m = octahedron();
  std::vector<int32_t> ring_tets, ring, ids;
  ASSERT_TRUE(edge_ring(m, 0, 0, 1, ring_tets, ring));
  // The other diagonal (ring[0], ring[2]): 4 tetrahedra over two triangles.
  std::array<int32_t, 4> nt[4];
  ring_triangle_tets(0, 1, ring[0], ring[1], ring[2], nt);
  ring_triangle_tets(0, 1, ring[0], ring[2], ring[3], nt + 2);
  ReplaceScratch scratch;
  const TetTopology before = m;
  EXPECT_EQ(replace_tets(m, ring_tets.data(), 4, nt, 3, ids, scratch),
            ReplaceError::kUnmatchedFace);
  EXPECT_EQ(m.tets.size(), before.tets.size());
  for (size_t t = 0; t < m.tets.size(); ++t)
    for (int k = 0; k < 4; ++k) {
      EXPECT_EQ(m.tets[t].v[k], before.tets[t].v[k]);
      EXPECT_EQ(m.tets[t].n[k], before.tets[t].n[k]);
    }
  // A constrained face inside the old set refuses.
  TetTopology c = m;
  const int k0 = slot_of(c.tet(ring_tets[0]), ring[1]);
  const int32_t e = c.neighbor(ring_tets[0], k0);
  c.constrained[size_t(ring_tets[0])] |= uint8_t(1u << k0);
  c.constrained[size_t(e >> 2)] |= uint8_t(1u << (e & 3));
  EXPECT_EQ(replace_tets(c, ring_tets.data(), 4, nt, 4, ids, scratch),
            ReplaceError::kConstrainedInside);
  // The 4-4 flip: old slots reused in order, links and incidences valid.
  ASSERT_EQ(replace_tets(m, ring_tets.data(), 4, nt, 4, ids, scratch), ReplaceError::kNone);
  EXPECT_EQ(ids, ring_tets);
  EXPECT_TRUE(check_topology(m, 6, false, true).ok())
      << check_topology(m, 6, false, true).message();
  std::vector<int32_t> star;
  tets_around_vertex(m, ring[0], star);
  EXPECT_EQ(star.size(), 4u);
  // A freed slot is the next one reused.
  const int32_t freed_first = ids[2];
  m.free_slot(ids[2]);
  EXPECT_FALSE(m.is_live(freed_first));
  EXPECT_EQ(m.new_slot(), freed_first);
}

TEST(TetTopology, CheckFindsBrokenLinks) {
  TetTopology m = octahedron();
  int32_t t = 0, k = 0;
  while (m.neighbor(t, k) < 0) ++k;
  m.tets[0].n[k] = -1;
  EXPECT_FALSE(check_topology(m, 6, false, true).ok());
  m = octahedron();
  m.vertex_tet[0] = -1;
  EXPECT_FALSE(check_topology(m, 6, false, true).ok());
  m = octahedron();
  m.tets[1].v[0] = -1;
  EXPECT_FALSE(check_topology(m, 6, false, true).ok());
  EXPECT_FALSE(check_topology(octahedron(), 5, false, true).ok());
}

}  // namespace
}  // namespace vm
