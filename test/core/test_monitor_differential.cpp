// The Monitor against an independent brute force (all pairs, ShapeDistance, compatibility) on
// seeded random configurations and random smooth trajectories, for every broad phase; and
// Check() against Update().
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
    EXPECT_EQ(report.stop, !expected.empty());
    EXPECT_EQ(checked.stop, report.stop);
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

TEST_P(MonitorDifferential, SmoothTrajectoriesMatchBruteForce) {
  const auto wc = LoadBundledWorkcell();
  std::mt19937_64 rng(test::PrintSeed(kSeed + 1));
  const test::JointLimits limits = LimitsOf(*wc);
  int cycles_with_warnings = 0;
  for (int trajectory = 0; trajectory < 10; ++trajectory) {
    Monitor monitor(wc, OptionsFor(GetParam()));
    const test::SmoothTrajectory path(limits, 0.8, &rng);
    Eigen::VectorXd q;
    for (int k = 0; k < 400; ++k) {
      path.At(k * monitor.options().cycle_period_s, &q);
      const CycleReport checked = monitor.Check(q);
      const CycleReport& report = monitor.Update(q);
      const auto expected = ReferenceWarnings(*wc, q);
      const std::string context = BroadPhaseMethodName(GetParam()) + " trajectory " +
                                  std::to_string(trajectory) + " cycle " + std::to_string(k);
      ExpectSameWarnings(*wc, expected, report.warnings, context);
      ExpectSameWarnings(*wc, expected, checked.warnings, context + " (Check)");
      EXPECT_EQ(checked.moved_primitives, report.moved_primitives) << context;
      cycles_with_warnings += expected.empty() ? 0 : 1;
      std::string error;
      ASSERT_TRUE(monitor.Validate(&error)) << error;
      if (::testing::Test::HasFailure()) return;
    }
  }
  EXPECT_GT(cycles_with_warnings, 0);
}

INSTANTIATE_TEST_SUITE_P(AllBroadPhases, MonitorDifferential, ::testing::ValuesIn(AllMethods()),
                         [](const ::testing::TestParamInfo<BroadPhaseMethod>& info) {
                           return BroadPhaseMethodName(info.param);
                         });

// The reach analysis leaves out statics no arm (nor anything it may carry) can reach; the
// differential tests above show none of them could ever warn. Here: some are left out, and
// everything else of the default model is in.
TEST(MonitorReach, UnreachableStaticsAreLeftOut) {
  const auto wc = LoadBundledWorkcell();
  Monitor monitor(wc, MonitorOptions{});
  int left_out = 0;
  for (PrimitiveId id = 0; id < monitor.primitive_count(); ++id) {
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
  options.auto_broad_phase = true;
  Monitor monitor(wc, options);
  std::uint32_t active = 0;
  for (PrimitiveId id = 0; id < monitor.primitive_count(); ++id) active += monitor.is_active(id);
  EXPECT_EQ(monitor.broad_phase_name(), active >= kAutoOctreeMinPrimitives ? "octree" : "naive");
}

}  // namespace
}  // namespace arm_collision_monitor
