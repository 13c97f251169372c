// replay's bag input (replay_bag.h): a first pass gathers the planned points, a second the usual
// offsets of the recorded states' stamps, a third takes the recorded states in bag order with
// the planned points merged in by stamp.
#include "replay_bag.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <set>
#include <string>
#include <unordered_set>
#include <utility>
#include <vector>

#include <ros/serialization.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <sensor_msgs/JointState.h>
#include <trajectory_msgs/JointTrajectory.h>

#include "arm_collision_monitor/core/constants.h"
#include "arm_collision_monitor/core/load_error.h"
#include "arm_collision_monitor/ros/conversions.h"
#include "arm_collision_monitor/ros/display_trajectory.h"
#include "arm_collision_monitor/safety/joint_merger.h"
#include "replay_plans.h"

namespace arm_collision_monitor {
namespace replay {
namespace {

const char kJointStateType[] = "sensor_msgs/JointState";
const char kJointTrajectoryType[] = "trajectory_msgs/JointTrajectory";
// The types of planned paths read (display_trajectory.h reads the last three).
const std::vector<std::string> kPlanTypes = {kJointTrajectoryType, kDisplayTrajectoryType,
                                             kFollowJointTrajectoryGoalType,
                                             kExecuteTrajectoryGoalType};

// "sensor_msgs/JointState, ... or moveit_msgs/ExecuteTrajectoryActionGoal": what is read.
std::string ReadTypesText() {
  std::string text = kJointStateType;
  for (std::size_t k = 0; k < kPlanTypes.size(); ++k) {
    text += (k + 1 < kPlanTypes.size() ? ", " : " or ") + kPlanTypes[k];
  }
  return text;
}

// "<bag>: <type> on <topic> at bag time <t>": the message `m` of the bag at `path`, for errors.
std::string MessageWhere(const std::string& path, const rosbag::MessageInstance& m) {
  return path + ": " + m.getDataType() + " on " + m.getTopic() + " at bag time " +
         std::to_string(m.getTime().toSec());
}

// Samples merged into cycles: consecutive samples with the same stamp form one cycle, if the
// merger accepts one of them (a refused message makes no cycle, as a refused planned point: the
// node asks a stop instead of checking). Offline, time is the bag's: a sample is its own "now"
// (never stale), but for a recorded message whose stamp leaps ahead of the recording (Add).
class Cycles {
 public:
  /// `path`: the bag's, which names a refused message.
  Cycles(const std::string& path, const Workcell& workcell, Input* result)
      : input_(workcell.joint_names, 1.0),
        path_(path),
        joint_names_(workcell.joint_names),
        result_(result) {
    input_.SetDefaults(workcell.joint_defaults);
    input_.SetMimicJoints(workcell.kinematics.MimicJointNames());
  }

