// Merges sensor_msgs/JointState messages from any number of topics (one per arm, or one
// combined) into the Monitor's joint vector q, ordered as Workcell::joint_names. Validates each
// message before touching q, so a refused message leaves the merged state as it was.
#pragma once

#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

#include <Eigen/Core>
#include <ros/time.h>
#include <sensor_msgs/JointState.h>

namespace arm_collision_monitor {

/// Outcome of merging one message; the values match MonitorReport's INPUT_* constants.
enum class MergeStatus : std::uint8_t {
  kAccepted = 0,
  kWrongSize = 1,       ///< name and position arrays of different lengths, or a name twice
  kNonFinite = 2,       ///< a NaN or inf position of a model joint
  kStale = 5,           ///< the message stamp is older than the input timeout
  kStampBackwards = 6,  ///< older than the last accepted stamp of one of its joints
  kNoKnownJoints = 7,   ///< names no joint of the model
  kFutureStamp = 8,     ///< stamped further ahead of now than the input timeout
};

/// Short lower-case name of a status ("wrong_size", ...), for logs and diagnostics.
const char* MergeStatusName(MergeStatus status);

class JointStateInput {
 public:
  /// `joint_names`: the model's joints in q order. `input_timeout_s` > 0: a joint whose newest
  /// accepted message was received longer ago is stale; a message stamped longer ago is
  /// refused as stale, one stamped further ahead as from the future (one such message would
  /// otherwise make every later one look "backwards").
  JointStateInput(const std::vector<std::string>& joint_names, double input_timeout_s);

  /// Validates `msg` (received at `now`) and, if it is acceptable, writes its model joints into
  /// q. Names that are not model joints are ignored and counted. A zero stamp means "unknown"
  /// and is replaced by `now`. Allocates only when a new name layout is seen.
  MergeStatus Merge(const sensor_msgs::JointState& msg, const ros::Time& now);

  /// Merges `msg` into a copy of the current q (for generate-and-test queries); the live state
  /// is not touched. Same validation as Merge() except the stamp checks.
  MergeStatus MergeIntoCopy(const sensor_msgs::JointState& msg, Eigen::VectorXd* q) const;

  /// Re-bases every time-derived state on `now` after the ROS clock jumped back (simulated
  /// time: a looping bag, a simulator reset): the per-joint stamps are forgotten, each joint's
  /// receipt time becomes `now` (so its age counts from the jump, never from a time now in the
  /// future), and every received joint awaits a message accepted after the jump. A joint
  /// awaiting input counts as stale (IsStale()) until then. Allocation-free.
  void OnTimeWentBackwards(const ros::Time& now);

  const Eigen::VectorXd& q() const { return q_; }
  /// Every model joint has been received at least once.
  bool is_complete() const { return missing_count_ == 0; }
  /// Index of the first model joint never received, -1 when complete.
  int FirstMissingJoint() const;
  /// Index of a joint awaiting input since the clock went back if any, else of the joint
  /// received longest ago (largest age); -1 before any input.
  int OldestJoint() const;
  /// True when joint `index` has received nothing since the ROS clock last went back.
  bool IsAwaitingInput(int index) const { return is_awaiting_[index]; }
  /// Seconds since joint `index` was last received at time `now` (inf if never).
  double JointAge(int index, const ros::Time& now) const;
  /// True when some joint is stale at time `now`, or awaits input since the clock went back
  /// (never received does not count: see is_complete()).
  bool IsStale(const ros::Time& now) const;
  const std::string& joint_name(int index) const { return joint_names_[index]; }
  int joint_count() const { return static_cast<int>(joint_names_.size()); }
  double input_timeout_s() const { return input_timeout_s_; }

  /// Unknown names in the last merged message, and in all messages so far.
  std::uint32_t last_unknown_joints() const { return last_unknown_joints_; }
  std::uint64_t total_unknown_joints() const { return total_unknown_joints_; }

 private:
  /// A name layout seen on the input: the model index of each entry of msg.name (-1 unknown).
  struct Layout {
    std::vector<std::string> names;
    std::vector<int> q_index;
    std::uint32_t unknown_count = 0;
    bool has_duplicate = false;
  };
  const Layout& FindOrAddLayout(const std::vector<std::string>& names);
  Layout BuildLayout(const std::vector<std::string>& names) const;
  MergeStatus ValidatePositions(const Layout& layout, const sensor_msgs::JointState& msg) const;

  std::vector<std::string> joint_names_;
  std::unordered_map<std::string, int> index_of_name_;
  double input_timeout_s_;
  Eigen::VectorXd q_;
  std::vector<ros::Time> stamp_;     ///< newest accepted stamp per joint
  std::vector<ros::Time> received_;  ///< receipt time of that message per joint
  std::vector<bool> is_received_;
  int missing_count_;
  std::vector<bool> is_awaiting_;    ///< received before the clock went back, not since
  int awaiting_count_ = 0;
  std::vector<Layout> layouts_;      ///< small: one per distinct publisher layout
  std::size_t last_layout_ = 0;
  std::uint32_t last_unknown_joints_ = 0;
  std::uint64_t total_unknown_joints_ = 0;
};

}  // namespace arm_collision_monitor
