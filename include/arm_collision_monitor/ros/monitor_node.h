// The monitor's ROS node: parameters, JointState subscriptions, the per-message (or fixed-rate)
// cycle, the report / stop / marker / diagnostics publishers and the services. It translates
// only; everything computed lives in the ROS-free Monitor.
//
// Stop policy (also in README): a stop is requested (~stop = true, report.stop = true) while any
// of these holds, evaluated every cycle and by the staleness timer:
//   - some model joint was never received (start-up: stop until the model is complete);
//   - the last input message was refused (wrong size, non-finite, out of limits, stamp going
//     backwards, stamped further than the input timeout from now, no model joint);
//   - some joint's newest input was received longer ago than ~input_timeout_s;
//   - the ROS clock went back (simulated time: a looping bag, a simulator reset) and some
//     joint has not been received since (every time-derived state is re-based on the jump);
//   - a frame-bound scene object's TF frame could not be looked up;
//   - the last cycle reported a warning.
// It is cleared by the first cycle on accepted, complete, fresh input with no warning that
// comes at least ~stop_hold_s after the condition was last seen (hold: no chattering on a
// pair hovering at its threshold).
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

#include "arm_collision_monitor/AttachObject.h"
#include "arm_collision_monitor/CheckJointState.h"
#include "arm_collision_monitor/DetachObject.h"
#include "arm_collision_monitor/MonitorReport.h"
#include "arm_collision_monitor/SetGraspTarget.h"
#include "arm_collision_monitor/monitor/monitor.h"
#include "arm_collision_monitor/ros/joint_state_input.h"
#include "arm_collision_monitor/ros/marker_builder.h"

namespace arm_collision_monitor {

/// The node's parameters (all private, ~name), with their defaults.
struct NodeOptions {
  std::string urdf_path;    ///< ~urdf (required)
  std::string scene_path;   ///< ~scene (required)
  std::string config_path;  ///< ~config: Monitor options YAML (required)
  /// ~input_topics: JointState topics merged by joint name (one per arm, or one combined).
  std::vector<std::string> input_topics{"left_arm/joint_states", "right_arm/joint_states"};
  int queue_size = 100;            ///< ~queue_size per input topic (1 kHz input: ~0.1 s)
  double cycle_rate_hz = 0.0;      ///< ~cycle_rate_hz: 0 = one cycle per message
  double input_timeout_s = 0.25;   ///< ~input_timeout_s: staleness bound (5 cycles at 20 Hz)
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
  void OnJointState(const sensor_msgs::JointState::ConstPtr& msg);
  void OnCycleTimer(const ros::TimerEvent& event);
  void OnStalenessTimer(const ros::TimerEvent& event);
  void OnStopTimer(const ros::TimerEvent& event);
  void OnDiagnosticsTimer(const ros::WallTimerEvent& event);

  /// ros::Time::now(), after calling OnTimeWentBackwards() if it is earlier than the last
  /// time read. Every time-derived state is compared with this, never with a raw now().
  ros::Time ClockNow();
  /// Re-bases all time-derived state on `now` at once after the ROS clock went back (only with
  /// simulated time: it is monotonic under wall time): the hold deadline, the input stamps and
  /// receipt times; a stop is requested until every joint is received again.
  void OnTimeWentBackwards(const ros::Time& now);
  /// One monitor cycle on the merged input; `start` is when the triggering message was taken.
  void RunCycle(std::chrono::steady_clock::time_point start);
  /// Moves frame-bound objects to their TF pose; false (and sets the stop reason) on failure.
  bool UpdateBoundObjects();
  /// Sets this cycle's stop condition (printf-style; no allocation once condition_ has grown).
  void SetCondition(const char* format, ...) __attribute__((format(printf, 2, 3)));
  /// Sets the stale-input condition, naming the joint silent longest (or since the jump back).
  void SetStaleCondition(const ros::Time& now);
  /// Applies the stop policy to this cycle's condition_ (empty: none) and fills the report's
  /// stop fields.
  void ApplyStopPolicy(const ros::Time& now);
  void PublishStop(bool only_on_change);
  void PublishVisualisation();
  void FillReportWarnings(const CycleReport& report, MonitorReport* msg) const;

