// PairCache (monitor/pair_cache.h): the slack rule and the pair updates on small cases, and a
// differential test against brute force over seeded random scenes and motions: the kept pairs
// are exactly the pairs whose indexed boxes overlap, every bound under-estimates the distance it
// bounds, and the narrow phase run through the cache's skip test finds exactly the pairs that
// an all-pairs test finds closer than their threshold.
#include <cmath>
#include <cstdio>
#include <memory>
#include <random>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "arm_collision_monitor/broadphase/broad_phase_factory.h"
#include "arm_collision_monitor/geometry/distance.h"
#include "arm_collision_monitor/monitor/motion_bounds.h"
#include "arm_collision_monitor/monitor/pair_cache.h"

namespace arm_collision_monitor {
namespace {

constexpr std::uint64_t kSeed = 902811;
constexpr double kWorldEdge_m = 2.0;

// Uniform in [-1, 1]^3.
Eigen::Vector3d RandomVector(std::mt19937_64* rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  return Eigen::Vector3d(u(*rng), u(*rng), u(*rng));
}

// A rotation by up to `max_angle_rad` about a random axis.
Eigen::Matrix3d RandomRotation(double max_angle_rad, std::mt19937_64* rng) {
  Eigen::Vector3d axis = RandomVector(rng);
  if (axis.norm() < 1e-3) axis = Eigen::Vector3d::UnitZ();
  const double angle = max_angle_rad * std::uniform_real_distribution<double>(-1.0, 1.0)(*rng);
  return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
}

Capsule CapsuleAt(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, double r) {
  return Capsule{p0, p1, r};
}

// A random scene: capsules and boxes in the world cube, some moving, random tolerances and
// compatibilities; indexed in `broad_phase` and in the cache as the Monitor does.
struct RandomScene {
  std::vector<Shape> shapes_W;
  std::vector<double> tol_m;
  std::vector<std::uint8_t> is_moving;
  CompatibilityMatrix compatible;
  std::unique_ptr<BroadPhase> broad_phase;
  PairCache cache;
  double slack_m = 0.0;
  std::uint64_t kept_pair_visits = 0;  // kept pairs over all steps
  std::uint64_t narrow_phase_calls = 0;
  std::uint64_t reindexed = 0;

