// The N-objects octree and the grid on hand-built scenes: minimum cell size, split and merge,
// location links, the update techniques' effect on work (never on answers), the outside list,
// jumps, the unlinked list, stamp wrap-around and the canonical shape shared with the rebuild
// scheme.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <limits>
#include <tuple>
#include <vector>

#include "arm_collision_monitor/broadphase/grid_broad_phase.h"
#include "arm_collision_monitor/broadphase/octree_broad_phase.h"
#include "arm_collision_monitor/core/constants.h"
#include "test_broadphase_scene.h"

namespace arm_collision_monitor {
namespace {

Aabb Box(double x0, double y0, double z0, double x1, double y1, double z1) {
  return Aabb{Eigen::Vector3d(x0, y0, z0), Eigen::Vector3d(x1, y1, z1)};
}

// World [0, 8]^3 with minimum leaf 1 m (depth 3), N = 2.
BroadPhaseOptions SmallWorld(int leaf_capacity = 2) {
  BroadPhaseOptions options;
  options.world_W = Box(0, 0, 0, 8, 8, 8);
  options.min_cell_size_m = 1.0;
  options.max_objects_per_leaf = leaf_capacity;
  return options;
}

void ExpectValid(const CellBroadPhase& bp) {
  std::string why;
  EXPECT_TRUE(bp.Validate(&why)) << why;
}

TEST(Octree, MinimumLeafIsTheSmallestRootOverPowerOfTwoAtLeastTheMotionPerCycle) {
  // The seed: a 250 in world and 1.2 in of motion per cycle give 250 / 2^7 = 1.95 in leaves.
  const double inch_m = 0.0254;
  BroadPhaseOptions options;
  options.world_W = Box(0, 0, 0, 250 * inch_m, 250 * inch_m, 250 * inch_m);
  options.min_cell_size_m = 1.2 * inch_m;
  OctreeBroadPhase octree(options, CellUpdateStrategy::kIncremental);
  EXPECT_EQ(octree.max_depth(), 7);
  EXPECT_NEAR(octree.min_leaf_size_m() / inch_m, 250.0 / 128.0, 1e-12);
  // Exactly root / 2^k is allowed; a hair more forces one level less.
  options.min_cell_size_m = 250 * inch_m / 64;
  EXPECT_EQ(OctreeBroadPhase(options, CellUpdateStrategy::kIncremental).max_depth(), 6);
  options.min_cell_size_m = 250 * inch_m / 64 * (1 + 1e-9);
  EXPECT_EQ(OctreeBroadPhase(options, CellUpdateStrategy::kIncremental).max_depth(), 5);
  // A non-cubic world becomes a cube on its min corner with the largest edge.
  options.world_W = Box(-1, 0, 0, 1, 4, 1);
  options.min_cell_size_m = 1.0;
  OctreeBroadPhase cube(options, CellUpdateStrategy::kIncremental);
  EXPECT_EQ(cube.root_W().max_W, Eigen::Vector3d(3, 4, 4));
  EXPECT_EQ(cube.max_depth(), 2);
}

TEST(Octree, ACrowdOfBoxesLargerThanTheChildrenDoesNotSplitTheirLeaf) {
  // 12 mutually overlapping 1.5 m boxes in a 64 m world with 1 m minimum leaves (depth 6),
  // N = 2: leaves of 4 m split (their 2 m children fit the boxes), 2 m leaves do not (1 m
  // children are smaller than every box), so each box lies in at most 2 x 2 x 2 leaves; splitting
  // down to the minimum would put each in up to 27 leaves and separate nothing.
  BroadPhaseOptions options;
  options.world_W = Box(0, 0, 0, 64, 64, 64);
  options.min_cell_size_m = 1.0;
  options.max_objects_per_leaf = 2;
  OctreeBroadPhase octree(options, CellUpdateStrategy::kIncremental);
  for (PrimitiveId id = 0; id < 12; ++id) {
    const double x = 33.0 + 0.04 * id;
    octree.Add(id, Box(x, x, x, x + 1.5, x + 1.5, x + 1.5), 0.0, Motion::kMoving);
    ExpectValid(octree);
  }
  OctreeStatistics stats = octree.ComputeStatistics();
  EXPECT_LE(stats.mean_leaves_per_primitive, 8.0);
  EXPECT_LE(stats.depth, 5);  // 2 m leaves: level 5 of 64 m
  // A small box entering the crowd's leaf still counts for a split only with more than N small
  // ones: three 0.5 m boxes (they fit a 1 m child) do split a 2 m leaf they share.
  for (PrimitiveId id = 12; id < 15; ++id) {
    const double x = 32.1 + 0.1 * (id - 12);
    octree.Add(id, Box(x, x, x, x + 0.5, x + 0.5, x + 0.5), 0.0, Motion::kMoving);
    ExpectValid(octree);
  }
  stats = octree.ComputeStatistics();
  EXPECT_EQ(stats.depth, 6);
  std::vector<CandidatePair> pairs;
  octree.FindPairs(CompatibilityMatrix(15), &pairs);
  EXPECT_EQ(pairs.size(), 12u * 11u / 2u + 3u);  // the crowd's pairs and the small boxes'
}

TEST(Octree, SplitsWhenMoreThanNAndMergesWhenTheyLeave) {
  OctreeBroadPhase octree(SmallWorld(2), CellUpdateStrategy::kIncremental);
  octree.Add(0, Box(1, 1, 1, 2, 2, 2), 0.0, Motion::kStatic);
  octree.Add(1, Box(5, 1, 1, 6, 2, 2), 0.0, Motion::kStatic);
  ExpectValid(octree);
  EXPECT_EQ(octree.ComputeStatistics().leaves, 1u);
  octree.Add(2, Box(2.8, 5, 1, 3.6, 6, 2), 0.0, Motion::kMoving);  // third: the root splits
  ExpectValid(octree);
  OctreeStatistics stats = octree.ComputeStatistics();
  EXPECT_EQ(stats.nodes, 9u);
  EXPECT_EQ(stats.leaves, 8u);
  EXPECT_EQ(stats.empty_leaves, 5u);
  EXPECT_DOUBLE_EQ(stats.mean_primitives_per_nonempty_leaf, 1.0);
  EXPECT_DOUBLE_EQ(stats.mean_leaves_per_primitive, 1.0);
  EXPECT_EQ(stats.depth, 1);
  EXPECT_EQ(octree.counters().splits, 1u);
  // Moving 2 across the middle plane x = 4 puts it in two leaves; no structural change.
  octree.Move(2, Box(3.5, 5, 1, 4.3, 6, 2));
  ExpectValid(octree);
  EXPECT_DOUBLE_EQ(octree.ComputeStatistics().mean_leaves_per_primitive, 4.0 / 3.0);
  EXPECT_EQ(octree.counters().reinsert_fallbacks, 0u);
  EXPECT_EQ(octree.counters().merges, 0u);
  octree.Remove(1);  // two distinct primitives left: the siblings merge into the root
  ExpectValid(octree);
  EXPECT_EQ(octree.counters().merges, 1u);
  EXPECT_EQ(octree.counters().splits, 1u);
  EXPECT_EQ(octree.ComputeStatistics().leaves, 1u);
}

TEST(Octree, NoSplitBelowTheMinimumLeaf) {
  OctreeBroadPhase octree(SmallWorld(2), CellUpdateStrategy::kIncremental);
  for (PrimitiveId id = 0; id < 20; ++id) {
    octree.Add(id, Box(2.25, 2.25, 2.25, 2.75, 2.75, 2.75), 0.0, Motion::kStatic);
    ExpectValid(octree);
  }
  const OctreeStatistics stats = octree.ComputeStatistics();
  EXPECT_EQ(stats.depth, octree.max_depth());
  std::vector<IndexCell> cells;
  octree.CollectCells(&cells);
  const auto full = std::max_element(cells.begin(), cells.end(), [](const auto& a, const auto& b) {
    return a.primitive_count < b.primitive_count;
  });
  EXPECT_EQ(full->primitive_count, 20u);
  EXPECT_DOUBLE_EQ((full->box_W.max_W - full->box_W.min_W).maxCoeff(), octree.min_leaf_size_m());
  EXPECT_FALSE(full->holds_moving);
}

TEST(Octree, CornerStraddlerIsLinkedToEightLeavesAndFollowsItsMotion) {
  OctreeBroadPhase octree(SmallWorld(1), CellUpdateStrategy::kIncremental);
  // Two statics force the root and one octant to split.
  octree.Add(0, Box(0.5, 0.5, 0.5, 1.5, 1.5, 1.5), 0.0, Motion::kStatic);
  octree.Add(1, Box(2.5, 2.5, 2.5, 3.5, 3.5, 3.5), 0.0, Motion::kStatic);
  ExpectValid(octree);
  // A mover exactly on the corner (4, 4, 4) of the eight root octants.
  octree.Add(2, Box(3.75, 3.75, 3.75, 4.25, 4.25, 4.25), 0.0, Motion::kMoving);
  ExpectValid(octree);
  std::vector<IndexCell> cells;
  octree.CollectCells(&cells);
  EXPECT_EQ(
      std::count_if(cells.begin(), cells.end(), [](const IndexCell& c) { return c.holds_moving; }),
      8);
  std::vector<CandidatePair> pairs;
  octree.FindPairs(CompatibilityMatrix(3), &pairs);
  EXPECT_TRUE(pairs.empty());
  // Walk it toward static 1 in steps shorter than the minimum leaf: links follow exactly.
  for (int step = 1; step <= 6; ++step) {
    const double shift = -0.15 * step;
    octree.Move(
        2, Box(3.75 + shift, 3.75 + shift, 3.75 + shift, 4.25 + shift, 4.25 + shift, 4.25 + shift));
    ExpectValid(octree);
  }
  EXPECT_EQ(octree.counters().reinsert_fallbacks, 0u);
  octree.FindPairs(CompatibilityMatrix(3), &pairs);
  EXPECT_EQ(pairs, (std::vector<CandidatePair>{{1, 2}}));  // reached 3.5 exactly: touching
}

TEST(Octree, InsideExitAndDirectionCutTheWorkButNotTheAnswer) {
  auto run = [](const BroadPhaseTechniques& techniques) {
    BroadPhaseOptions options = SmallWorld(1);
    options.techniques = techniques;
    OctreeBroadPhase octree(options, CellUpdateStrategy::kIncremental);
    octree.Add(0, Box(0.2, 0.2, 0.2, 0.4, 0.4, 0.4), 0.0, Motion::kStatic);
    octree.Add(1, Box(6.2, 6.2, 6.2, 6.4, 6.4, 6.4), 0.0, Motion::kStatic);
    octree.Add(2, Box(2.2, 2.2, 2.2, 2.4, 2.4, 2.4), 0.0, Motion::kMoving);
    octree.ResetCounters();
    octree.Move(2, Box(2.3, 2.2, 2.2, 2.5, 2.4, 2.4));  // still strictly inside its leaf
    const std::uint64_t inside_neighbours = octree.counters().neighbours_visited;
    octree.Move(2, Box(2.9, 2.2, 2.2, 3.1, 2.4, 2.4));  // leaf [2, 4]^3: still inside
    octree.Move(2, Box(3.5, 2.2, 2.2, 3.7, 2.4, 2.4));
    octree.Move(2, Box(3.9, 2.2, 2.2, 4.1, 2.4, 2.4));  // crosses the leaf's face x = 4 only
    ExpectValid(octree);
    std::vector<CandidatePair> pairs;
    octree.FindPairs(CompatibilityMatrix(3), &pairs);
    EXPECT_TRUE(pairs.empty());
    return std::make_tuple(inside_neighbours, octree.counters().neighbours_visited);
  };
  BroadPhaseTechniques on;
  BroadPhaseTechniques off = on;
  off.inside_node_exit = false;
  off.directional_neighbours = false;
  const auto [inside_on, total_on] = run(on);
  const auto [inside_off, total_off] = run(off);
  EXPECT_EQ(inside_on, 0u);  // BoundingBoxInsideNode: no neighbour looked at
  EXPECT_GT(inside_off, 0u);
  EXPECT_EQ(total_on, 1u);  // only the +x face neighbour
  EXPECT_GT(total_off, total_on);
}

TEST(Octree, JumpsTakeTheFallbackOrTheUnlinkedListAndOutsidePrimitivesAreNeverLost) {
  // Leaves of 1 m: steps of 1 m or more take the fallback; steps of 2 m (kJumpSpacingFraction
  // of the 8 m oversize spacing) or more unlink the box until a shorter step.
  static_assert(kJumpSpacingFraction == 0.25, "the steps below assume a 2 m jump step");
  OctreeBroadPhase octree(SmallWorld(2), CellUpdateStrategy::kIncremental);
  const CompatibilityMatrix none(2);
  std::vector<CandidatePair> pairs;
  const std::vector<CandidatePair> both = {{0, 1}};
  octree.Add(0, Box(7.5, 1, 1, 9, 2, 2), 0.0, Motion::kStatic);  // straddles the x = 8 face
  octree.Add(1, Box(1, 1, 1, 2, 2, 2), 0.0, Motion::kMoving);
  EXPECT_EQ(octree.outside_count(), 1u);
  EXPECT_EQ(octree.counters().outside_world, 1u);
  ExpectValid(octree);
  octree.Move(1, Box(2.5, 1, 1, 3.5, 2, 2));  // a step of 1.5 m: the fallback, still linked
  EXPECT_EQ(octree.counters().reinsert_fallbacks, 1u);
  EXPECT_EQ(octree.unlinked_count(), 0u);
  ExpectValid(octree);
  octree.Move(1, Box(6.5, 1, 1, 7.6, 2, 2));  // a jump of 4 m: unlinked, tested against all
  EXPECT_EQ(octree.counters().reinsert_fallbacks, 1u);
  EXPECT_EQ(octree.unlinked_count(), 1u);
  EXPECT_EQ(octree.outside_count(), 1u);
  ExpectValid(octree);
  octree.FindPairs(none, &pairs);
  EXPECT_EQ(pairs, both);
  octree.Move(1, Box(7.3, 1, 1, 8.3, 2, 2));  // a short step: back into the cells
  EXPECT_EQ(octree.unlinked_count(), 0u);
  EXPECT_EQ(octree.counters().unlinked_changes, 2u);
  ExpectValid(octree);
  octree.FindPairs(none, &pairs);
  EXPECT_EQ(pairs, both);                     // the straddler's part inside the cube is indexed
  octree.Move(1, Box(7.4, 1, 1, 8.4, 2, 2));  // straddles too: the incremental update
  EXPECT_EQ(octree.outside_count(), 2u);
  EXPECT_EQ(octree.counters().reinsert_fallbacks, 1u);
  ExpectValid(octree);
  octree.FindPairs(none, &pairs);
  EXPECT_EQ(pairs, both);
  octree.Move(1, Box(8.2, 1, 1, 9.0, 2, 2));  // wholly outside: no cell, brute force pairs it
  ExpectValid(octree);
  octree.FindPairs(none, &pairs);
  EXPECT_EQ(pairs, both);
  octree.Move(1, Box(7.6, 1, 1, 8.4, 2, 2));  // re-entering from wholly outside: full insert
  EXPECT_EQ(octree.counters().reinsert_fallbacks, 2u);
  ExpectValid(octree);
  octree.FindPairs(none, &pairs);
  EXPECT_EQ(pairs, both);
  // A corrupt (NaN) box is unlinked, pairs with nothing, and recovers: the step from NaN is a
  // jump too, then a short step links it again.
  octree.Move(1, Box(std::numeric_limits<double>::quiet_NaN(), 1, 1, 7.9, 2, 2));
  EXPECT_EQ(octree.unlinked_count(), 1u);
  ExpectValid(octree);
  octree.FindPairs(none, &pairs);
  EXPECT_TRUE(pairs.empty());
  octree.Move(1, Box(7.2, 1, 1, 7.9, 2, 2));
  EXPECT_EQ(octree.unlinked_count(), 1u);
  ExpectValid(octree);
  octree.FindPairs(none, &pairs);
  EXPECT_EQ(pairs, both);
  octree.Move(1, Box(7.3, 1, 1, 7.9, 2, 2));
  EXPECT_EQ(octree.unlinked_count(), 0u);
  EXPECT_EQ(octree.counters().reinsert_fallbacks, 2u);
  ExpectValid(octree);
  octree.FindPairs(none, &pairs);
  EXPECT_EQ(pairs, both);
  EXPECT_EQ(octree.outside_count(), 1u);
}

TEST(Octree, VisitStampWrapResetsEveryNodeStamp) {
  OctreeBroadPhase octree(SmallWorld(1), CellUpdateStrategy::kIncremental);
  octree.ForceStampsNearWrap(2);
  octree.Add(0, Box(0.2, 0.2, 0.2, 0.4, 0.4, 0.4), 0.0, Motion::kStatic);
  octree.Add(1, Box(2.2, 2.2, 2.2, 2.4, 2.4, 2.4), 0.0, Motion::kMoving);
  for (int step = 1; step <= 8; ++step) {  // crosses x = 3 and x = 4 while the counter wraps
    const double x = 2.2 + 0.3 * step;
    octree.Move(1, Box(x, 2.2, 2.2, x + 0.2, 2.4, 2.4));
    ExpectValid(octree);  // includes: no node stamp ahead of the counter
  }
  std::vector<CandidatePair> pairs;
  octree.FindPairs(CompatibilityMatrix(2), &pairs);
  EXPECT_TRUE(pairs.empty());
  EXPECT_GT(octree.counters().neighbours_visited, 0u);
}

TEST(Octree, IncrementalShapeEqualsTheRebuiltShape) {
  // The structure is a function of the boxes alone (split iff more than N distinct primitives
  // overlap the cell), so the incremental update and a rebuild must agree leaf for leaf.
  test::SceneConfig config;
  config.seed = 91;
  config.statics = 60;
  config.movers = 14;
  config.jump_probability = 0.01;
  std::printf("[ seed ] %llu\n", static_cast<unsigned long long>(config.seed));
  test::RandomScene scene(config);
  BroadPhaseOptions options = scene.Options(BroadPhaseMethod::kOctree);
  options.max_objects_per_leaf = 3;
  OctreeBroadPhase incremental(options, CellUpdateStrategy::kIncremental);
  OctreeBroadPhase rebuilt(options, CellUpdateStrategy::kRebuild);
  std::vector<test::SceneOp> ops;
  std::vector<CandidatePair> pairs;
  std::vector<IndexCell> a, b;
  auto key = [](const IndexCell& c) {
    return std::make_tuple(c.box_W.min_W.x(), c.box_W.min_W.y(), c.box_W.min_W.z(),
                           c.box_W.max_W.x(), c.primitive_count);
  };
  auto less = [&](const IndexCell& x, const IndexCell& y) { return key(x) < key(y); };
  int unlinked_cycles = 0;
  scene.Initial(&ops);
  for (int cycle = 0; cycle < 300; ++cycle) {
    if (cycle > 0) scene.Step(&ops);
    test::RandomScene::Apply(ops, &incremental);
    test::RandomScene::Apply(ops, &rebuilt);
    incremental.FindPairs(scene.compatible(), &pairs);
    rebuilt.FindPairs(scene.compatible(), &pairs);
    // A box unlinked after a jump is in no cell of the incremental octree but in the rebuilt
    // one's: compare the cycles where every box is linked.
    if (incremental.unlinked_count() > 0) {
      ++unlinked_cycles;
      continue;
    }
    incremental.CollectCells(&a);
    rebuilt.CollectCells(&b);
    std::sort(a.begin(), a.end(), less);
    std::sort(b.begin(), b.end(), less);
    ASSERT_EQ(a.size(), b.size()) << "cycle " << cycle;
    for (std::size_t i = 0; i < a.size(); ++i) {
      ASSERT_EQ(key(a[i]), key(b[i])) << "cycle " << cycle << " leaf " << i;
    }
  }
  EXPECT_GT(incremental.counters().splits, 0u);
  EXPECT_GT(incremental.counters().merges, 0u);
  EXPECT_GT(unlinked_cycles, 0);    // the jumps were unlinked ...
  EXPECT_LT(unlinked_cycles, 100);  // ... and linked again: most cycles compared
}

TEST(Grid, BoxesSpanningManyCellsAreListedOversizeAndTestedAgainstAll) {
  BroadPhaseOptions options = SmallWorld();
  options.grid_cells_per_axis = 8;  // 1 m cells: a box over 27 cells (a cube over 2 m) is listed
  GridBroadPhase grid(options);
  const CompatibilityMatrix none(3);
  std::vector<CandidatePair> pairs;
  grid.Add(0, Box(1, 1, 1, 5, 5, 5), 0.0, Motion::kStatic);            // 125 cells
  grid.Add(1, Box(4.5, 4.5, 4.5, 5.5, 5.5, 5.5), 0.0, Motion::kMoving);  // 8 cells
  grid.Add(2, Box(0, 0, 0, 3, 3, 3), 0.0, Motion::kMoving);            // 64 cells
  EXPECT_EQ(grid.unlinked_count(), 2u);
  ExpectValid(grid);
  grid.FindPairs(none, &pairs);
  EXPECT_EQ(pairs, (std::vector<CandidatePair>{{0, 1}, {0, 2}}));
  grid.Move(2, Box(4, 4, 4, 5, 5, 5));  // small now, but a jump: still unlinked
  EXPECT_EQ(grid.unlinked_count(), 2u);
  ExpectValid(grid);
  grid.FindPairs(none, &pairs);
  EXPECT_EQ(pairs, (std::vector<CandidatePair>{{0, 1}, {0, 2}, {1, 2}}));
  grid.Move(2, Box(4.1, 4, 4, 5.1, 5, 5));  // a short step: back into the cells
  EXPECT_EQ(grid.unlinked_count(), 1u);
  EXPECT_EQ(grid.counters().unlinked_changes, 3u);
  ExpectValid(grid);
  grid.FindPairs(none, &pairs);
  EXPECT_EQ(pairs, (std::vector<CandidatePair>{{0, 1}, {0, 2}, {1, 2}}));
  grid.Move(1, Box(0, 0, 0, 6, 1, 1));  // 7 x 2 x 2 cells: long and thin, listed too
  EXPECT_EQ(grid.unlinked_count(), 2u);
  ExpectValid(grid);
  grid.FindPairs(none, &pairs);
  EXPECT_EQ(pairs, (std::vector<CandidatePair>{{0, 1}, {0, 2}}));  // touching faces overlap
  grid.FindPairsOf(1, none, &pairs);
  EXPECT_EQ(pairs, (std::vector<CandidatePair>{{0, 1}}));
  grid.Remove(0);
  EXPECT_EQ(grid.unlinked_count(), 1u);
  ExpectValid(grid);
  grid.FindPairs(none, &pairs);
  EXPECT_TRUE(pairs.empty());
}

TEST(Grid, CellsFollowTheBoxAndOnlyNonEmptyCellsAreCollected) {
  BroadPhaseOptions options;
  options.world_W = Box(0, 0, 0, 8, 8, 8);
  options.grid_cells_per_axis = 8;
  GridBroadPhase grid(options);
  EXPECT_DOUBLE_EQ(grid.cell_size_m(), 1.0);
  grid.Add(0, Box(0.5, 0.5, 0.5, 1.0, 1.0, 1.0), 0.0, Motion::kStatic);  // touches 8 cells
  grid.Add(1, Box(3.2, 3.2, 3.2, 3.4, 3.4, 3.4), 0.0, Motion::kMoving);
  ExpectValid(grid);
  std::vector<IndexCell> cells;
  grid.CollectCells(&cells);
  EXPECT_EQ(cells.size(), 9u);
  EXPECT_EQ(
      std::count_if(cells.begin(), cells.end(), [](const IndexCell& c) { return c.holds_moving; }),
      1);
  for (int step = 1; step <= 20; ++step) {  // toward static 0 in 0.12 m steps
    const double x = 3.2 - 0.12 * step;
    grid.Move(1, Box(x, x, x, x + 0.2, x + 0.2, x + 0.2));
    ExpectValid(grid);
  }
  EXPECT_EQ(grid.counters().reinsert_fallbacks, 0u);
  std::vector<CandidatePair> pairs;
  grid.FindPairs(CompatibilityMatrix(2), &pairs);
  EXPECT_EQ(pairs, (std::vector<CandidatePair>{{0, 1}}));  // x = 0.8..1.0 overlaps static 0
}

}  // namespace
}  // namespace arm_collision_monitor
