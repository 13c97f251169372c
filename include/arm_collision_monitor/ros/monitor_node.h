// The monitor's ROS node: parameters, JointState subscriptions, the per-message (or fixed-rate)
// cycle, the report / stop / marker / diagnostics publishers and the services. It translates
// only; everything computed or decided lives in the ROS-free core (Monitor, JointMerger,
// StopPolicy).
//
// The stop policy itself (README "Stop policy") is the ROS-free StopPolicy
// (safety/stop_policy.h); joint merging by name is the ROS-free JointMerger
// (safety/joint_merger.h). The node feeds them ROS time in seconds and publishes their decision.
#pragma once

#include <chrono>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <diagnostic_updater/diagnostic_updater.h>
#include <ros/ros.h>
#include <sensor_msgs/JointState.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>

#include "arm_collision_monitor/AddObject.h"
#include "arm_collision_monitor/AttachObject.h"
#include "arm_collision_monitor/CheckJointState.h"
#include "arm_collision_monitor/DetachObject.h"
#include "arm_collision_monitor/MonitorReport.h"
#include "arm_collision_monitor/MoveObject.h"
#include "arm_collision_monitor/RemoveObject.h"
#include "arm_collision_monitor/SetGraspTarget.h"
#include "arm_collision_monitor/core/constants.h"
#include "arm_collision_monitor/core/timing_summary.h"
#include "arm_collision_monitor/monitor/monitor.h"
#include "arm_collision_monitor/ros/marker_builder.h"
#include "arm_collision_monitor/safety/joint_merger.h"
#include "arm_collision_monitor/safety/stop_policy.h"

namespace arm_collision_monitor {

/// The node's parameters (all private, ~name), with their defaults.
struct NodeOptions {
  std::string urdf_path;    ///< ~urdf (required)
  std::string scene_path;   ///< ~scene (required)
  std::string config_path;  ///< ~config: Monitor options YAML (required)
  /// ~input_topics: JointState topics merged by joint name (one per arm, or one combined).
  std::vector<std::string> input_topics{"left_arm/joint_states", "right_arm/joint_states"};
  /// ~input_joint_prefixes: per input topic, put in front of its joint names (drivers of alike
  /// arms that publish the same names, one topic each); empty: none.
  std::vector<std::string> input_joint_prefixes;
  int queue_size = 100;            ///< ~queue_size per input topic (1 kHz input: ~0.1 s)
  /// ~cycle_rate_hz: 0 = one cycle per message; else cycles at this rate on the newest input,
  /// and at once on a message whose reading the Monitor refuses (outside the joint limits)
  double cycle_rate_hz = 0.0;
  double input_timeout_s = kDefaultInputTimeout_s;  ///< ~input_timeout_s: staleness bound
  /// ~frame_timeout_s: a frame-bound object's TF frame whose newest transform is older, or
  /// stamped further ahead of the node's clock, is stale (a static frame never is); 0 = never
  double frame_timeout_s = 0.5;
  double stop_hold_s = 0.25;       ///< ~stop_hold_s: minimum duration of a requested stop
  double stop_period_s = 0.1;      ///< ~stop_period_s: ~stop is re-published this often
  double marker_rate_hz = 10.0;    ///< ~marker_rate_hz: bound on ~markers and ~joint_states
  std::string fixed_frame;         ///< ~fixed_frame: "" = fixed_frame of the ~config file
};

/// Reads and validates the parameters. Throws LoadError naming the parameter.
NodeOptions LoadNodeOptions(const ros::NodeHandle& private_nh);

class MonitorNode {
 public:
  /// Loads the workcell and options (throws LoadError naming the file or parameter), then
  /// subscribes, advertises and starts the timers.
  MonitorNode(ros::NodeHandle nh, ros::NodeHandle private_nh);
  ~MonitorNode();

 private:
  // A message of input topic `topic` (its index in NodeOptions::input_topics).
  void OnJointState(const sensor_msgs::JointState::ConstPtr& msg, std::size_t topic);
  void OnCycleTimer(const ros::TimerEvent& event);
  void OnStalenessTimer(const ros::TimerEvent& event);
  void OnStopTimer(const ros::TimerEvent& event);
  void OnDiagnosticsTimer(const ros::WallTimerEvent& event);

  /// The constructor's publishers, services and diagnostic tasks.
  void Advertise();

  /// What a message on input `topic` naming no model joint (`names`) is told besides: the
  /// topic, and the model's joints that have its names with a prefix (PrefixedNamesHint).
  std::string NoKnownJointsHint(const std::vector<std::string>& names, std::size_t topic) const;

