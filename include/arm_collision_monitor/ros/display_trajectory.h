// MoveIt's planned path as move_group publishes it for display (moveit_msgs/DisplayTrajectory on
// display_planned_path), read from a bag without moveit_msgs: a bag carries the full definition
// of each message type, and the reader walks the serialized bytes by that definition. It takes
// out each trajectory's joint_trajectory and the start state's joint_state, whose layouts must
// equal this build's trajectory_msgs/JointTrajectory and sensor_msgs/JointState field by field;
// every other field is skipped by its definition, so the versions of moveit_msgs that differ
// elsewhere (RobotTrajectory's group_name, RobotState's attached objects) read alike. The action
// goals that carry one joint trajectory (to a trajectory controller, or to move_group to
// execute) are read the same way.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <geometry_msgs/Transform.h>
#include <sensor_msgs/JointState.h>
#include <sensor_msgs/MultiDOFJointState.h>
#include <trajectory_msgs/JointTrajectory.h>
#include <trajectory_msgs/MultiDOFJointTrajectory.h>

namespace arm_collision_monitor {

inline constexpr char kDisplayTrajectoryType[] = "moveit_msgs/DisplayTrajectory";
/// What MoveIt (or a script) sends a trajectory controller: its goal.trajectory.
inline constexpr char kFollowJointTrajectoryGoalType[] =
    "control_msgs/FollowJointTrajectoryActionGoal";
/// What a MoveIt client sends move_group to execute: its goal.trajectory.joint_trajectory.
inline constexpr char kExecuteTrajectoryGoalType[] = "moveit_msgs/ExecuteTrajectoryActionGoal";

/// What replay takes from a moveit_msgs/DisplayTrajectory.
struct DisplayedPlan {
  /// trajectory_start.joint_state: where the joints are at the start, those the trajectories
  /// leave out included
  sensor_msgs::JointState start_state;
  /// trajectory_start.multi_dof_joint_state: where a mobile base's virtual joint is at the start
  sensor_msgs::MultiDOFJointState start_multi_dof;
  /// trajectory[k].joint_trajectory in order (executed one after the other)
  std::vector<trajectory_msgs::JointTrajectory> trajectories;
  /// trajectory[k].multi_dof_joint_trajectory beside each (empty where the bag's definition of
  /// RobotTrajectory has none): the motion of the SRDF's virtual joint, a mobile base's
  std::vector<trajectory_msgs::MultiDOFJointTrajectory> multi_dof_trajectories;
};

/// Reads the `size` bytes at `data`, a message of type kDisplayTrajectoryType serialized by
/// `definition` (the bag connection's message definition: the type's fields, then each type it
/// uses after a line of '=' and "MSG: <package>/<Type>"). Throws std::runtime_error naming the
/// field (as a path, e.g. "trajectory[1].joint_trajectory") where the definition lacks what
/// is read, differs from this build's, or the bytes end early or leave some over.
DisplayedPlan ReadDisplayTrajectory(const std::string& definition, const std::uint8_t* data,
                                    std::size_t size);

/// Reads the joint trajectory of an action goal of `type` (kFollowJointTrajectoryGoalType or
/// kExecuteTrajectoryGoalType) from its `size` bytes at `data`, serialized by `definition`, as
/// ReadDisplayTrajectory does (the same errors); std::invalid_argument for another type.
/// `multi_dof` (unless null) gets an ExecuteTrajectory goal's multi_dof_joint_trajectory.
trajectory_msgs::JointTrajectory ReadGoalTrajectory(
    const std::string& type, const std::string& definition, const std::uint8_t* data,
    std::size_t size, trajectory_msgs::MultiDOFJointTrajectory* multi_dof = nullptr);

/// Where a plan's multi-DOF joints (a mobile base's virtual joint) are, by name.
using MultiDofPoses = std::map<std::string, geometry_msgs::Transform>;

/// The poses of a plan's start state (a DisplayedPlan's start_multi_dof).
MultiDofPoses StartMultiDofPoses(const sensor_msgs::MultiDOFJointState& state);

/// The poses of a multi-DOF trajectory's first point (none without points).
MultiDofPoses FirstMultiDofPoses(const trajectory_msgs::MultiDOFJointTrajectory& trajectory);

/// Empty when `at` has each joint of `expected` it has where `expected` has it, within
/// kSceneBaseAgreement_m and _rad; else the first that is not, `joint` set to its name, and
/// how far, to be followed by what gives `expected`: "puts 'base' 0.5 m and 0 rad from where"
/// (or "... at a pose not finite, or of a zero quaternion, not where").
std::string DescribeMultiDofAway(const MultiDofPoses& expected, const MultiDofPoses& at,
                                 std::string* joint);

/// Empty when every point of `trajectory` has each of its joints where `at` has it (a joint `at`
/// lacks: where the trajectory's first point has it), within kMultiDofStill_m and
/// kMultiDofStill_rad; else what moves and how far ("its multi_dof_joint_trajectory moves
/// 'virtual_joint' by up to 0.4 m and 0 rad"), a pose not finite or a zero quaternion moving, a
/// point whose transforms do not match the joint names said to. Sets `at` to where the
/// trajectory ends: the next trajectory of a plan starts there.
std::string DescribeMultiDofMotion(const trajectory_msgs::MultiDOFJointTrajectory& trajectory,
                                   MultiDofPoses* at);

}  // namespace arm_collision_monitor
