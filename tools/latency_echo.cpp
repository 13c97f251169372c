// The latency benchmark's reference: the cheapest node shaped like the monitor (JointState in
// over TCP_NODELAY, one message out per message in). launch/latency_benchmark.launch runs it
// beside the monitor on the same input stream.
#include <ros/ros.h>
#include <sensor_msgs/JointState.h>

int main(int argc, char** argv) {
  ros::init(argc, argv, "latency_echo");
  ros::NodeHandle nh;
  ros::NodeHandle private_nh("~");
  const ros::Publisher out = private_nh.advertise<sensor_msgs::JointState>("joint_states", 100);
  const ros::Subscriber in = nh.subscribe<sensor_msgs::JointState>(
      "joint_states", 100,
      [&out](const sensor_msgs::JointState::ConstPtr& msg) { out.publish(msg); },
      ros::VoidConstPtr(), ros::TransportHints().tcpNoDelay());
  ros::spin();
  return 0;
}
