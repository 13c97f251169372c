// Merges named joint positions from any number of sources (one per arm, or one combined) into
// the Monitor's joint vector q, ordered as Workcell::joint_names. ROS-free: the node translates
// each sensor_msgs/JointState into a NamedPositions and the ROS time into seconds. Each message
// is validated before q is touched, so a refused message leaves the merged state as it was.
// Joint limits are not checked here: the Monitor owns them (with their margin) and refuses q.
#pragma once

#include <cstdint>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "arm_collision_monitor/safety/safety_status.h"

namespace arm_collision_monitor {

/// Outcome of merging one message: a subset of SafetyStatus, with its values (so of
/// MonitorReport's INPUT_* constants too), and kNoPositions, which is not a refusal.
enum class MergeStatus : std::uint8_t {
  kAccepted = static_cast<std::uint8_t>(SafetyStatus::kOk),
  /// name and position arrays of different lengths, or a name twice
  kWrongSize = static_cast<std::uint8_t>(SafetyStatus::kWrongSize),
  /// a NaN or inf position of a model joint
  kNonFinite = static_cast<std::uint8_t>(SafetyStatus::kNonFinite),
  /// the message stamp is older than the input timeout
  kStale = static_cast<std::uint8_t>(SafetyStatus::kStale),
  /// older than the last accepted stamp of one of its joints
  kStampBackwards = static_cast<std::uint8_t>(SafetyStatus::kStampBackwards),
  /// names no joint of the model
  kNoKnownJoints = static_cast<std::uint8_t>(SafetyStatus::kNoKnownJoints),
  /// stamped further ahead of now than the input timeout
  kFutureStamp = static_cast<std::uint8_t>(SafetyStatus::kFutureStamp),
  /// names joints but gives no positions (JointState's arrays may be empty: a driver that
  /// publishes efforts only): nothing to merge, the message is counted and ignored, not refused
  /// (joints that only such messages name go stale)
  kNoPositions = 255,
};

/// The SafetyStatus of a refusal (not of kNoPositions).
inline SafetyStatus ToSafetyStatus(MergeStatus status) {
  return static_cast<SafetyStatus>(status);
}

/// Short lower-case name of a status ("accepted", "wrong_size", ...), for logs and diagnostics.
const char* MergeStatusName(MergeStatus status);

/// What to do about `count` model joints that no input gives, for the messages that name them.
const char* JointDefaultsHint(std::size_t count);

/// "model joint 'a'" for one name, "3 model joints: 'a', 'b', 'c'" for more: every joint of a
/// start-up error at once, so that a user fixes them in one go.
std::string ModelJointsText(const std::vector<std::string>& names);

/// One message's named positions, borrowed from the caller for the duration of a call.
struct NamedPositions {
  const std::vector<std::string>& names;
  const std::vector<double>& positions;  ///< rad or m, one per name
  double stamp_s = 0.0;                  ///< source time stamp, s; 0 = unknown (receipt time)
};

class JointMerger {
 public:
  /// `joint_names`: the model's joints in q order. `input_timeout_s` > 0: a joint whose newest
  /// accepted message was received longer ago is stale; a message stamped longer ago is
  /// refused as stale, one stamped further ahead as from the future (one such message would
  /// otherwise make every later one look "backwards").
  JointMerger(const std::vector<std::string>& joint_names, double input_timeout_s);

  /// Each (joint index, position in rad or m) of `defaults`: the joint is at that position
  /// until a message gives it; it counts as received for is_complete() but has no age, so it is
  /// never stale, until then; from the first message on it is an input joint like the others
  /// (the scene file's joint_defaults, Workcell::joint_defaults: joints that the input may
  /// leave out, e.g. a gripper's in a planned arm path).
  void SetDefaults(const std::vector<std::pair<int, double>>& defaults);

  /// The URDF's mimic joints (KinematicModel::MimicJointNames): their positions follow from the
  /// joints they mimic, so a message's mimic joints are ignored like unknown names but counted
  /// apart, and a refusal says what they are. Call before the first Merge.
  void SetMimicJoints(const std::vector<std::string>& names);

  /// Validates `input` (received at `now_s`, the same clock as its stamps) and, if it is
  /// acceptable, writes its model joints into q. Names that are not model joints are ignored and
  /// counted. Allocates only when a new name layout is seen.
  MergeStatus Merge(const NamedPositions& input, double now_s);

  /// What in `input`, received at `now_s`, Merge refused with `status`: the joint and its value
  /// (non-finite), the sizes or the repeated name (wrong size), the names (none a model joint),
  /// the stamp's age at arrival (stale, future), the first joint accepted with a later stamp
  /// and by how much (backwards). Allocates: for logs of refusals only.
  std::string DescribeRefusal(const NamedPositions& input, MergeStatus status,
                              double now_s) const;

  /// Merges `input` into a copy of the current q (for generate-and-test queries); the live state
  /// is not touched. Same validation as Merge() except the stamp checks.
  MergeStatus MergeIntoCopy(const NamedPositions& input, Eigen::VectorXd* q) const;

  /// Re-bases every time-derived state on `now_s` after the clock jumped back (simulated time:
  /// a looping bag, a simulator reset): the per-joint stamps are forgotten, each joint's receipt
  /// time becomes `now_s` (so its age counts from the jump, never from a time now in the
  /// future), and every received joint awaits a message accepted after the jump. A joint
  /// awaiting input counts as stale (IsStale()) until then. Allocation-free.
  void OnTimeWentBackwards(double now_s);

