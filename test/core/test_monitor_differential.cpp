// The Monitor against an independent brute force (all pairs, ShapeDistance, compatibility) on
// seeded random configurations and random smooth trajectories, for every broad phase; and
// Check() against Update().
#include <limits>
#include <string>
#include <vector>

#include "test_monitor_util.h"

namespace arm_collision_monitor {
namespace {

using test::AllMethods;
using test::ExpectSameWarnings;
using test::LimitsOf;
using test::LoadBundledWorkcell;
using test::OptionsFor;
using test::ReferenceWarnings;

constexpr std::uint64_t kSeed = 20261121;

class MonitorDifferential : public ::testing::TestWithParam<BroadPhaseMethod> {};

TEST_P(MonitorDifferential, RandomConfigurationsMatchBruteForce) {
  const auto wc = LoadBundledWorkcell();
  Monitor monitor(wc, OptionsFor(GetParam()));
  std::mt19937_64 rng(test::PrintSeed(kSeed));
  const test::JointLimits limits = LimitsOf(*wc);
  int configurations_with_warnings = 0;
  for (int k = 0; k < 2000; ++k) {
    const Eigen::VectorXd q = test::RandomQ(limits, &rng);
    const CycleReport checked = monitor.Check(q);
    const CycleReport& report = monitor.Update(q);
    const auto expected = ReferenceWarnings(*wc, q);
    const std::string context = BroadPhaseMethodName(GetParam()) + " configuration " +
                                std::to_string(k);
    ExpectSameWarnings(*wc, expected, report.warnings, context);
    ExpectSameWarnings(*wc, expected, checked.warnings, context + " (Check)");
    EXPECT_EQ(report.stop, test::ExpectedStop(report, !expected.empty()));
    EXPECT_EQ(checked.stop, !expected.empty());
    EXPECT_EQ(report.input, InputStatus::kOk);
    EXPECT_EQ(report.cycle, static_cast<std::uint64_t>(k + 1));
    configurations_with_warnings += expected.empty() ? 0 : 1;
    std::string error;
    ASSERT_TRUE(monitor.Validate(&error)) << error;
    if (::testing::Test::HasFailure()) break;
  }
  // Random configurations of two 7-DOF arms collide often; both outcomes must be exercised.
  EXPECT_GT(configurations_with_warnings, 100);
  EXPECT_LT(configurations_with_warnings, 2000);
}

// Odd trajectories move the arms in turns, as from one topic per arm: each cycle takes one
// arm's joints along the path while the other's hold (the kinematics then recomputes one arm).
TEST_P(MonitorDifferential, SmoothTrajectoriesMatchBruteForce) {
  const auto wc = LoadBundledWorkcell();
  std::mt19937_64 rng(test::PrintSeed(kSeed + 1));
  const test::JointLimits limits = LimitsOf(*wc);
  int cycles_with_warnings = 0;
  for (int trajectory = 0; trajectory < 10; ++trajectory) {
    Monitor monitor(wc, OptionsFor(GetParam()));
    const test::SmoothTrajectory path(limits, 0.8, &rng);
    Eigen::VectorXd q, q_path;
    for (int k = 0; k < 400; ++k) {
      path.At(k * monitor.options().cycle_period_s, &q_path);
      if (k == 0 || trajectory % 2 == 0) q = q_path;
      test::TakeArmsTurn(*wc, k, q_path, &q);
      const CycleReport checked = monitor.Check(q);
      const CycleReport& report = monitor.Update(q);
      const auto expected = ReferenceWarnings(*wc, q);
      const std::string context = BroadPhaseMethodName(GetParam()) + " trajectory " +
                                  std::to_string(trajectory) + " cycle " + std::to_string(k);
      ExpectSameWarnings(*wc, expected, report.warnings, context);
      ExpectSameWarnings(*wc, expected, checked.warnings, context + " (Check)");
      // A bounded cycle computes no poses: it reports none moved.
      EXPECT_EQ(report.bounded ? 0u : checked.moved_primitives, report.moved_primitives)
          << context;
      cycles_with_warnings += expected.empty() ? 0 : 1;
      std::string error;
      ASSERT_TRUE(monitor.Validate(&error)) << error;
      if (::testing::Test::HasFailure()) return;
    }
  }
  EXPECT_GT(cycles_with_warnings, 0);
}

// Links modelled by spheres (capsules whose endpoints coincide, as a sphere-tree robot's), which
// the cycle transforms and follows by one point: the bundled scene with a variant "spheres" of
// three spheres and one capsule for links 2 to 6 of both arms, switched in.
std::shared_ptr<const Workcell> LoadSphereLinkedWorkcell(std::vector<std::string>* links) {
  std::string variants;
  for (const char* arm : {"left", "right"}) {
    for (int k = 2; k <= 6; ++k) {
      const std::string link = std::string(arm) + "_link" + std::to_string(k);
      links->push_back(link);
      variants += "  - link: " + link + "\n    name: spheres\n    capsules:\n";
      for (int s = 0; s < 3; ++s) {
        const std::string z = std::to_string(0.08 * s);
        variants += "      - {name: s" + std::to_string(s) + ", p0_m: [0.0, 0.0, " + z +
                    "], p1_m: [0.0, 0.0, " + z + "], radius_m: 0.07}\n";
      }
      variants += "      - {name: c, p0_m: [0.0, 0.03, 0.0], p1_m: [0.0, 0.03, 0.16], "
                  "radius_m: 0.03}\n";
    }
  }
  return test::LoadBundledSceneEdited("differential_spheres", [&](std::string* scene) {
    const std::size_t at = scene->find("\nvariants:\n");
    EXPECT_NE(at, std::string::npos);
    scene->insert(at + 11, variants);
  });
}

TEST_P(MonitorDifferential, SphereModelledLinksMatchBruteForce) {
  std::vector<std::string> links;
  const auto wc = LoadSphereLinkedWorkcell(&links);
  std::mt19937_64 rng(test::PrintSeed(kSeed + 2));
  const test::JointLimits limits = LimitsOf(*wc);
  test::ReferenceScene reference;
  for (const std::string& link : links) {
    reference.variant_of_link[wc->kinematics.FindLink(link)] = "spheres";
  }
  int cycles_with_warnings = 0, bounded_cycles = 0;
  for (int trajectory = 0; trajectory < 6; ++trajectory) {
    Monitor monitor(wc, OptionsFor(GetParam()));
    std::string error;
    for (const std::string& link : links) {
      ASSERT_TRUE(monitor.SwitchModel(link, "spheres", &error)) << error;
    }
    const test::SmoothTrajectory path(limits, 0.8, &rng);
    Eigen::VectorXd q;
    // Sampled at four times the cycle rate: small steps, so that bounded cycles occur.
    for (int k = 0; k < 800; ++k) {
      path.At(0.25 * k * monitor.options().cycle_period_s, &q);
      const CycleReport& report = monitor.Update(q);
      const auto expected = ReferenceWarnings(*wc, q, reference);
      ExpectSameWarnings(*wc, expected, report.warnings,
                         BroadPhaseMethodName(GetParam()) + " trajectory " +
                             std::to_string(trajectory) + " cycle " + std::to_string(k));
      cycles_with_warnings += expected.empty() ? 0 : 1;
      bounded_cycles += report.bounded ? 1 : 0;
      ASSERT_TRUE(monitor.Validate(&error)) << error;
      if (::testing::Test::HasFailure()) return;
    }
  }
  EXPECT_GT(cycles_with_warnings, 0);
  EXPECT_GT(bounded_cycles, 0);  // the kinematics cycles between follow slack kept by bounds
}

INSTANTIATE_TEST_SUITE_P(AllBroadPhases, MonitorDifferential, ::testing::ValuesIn(AllMethods()),
                         [](const ::testing::TestParamInfo<BroadPhaseMethod>& info) {
                           return BroadPhaseMethodName(info.param);
                         });

// A bounded cycle's motion bounds hold: one step from a start pose (near home, where the roll
// axes run along the links, or anywhere) by a random joint step of one of several sizes; after
// each bounded step Validate() recomputes the true shapes and checks every primitive's motion
// against its bound, the slack, and every kept pair against its relative bound and threshold.
TEST(MonitorBounds, BoundedStepsStayWithinTheirMotionBounds) {
  const auto wc = LoadBundledWorkcell();
  const test::JointLimits limits = LimitsOf(*wc);
  std::mt19937_64 rng(test::PrintSeed(kSeed + 11));
  int bounded = 0;
  for (const double slack_m : {kDefaultIndexSlack_m, 0.5, 3.0}) {
    MonitorOptions options = OptionsFor(BroadPhaseMethod::kOctree);
    options.index_slack_m = slack_m;
    Monitor monitor(wc, options);
    for (int trial = 0; trial < 3000; ++trial) {
      const double spread = std::array<double, 3>{0.0, 0.1, 1.0}[trial % 3];
      const double step_rad = std::array<double, 4>{0.01, 0.05, 0.2, 0.6}[(trial / 3) % 4];
      const Eigen::VectorXd centre = (limits.lower + limits.upper) / 2;
      Eigen::VectorXd q0 = centre + spread * (test::RandomQ(limits, &rng) - centre);
      q0 = q0.cwiseMax(limits.lower).cwiseMin(limits.upper);
      if (!monitor.Update(q0).warnings.empty()) continue;
      Eigen::VectorXd q1 = q0;
      for (int i = 0; i < q1.size(); ++i) {
        q1[i] += std::uniform_real_distribution<double>(-step_rad, step_rad)(rng);
      }
      q1 = q1.cwiseMax(limits.lower).cwiseMin(limits.upper);
      bounded += monitor.Update(q1).bounded ? 1 : 0;
      std::string error;
      ASSERT_TRUE(monitor.Validate(&error))
          << error << " (slack " << slack_m << ", trial " << trial << ")";
    }
  }
  // The bounds must be exercised: a fair share of the steps are decided without kinematics.
  EXPECT_GT(bounded, 1000);
}

// Bounded cycles must count each primitive's displacement at the last kinematics, not only its
// motion since (IsProvablyClear). One joint (the first arm's wrist pitch) turns: its bound is
// tight for the farthest primitive. The turn leaves that primitive 45 % of the slack from its
// indexed copy (under the re-index rule's half), a refused message forces a kinematics cycle
// there, and the turn goes on in small steps: Validate measures every primitive's distance
// from its indexed copy.
TEST(MonitorBounds, BoundedCyclesCountTheDisplacementAtTheKinematics) {
  const auto wc = LoadBundledWorkcell();
  const test::JointLimits limits = LimitsOf(*wc);
  constexpr int kJoint = 5;  // the first arm's wrist pitch: levers rigid beyond it, so tight
  for (const BroadPhaseMethod method : {BroadPhaseMethod::kNaive, BroadPhaseMethod::kOctree}) {
    for (const double slack_m : {0.02, 0.05}) {
      MonitorOptions options = OptionsFor(method);
      options.index_slack_m = slack_m;
      Monitor monitor(wc, options);
      const Eigen::VectorXd q0 = (limits.lower + limits.upper) / 2;
      ASSERT_TRUE(monitor.Update(q0).warnings.empty());
      Eigen::VectorXd q = q0;
      q[kJoint] += 1e-3;
      const double lever_m = monitor.Update(q).step_motion_m / 1e-3;  // the farthest's radius
      ASSERT_GT(lever_m, 0.1);
      q[kJoint] = q0[kJoint] + 0.45 * slack_m / lever_m;
      monitor.Update(q);
      Eigen::VectorXd bad = q;
      bad[0] = std::numeric_limits<double>::quiet_NaN();
      ASSERT_EQ(monitor.Update(bad).input, InputStatus::kNonFinite);
      ASSERT_FALSE(monitor.Update(q).bounded);  // the kinematics, at 45 % of the slack
      int bounded = 0;
      for (int k = 1; k <= 150; ++k) {  // 1.5 slacks more, 1 % of the slack per step
        q[kJoint] += 0.01 * slack_m / lever_m;
        bounded += monitor.Update(q).bounded ? 1 : 0;
        std::string error;
        ASSERT_TRUE(monitor.Validate(&error))
            << error << " (" << BroadPhaseMethodName(method) << ", slack " << slack_m
            << ", step " << k << ")";
      }
      EXPECT_GT(bounded, 100) << BroadPhaseMethodName(method) << ", slack " << slack_m;
    }
  }
}

// Bounded cycles must stop at a pair's first warning: with a slack longer than an arm, only
// the kept pairs' gaps end a run of bounded cycles. One joint at a time turns in steps of about
// 2 mm at its farthest primitive, from seeded warning-free configurations (back at a limit)
// until a warning or 1,500 steps; every cycle's warnings must equal the brute force's.
TEST(MonitorBounds, BoundedCyclesStopAtTheFirstWarningOfAClosingPair) {
  const auto wc = LoadBundledWorkcell();
  const test::JointLimits limits = LimitsOf(*wc);
  std::mt19937_64 rng(test::PrintSeed(kSeed + 13));
  std::uniform_int_distribution<int> joint(0, static_cast<int>(limits.lower.size()) - 1);
  MonitorOptions options = OptionsFor(BroadPhaseMethod::kNaive);
  options.index_slack_m = 3.0;
  int bounded = 0, sweeps_warned = 0;
  for (int sweep = 0; sweep < 200 && !::testing::Test::HasFailure(); ++sweep) {
    Monitor monitor(wc, options);
    Eigen::VectorXd q = test::RandomQ(limits, &rng);
    if (!ReferenceWarnings(*wc, q).empty()) continue;
    monitor.Update(q);
    const int k = joint(rng);
    q[k] += 1e-3;
    const double lever_m = monitor.Update(q).step_motion_m / 1e-3;
    if (!(lever_m > 0.05)) continue;
    double step_rad = (sweep % 2 == 0 ? 1.0 : -1.0) * 0.002 / lever_m;
    for (int step = 0; step < 1500; ++step) {
      if (q[k] + step_rad < limits.lower[k] || q[k] + step_rad > limits.upper[k]) {
        step_rad = -step_rad;  // back from the limit
      }
      q[k] += step_rad;
      const CycleReport& report = monitor.Update(q);
      bounded += report.bounded ? 1 : 0;
      const auto expected = ReferenceWarnings(*wc, q);
      ExpectSameWarnings(*wc, expected, report.warnings,
                         "sweep " + std::to_string(sweep) + " step " + std::to_string(step));
      if (!expected.empty()) {
        ++sweeps_warned;
        break;
      }
    }
  }
  std::printf("%d sweeps ended in a warning, %d bounded cycles\n", sweeps_warned, bounded);
  // Enough sweeps meet a part for the shortcut to matter (24 with this seed), and most cycles
  // of the approach are bounded.
  EXPECT_GT(sweeps_warned, 15);
  EXPECT_GT(bounded, 50000);
}

// The index slack changes the work, never the warnings: for slacks from 0 (the seed's loop) to
// more than an arm's length, on smooth motion at three speeds with occasional jumps, with fixed
// and speed-scaled tolerances, the Monitor's warnings equal the brute force's in every cycle,
// Validate() holds (kept pairs = overlapping indexed boxes, bounds below the indexed shapes'
// distances), and a positive slack re-indexes and tests less than slack 0.
TEST(MonitorSlack, EverySlackGivesTheBruteForceWarnings) {
  const auto wc = LoadBundledWorkcell();
  const test::JointLimits limits = LimitsOf(*wc);
  struct Work {
    std::uint64_t moved = 0, reindexed = 0, candidates = 0, narrow = 0;
    std::uint64_t slow_candidates = 0, slow_narrow = 0;  // in the slowest motion
    std::uint64_t bounded = 0;  // cycles decided without kinematics
  };
  for (const BroadPhaseMethod method : {BroadPhaseMethod::kOctree, BroadPhaseMethod::kNaive}) {
    for (const bool speed_scaled : {false, true}) {
      for (const double slack_m : {0.0, 0.02, kDefaultIndexSlack_m, 0.5, 3.0}) {
        MonitorOptions options = OptionsFor(method);
        options.index_slack_m = slack_m;
        options.speed_scaled_tolerance = speed_scaled;
        Monitor monitor(wc, options);
        std::mt19937_64 rng(test::PrintSeed(kSeed + 7));
        Work work;
        int cycles_with_warnings = 0;
        for (const double speed_fraction : {0.05, 0.3, 0.9}) {
          const test::SmoothTrajectory path(limits, speed_fraction, &rng);
          Eigen::VectorXd q;
          for (int k = 0; k < 300; ++k) {
            if (k % 97 == 96) {
              q = test::RandomQ(limits, &rng);  // a jump: far beyond any slack
            } else {
              path.At(k * options.cycle_period_s, &q);
            }
            // Speed-scaled tolerances depend on the motion: the brute force is then Check()
            // (all pairs on a copy of the model, no index, no bounds).
            const CycleReport checked = monitor.Check(q);
            const CycleReport& report = monitor.Update(q);
            const auto expected = ReferenceWarnings(*wc, q);
            const std::string context = BroadPhaseMethodName(method) + " slack " +
                                        std::to_string(slack_m) + " speed-scaled " +
                                        std::to_string(speed_scaled) + " speed " +
                                        std::to_string(speed_fraction) + " cycle " +
                                        std::to_string(k);
            if (speed_scaled) {
              const std::vector<Warning> at_q = test::AtSampleWarnings(report.warnings);
              ASSERT_EQ(checked.warnings.size(), at_q.size()) << context;
              for (std::size_t i = 0; i < at_q.size(); ++i) {
                EXPECT_EQ(checked.warnings[i].a, at_q[i].a) << context;
                EXPECT_EQ(checked.warnings[i].b, at_q[i].b) << context;
              }
            } else {
              ExpectSameWarnings(*wc, expected, report.warnings, context);
            }
            std::string error;
            ASSERT_TRUE(monitor.Validate(&error)) << context << ": " << error;
            if (::testing::Test::HasFailure()) return;
            cycles_with_warnings += report.warnings.empty() ? 0 : 1;
            work.moved += report.moved_primitives;
            work.reindexed += report.reindexed_primitives;
            work.candidates += report.candidate_pairs;
            work.bounded += report.bounded ? 1 : 0;
            work.narrow += report.narrow_phase_tests;
            if (speed_fraction == 0.05) {
              work.slow_candidates += report.candidate_pairs;
              work.slow_narrow += report.narrow_phase_tests;
            }
          }
        }
        EXPECT_GT(cycles_with_warnings, 0);
        std::printf(
            "[ slack %.2f ] moved %llu re-indexed %llu candidate pairs %llu narrow %llu (slowest "
            "motion: %llu, %llu) bounded cycles %llu\n",
            slack_m, static_cast<unsigned long long>(work.moved),
            static_cast<unsigned long long>(work.reindexed),
            static_cast<unsigned long long>(work.candidates),
            static_cast<unsigned long long>(work.narrow),
            static_cast<unsigned long long>(work.slow_candidates),
            static_cast<unsigned long long>(work.slow_narrow),
            static_cast<unsigned long long>(work.bounded));
        if (slack_m == 0.0) {
          // Every move re-indexes but a link turning about its own capsule's axis (link 1).
          EXPECT_GT(work.reindexed, work.moved * 3 / 4);
        } else if (slack_m >= kDefaultIndexSlack_m) {
          EXPECT_LT(work.reindexed, work.moved / 3) << slack_m;
          // Bounded cycles happen (and were checked against the brute force above).
          if (!speed_scaled) {
            EXPECT_GT(work.bounded, 0u) << slack_m;
          }
          // In slow motion most kept pairs are cleared by their bounds (not all: links two
          // apart on one arm stay within their slack of each other).
          EXPECT_LT(work.slow_narrow, work.slow_candidates / 2) << slack_m;
        }
      }
    }
  }
}

// The reach analysis leaves out statics no arm (nor anything it may carry) can reach; the
// differential tests above show none of them could ever warn. Here: some are left out, and
// everything else of the default model is in.
TEST(MonitorReach, UnreachableStaticsAreLeftOut) {
  const auto wc = LoadBundledWorkcell();
  Monitor monitor(wc, MonitorOptions{});
  int left_out = 0;
  // The loaded primitives (the live objects' free slots after them are inactive too).
  for (PrimitiveId id = 0; id < wc->primitives.size(); ++id) {
    const PrimitiveSpec& p = wc->primitives[id];
    const bool is_default_model = p.link_index < 0 || p.variant.empty();
    if (!monitor.is_active(id)) {
      EXPECT_TRUE(p.is_static || !is_default_model) << p.name;
      if (is_default_model) ++left_out;
    } else {
      EXPECT_TRUE(is_default_model) << p.name;
    }
  }
  EXPECT_GT(left_out, 0);
  // The back wall is 3 m behind arms that reach 1.9 m.
  EXPECT_FALSE(monitor.is_active(test::Prim(*wc, "back_wall")));
  EXPECT_TRUE(monitor.is_active(test::Prim(*wc, "front_table_top")));
  EXPECT_TRUE(monitor.is_active(test::Prim(*wc, "floor")));
}

TEST(MonitorReach, AutoBroadPhasePicksByScaleRule) {
  const auto wc = LoadBundledWorkcell();
  MonitorOptions options;
  options.broad_phase.method = BroadPhaseMethod::kAuto;
  Monitor monitor(wc, options);
  // The rule's inputs counted independently: active primitives of the scene, moving or not.
  std::uint32_t moving = 0, statics = 0;
  for (PrimitiveId id = 0; id < monitor.primitive_count(); ++id) {
    if (!monitor.is_active(id)) continue;
    const PrimitiveSpec& spec = wc->primitives[id];
    const bool is_moving = spec.link_index >= 0 ? !spec.is_static
                                                : !wc->objects[spec.object_index].frame.empty();
    ++(is_moving ? moving : statics);
  }
  EXPECT_GT(moving, 0u);
  EXPECT_GT(statics, 0u);
  EXPECT_EQ(monitor.broad_phase_name(),
            BroadPhaseMethodName(ChooseBroadPhaseMethod(moving, statics)));
}

}  // namespace
}  // namespace arm_collision_monitor
