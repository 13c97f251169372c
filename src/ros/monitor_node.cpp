#include "arm_collision_monitor/ros/monitor_node.h"

#include <algorithm>
#include <cstdarg>
#include <cstdio>
#include <numeric>
#include <unordered_set>

#include <std_msgs/Bool.h>
#include <tf2_eigen/tf2_eigen.h>
#include <visualization_msgs/MarkerArray.h>

#include "arm_collision_monitor/core/load_error.h"
#include "arm_collision_monitor/ros/conversions.h"

namespace arm_collision_monitor {
namespace {

// Cycle times kept for the diagnostics' statistics (about 1 s at 1 kHz, 50 s at 20 Hz).
constexpr std::size_t kCycleTimeWindow = 1024;
// The staleness timer runs this many times per input timeout, so a stale input is noticed at
// most timeout * (1 + 1/kStalenessChecksPerTimeout) after the last message.
constexpr double kStalenessChecksPerTimeout = 4.0;
// Diagnostics: the updater publishes at its own ~diagnostic_period (1 s by default); this is
// how often it is asked.
constexpr double kDiagnosticsPollPeriod_s = 0.25;

template <typename T>
T GetParamOr(const ros::NodeHandle& nh, const std::string& name, const T& fallback) {
  T value = fallback;
  nh.param(name, value, fallback);
  return value;
}

void RequirePositive(const ros::NodeHandle& nh, const std::string& name, double value,
                     bool allow_zero) {
  if (!(value > 0.0 || (allow_zero && value == 0.0))) {
    throw LoadError("parameter " + nh.resolveName(name) + " = " + std::to_string(value) +
                    ": expected a " + (allow_zero ? "non-negative" : "positive") + " number");
  }
}

}  // namespace

NodeOptions LoadNodeOptions(const ros::NodeHandle& private_nh) {
  NodeOptions o;
  for (auto [name, path] : {std::pair<const char*, std::string*>{"urdf", &o.urdf_path},
                            {"scene", &o.scene_path},
                            {"config", &o.config_path}}) {
    if (!private_nh.getParam(name, *path) || path->empty()) {
      throw LoadError("parameter " + private_nh.resolveName(name) +
                      " not set: expected the path of the " + name + " file");
    }
  }
  if (private_nh.hasParam("input_topics")) {
    std::string single_topic;
    if (private_nh.getParam("input_topics", single_topic)) {
      o.input_topics = {single_topic};
    } else if (!private_nh.getParam("input_topics", o.input_topics)) {
      throw LoadError("parameter " + private_nh.resolveName("input_topics") +
                      ": expected a topic name or a list of topic names");
    }
  }
  if (o.input_topics.empty() ||
      std::any_of(o.input_topics.begin(), o.input_topics.end(),
                  [](const std::string& t) { return t.empty(); })) {
    throw LoadError("parameter " + private_nh.resolveName("input_topics") +
                    ": expected at least one non-empty topic name");
  }
  o.queue_size = GetParamOr(private_nh, "queue_size", o.queue_size);
  RequirePositive(private_nh, "queue_size", o.queue_size, false);
  o.cycle_rate_hz = GetParamOr(private_nh, "cycle_rate_hz", o.cycle_rate_hz);
  RequirePositive(private_nh, "cycle_rate_hz", o.cycle_rate_hz, true);
  o.input_timeout_s = GetParamOr(private_nh, "input_timeout_s", o.input_timeout_s);
  RequirePositive(private_nh, "input_timeout_s", o.input_timeout_s, false);
  o.stop_hold_s = GetParamOr(private_nh, "stop_hold_s", o.stop_hold_s);
  RequirePositive(private_nh, "stop_hold_s", o.stop_hold_s, true);
  o.stop_period_s = GetParamOr(private_nh, "stop_period_s", o.stop_period_s);
  RequirePositive(private_nh, "stop_period_s", o.stop_period_s, false);
  o.marker_rate_hz = GetParamOr(private_nh, "marker_rate_hz", o.marker_rate_hz);
  RequirePositive(private_nh, "marker_rate_hz", o.marker_rate_hz, false);
  o.fixed_frame = GetParamOr(private_nh, "fixed_frame", o.fixed_frame);
  return o;
}

MonitorNode::MonitorNode(ros::NodeHandle nh, ros::NodeHandle private_nh)
    : nh_(nh), private_nh_(private_nh), options_(LoadNodeOptions(private_nh)),
      updater_(nh, private_nh) {
  const MonitorOptions monitor_options = LoadMonitorOptions(options_.config_path);
  workcell_ = std::make_shared<const Workcell>(
      LoadWorkcell(options_.urdf_path, options_.scene_path, monitor_options.tolerance_m));
  for (const std::string& finding : workcell_->warnings) {
    ROS_WARN("arm_collision_monitor: %s", finding.c_str());
  }
  monitor_ = std::make_unique<Monitor>(workcell_, monitor_options);
  fixed_frame_ =
      options_.fixed_frame.empty() ? monitor_options.fixed_frame : options_.fixed_frame;
  input_ = std::make_unique<JointStateInput>(workcell_->joint_names, options_.input_timeout_s);
  markers_ = std::make_unique<MarkerBuilder>(*monitor_, fixed_frame_);
  for (const ObjectSpec& object : workcell_->objects) {
    if (!object.frame.empty()) {
      bound_objects_.push_back(BoundObject{object.name, object.frame});
    }
  }
  if (!bound_objects_.empty()) {
    tf_listener_ = std::make_unique<tf2_ros::TransformListener>(tf_buffer_, nh_);
  }

  report_.header.frame_id = fixed_frame_;
  cycle_times_s_.reserve(kCycleTimeWindow);
  joint_state_out_.name = workcell_->joint_names;
  joint_state_out_.position.resize(workcell_->joint_names.size());
  condition_.reserve(256);
  stop_reason_.reserve(256);
  stop_reason_ = "waiting for joint states";

  report_pub_ = private_nh_.advertise<MonitorReport>("report", options_.queue_size);
  stop_pub_ = private_nh_.advertise<std_msgs::Bool>("stop", 1, /*latch=*/true);
  markers_pub_ = private_nh_.advertise<visualization_msgs::MarkerArray>("markers", 1);
  joint_states_pub_ = private_nh_.advertise<sensor_msgs::JointState>("joint_states", 1);
  services_.push_back(private_nh_.advertiseService("check", &MonitorNode::OnCheck, this));
  services_.push_back(private_nh_.advertiseService("attach", &MonitorNode::OnAttach, this));
  services_.push_back(private_nh_.advertiseService("detach", &MonitorNode::OnDetach, this));
  services_.push_back(
      private_nh_.advertiseService("set_grasp_target", &MonitorNode::OnSetGraspTarget, this));

  updater_.setHardwareID("arm_collision_monitor");
  updater_.add("Input", this, &MonitorNode::DiagnoseInput);
  updater_.add("Cycle", this, &MonitorNode::DiagnoseCycle);
  updater_.add("Safety", this, &MonitorNode::DiagnoseSafety);
  diag_time_ = ros::WallTime::now();

  PublishStop(/*only_on_change=*/false);
  for (const std::string& topic : options_.input_topics) {
    subscribers_.push_back(nh_.subscribe(topic, options_.queue_size, &MonitorNode::OnJointState,
                                         this, ros::TransportHints().tcpNoDelay()));
  }
  if (options_.cycle_rate_hz > 0.0) {
    cycle_timer_ = nh_.createTimer(ros::Duration(1.0 / options_.cycle_rate_hz),
                                   &MonitorNode::OnCycleTimer, this);
  }
  staleness_timer_ =
      nh_.createTimer(ros::Duration(options_.input_timeout_s / kStalenessChecksPerTimeout),
                      &MonitorNode::OnStalenessTimer, this);
  stop_timer_ =
      nh_.createTimer(ros::Duration(options_.stop_period_s), &MonitorNode::OnStopTimer, this);
  diagnostics_timer_ = nh_.createWallTimer(ros::WallDuration(kDiagnosticsPollPeriod_s),
                                           &MonitorNode::OnDiagnosticsTimer, this);
  ROS_INFO("arm_collision_monitor: %zu joints, %u primitives, broad phase %s, frame '%s'; "
           "input from %zu topic(s), %s",
           workcell_->joint_names.size(), monitor_->primitive_count(),
           monitor_->broad_phase_name().c_str(), fixed_frame_.c_str(),
           options_.input_topics.size(),
           options_.cycle_rate_hz > 0.0 ? "cycles at a fixed rate" : "one cycle per message");
}

MonitorNode::~MonitorNode() = default;

void MonitorNode::SetCondition(const char* format, ...) {
  char text[256];
  va_list args;
  va_start(args, format);
  std::vsnprintf(text, sizeof(text), format, args);
  va_end(args);
  condition_.assign(text);
}

void MonitorNode::OnJointState(const sensor_msgs::JointState::ConstPtr& msg) {
  const auto start = std::chrono::steady_clock::now();
  const ros::Time now = ClockNow();
  ++messages_;
  const MergeStatus status = input_->Merge(*msg, now);
  if (status == MergeStatus::kAccepted) {
    newest_input_stamp_ = msg->header.stamp.isZero() ? now : msg->header.stamp;
  } else {
    const std::uint8_t code = ToInputStatusMsg(status);
    ++refused_;
    ++refused_by_status_[code];
    if (pending_status_ == MonitorReport::INPUT_OK) {
      pending_status_ = code;
    }
    ROS_WARN_THROTTLE(1.0, "arm_collision_monitor: refused a JointState (%s), %lu so far",
                      MergeStatusName(status), static_cast<unsigned long>(refused_));
  }
  report_.unknown_joints = input_->last_unknown_joints();
  has_pending_input_ = true;
  if (options_.cycle_rate_hz <= 0.0) {
    RunCycle(start);
  }
}

ros::Time MonitorNode::ClockNow() {
  const ros::Time now = ros::Time::now();
  if (now < last_now_) {
    OnTimeWentBackwards(now);
  }
  last_now_ = now;
  return now;
}

void MonitorNode::OnTimeWentBackwards(const ros::Time& now) {
  ROS_WARN("arm_collision_monitor: ROS time went back by %.3f s: stop until every joint is "
           "received again", last_now_.toSec() - now.toSec());
  input_->OnTimeWentBackwards(now);
  // A deadline or stamp from the old timeline would lie in the future: hold from the jump, and
  // report no input stamp until input of the new timeline is accepted.
  stop_hold_until_ = now;
  newest_input_stamp_ = ros::Time();
}

void MonitorNode::OnCycleTimer(const ros::TimerEvent&) {
  if (has_pending_input_) {
    RunCycle(std::chrono::steady_clock::now());
  }
}

bool MonitorNode::UpdateBoundObjects() {
  for (BoundObject& bound : bound_objects_) {
    std::string error;
    try {
      const Eigen::Isometry3d X_WO = tf2::transformToEigen(
          tf_buffer_.lookupTransform(fixed_frame_, bound.frame, ros::Time(0)));
      // Most frames (a calibrated camera) do not move: skip the index update then.
      if ((bound.has_pose && X_WO.matrix() == bound.X_WO.matrix()) ||
          monitor_->SetObjectPose(bound.object, X_WO, &error)) {
        bound.X_WO = X_WO;
        bound.has_pose = true;
        continue;
      }
    } catch (const tf2::TransformException& e) {
      error = e.what();
    }
    ++tf_failures_;
    SetCondition("object '%s': pose from frame '%s' unavailable: %s", bound.object.c_str(),
                 bound.frame.c_str(), error.c_str());
    return false;
  }
  return true;
}

void MonitorNode::RunCycle(std::chrono::steady_clock::time_point start) {
  const ros::Time now = ClockNow();
  ++cycles_;
  std::uint8_t status = pending_status_;
  pending_status_ = MonitorReport::INPUT_OK;
  has_pending_input_ = false;
  condition_.clear();
  report_.moved_primitives = 0;
  report_.reinsert_fallbacks = 0;
  if (status != MonitorReport::INPUT_OK) {
    SetCondition("input refused: %s", InputStatusMsgName(status));
  } else if (!input_->is_complete()) {
    status = MonitorReport::INPUT_INCOMPLETE;
    SetCondition("joint '%s' never received",
                 input_->joint_name(input_->FirstMissingJoint()).c_str());
  } else {
    const bool is_tf_ok = UpdateBoundObjects();
    const CycleReport& cycle = monitor_->Update(input_->q());
    if (cycle.input != InputStatus::kOk) {
      status = ToInputStatusMsg(cycle.input);
      ++refused_;
      ++refused_by_status_[status];
      SetCondition("input refused: %s", InputStatusMsgName(status));
    } else {
      FillReportWarnings(cycle, &report_);
      report_.moved_primitives = cycle.moved_primitives;
      report_.reinsert_fallbacks = static_cast<std::uint32_t>(cycle.counters.reinsert_fallbacks);
      reinsert_fallbacks_ += cycle.counters.reinsert_fallbacks;
      outside_world_ += cycle.counters.outside_world;
      if (input_->IsStale(now)) {
        status = MonitorReport::INPUT_STALE;
        SetStaleCondition(now);
      } else if (is_tf_ok && !report_.warnings.empty()) {
        const CollisionWarning& w = report_.warnings.front();
        SetCondition("%zu warning(s), e.g. %s - %s at %.3f m", report_.warnings.size(),
                     w.primitive_a_name.c_str(), w.primitive_b_name.c_str(), w.distance_m);
      }
    }
  }
  report_.header.stamp = newest_input_stamp_;
  report_.cycle = cycles_;
  report_.input_status = status;
  ApplyStopPolicy(now);
  report_.refused_inputs = refused_;
  const double cycle_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  report_.cycle_time_s = cycle_time_s;
  if (cycle_times_s_.size() < kCycleTimeWindow) {
    cycle_times_s_.push_back(cycle_time_s);
  } else {
    cycle_times_s_[cycle_time_next_] = cycle_time_s;
    cycle_time_next_ = (cycle_time_next_ + 1) % kCycleTimeWindow;
  }
  report_pub_.publish(report_);
  PublishStop(/*only_on_change=*/true);
  PublishVisualisation();
}

void MonitorNode::ApplyStopPolicy(const ros::Time& now) {
  const bool was_stop = stop_;
  if (!condition_.empty()) {
    stop_ = true;
    stop_reason_.assign(condition_);
    stop_hold_until_ = ros::Time(now.toSec() + options_.stop_hold_s);
  } else if (stop_ && now >= stop_hold_until_) {
    stop_ = false;
    stop_reason_.clear();
  }
  report_.stop = stop_;
  report_.stop_reason = stop_reason_;
  if (stop_ != was_stop) {
    if (stop_) {
      ROS_WARN("arm_collision_monitor: stop requested: %s", stop_reason_.c_str());
    } else {
      ROS_INFO("arm_collision_monitor: stop cleared");
    }
  }
}

void MonitorNode::SetStaleCondition(const ros::Time& now) {
  const int oldest = input_->OldestJoint();
  SetCondition(input_->IsAwaitingInput(oldest)
                   ? "joint '%s' not received since the ROS clock went back %.3f s ago"
                   : "joint '%s' not received for %.3f s",
               input_->joint_name(oldest).c_str(), input_->JointAge(oldest, now));
}

void MonitorNode::OnStalenessTimer(const ros::TimerEvent&) {
  const ros::Time now = ClockNow();
  if (!input_->is_complete() || !input_->IsStale(now)) {
    is_stale_reported_ = false;
    return;
  }
  SetStaleCondition(now);
  ApplyStopPolicy(now);
  PublishStop(/*only_on_change=*/true);
  if (!is_stale_reported_) {
    // One report per stale episode (no cycle ran: the cycle number stays).
    is_stale_reported_ = true;
    ++stale_episodes_;
    report_.input_status = MonitorReport::INPUT_STALE;
    report_.cycle_time_s = 0.0;
    report_pub_.publish(report_);
  }
}

void MonitorNode::PublishStop(bool only_on_change) {
  if (only_on_change && stop_ == published_stop_) {
    return;
  }
  std_msgs::Bool msg;
  msg.data = stop_;
  stop_pub_.publish(msg);
  published_stop_ = stop_;
}

void MonitorNode::OnStopTimer(const ros::TimerEvent&) { PublishStop(/*only_on_change=*/false); }

void MonitorNode::PublishVisualisation() {
  const ros::WallTime now = ros::WallTime::now();
  if ((now - last_visualisation_).toSec() < 1.0 / options_.marker_rate_hz) {
    return;
  }
  bool is_published = false;
  if (markers_pub_.getNumSubscribers() > 0) {
    monitor_->SyncShapes();  // the markers read shape_W: at the last good q
    // Stamp 0: rviz draws with the latest transform of the fixed frame.
    markers_pub_.publish(markers_->Build(report_.warnings, ros::Time(0)));
    is_published = true;
  }
  if (joint_states_pub_.getNumSubscribers() > 0 && input_->is_complete()) {
    joint_state_out_.header.stamp = newest_input_stamp_;
    for (int i = 0; i < input_->joint_count(); ++i) {
      joint_state_out_.position[i] = input_->q()[i];
    }
    joint_states_pub_.publish(joint_state_out_);
    is_published = true;
  }
  if (is_published) {
    last_visualisation_ = now;
  }
}

void MonitorNode::FillReportWarnings(const CycleReport& report, MonitorReport* msg) const {
  msg->warnings.resize(report.warnings.size());
  for (std::size_t i = 0; i < report.warnings.size(); ++i) {
    ToWarningMsg(*workcell_, report.warnings[i], &msg->warnings[i]);
  }
}

bool MonitorNode::OnCheck(CheckJointState::Request& req, CheckJointState::Response& res) {
  Eigen::VectorXd q;
  const MergeStatus status = input_->MergeIntoCopy(req.joint_state, &q);
  res.report.header.frame_id = fixed_frame_;
  res.report.header.stamp = req.joint_state.header.stamp;
  if (status != MergeStatus::kAccepted) {
    res.success = false;
    res.report.input_status = ToInputStatusMsg(status);
    res.report.stop = true;
    res.message = std::string("joint state refused: ") + MergeStatusName(status);
    return true;
  }
  const std::unordered_set<std::string> requested(req.joint_state.name.begin(),
                                                  req.joint_state.name.end());
  const ros::Time now = ClockNow();
  for (int i = 0; i < input_->joint_count(); ++i) {
    if (std::isinf(input_->JointAge(i, now)) && requested.count(input_->joint_name(i)) == 0) {
      res.success = false;
      res.report.input_status = MonitorReport::INPUT_INCOMPLETE;
      res.report.stop = true;
      res.message = "joint '" + input_->joint_name(i) +
                    "' was never received and is not in the request";
      return true;
    }
  }
  const CycleReport report = monitor_->Check(q);
  res.report.input_status = ToInputStatusMsg(report.input);
  res.report.stop = report.stop;
  res.report.moved_primitives = report.moved_primitives;
  res.report.reinsert_fallbacks = static_cast<std::uint32_t>(report.counters.reinsert_fallbacks);
  FillReportWarnings(report, &res.report);
  res.success = report.input == InputStatus::kOk;
  res.message = res.success ? std::to_string(report.warnings.size()) + " warning(s)"
                            : std::string("joint state refused: ") +
                                  InputStatusMsgName(res.report.input_status);
  return true;
}

bool MonitorNode::OnAttach(AttachObject::Request& req, AttachObject::Response& res) {
  res.success = monitor_->Attach(req.object, req.link, &res.message);
  if (res.success) {
    res.message = "attached '" + req.object + "' to '" + req.link + "'";
  }
  return true;
}

bool MonitorNode::OnDetach(DetachObject::Request& req, DetachObject::Response& res) {
  res.success = monitor_->Detach(req.object, &res.message);
  if (res.success) {
    res.message = "detached '" + req.object + "'";
  }
  return true;
}

bool MonitorNode::OnSetGraspTarget(SetGraspTarget::Request& req,
                                   SetGraspTarget::Response& res) {
  res.success = monitor_->SetGraspTarget(req.link, req.object, req.is_target, &res.message);
  if (res.success) {
    res.message = std::string(req.is_target ? "set" : "cleared") + " grasp target '" +
                  req.object + "' of '" + req.link + "'";
  }
  return true;
}

void MonitorNode::OnDiagnosticsTimer(const ros::WallTimerEvent&) { updater_.update(); }

void MonitorNode::DiagnoseInput(diagnostic_updater::DiagnosticStatusWrapper& status) {
  const ros::WallTime wall_now = ros::WallTime::now();
  const double elapsed_s = (wall_now - diag_time_).toSec();
  const double rate_hz = elapsed_s > 0.0 ? (messages_ - diag_messages_) / elapsed_s : 0.0;
  const std::uint64_t refused_recently = refused_ - diag_refused_;
  diag_time_ = wall_now;
  diag_messages_ = messages_;
  diag_refused_ = refused_;
  const ros::Time now = ClockNow();
  const int oldest = input_->OldestJoint();
  const double oldest_age_s = oldest >= 0 ? input_->JointAge(oldest, now) : 0.0;
  if (!input_->is_complete()) {
    status.summaryf(diagnostic_msgs::DiagnosticStatus::ERROR, "joint '%s' never received",
                    input_->joint_name(input_->FirstMissingJoint()).c_str());
  } else if (input_->IsStale(now)) {
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
  status.add("refused (total)", refused_);
  for (std::uint8_t code = MonitorReport::INPUT_WRONG_SIZE;
       code <= MonitorReport::INPUT_FUTURE_STAMP; ++code) {
    if (code != MonitorReport::INPUT_INCOMPLETE && code != MonitorReport::INPUT_STALE) {
      status.add(std::string("refused: ") + InputStatusMsgName(code), refused_by_status_[code]);
    }
  }
  status.add("unknown joint names (total)", input_->total_unknown_joints());
  status.addf("oldest joint age (s)", "%.3f", oldest_age_s);
  status.addf("input timeout (s)", "%.3f", options_.input_timeout_s);
  status.add("stale episodes", stale_episodes_);
  status.add("tf lookup failures", tf_failures_);
}

void MonitorNode::DiagnoseCycle(diagnostic_updater::DiagnosticStatusWrapper& status) {
  std::vector<double> times_s = cycle_times_s_;
  double mean_s = 0.0, p99_s = 0.0, max_s = 0.0;
  if (!times_s.empty()) {
    mean_s = std::accumulate(times_s.begin(), times_s.end(), 0.0) / times_s.size();
    max_s = *std::max_element(times_s.begin(), times_s.end());
    const std::size_t k = (times_s.size() * 99) / 100;
    std::nth_element(times_s.begin(), times_s.begin() + k, times_s.end());
    p99_s = times_s[k];
  }
  status.summaryf(diagnostic_msgs::DiagnosticStatus::OK, "%lu cycles, mean %.1f us",
                  static_cast<unsigned long>(cycles_), 1e6 * mean_s);
  status.add("cycles", cycles_);
  status.add("cycle time window (cycles)", times_s.size());
  status.addf("cycle time mean (us)", "%.1f", 1e6 * mean_s);
  status.addf("cycle time p99 (us)", "%.1f", 1e6 * p99_s);
  status.addf("cycle time max (us)", "%.1f", 1e6 * max_s);
  status.add("broad phase", monitor_->broad_phase_name());
  status.add("re-insert fallbacks (total)", reinsert_fallbacks_);
  status.add("moves outside the world (total)", outside_world_);
  status.add("inputs refused by the monitor", monitor_->refused_inputs());
}

void MonitorNode::DiagnoseSafety(diagnostic_updater::DiagnosticStatusWrapper& status) {
  if (stop_) {
    status.summaryf(diagnostic_msgs::DiagnosticStatus::WARN, "stop requested: %s",
                    stop_reason_.c_str());
  } else {
    status.summary(diagnostic_msgs::DiagnosticStatus::OK, "clear");
  }
  status.add("stop", stop_ ? "true" : "false");
  status.add("warnings", report_.warnings.size());
  status.add("fixed frame", fixed_frame_);
}

}  // namespace arm_collision_monitor
