#include "arm_collision_monitor/ros/joint_state_input.h"

#include <cmath>
#include <limits>

namespace arm_collision_monitor {
namespace {

// Distinct name layouts kept (one per publisher in practice: two arms, maybe a combined
// topic). Past this, the oldest entry is replaced, so memory stays bounded whatever arrives.
constexpr std::size_t kMaxLayouts = 16;

}  // namespace

const char* MergeStatusName(MergeStatus status) {
  switch (status) {
    case MergeStatus::kAccepted:
      return "accepted";
    case MergeStatus::kWrongSize:
      return "wrong_size";
    case MergeStatus::kNonFinite:
      return "non_finite";
    case MergeStatus::kStale:
      return "stale";
    case MergeStatus::kStampBackwards:
      return "stamp_backwards";
    case MergeStatus::kNoKnownJoints:
      return "no_known_joints";
    case MergeStatus::kFutureStamp:
      return "future_stamp";
  }
  return "unknown";
}

JointStateInput::JointStateInput(const std::vector<std::string>& joint_names,
                                 double input_timeout_s)
    : joint_names_(joint_names),
      input_timeout_s_(input_timeout_s),
      q_(Eigen::VectorXd::Zero(static_cast<Eigen::Index>(joint_names.size()))),
      stamp_(joint_names.size()),
      received_(joint_names.size()),
      is_received_(joint_names.size(), false),
      missing_count_(static_cast<int>(joint_names.size())),
      is_awaiting_(joint_names.size(), false) {
  for (std::size_t i = 0; i < joint_names_.size(); ++i) {
    index_of_name_.emplace(joint_names_[i], static_cast<int>(i));
  }
  layouts_.reserve(kMaxLayouts);
}

JointStateInput::Layout JointStateInput::BuildLayout(const std::vector<std::string>& names) const {
  Layout layout;
  layout.names = names;
  layout.q_index.assign(names.size(), -1);
  std::vector<bool> seen(joint_names_.size(), false);
  for (std::size_t k = 0; k < names.size(); ++k) {
    const auto it = index_of_name_.find(names[k]);
    if (it == index_of_name_.end()) {
      ++layout.unknown_count;
      continue;
    }
    if (seen[it->second]) {
      layout.has_duplicate = true;
    }
    seen[it->second] = true;
    layout.q_index[k] = it->second;
  }
  return layout;
}

const JointStateInput::Layout& JointStateInput::FindOrAddLayout(
    const std::vector<std::string>& names) {
  // The steady state: the same publisher layouts over and over, compared without allocating.
  if (last_layout_ < layouts_.size() && layouts_[last_layout_].names == names) {
    return layouts_[last_layout_];
  }
  for (std::size_t i = 0; i < layouts_.size(); ++i) {
    if (layouts_[i].names == names) {
      last_layout_ = i;
      return layouts_[i];
    }
  }
  if (layouts_.size() < kMaxLayouts) {
    layouts_.push_back(BuildLayout(names));
    last_layout_ = layouts_.size() - 1;
  } else {
    last_layout_ = (last_layout_ + 1) % kMaxLayouts;
    layouts_[last_layout_] = BuildLayout(names);
  }
  return layouts_[last_layout_];
}

MergeStatus JointStateInput::ValidatePositions(const Layout& layout,
                                               const sensor_msgs::JointState& msg) const {
  if (msg.position.size() != msg.name.size() || layout.has_duplicate) {
    return MergeStatus::kWrongSize;
  }
  if (layout.unknown_count == layout.names.size()) {
    return MergeStatus::kNoKnownJoints;
  }
  for (std::size_t k = 0; k < layout.q_index.size(); ++k) {
    if (layout.q_index[k] >= 0 && !std::isfinite(msg.position[k])) {
      return MergeStatus::kNonFinite;
    }
  }
  return MergeStatus::kAccepted;
}

MergeStatus JointStateInput::Merge(const sensor_msgs::JointState& msg, const ros::Time& now) {
  const Layout& layout = FindOrAddLayout(msg.name);
  last_unknown_joints_ = layout.unknown_count;
  total_unknown_joints_ += layout.unknown_count;
  const MergeStatus status = ValidatePositions(layout, msg);
  if (status != MergeStatus::kAccepted) {
    return status;
  }
  const ros::Time stamp = msg.header.stamp.isZero() ? now : msg.header.stamp;
  // Seconds as doubles: ros::Time arithmetic throws on out-of-range stamps, and a message's
  // stamp is untrusted input.
  const double age_s = now.toSec() - stamp.toSec();
  if (age_s > input_timeout_s_) {
    return MergeStatus::kStale;
  }
  if (-age_s > input_timeout_s_) {
    return MergeStatus::kFutureStamp;
  }
  for (const int i : layout.q_index) {
    if (i >= 0 && stamp < stamp_[i]) {
      return MergeStatus::kStampBackwards;
    }
  }
  for (std::size_t k = 0; k < layout.q_index.size(); ++k) {
    const int i = layout.q_index[k];
    if (i < 0) {
      continue;
    }
    if (!is_received_[i]) {
      is_received_[i] = true;
      --missing_count_;
    }
    if (is_awaiting_[i]) {
      is_awaiting_[i] = false;
      --awaiting_count_;
    }
    q_[i] = msg.position[k];
    stamp_[i] = stamp;
    received_[i] = now;
  }
  return MergeStatus::kAccepted;
}

MergeStatus JointStateInput::MergeIntoCopy(const sensor_msgs::JointState& msg,
                                           Eigen::VectorXd* q) const {
  const Layout layout = BuildLayout(msg.name);
  const MergeStatus status = ValidatePositions(layout, msg);
  if (status != MergeStatus::kAccepted) {
    return status;
  }
  *q = q_;
  for (std::size_t k = 0; k < layout.q_index.size(); ++k) {
    if (layout.q_index[k] >= 0) {
      (*q)[layout.q_index[k]] = msg.position[k];
    }
  }
  return MergeStatus::kAccepted;
}

void JointStateInput::OnTimeWentBackwards(const ros::Time& now) {
  awaiting_count_ = 0;
  for (std::size_t i = 0; i < stamp_.size(); ++i) {
    stamp_[i] = ros::Time();
    received_[i] = now;
    is_awaiting_[i] = is_received_[i];
    awaiting_count_ += is_received_[i] ? 1 : 0;
  }
}

int JointStateInput::FirstMissingJoint() const {
  for (std::size_t i = 0; i < is_received_.size(); ++i) {
    if (!is_received_[i]) {
      return static_cast<int>(i);
    }
  }
  return -1;
}

int JointStateInput::OldestJoint() const {
  int oldest = -1;
  for (std::size_t i = 0; i < received_.size(); ++i) {
    if (awaiting_count_ > 0 && !is_awaiting_[i]) {
      continue;  // a joint silent since the clock went back is the one to name
    }
    if (is_received_[i] && (oldest < 0 || received_[i] < received_[oldest])) {
      oldest = static_cast<int>(i);
    }
  }
  return oldest;
}

double JointStateInput::JointAge(int index, const ros::Time& now) const {
  if (!is_received_[index]) {
    return std::numeric_limits<double>::infinity();
  }
  return now.toSec() - received_[index].toSec();
}

bool JointStateInput::IsStale(const ros::Time& now) const {
  if (awaiting_count_ > 0) {
    return true;
  }
  const int oldest = OldestJoint();
  return oldest >= 0 && JointAge(oldest, now) > input_timeout_s_;
}

}  // namespace arm_collision_monitor