  /// `sample`, of the bag's `message` (null: a plan's, `plan`, at its `point`, null between
  /// two points: refused uncounted, as no message or point read), at `stamp`
  /// (an unstamped message's, its sample's stamp_s 0: the time the bag recorded it, unordered
  /// as the node takes it). A recorded message stamped further ahead of the time the bag
  /// recorded it than `offset_s` (the usual offset of its joints' stamps, UsualOffset) by
  /// more than the input timeout is refused as the node refuses a stamp ahead of its clock
  /// (future_stamp): accepted, it would freeze its joints, each later sample of them going
  /// backwards. Stamps a constant time off the recorder's (a robot's own clock) are read as
  /// they are.
  void Add(const NamedPositions& sample, const ros::Time& stamp,
           const rosbag::MessageInstance* message, double offset_s,
           const Plans::Joints* plan = nullptr, const Plans::Point* point = nullptr) {
    double now_s = stamp.toSec();
    if (message != nullptr && sample.stamp_s != 0.0) {
      now_s -= std::max(stamp.toSec() - message->getTime().toSec() - offset_s, 0.0);
    }
    arrival_s_ = std::max(arrival_s_, now_s);
    if (JointMerger::GivesNoPositions(sample)) {  // nothing to merge, and no cycle of its own
      ++result_->position_less;
      return;
    }
    if (!has_group_ || stamp != group_stamp_) {
      Flush();
      group_stamp_ = stamp;
      has_group_ = true;
      is_group_accepted_ = false;
    }
    const MergeStatus status = input_.Merge(sample, now_s);
    if (input_.last_unknown_joints() + input_.last_mimic_joints() > 0) {
      NoteUnknownNames(sample.names);
    }
    if (status == MergeStatus::kAccepted) {
      is_group_accepted_ = true;
      return;
    }
    // A sample no message or point gave (a plan between its points) is refused with the points
    // it lies between: no refused message of its own.
    if (plan != nullptr && (point == nullptr || point->index == Plans::kBetween)) return;
    ++result_->refused[MergeStatusName(status)];
    NoteRefusal(
        arrival_s_, message == nullptr, stamp.toSec(),
        [&] {
          const std::string why = input_.DescribeRefusal(sample, status, now_s);
          const std::string source = message != nullptr ? MessageWhere(path_, *message)
                                     : plan != nullptr  ? Plans::Describe(*plan, *point)
                                                        : std::string();
          return (source.empty() ? source : source + ": ") + MergeStatusName(status) +
                 (why.empty() ? "" : " (" + why + ")");
        },
        result_);
  }

  /// Ends the last cycle; a LoadError naming the bag at `path`, every joint never given, the
  /// refusals (which may be why), and `hint` (what the plans held that may explain it; "" for
  /// nothing).
  void Finish(const std::string& path, const std::string& hint) {
    Flush();
    if (!input_.is_complete()) {
      const std::vector<std::string> missing = input_.MissingJoints();
      std::string refused;
      std::uint64_t refused_count = 0;
      for (const auto& [status, count] : result_->refused) {
        refused += (refused.empty() ? "" : ", ") + std::to_string(count) + " " + status;
        refused_count += count;
      }
      if (refused_count > 0) {
        refused = "; " + std::to_string(refused_count) + " messages or planned points were "
                  "refused (" + refused + "), the first " + result_->first_refused_message;
      }
      std::string unknown;
      const std::vector<std::string>& ignored = result_->ignored_names;
      if (!ignored.empty()) {
        // Drivers of two alike arms publish the same names (an ALOHA's, 'waist' on each arm's
        // topic): the model's, told apart, have prefixes.
        // Such names with a prefix in the model: --joint-prefix puts it on them, topic by topic.
        const std::string prefixed = PrefixedNamesHint(joint_names_, ignored, "the model");
        unknown = "; the input gives " + std::string(result_->more_ignored_names
                                                          ? "these names, and more, "
                                                          : "these names ") +
                  "that are no joints of the model: " + QuotedNames(ignored) + prefixed +
                  (prefixed.empty() ? " (publish the model's joint names)"
                                    : " (publish the model's joint names, or give each topic's "
                                      "prefix: --joint-prefix TOPIC=PREFIX)");
      }
      throw LoadError(path + ": no accepted sensor_msgs/JointState message or trajectory point " +
                      "gives " + ModelJointsText(missing) + " (" +
                      JointDefaultsHint(missing.size()) + ")" + refused + unknown + hint);
    }
  }

 private:
  // Notes up to kNotedNames names of the input that are no model joints, and as many of mimic
  // joints, apart, and whether there were more.
  void NoteUnknownNames(const std::vector<std::string>& names) {
    for (const std::string& name : names) {
      if (input_.IsModelJoint(name)) continue;
      const bool is_mimic = input_.IsMimicJoint(name);
      std::vector<std::string>& noted = is_mimic ? result_->mimic_names : result_->ignored_names;
      if (std::find(noted.begin(), noted.end(), name) != noted.end()) continue;
      if (noted.size() < kNotedNames) {
        noted.push_back(name);
      } else {
        (is_mimic ? result_->more_mimic_names : result_->more_ignored_names) = true;
      }
    }
  }