  bool OnCheck(CheckJointState::Request& req, CheckJointState::Response& res);
  bool OnAttach(AttachObject::Request& req, AttachObject::Response& res);
  bool OnDetach(DetachObject::Request& req, DetachObject::Response& res);
  bool OnSetGraspTarget(SetGraspTarget::Request& req, SetGraspTarget::Response& res);

  void DiagnoseInput(diagnostic_updater::DiagnosticStatusWrapper& status);
  void DiagnoseCycle(diagnostic_updater::DiagnosticStatusWrapper& status);
  void DiagnoseSafety(diagnostic_updater::DiagnosticStatusWrapper& status);

  ros::NodeHandle nh_;
  ros::NodeHandle private_nh_;
  NodeOptions options_;
  std::shared_ptr<const Workcell> workcell_;
  std::unique_ptr<Monitor> monitor_;
  std::unique_ptr<JointStateInput> input_;
  std::unique_ptr<MarkerBuilder> markers_;
  std::string fixed_frame_;

  tf2_ros::Buffer tf_buffer_;
  std::unique_ptr<tf2_ros::TransformListener> tf_listener_;
  /// A scene object whose pose follows a TF frame, and its last pose given to the Monitor.
  struct BoundObject {
    std::string object;
    std::string frame;
    Eigen::Isometry3d X_WO = Eigen::Isometry3d::Identity();
    bool has_pose = false;
  };
  std::vector<BoundObject> bound_objects_;

  std::vector<ros::Subscriber> subscribers_;
  ros::Publisher report_pub_, stop_pub_, markers_pub_, joint_states_pub_;
  std::vector<ros::ServiceServer> services_;
  ros::Timer cycle_timer_, staleness_timer_, stop_timer_;
  ros::WallTimer diagnostics_timer_;
  diagnostic_updater::Updater updater_;

  // --- per-cycle state (preallocated) ------------------------------------------------------
  MonitorReport report_;               ///< reused every cycle
  sensor_msgs::JointState joint_state_out_;
  std::uint8_t pending_status_ = MonitorReport::INPUT_OK;  ///< first refusal since last cycle
  ros::Time newest_input_stamp_;
  ros::Time last_now_;                 ///< the latest ClockNow()
  bool has_pending_input_ = false;
  std::string condition_;              ///< this cycle's stop condition ("" none)
  bool stop_ = true;                   ///< requested; true until the model is complete
  std::string stop_reason_;            ///< the condition that requested the current stop
  bool published_stop_ = true;
  ros::Time stop_hold_until_;
  bool is_stale_reported_ = false;
  ros::WallTime last_visualisation_;

  // --- statistics for diagnostics ------------------------------------------------------------
  std::uint64_t cycles_ = 0;
  std::uint64_t messages_ = 0;
  std::uint64_t refused_ = 0;
  std::uint64_t refused_by_status_[MonitorReport::INPUT_FUTURE_STAMP + 1] = {};
  std::uint64_t reinsert_fallbacks_ = 0;
  std::uint64_t outside_world_ = 0;
  std::uint64_t tf_failures_ = 0;
  std::uint64_t stale_episodes_ = 0;
  std::vector<double> cycle_times_s_;  ///< ring buffer of the latest cycle times
  std::size_t cycle_time_next_ = 0;
  std::uint64_t diag_messages_ = 0;    ///< messages_ at the previous diagnostics update
  std::uint64_t diag_refused_ = 0;     ///< refused_ at the previous diagnostics update
  ros::WallTime diag_time_;
};

}  // namespace arm_collision_monitor
