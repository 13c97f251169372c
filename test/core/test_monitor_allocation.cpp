// The steady-state cycle allocates nothing: every allocation of the process is counted through
// a replaced global operator new, over a few thousand moving cycles of both arms (speed-scaled,
// with re-samples of some joints at rest too).
#include <atomic>
#include <cstdlib>
#include <new>

#include "allocation_counter.h"
#include "arm_collision_monitor/monitor/monitor_model.h"
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
    Eigen::VectorXd t_s = Eigen::VectorXd::Zero(qs[0].size());
    const std::uint64_t before = test::AllocationCount();
    for (int k = cycles; k < 2 * cycles; ++k) {
      const CycleReport& report = monitor.Update(qs[k]);
      moved += report.moved_primitives;
      warned += report.warnings.size();
      if (!speed_scaled || k % 4 != 0) continue;
      // The same q again, every other joint sampled anew (its own time): they come to rest.
      for (Eigen::Index i = 0; i < t_s.size(); i += 2) t_s[i] = k;
      monitor.Update(qs[k], t_s);
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

// The per-cycle pair buffers are reserved for the pairs with a primitive that may move (a link
// below a moving joint, an attachable or frame-bound object, a live slot): two resting ones are
// never tested. 2,000 more resting boxes add 2,000 pairs per such primitive, not 2 million (all
// pairs of 20,000 boxes took 5 GB at start-up).
TEST(MonitorModelReservation, PairBuffersCountPairsWithAPrimitiveThatMayMove) {
  const auto expected_pairs = [](const MonitorModel& model) {
    const Workcell& w = *model.workcell;
    std::size_t may_move = 0;
    for (PrimitiveId id = 0; id < model.primitive_count; ++id) {
      const PrimitiveSpec& p = w.primitives[id];
      const ObjectSpec* o = p.object_index >= 0 ? &w.objects[p.object_index] : nullptr;
      may_move += (p.link_index >= 0 && !p.is_static) || model.is_live(id) ||
                  (o != nullptr && (o->is_attachable || !o->frame.empty()));
    }
    const std::size_t n = model.primitive_count;
    return may_move * (may_move - 1) / 2 + may_move * (n - may_move);
  };
  const MonitorModel bundled(test::LoadBundledWorkcell(), MonitorOptions{});
  EXPECT_EQ(bundled.max_tested_pairs, expected_pairs(bundled));
  std::string boxes;
  for (int k = 0; k < 2000; ++k) {
    boxes += "  - {name: crate" + std::to_string(k) + ", size_m: [0.01, 0.01, 0.01], pose: " +
             "{xyz_m: [" + std::to_string(-2.9 + 0.02 * (k % 40)) + ", " +
             std::to_string(-1.5 + 0.05 * (k / 40)) + ", 0.02]}}\n";
  }
  const MonitorModel crowded(test::LoadBundledSceneEdited("crates", [&](std::string* scene) {
                               const std::string objects = "\nobjects:\n";
                               scene->insert(scene->find(objects) + objects.size(), boxes);
                             }),
                             MonitorOptions{});
  EXPECT_EQ(crowded.max_tested_pairs, expected_pairs(crowded));
  const std::size_t may_move = (crowded.max_tested_pairs - bundled.max_tested_pairs) / 2000;
  EXPECT_EQ(crowded.max_tested_pairs, bundled.max_tested_pairs + 2000 * may_move);
  // About 150 may move here (the arms, the grip variants, two boxes, the camera, 128 live slots).
  EXPECT_LT(may_move, 200u);
  EXPECT_LT(crowded.max_tested_pairs, std::size_t{crowded.primitive_count} *
                                          (crowded.primitive_count - 1) / 2 / 5);
}

INSTANTIATE_TEST_SUITE_P(AllBroadPhases, MonitorAllocation,
                         ::testing::ValuesIn(test::AllMethods()),
                         [](const ::testing::TestParamInfo<BroadPhaseMethod>& info) {
                           return BroadPhaseMethodName(info.param);
                         });

}  // namespace
}  // namespace arm_collision_monitor