  // Ends the cycle of the samples so far (counted as incomplete before every joint is known).
  void Flush() {
    if (!has_group_ || !is_group_accepted_) return;
    if (!input_.is_complete()) {
      ++result_->incomplete_cycles;
      return;
    }
    if (result_->q.empty()) first_stamp_ = group_stamp_;
    result_->q.push_back(input_.q());
    result_->time_s.push_back(1e-9 * static_cast<double>(NsBetween(first_stamp_, group_stamp_)));
    const std::vector<double>& stamps = input_.joint_stamps();
    Eigen::VectorXd joint_time_s(static_cast<Eigen::Index>(stamps.size()));
    for (std::size_t i = 0; i < stamps.size(); ++i) {
      joint_time_s[static_cast<Eigen::Index>(i)] = stamps[i] - first_stamp_.toSec();
    }
    result_->joint_time_s.push_back(joint_time_s);
  }

  JointMerger input_;
  const std::string path_;
  const std::vector<std::string>& joint_names_;
  Input* result_;
  ros::Time group_stamp_, first_stamp_;
  bool has_group_ = false;
  bool is_group_accepted_ = false;  // a sample of the group was merged
  // The latest time of the samples so far (a refusal is met then: NoteRefusal).
  double arrival_s_ = -std::numeric_limits<double>::infinity();
};

// `read` (ReadDisplayTrajectory, or ReadGoalTrajectory's type bound) of the message `m` of the
// bag at `path`, by the definition the bag carries; a LoadError naming the message when it
// cannot be read.
template <typename Read>
auto ReadRaw(const std::string& path, const rosbag::MessageInstance& m, Read&& read) {
  std::vector<std::uint8_t> bytes(m.size());
  ros::serialization::OStream stream(bytes.data(), static_cast<std::uint32_t>(bytes.size()));
  m.write(stream);
  try {
    return read(m.getMessageDefinition(), bytes.data(), bytes.size());
  } catch (const std::runtime_error& e) {
    throw LoadError(MessageWhere(path, m) + ": " + e.what());
  }
}

// The topics the plans came on, and the joints they give.
struct PlanSources {
  std::set<std::string> topics;
  std::unordered_set<std::string> joints;
  std::size_t trajectories = 0, empty_trajectories = 0;  // read, and of those without points
};

// What the plans of `sources` held that may explain joints never given: trajectories without
// points (their names that are no model joints, a misspelt one, Cycles::Finish gives with the
// recorded states' ones).
std::string PlanHint(const PlanSources& sources) {
  if (sources.empty_trajectories == 0) return "";
  return "; " + std::to_string(sources.empty_trajectories) + " of the " +
         std::to_string(sources.trajectories) + " trajectories read have no points";
}

// Whether `m` is on one of `topics` (empty: all are read).
bool IsRead(const rosbag::MessageInstance& m, const std::vector<std::string>& topics) {
  return topics.empty() || std::find(topics.begin(), topics.end(), m.getTopic()) != topics.end();
}

// Per topic, a prefix of its joint names (ReadBag).
using JointPrefixes = std::map<std::string, std::string>;

// `names` with the prefix of `topic`, if it has one.
void PrefixNames(const JointPrefixes& prefixes, const std::string& topic,
                 std::vector<std::string>* names) {
  const auto it = prefixes.find(topic);
  if (it == prefixes.end()) return;
  for (std::string& name : *names) name.insert(0, it->second);
}

// MoveIt unwinds a plan before it executes it (plan_execution.cpp): each point's position of a
// joint of `turning` (KinematicModel::TurningLinks' joints) whole turns from where the point
// before it has the joint (the first point: `last`, where the display's start state or its
// trajectory before had it), so that the robot turns it the short way; a display of the plan
// may carry them wrapped into [-pi, pi]. `last` gets the plan's last positions.
void UnwindAsMoveItExecutes(const std::map<std::string, double>& turning,
                            std::map<std::string, double>* last,
                            trajectory_msgs::JointTrajectory* plan) {
  for (std::size_t j = 0; j < plan->joint_names.size(); ++j) {
    const std::string& name = plan->joint_names[j];
    if (turning.count(name) == 0) continue;
    const auto before = last->find(name);
    double previous = before != last->end() ? before->second : std::nan("");
    for (trajectory_msgs::JointTrajectoryPoint& point : plan->points) {
      if (j >= point.positions.size() || !std::isfinite(point.positions[j])) continue;
      if (std::isfinite(previous)) {
        point.positions[j] += kTurn * std::round((previous - point.positions[j]) / kTurn);
      }
      previous = point.positions[j];
    }
    if (std::isfinite(previous)) (*last)[name] = previous;
  }
}

// A LoadError naming the plan at `where` when its multi-DOF part (a mobile base's virtual joint)
// moves from `at` (DescribeMultiDofMotion, which moves `at` to its end): the monitor keeps the
// URDF root where the fixed frame is, and would check the arms as if the base stood still.
void RefuseBaseMotion(const std::string& where,
                      const trajectory_msgs::MultiDOFJointTrajectory& multi_dof,
                      MultiDofPoses* at) {
  const std::string motion = DescribeMultiDofMotion(multi_dof, at);
  if (motion.empty()) return;
  throw LoadError(where + ": " + motion + "; the monitor keeps the robot's root link fixed "
                  "(a fixed base), so it cannot check a plan that moves it (plan the arms with "
                  "the base standing still)");
}

// Where a planning scene placed its objects with the robot: the base's pose by virtual joint
// (Workcell::placed_roots), and where the scene says so.
struct ScenePlacement {
  MultiDofPoses poses;
  std::map<std::string, std::string> where;

