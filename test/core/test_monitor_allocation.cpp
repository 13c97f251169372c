// The steady-state cycle allocates nothing: every allocation of the process is counted through
// a replaced global operator new, over a few thousand moving cycles of both arms.
#include <atomic>
#include <cstdlib>
#include <new>

#include "allocation_counter.h"
#include "test_monitor_util.h"


namespace arm_collision_monitor {
namespace {

class MonitorAllocation : public ::testing::TestWithParam<BroadPhaseMethod> {};

TEST_P(MonitorAllocation, SteadyStateUpdateDoesNotAllocate) {
  const auto wc = test::LoadBundledWorkcell();
  MonitorOptions options = test::OptionsFor(GetParam());
  for (const bool speed_scaled : {false, true}) {
    options.speed_scaled_tolerance = speed_scaled;
    Monitor monitor(wc, options);
    std::mt19937_64 rng(test::PrintSeed(4242));
    const test::JointLimits limits = test::LimitsOf(*wc);
    const test::SmoothTrajectory path(limits, 0.8, &rng);
    const int cycles = 3000;
    std::vector<Eigen::VectorXd> qs(2 * cycles);
    for (int k = 0; k < 2 * cycles; ++k) path.At(k * options.cycle_period_s, &qs[k]);
    // Warm-up: the first pass may grow pools (octree nodes, location links) once.
    for (int k = 0; k < cycles; ++k) monitor.Update(qs[k]);
    std::uint64_t moved = 0, warned = 0;
    const std::uint64_t before = test::AllocationCount();
    for (int k = cycles; k < 2 * cycles; ++k) {
      const CycleReport& report = monitor.Update(qs[k]);
      moved += report.moved_primitives;
      warned += report.warnings.size();
    }
    const std::uint64_t allocations = test::AllocationCount() - before;
    EXPECT_EQ(allocations, 0u) << BroadPhaseMethodName(GetParam())
                               << (speed_scaled ? " speed-scaled" : "");
    // The cycles really moved things (every arm primitive, nearly every cycle).
    EXPECT_GT(moved, static_cast<std::uint64_t>(cycles) * 10);
    std::printf("%s%s: %llu allocations, %llu primitive moves, %llu warnings\n",
                BroadPhaseMethodName(GetParam()).c_str(), speed_scaled ? " speed-scaled" : "",
                static_cast<unsigned long long>(allocations),
                static_cast<unsigned long long>(moved), static_cast<unsigned long long>(warned));
  }
}

// The swept check on fast steps (5 Hz at the velocity limits: beyond the index slack, and
// contacts between samples) does not allocate either.
TEST_P(MonitorAllocation, SweptStepsDoNotAllocate) {
  const auto wc = test::LoadBundledWorkcell();
  MonitorOptions options = test::OptionsFor(GetParam());
  Monitor monitor(wc, options);
  std::mt19937_64 rng(test::PrintSeed(4343));
  const test::JointLimits limits = test::LimitsOf(*wc);
  const test::SmoothTrajectory path(limits, 1.0, &rng);
  const int cycles = 400;
  std::vector<Eigen::VectorXd> qs(2 * cycles);
  for (int k = 0; k < 2 * cycles; ++k) path.At(k * 0.2, &qs[k]);
  for (int k = 0; k < cycles; ++k) monitor.Update(qs[k]);
  std::uint64_t swept_pairs = 0, between = 0;
  const std::uint64_t before = test::AllocationCount();
  for (int k = cycles; k < 2 * cycles; ++k) {
    const CycleReport& report = monitor.Update(qs[k]);
    swept_pairs += report.swept_pairs;
    for (const Warning& w : report.warnings) between += w.between_samples ? 1 : 0;
  }
  const std::uint64_t allocations = test::AllocationCount() - before;
  EXPECT_EQ(allocations, 0u) << BroadPhaseMethodName(GetParam());
  EXPECT_GT(swept_pairs, 0u);
  EXPECT_GT(between, 0u);
  std::printf("%s: %llu allocations, %llu swept pairs, %llu between-samples warnings\n",
              BroadPhaseMethodName(GetParam()).c_str(),
              static_cast<unsigned long long>(allocations),
              static_cast<unsigned long long>(swept_pairs),
              static_cast<unsigned long long>(between));
}

// Run-time scene changes (grasp targets, model switching, attach / detach, frame-bound poses)
// and the cycles after them do not allocate either, once each has happened once.
TEST_P(MonitorAllocation, SceneChangesDoNotAllocate) {
  const auto wc = test::LoadBundledWorkcell();
  Monitor monitor(wc, test::OptionsFor(GetParam()));
  const Eigen::VectorXd grasp_q = test::ArmReachDown(*wc, "right", 0.1, -1.55, 0.95);
  Eigen::VectorXd carry_q = grasp_q;
  carry_q[test::JointIndex(*wc, "right_joint1")] *= 0.5;
  Eigen::Isometry3d X_WO = Eigen::Isometry3d::Identity();
  X_WO.translation() << 0.5, 0.0, 1.8;
  std::string error;
  error.reserve(512);  // error messages are not expected; keep them off the count if any
  auto round = [&](bool* ok) {
    *ok = monitor.SetGraspTarget("right_link7", "right_box", true, &error);
    monitor.Update(grasp_q);
    *ok = *ok && monitor.Attach("right_box", "right_link7", &error);
    *ok = *ok && monitor.SwitchModel("right_link7", "grasp", &error);
    monitor.Update(carry_q);
    *ok = *ok && monitor.SetObjectPose("camera", X_WO, &error);
    monitor.Update(grasp_q);
    *ok = *ok && monitor.Detach("right_box", &error);
    *ok = *ok && monitor.SwitchModel("right_link7", "", &error);
    *ok = *ok && monitor.SetGraspTarget("right_link7", "right_box", false, &error);
    monitor.Update(carry_q);
  };
  bool ok = false;
  round(&ok);  // warm-up
  ASSERT_TRUE(ok) << error;
  const std::uint64_t before = test::AllocationCount();
  for (int k = 0; k < 100; ++k) round(&ok);
  const std::uint64_t allocations = test::AllocationCount() - before;
  EXPECT_TRUE(ok) << error;
  EXPECT_EQ(allocations, 0u) << BroadPhaseMethodName(GetParam());
  std::string validate_error;
  EXPECT_TRUE(monitor.Validate(&validate_error)) << validate_error;
}

INSTANTIATE_TEST_SUITE_P(AllBroadPhases, MonitorAllocation,
                         ::testing::ValuesIn(test::AllMethods()),
                         [](const ::testing::TestParamInfo<BroadPhaseMethod>& info) {
                           return BroadPhaseMethodName(info.param);
                         });

}  // namespace
}  // namespace arm_collision_monitor