  const Eigen::VectorXd& q() const { return q_; }
  /// Every model joint has been received at least once or has a default (SetDefaults).
  bool is_complete() const { return missing_count_ == 0; }
  /// Index of the first model joint never received and without a default, -1 when complete.
  int FirstMissingJoint() const;
  /// How many model joints were never received and have no default.
  int missing_count() const { return missing_count_; }
  /// The names of those joints, in q order (allocates: for errors, not for the cycle).
  std::vector<std::string> MissingJoints() const { return MissingJointsNotIn({}); }
  /// Those of them not in `names`, in q order: a request naming them all could complete the
  /// model (the check service's rule).
  std::vector<std::string> MissingJointsNotIn(const std::vector<std::string>& names) const;
  /// Index of a joint awaiting input since the clock went back if any, else of the joint
  /// received longest ago (largest age); -1 before any input.
  int OldestJoint() const;
  /// True when joint `index` has received nothing since the clock last went back.
  bool IsAwaitingInput(int index) const { return is_awaiting_[index]; }
  /// Per joint (q order): the stamp of the message that gave its position (its receipt time
  /// when unstamped), s; -inf for one never received. For Monitor::Update's jump test.
  const std::vector<double>& joint_stamps() const { return stamp_s_; }
  /// Seconds since joint `index` was last received at time `now_s` (inf if never).
  double JointAge(int index, double now_s) const;
  /// True when some joint is stale at time `now_s`, or awaits input since the clock went back
  /// (never received does not count: see is_complete()).
  bool IsStale(double now_s) const;
  const std::string& joint_name(int index) const { return joint_names_[index]; }
  /// Whether `name` is a joint of the model (Merge ignores and counts the others).
  bool IsModelJoint(const std::string& name) const { return index_of_name_.count(name) > 0; }
  /// Whether `name` is one of SetMimicJoints' (no model joint).
  bool IsMimicJoint(const std::string& name) const { return mimic_names_.count(name) > 0; }
  int joint_count() const { return static_cast<int>(joint_names_.size()); }
  double input_timeout_s() const { return input_timeout_s_; }

  /// Unknown names in the last merged message, and in all messages so far (mimic joints'
  /// names not among them).
  std::uint32_t last_unknown_joints() const { return last_unknown_joints_; }
  std::uint64_t total_unknown_joints() const { return total_unknown_joints_; }
  /// Names of mimic joints (SetMimicJoints), ignored, in the last merged message and in all
  /// messages so far.
  std::uint32_t last_mimic_joints() const { return last_mimic_joints_; }
  std::uint64_t total_mimic_joints() const { return total_mimic_joints_; }
  /// Messages refused by Merge() so far, in all and per status (indexed by its value).
  std::uint64_t refused() const { return refused_; }
  std::uint64_t refused_with(MergeStatus status) const;
  /// Messages Merge() ignored as giving no positions (MergeStatus::kNoPositions) so far.
  std::uint64_t position_less() const { return position_less_; }
  /// Whether `input` names joints but gives no positions (MergeStatus::kNoPositions).
  static bool GivesNoPositions(const NamedPositions& input) {
    return input.positions.empty() && !input.names.empty();
  }

 private:
  /// A name layout seen on the input: the model index of each entry of names (-1 unknown).
  struct Layout {
    std::vector<std::string> names;
    std::vector<int> q_index;
    std::uint32_t unknown_count = 0;  // no model joint, nor a mimic one
    std::uint32_t mimic_count = 0;
    int first_duplicate = -1;  // the first entry naming a model joint named before; -1 none
  };
  const Layout& FindOrAddLayout(const std::vector<std::string>& names);
  Layout BuildLayout(const std::vector<std::string>& names) const;
  MergeStatus ValidatePositions(const Layout& layout, const NamedPositions& input) const;
  MergeStatus ValidateStamp(const Layout& layout, double stamp_s, double now_s) const;
  MergeStatus Refuse(MergeStatus status);
  /// Model joint `i` was never received and has no default.
  bool IsMissing(std::size_t i) const { return !is_received_[i] && !has_default_[i]; }

  std::vector<std::string> joint_names_;
  std::unordered_map<std::string, int> index_of_name_;
  std::unordered_set<std::string> mimic_names_;
  double input_timeout_s_;
  Eigen::VectorXd q_;
  std::vector<double> stamp_s_;     ///< newest accepted stamp per joint (-inf: none)
  std::vector<double> received_s_;  ///< receipt time of that message per joint
  std::vector<bool> is_received_;
  std::vector<bool> has_default_;   ///< SetDefaults' joints
  int missing_count_;               ///< joints neither received nor with a default
  std::vector<bool> is_awaiting_;   ///< received before the clock went back, not since
  int awaiting_count_ = 0;
  std::vector<Layout> layouts_;     ///< small: one per distinct publisher layout
  std::size_t last_layout_ = 0;
  std::uint32_t last_unknown_joints_ = 0;
  std::uint64_t total_unknown_joints_ = 0;
  std::uint32_t last_mimic_joints_ = 0;
  std::uint64_t total_mimic_joints_ = 0;
  std::uint64_t refused_ = 0;
  std::uint64_t refused_by_status_[kSafetyStatusCount] = {};
  std::uint64_t position_less_ = 0;
};

}  // namespace arm_collision_monitor
