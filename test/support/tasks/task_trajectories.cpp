#include "arm_collision_monitor/tasks/task_trajectories.h"

#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

#include "arm_collision_monitor/core/constants.h"

namespace arm_collision_monitor {
namespace {

using ArmQ = std::array<double, 7>;  // joint1..joint7 of one arm, rad

// The frozen waypoints. They were found once with a damped-least-squares IK on the bundled
// workcell's KinematicModel (tool point and tool z axis pointing down as the targets) and
// checked with a brute-force distance over all pairs; the comment gives each pose's tool point
// (world frame, m). Rounded to 1e-4 rad: test_tasks_trajectories re-checks every outcome on
// these exact values, so they need not reproduce the IK.
constexpr ArmQ kReady = {0.0, -0.1047, 0.0, 1.3209, 0.0, 1.9253, 0.0};  // (0.5, +-0.55, 1.5)
// Left arm: 0.2 m above front_box (top at z 0.95), then 45 mm above it: the close approach
// (the threshold is 30.5 mm, twice it 61 mm).
constexpr ArmQ kLeftAboveBox = {-0.5018, 1.0395, -0.1533, 0.2797, 0.1365, 1.8253, 0.0};
constexpr ArmQ kLeftNearBox = {-0.4725, 0.9846, -0.1597, 0.6458, 0.1330, 1.5176, 0.0};
// Left arm: tool 50 mm into front_table_top (top at z 0.75) at (0.75, 0.35), clear of the box.
constexpr ArmQ kLeftIntoTable = {-0.2892, 0.6974, 0.0375, 1.7347, -0.0369, 0.7102, 0.0};
// Right arm over the right table: (0.1, -1.45, 1.35), then 0.15 m above right_box's top.
constexpr ArmQ kRightApproachRightBox = {-1.4616, 0.5718, 0.0033, 0.7455, -0.0018, 1.8243, 0.0};
constexpr ArmQ kRightAboveRightBox = {-1.4709, 0.7435, -0.0004, 0.8885, 0.0003, 1.5096, 0.0};
// Right arm grasping front_box with a 0.27 m positioning error in y: above the wrong spot
// (0.95, -0.27, 1.15), down into the table beside the box (tool 30 mm into the top), then
// corrected: above the box (0.95, 0, 1.15) and down around it (tool at z 0.90, inside the box:
// excused while front_box is right_link7's grasp target).
constexpr ArmQ kRightAboveMiss = {0.2167, 0.7120, 0.1523, 0.8633, -0.0993, 1.5720, 0.0};
constexpr ArmQ kRightIntoTable = {0.2033, 0.9511, 0.1481, 1.1991, -0.1431, 1.0014, 0.0};
constexpr ArmQ kRightAboveBox = {0.5016, 1.0396, 0.1543, 0.2797, -0.1374, 1.8253, 0.0};
constexpr ArmQ kRightGraspBox = {0.4676, 1.0151, 0.1542, 0.7496, -0.1332, 1.3839, 0.0};

// Both arms at time_s; consecutive waypoints are joined by rest-to-rest minimum-jerk blends.
struct Waypoint {
  double time_s;
  ArmQ left;
  ArmQ right;
};

const std::vector<Waypoint>& Waypoints(int task) {
  static const std::vector<Waypoint> task1 = {
      {0.0, kReady, kReady},
      {1.0, kReady, kReady},
      {9.0, kLeftAboveBox, kRightApproachRightBox},
      {17.0, kLeftNearBox, kRightAboveRightBox},
      {22.0, kLeftNearBox, kRightAboveRightBox},
      {30.0, kLeftAboveBox, kRightApproachRightBox},
      {42.0, kReady, kReady},
  };
  static const std::vector<Waypoint> task2 = {
      {0.0, kReady, kReady},
      {0.5, kReady, kReady},
      {7.0, kLeftIntoTable, kRightApproachRightBox},
  };
  static const std::vector<Waypoint> task3 = {
      {0.0, kReady, kReady},
      {2.0, kReady, kReady},
      {12.0, kReady, kRightAboveMiss},
      {14.0, kReady, kRightAboveMiss},
      {24.0, kReady, kRightIntoTable},
      {28.0, kReady, kRightIntoTable},
      {36.0, kReady, kRightAboveMiss},
      {42.0, kReady, kRightAboveBox},
      {52.0, kReady, kRightGraspBox},
      {60.0, kReady, kRightGraspBox},
      {70.0, kReady, kRightAboveBox},
      {85.0, kReady, kReady},
  };
  switch (task) {
    case 1: return task1;
    case 2: return task2;
    case 3: return task3;
    default: break;
  }
  throw std::invalid_argument("no task " + std::to_string(task) + " (tasks are 1.." +
                              std::to_string(kTaskCount) + ")");
}

const std::vector<TaskSpec>& Specs() {
  static const std::vector<TaskSpec> specs = [] {
    std::vector<TaskSpec> s(kTaskCount);
    s[0].number = 1;
    s[0].name = "task1";
    s[0].cycle_count = 1000;
    s[0].description =
        "left arm approaches front_box, right arm positions itself above right_box; close "
        "approaches, no warning";
    s[1].number = 2;
    s[1].name = "task2";
    s[1].cycle_count = 150;
    s[1].description = "as task 1, but the left arm runs into front_table_top";
    s[1].expects_warning = true;
    s[1].first_warning_arm = "left";
    s[1].first_warning_object = "front_table_top";
    s[1].first_warning_before_contact = true;
    s[2].number = 3;
    s[2].name = "task3";
    s[2].cycle_count = 2000;
    s[2].description =
        "right arm tries to grasp front_box (its grasp target), hits front_table_top beside "
        "it, then grasps it";
    s[2].grasp_targets = {{"right_link7", "front_box"}};
    s[2].expects_warning = true;
    s[2].first_warning_arm = "right";
    s[2].first_warning_object = "front_table_top";
    s[2].never_warned_object = "front_box";
    return s;
  }();
  return specs;
}

// Where each workcell joint takes its value: arm (0 left, 1 right) and joint (0..6).
struct JointSource {
  int arm;
  int joint;
};

JointSource SourceOf(const std::string& joint_name) {
  for (int arm = 0; arm < 2; ++arm) {
    const std::string prefix = arm == 0 ? "left_joint" : "right_joint";
    if (joint_name.size() == prefix.size() + 1 &&
        joint_name.compare(0, prefix.size(), prefix) == 0) {
      const int joint = joint_name.back() - '1';
      if (joint >= 0 && joint < 7) return {arm, joint};
    }
  }
  throw std::invalid_argument("task trajectories need the bundled workcell's joints "
                              "left_joint1..7 and right_joint1..7, not '" + joint_name + "'");
}

}  // namespace

const TaskSpec& GetTaskSpec(int task) {
  Waypoints(task);  // validates the number
  return Specs()[task - 1];
}

void TaskStateAt(int task, const Workcell& workcell, double t_s, Eigen::VectorXd* q,
                 Eigen::VectorXd* qdot) {
  const std::vector<Waypoint>& waypoints = Waypoints(task);
  // The blend that contains t_s: [from.time_s, to.time_s]; before the first waypoint or after
  // the last one the arms rest there.
  std::size_t i = 0;
  while (i + 1 < waypoints.size() && waypoints[i + 1].time_s <= t_s) ++i;
  const Waypoint& from = waypoints[i];
  const Waypoint& to = waypoints[i + 1 < waypoints.size() ? i + 1 : i];
  double s = 0.0, ds_dt = 0.0;
  if (&to != &from && t_s > from.time_s) {
    // Minimum-jerk position profile (Flash & Hogan 1985): s = 10 u^3 - 15 u^4 + 6 u^5, zero
    // velocity and acceleration at both ends, so the blends join with continuous acceleration.
    const double duration_s = to.time_s - from.time_s;
    const double u = (t_s - from.time_s) / duration_s;
    s = u * u * u * (10.0 + u * (-15.0 + 6.0 * u));
    ds_dt = 30.0 * u * u * (1.0 - u) * (1.0 - u) / duration_s;
  }
  const int n = static_cast<int>(workcell.joint_names.size());
  q->resize(n);
  qdot->resize(n);
  for (int k = 0; k < n; ++k) {
    const JointSource src = SourceOf(workcell.joint_names[k]);
    const double a = (src.arm == 0 ? from.left : from.right)[src.joint];
    const double b = (src.arm == 0 ? to.left : to.right)[src.joint];
    (*q)[k] = a + (b - a) * s;
    (*qdot)[k] = (b - a) * ds_dt;
  }
}

std::vector<Eigen::VectorXd> MakeTaskTrajectory(int task, const Workcell& workcell) {
  const TaskSpec& spec = GetTaskSpec(task);
  std::vector<Eigen::VectorXd> trajectory(spec.cycle_count);
  Eigen::VectorXd qdot;
  for (int k = 0; k < spec.cycle_count; ++k) {
    TaskStateAt(task, workcell, k * kTaskCyclePeriod_s, &trajectory[k], &qdot);
  }
  return trajectory;
}

}  // namespace arm_collision_monitor
