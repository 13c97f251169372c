// StopPolicy with plain numbers: every stop reason (start-up, refused input, incomplete model,
// monitor refusal, stale joints, clock going back, object pose, warnings), their ranking within
// a cycle, and each one's clearing only after the hold.
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "arm_collision_monitor/safety/stop_policy.h"

namespace arm_collision_monitor {
namespace {

constexpr double kHold_s = 0.25;
constexpr double kTimeout_s = 0.5;
constexpr double kStep_s = 0.0625;
const std::vector<std::string> kJoints = {"a1", "b1"};

std::vector<PrimitiveSpec> Primitives() {
  std::vector<PrimitiveSpec> primitives(3);
  primitives[0].name = "left_link3";
  primitives[1].name = "right_link4";
  primitives[2].name = "right_link5";
  return primitives;
}

CycleReport CleanReport() {
  CycleReport report;
  report.stop = false;
  return report;
}

CycleReport WarningReport() {
  CycleReport report;
  Warning w;
  w.a = 0;
  w.b = 1;
  w.distance_m = 0.012;
  w.threshold_m = 0.061;
  report.warnings.push_back(w);
  report.stop = true;
  return report;
}

class StopPolicyTest : public ::testing::Test {
 protected:
  // Both joints received at now_s.
  void Feed(double now_s) {
    for (const std::string& name : kJoints) {
      const std::vector<std::string> names = {name};
      const std::vector<double> positions = {0.0};
      ASSERT_EQ(input_.Merge(NamedPositions{names, positions, now_s}, now_s),
                MergeStatus::kAccepted);
    }
  }
  // One cycle the way the node runs it: fresh input at now_s, then `report` (if the input
  // allows running the Monitor).
  // `why`: what the refusal (pending, or the Monitor's of `report`) was about.
  void Cycle(double now_s, const CycleReport& report,
             MergeStatus pending = MergeStatus::kAccepted, const std::string& why = "") {
    policy_.ObserveClock(now_s);
    if (policy_.BeginCycle(pending, why, input_)) {
      policy_.OnCycleReport(report, why, primitives_, input_, now_s);
    }
    policy_.EndCycle(now_s);
  }
  // Clean cycles every kStep_s from t0_s: the time of the first one that clears the stop.
  // Times in the tests are multiples of kStep_s, exact in binary, so that "at least the hold
  // after" is tested at its boundary without rounding.
  double ClearedAt(double t0_s) {
    for (double t = t0_s; t < t0_s + 10.0 * kHold_s; t += kStep_s) {
      Feed(t);
      Cycle(t, CleanReport());
      if (!policy_.stop()) return t;
    }
    return -1.0;
  }

