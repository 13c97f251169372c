// The monitor as a nodelet (README "In-process input"): the same MonitorNode as monitor_node,
// constructed on the nodelet's node handles, so that a driver loaded into the same manager hands
// it JointState without serialisation. MonitorNode subscribes with JointState::ConstPtr
// (boost::shared_ptr<const JointState>): a publisher in the same process that publishes a
// shared pointer delivers that very message, with no copy.
//
// The node handles are the single-threaded ones on purpose: MonitorNode's state (the merger, the
// stop policy, the Monitor's per-cycle data) is touched by its subscriptions, timers and services
// without locks, as in monitor_node's ros::spin(). The nodelet's ST queue runs its callbacks one
// at a time on the manager's worker threads, which is that same guarantee; the multi-threaded
// handles would run them concurrently.
//
// ~inline_input (default true): the input runs the cycle at once in the delivering thread (for a
// driver nodelet: inside its publish()), through InlineInputQueue over the ST queue, which keeps
// the one-callback-at-a-time guarantee. Without it each message waits for the manager to wake a
// worker thread, which costs more than the cycle itself; with it the driver's publish() returns
// after the cycle (microseconds; see the latency benchmark's cycle times).
#include <exception>
#include <memory>

#include <nodelet/nodelet.h>
#include <pluginlib/class_list_macros.hpp>

#include "arm_collision_monitor/ros/inline_input_queue.h"
#include "arm_collision_monitor/ros/monitor_node.h"

namespace arm_collision_monitor {

class MonitorNodelet : public nodelet::Nodelet {
 private:
  void onInit() override {
    ros::NodeHandle nh = getNodeHandle();
    ros::NodeHandle private_nh = getPrivateNodeHandle();
    if (private_nh.param("inline_input", true)) {
      inline_queue_ = std::make_unique<InlineInputQueue>(nh.getCallbackQueue());
      nh.setCallbackQueue(inline_queue_.get());
      private_nh.setCallbackQueue(inline_queue_.get());
    }
    try {
      node_ = std::make_unique<MonitorNode>(nh, private_nh);
    } catch (const std::exception& e) {
      // Start-up errors (LoadError names the file or parameter). Rethrown: the manager then
      // refuses the load, `nodelet load` fails, and a required launch node ends the launch.
      NODELET_FATAL("arm_collision_monitor: cannot start: %s", e.what());
      throw;
    }
  }

  std::unique_ptr<InlineInputQueue> inline_queue_;  // declared first: outlives node_
  std::unique_ptr<MonitorNode> node_;
};

}  // namespace arm_collision_monitor

PLUGINLIB_EXPORT_CLASS(arm_collision_monitor::MonitorNodelet, nodelet::Nodelet)