  explicit ScenePlacement(const Workcell& workcell) {
    for (const PlacedRootSpec& root : workcell.placed_roots) {
      poses[root.joint] = ToTransformMsg(root.X_FR);
      where[root.joint] = root.where;
    }
  }

  /// A LoadError naming `what` of the plan at `plan_where` (its start state, a base
  /// trajectory's first point) when its `at` puts the base elsewhere than here.
  void RefuseAway(const std::string& plan_where, const std::string& what,
                  const MultiDofPoses& at) const {
    std::string joint;
    const std::string away = DescribeMultiDofAway(poses, at, &joint);
    if (away.empty()) return;
    throw LoadError(plan_where + ": " + what + " " + away + " " + where.at(joint) +
                    " places the robot; the monitor checks the arms against the planning "
                    "scene's objects placed with the robot there (save the scene with the "
                    "robot where the plans start)");
  }
};

// The plans of the bag at `path` on `topics`, in bag order, their joint names prefixed; those
// of MoveIt's displays unwound as MoveIt executes them (the plans' turning joints). A plan
// whose base starts or moves away from where `workcell`'s planning scene placed its objects
// with the robot is a LoadError.
PlanSources ReadPlans(const std::string& path, const rosbag::Bag& bag,
                      const std::vector<std::string>& topics, const JointPrefixes& prefixes,
                      const Workcell& workcell, Plans* plans) {
  const ScenePlacement placed(workcell);
  const std::map<std::string, double>& turning = plans->turning();
  PlanSources sources;
  rosbag::View view(bag, rosbag::TypeQuery(kPlanTypes));
  std::string topic;  // of the message read
  // A display's joints where its start state or its last trajectory has them (null: no
  // display, nothing unwound).
  std::map<std::string, double>* displayed_at = nullptr;
  auto add = [&](trajectory_msgs::JointTrajectory plan, const ros::Time& start,
                 const std::string& where) {
    PrefixNames(prefixes, topic, &plan.joint_names);
    if (displayed_at != nullptr) UnwindAsMoveItExecutes(turning, displayed_at, &plan);
    sources.joints.insert(plan.joint_names.begin(), plan.joint_names.end());
    ++sources.trajectories;
    sources.empty_trajectories += plan.points.empty() ? 1 : 0;
    return plans->AddTrajectory(plan, start, where);
  };
  for (const rosbag::MessageInstance& m : view) {
    if (!IsRead(m, topics)) continue;
    topic = m.getTopic();
    sources.topics.insert(topic);
    const std::string where = MessageWhere(path, m);
    if (const auto plan = m.instantiate<trajectory_msgs::JointTrajectory>()) {
      // A header.stamp of 0 (MoveIt's "start now") is the time the bag recorded it.
      add(*plan, plan->header.stamp.isZero() ? m.getTime() : plan->header.stamp, where);
    } else if (m.getDataType() == kDisplayTrajectoryType) {
      // MoveIt's display of a plan, at the time the bag recorded it: the start state (the
      // joints the trajectories leave out too), then the trajectories one after the other.
      DisplayedPlan displayed = ReadRaw(path, m, ReadDisplayTrajectory);
      ros::Time start = m.getTime();
      sensor_msgs::JointState& state = displayed.start_state;
      PrefixNames(prefixes, topic, &state.name);
      if (!state.name.empty()) plans->AddState(state, start, where);
      sources.joints.insert(state.name.begin(), state.name.end());
      std::map<std::string, double> at;
      for (std::size_t j = 0; j < state.name.size() && j < state.position.size(); ++j) {
        at[state.name[j]] = state.position[j];
      }
      displayed_at = &at;
      // The base where the start state has it (which must be where the scene placed the
      // objects with the robot), then where each trajectory leaves it.
      MultiDofPoses base_at = StartMultiDofPoses(displayed.start_multi_dof);
      placed.RefuseAway(where, "its start state", base_at);
      for (std::size_t k = 0; k < displayed.trajectories.size(); ++k) {
        const trajectory_msgs::JointTrajectory& plan = displayed.trajectories[k];
        const std::string where_k = where + ", trajectory " + std::to_string(k);
        // Its first point, within the agreement of the scene's placement, is where the base
        // stands for those the start state leaves out (DescribeMultiDofMotion).
        placed.RefuseAway(where_k, "its multi_dof_joint_trajectory's first point",
                          FirstMultiDofPoses(displayed.multi_dof_trajectories[k]));
        RefuseBaseMotion(where_k, displayed.multi_dof_trajectories[k], &base_at);
        start = add(plan, plan.header.stamp.isZero() ? start : plan.header.stamp, where_k);
      }
      displayed_at = nullptr;
    } else {
      // An action goal's trajectory: header.stamp 0 is when the goal arrived.
      const std::string type = m.getDataType();
      trajectory_msgs::MultiDOFJointTrajectory multi_dof;
      const trajectory_msgs::JointTrajectory plan = ReadRaw(
          path, m, [&](const std::string& definition, const std::uint8_t* data, std::size_t size) {
            return ReadGoalTrajectory(type, definition, data, size, &multi_dof);
          });
      placed.RefuseAway(where, "its multi_dof_joint_trajectory's first point",
                        FirstMultiDofPoses(multi_dof));
      MultiDofPoses base_at;  // where its first point has it
      RefuseBaseMotion(where, multi_dof, &base_at);
      add(plan, plan.header.stamp.isZero() ? m.getTime() : plan.header.stamp, where);
    }
  }
  return sources;
}

// A LoadError unless each of `topics` (of the command-line `option`) holds a message of a type
// read in the bag at `path`.
void CheckTopics(const std::string& path, rosbag::View* view,
                 const std::vector<std::string>& topics, const std::string& option) {
  for (const std::string& topic : topics) {
    bool is_found = false;
    for (const rosbag::ConnectionInfo* connection : view->getConnections()) {
      is_found |= connection->topic == topic;
    }
    if (!is_found) {
      throw LoadError(path + ": " + option + " " + topic + ": no " + ReadTypesText() +
                      " message on it");
    }
  }
}

// A LoadError when the recorded state `msg` gives a joint the plans give too (unless the topics
// were chosen).
void CheckNotPlanned(const std::string& path, const rosbag::MessageInstance& m,
                     const sensor_msgs::JointState& msg, const PlanSources& plans) {
  if (msg.position.empty()) return;
  for (const std::string& name : msg.name) {
    if (plans.joints.count(name) == 0) continue;
    std::string plan_topics;
    for (const std::string& topic : plans.topics) {
      plan_topics += (plan_topics.empty() ? "" : ", ") + topic;
    }
    throw LoadError(path + ": joint '" + name + "' has both recorded states (" + kJointStateType +
                    " on " + m.getTopic() + ") and planned paths (on " + plan_topics +
                    "): replay one of them with --topic");
  }
}

// Per topic and joint name: the stamp offsets (s) of the stamped JointState messages giving the
// joint, from the times the bag recorded them, gathered by ReadOffsets.
using JointOffsets = std::map<std::string, std::map<std::string, std::vector<double>>>;

// The stamped JointState messages' offsets on `topics` (all when empty), and the lower median of
// each joint's (in place of its list). A robot's clock off the recorder's gives its constant
// offset; a few messages stamped far off, or with other joints, do not move it.
JointOffsets ReadOffsets(const rosbag::Bag& bag, const std::vector<std::string>& topics) {
  JointOffsets offsets;
  for (const rosbag::MessageInstance& m : rosbag::View(bag, rosbag::TypeQuery(kJointStateType))) {
    const auto msg = m.instantiate<sensor_msgs::JointState>();
    if (msg == nullptr || !IsRead(m, topics) || msg->header.stamp.isZero()) continue;
    // In doubles: a difference of ros::Time beyond 68 years throws.
    const double offset_s = msg->header.stamp.toSec() - m.getTime().toSec();
    std::map<std::string, std::vector<double>>& of_topic = offsets[m.getTopic()];
    for (const std::string& name : msg->name) of_topic[name].push_back(offset_s);
  }
  for (auto& [topic, of_topic] : offsets) {
    for (auto& [name, values] : of_topic) {
      const auto lower = values.begin() + static_cast<std::ptrdiff_t>((values.size() - 1) / 2);
      std::nth_element(values.begin(), lower, values.end());
      values = {*lower};
    }
  }
  return offsets;
}

// The usual offset of `msg`'s stamps (ReadOffsets' medians): the smallest of its joints', so
// that a message stamped ahead of any of them is judged ahead.
double UsualOffset(const JointOffsets& offsets, const rosbag::MessageInstance& m,
                   const sensor_msgs::JointState& msg) {
  double usual_s = std::numeric_limits<double>::infinity();
  const auto of_topic = offsets.find(m.getTopic());
  if (of_topic == offsets.end()) return 0.0;
  for (const std::string& name : msg.name) {
    const auto joint = of_topic->second.find(name);
    if (joint != of_topic->second.end()) usual_s = std::min(usual_s, joint->second.front());
  }
  return std::isfinite(usual_s) ? usual_s : 0.0;
}

}  // namespace

Input ReadBag(const std::string& path, const std::vector<std::string>& topics,
              const JointPrefixes& joint_prefixes, const Workcell& workcell) {
  rosbag::Bag bag(path, rosbag::bagmode::Read);
  std::vector<std::string> types = kPlanTypes;
  types.push_back(kJointStateType);
  rosbag::View all(bag, rosbag::TypeQuery(types));
  if (all.size() == 0) throw LoadError(path + ": no " + ReadTypesText() + " message");
  CheckTopics(path, &all, topics, "--topic");
  std::vector<std::string> prefixed_topics;
  for (const auto& [topic, prefix] : joint_prefixes) {
    if (!topics.empty() && std::find(topics.begin(), topics.end(), topic) == topics.end()) {
      throw LoadError(path + ": --joint-prefix " + topic + ": not among the topics read (--topic)");
    }
    prefixed_topics.push_back(topic);
  }
  CheckTopics(path, &all, prefixed_topics, "--joint-prefix");
  Input result;
  std::map<std::string, double> turning;
  for (const int link : workcell.kinematics.TurningLinks()) {
    const JointSpec& joint = workcell.kinematics.joint(link);
    turning[joint.name] = joint.max_velocity;
  }
  Plans plans(&result, std::move(turning));
  const PlanSources sources = ReadPlans(path, bag, topics, joint_prefixes, workcell, &plans);
  const auto planned = plans.InTimeOrder();
  Cycles cycles(path, workcell, &result);
  // Each sample at `stamp` (of plan `joints` at its `point`, null for a recorded state, the
  // bag's `message`) with the other plans under way then.
  auto add = [&](const NamedPositions& sample, const ros::Time& stamp,
                 const Plans::Joints* joints, const Plans::Point* point,
                 const rosbag::MessageInstance* message, double offset_s) {
    cycles.Add(sample, stamp, message, offset_s, joints, point);
    plans.ForEachUnderWayAt(
        stamp, joints, [&](const NamedPositions& under_way, const Plans::Joints& plan) {
          cycles.Add(under_way, stamp, nullptr, 0.0, &plan);
        });
  };
  // The planned points before `stamp` (all that are left when null); at equal stamps the
  // recorded state comes first, in the same cycle.
  std::size_t next = 0;
  auto add_planned_before = [&](const ros::Time* stamp) {
    for (; next < planned.size() && (stamp == nullptr || planned[next].second->stamp < *stamp);
         ++next) {
      const auto& [joints, point] = planned[next];
      add(NamedPositions{joints->names, point->positions, point->stamp.toSec()}, point->stamp,
          joints, point, nullptr, 0.0);
    }
  };
  const JointOffsets offsets = ReadOffsets(bag, topics);
  // The model's joint farthest off (a gripper's driver on the recorder's clock beside an arm's
  // on the robot's does not hide the arm's offset; names of no model joint do not count).
  const std::set<std::string> model_joints(workcell.joint_names.begin(),
                                           workcell.joint_names.end());
  for (const auto& [topic, of_topic] : offsets) {
    const auto prefix = joint_prefixes.find(topic);
    double farthest_s = 0.0;
    for (const auto& [name, offset_s] : of_topic) {
      const std::string model_name = prefix != joint_prefixes.end() ? prefix->second + name : name;
      if (model_joints.count(model_name) == 0) continue;
      if (std::abs(offset_s.front()) > std::abs(farthest_s)) farthest_s = offset_s.front();
    }
    if (std::abs(farthest_s) > kDefaultInputTimeout_s) result.clock_offsets[topic] = farthest_s;
  }
  for (const rosbag::MessageInstance& m : rosbag::View(bag, rosbag::TypeQuery(kJointStateType))) {
    const auto msg = m.instantiate<sensor_msgs::JointState>();
    if (msg == nullptr || !IsRead(m, topics)) continue;
    const double usual_s = UsualOffset(offsets, m, *msg);
    PrefixNames(joint_prefixes, m.getTopic(), &msg->name);
    if (topics.empty()) CheckNotPlanned(path, m, *msg, sources);
    ++result.messages;
    // An unstamped message (0) was sampled when the bag recorded it, as the node takes it.
    const ros::Time stamp = msg->header.stamp.isZero() ? m.getTime() : msg->header.stamp;
    add_planned_before(&stamp);
    add(ToNamedPositions(*msg), stamp, nullptr, nullptr, &m, usual_s);
  }
  add_planned_before(nullptr);
  cycles.Finish(path, PlanHint(sources));
  return result;
}

}  // namespace replay
}  // namespace arm_collision_monitor
