// ReadDisplayTrajectory: a moveit_msgs/DisplayTrajectory walked by the definition its bag
// carries (and ReadGoalTrajectory: the trajectory of an action goal, the same way, last). What was written is read back, with or without RobotTrajectory's group_name; every
// truncation and every corrupted byte gives a runtime_error naming a field, never a crash or an
// allocation as large as a corrupted count; a definition that fans out over empty types costs
// no more than its bytes; definitions that lack what is read, that differ from this build's,
// whose type contains itself or that nest too deep are refused before any byte is read.
#include <cmath>
#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <ros/message_traits.h>
#include <ros/serialization.h>
#include <sensor_msgs/MultiDOFJointState.h>
#include <std_msgs/Header.h>
#include <trajectory_msgs/MultiDOFJointTrajectory.h>

#include "arm_collision_monitor/ros/display_trajectory.h"

namespace arm_collision_monitor {
namespace {

const std::string kSeparator = std::string(80, '=') + "\n";

// {type: its own fields} of a generated message's full definition.
template <typename Msg>
void AddSections(std::map<std::string, std::string>* sections) {
  const std::string text = ros::message_traits::Definition<Msg>::value();
  std::string type = ros::message_traits::DataType<Msg>::value();
  std::size_t at = 0;
  while (true) {
    const std::size_t next = text.find(kSeparator, at);
    (*sections)[type] = text.substr(at, next == std::string::npos ? std::string::npos : next - at);
    if (next == std::string::npos) return;
    at = next + kSeparator.size();
    const std::size_t line_end = text.find('\n', at);
    type = text.substr(at + 5, line_end - at - 5);  // after "MSG: "
    at = line_end + 1;
  }
}

// The definition of a DisplayTrajectory (moveit_msgs' .msg files; AttachedCollisionObject
// abridged) with `overrides` replacing types' fields.
std::string Definition(bool group_name, const std::map<std::string, std::string>& overrides = {}) {
  std::map<std::string, std::string> sections = {
      {"moveit_msgs/RobotTrajectory",
       "trajectory_msgs/JointTrajectory joint_trajectory\n"
       "trajectory_msgs/MultiDOFJointTrajectory multi_dof_joint_trajectory\n" +
           std::string(group_name ? "string group_name\n" : "")},
      {"moveit_msgs/RobotState",
       "sensor_msgs/JointState joint_state\n"
       "sensor_msgs/MultiDOFJointState multi_dof_joint_state\n"
       "AttachedCollisionObject[] attached_collision_objects\nbool is_diff\n"},
      {"moveit_msgs/AttachedCollisionObject",
       "string link_name\nstring[] touch_links\nfloat64 weight\nbyte ADD=0 # a constant\n"}};
  AddSections<trajectory_msgs::JointTrajectory>(&sections);
  AddSections<trajectory_msgs::MultiDOFJointTrajectory>(&sections);
  AddSections<sensor_msgs::JointState>(&sections);
  AddSections<sensor_msgs::MultiDOFJointState>(&sections);
  for (const auto& [type, fields] : overrides) sections[type] = fields;
  std::string text = overrides.count("moveit_msgs/DisplayTrajectory")
                         ? overrides.at("moveit_msgs/DisplayTrajectory")
                         : "# The model id\nstring model_id\nRobotTrajectory[] trajectory\n"
                           "RobotState trajectory_start\n";
  for (const auto& [type, fields] : sections) {
    if (type == "moveit_msgs/DisplayTrajectory") continue;
    text += kSeparator + "MSG: " + type + "\n" + fields;
  }
  return text;
}

trajectory_msgs::JointTrajectory Trajectory(double offset) {
  trajectory_msgs::JointTrajectory plan;
  plan.header.stamp = ros::Time(offset > 0 ? 7 : 0, 0);
  plan.joint_names = {"a", "b"};
  for (int k = 0; k < 3; ++k) {
    trajectory_msgs::JointTrajectoryPoint point;
    point.positions = {offset + k, offset - k};
    point.velocities = {0.5, 0.25};
    point.time_from_start = ros::Duration(0.1 * k);
    plan.points.push_back(point);
  }
  return plan;
}

// A mobile base's plan: 'virtual_joint' at its first point's pose, then moved by `step_m` along
// y and turned by `turn_rad` about z.
trajectory_msgs::MultiDOFJointTrajectory BasePlan(double step_m, double turn_rad) {
  trajectory_msgs::MultiDOFJointTrajectory plan;
  plan.joint_names = {"virtual_joint"};
  for (int k = 0; k < 2; ++k) {
    trajectory_msgs::MultiDOFJointTrajectoryPoint point;
    geometry_msgs::Transform pose;
    pose.translation.x = 1.0;
    pose.translation.y = k * step_m;
    pose.rotation.z = std::sin(0.5 * k * turn_rad);
    pose.rotation.w = std::cos(0.5 * k * turn_rad);
    point.transforms = {pose};
    point.time_from_start = ros::Duration(0.5 * k);
    plan.points.push_back(point);
  }
  return plan;
}

// The bytes of a DisplayTrajectory laid out as Definition(group_name), the second trajectory's
// multi-DOF part `multi_dof`, the start state's `start_multi_dof`.
std::vector<std::uint8_t> Bytes(bool group_name,
                                const trajectory_msgs::MultiDOFJointTrajectory& multi_dof = {},
                                const sensor_msgs::MultiDOFJointState& start_multi_dof = {}) {
  namespace ser = ros::serialization;
  std::vector<std::uint8_t> bytes(4096);
  ser::OStream out(bytes.data(), static_cast<std::uint32_t>(bytes.size()));
  ser::serialize(out, std::string("robot"));
  ser::serialize(out, std::uint32_t{2});
  for (const double offset : {0.0, 10.0}) {
    ser::serialize(out, Trajectory(offset));
    ser::serialize(out, offset > 0.0 ? multi_dof : trajectory_msgs::MultiDOFJointTrajectory());
    if (group_name) ser::serialize(out, std::string("arms"));
  }
  sensor_msgs::JointState start;
  start.name = {"a", "b", "c"};
  start.position = {1.0, 2.0, 3.0};
  ser::serialize(out, start);
  ser::serialize(out, start_multi_dof);
  ser::serialize(out, std::uint32_t{1});  // one attached object
  ser::serialize(out, std::string("hand"));
  ser::serialize(out, std::vector<std::string>{"finger", "palm"});
  ser::serialize(out, 0.5);
  ser::serialize(out, std::uint8_t{0});  // is_diff
  bytes.resize(static_cast<std::size_t>(out.getData() - bytes.data()));
  return bytes;
}

TEST(DisplayTrajectory, ReadsWhatWasWritten) {
  for (const bool group_name : {false, true}) {
    const std::vector<std::uint8_t> bytes = Bytes(group_name);
    const DisplayedPlan plan = ReadDisplayTrajectory(Definition(group_name), bytes.data(),
                                                     bytes.size());
    ASSERT_EQ(plan.trajectories.size(), 2u);
    EXPECT_EQ(plan.trajectories[0], Trajectory(0.0));
    EXPECT_EQ(plan.trajectories[1], Trajectory(10.0));
    EXPECT_EQ(plan.start_state.name, (std::vector<std::string>{"a", "b", "c"}));
    EXPECT_EQ(plan.start_state.position, (std::vector<double>{1.0, 2.0, 3.0}));
    // The other layout's definition does not fit these bytes.
    EXPECT_THROW(ReadDisplayTrajectory(Definition(!group_name), bytes.data(), bytes.size()),
                 std::runtime_error);
  }
}

// DescribeMultiDofMotion from where the trajectory's first point has its joints.
std::string MotionOf(const trajectory_msgs::MultiDOFJointTrajectory& trajectory) {
  MultiDofPoses at;
  return DescribeMultiDofMotion(trajectory, &at);
}

// Each trajectory's multi-DOF part is read beside it, and the start state's: replay refuses a
// plan that moves a mobile base (the monitor's robot stands on a fixed root); standing still, or
// without a multi-DOF part, it is no motion.
TEST(DisplayTrajectory, ReadsEachMultiDofPartAndTellsItsMotion) {
  const trajectory_msgs::MultiDOFJointTrajectory base = BasePlan(0.4, 0.0);
  sensor_msgs::MultiDOFJointState start;
  start.joint_names = {"virtual_joint"};
  start.transforms = {base.points[1].transforms[0]};
  const std::vector<std::uint8_t> bytes = Bytes(true, base, start);
  const DisplayedPlan plan = ReadDisplayTrajectory(Definition(true), bytes.data(), bytes.size());
  ASSERT_EQ(plan.multi_dof_trajectories.size(), 2u);
  EXPECT_EQ(plan.multi_dof_trajectories[0], trajectory_msgs::MultiDOFJointTrajectory());
  EXPECT_EQ(plan.multi_dof_trajectories[1], base);
  EXPECT_EQ(plan.start_multi_dof, start);
  EXPECT_EQ(plan.trajectories[1], Trajectory(10.0));
  EXPECT_EQ(plan.start_state.name, (std::vector<std::string>{"a", "b", "c"}));
  EXPECT_EQ(MotionOf(plan.multi_dof_trajectories[0]), "");
  EXPECT_EQ(MotionOf(base),
            "its multi_dof_joint_trajectory moves 'virtual_joint' by up to 0.4 m and 0 rad");
  EXPECT_EQ(MotionOf(BasePlan(0.0, 0.0)), "");
  EXPECT_EQ(MotionOf(BasePlan(0.0, 0.3)),
            "its multi_dof_joint_trajectory moves 'virtual_joint' by up to 0 m and 0.3 rad");
  EXPECT_EQ(MotionOf(BasePlan(1e-9, 1e-9)), "");
  EXPECT_NE(MotionOf(BasePlan(2e-9, 0.0)), "");
  EXPECT_NE(MotionOf(BasePlan(0.0, 2e-9)), "");  // atan2's angle: acos would read 0
  const std::string not_finite = "(and to a pose not finite, or a zero quaternion)";
  EXPECT_NE(MotionOf(BasePlan(std::nan(""), 0.0)).find(not_finite), std::string::npos);
  EXPECT_NE(MotionOf(BasePlan(0.0, std::nan(""))).find(not_finite), std::string::npos);
  trajectory_msgs::MultiDOFJointTrajectory zero = BasePlan(0.0, 0.0);
  zero.points[1].transforms[0].rotation.w = 0.0;
  EXPECT_NE(MotionOf(zero).find(not_finite), std::string::npos);
  trajectory_msgs::MultiDOFJointTrajectory uneven = BasePlan(0.0, 0.0);
  uneven.points[1].transforms.push_back(uneven.points[1].transforms[0]);
  EXPECT_EQ(MotionOf(uneven),
            "its multi_dof_joint_trajectory has a point of 2 transforms for 1 joints");
}

// A base standing still in each trajectory is still moved when it stands elsewhere than the
// start state, or than where the trajectory before left it; each trajectory leaves `at` at its
// end.
TEST(DisplayTrajectory, AStillBaseMovesFromTheStartOrTheTrajectoryBefore) {
  const trajectory_msgs::MultiDOFJointTrajectory still = BasePlan(0.0, 0.0);  // x = 1
  sensor_msgs::MultiDOFJointState start;
  start.joint_names = {"virtual_joint"};
  start.transforms = {still.points[0].transforms[0]};
  MultiDofPoses at = StartMultiDofPoses(start);
  EXPECT_EQ(DescribeMultiDofMotion(still, &at), "");
  start.transforms[0].translation.x = 1.25;
  at = StartMultiDofPoses(start);
  EXPECT_EQ(DescribeMultiDofMotion(still, &at),
            "its multi_dof_joint_trajectory moves 'virtual_joint' by up to 0.25 m and 0 rad");
  at.clear();
  const trajectory_msgs::MultiDOFJointTrajectory forward = BasePlan(0.5, 0.0);
  EXPECT_NE(DescribeMultiDofMotion(forward, &at), "");
  EXPECT_EQ(at.at("virtual_joint"), forward.points.back().transforms[0]);
  // A still trajectory at the first's start, after it: the base went back 0.5 m in between.
  EXPECT_EQ(DescribeMultiDofMotion(still, &at),
            "its multi_dof_joint_trajectory moves 'virtual_joint' by up to 0.5 m and 0 rad");
}

TEST(DisplayTrajectory, EveryTruncationIsRefused) {
  const std::vector<std::uint8_t> bytes = Bytes(true);
  const std::string definition = Definition(true);
  for (std::size_t size = 0; size < bytes.size(); ++size) {
    EXPECT_THROW(ReadDisplayTrajectory(definition, bytes.data(), size), std::runtime_error)
        << size << " of " << bytes.size() << " bytes";
  }
}

TEST(DisplayTrajectory, CorruptBytesAreReadOrRefusedNeverCrash) {
  const std::vector<std::uint8_t> good = Bytes(true);
  const std::string definition = Definition(true);
  int refused = 0;
  for (std::size_t at = 0; at < good.size(); ++at) {
    for (const std::uint8_t value : {std::uint8_t{0xff}, std::uint8_t{0x7f}}) {
      std::vector<std::uint8_t> bytes = good;
      bytes[at] = value;
      // Any other exception (std::bad_alloc from a count taken at its word) fails the test.
      try {
        ReadDisplayTrajectory(definition, bytes.data(), bytes.size());
      } catch (const std::runtime_error&) {
        ++refused;
      }
    }
  }
  // Counts and string lengths corrupted: most of the bytes are counts or lengths' bytes.
  EXPECT_GT(refused, static_cast<int>(good.size()) / 2);
}

// Types that fan out (eight fields of the next type, twenty deep) over a type without fields:
// 8^20 values of no size, each taken at once by its size rather than visited.
TEST(DisplayTrajectory, FanningOutDefinitionsCostNoMoreThanTheirBytes) {
  std::map<std::string, std::string> overrides = {
      {"moveit_msgs/AttachedCollisionObject",
       "string link_name\nstring[] touch_links\nfloat64 weight\nFan0 fan\n"},
      {"moveit_msgs/Fan20", ""}};
  for (int level = 0; level < 20; ++level) {
    std::string fields;
    for (int k = 0; k < 8; ++k) {
      fields += "Fan" + std::to_string(level + 1) + " f" + std::to_string(k) + "\n";
    }
    overrides["moveit_msgs/Fan" + std::to_string(level)] = fields;
  }
  const std::vector<std::uint8_t> bytes = Bytes(false);
  const DisplayedPlan plan =
      ReadDisplayTrajectory(Definition(false, overrides), bytes.data(), bytes.size());
  EXPECT_EQ(plan.trajectories.size(), 2u);
}

TEST(DisplayTrajectory, BadDefinitionsAreRefusedNamingWhat) {
  const std::vector<std::uint8_t> bytes = Bytes(false);
  auto message = [&](const std::string& definition) {
    try {
      ReadDisplayTrajectory(definition, bytes.data(), bytes.size());
    } catch (const std::runtime_error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message(Definition(false, {{"moveit_msgs/DisplayTrajectory",
                                        "string model_id\nRobotState trajectory_start\n"}}))
                .find("no field 'moveit_msgs/RobotTrajectory[] trajectory'"),
            std::string::npos);
  EXPECT_NE(message(Definition(false, {{"moveit_msgs/RobotTrajectory",
                                        "trajectory_msgs/MultiDOFJointTrajectory other\n"}}))
                .find("trajectory: moveit_msgs/RobotTrajectory has no field"),
            std::string::npos);
  EXPECT_NE(message(Definition(false, {{"moveit_msgs/RobotState", "RobotState inner\n"}}))
                .find("type moveit_msgs/RobotState contains itself"),
            std::string::npos);
  // Eight fields of itself, in an array the bytes hold one element of.
  EXPECT_NE(message(Definition(false, {{"moveit_msgs/AttachedCollisionObject",
                                        "AttachedCollisionObject a\nAttachedCollisionObject b\n"
                                        "AttachedCollisionObject c\nAttachedCollisionObject d\n"
                                        "AttachedCollisionObject e\nAttachedCollisionObject f\n"
                                        "AttachedCollisionObject g\nAttachedCollisionObject h\n"}}))
                .find("contains itself"),
            std::string::npos);
  std::map<std::string, std::string> deep = {{"moveit_msgs/RobotState", "Deep0 d\n"}};
  for (int level = 0; level < 40; ++level) {
    deep["moveit_msgs/Deep" + std::to_string(level)] =
        "Deep" + std::to_string(level + 1) + " d\n";
  }
  EXPECT_NE(message(Definition(false, deep)).find("types nested too deep"), std::string::npos);
  EXPECT_NE(message(Definition(false, {{"moveit_msgs/AttachedCollisionObject",
                                        "float64[x] weights\n"}}))
                .find("bad array type 'float64[x]'"),
            std::string::npos);
  EXPECT_NE(message("string model_id\n" + kSeparator + "int32 orphan\n")
                .find("a field before its type's 'MSG:' line"),
            std::string::npos);
  EXPECT_NE(message(Definition(false, {{"moveit_msgs/RobotState", "Missing thing\n"}}))
                .find("type moveit_msgs/Missing is not in the definition"),
            std::string::npos);
}

// The definition of an action goal of `type` (control_msgs/FollowJointTrajectoryActionGoal or
// moveit_msgs/ExecuteTrajectoryActionGoal, from their packages' and actionlib_msgs' .msg
// files); `overrides` replace types' fields.
std::string GoalDefinition(const std::string& type,
                           const std::map<std::string, std::string>& overrides = {}) {
  const bool is_follow = type == kFollowJointTrajectoryGoalType;
  const std::string goal = is_follow ? "FollowJointTrajectoryGoal" : "ExecuteTrajectoryGoal";
  std::map<std::string, std::string> sections = {
      {"actionlib_msgs/GoalID", "time stamp\nstring id\n"},
      {"control_msgs/FollowJointTrajectoryGoal",
       "trajectory_msgs/JointTrajectory trajectory\nJointTolerance[] path_tolerance\n"
       "JointTolerance[] goal_tolerance\nduration goal_time_tolerance\n"},
      {"control_msgs/JointTolerance",
       "string name\nfloat64 position\nfloat64 velocity\nfloat64 acceleration\n"},
      {"moveit_msgs/ExecuteTrajectoryGoal", "RobotTrajectory trajectory\n"},
      {"moveit_msgs/RobotTrajectory",
       "trajectory_msgs/JointTrajectory joint_trajectory\n"
       "trajectory_msgs/MultiDOFJointTrajectory multi_dof_joint_trajectory\n"}};
  AddSections<trajectory_msgs::JointTrajectory>(&sections);
  AddSections<trajectory_msgs::MultiDOFJointTrajectory>(&sections);
  for (const auto& [name, fields] : overrides) sections[name] = fields;
  std::string text = overrides.count(type) ? overrides.at(type)
                                           : "Header header\nactionlib_msgs/GoalID goal_id\n" +
                                                 goal + " goal\n";
  for (const auto& [name, fields] : sections) {
    if (name != type) text += kSeparator + "MSG: " + name + "\n" + fields;
  }
  return text;
}

// The bytes of a goal of `type` laid out as GoalDefinition(type), carrying Trajectory(1.0).
std::vector<std::uint8_t> GoalBytes(const std::string& type) {
  namespace ser = ros::serialization;
  std::vector<std::uint8_t> bytes(4096);
  ser::OStream out(bytes.data(), static_cast<std::uint32_t>(bytes.size()));
  std_msgs::Header header;
  header.frame_id = "base";
  ser::serialize(out, header);
  ser::serialize(out, ros::Time(3, 0));
  ser::serialize(out, std::string("goal-1"));
  ser::serialize(out, Trajectory(1.0));
  if (type == kFollowJointTrajectoryGoalType) {
    ser::serialize(out, std::uint32_t{1});  // one path tolerance
    ser::serialize(out, std::string("a"));
    for (const double x : {0.1, 0.2, 0.3}) ser::serialize(out, x);
    ser::serialize(out, std::uint32_t{0});  // no goal tolerance
    ser::serialize(out, ros::Duration(0.5));
  } else {
    ser::serialize(out, BasePlan(0.25, 0.0));
  }
  bytes.resize(static_cast<std::size_t>(out.getData() - bytes.data()));
  return bytes;
}

TEST(GoalTrajectory, ReadsWhatWasWrittenAndRefusesEveryTruncation) {
  for (const std::string type : {kFollowJointTrajectoryGoalType, kExecuteTrajectoryGoalType}) {
    const std::vector<std::uint8_t> bytes = GoalBytes(type);
    const std::string definition = GoalDefinition(type);
    EXPECT_EQ(ReadGoalTrajectory(type, definition, bytes.data(), bytes.size()), Trajectory(1.0))
        << type;
    // An ExecuteTrajectory goal's RobotTrajectory carries a multi-DOF part; a
    // FollowJointTrajectory goal none.
    trajectory_msgs::MultiDOFJointTrajectory multi_dof;
    ReadGoalTrajectory(type, definition, bytes.data(), bytes.size(), &multi_dof);
    EXPECT_EQ(multi_dof, type == kExecuteTrajectoryGoalType
                             ? BasePlan(0.25, 0.0)
                             : trajectory_msgs::MultiDOFJointTrajectory())
        << type;
    for (std::size_t size = 0; size < bytes.size(); ++size) {
      EXPECT_THROW(ReadGoalTrajectory(type, definition, bytes.data(), size), std::runtime_error)
          << type << ": " << size << " of " << bytes.size() << " bytes";
    }
  }
  const std::vector<std::uint8_t> bytes = GoalBytes(kExecuteTrajectoryGoalType);
  EXPECT_THROW(ReadGoalTrajectory("moveit_msgs/MoveGroupActionGoal",
                                  GoalDefinition(kExecuteTrajectoryGoalType), bytes.data(),
                                  bytes.size()),
               std::invalid_argument);
}

TEST(GoalTrajectory, CorruptBytesAreReadOrRefusedNeverCrash) {
  const std::string type = kFollowJointTrajectoryGoalType;
  const std::vector<std::uint8_t> good = GoalBytes(type);
  const std::string definition = GoalDefinition(type);
  int refused = 0;
  for (std::size_t at = 0; at < good.size(); ++at) {
    std::vector<std::uint8_t> bytes = good;
    bytes[at] = 0xff;
    try {
      ReadGoalTrajectory(type, definition, bytes.data(), bytes.size());
    } catch (const std::runtime_error&) {
      ++refused;
    }
  }
  // Each byte of the 22 counts and lengths (3 frame_id and id lengths, 2 names, their count,
  // the points' count, 4 arrays in each of 3 points, the tolerances' 2 counts and name) makes
  // it 255 or more, which the bytes cannot hold; any other byte is a value, read as it is.
  EXPECT_EQ(refused, 4 * 22);
}

TEST(GoalTrajectory, DefinitionsWithoutTheTrajectoryAreRefusedNamingWhere) {
  const std::string type = kExecuteTrajectoryGoalType;
  const std::vector<std::uint8_t> bytes = GoalBytes(type);
  auto message = [&](const std::map<std::string, std::string>& overrides) {
    try {
      ReadGoalTrajectory(type, GoalDefinition(type, overrides), bytes.data(), bytes.size());
    } catch (const std::runtime_error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message({{"moveit_msgs/RobotTrajectory",
                      "trajectory_msgs/MultiDOFJointTrajectory multi_dof_joint_trajectory\n"}}),
            "goal.trajectory: moveit_msgs/RobotTrajectory has no field 'joint_trajectory'");
  EXPECT_EQ(message({{"moveit_msgs/ExecuteTrajectoryGoal", "RobotTrajectory[] trajectory\n"}}),
            "goal: moveit_msgs/ExecuteTrajectoryGoal has no field 'trajectory'");
  EXPECT_EQ(message({{"moveit_msgs/RobotTrajectory",
                      "trajectory_msgs/MultiDOFJointTrajectory joint_trajectory\n"}}),
            "goal.trajectory.joint_trajectory: is trajectory_msgs/MultiDOFJointTrajectory, not "
            "trajectory_msgs/JointTrajectory");
}

}  // namespace
}  // namespace arm_collision_monitor
