// PairCache::TestPairs' batched narrow phase (pair_cache.h, geometry/clearance_batch.h): the
// float clearance bound settles a pair only when its exact distance is above the threshold, so
// every pair at or below it reaches the exact distance (and its warning); the pairs it settles
// keep valid lower bounds for the bounded cycles and the swept check. Seeded (kSeed, printed).
#include <cmath>
#include <cstdio>
#include <random>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "arm_collision_monitor/broadphase/broad_phase_factory.h"
#include "arm_collision_monitor/geometry/distance.h"
#include "arm_collision_monitor/monitor/pair_cache.h"

namespace arm_collision_monitor {
namespace {

constexpr std::uint64_t kSeed = 7340;
constexpr double kWorldEdge_m = 4.0;

// Pairs of one moving capsule and one static box each, far apart from the other pairs, indexed
// as the Monitor does with slack 0 (every cycle a full kinematics cycle), but with boxes grown by
// kIndexGrowth_m more than the tolerance, so that pairs somewhat beyond the threshold are
// candidates too.
constexpr double kIndexGrowth_m = 0.05;
struct PairScene {
  std::vector<Shape> shapes_W;
  std::vector<double> tol_m;
  CompatibilityMatrix compatible;
  std::unique_ptr<BroadPhase> broad_phase;
  PairCache cache;

  explicit PairScene(const std::vector<std::pair<Shape, Shape>>& pairs, double tol_each_m)
      : compatible(static_cast<std::uint32_t>(2 * pairs.size())) {
    for (const auto& [capsule, box] : pairs) {
      shapes_W.push_back(capsule);
      shapes_W.push_back(box);
    }
    tol_m.assign(shapes_W.size(), tol_each_m);
    BroadPhaseOptions options;
    options.method = BroadPhaseMethod::kNaive;
    options.world_W.min_W = Eigen::Vector3d::Constant(-kWorldEdge_m);
    options.world_W.max_W = Eigen::Vector3d::Constant(kWorldEdge_m);
    options.reserve_primitives = static_cast<std::uint32_t>(shapes_W.size());
    broad_phase = MakeBroadPhase(options);
    const auto n = static_cast<std::uint32_t>(shapes_W.size());
    cache = PairCache(n, std::size_t{n} * (n - 1) / 2, 0.0, 2.0 * kWorldEdge_m);
    for (PrimitiveId id = 0; id < n; ++id) {
      const bool is_moving = id % 2 == 0;
      broad_phase->Add(id, ComputeAabb(shapes_W[id]), tol_m[id] + kIndexGrowth_m,
                       is_moving ? Motion::kMoving : Motion::kStatic);
      cache.SetIndexed(id, shapes_W[id]);
    }
  }

