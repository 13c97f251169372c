// replay's bag input: recorded states (sensor_msgs/JointState) and planned paths
// (trajectory_msgs/JointTrajectory, moveit_msgs/DisplayTrajectory, and the action goals
// control_msgs/FollowJointTrajectoryActionGoal and moveit_msgs/ExecuteTrajectoryActionGoal)
// merged into cycles (src/nodes/replay.cpp runs them).
#pragma once

#include <map>
#include <string>
#include <vector>

#include "arm_collision_monitor/scene/workcell.h"
#include "replay_output.h"

namespace arm_collision_monitor {
namespace replay {

// The cycles of the bag at `path` for `workcell`'s joints. The recorded states (JointState) are
// taken in bag order, stamped as the node takes them (Cycles::Add); the planned points (each
// trajectory point a sample at its start plus time_from_start, a DisplayTrajectory's start
// state one at the bag's time, its continuous joints unwound as MoveIt executes it) in time
// order, merged with the states by stamp. A plan supersedes, for its joints, the points of
// earlier plans after its start, as a trajectory controller replaces a trajectory. Consecutive
// samples with equal stamps form one cycle; at each sample's stamp the other plans under way give
// their joints interpolated between their points. `topics`: the topics read (empty: all); without
// them, recorded states and planned paths of the same joint are an error (a bag recorded with
// `rosbag record -a` holds both: what was planned and what was done). A LoadError names the bag
// (and the message or topic) when it cannot be read, some joint is never given, or a topic given
// holds none of the types read. `joint_prefixes`: per topic, a prefix of its joint names (its
// states' and plans').
Input ReadBag(const std::string& path, const std::vector<std::string>& topics,
              const std::map<std::string, std::string>& joint_prefixes, const Workcell& workcell);

}  // namespace replay
}  // namespace arm_collision_monitor