  RandomScene(BroadPhaseMethod method, std::uint32_t n, double slack, std::mt19937_64* rng)
      : compatible(n), slack_m(slack) {
    std::uniform_real_distribution<double> pos(0.2, kWorldEdge_m - 0.2), unit(0.0, 1.0);
    for (std::uint32_t id = 0; id < n; ++id) {
      const Eigen::Vector3d c(pos(*rng), pos(*rng), pos(*rng));
      if (unit(*rng) < 0.6) {
        const Eigen::Vector3d half = 0.15 * RandomVector(rng);
        shapes_W.push_back(CapsuleAt(c - half, c + half, 0.01 + 0.05 * unit(*rng)));
      } else {
        Box box;
        box.X_WB.linear() = RandomRotation(M_PI, rng);
        box.X_WB.translation() = c;
        box.half_extents_m =
            Eigen::Vector3d::Constant(0.02) + 0.1 * RandomVector(rng).cwiseAbs();
        shapes_W.push_back(box);
      }
      tol_m.push_back(unit(*rng) < 0.3 ? 0.0 : 0.05 * unit(*rng));
      is_moving.push_back(unit(*rng) < 0.5 ? 1 : 0);
    }
    for (std::uint32_t a = 0; a < n; ++a) {
      for (std::uint32_t b = a + 1; b < n; ++b) compatible.Set(a, b, unit(*rng) < 0.05);
    }
    BroadPhaseOptions options;
    options.method = method;
    options.world_W.min_W = Eigen::Vector3d::Zero();
    options.world_W.max_W = Eigen::Vector3d::Constant(kWorldEdge_m);
    options.min_cell_size_m = 0.03 + slack_m;
    options.reserve_primitives = n;
    broad_phase = MakeBroadPhase(options);
    cache = PairCache(n, std::size_t{n} * (n - 1) / 2, slack_m, kWorldEdge_m);
    for (std::uint32_t id = 0; id < n; ++id) Add(id);
  }
  double IndexTolerance(PrimitiveId id) const {
    return tol_m[id] + (is_moving[id] ? slack_m : 0.0);
  }
  void Add(PrimitiveId id) {
    broad_phase->Add(id, ComputeAabb(shapes_W[id]), IndexTolerance(id),
                     is_moving[id] ? Motion::kMoving : Motion::kStatic);
    cache.SetIndexed(id, shapes_W[id]);
  }
  // A small random rigid motion of every moving primitive, then the cycle's cache work; returns
  // the pairs the narrow phase found closer than their threshold.
  std::set<std::pair<PrimitiveId, PrimitiveId>> Step(double step_m, std::mt19937_64* rng) {
    cache.BeginReindex();
    // The Monitor's two re-index thresholds, at random: the slack and half of it.
    const double reindex_at_m =
        ((*rng)() % 2 == 0 ? PairCache::kReindexSlackFraction : 1.0) * slack_m;
    for (PrimitiveId id = 0; id < shapes_W.size(); ++id) {
      if (!is_moving[id]) continue;
      Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
      X.translation() = step_m * RandomVector(rng);
      // A turn about a corner of the box: the far points move more than step_m.
      const Eigen::Vector3d corner = ComputeAabb(shapes_W[id]).min_W;
      X = Eigen::Translation3d(corner) * X * Eigen::Isometry3d(RandomRotation(2.0 * step_m, rng)) *
          Eigen::Translation3d(-corner);
      Shape& s = shapes_W[id];
      if (auto* c = std::get_if<Capsule>(&s)) {
        c->p0_W = X * c->p0_W;
        c->p1_W = X * c->p1_W;
      } else {
        std::get<Box>(s).X_WB = X * std::get<Box>(s).X_WB;
      }
      if (cache.FollowMoved(id, s, reindex_at_m)) broad_phase->Move(id, ComputeAabb(s));
    }
    reindexed += cache.reindexed().size();
    cache.Update(broad_phase.get(), compatible);
    kept_pair_visits += cache.pairs().size();
    std::set<std::pair<PrimitiveId, PrimitiveId>> close;
    cache.TestPairs(shapes_W, tol_m, [&](PrimitiveId a, PrimitiveId b) {
      ++narrow_phase_calls;
      const double d_m = ShapeDistance(shapes_W[a], shapes_W[b]).distance_m;
      if (d_m < tol_m[a] + tol_m[b] || d_m <= 0.0) close.insert({a, b});
      return d_m;
    });
    return close;
  }
};

// Brute force: every pair, not both static, not compatible.
template <typename Keep>
std::vector<CandidatePair> AllPairs(const RandomScene& scene, Keep keep) {
  std::vector<CandidatePair> pairs;
  const PrimitiveId n = static_cast<PrimitiveId>(scene.shapes_W.size());
  for (PrimitiveId a = 0; a < n; ++a) {
    for (PrimitiveId b = a + 1; b < n; ++b) {
      if ((!scene.is_moving[a] && !scene.is_moving[b]) || scene.compatible.AreCompatible(a, b)) {
        continue;
      }
      if (keep(a, b)) pairs.push_back({a, b});
    }
  }
  return pairs;
}

void ExpectMatchesBruteForce(const RandomScene& scene,
                             const std::set<std::pair<PrimitiveId, PrimitiveId>>& close,
                             const std::string& where) {
  const PairCache& cache = scene.cache;
  // The indexed copies: within the slack of the shapes, the recorded displacement exact.
  for (PrimitiveId id = 0; id < scene.shapes_W.size(); ++id) {
    const double d_m = MaxPointDisplacement_m(cache.indexed_shape_W(id), scene.shapes_W[id]);
    ASSERT_LE(d_m, scene.slack_m) << where;
    ASSERT_EQ(d_m, cache.displacement_m(id)) << where;
    std::string why;
    ASSERT_TRUE(cache.ValidatePrimitive(id, scene.shapes_W[id], &why)) << where << ": " << why;
  }
  // Kept pairs: exactly those whose indexed boxes (grown by the index tolerance) overlap.
  const auto expected = AllPairs(scene, [&](PrimitiveId a, PrimitiveId b) {
    return ComputeAabb(cache.indexed_shape_W(a))
        .Inflated(scene.IndexTolerance(a))
        .Overlaps(ComputeAabb(cache.indexed_shape_W(b)).Inflated(scene.IndexTolerance(b)));
  });
  ASSERT_EQ(cache.pairs().size(), expected.size()) << where;
  for (std::size_t i = 0; i < expected.size(); ++i) {
    const KeptPair& kept = cache.pairs()[i];
    ASSERT_EQ(kept.pair, expected[i]) << where << " pair " << i;
    const PrimitiveId a = kept.pair.a, b = kept.pair.b;
    const double indexed_m =
        ShapeDistance(cache.indexed_shape_W(a), cache.indexed_shape_W(b)).distance_m;
    const double now_m = ShapeDistance(scene.shapes_W[a], scene.shapes_W[b]).distance_m;
    EXPECT_LE(kept.lower_bound_m, indexed_m + cache.BoundMargin_m(indexed_m)) << where;
    EXPECT_LE(kept.kinematics_bound_m, now_m + cache.BoundMargin_m(now_m)) << where;
  }
  std::string why;
  const std::vector<std::uint8_t> none_moved(scene.shapes_W.size(), 0);
  EXPECT_TRUE(cache.ValidatePairs(expected, scene.shapes_W, none_moved, &why))
      << where << ": " << why;
  // The skip test loses nothing: the close pairs are those of an all-pairs narrow phase.
  const auto all_close = AllPairs(scene, [&](PrimitiveId a, PrimitiveId b) {
    const double d_m = ShapeDistance(scene.shapes_W[a], scene.shapes_W[b]).distance_m;
    return d_m < scene.tol_m[a] + scene.tol_m[b] || d_m <= 0.0;
  });
  std::set<std::pair<PrimitiveId, PrimitiveId>> reference;
  for (const CandidatePair& p : all_close) reference.insert({p.a, p.b});
  EXPECT_EQ(close, reference) << where;
}

TEST(MonitorPairCache, SlackRuleAndReindexList) {
  PairCache cache(2, 1, 0.1, kWorldEdge_m);
  const Capsule c0 = CapsuleAt(Eigen::Vector3d(1, 1, 1), Eigen::Vector3d(1.2, 1, 1), 0.05);
  cache.SetIndexed(0, c0);
  EXPECT_TRUE(cache.is_stale());
  cache.BeginReindex();
  Capsule c1 = c0;
  c1.p1_W.z() += 0.06;  // within the slack: only the displacement is recorded
  EXPECT_FALSE(cache.FollowMoved(0, c1, 0.1));
  EXPECT_NEAR(cache.displacement_m(0), 0.06, 1e-15);
  EXPECT_TRUE(cache.reindexed().empty());
  EXPECT_FALSE(cache.FollowMoved(0, c1, 1.0));  // a threshold beyond the slack: the slack's
  c1.p0_W.x() -= 0.11;
  EXPECT_TRUE(cache.FollowMoved(0, c1, 1.0));
  EXPECT_EQ(cache.displacement_m(0), 0.0);
  c1.p1_W.z() += 0.06;  // beyond a threshold of half the slack (still within it): re-indexed
  EXPECT_TRUE(cache.FollowMoved(0, c1, 0.05));
  EXPECT_EQ(cache.displacement_m(0), 0.0);
  ASSERT_EQ(cache.reindexed().size(), 2u);
  EXPECT_EQ(cache.reindexed()[0], 0u);
  EXPECT_EQ(std::get<Capsule>(cache.indexed_shape_W(0)).p0_W, c1.p0_W);
  cache.BeginReindex();
  EXPECT_TRUE(cache.reindexed().empty());
}

TEST(MonitorPairCache, SkipTestMarginAndNaN) {
  PairCache cache(1, 0, 0.0, kWorldEdge_m);
  const double margin_m = cache.BoundMargin_m(0.5);
  EXPECT_GT(margin_m, 0.0);
  EXPECT_TRUE(cache.IsClear(0.5, 0.1, 0.4 - 2.0 * margin_m));
  EXPECT_FALSE(cache.IsClear(0.5, 0.1, 0.4));  // exactly at the threshold: not clear
  EXPECT_FALSE(cache.IsClear(std::nan(""), 0.0, 0.0));
}

TEST(MonitorPairCache, MatchesBruteForceOverRandomScenes) {
  std::printf("seed %llu\n", static_cast<unsigned long long>(kSeed));
  std::mt19937_64 rng(kSeed);
  for (const BroadPhaseMethod method : {BroadPhaseMethod::kOctree, BroadPhaseMethod::kNaive}) {
    for (const double slack_m : {0.0, 0.02, 0.08}) {
      for (int scene_index = 0; scene_index < 3; ++scene_index) {
        RandomScene scene(method, 60, slack_m, &rng);
        std::uniform_real_distribution<double> unit(0.0, 1.0);
        for (int step = 0; step < 60; ++step) {
          const std::string where = "slack " + std::to_string(slack_m) + " scene " +
                                    std::to_string(scene_index) + " step " +
                                    std::to_string(step);
          // Now and then a scene change: a primitive removed and added back (stale), or a
          // compatibility flipped.
          if (unit(rng) < 0.1) {
            const PrimitiveId id = static_cast<PrimitiveId>(unit(rng) * 60) % 60;
            scene.broad_phase->Remove(id);
            scene.Add(id);
          } else if (unit(rng) < 0.1) {
            const PrimitiveId a = static_cast<PrimitiveId>(unit(rng) * 59) % 59;
            scene.compatible.Set(a, a + 1, !scene.compatible.AreCompatible(a, a + 1));
            scene.cache.MarkStale();
          }
          const auto close = scene.Step(0.01, &rng);
          ExpectMatchesBruteForce(scene, close, where);
          if (HasFatalFailure()) return;
        }
        // The test exercises the cache: with a slack, pairs are skipped and primitives stay
        // within it; without, every moved primitive is re-indexed.
        std::printf("slack %.2f: %llu kept pair visits, %llu narrow phases, %llu re-indexed\n",
                    slack_m, static_cast<unsigned long long>(scene.kept_pair_visits),
                    static_cast<unsigned long long>(scene.narrow_phase_calls),
                    static_cast<unsigned long long>(scene.reindexed));
        EXPECT_GT(scene.narrow_phase_calls, 0u);
        if (slack_m > 0.0) {
          EXPECT_LT(scene.narrow_phase_calls, scene.kept_pair_visits);
        }
      }
    }
  }
}

}  // namespace
}  // namespace arm_collision_monitor
