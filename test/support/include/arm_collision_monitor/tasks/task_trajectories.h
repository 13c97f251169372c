// The seed's three test tasks (Shaffer & Herb, TR 90-28, section 5) on the bundled workcell
// (urdf/workcell.urdf + config/scene.yaml), as deterministic joint trajectories: one q per
// 50 ms cycle, generated from frozen joint-space waypoints, so the bags, the rostests, the
// replay tool and the benchmarks all see exactly the same motion without reading a file.
//   task 1 (1000 cycles): the left arm approaches front_box, the right arm positions itself
//          above right_box; close approaches, no warning.
//   task 2 (150 cycles):  as task 1, but the left arm runs into front_table_top.
//   task 3 (2000 cycles): the right arm, with front_box declared its grasp target, misses the
//          box and hits front_table_top, then grasps the box; never a warning against the box.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "arm_collision_monitor/scene/workcell.h"

namespace arm_collision_monitor {

/// A (link, object) pair to declare a grasp target (Monitor::SetGraspTarget) before a task.
struct TaskGraspTarget {
  std::string link;
  std::string object;
};

/// What a task is and what the monitor must report for it (checked by the tests against an
/// independent brute force, and by the rostests against the node).
struct TaskSpec {
  int number = 0;               ///< 1, 2 or 3
  std::string name;             ///< "task1", ...
  int cycle_count = 0;          ///< one q per cycle, cycle_period_s apart
  std::string description;
  std::vector<TaskGraspTarget> grasp_targets;  ///< set before the first cycle
  bool expects_warning = false;
  /// The first warning pairs a link of this arm ("left", "right") with this object.
  std::string first_warning_arm;
  std::string first_warning_object;
  /// True when the first warning must come while the real surfaces are still apart.
  bool first_warning_before_contact = false;
  /// An object no warning may name (the grasped box of task 3); "" for none.
  std::string never_warned_object;
};

/// Task numbers are 1..kTaskCount.
constexpr int kTaskCount = 3;

/// The specification of task `task` (1..3). Throws std::invalid_argument otherwise.
const TaskSpec& GetTaskSpec(int task);

/// Joint positions (rad) and velocities (rad/s) of task `task` at time `t_s` after its start,
/// ordered as workcell.joint_names. Smooth between cycles (minimum-jerk blends), so tests can
/// sample in between. Throws std::invalid_argument for an unknown task or when the workcell's
/// joints are not the bundled two arms' left_joint1..7, right_joint1..7.
void TaskStateAt(int task, const Workcell& workcell, double t_s, Eigen::VectorXd* q,
                 Eigen::VectorXd* qdot);

/// One q per cycle (cycle k at k * kTaskCyclePeriod_s), GetTaskSpec(task).cycle_count of them.
std::vector<Eigen::VectorXd> MakeTaskTrajectory(int task, const Workcell& workcell);

}  // namespace arm_collision_monitor