  /// ros::Time::now(), after re-basing every time-derived state if it is earlier than the last
  /// time read (only with simulated time: a looping bag, a simulator reset). Every time-derived
  /// state is compared with this, never with a raw now().
  ros::Time ClockNow();
  /// One monitor cycle on the merged input; `start` is when the triggering message was taken.
  void RunCycle(std::chrono::steady_clock::time_point start);
  /// Moves frame-bound objects to their TF poses; tells the stop policy of the objects whose
  /// frames are unavailable (each keeps its last pose).
  void UpdateBoundObjects(const ros::Time& now);
  /// Copies the policy's decision into the report and logs a change of the stop.
  void TakeStopDecision(bool was_stop);
  /// Messages refused so far: by the merger, and by the Monitor (out of limits).
  std::uint64_t RefusedInputs() const;
  // Logs a refused JointState of `kind` for `why`: the first of its kind (`is_first`) always, the
  // others at most once a second after `*last_logged` (a burst of one kind must not hide
  // another); nothing is formatted for a line not logged.
  void LogRefusal(bool is_first, const char* kind, const std::string& why,
                  ros::WallTime* last_logged) const;
  /// Publishes report_ as a shared pointer (see report_pool_).
  void PublishReport();
  void PublishStop(bool only_on_change);
  void PublishVisualisation();
  void FillReportWarnings(const CycleReport& report, MonitorReport* msg) const;

  // ~check's text of the request's `names` that are no model joints ("" for none: merged, they
  // are ignored); each but a mimic joint's counted in `unknown`, as the live report counts
  // them, and the model joints among `names` in `given`.
  std::string CheckedNamesText(const std::vector<std::string>& names, std::uint32_t* unknown,
                               std::size_t* given) const;
  bool OnCheck(CheckJointState::Request& req, CheckJointState::Response& res);
  bool OnAttach(AttachObject::Request& req, AttachObject::Response& res);
  bool OnDetach(DetachObject::Request& req, DetachObject::Response& res);
  bool OnSetGraspTarget(SetGraspTarget::Request& req, SetGraspTarget::Response& res);
  // Live objects (monitor_node_live_objects.cpp).
  bool OnAddObject(AddObject::Request& req, AddObject::Response& res);
  bool OnMoveObject(MoveObject::Request& req, MoveObject::Response& res);
  bool OnRemoveObject(RemoveObject::Request& req, RemoveObject::Response& res);
  // primitives_ from Monitor::primitive after a live object came or went.
  void RefreshPrimitives();
  // The fixed frame and TF (monitor_node_frames.cpp). fixed_frame_ from the parameter, else
  // `config_fixed_frame`, else the URDF root's name; a LoadError, naming where it came from,
  // for a name tf2 refuses, a moving virtual joint's parent frame or a link of the URDF away
  // from the root.
  void ResolveFixedFrame(const std::string& config_fixed_frame);
  // "" unless TF puts the fixed frame apart from the URDF root, or has both and does not
  // relate them (the fixed frame only renames the root's frame, in which the monitor computes):
  // then how far, and what to do. Never throws.
  std::string FixedFrameOffset() const;
  // TF's newest transform from `frame` to the fixed frame (the root's own frame: the identity);
  // throws tf2::TransformException as TF's lookup does. After FixedFrameOffset: "" for a pose
  // the monitor may take.
  geometry_msgs::TransformStamped LookupInFixedFrame(const std::string& frame) const;

  // X_WO from a pose in `frame` (the URDF root's: as is; "" or the fixed frame: as is, unless
  // FixedFrameOffset; else through TF now).
  bool ResolvePose(const geometry_msgs::Pose& pose, const std::string& frame,
                   Eigen::Isometry3d* X_WO, std::string* error);

  void DiagnoseInput(diagnostic_updater::DiagnosticStatusWrapper& status);
  void DiagnoseCycle(diagnostic_updater::DiagnosticStatusWrapper& status);
  void DiagnoseSafety(diagnostic_updater::DiagnosticStatusWrapper& status);

  ros::NodeHandle nh_;
  ros::NodeHandle private_nh_;
  NodeOptions options_;
  std::shared_ptr<const Workcell> workcell_;
  std::unique_ptr<Monitor> monitor_;
  /// Monitor::primitive of every id (live objects' names included), for the reports and the
  /// stop reason; refreshed by the live-object services.
  std::vector<PrimitiveSpec> primitives_;
  std::unique_ptr<JointMerger> input_;
  StopPolicy policy_;
  std::unique_ptr<MarkerBuilder> markers_;
  std::string fixed_frame_;

