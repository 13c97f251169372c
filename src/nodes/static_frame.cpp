// Publishes one static transform on /tf_static (Debian's ROS ships no static_transform_publisher
// executable). Used by the launch files and rostests for the scene's frame-bound camera.
//   static_frame x y z yaw pitch roll parent_frame child_frame   (metres, radians)
#include <cstdlib>
#include <string>

#include <geometry_msgs/TransformStamped.h>
#include <ros/ros.h>
#include <tf2/LinearMath/Quaternion.h>
#include <tf2_ros/static_transform_broadcaster.h>

int main(int argc, char** argv) {
  ros::init(argc, argv, "static_frame", ros::init_options::AnonymousName);
  if (argc != 9) {
    ROS_FATAL("usage: static_frame x y z yaw pitch roll parent_frame child_frame");
    return 1;
  }
  ros::NodeHandle nh;  // starts roscpp (and its clock) before ros::Time::now()
  geometry_msgs::TransformStamped X_PC;
  X_PC.header.stamp = ros::Time::now();
  X_PC.header.frame_id = argv[7];
  X_PC.child_frame_id = argv[8];
  X_PC.transform.translation.x = std::atof(argv[1]);
  X_PC.transform.translation.y = std::atof(argv[2]);
  X_PC.transform.translation.z = std::atof(argv[3]);
  tf2::Quaternion R_PC;
  R_PC.setRPY(std::atof(argv[6]), std::atof(argv[5]), std::atof(argv[4]));  // roll, pitch, yaw
  X_PC.transform.rotation.x = R_PC.x();
  X_PC.transform.rotation.y = R_PC.y();
  X_PC.transform.rotation.z = R_PC.z();
  X_PC.transform.rotation.w = R_PC.w();
  tf2_ros::StaticTransformBroadcaster broadcaster;
  broadcaster.sendTransform(X_PC);
  ros::spin();
  return 0;
}
