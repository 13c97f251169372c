// The reference broad phase and the factory: hand-checked scenes.
#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <random>
#include <string>
#include <vector>

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

TEST(NaiveBroadPhase, RandomAddRemoveMoveMatchesEveryBoxAgainstEvery) {
  // Add, Remove and Move in random order against Aabb::Overlaps on every present pair, with
  // NaN boxes (they overlap nothing) among them; FindPairsOf against FindPairs.
  // Ids over three 64-bit words (the hits are masked a word at a time), the last 30 outside the
  // compatibility matrix (never compatible).
  constexpr PrimitiveId kIds = 150;
  constexpr PrimitiveId kMatrixIds = kIds - 30;
  std::mt19937_64 rng(20261124);
  std::uniform_real_distribution<double> coord(-1.0, 1.0), half(0.05, 0.4), unit(0.0, 1.0);
  auto random_box = [&] {
    if (unit(rng) < 0.05) {
      const double nan = std::numeric_limits<double>::quiet_NaN();
      return Aabb{Eigen::Vector3d(nan, 0, 0), Eigen::Vector3d(nan, 0, 0)};
    }
    return Cube(coord(rng), coord(rng), coord(rng), half(rng));
  };
  NaiveBroadPhase bp;
  std::vector<Aabb> box(kIds);
  std::vector<std::uint8_t> present(kIds, 0), moving(kIds, 0);
  CompatibilityMatrix compatible(kMatrixIds);
  for (PrimitiveId a = 0; a < kMatrixIds; a += 3) {
    compatible.Set(a, (a * 7 + 1) % kMatrixIds, true);
  }
  std::vector<CandidatePair> pairs, expected;
  for (int round = 0; round < 1500; ++round) {
    const auto id = static_cast<PrimitiveId>(rng() % kIds);
    const double op = unit(rng);
    if (!present[id]) {
      box[id] = random_box();
      moving[id] = unit(rng) < 0.6 ? 1 : 0;
      present[id] = 1;
      bp.Add(id, box[id], 0.0, moving[id] ? Motion::kMoving : Motion::kStatic);
    } else if (op < 0.3) {
      bp.Remove(id);
      present[id] = 0;
    } else {
      box[id] = random_box();
      bp.Move(id, box[id]);
    }
    expected.clear();
    for (PrimitiveId a = 0; a < kIds; ++a) {
      for (PrimitiveId b = a + 1; b < kIds; ++b) {
        if (present[a] && present[b] && (moving[a] || moving[b]) && box[a].Overlaps(box[b]) &&
            !(b < kMatrixIds && compatible.AreCompatible(a, b))) {
          expected.push_back({a, b});
        }
      }
    }
    bp.FindPairs(compatible, &pairs);
    ASSERT_EQ(pairs, expected) << "round " << round;
    std::string why;
    ASSERT_TRUE(bp.Validate(&why)) << "round " << round << ": " << why;
    if (!present[id]) continue;
    std::vector<CandidatePair> of_id;
    for (const CandidatePair& p : expected) {
      if (p.a == id || p.b == id) of_id.push_back(p);
    }
    bp.FindPairsOf(id, compatible, &pairs);
    ASSERT_EQ(pairs, of_id) << "round " << round << " primitive " << id;
    // FindPairsOfGroup for the ids from id on (2 to 7 of them, present or not, across words):
    // the pairs of `expected` that contain any, each once.
    const auto group_end = std::min<PrimitiveId>(kIds, id + 2 + rng() % 6);
    std::vector<PrimitiveId> group;
    for (PrimitiveId g = id; g < group_end; ++g) group.push_back(g);
    std::vector<CandidatePair> of_group;
    for (const CandidatePair& p : expected) {
      if ((p.a >= id && p.a < group_end) || (p.b >= id && p.b < group_end)) of_group.push_back(p);
    }
    ASSERT_TRUE(bp.FindPairsOfGroup(group.data(), static_cast<std::uint32_t>(group.size()),
                                    compatible, &pairs));
    std::sort(pairs.begin(), pairs.end());
    ASSERT_EQ(pairs, of_group) << "round " << round << " primitives " << id << " to "
                               << group_end - 1;
    ASSERT_TRUE(bp.Validate(&why)) << "round " << round << ": " << why;
  }
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