  tf2_ros::Buffer tf_buffer_;
  std::unique_ptr<tf2_ros::TransformListener> tf_listener_;
  /// A scene object whose pose follows a TF frame, and its last pose given to the Monitor.
  struct BoundObject {
    std::string object;
    std::string frame;
    Eigen::Isometry3d X_WO = Eigen::Isometry3d::Identity();  // the frame's, last read
    double stamp_s = 0.0;  // its stamp, last read (0: a static chain's)
    // Held since the frame last posed it: let go, it stays there until the frame's pose moves
    // (a stamped frame that does not follow it, re-sent unmoved, would pull it back).
    bool is_let_go = false;
    bool has_pose = false;
    bool is_available = false;  // the frame's pose read in the last cycle (OnAttach asks)
  };
  std::vector<BoundObject> bound_objects_;
  // UpdateBoundObjects' step for one object: true when its frame's pose is taken (or noted,
  // held), else false with why in `error`.
  bool PoseBoundObject(BoundObject* bound, bool is_held, const ros::Time& now,
                       std::string* error);
  std::string logged_offset_;  // FixedFrameOffset as last logged (DiagnoseSafety)

  std::vector<ros::Subscriber> subscribers_;
  // Per input topic with a joint prefix: the names of its last message and those prefixed (made
  // again only when its names change).
  struct PrefixedNames {
    std::vector<std::string> names, prefixed;
  };
  std::vector<PrefixedNames> prefixed_names_;
  // When a refusal was last logged (LogRefusal): of the merger's, of the monitor's.
  ros::WallTime merger_refusal_logged_, monitor_refusal_logged_;
  ros::Publisher report_pub_, stop_pub_, markers_pub_, joint_states_pub_;
  std::vector<ros::ServiceServer> services_;
  ros::Timer cycle_timer_, staleness_timer_, stop_timer_;
  ros::WallTimer diagnostics_timer_;
  diagnostic_updater::Updater updater_;

  // --- per-cycle state (preallocated) ------------------------------------------------------
  MonitorReport report_;               ///< reused every cycle
  /// Copies of report_ published as shared pointers: a subscriber in the same process (a nodelet
  /// in the monitor nodelet's manager) receives the very message, neither serialised nor passed
  /// through roscpp's poll thread. A copy that no subscriber holds any more is reused; a new one
  /// is made only while all are held (bounded by the in-process subscribers' queues).
  std::vector<boost::shared_ptr<MonitorReport>> report_pool_;
  sensor_msgs::JointState joint_state_out_;
  MergeStatus pending_refusal_ = MergeStatus::kAccepted;  ///< first refusal since last cycle
  std::string pending_why_;  ///< what in its message was refused (JointMerger::DescribeRefusal)
  ros::Time pending_stamp_;  ///< that message's stamp (the report's, with its refusal)
  ros::Time newest_input_stamp_;  ///< of the newest accepted message
  bool has_pending_input_ = false;
  bool published_stop_ = true;
  ros::WallTime last_visualisation_;

  // --- statistics for diagnostics ------------------------------------------------------------
  /// Samples kept for the diagnostics' statistics (about 1 s at 1 kHz, 50 s at 20 Hz).
  static constexpr std::size_t kSampleWindow = 1024;
  std::uint64_t cycles_ = 0;
  std::uint64_t messages_ = 0;
  std::uint64_t reinsert_fallbacks_ = 0;
  std::uint64_t outside_world_ = 0;
  double largest_step_m_ = 0.0;    ///< largest step motion bound over the run (m)
  std::uint64_t input_jumps_ = 0;  ///< cycles whose step exceeded max_step_m
  /// Per cycle and frame-bound object: frames not looked up (or poses refused), and frames
  /// found stale.
  std::uint64_t tf_failures_ = 0;
  std::uint64_t stale_frames_ = 0;
  std::uint64_t stale_episodes_ = 0;
  SampleWindow cycle_times_s_{kSampleWindow};  ///< the latest cycle times
  /// The latest accepted stamped messages' ages at arrival (ROS time less header.stamp).
  SampleWindow input_ages_s_{kSampleWindow};
  std::uint64_t diag_messages_ = 0;    ///< messages_ at the previous diagnostics update
  std::uint64_t diag_refused_ = 0;     ///< RefusedInputs() at the previous diagnostics update
  ros::WallTime diag_time_;
};

}  // namespace arm_collision_monitor