  JointMerger input_{kJoints, kTimeout_s};
  StopPolicy policy_{kHold_s};
  std::vector<PrimitiveSpec> primitives_ = Primitives();
};

TEST_F(StopPolicyTest, StartsStoppedUntilTheModelIsComplete) {
  EXPECT_TRUE(policy_.stop());
  EXPECT_EQ(policy_.reason(), "waiting for joint states");
  // A cycle before any input: both joints missing, counted, the first named.
  Cycle(0.5, CleanReport());
  EXPECT_EQ(policy_.status(), SafetyStatus::kIncomplete);
  EXPECT_EQ(policy_.reason(), std::string("2 joints never received, the first 'a1' (") +
                                  JointDefaultsHint(2) + ")");
  const std::vector<std::string> names = {"a1"};
  const std::vector<double> positions = {0.0};
  ASSERT_EQ(input_.Merge(NamedPositions{names, positions, 1.0}, 1.0), MergeStatus::kAccepted);
  Cycle(1.0, CleanReport());
  EXPECT_TRUE(policy_.stop());
  EXPECT_EQ(policy_.status(), SafetyStatus::kIncomplete);
  EXPECT_EQ(policy_.reason(),
            std::string("joint 'b1' never received (") + JointDefaultsHint(1) + ")");
  // Complete: cleared only after the hold from the last incomplete cycle.
  EXPECT_EQ(ClearedAt(1.0 + kStep_s), 1.0 + kHold_s);
  EXPECT_EQ(policy_.status(), SafetyStatus::kOk);
  EXPECT_EQ(policy_.reason(), "");
}

TEST_F(StopPolicyTest, CleanStartClearsAtOnce) {
  EXPECT_EQ(ClearedAt(1.0), 1.0);  // no condition was ever seen: no hold pending
}

TEST_F(StopPolicyTest, RefusedInputStopsAndHolds) {
  ASSERT_GE(ClearedAt(1.0), 0.0);
  for (const MergeStatus refused :
       {MergeStatus::kWrongSize, MergeStatus::kNonFinite, MergeStatus::kStale,
        MergeStatus::kStampBackwards, MergeStatus::kNoKnownJoints, MergeStatus::kFutureStamp}) {
    const double t = 10.0 * static_cast<double>(refused);
    Feed(t);
    Cycle(t, CleanReport(), refused);
    EXPECT_TRUE(policy_.stop());
    EXPECT_EQ(static_cast<int>(policy_.status()), static_cast<int>(refused));
    EXPECT_EQ(policy_.reason(), std::string("input refused: ") + MergeStatusName(refused));
    EXPECT_DOUBLE_EQ(policy_.hold_until_s(), t + kHold_s);
    // Still stopped just before the hold ends, cleared by the first clean cycle after it.
    Feed(t + kHold_s - kStep_s);
    Cycle(t + kHold_s - kStep_s, CleanReport());
    EXPECT_TRUE(policy_.stop());
    EXPECT_EQ(policy_.status(), SafetyStatus::kOk);
    Feed(t + kHold_s);
    Cycle(t + kHold_s, CleanReport());
    EXPECT_FALSE(policy_.stop());
  }
}

TEST_F(StopPolicyTest, MonitorRefusalStops) {
  ASSERT_GE(ClearedAt(1.0), 0.0);
  Feed(2.0);
  CycleReport refused = CleanReport();
  refused.input = InputStatus::kOutOfLimits;
  Cycle(2.0, refused);
  EXPECT_TRUE(policy_.stop());
  EXPECT_EQ(policy_.status(), SafetyStatus::kOutOfLimits);
  EXPECT_EQ(policy_.reason(), "input refused: out_of_limits");
  EXPECT_EQ(ClearedAt(2.0 + kStep_s), 2.0 + kHold_s);
  // With the Monitor's account of it, the reason names the joint.
  Feed(3.0);
  Cycle(3.0, refused, MergeStatus::kAccepted, "joint 'a1' at 4, outside its limits [-1, 1]");
  EXPECT_EQ(policy_.reason(),
            "input refused: out_of_limits (joint 'a1' at 4, outside its limits [-1, 1])");
}

TEST_F(StopPolicyTest, RefusedMessageReasonSaysWhat) {
  ASSERT_GE(ClearedAt(1.0), 0.0);
  Feed(2.0);
  Cycle(2.0, CleanReport(), MergeStatus::kNonFinite, "joint 'b1' at nan");
  EXPECT_TRUE(policy_.stop());
  EXPECT_EQ(policy_.reason(), "input refused: non_finite (joint 'b1' at nan)");
}

TEST_F(StopPolicyTest, WarningStopsAndClearsAfterTheHold) {
  ASSERT_GE(ClearedAt(1.0), 0.0);
  Feed(2.0);
  Cycle(2.0, WarningReport());
  EXPECT_TRUE(policy_.stop());
  EXPECT_EQ(policy_.status(), SafetyStatus::kOk);
  EXPECT_EQ(policy_.reason(),
            "1 warning(s), the deepest left_link3 - right_link4 at 0.0120 m (threshold 0.0610 m)");
  // A warning seen again renews the hold.
  Feed(2.125);
  Cycle(2.125, WarningReport());
  EXPECT_TRUE(policy_.stop());
  // Gone at the next cycle: the stop is held, and its reason says so, the condition first.
  Feed(2.25);
  Cycle(2.25, CleanReport());
  ASSERT_TRUE(policy_.stop());
  EXPECT_EQ(policy_.reason(),
            "1 warning(s), the deepest left_link3 - right_link4 at 0.0120 m (threshold 0.0610 m) "
            "(no longer seen; the stop is held for stop_hold_s, 0.25 s)");
  EXPECT_EQ(ClearedAt(2.25 + kStep_s), 2.125 + kHold_s);
}

// The reason names the pair deepest in its tolerance zone, not the first in pair order (a pair
// within the swept check's resolution above its threshold, say, before a touching one).
TEST_F(StopPolicyTest, WarningReasonNamesTheDeepestPair) {
  ASSERT_GE(ClearedAt(1.0), 0.0);
  CycleReport report = WarningReport();
  report.warnings.front().distance_m = 0.0614;
  Warning touching = report.warnings.front();
  touching.b = 2;
  touching.distance_m = 0.0;
  touching.threshold_m = 0.05;
  Warning near = touching;
  near.distance_m = 0.049;
  report.warnings.push_back(near);
  report.warnings.push_back(touching);
  Feed(2.0);
  Cycle(2.0, report);
  EXPECT_EQ(policy_.reason(),
            "3 warning(s), the deepest left_link3 - right_link5 at 0.0000 m (threshold 0.0500 m)");
}

// A pair found by the swept check says where along the step; one found only within the swept
// check's resolution above its threshold says it was not certified clear (an iiwa user read
// "at 0.0601 m (threshold 0.0600 m)" as a warning that was not one).
TEST_F(StopPolicyTest, WarningReasonOfAPairBetweenSamplesSaysWhere) {
  ASSERT_GE(ClearedAt(1.0), 0.0);
  CycleReport report = WarningReport();
  report.warnings.front().between_samples = true;
  report.warnings.front().step_fraction = 0.5625;
  Feed(2.0);
  Cycle(2.0, report);
  EXPECT_EQ(policy_.reason(),
            "1 warning(s), the deepest left_link3 - right_link4 at 0.0120 m (threshold 0.0610 m) "
            "between samples, at 0.562 of the step");
  report.warnings.front().distance_m = 0.0614;
  report.warnings.front().step_fraction = 0.5;
  Feed(2.125);
  Cycle(2.125, report);
  EXPECT_EQ(policy_.reason(),
            "1 warning(s), the deepest left_link3 - right_link4 at 0.0614 m (threshold 0.0610 m) "
            "between samples, at 0.500 of the step (above its threshold there: "
            "not certified clear)");
}

// One arm's driver gone silent beside joints held at their defaults and never published (a
// mobile base's wheels, a lift): the reason names the arm's joints alone.
TEST(StopPolicy, StaleReasonLeavesOutDefaultedJointsNeverReceived) {
  const std::vector<std::string> joints = {"lift", "l_joint1", "l_joint2", "r_joint1", "wheel"};
  JointMerger input(joints, kTimeout_s);
  input.SetDefaults({{0, 0.4}, {4, 0.0}});
  const std::vector<std::string> left = {"l_joint1", "l_joint2"};
  const std::vector<std::string> right = {"r_joint1"};
  ASSERT_EQ(input.Merge(NamedPositions{left, {0.1, 0.2}, 1.0}, 1.0), MergeStatus::kAccepted);
  ASSERT_EQ(input.Merge(NamedPositions{right, {0.3}, 1.9}, 1.9), MergeStatus::kAccepted);
  StopPolicy policy(kHold_s);
  ASSERT_TRUE(policy.CheckStaleness(input, 2.0).is_stale);
  EXPECT_EQ(policy.reason(),
            "2 joints not received for over input_timeout_s (0.500 s): 'l_joint1' for 1.000 s, "
            "'l_joint2'");
}

// A driver of many joints gone silent: as many names as the reason holds, the rest counted.
TEST(StopPolicy, StaleReasonCountsTheJointsItCannotName) {
  std::vector<std::string> joints;
  for (int i = 0; i < 20; ++i) joints.push_back("a_rather_long_joint_name_" + std::to_string(i));
  JointMerger input(joints, kTimeout_s);
  const std::vector<double> positions(joints.size(), 0.0);
  ASSERT_EQ(input.Merge(NamedPositions{joints, positions, 1.0}, 1.0), MergeStatus::kAccepted);
  StopPolicy policy(kHold_s);
  ASSERT_TRUE(policy.CheckStaleness(input, 2.0).is_stale);
  EXPECT_EQ(policy.reason(),
            "20 joints not received for over input_timeout_s (0.500 s): "
            "'a_rather_long_joint_name_0' for 1.000 s, 'a_rather_long_joint_name_1', "
            "'a_rather_long_joint_name_2', 'a_rather_long_joint_name_3', "
            "'a_rather_long_joint_name_4' and 15 more");
}

TEST_F(StopPolicyTest, InputJumpStopsUntilANormalStepAndOutranksAWarning) {
  ASSERT_GE(ClearedAt(1.0), 0.0);
  CycleReport jump = WarningReport();
  jump.input_jumped = true;
  jump.step_motion_m = 1.25;
  Feed(2.0);
  Cycle(2.0, jump);
  EXPECT_TRUE(policy_.stop());
  EXPECT_EQ(policy_.reason(), "input jumped: a 1.250 m step in one cycle");
  // The next normal step with a warning: the warning is the reason now.
  Feed(2.125);
  Cycle(2.125, WarningReport());
  EXPECT_EQ(policy_.reason(),
            "1 warning(s), the deepest left_link3 - right_link4 at 0.0120 m (threshold 0.0610 m)");
  EXPECT_EQ(ClearedAt(2.125 + kStep_s), 2.125 + kHold_s);
}

// The swept check off, a step that moves a primitive beyond its tolerance is a jump that says
// so (it read "input jumped: a 0.043 m step", as if the input were broken, for sparse input).
TEST_F(StopPolicyTest, AStepTheSamplesDoNotCoverNamesThePrimitiveAndItsTolerance) {
  ASSERT_GE(ClearedAt(1.0), 0.0);
  CycleReport step = WarningReport();
  step.input_jumped = true;
  step.step_motion_m = 0.0431;
  step.beyond_samples = StepBeyondSamples{true, 2, 0.0431, 0.0305};
  Feed(2.0);
  Cycle(2.0, step);
  EXPECT_TRUE(policy_.stop());
  EXPECT_EQ(policy_.reason(),
            "a step the samples do not cover (swept_check false): 'right_link5' may move "
            "0.0431 m in it, over its tolerance 0.0305 m");
}

TEST_F(StopPolicyTest, ObjectPoseFailureStops) {
  ASSERT_GE(ClearedAt(1.0), 0.0);
  Feed(2.0);
  policy_.ObserveClock(2.0);
  ASSERT_TRUE(policy_.BeginCycle(MergeStatus::kAccepted, "", input_));
  policy_.OnObjectPoseUnavailable("camera", "camera_link", "no transform");
  // Outranks a warning of the same cycle.
  policy_.OnCycleReport(WarningReport(), "", primitives_, input_, 2.0);
  policy_.EndCycle(2.0);
  EXPECT_TRUE(policy_.stop());
  EXPECT_EQ(policy_.reason(),
            "object 'camera': pose from frame 'camera_link' unavailable: no transform");
  EXPECT_EQ(ClearedAt(2.0 + kStep_s), 2.0 + kHold_s);
}

TEST_F(StopPolicyTest, StaleJointStopsInCycleAndOnTheTimer) {
  ASSERT_GE(ClearedAt(1.0), 0.0);  // both joints received at 1.0
  // Only a1 keeps coming: b1 is stale past 1.0 + timeout; a cycle then stops, and the stale
  // condition outranks a warning.
  const std::vector<std::string> names = {"a1"};
  const std::vector<double> positions = {0.0};
  const double t = 1.0 + kTimeout_s + kStep_s;
  ASSERT_EQ(input_.Merge(NamedPositions{names, positions, t}, t), MergeStatus::kAccepted);
  Cycle(t, WarningReport());
  EXPECT_TRUE(policy_.stop());
  EXPECT_EQ(policy_.status(), SafetyStatus::kStale);
  EXPECT_EQ(policy_.reason().rfind("joint 'b1' not received for 0.56", 0), 0u)
      << policy_.reason();
  // The timer: a new episode once, then the same episode.
  const StaleCheck first = policy_.CheckStaleness(input_, t + 2 * kStep_s);
  EXPECT_TRUE(first.is_stale);
  EXPECT_TRUE(first.is_new_episode);
  const StaleCheck second = policy_.CheckStaleness(input_, t + 3 * kStep_s);
  EXPECT_TRUE(second.is_stale);
  EXPECT_FALSE(second.is_new_episode);
  EXPECT_EQ(policy_.hold_until_s(), t + 3 * kStep_s + kHold_s);
  // Fresh again: the timer sees no staleness and ends the episode; clears after the hold.
  Feed(t + 4 * kStep_s);
  EXPECT_FALSE(policy_.CheckStaleness(input_, t + 4 * kStep_s).is_stale);
  EXPECT_EQ(ClearedAt(t + 4 * kStep_s), t + 3 * kStep_s + kHold_s);
  Feed(t + 2.0);
  EXPECT_FALSE(policy_.CheckStaleness(input_, t + 2.0).is_stale);
  // Silence without cycles: only the timer notices, and a new episode starts.
  const StaleCheck again = policy_.CheckStaleness(input_, t + 2.0 + kTimeout_s + kStep_s);
  EXPECT_TRUE(again.is_stale);
  EXPECT_TRUE(again.is_new_episode);
  // Both joints silent: both named, the oldest first with its age.
  EXPECT_EQ(policy_.reason(),
            "2 joints not received for over input_timeout_s (0.500 s): 'a1' for 0.562 s, 'b1'");
  EXPECT_TRUE(policy_.stop());
}

// A stale stop naming many joints keeps the note of its hold once input is back: the names took
// the whole reason and the note was cut off (an iiwa user's 14 joints read as if still stale).
TEST(StopPolicy, HeldStaleReasonOfManyJointsSaysItIsHeld) {
  std::vector<std::string> joints;
  for (const char* arm : {"left", "right"}) {
    for (int i = 1; i <= 7; ++i) {
      joints.push_back(std::string(arm) + "_iiwa_joint_" + std::to_string(i));
    }
  }
  JointMerger input(joints, kTimeout_s);
  StopPolicy policy(kHold_s);
  const std::vector<PrimitiveSpec> primitives = Primitives();
  const std::vector<double> positions(joints.size(), 0.0);
  auto cycle = [&](double now_s) {
    ASSERT_EQ(input.Merge(NamedPositions{joints, positions, now_s}, now_s),
              MergeStatus::kAccepted);
    policy.ObserveClock(now_s);
    if (policy.BeginCycle(MergeStatus::kAccepted, "", input)) {
      policy.OnCycleReport(CleanReport(), "", primitives, input, now_s);
    }
    policy.EndCycle(now_s);
  };
  for (double t = 1.0; t <= 2.0; t += kStep_s) cycle(t);
  ASSERT_FALSE(policy.stop());
  ASSERT_TRUE(policy.CheckStaleness(input, 11.0).is_stale);
  const std::string stale = policy.reason();
  ASSERT_EQ(stale.rfind("14 joints not received for over input_timeout_s", 0), 0u) << stale;
  cycle(11.0 + kStep_s);
  EXPECT_TRUE(policy.stop());
  EXPECT_EQ(policy.reason(), stale + " (no longer seen; the stop is held for stop_hold_s, 0.25 s)");
}

TEST_F(StopPolicyTest, IncompleteModelIsNotStaleOnTheTimer) {
  EXPECT_FALSE(policy_.CheckStaleness(input_, 100.0).is_stale);
  EXPECT_TRUE(policy_.stop());  // still the start-up stop
}

TEST_F(StopPolicyTest, ClockGoingBackStopsUntilEveryJointIsReceivedAgain) {
  ASSERT_GE(ClearedAt(100.0), 0.0);
  EXPECT_EQ(policy_.ObserveClock(100.0 + kStep_s), 0.0);
  // A looping bag: time back to 5 s.
  const double back_s = policy_.ObserveClock(5.0);
  EXPECT_EQ(back_s, 100.0 + kStep_s - 5.0);
  input_.OnTimeWentBackwards(5.0);
  EXPECT_EQ(policy_.hold_until_s(), 5.0);  // no deadline of the old timeline
  // a1 comes back, b1 not yet: stale, naming b1 as silent since the jump.
  const std::vector<std::string> names = {"a1"};
  const std::vector<double> positions = {0.0};
  ASSERT_EQ(input_.Merge(NamedPositions{names, positions, 5.125}, 5.125), MergeStatus::kAccepted);
  Cycle(5.125, CleanReport());
  EXPECT_TRUE(policy_.stop());
  EXPECT_EQ(policy_.status(), SafetyStatus::kStale);
  EXPECT_EQ(policy_.reason(), "joint 'b1' not received since the clock went back 0.125 s ago");
  // Every joint received again: clears after the hold from that last stale cycle.
  EXPECT_EQ(ClearedAt(5.125 + kStep_s), 5.125 + kHold_s);
}

}  // namespace
}  // namespace arm_collision_monitor
