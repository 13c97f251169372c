// Differential tests: over seeded random scenes, every broad phase (the octree with every
// technique on and off, the rebuild and reinsert schemes, the uniform grid) returns exactly the
// pairs of the all-pairs reference after every cycle, and passes Validate() after every cycle;
// every few cycles each primitive's FindPairsOf equals its share of those pairs.
#include <gtest/gtest.h>

#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "arm_collision_monitor/broadphase/grid_broad_phase.h"
#include "arm_collision_monitor/broadphase/naive_broad_phase.h"
#include "arm_collision_monitor/broadphase/octree_broad_phase.h"
#include "test_broadphase_scene.h"

namespace arm_collision_monitor {
namespace {

using test::RandomScene;
using test::SceneConfig;
using test::SceneOp;

struct Candidate {
  std::string label;
  std::unique_ptr<CellBroadPhase> bp;
};

std::vector<Candidate> MakeCandidates(const RandomScene& scene, int leaf_capacity) {
  std::vector<Candidate> out;
  BroadPhaseOptions options = scene.Options(BroadPhaseMethod::kOctree);
  options.max_objects_per_leaf = leaf_capacity;
  auto octree = [&](const std::string& label, const BroadPhaseTechniques& t,
                    CellUpdateStrategy strategy) {
    BroadPhaseOptions o = options;
    o.techniques = t;
    out.push_back({label, std::make_unique<OctreeBroadPhase>(o, strategy)});
  };
  const BroadPhaseTechniques all_on;
  BroadPhaseTechniques all_off;
  all_off.directional_neighbours = false;
  all_off.inside_node_exit = false;
  all_off.pair_deduplication = false;
  all_off.bounding_box_pretests = false;
  octree("octree", all_on, CellUpdateStrategy::kIncremental);
  octree("octree-all-off", all_off, CellUpdateStrategy::kIncremental);
  BroadPhaseTechniques t = all_on;
  t.directional_neighbours = false;
  octree("octree-no-direction", t, CellUpdateStrategy::kIncremental);
  t = all_on;
  t.inside_node_exit = false;
  octree("octree-no-inside-exit", t, CellUpdateStrategy::kIncremental);
  octree("rebuild", all_on, CellUpdateStrategy::kRebuild);
  octree("reinsert", all_on, CellUpdateStrategy::kReinsert);
  BroadPhaseOptions g = options;
  out.push_back({"grid", std::make_unique<GridBroadPhase>(g)});
  g.techniques = all_off;
  g.grid_cells_per_axis = 13;  // cell edges not on the octree lattice
  out.push_back({"grid13-all-off", std::make_unique<GridBroadPhase>(g)});
  return out;
}

std::string PairsToString(const std::vector<CandidatePair>& pairs) {
  std::string s;
  for (const CandidatePair& p : pairs)
    s += "(" + std::to_string(p.a) + "," + std::to_string(p.b) + ")";
  return s;
}

// Every primitive's FindPairsOf must be exactly the pairs of FindPairs (`all`) that contain it
// (absent ids: none). Returns false on the first mismatch.
bool PairsOfMatch(BroadPhase* bp, const std::string& label, int cycle, int count,
                  const CompatibilityMatrix& compatible, const std::vector<CandidatePair>& all) {
  std::vector<CandidatePair> of, expected_of;
  for (PrimitiveId id = 0; id < static_cast<PrimitiveId>(count); ++id) {
    expected_of.clear();
    for (const CandidatePair& p : all) {
      if (p.a == id || p.b == id) expected_of.push_back(p);
    }
    bp->FindPairsOf(id, compatible, &of);
    EXPECT_EQ(of, expected_of) << label << " cycle " << cycle << " FindPairsOf(" << id
                               << ")\n got      " << PairsToString(of) << "\n expected "
                               << PairsToString(expected_of);
    if (of != expected_of) return false;
  }
  return true;
}

// Forcing of the 32-bit stamps near their wrap-around (ForceStampsNearWrap): before the first
// Add with `first_steps_before_wrap`, then before every `every_cycles`-th cycle's changes with
// r = 0, 1, .., kMidRunMaxSteps - 1 steps in turn (a wrap mid-run, in a populated structure).
struct StampForcing {
  bool enabled = false;
  std::uint32_t first_steps_before_wrap = 0;
  int every_cycles = 0;  // 0: only before the first Add
  static constexpr std::uint32_t kMidRunMaxSteps = 8;
};

// Runs `cycles` cycles of `config` and checks every candidate against the reference after each.
// Returns the summed counters of the incremental octree (to check that paths were exercised).
BroadPhaseCounters RunDifferential(const SceneConfig& config, int cycles, int leaf_capacity,
                                   const StampForcing& forcing = StampForcing{}) {
  std::printf("[ seed ] %llu  statics %d movers %d N %d cycles %d\n",
              static_cast<unsigned long long>(config.seed), config.statics, config.movers,
              leaf_capacity, cycles);
  RandomScene scene(config);
  NaiveBroadPhase reference;
  std::vector<Candidate> candidates = MakeCandidates(scene, leaf_capacity);
  if (forcing.enabled) {
    for (Candidate& c : candidates) c.bp->ForceStampsNearWrap(forcing.first_steps_before_wrap);
  }
  std::vector<SceneOp> ops;
  std::vector<CandidatePair> expected, actual;
  scene.Initial(&ops);
  std::uint32_t mid_run_forcings = 0;
  for (int cycle = 0; cycle <= cycles; ++cycle) {
    if (forcing.enabled && forcing.every_cycles > 0 && cycle > 0 &&
        cycle % forcing.every_cycles == 0) {
      const std::uint32_t steps = mid_run_forcings++ % StampForcing::kMidRunMaxSteps;
      for (Candidate& c : candidates) c.bp->ForceStampsNearWrap(steps);
    }
    if (cycle > 0) scene.Step(&ops);
    RandomScene::Apply(ops, &reference);
    reference.FindPairs(scene.compatible(), &expected);
    // Each primitive's own pairs, on every few cycles (the per-primitive query of a kept pair
    // set), from the reference and from every candidate.
    const bool check_pairs_of = cycle % 7 == 0;
    if (check_pairs_of && !PairsOfMatch(&reference, "naive", cycle, scene.Count(),
                                        scene.compatible(), expected)) {
      return candidates[0].bp->counters();
    }
    for (Candidate& c : candidates) {
      RandomScene::Apply(ops, c.bp.get());
      c.bp->FindPairs(scene.compatible(), &actual);
      std::string why;
      const bool valid = c.bp->Validate(&why);
      EXPECT_TRUE(valid) << c.label << " cycle " << cycle << ": " << why;
      EXPECT_EQ(actual, expected) << c.label << " cycle " << cycle << "\n got      "
                                  << PairsToString(actual) << "\n expected "
                                  << PairsToString(expected);
      if (!valid || actual != expected) return candidates[0].bp->counters();
      if (check_pairs_of && !PairsOfMatch(c.bp.get(), c.label, cycle, scene.Count(),
                                          scene.compatible(), expected)) {
        return candidates[0].bp->counters();
      }
    }
  }
  const BroadPhaseCounters& c = candidates[0].bp->counters();
  std::printf(
      "[ octree ] node tests %llu, object tests %llu, neighbours %llu, splits %llu, "
      "merges %llu, fallbacks %llu, outside %llu, unlinked changes %llu\n",
      static_cast<unsigned long long>(c.object_node_tests),
      static_cast<unsigned long long>(c.object_object_tests),
      static_cast<unsigned long long>(c.neighbours_visited),
      static_cast<unsigned long long>(c.splits), static_cast<unsigned long long>(c.merges),
      static_cast<unsigned long long>(c.reinsert_fallbacks),
      static_cast<unsigned long long>(c.outside_world),
      static_cast<unsigned long long>(c.unlinked_changes));
  return c;
}

TEST(BroadPhaseDifferential, SmallScenesWithinTheSpeedBound) {
  std::uint64_t splits = 0, merges = 0;
  for (std::uint64_t seed : {11u, 12u, 13u}) {
    SceneConfig config;
    config.seed = seed;
    config.statics = 10 + static_cast<int>(seed % 3) * 20;
    config.movers = 14;
    const BroadPhaseCounters c = RunDifferential(config, 800, 3);
    splits += c.splits;
    merges += c.merges;
    EXPECT_EQ(c.reinsert_fallbacks, 0u);  // every move was within the bound
    if (HasFailure()) return;
  }
  EXPECT_GT(splits, 0u);  // the structure did change under the incremental update
  EXPECT_GT(merges, 0u);
}

TEST(BroadPhaseDifferential, JumpsLeavingTheWorldAndAddRemove) {
  for (std::uint64_t seed : {21u, 22u}) {
    SceneConfig config;
    config.seed = seed;
    config.statics = 60;
    config.movers = 14;
    config.jump_probability = 0.01;
    config.leave_probability = 0.01;
    config.remove_probability = 0.05;
    config.flip_probability = 0.2;
    const BroadPhaseCounters c = RunDifferential(config, 1000, 4);
    EXPECT_GT(c.reinsert_fallbacks, 0u);
    EXPECT_GT(c.outside_world, 0u);
    if (HasFailure()) return;
  }
}

TEST(BroadPhaseDifferential, CrowdedSmallWorldDeepSplits) {
  SceneConfig config;
  config.seed = 31;
  config.statics = 150;
  config.movers = 20;
  config.world_edge_m = 2.0;
  config.static_half_min_m = 0.005;
  config.static_half_max_m = 0.08;
  config.mover_length_m = 0.2;
  config.mover_radius_m = 0.02;
  config.jump_probability = 0.002;
  const BroadPhaseCounters c = RunDifferential(config, 300, 2);
  EXPECT_GT(c.splits, 0u);
  EXPECT_GT(c.merges, 0u);
}

TEST(BroadPhaseDifferential, BoxesExactlyOnCellFacesEdgesAndCorners) {
  for (std::uint64_t seed : {41u, 42u}) {
    SceneConfig config;
    config.seed = seed;
    config.statics = 40;
    config.movers = 14;
    config.world_edge_m = 6.4;
    config.world_min_W = Eigen::Vector3d(-3.2, -1.6, 0.0);
    // A quarter of the minimum leaf: coordinates land on leaf faces, edges and corners often.
    BroadPhaseOptions options = RandomScene(config).Options(BroadPhaseMethod::kOctree);
    config.snap_m =
        OctreeBroadPhase(options, CellUpdateStrategy::kIncremental).min_leaf_size_m() / 4;
    config.leave_probability = 0.005;
    RunDifferential(config, 800, 3);
    if (HasFailure()) return;
  }
}

TEST(BroadPhaseDifferential, LargeSceneOfTwoThousand) {
  SceneConfig config;
  config.seed = 51;
  config.statics = 1986;
  config.movers = 14;
  config.static_half_min_m = 0.01;
  config.static_half_max_m = 0.12;
  config.jump_probability = 0.002;
  config.remove_probability = 0.05;
  RunDifferential(config, 40, 10);
}

TEST(BroadPhaseDifferential, FarFromTheOrigin) {
  SceneConfig config;
  config.seed = 61;
  config.world_min_W = Eigen::Vector3d(1000.0, -2000.0, 512.0);
  config.jump_probability = 0.005;
  RunDifferential(config, 500, 3);
}

TEST(BroadPhaseDifferential, StampsWrapAroundWithoutLosingPairs) {
  SceneConfig config;
  config.seed = 71;
  config.statics = 30;
  config.movers = 14;
  // The stamp counters wrap within the first cycles (14 updates and scans per cycle), then
  // again after each mid-run forcing, 0 to 7 stamps later, in a populated structure.
  StampForcing forcing;
  forcing.enabled = true;
  forcing.first_steps_before_wrap = 40;
  forcing.every_cycles = 11;
  RunDifferential(config, 200, 3, forcing);
}

// The inputs of issue 15 that used to cost more than all pairs, each against the reference.
TEST(BroadPhaseDifferential, PrimitivesOutsideTheWorldCube) {
  for (std::uint64_t seed : {81u, 82u}) {
    SceneConfig config;
    config.seed = seed;
    config.statics = 80;
    config.index_world_edge_m = 2.0;  // most of the scene partly or wholly outside the index
    config.leave_probability = 0.02;
    const BroadPhaseCounters c = RunDifferential(config, 400, 4);
    EXPECT_GT(c.outside_world, 0u);
    if (HasFailure()) return;
  }
}

TEST(BroadPhaseDifferential, StepsOfManyCells) {
  for (std::uint64_t seed : {91u, 92u}) {
    SceneConfig config;
    config.seed = seed;
    config.statics = 80;
    config.max_speed_mps = 12.0;  // steps up to 20 minimum cells
    config.index_speed_mps = 0.61;
    const BroadPhaseCounters c = RunDifferential(config, 400, 4);
    EXPECT_GT(c.reinsert_fallbacks, 0u);
    if (HasFailure()) return;
  }
}

TEST(BroadPhaseDifferential, InflatedBoxesLargerThanCells) {
  SceneConfig config;
  config.seed = 101;
  config.statics = 80;
  config.tolerance_max_m = 0.6;  // up to 1.2 m more per box: many grid cells and leaves
  config.world_edge_m = 3.0;
  // The largest boxes go to the unlinked list and, as the capsules turn, in and out of it.
  const BroadPhaseCounters c = RunDifferential(config, 300, 3);
  EXPECT_GT(c.unlinked_changes, 10u);
}

TEST(BroadPhaseDifferential, ManyPrimitivesCrowdedTogether) {
  // A dual-arm sphere model: 75 spheres within 1.2 m, 15 shelf boards, a large index; then the
  // same with large steps and a small index that leaves most of it outside.
  SceneConfig config;
  config.seed = 111;
  config.statics = 15;
  config.movers = 75;
  config.world_edge_m = 1.2;
  config.world_min_W = Eigen::Vector3d::Constant(-0.6);
  config.index_world_edge_m = 6.35;
  config.mover_length_m = 0.0;
  config.mover_radius_m = 0.06;
  config.static_half_max_m = 0.4;
  config.tolerance_max_m = 0.1;
  RunDifferential(config, 200, 10);
  if (HasFailure()) return;
  config.seed = 112;
  config.max_speed_mps = 6.0;
  config.index_speed_mps = 0.61;
  config.index_world_edge_m = 0.8;
  config.leave_probability = 0.05;
  RunDifferential(config, 200, 10);
}

}  // namespace
}  // namespace arm_collision_monitor
