// The steady-state cycle allocates nothing: global operator new/delete are replaced by counting
// versions, and every broad phase runs 10,000 cycles of motion (with splits, merges, jumps that
// take the re-insert fallback, excursions out of the world, removals and re-additions) after a
// warm-up, with the counter armed only around the broad-phase calls.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <new>
#include <vector>

#include "arm_collision_monitor/broadphase/broad_phase_factory.h"
#include "allocation_counter.h"
#include "test_broadphase_scene.h"


namespace arm_collision_monitor {
namespace {

using test::RandomScene;
using test::SceneConfig;
using test::SceneOp;

TEST(BroadPhaseAllocation, CounterSeesAllocations) {
  const std::uint64_t before = test::AllocationCount();
  auto* v = new std::vector<int>(100);
  const std::uint64_t allocations = test::AllocationCount() - before;
  delete v;
  EXPECT_GE(allocations, 2u);  // the vector object and its buffer
}

TEST(BroadPhaseAllocation, SteadyStateCyclesAllocateNothing) {
  for (const BroadPhaseMethod method :
       {BroadPhaseMethod::kOctree, BroadPhaseMethod::kGrid, BroadPhaseMethod::kReinsert,
        BroadPhaseMethod::kRebuild, BroadPhaseMethod::kNaive}) {
    SceneConfig config;
    config.seed = 81;
    config.statics = 35;
    config.movers = 14;
    config.jump_probability = 0.003;
    config.leave_probability = 0.002;
    config.remove_probability = 0.02;
    config.flip_probability = 0.1;
    std::printf("[ seed ] %llu  method %s\n", static_cast<unsigned long long>(config.seed),
                BroadPhaseMethodName(method).c_str());
    RandomScene scene(config);
    BroadPhaseOptions options = scene.Options(method);
    options.max_objects_per_leaf = 3;  // small N: the tree splits and merges often
    const std::unique_ptr<BroadPhase> bp = MakeBroadPhase(options);
    std::vector<SceneOp> ops;
    ops.reserve(4 * scene.Count());
    std::vector<CandidatePair> pairs;
    pairs.reserve(static_cast<std::size_t>(scene.Count()) * scene.Count());
    scene.Initial(&ops);
    RandomScene::Apply(ops, bp.get());
    for (int cycle = 0; cycle < 2000; ++cycle) {  // warm-up: pools reach their high-water mark
      scene.Step(&ops);
      RandomScene::Apply(ops, bp.get());
      bp->FindPairs(scene.compatible(), &pairs);
    }
    bp->ResetCounters();
    std::uint64_t allocations = 0;
    for (int cycle = 0; cycle < 10000; ++cycle) {
      scene.Step(&ops);
      const std::uint64_t before = test::AllocationCount();
      RandomScene::Apply(ops, bp.get());
      bp->FindPairs(scene.compatible(), &pairs);
      allocations += test::AllocationCount() - before;
    }
    const BroadPhaseCounters& c = bp->counters();
    std::printf("  splits %llu merges %llu fallbacks %llu outside %llu\n",
                static_cast<unsigned long long>(c.splits),
                static_cast<unsigned long long>(c.merges),
                static_cast<unsigned long long>(c.reinsert_fallbacks),
                static_cast<unsigned long long>(c.outside_world));
    EXPECT_EQ(allocations, 0u) << BroadPhaseMethodName(method);
    if (method == BroadPhaseMethod::kOctree) {
      EXPECT_GT(c.splits, 0u);  // the measured cycles did exercise the structural paths
      EXPECT_GT(c.merges, 0u);
      EXPECT_GT(c.reinsert_fallbacks, 0u);
      EXPECT_GT(c.outside_world, 0u);
    }
  }
}

}  // namespace
}  // namespace arm_collision_monitor
