// The seed's three task trajectories: speed, joint limits and smoothness, determinism, each
// task's outcome against the independent brute force of test_monitor_util.h, and the Monitor's
// per-cycle agreement with it for every broad phase.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "arm_collision_monitor/core/constants.h"
#include "arm_collision_monitor/tasks/task_trajectories.h"
#include "../core/test_monitor_util.h"

namespace arm_collision_monitor {
namespace {

using test::ExpectSameWarnings;
using test::LoadBundledWorkcell;
using test::ReferenceScene;
using test::ReferenceWarning;
using test::ReferenceWarnings;

// Sub-steps per cycle at which the continuous trajectory is sampled "in between" cycles.
constexpr int kSubSteps = 10;
// Bound on joint accelerations (rad/s^2) the blends must keep: smooth motion for a real arm.
// The steepest blend (task 2's 6.5 s into the table) peaks near 5.77 * 1.2 / 6.5^2 = 0.17.
constexpr double kMaxJointAcceleration_radps2 = 0.5;

ReferenceScene SceneOf(const Workcell& workcell, const TaskSpec& spec) {
  ReferenceScene scene;
  for (const TaskGraspTarget& target : spec.grasp_targets) {
    scene.grasp.insert({workcell.kinematics.FindLink(target.link),
                        workcell.FindObject(target.object)});
  }
  return scene;
}

// The arm group of a link primitive, or the object name of an environment primitive.
const std::string& ArmOf(const Workcell& wc, PrimitiveId id) { return wc.primitives[id].group; }
const std::string& OwnerOf(const Workcell& wc, PrimitiveId id) { return wc.primitives[id].owner; }

TEST(TaskTrajectories, SizesAndDeterminism) {
  const auto workcell = LoadBundledWorkcell();
  for (int task = 1; task <= kTaskCount; ++task) {
    const TaskSpec& spec = GetTaskSpec(task);
    EXPECT_EQ(spec.number, task);
    const std::vector<Eigen::VectorXd> a = MakeTaskTrajectory(task, *workcell);
    const std::vector<Eigen::VectorXd> b = MakeTaskTrajectory(task, *workcell);
    ASSERT_EQ(static_cast<int>(a.size()), spec.cycle_count);
    Eigen::VectorXd q, qdot;
    for (std::size_t k = 0; k < a.size(); ++k) {
      ASSERT_EQ(a[k].size(), static_cast<Eigen::Index>(workcell->joint_names.size()));
      EXPECT_TRUE((a[k].array() == b[k].array()).all()) << spec.name << " cycle " << k;
      TaskStateAt(task, *workcell, static_cast<double>(k) * kTaskCyclePeriod_s, &q, &qdot);
      EXPECT_TRUE((a[k].array() == q.array()).all()) << spec.name << " cycle " << k;
    }
  }
  // The seed's cycle counts.
  EXPECT_EQ(GetTaskSpec(1).cycle_count, 1000);
  EXPECT_EQ(GetTaskSpec(2).cycle_count, 150);
  EXPECT_EQ(GetTaskSpec(3).cycle_count, 2000);
  EXPECT_THROW(GetTaskSpec(0), std::invalid_argument);
  EXPECT_THROW(GetTaskSpec(4), std::invalid_argument);
}

TEST(TaskTrajectories, RejectsAForeignWorkcell) {
  Workcell workcell = *LoadBundledWorkcell();
  workcell.joint_names[3] = "elbow";
  Eigen::VectorXd q, qdot;
  EXPECT_THROW(TaskStateAt(1, workcell, 0.0, &q, &qdot), std::invalid_argument);
}

// Every link frame (tool points included) moves at most kTaskMaxPointSpeed_mps, sampled at
// every cycle and kSubSteps times in between; joints stay within position and velocity limits;
// the analytic velocity is the derivative of the position; accelerations stay bounded.
TEST(TaskTrajectories, SpeedsLimitsAndSmoothness) {
  const auto workcell = LoadBundledWorkcell();
  const KinematicModel& model = workcell->kinematics;
  const test::JointLimits limits = test::LimitsOf(*workcell);
  const double h_s = kTaskCyclePeriod_s / kSubSteps;
  for (int task = 1; task <= kTaskCount; ++task) {
    const TaskSpec& spec = GetTaskSpec(task);
    std::vector<Eigen::Isometry3d> X_WL(model.link_count()), X_WL_previous(model.link_count());
    Eigen::VectorXd q, qdot, qdot_previous, q_minus, q_plus, unused;
    double max_speed_mps = 0.0, max_acceleration = 0.0, max_derivative_error = 0.0;
    const int samples = spec.cycle_count * kSubSteps;
    for (int i = 0; i <= samples; ++i) {
      const double t_s = i * h_s;
      TaskStateAt(task, *workcell, t_s, &q, &qdot);
      model.ComputeLinkPoses(q, &X_WL);
      for (int j = 0; j < q.size(); ++j) {
        ASSERT_GE(q[j], limits.lower[j]) << spec.name << " t " << t_s << " joint " << j;
        ASSERT_LE(q[j], limits.upper[j]) << spec.name << " t " << t_s << " joint " << j;
        ASSERT_LE(std::abs(qdot[j]), limits.max_velocity[j]) << spec.name << " t " << t_s;
      }
      // Central difference over +-1 ms against the analytic velocity (O(h^2) truncation).
      TaskStateAt(task, *workcell, t_s - 1e-3, &q_minus, &unused);
      TaskStateAt(task, *workcell, t_s + 1e-3, &q_plus, &unused);
      max_derivative_error =
          std::max(max_derivative_error, ((q_plus - q_minus) / 2e-3 - qdot).cwiseAbs().maxCoeff());
      if (i > 0) {
        for (int link = 0; link < model.link_count(); ++link) {
          const double speed_mps =
              (X_WL[link].translation() - X_WL_previous[link].translation()).norm() / h_s;
          max_speed_mps = std::max(max_speed_mps, speed_mps);
        }
        max_acceleration =
            std::max(max_acceleration, (qdot - qdot_previous).cwiseAbs().maxCoeff() / h_s);
      }
      X_WL_previous = X_WL;
      qdot_previous = qdot;
    }
    std::printf("%s: max point speed %.3f m/s, max joint acceleration %.3f rad/s^2, "
                "derivative error %.2e rad/s\n",
                spec.name.c_str(), max_speed_mps, max_acceleration, max_derivative_error);
    EXPECT_LE(max_speed_mps, kTaskMaxPointSpeed_mps) << spec.name;
    EXPECT_LE(max_acceleration, kMaxJointAcceleration_radps2) << spec.name;
    EXPECT_LT(max_derivative_error, 1e-4) << spec.name;
  }
}

// The states the node sees when the two arms arrive on separate topics, one message per
// cycle each: after the leading arm's message of cycle k the other arm is still at cycle
// k - 1. Which arm leads depends on the player (a bag orders equal stamps as it likes).
std::vector<Eigen::VectorXd> NodeStates(const Workcell& wc,
                                        const std::vector<Eigen::VectorXd>& trajectory,
                                        const std::string& leading_prefix) {
  std::vector<Eigen::VectorXd> states;
  for (std::size_t k = 0; k < trajectory.size(); ++k) {
    if (k > 0) {
      Eigen::VectorXd mixed = trajectory[k - 1];
      for (std::size_t j = 0; j < wc.joint_names.size(); ++j) {
        if (wc.joint_names[j].rfind(leading_prefix, 0) == 0) mixed[j] = trajectory[k][j];
      }
      states.push_back(mixed);
    }
    states.push_back(trajectory[k]);
  }
  return states;
}

struct Outcome {
  int first_warning_state = -1;
  std::vector<ReferenceWarning> first_warnings;
  int warning_states = 0;
  bool has_contact = false;
  std::vector<std::string> never_object_hits;
};

Outcome OutcomeOf(const Workcell& wc, const TaskSpec& spec,
                  const std::vector<Eigen::VectorXd>& states) {
  const ReferenceScene scene = SceneOf(wc, spec);
  Outcome outcome;
  for (std::size_t k = 0; k < states.size(); ++k) {
    const std::vector<ReferenceWarning> warnings = ReferenceWarnings(wc, states[k], scene);
    if (warnings.empty()) continue;
    ++outcome.warning_states;
    if (outcome.first_warning_state < 0) {
      outcome.first_warning_state = static_cast<int>(k);
      outcome.first_warnings = warnings;
    }
    for (const ReferenceWarning& w : warnings) {
      outcome.has_contact |= w.distance_m == 0.0;
      if (OwnerOf(wc, w.a) == spec.never_warned_object ||
          OwnerOf(wc, w.b) == spec.never_warned_object) {
        outcome.never_object_hits.push_back(test::Describe(wc, w.a, w.b));
      }
    }
  }
  return outcome;
}

void ExpectOutcome(const Workcell& wc, const TaskSpec& spec,
                   const std::vector<Eigen::VectorXd>& states, const std::string& what) {
  const Outcome outcome = OutcomeOf(wc, spec, states);
  if (!spec.expects_warning) {
    EXPECT_EQ(outcome.warning_states, 0) << spec.name << " " << what;
    return;
  }
  ASSERT_GE(outcome.first_warning_state, 0) << spec.name << " " << what;
  for (const ReferenceWarning& w : outcome.first_warnings) {
    // One side is a link of the expected arm, the other the expected object.
    const bool a_is_arm = ArmOf(wc, w.a) == spec.first_warning_arm;
    const PrimitiveId arm = a_is_arm ? w.a : w.b;
    const PrimitiveId object = a_is_arm ? w.b : w.a;
    EXPECT_EQ(ArmOf(wc, arm), spec.first_warning_arm) << test::Describe(wc, w.a, w.b);
    EXPECT_EQ(OwnerOf(wc, object), spec.first_warning_object) << test::Describe(wc, w.a, w.b);
    if (spec.first_warning_before_contact) {
      EXPECT_GT(w.distance_m, 0.0) << what;
    }
    std::printf("%s %s: first warning at state %d: %s at %.4f m (threshold %.4f m)\n",
                spec.name.c_str(), what.c_str(), outcome.first_warning_state,
                test::Describe(wc, w.a, w.b).c_str(), w.distance_m, w.threshold_m);
  }
  EXPECT_TRUE(outcome.has_contact) << spec.name << " " << what << ": never runs into it";
  EXPECT_TRUE(outcome.never_object_hits.empty())
      << spec.name << " " << what << ": warned against " << spec.never_warned_object << ": "
      << outcome.never_object_hits.front();
}

TEST(TaskTrajectories, OutcomesPerCycle) {
  const auto workcell = LoadBundledWorkcell();
  for (int task = 1; task <= kTaskCount; ++task) {
    const TaskSpec& spec = GetTaskSpec(task);
    ExpectOutcome(*workcell, spec, MakeTaskTrajectory(task, *workcell), "per cycle");
  }
}

TEST(TaskTrajectories, OutcomesPerArmMessage) {
  const auto workcell = LoadBundledWorkcell();
  for (int task = 1; task <= kTaskCount; ++task) {
    const TaskSpec& spec = GetTaskSpec(task);
    for (const std::string leading : {"left_", "right_"}) {
      ExpectOutcome(*workcell, spec,
                    NodeStates(*workcell, MakeTaskTrajectory(task, *workcell), leading),
                    "per arm message, " + leading + "arm first");
    }
  }
}

// Task 1 comes close: some pair within twice its threshold (a workcell with every tolerance
// doubled warns), though never within it.
TEST(TaskTrajectories, Task1ComesClose) {
  const auto workcell = LoadBundledWorkcell();
  Workcell doubled = *workcell;
  for (PrimitiveSpec& p : doubled.primitives) p.tolerance_m *= 2.0;
  const std::vector<Eigen::VectorXd> trajectory = MakeTaskTrajectory(1, *workcell);
  double closest_m = 1e9, closest_threshold_m = 0.0;  // threshold with the real tolerances
  std::string closest_pair;
  for (const Eigen::VectorXd& q : trajectory) {
    for (const ReferenceWarning& w : ReferenceWarnings(doubled, q)) {
      if (w.distance_m < closest_m) {
        closest_m = w.distance_m;
        closest_threshold_m = w.threshold_m / 2.0;
        closest_pair = test::Describe(*workcell, w.a, w.b);
      }
    }
  }
  std::printf("task1: closest approach %s at %.4f m (threshold %.4f m)\n",
              closest_pair.c_str(), closest_m, closest_threshold_m);
  ASSERT_LT(closest_m, 1e9) << "task 1 never comes within twice the tolerances";
  EXPECT_GE(closest_m, closest_threshold_m);
}

// Without the grasp target, task 3's grasp warns against the box: the target is what excuses it.
TEST(TaskTrajectories, Task3GraspTargetMatters) {
  const auto workcell = LoadBundledWorkcell();
  const std::vector<Eigen::VectorXd> trajectory = MakeTaskTrajectory(3, *workcell);
  const PrimitiveId box = test::Prim(*workcell, "front_box");
  const PrimitiveId gripper = test::Prim(*workcell, "right_link7");
  int box_warnings = 0;
  for (const Eigen::VectorXd& q : trajectory) {
    for (const ReferenceWarning& w : ReferenceWarnings(*workcell, q)) {
      box_warnings += (w.a == std::min(box, gripper) && w.b == std::max(box, gripper));
    }
  }
  EXPECT_GT(box_warnings, 0);
}

// The Monitor reports, cycle by cycle, exactly the brute force, with every broad phase.
TEST(TaskTrajectories, MonitorAgreesWithBruteForceForEveryMethod) {
  const auto workcell = LoadBundledWorkcell();
  for (int task = 1; task <= kTaskCount; ++task) {
    const TaskSpec& spec = GetTaskSpec(task);
    const std::vector<Eigen::VectorXd> trajectory = MakeTaskTrajectory(task, *workcell);
    const ReferenceScene scene = SceneOf(*workcell, spec);
    std::vector<std::vector<ReferenceWarning>> expected;
    for (const Eigen::VectorXd& q : trajectory)
      expected.push_back(ReferenceWarnings(*workcell, q, scene));
    for (const BroadPhaseMethod method : test::AllMethods()) {
      Monitor monitor(workcell, test::OptionsFor(method));
      for (const TaskGraspTarget& target : spec.grasp_targets) {
        std::string error;
        ASSERT_TRUE(monitor.SetGraspTarget(target.link, target.object, true, &error)) << error;
      }
      for (std::size_t k = 0; k < trajectory.size(); ++k) {
        const CycleReport& report = monitor.Update(trajectory[k]);
        ASSERT_EQ(report.input, InputStatus::kOk);
        EXPECT_EQ(report.stop, !report.warnings.empty());
        ExpectSameWarnings(*workcell, expected[k], report.warnings,
                           spec.name + " " + BroadPhaseMethodName(method) + " cycle " +
                               std::to_string(k));
        if (::testing::Test::HasFailure()) return;
      }
    }
  }
}

}  // namespace
}  // namespace arm_collision_monitor
