// libFuzzer harness for replay's readers of MoveIt's plan display (ReadDisplayTrajectory) and of
// the action goals that carry a trajectory (ReadGoalTrajectory): a message's definition and
// bytes as a bag could hold them, both mutated, read as each of the three types.
// std::runtime_error is the expected answer to bad input; any other exception (std::bad_alloc
// from a count taken at its word), a crash, undefined behaviour, a read past the bytes, a leak,
// a timeout (a definition whose walk does not end) or a broken invariant of the result is a
// finding.
//
// Input: the definition (libFuzzer's random-length string: a backslash ends it, two stand for
// one), then the message's bytes. Seeds: test/fuzz/corpus/ros_display_trajectory/, written by
// test/ros/replay_trajectory_test.py's helpers (task 2's first samples: a display in both
// layouts, and a control_msgs/FollowJointTrajectoryActionGoal).
#include <cstdint>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

#include <fuzzer/FuzzedDataProvider.h>

#include "arm_collision_monitor/ros/display_trajectory.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace arm_collision_monitor;
  FuzzedDataProvider in(data, size);
  const std::string definition = in.ConsumeRandomLengthString(size);
  const std::vector<std::uint8_t> bytes = in.ConsumeRemainingBytes<std::uint8_t>();
  try {
    const DisplayedPlan plan = ReadDisplayTrajectory(definition, bytes.data(), bytes.size());
    // What was read came from the bytes: each name at least its 4-byte length, each position 8.
    std::size_t least = 0;
    for (const auto& trajectory : plan.trajectories) {
      least += 4 * trajectory.joint_names.size();
      for (const auto& point : trajectory.points) least += 8 * point.positions.size();
    }
    least += 4 * plan.start_state.name.size() + 8 * plan.start_state.position.size();
    if (least > bytes.size()) std::abort();
    // The base's motion over what was read, as replay takes it (any numbers, any counts).
    MultiDofPoses at = StartMultiDofPoses(plan.start_multi_dof);
    for (const auto& multi_dof : plan.multi_dof_trajectories) {
      DescribeMultiDofMotion(multi_dof, &at);
    }
  } catch (const std::runtime_error&) {
  }
  for (const char* type : {kFollowJointTrajectoryGoalType, kExecuteTrajectoryGoalType}) {
    try {
      trajectory_msgs::MultiDOFJointTrajectory multi_dof;
      const trajectory_msgs::JointTrajectory trajectory =
          ReadGoalTrajectory(type, definition, bytes.data(), bytes.size(), &multi_dof);
      std::size_t least = 4 * trajectory.joint_names.size();
      for (const auto& point : trajectory.points) least += 8 * point.positions.size();
      if (least > bytes.size()) std::abort();
      MultiDofPoses at;
      DescribeMultiDofMotion(multi_dof, &at);
    } catch (const std::runtime_error&) {
    }
  }
  return 0;
}
