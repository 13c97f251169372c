// The collision monitor node: see include/arm_collision_monitor/ros/monitor_node.h.
#include <cstdio>
#include <exception>

#include <ros/ros.h>

#include "arm_collision_monitor/ros/monitor_node.h"

int main(int argc, char** argv) {
  // rosconsole writes INFO to stdout without flushing: into a file or pipe (roslaunch's log,
  // `> file`) the start-up lines would wait for a full buffer or the exit.
  std::setvbuf(stdout, nullptr, _IOLBF, BUFSIZ);
  ros::init(argc, argv, "arm_collision_monitor");
  // Held outside the try: the last NodeHandle going out of scope shuts roscpp (and its
  // logging) down, which would swallow the start-up error message below.
  ros::NodeHandle nh;
  ros::NodeHandle private_nh("~");
  try {
    arm_collision_monitor::MonitorNode node(nh, private_nh);
    ros::spin();
  } catch (const std::exception& e) {
    // Start-up errors (LoadError names the file or parameter); the cycle itself never throws.
    ROS_FATAL("arm_collision_monitor: cannot start: %s", e.what());
    return 1;
  }
  return 0;
}