  // One cycle: the cache brought up to date, the narrow phase; returns the pairs it computed
  // exactly.
  std::set<std::pair<PrimitiveId, PrimitiveId>> Cycle() {
    cache.BeginReindex();
    cache.Update(broad_phase.get(), compatible);
    std::set<std::pair<PrimitiveId, PrimitiveId>> exact;
    cache.TestPairs(shapes_W, tol_m, [&](PrimitiveId a, PrimitiveId b) {
      exact.insert({a, b});
      return ShapeDistance(shapes_W[a], shapes_W[b]).distance_m;
    });
    return exact;
  }
};

Box AxisBox(const Eigen::Vector3d& centre_W, const Eigen::Vector3d& half_m) {
  Box box;
  box.X_WB.translation() = centre_W;
  box.half_extents_m = half_m;
  return box;
}

// A capsule parallel to the top face of a box (random size and turn), `gap_m` above it; the
// pairs are spread over a grid so that each box overlaps only its own capsule.
std::pair<Shape, Shape> CapsuleOverBox(int slot, double gap_m, std::mt19937_64* rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const Eigen::Vector3d centre_W(-3.0 + 0.5 * (slot % 12), -3.0 + 0.5 * ((slot / 12) % 12),
                                 -3.0 + 0.5 * (slot / 144));
  const Eigen::Vector3d half_m(0.05 + 0.1 * unit(*rng), 0.05 + 0.1 * unit(*rng),
                               0.02 + 0.05 * unit(*rng));
  const double radius_m = 0.01 + 0.04 * unit(*rng);
  const double turn_rad = 2.0 * M_PI * unit(*rng);
  const Eigen::Vector3d axis_W(std::cos(turn_rad), std::sin(turn_rad), 0.0);
  const Eigen::Vector3d mid_W = centre_W + Eigen::Vector3d(0.3 * half_m.x() * (unit(*rng) - 0.5),
                                                           0.3 * half_m.y() * (unit(*rng) - 0.5),
                                                           half_m.z() + gap_m + radius_m);
  const double half_length_m = 0.03 * unit(*rng);
  Capsule capsule;
  capsule.p0_W = mid_W - half_length_m * axis_W;
  capsule.p1_W = mid_W + half_length_m * axis_W;
  capsule.radius_m = radius_m;
  return {capsule, AxisBox(centre_W, half_m)};
}

TEST(MonitorNarrowPhase, PairsAtOrBelowTheThresholdReachTheExactDistance) {
  // Threshold 2 x 2 cm; gaps within a few float margins (about 1e-5 m here) of it, on both
  // sides, and far above: every pair at or below gets its exact distance.
  std::printf("seed %llu\n", static_cast<unsigned long long>(kSeed));
  std::mt19937_64 rng(kSeed);
  constexpr double kTol_m = 0.02;
  const double threshold_m = 2.0 * kTol_m;
  std::uniform_real_distribution<double> offset(-1e-4, 1e-4);
  std::vector<std::pair<Shape, Shape>> pairs;
  for (int slot = 0; slot < 1000; ++slot) {
    const double gap_m = slot % 4 == 0   ? threshold_m
                         : slot % 4 == 1 ? threshold_m + offset(rng)
                         : slot % 4 == 2 ? threshold_m * (1.0 + 1e-12 * offset(rng))
                                         : threshold_m + 0.01;
    pairs.push_back(CapsuleOverBox(slot, gap_m, &rng));
  }
  PairScene scene(pairs, kTol_m);
  const auto exact = scene.Cycle();
  ASSERT_EQ(scene.cache.pairs().size(), pairs.size());
  int at_or_below = 0, settled = 0, settled_far = 0;
  for (const KeptPair& kept : scene.cache.pairs()) {
    const PrimitiveId a = kept.pair.a, b = kept.pair.b;
    const double d_m = ShapeDistance(scene.shapes_W[a], scene.shapes_W[b]).distance_m;
    const bool is_exact = exact.count({a, b}) > 0;
    if (d_m <= threshold_m) {
      ++at_or_below;
      EXPECT_TRUE(is_exact) << "pair (" << a << "," << b << ") at " << d_m
                            << " m <= threshold " << threshold_m << " m settled by its bound "
                            << kept.kinematics_bound_m;
    }
    EXPECT_EQ(kept.is_exact, is_exact);
    // Every bound a lower bound (the swept check and the bounded cycles read them).
    EXPECT_LE(kept.kinematics_bound_m, d_m);
    EXPECT_LE(kept.lower_bound_m, d_m);
    if (!is_exact) {
      ++settled;
      settled_far += d_m > threshold_m + 0.005;
      // Not much below the distance either: the batch's bound is within 1e-4 m of it here.
      EXPECT_GE(kept.kinematics_bound_m, d_m - 1e-4);
    }
  }
  std::printf("%zu pairs: %d at or below the threshold, %d settled by the float bound (%d of "
              "them 1 cm above it)\n",
              pairs.size(), at_or_below, settled, settled_far);
  EXPECT_GT(at_or_below, 0);
  // Every pair 1 cm above the threshold (a quarter of them) is settled without the exact test.
  EXPECT_EQ(settled_far, static_cast<int>(pairs.size() / 4));
}

TEST(MonitorNarrowPhase, FloatCopiesFollowTheShapes) {
  // Moved primitives' float copies follow FollowMoved (ValidatePrimitive compares them): 20
  // pairs (a batch: kClearanceBatchMinPairs), moved from above the threshold to below it, are
  // then all tested exactly.
  constexpr int kPairs = 20;
  static_assert(kPairs >= kClearanceBatchMinPairs, "the float batch must run");
  std::mt19937_64 rng(kSeed + 1);
  std::vector<std::pair<Shape, Shape>> pairs;
  for (int slot = 0; slot < kPairs; ++slot) pairs.push_back(CapsuleOverBox(slot, 0.06, &rng));
  PairScene scene(pairs, 0.02);
  EXPECT_TRUE(scene.Cycle().empty());  // 6 cm apart, threshold 4 cm: all settled by the batch
  ASSERT_EQ(scene.cache.pairs().size(), static_cast<std::size_t>(kPairs));
  for (const KeptPair& kept : scene.cache.pairs()) EXPECT_FALSE(kept.is_exact);
  scene.cache.BeginReindex();
  for (PrimitiveId id = 0; id < 2 * kPairs; id += 2) {
    Capsule moved = std::get<Capsule>(scene.shapes_W[id]);
    moved.p0_W.z() -= 0.05;
    moved.p1_W.z() -= 0.05;  // now 1 cm apart
    scene.shapes_W[id] = moved;
    if (scene.cache.FollowMoved(id, moved, 0.0)) {  // slack 0: every move re-indexes
      scene.broad_phase->Move(id, ComputeAabb(moved));
    }
  }
  scene.cache.Update(scene.broad_phase.get(), scene.compatible);
  int exact = 0;
  scene.cache.TestPairs(scene.shapes_W, scene.tol_m, [&](PrimitiveId a, PrimitiveId b) {
    ++exact;
    return ShapeDistance(scene.shapes_W[a], scene.shapes_W[b]).distance_m;
  });
  EXPECT_EQ(exact, kPairs);
  for (PrimitiveId id = 0; id < 2 * kPairs; ++id) {
    std::string why;
    EXPECT_TRUE(scene.cache.ValidatePrimitive(id, scene.shapes_W[id], &why)) << why;
  }
}

}  // namespace
}  // namespace arm_collision_monitor
