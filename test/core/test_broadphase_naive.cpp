// The reference broad phase and the factory: hand-checked scenes.
#include <gtest/gtest.h>

#include "arm_collision_monitor/broadphase/broad_phase_factory.h"
#include "arm_collision_monitor/broadphase/naive_broad_phase.h"

namespace arm_collision_monitor {
namespace {

Aabb Cube(double x, double y, double z, double half_m) {
  return Aabb{Eigen::Vector3d(x - half_m, y - half_m, z - half_m),
              Eigen::Vector3d(x + half_m, y + half_m, z + half_m)};
}

TEST(NaiveBroadPhase, ReportsOverlapsOnceOrderedAndSkipsStaticStaticAndCompatible) {
  NaiveBroadPhase bp;
  bp.Add(0, Cube(0, 0, 0, 1), 0.0, Motion::kStatic);
  bp.Add(1, Cube(1.5, 0, 0, 1), 0.0, Motion::kStatic);  // overlaps 0, both static: never
  bp.Add(2, Cube(0.5, 0, 0, 0.2), 0.0, Motion::kMoving);  // inside 0 and 1
  bp.Add(3, Cube(0.5, 0.3, 0, 0.2), 0.0, Motion::kMoving);  // overlaps 0, 1, 2
  bp.Add(4, Cube(10, 0, 0, 0.1), 0.0, Motion::kMoving);  // alone
  CompatibilityMatrix compatible(5);
  compatible.Set(1, 3, true);
  std::vector<CandidatePair> pairs;
  bp.FindPairs(compatible, &pairs);
  const std::vector<CandidatePair> expected = {{0, 2}, {0, 3}, {1, 2}, {2, 3}};
  EXPECT_EQ(pairs, expected);
}

TEST(NaiveBroadPhase, ClosedBoxesTouchingAtACornerAndToleranceInflation) {
  NaiveBroadPhase bp;
  bp.Add(0, Cube(0, 0, 0, 1), 0.0, Motion::kStatic);
  bp.Add(1, Cube(2, 2, 2, 1), 0.0, Motion::kMoving);  // shares the corner (1,1,1)
  bp.Add(2, Cube(0, 0, 2.5, 1), 0.25, Motion::kMoving);  // inflated down to z = 1.25: no touch
  std::vector<CandidatePair> pairs;
  bp.FindPairs(CompatibilityMatrix(), &pairs);
  EXPECT_EQ(pairs, (std::vector<CandidatePair>{{0, 1}, {1, 2}}));
  bp.Move(2, Cube(0, 0, 2.25, 1));  // now reaches z = 1.0: touches 0
  bp.FindPairs(CompatibilityMatrix(), &pairs);
  EXPECT_EQ(pairs, (std::vector<CandidatePair>{{0, 1}, {0, 2}, {1, 2}}));
  bp.Remove(1);
  bp.Remove(1);  // absent: no-op
  bp.FindPairs(CompatibilityMatrix(), &pairs);
  EXPECT_EQ(pairs, (std::vector<CandidatePair>{{0, 2}}));
  bp.Move(7, Cube(0, 0, 0, 1));  // unknown id: refused, no crash
  bp.FindPairs(CompatibilityMatrix(), &pairs);
  EXPECT_EQ(pairs, (std::vector<CandidatePair>{{0, 2}}));
}

TEST(BroadPhaseFactory, NamesRoundTripAndUnknownIsRefused) {
  for (const char* name : {"octree", "naive", "grid", "rebuild", "reinsert"}) {
    BroadPhaseMethod method;
    ASSERT_TRUE(ParseBroadPhaseMethod(name, &method)) << name;
    EXPECT_EQ(BroadPhaseMethodName(method), name);
    BroadPhaseOptions options;
    options.method = method;
    options.world_W = Cube(0, 0, 0, 3.175);
    EXPECT_NE(MakeBroadPhase(options), nullptr);
  }
  BroadPhaseMethod method = BroadPhaseMethod::kGrid;
  EXPECT_FALSE(ParseBroadPhaseMethod("Octree", &method));
  EXPECT_FALSE(ParseBroadPhaseMethod("", &method));
  EXPECT_EQ(method, BroadPhaseMethod::kGrid);
}

}  // namespace
}  // namespace arm_collision_monitor
