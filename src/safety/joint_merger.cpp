#include "arm_collision_monitor/safety/joint_merger.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

#include "arm_collision_monitor/core/load_error.h"

namespace arm_collision_monitor {
namespace {

// Distinct name layouts kept (one per publisher in practice: two arms, maybe a combined
// topic). Past this, the oldest entry is replaced, so memory stays bounded whatever arrives.
constexpr std::size_t kMaxLayouts = 16;
constexpr double kNoStamp_s = -std::numeric_limits<double>::infinity();

}  // namespace

const char* MergeStatusName(MergeStatus status) {
  if (status == MergeStatus::kNoPositions) return "no_positions";
  return status == MergeStatus::kAccepted ? "accepted" : SafetyStatusName(ToSafetyStatus(status));
}

const char* JointDefaultsHint(std::size_t count) {
  return count == 1 ? "publish it, or give it a position in the scene file's joint_defaults"
                    : "publish them, or give them positions in the scene file's joint_defaults";
}

std::string ModelJointsText(const std::vector<std::string>& names) {
  return (names.size() == 1 ? "model joint " : std::to_string(names.size()) + " model joints: ") +
         QuotedNames(names);
}

JointMerger::JointMerger(const std::vector<std::string>& joint_names, double input_timeout_s)
    : joint_names_(joint_names),
      input_timeout_s_(input_timeout_s),
      q_(Eigen::VectorXd::Zero(static_cast<Eigen::Index>(joint_names.size()))),
      stamp_s_(joint_names.size(), kNoStamp_s),
      received_s_(joint_names.size(), 0.0),
      is_received_(joint_names.size(), false),
      has_default_(joint_names.size(), false),
      missing_count_(static_cast<int>(joint_names.size())),
      is_awaiting_(joint_names.size(), false) {
  for (std::size_t i = 0; i < joint_names_.size(); ++i) {
    index_of_name_.emplace(joint_names_[i], static_cast<int>(i));
  }
  layouts_.reserve(kMaxLayouts);
}

void JointMerger::SetDefaults(const std::vector<std::pair<int, double>>& defaults) {
  for (const auto& [index, position_rad_or_m] : defaults) {
    if (!is_received_[index]) {
      q_[index] = position_rad_or_m;
      if (!has_default_[index]) --missing_count_;
    }
    has_default_[index] = true;
  }
}

void JointMerger::SetMimicJoints(const std::vector<std::string>& names) {
  mimic_names_.clear();
  mimic_names_.insert(names.begin(), names.end());
  layouts_.clear();  // their counts change
  last_layout_ = 0;
}

JointMerger::Layout JointMerger::BuildLayout(const std::vector<std::string>& names) const {
  Layout layout;
  layout.names = names;
  layout.q_index.assign(names.size(), -1);
  std::vector<bool> seen(joint_names_.size(), false);
  for (std::size_t k = 0; k < names.size(); ++k) {
    const auto it = index_of_name_.find(names[k]);
    if (it == index_of_name_.end()) {
      ++(IsMimicJoint(names[k]) ? layout.mimic_count : layout.unknown_count);
      continue;
    }
    if (seen[it->second] && layout.first_duplicate < 0) {
      layout.first_duplicate = static_cast<int>(k);
    }
    seen[it->second] = true;
    layout.q_index[k] = it->second;
  }
  return layout;
}

const JointMerger::Layout& JointMerger::FindOrAddLayout(const std::vector<std::string>& names) {
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

MergeStatus JointMerger::ValidatePositions(const Layout& layout,
                                           const NamedPositions& input) const {
  if (input.positions.size() != input.names.size() || layout.first_duplicate >= 0) {
    return MergeStatus::kWrongSize;
  }
  if (layout.unknown_count + layout.mimic_count == layout.names.size()) {
    return MergeStatus::kNoKnownJoints;
  }
  for (std::size_t k = 0; k < layout.q_index.size(); ++k) {
    if (layout.q_index[k] >= 0 && !std::isfinite(input.positions[k])) {
      return MergeStatus::kNonFinite;
    }
  }
  return MergeStatus::kAccepted;
}

std::string JointMerger::DescribeRefusal(const NamedPositions& input, MergeStatus status,
                                         double now_s) const {
  const std::vector<std::string>& names = input.names;
  // The first model joint whose last accepted stamp is later than the message's ("" if none).
  auto backwards = [&]() -> std::string {
    for (const std::string& name : names) {
      const auto it = index_of_name_.find(name);
      if (it == index_of_name_.end() || !(input.stamp_s < stamp_s_[it->second])) continue;
      // Under a millisecond (two drivers' messages racing) in whole microseconds, not
      // "0.000 s" (a stamp near 1.7e9 s holds no finer than a quarter microsecond).
      const double back_s = stamp_s_[it->second] - input.stamp_s;
      char text[64];
      if (back_s >= 0.9995e-3) {
        std::snprintf(text, sizeof(text), "' %.3f s before its last accepted stamp", back_s);
      } else {
        std::snprintf(text, sizeof(text), "' %.0f us before its last accepted stamp",
                      back_s * 1e6);
      }
      return "joint '" + name + text;
    }
    return "";
  };
  switch (status) {
    case MergeStatus::kWrongSize: {
      if (input.positions.size() != names.size()) {
        return std::to_string(names.size()) + " names but " +
               std::to_string(input.positions.size()) + " positions";
      }
      // The model joint named twice (a name the model does not know may repeat).
      const int twice = BuildLayout(names).first_duplicate;
      return twice < 0 ? "" : "joint '" + names[twice] + "' named twice";
    }
    case MergeStatus::kNonFinite:
      for (std::size_t k = 0; k < names.size() && k < input.positions.size(); ++k) {
        if (IsModelJoint(names[k]) && !std::isfinite(input.positions[k])) {
          std::ostringstream text;
          text << "joint '" << names[k] << "' at " << input.positions[k];
          return text.str();
        }
      }
      return "";
    case MergeStatus::kNoKnownJoints:
      return names.empty() ? "no name"
                           : "none of its " + std::to_string(names.size()) +
                                 " names is a model joint, the first '" + names.front() + "'" +
                                 (IsMimicJoint(names.front())
                                      ? " (a mimic joint: its position follows from the joint "
                                        "it mimics in the URDF; give that one)"
                                      : "");
    case MergeStatus::kStale:
    case MergeStatus::kFutureStamp: {
      const double age_s = now_s - input.stamp_s;
      char text[128];
      std::snprintf(text, sizeof(text), "stamped %.3f s %s its arrival, over input_timeout_s "
                    "(%.3f s)", std::abs(age_s), age_s >= 0.0 ? "before" : "after",
                    input_timeout_s_);
      // Staleness is checked first; a stale message going back in time says that too.
      const std::string behind = backwards();
      return behind.empty() ? std::string(text) : text + ("; also " + behind);
    }
    case MergeStatus::kStampBackwards:
      return backwards();
    default:
      return "";
  }
}

MergeStatus JointMerger::ValidateStamp(const Layout& layout, double stamp_s,
                                       double now_s) const {
  const double age_s = now_s - stamp_s;
  if (age_s > input_timeout_s_) {
    return MergeStatus::kStale;
  }
  if (-age_s > input_timeout_s_) {
    return MergeStatus::kFutureStamp;
  }
  for (const int i : layout.q_index) {
    if (i >= 0 && stamp_s < stamp_s_[i]) {
      return MergeStatus::kStampBackwards;
    }
  }
  return MergeStatus::kAccepted;
}

MergeStatus JointMerger::Refuse(MergeStatus status) {
  ++refused_;
  ++refused_by_status_[static_cast<int>(status)];
  return status;
}

MergeStatus JointMerger::Merge(const NamedPositions& input, double now_s) {
  if (GivesNoPositions(input)) {
    ++position_less_;
    return MergeStatus::kNoPositions;
  }
  const Layout& layout = FindOrAddLayout(input.names);
  last_unknown_joints_ = layout.unknown_count;
  total_unknown_joints_ += layout.unknown_count;
  last_mimic_joints_ = layout.mimic_count;
  total_mimic_joints_ += layout.mimic_count;
  // An unstamped message (0) was sampled when it arrived: its order cannot be checked (a clock
  // behind the stamps of the joints' other messages, simulated time published at 100 Hz, would
  // make it go backwards), and each joint's stamp stays where it is if later.
  const bool is_unstamped = input.stamp_s == 0.0;
  MergeStatus status = ValidatePositions(layout, input);
  if (status == MergeStatus::kAccepted && !is_unstamped) {
    status = ValidateStamp(layout, input.stamp_s, now_s);
  }
  if (status != MergeStatus::kAccepted) {
    return Refuse(status);
  }
  for (std::size_t k = 0; k < layout.q_index.size(); ++k) {
    const int i = layout.q_index[k];
    if (i < 0) {
      continue;
    }
    if (!is_received_[i]) {
      is_received_[i] = true;
      if (!has_default_[i]) --missing_count_;
    }
    if (is_awaiting_[i]) {
      is_awaiting_[i] = false;
      --awaiting_count_;
    }
    q_[i] = input.positions[k];
    stamp_s_[i] = is_unstamped ? std::max(stamp_s_[i], now_s) : input.stamp_s;
    received_s_[i] = now_s;
  }
  return MergeStatus::kAccepted;
}

MergeStatus JointMerger::MergeIntoCopy(const NamedPositions& input, Eigen::VectorXd* q) const {
  const Layout layout = BuildLayout(input.names);
  const MergeStatus status = ValidatePositions(layout, input);
  if (status != MergeStatus::kAccepted) {
    return status;
  }
  *q = q_;
  for (std::size_t k = 0; k < layout.q_index.size(); ++k) {
    if (layout.q_index[k] >= 0) {
      (*q)[layout.q_index[k]] = input.positions[k];
    }
  }
  return MergeStatus::kAccepted;
}

void JointMerger::OnTimeWentBackwards(double now_s) {
  awaiting_count_ = 0;
  for (std::size_t i = 0; i < stamp_s_.size(); ++i) {
    stamp_s_[i] = kNoStamp_s;
    received_s_[i] = now_s;
    is_awaiting_[i] = is_received_[i];
    awaiting_count_ += is_received_[i] ? 1 : 0;
  }
}

int JointMerger::FirstMissingJoint() const {
  for (std::size_t i = 0; i < is_received_.size(); ++i) {
    if (IsMissing(i)) return static_cast<int>(i);
  }
  return -1;
}

std::vector<std::string> JointMerger::MissingJointsNotIn(
    const std::vector<std::string>& names) const {
  std::vector<std::string> missing;
  for (std::size_t i = 0; i < is_received_.size(); ++i) {
    if (IsMissing(i) && std::find(names.begin(), names.end(), joint_names_[i]) == names.end()) {
      missing.push_back(joint_names_[i]);
    }
  }
  return missing;
}

int JointMerger::OldestJoint() const {
  int oldest = -1;
  for (std::size_t i = 0; i < received_s_.size(); ++i) {
    if (awaiting_count_ > 0 && !is_awaiting_[i]) {
      continue;  // a joint silent since the clock went back is the one to name
    }
    if (is_received_[i] && (oldest < 0 || received_s_[i] < received_s_[oldest])) {
      oldest = static_cast<int>(i);
    }
  }
  return oldest;
}

double JointMerger::JointAge(int index, double now_s) const {
  if (!is_received_[index]) {
    return std::numeric_limits<double>::infinity();
  }
  return now_s - received_s_[index];
}

bool JointMerger::IsStale(double now_s) const {
  if (awaiting_count_ > 0) {
    return true;
  }
  const int oldest = OldestJoint();
  return oldest >= 0 && JointAge(oldest, now_s) > input_timeout_s_;
}

std::uint64_t JointMerger::refused_with(MergeStatus status) const {
  const int i = static_cast<int>(status);
  return i < kSafetyStatusCount ? refused_by_status_[i] : 0;  // kNoPositions is no refusal
}

}  // namespace arm_collision_monitor
