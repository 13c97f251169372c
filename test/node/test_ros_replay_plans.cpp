// replay's planned samples (src/nodes/replay/replay_plans.h): what a later plan's cut leaves at
// equal stamps, and how superseded points are counted.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "replay_plans.h"

namespace arm_collision_monitor {
namespace replay {
namespace {

trajectory_msgs::JointTrajectory Trajectory(
    const std::vector<std::string>& names,
    const std::vector<std::pair<double, std::vector<double>>>& points) {
  trajectory_msgs::JointTrajectory trajectory;
  trajectory.joint_names = names;
  for (const auto& [t_s, positions] : points) {
    trajectory_msgs::JointTrajectoryPoint point;
    point.positions = positions;
    point.time_from_start = ros::Duration(t_s);
    trajectory.points.push_back(point);
  }
  return trajectory;
}

/// The position of joint `name` at `stamp` that the last sample of it there in time order gives
/// (what the cycle at `stamp` takes), NaN for none.
double LastAt(const Plans& plans, const ros::Time& stamp, const std::string& name) {
  double position = std::nan("");
  for (const auto& [joints, point] : plans.InTimeOrder()) {
    if (point->stamp != stamp) continue;
    for (std::size_t j = 0; j < joints->names.size(); ++j) {
      if (joints->names[j] == name) position = point->positions[j];
    }
  }
  return position;
}

// Plan A of both arms (points at 100, 110, 120 s); plan Y of the left arm, read next, starting at
// 111 s with a point a second before its start; plan B of the right arm from 110 s, a point of
// A. A's left arm goes on from 110 s in a part of its own, whose point there is A's: at 110 s Y,
// read later than A, gives the left arm, not that copy (a 6 rad jump to Y's next point).
TEST(ReplayPlans, ACutPlansPointAtTheCutIsAsOldAsThePlan) {
  Input counts;
  Plans plans(&counts, {});
  plans.AddTrajectory(Trajectory({"L", "R"}, {{0, {0, 0}}, {10, {1, 1}}, {20, {2, 2}}}),
                      ros::Time(100), "A");
  plans.AddTrajectory(Trajectory({"L"}, {{-1, {7}}, {0, {7.01}}}), ros::Time(111), "Y");
  plans.AddTrajectory(Trajectory({"R"}, {{0, {1}}, {10, {5}}}), ros::Time(110), "B");
  EXPECT_EQ(LastAt(plans, ros::Time(110), "L"), 7.0);
  EXPECT_EQ(LastAt(plans, ros::Time(110), "R"), 1.0);  // B's
  EXPECT_EQ(counts.superseded_points, 1u);             // A's point at 120 s
}

// Each planned point is counted superseded once: A's points at 110 and 120 s lose the right arm
// to B (2), then the part of A's left arm split off them loses it to C (counted already). A
// display's start state cut by a plan starting before it counts too.
TEST(ReplayPlans, APointIsCountedSupersededOnce) {
  Input counts;
  Plans plans(&counts, {});
  plans.AddTrajectory(Trajectory({"L", "R"}, {{0, {0, 0}}, {10, {1, 1}}, {20, {2, 2}}}),
                      ros::Time(100), "A");
  plans.AddTrajectory(Trajectory({"R"}, {{0, {1}}}), ros::Time(105), "B");
  EXPECT_EQ(counts.superseded_points, 2u);
  plans.AddTrajectory(Trajectory({"L"}, {{0, {1}}}), ros::Time(106), "C");
  EXPECT_EQ(counts.superseded_points, 2u);
  sensor_msgs::JointState state;
  state.name = {"W"};
  state.position = {1.0};
  plans.AddState(state, ros::Time(130), "D");
  plans.AddTrajectory(Trajectory({"W"}, {{0, {2}}}), ros::Time(125), "E");
  EXPECT_EQ(counts.superseded_points, 3u);
}

}  // namespace
}  // namespace replay
}  // namespace arm_collision_monitor
