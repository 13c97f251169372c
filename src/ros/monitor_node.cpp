#include "arm_collision_monitor/ros/monitor_node.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <boost/make_shared.hpp>

#include <std_msgs/Bool.h>
#include <visualization_msgs/MarkerArray.h>

#include "arm_collision_monitor/core/load_error.h"
#include "arm_collision_monitor/monitor/monitor_startup.h"
#include "arm_collision_monitor/core/timing_summary.h"
#include "arm_collision_monitor/ros/conversions.h"
#include "arm_collision_monitor/ros/resource_fetch_ros.h"

namespace arm_collision_monitor {
namespace {

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

/// Parameter `name` into *value (kept when unset); a positive number, or zero if `allow_zero`.
template <typename T>
void ReadPositive(const ros::NodeHandle& nh, const std::string& name, bool allow_zero, T* value) {
  *value = GetParamOr(nh, name, *value);
  if (!(*value > 0 || (allow_zero && *value == 0))) {
    throw LoadError("parameter " + nh.resolveName(name) + " = " + std::to_string(*value) +
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
  if (private_nh.hasParam("input_joint_prefixes") &&
      (!private_nh.getParam("input_joint_prefixes", o.input_joint_prefixes) ||
       (!o.input_joint_prefixes.empty() &&
        o.input_joint_prefixes.size() != o.input_topics.size()))) {
    throw LoadError("parameter " + private_nh.resolveName("input_joint_prefixes") +
                    ": expected a list of one prefix per input topic (" +
                    std::to_string(o.input_topics.size()) + ", as ~input_topics), or none");
  }
  ReadPositive(private_nh, "queue_size", false, &o.queue_size);
  ReadPositive(private_nh, "cycle_rate_hz", true, &o.cycle_rate_hz);
  ReadPositive(private_nh, "input_timeout_s", false, &o.input_timeout_s);
  ReadPositive(private_nh, "frame_timeout_s", true, &o.frame_timeout_s);
  ReadPositive(private_nh, "stop_hold_s", true, &o.stop_hold_s);
  ReadPositive(private_nh, "stop_period_s", false, &o.stop_period_s);
  ReadPositive(private_nh, "marker_rate_hz", false, &o.marker_rate_hz);
  o.fixed_frame = GetParamOr(private_nh, "fixed_frame", o.fixed_frame);
  return o;
}

MonitorNode::MonitorNode(ros::NodeHandle nh, ros::NodeHandle private_nh)
    : nh_(nh), private_nh_(private_nh), options_(LoadNodeOptions(private_nh)),
      policy_(options_.stop_hold_s), updater_(nh, private_nh) {
  const MonitorStartup startup =
      LoadMonitorStartup(options_.urdf_path, options_.scene_path, options_.config_path,
                         FetchRosResource);
  const MonitorOptions& monitor_options = startup.options;
  workcell_ = startup.workcell;
  ResolveFixedFrame(monitor_options.fixed_frame);
  for (const std::string& finding : workcell_->warnings) {
    ROS_WARN("arm_collision_monitor: %s", finding.c_str());
  }
  for (const std::string& notice : workcell_->notices) {
    ROS_INFO("arm_collision_monitor: %s", notice.c_str());
  }
  monitor_ = std::make_unique<Monitor>(workcell_, monitor_options);
  primitives_ = monitor_->workcell().primitives;
  for (const std::string& notice : monitor_->startup_notices()) {
    ROS_INFO("arm_collision_monitor: %s", notice.c_str());
  }
  input_ = std::make_unique<JointMerger>(workcell_->joint_names, options_.input_timeout_s);
  input_->SetDefaults(workcell_->joint_defaults);
  input_->SetMimicJoints(workcell_->kinematics.MimicJointNames());
  markers_ = std::make_unique<MarkerBuilder>(*monitor_, fixed_frame_);
  for (const ObjectSpec& object : workcell_->objects) {
    if (!object.frame.empty()) {
      bound_objects_.push_back(BoundObject{object.name, object.frame});
    }
  }
  // Live objects given in a frame other than the fixed one are looked up in TF too, and a fixed
  // frame other than the root's name is checked against it (FixedFrameOffset).
  if (!bound_objects_.empty() || monitor_options.live_objects.capacity > 0 ||
      fixed_frame_ != workcell_->fixed_frame) {
    tf_listener_ = std::make_unique<tf2_ros::TransformListener>(tf_buffer_, nh_);
  }

  report_.header.frame_id = fixed_frame_;
  joint_state_out_.name = workcell_->joint_names;
  joint_state_out_.position.resize(workcell_->joint_names.size());

  Advertise();

  PublishStop(/*only_on_change=*/false);
  prefixed_names_.resize(options_.input_topics.size());
  for (std::size_t topic = 0; topic < options_.input_topics.size(); ++topic) {
    subscribers_.push_back(nh_.subscribe<sensor_msgs::JointState>(
        options_.input_topics[topic], options_.queue_size,
        [this, topic](const sensor_msgs::JointState::ConstPtr& msg) { OnJointState(msg, topic); },
        ros::VoidConstPtr(), ros::TransportHints().tcpNoDelay()));
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
  ROS_INFO("arm_collision_monitor: %zu joints, %zu primitives (and %zu slots for live "
           "objects), broad phase %s, frame '%s'; input from %zu topic(s), %s",
           workcell_->joint_names.size(), workcell_->primitives.size(),
           monitor_->primitive_count() - workcell_->primitives.size(),
           monitor_->broad_phase_name().c_str(), fixed_frame_.c_str(),
           options_.input_topics.size(),
           options_.cycle_rate_hz > 0.0 ? "cycles at a fixed rate" : "one cycle per message");
}

MonitorNode::~MonitorNode() = default;

void MonitorNode::Advertise() {
  report_pub_ = private_nh_.advertise<MonitorReport>("report", options_.queue_size);
  stop_pub_ = private_nh_.advertise<std_msgs::Bool>("stop", 1, /*latch=*/true);
  markers_pub_ = private_nh_.advertise<visualization_msgs::MarkerArray>("markers", 1);
  joint_states_pub_ = private_nh_.advertise<sensor_msgs::JointState>("joint_states", 1);
  services_.push_back(private_nh_.advertiseService("check", &MonitorNode::OnCheck, this));
  services_.push_back(private_nh_.advertiseService("attach", &MonitorNode::OnAttach, this));
  services_.push_back(private_nh_.advertiseService("detach", &MonitorNode::OnDetach, this));
  services_.push_back(
      private_nh_.advertiseService("set_grasp_target", &MonitorNode::OnSetGraspTarget, this));
  services_.push_back(
      private_nh_.advertiseService("add_object", &MonitorNode::OnAddObject, this));
  services_.push_back(
      private_nh_.advertiseService("move_object", &MonitorNode::OnMoveObject, this));
  services_.push_back(
      private_nh_.advertiseService("remove_object", &MonitorNode::OnRemoveObject, this));

  updater_.setHardwareID("arm_collision_monitor");
  updater_.add("Input", this, &MonitorNode::DiagnoseInput);
  updater_.add("Cycle", this, &MonitorNode::DiagnoseCycle);
  updater_.add("Safety", this, &MonitorNode::DiagnoseSafety);
  diag_time_ = ros::WallTime::now();
}

void MonitorNode::OnJointState(const sensor_msgs::JointState::ConstPtr& msg, std::size_t topic) {
  const auto start = std::chrono::steady_clock::now();
  const ros::Time now = ClockNow();
  ++messages_;
  const std::vector<std::string>* names = &msg->name;
  if (!options_.input_joint_prefixes.empty() && !options_.input_joint_prefixes[topic].empty()) {
    PrefixedNames& cache = prefixed_names_[topic];
    if (cache.names != msg->name) {
      cache.names = msg->name;
      cache.prefixed = msg->name;
      for (std::string& name : cache.prefixed) {
        name.insert(0, options_.input_joint_prefixes[topic]);
      }
    }
    names = &cache.prefixed;
  }
  const NamedPositions input{*names, msg->position, msg->header.stamp.toSec()};
  const MergeStatus status = input_->Merge(input, now.toSec());
  // Nothing to merge: no cycle (the merger counts it; DiagnoseInput reports the count).
  if (status == MergeStatus::kNoPositions) return;
  const ros::Time stamp = msg->header.stamp.isZero() ? now : msg->header.stamp;
  if (status == MergeStatus::kAccepted) {
    newest_input_stamp_ = stamp;
    // How late messages arrive (transport and the subscriber's queue): a node falling behind
    // fast input shows here first.
    if (!msg->header.stamp.isZero()) input_ages_s_.Add((now - msg->header.stamp).toSec());
  } else {
    std::string why = input_->DescribeRefusal(input, status, now.toSec());
    if (status == MergeStatus::kNoKnownJoints) why += NoKnownJointsHint(*names, topic);
    // The cycle's reason names the first refusal since the last cycle.
    if (pending_refusal_ == MergeStatus::kAccepted) {
      pending_refusal_ = status;
      pending_why_ = why;
      pending_stamp_ = stamp;
    }
    LogRefusal(input_->refused_with(status) == 1, MergeStatusName(status), why,
               &merger_refusal_logged_);
  }
  report_.unknown_joints = input_->last_unknown_joints();
  has_pending_input_ = true;
  // At a fixed rate, a later message could overwrite a reading the Monitor refuses (outside the
  // limits, which the merger passes) before the timer's cycle: its cycle runs at once instead.
  if (options_.cycle_rate_hz <= 0.0 ||
      (status == MergeStatus::kAccepted && input_->is_complete() &&
       !monitor_->DescribeRefusal(input_->q()).empty())) {
    RunCycle(start);
  }
}

std::string MonitorNode::NoKnownJointsHint(const std::vector<std::string>& names,
                                           std::size_t topic) const {
  // The first names only: a message of 200,000 junk names is looked at no longer than a few.
  constexpr std::size_t kHintedNames = 64;
  const std::vector<std::string> first(names.begin(),
                                       names.begin() + std::min(names.size(), kHintedNames));
  const std::string prefixed = PrefixedNamesHint(workcell_->joint_names, first, "the model");
  return " on " + subscribers_[topic].getTopic() + prefixed +
         (prefixed.empty() ? "" : " (give each input topic its prefix: ~input_joint_prefixes)");
}

ros::Time MonitorNode::ClockNow() {
  const ros::Time now = ros::Time::now();
  const double back_s = policy_.ObserveClock(now.toSec());
  if (back_s > 0.0) {
    ROS_WARN("arm_collision_monitor: ROS time went back by %.3f s: stop until every joint is "
             "received again", back_s);
    input_->OnTimeWentBackwards(now.toSec());
    // No input stamp until input of the new timeline is accepted.
    newest_input_stamp_ = ros::Time();
  }
  return now;
}

void MonitorNode::OnCycleTimer(const ros::TimerEvent&) {
  if (has_pending_input_) {
    RunCycle(std::chrono::steady_clock::now());
  }
}

void MonitorNode::UpdateBoundObjects(const ros::Time& now) {
  // Each object on its own: one whose frame is unavailable keeps its last pose (at first its
  // scene pose), the others still follow theirs. The stop names the first unavailable one and
  // the objects of the others. Through a fixed frame TF puts apart from the root, none is.
  const std::string offset = FixedFrameOffset();
  const BoundObject* first = nullptr;
  std::string first_error, others;
  for (BoundObject& bound : bound_objects_) {
    // A held object follows its holder link, not its frame (SetObjectPose refuses it): the
    // frame's pose is only noted, and neither it nor its absence stops. Let go, the object
    // stays where it was let go until its frame moves (a static frame never does).
    const bool is_held = monitor_->IsHeld(bound.object);
    std::string error = offset;
    if (error.empty() && PoseBoundObject(&bound, is_held, now, &error)) continue;
    if (!offset.empty()) ++tf_failures_;
    bound.is_available = false;
    if (is_held) continue;
    if (first == nullptr) {
      first = &bound;
      first_error = error;
    } else {
      others += (others.empty() ? "'" : ", '") + bound.object + "'";
    }
  }
  if (first != nullptr) {
    policy_.OnObjectPoseUnavailable(
        first->object, first->frame,
        others.empty() ? first_error : first_error + "; also unavailable: " + others);
  }
}

bool MonitorNode::PoseBoundObject(BoundObject* bound, bool is_held, const ros::Time& now,
                                  std::string* error) {
  try {
    const geometry_msgs::TransformStamped X = LookupInFixedFrame(bound->frame);
    // A broadcast frame (a static chain comes stamped 0) not sent for frame_timeout_s is
    // stale: the object may have moved since (a tracker or a conveyor's driver stopped). One
    // stamped further ahead of the node's clock cannot be dated, as JointState input. In
    // seconds: ros::Time's difference throws past 2^31 s (a stamp from a broken clock).
    const double age_s = now.toSec() - X.header.stamp.toSec();
    if (options_.frame_timeout_s > 0.0 && !X.header.stamp.isZero() &&
        std::abs(age_s) > options_.frame_timeout_s) {
      char text[160];
      std::snprintf(text, sizeof(text),
                    age_s > 0.0
                        ? "its newest transform is %.3f s old, over ~frame_timeout_s (%.3f s)"
                        : "its newest transform is stamped %.3f s ahead of the node's clock, "
                          "over ~frame_timeout_s (%.3f s)",
                    std::abs(age_s), options_.frame_timeout_s);
      ++stale_frames_;
      *error = text;
      return false;
    }
    // Its quaternion normalised (TF keeps one off unit norm by up to 0.5 %).
    Eigen::Isometry3d X_WO = Eigen::Isometry3d::Identity();
    *error = ToRigidTransform(X.transform, &X_WO);
    // Most frames (a calibrated camera) do not move: skip the index update then. A stamped
    // one (a tracker's) is posed with each new stamp, moved or not: with speed-scaled
    // tolerance, its speed spans the interval between its samples, and an unmoved sample
    // takes it to rest; now stamped 0, it is posed untimed again. Let go, the object waits
    // for its frame's pose to move, whatever the stamps.
    const bool is_stamped = !X.header.stamp.isZero();
    const double stamp_s = X.header.stamp.toSec();
    bound->is_let_go |= is_held;
    const bool is_same = bound->has_pose && X_WO.matrix() == bound->X_WO.matrix() &&
                         (stamp_s == bound->stamp_s || bound->is_let_go);
    if (error->empty() &&
        (is_held || is_same ||
         (is_stamped ? monitor_->SetObjectPoseAt(bound->object, X_WO, stamp_s, error)
                     : monitor_->SetObjectPose(bound->object, X_WO, error)))) {
      bound->is_let_go = bound->is_let_go && (is_held || is_same);
      bound->X_WO = X_WO;
      bound->stamp_s = stamp_s;
      bound->has_pose = true;
      bound->is_available = true;
      return true;
    }
  } catch (const tf2::TransformException& e) {
    *error = e.what();
  }
  ++tf_failures_;
  return false;
}

void MonitorNode::RunCycle(std::chrono::steady_clock::time_point start) {
  const ros::Time now = ClockNow();
  const bool was_stop = policy_.stop();
  ++cycles_;
  const MergeStatus pending = pending_refusal_;
  pending_refusal_ = MergeStatus::kAccepted;
  has_pending_input_ = false;
  report_.moved_primitives = 0;
  report_.reinsert_fallbacks = 0;
  report_.step_motion_m = 0.0;
  report_.input_jumped = false;
  report_.swept_pairs = 0;
  if (policy_.BeginCycle(pending, pending_why_, *input_)) {
    UpdateBoundObjects(now);
    // Each joint dated by the message that gave it (per-arm topics sample the arms apart).
    const std::vector<double>& stamps = input_->joint_stamps();
    const CycleReport& cycle = monitor_->Update(
        input_->q(), Eigen::Map<const Eigen::VectorXd>(stamps.data(),
                                                       static_cast<Eigen::Index>(stamps.size())));
    if (cycle.input == InputStatus::kOk) {
      FillReportWarnings(cycle, &report_);
      report_.moved_primitives = cycle.moved_primitives;
      report_.reinsert_fallbacks = static_cast<std::uint32_t>(cycle.counters.reinsert_fallbacks);
      reinsert_fallbacks_ += cycle.counters.reinsert_fallbacks;
      outside_world_ += cycle.counters.outside_world;
      report_.step_motion_m = cycle.step_motion_m;
      report_.input_jumped = cycle.input_jumped;
      report_.swept_pairs = cycle.swept_pairs;
      largest_step_m_ = std::max(largest_step_m_, cycle.step_motion_m);
      input_jumps_ += cycle.input_jumped ? 1 : 0;
    }
    const std::string refusal =
        cycle.input == InputStatus::kOk ? std::string() : monitor_->DescribeRefusal(input_->q());
    if (!refusal.empty()) {
      // What the merger passes and the monitor refuses: positions outside the joint limits.
      LogRefusal(monitor_->refused_inputs() == 1, SafetyStatusName(ToSafetyStatus(cycle.input)),
                 refusal, &monitor_refusal_logged_);
    }
    policy_.OnCycleReport(cycle, refusal, primitives_, *input_, now.toSec());
  }
  policy_.EndCycle(now.toSec());
  // The refused message's stamp with its refusal (the first since the last cycle, which the
  // report gives), else the newest accepted one's.
  report_.header.stamp = pending != MergeStatus::kAccepted ? pending_stamp_ : newest_input_stamp_;
  report_.cycle = cycles_;
  report_.input_status = ToInputStatusMsg(policy_.status());
  TakeStopDecision(was_stop);
  report_.refused_inputs = RefusedInputs();
  const double cycle_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  report_.cycle_time_s = cycle_time_s;
  cycle_times_s_.Add(cycle_time_s);
  PublishReport();
  PublishStop(/*only_on_change=*/true);
  PublishVisualisation();
}

void MonitorNode::TakeStopDecision(bool was_stop) {
  report_.stop = policy_.stop();
  report_.stop_reason = policy_.reason();
  if (policy_.stop() != was_stop) {
    if (policy_.stop()) {
      ROS_WARN("arm_collision_monitor: stop requested: %s", policy_.reason().c_str());
    } else {
      ROS_INFO("arm_collision_monitor: stop cleared");
    }
  }
}

std::uint64_t MonitorNode::RefusedInputs() const {
  return input_->refused() + monitor_->refused_inputs();
}

void MonitorNode::LogRefusal(bool is_first, const char* kind, const std::string& why,
                             ros::WallTime* last_logged) const {
  const ros::WallTime now = ros::WallTime::now();
  if (!is_first && (now - *last_logged).toSec() < 1.0) return;
  *last_logged = now;
  ROS_WARN("arm_collision_monitor: refused a JointState (%s%s%s), %lu so far", kind,
           why.empty() ? "" : ": ", why.c_str(), static_cast<unsigned long>(RefusedInputs()));
}

void MonitorNode::OnStalenessTimer(const ros::TimerEvent&) {
  const ros::Time now = ClockNow();
  const bool was_stop = policy_.stop();
  const StaleCheck check = policy_.CheckStaleness(*input_, now.toSec());
  if (!check.is_stale) {
    return;
  }
  TakeStopDecision(was_stop);
  PublishStop(/*only_on_change=*/true);
  if (check.is_new_episode) {
    // One report per stale episode (no cycle ran: the cycle number stays).
    ++stale_episodes_;
    report_.input_status = ToInputStatusMsg(policy_.status());
    report_.cycle_time_s = 0.0;
    PublishReport();
  }
}

void MonitorNode::PublishReport() {
  for (const boost::shared_ptr<MonitorReport>& msg : report_pool_) {
    if (msg.use_count() == 1) {  // only the pool holds it: nobody can be reading it
      *msg = report_;            // reuses the copy's capacity
      report_pub_.publish(msg);
      return;
    }
  }
  report_pool_.push_back(boost::make_shared<MonitorReport>(report_));
  report_pub_.publish(report_pool_.back());
}

void MonitorNode::PublishStop(bool only_on_change) {
  if (only_on_change && policy_.stop() == published_stop_) {
    return;
  }
  std_msgs::Bool msg;
  msg.data = policy_.stop();
  stop_pub_.publish(msg);
  published_stop_ = policy_.stop();
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
    markers_pub_.publish(markers_->Build(ros::Time(0)));
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
    ToWarningMsg(primitives_, report.warnings[i], &msg->warnings[i]);
  }
}

}  // namespace arm_collision_monitor
