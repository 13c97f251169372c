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
#include <exception>
#include <memory>

#include <nodelet/nodelet.h>
#include <pluginlib/class_list_macros.hpp>

#include "arm_collision_monitor/ros/monitor_node.h"

namespace arm_collision_monitor {

class MonitorNodelet : public nodelet::Nodelet {
 private:
  void onInit() override {
    try {
      node_ = std::make_unique<MonitorNode>(getNodeHandle(), getPrivateNodeHandle());
    } catch (const std::exception& e) {
      // Start-up errors (LoadError names the file or parameter). Rethrown: the manager then
      // refuses the load, `nodelet load` fails, and a required launch node ends the launch.
      NODELET_FATAL("arm_collision_monitor: cannot start: %s", e.what());
      throw;
    }
  }

  std::unique_ptr<MonitorNode> node_;
};

}  // namespace arm_collision_monitor

PLUGINLIB_EXPORT_CLASS(arm_collision_monitor::MonitorNodelet, nodelet::Nodelet)
