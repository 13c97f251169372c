// The node's diagnostics (diagnostic_updater tasks, published on /diagnostics once a second):
// the input (rates, refusals by kind, unknown and mimic joint names, message ages, staleness),
// the cycle (times, broad phase) and the safety state (the stop and its reason).
#include "arm_collision_monitor/ros/monitor_node.h"

namespace arm_collision_monitor {

void MonitorNode::OnDiagnosticsTimer(const ros::WallTimerEvent&) { updater_.update(); }

void MonitorNode::DiagnoseInput(diagnostic_updater::DiagnosticStatusWrapper& status) {
  const ros::WallTime wall_now = ros::WallTime::now();
  const double elapsed_s = (wall_now - diag_time_).toSec();
  const double rate_hz = elapsed_s > 0.0 ? (messages_ - diag_messages_) / elapsed_s : 0.0;
  const std::uint64_t refused = RefusedInputs();
  const std::uint64_t refused_recently = refused - diag_refused_;
  diag_time_ = wall_now;
  diag_messages_ = messages_;
  diag_refused_ = refused;
  const double now_s = ClockNow().toSec();
  const int oldest = input_->OldestJoint();
  const double oldest_age_s = oldest >= 0 ? input_->JointAge(oldest, now_s) : 0.0;
  if (!input_->is_complete()) {
    status.summaryf(diagnostic_msgs::DiagnosticStatus::ERROR,
                    "%d joint(s) never received, the first '%s'", input_->missing_count(),
                    input_->joint_name(input_->FirstMissingJoint()).c_str());
  } else if (input_->IsStale(now_s)) {
    status.summaryf(diagnostic_msgs::DiagnosticStatus::ERROR, "stale: '%s' %.3f s old",
                    input_->joint_name(oldest).c_str(), oldest_age_s);
  } else if (refused_recently > 0) {
    status.summaryf(diagnostic_msgs::DiagnosticStatus::WARN, "%lu message(s) refused",
                    static_cast<unsigned long>(refused_recently));
  } else {
    status.summary(diagnostic_msgs::DiagnosticStatus::OK, "ok");
  }
  std::string topics;
  for (const std::string& topic : options_.input_topics) {
    topics += (topics.empty() ? "" : ", ") + nh_.resolveName(topic);
  }
  status.add("topics", topics);
  status.addf("message rate (Hz)", "%.1f", rate_hz);
  status.add("messages", messages_);
  status.add("refused (total)", refused);
  // Out of limits is the Monitor's refusal (it owns the limits); the others are the merger's.
  for (const MergeStatus code : {MergeStatus::kWrongSize, MergeStatus::kNonFinite}) {
    status.add(std::string("refused: ") + MergeStatusName(code), input_->refused_with(code));
  }
  status.add("refused: out_of_limits", monitor_->refused_inputs());
  for (const MergeStatus code : {MergeStatus::kStale, MergeStatus::kStampBackwards,
                                 MergeStatus::kNoKnownJoints, MergeStatus::kFutureStamp}) {
    status.add(std::string("refused: ") + MergeStatusName(code), input_->refused_with(code));
  }
  status.add("unknown joint names (total)", input_->total_unknown_joints());
  status.add("mimic joint names, ignored (total)", input_->total_mimic_joints());
  status.add("position-less messages (ignored)", input_->position_less());
  const TimingSummary ages_s = SummarizeTimings(input_ages_s_.samples());
  status.add("stamped messages in the age window", ages_s.count);
  status.addf("message age at arrival median (ms)", "%.3f", 1e3 * ages_s.median);
  status.addf("message age at arrival p99 (ms)", "%.3f", 1e3 * ages_s.p99);
  status.addf("message age at arrival max (ms)", "%.3f", 1e3 * ages_s.max);
  status.addf("oldest joint age (s)", "%.3f", oldest_age_s);
  status.addf("input timeout (s)", "%.3f", options_.input_timeout_s);
  status.add("stale episodes", stale_episodes_);
  status.add("tf lookup failures", tf_failures_);
  status.add("stale tf frames", stale_frames_);
}

void MonitorNode::DiagnoseCycle(diagnostic_updater::DiagnosticStatusWrapper& status) {
  const TimingSummary times_s = SummarizeTimings(cycle_times_s_.samples());
  status.summaryf(diagnostic_msgs::DiagnosticStatus::OK, "%lu cycles, mean %.1f us",
                  static_cast<unsigned long>(cycles_), 1e6 * times_s.mean);
  status.add("cycles", cycles_);
  status.add("cycle time window (cycles)", times_s.count);
  status.addf("cycle time mean (us)", "%.1f", 1e6 * times_s.mean);
  status.addf("cycle time p99 (us)", "%.1f", 1e6 * times_s.p99);
  status.addf("cycle time max (us)", "%.1f", 1e6 * times_s.max);
  status.add("broad phase", monitor_->broad_phase_name());
  status.add("re-insert fallbacks (total)", reinsert_fallbacks_);
  status.add("moves outside the world (total)", outside_world_);
  status.add("inputs refused by the monitor", monitor_->refused_inputs());
  status.addf("step motion bound, last cycle (m)", "%.4f", report_.step_motion_m);
  status.addf("step motion bound, largest (m)", "%.4f", largest_step_m_);
  status.add("swept path needed (cycles, total)", monitor_->swept_cycles());
  status.add("input jumps (total)", input_jumps_);
}

void MonitorNode::DiagnoseSafety(diagnostic_updater::DiagnosticStatusWrapper& status) {
  if (policy_.stop()) {
    status.summaryf(diagnostic_msgs::DiagnosticStatus::WARN, "stop requested: %s",
                    policy_.reason().c_str());
  } else {
    status.summary(diagnostic_msgs::DiagnosticStatus::OK, "clear");
  }
  // Reports and markers carry the fixed frame's name on the root's coordinates. Logged when it
  // changes.
  const std::string offset = FixedFrameOffset();
  if (!offset.empty()) {
    status.mergeSummaryf(diagnostic_msgs::DiagnosticStatus::ERROR, "%s", offset.c_str());
  }
  if (offset != logged_offset_) {
    if (offset.empty()) {
      ROS_INFO("arm_collision_monitor: the fixed frame '%s' is at the URDF root's pose again",
               fixed_frame_.c_str());
    } else {
      ROS_ERROR("arm_collision_monitor: %s", offset.c_str());
    }
    logged_offset_ = offset;
  }
  status.add("stop", policy_.stop() ? "true" : "false");
  status.add("warnings", report_.warnings.size());
  status.add("fixed frame", fixed_frame_);
}

}  // namespace arm_collision_monitor
