// Writes the seed's three tasks (arm_collision_monitor/tasks/task_trajectories.h) as bags,
// <out_dir>/task{1,2,3}.bag: sensor_msgs/JointState on left_arm/joint_states and
// right_arm/joint_states (the node's default inputs), one message per arm per 50 ms cycle,
// stamped from the fixed kTaskBagStartStamp_s, uncompressed. Deterministic: regenerating gives
// byte-identical files (test/ros/task_bags.test checks it against test/bags/).
//
//   rosrun arm_collision_monitor generate_task_bags <out_dir> [urdf scene]
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include <rosbag/bag.h>
#include <ros/package.h>
#include <sensor_msgs/JointState.h>

#include "arm_collision_monitor/core/constants.h"
#include "arm_collision_monitor/scene/workcell.h"
#include "arm_collision_monitor/tasks/task_trajectories.h"

namespace arm_collision_monitor {
namespace {

constexpr const char* kArmTopics[2] = {"left_arm/joint_states", "right_arm/joint_states"};
constexpr const char* kArmPrefixes[2] = {"left_", "right_"};

void WriteTaskBag(int task, const Workcell& workcell, const std::string& path) {
  const TaskSpec& spec = GetTaskSpec(task);
  // Per arm: the workcell joint indices it publishes, in workcell order.
  std::vector<int> joints[2];
  for (int arm = 0; arm < 2; ++arm) {
    for (std::size_t j = 0; j < workcell.joint_names.size(); ++j) {
      if (workcell.joint_names[j].rfind(kArmPrefixes[arm], 0) == 0) {
        joints[arm].push_back(static_cast<int>(j));
      }
    }
  }
  rosbag::Bag bag(path, rosbag::bagmode::Write);
  bag.setCompression(rosbag::compression::Uncompressed);
  const ros::Time start(kTaskBagStartStamp_s);
  Eigen::VectorXd q, qdot;
  sensor_msgs::JointState msg;
  for (int k = 0; k < spec.cycle_count; ++k) {
    TaskStateAt(task, workcell, k * kTaskCyclePeriod_s, &q, &qdot);
    // Stamps from integer nanoseconds, so every cycle is exactly 50 ms after the previous one.
    const ros::Time stamp = start + ros::Duration().fromNSec(
        static_cast<std::int64_t>(k) * static_cast<std::int64_t>(kTaskCyclePeriod_s * 1e9 + 0.5));
    for (int arm = 0; arm < 2; ++arm) {
      msg.header.seq = static_cast<std::uint32_t>(k);
      msg.header.stamp = stamp;
      msg.header.frame_id.clear();
      msg.name.clear();
      msg.position.clear();
      msg.velocity.clear();
      for (const int j : joints[arm]) {
        msg.name.push_back(workcell.joint_names[j]);
        msg.position.push_back(q[j]);
        msg.velocity.push_back(qdot[j]);
      }
      bag.write(kArmTopics[arm], stamp, msg);
    }
  }
  bag.close();
  std::printf("generate_task_bags: %s: %s, %d cycles x 2 messages\n", path.c_str(),
              spec.name.c_str(), spec.cycle_count);
}

}  // namespace
}  // namespace arm_collision_monitor

int main(int argc, char** argv) {
  using namespace arm_collision_monitor;
  if (argc != 2 && argc != 4) {
    std::fprintf(stderr,
                 "usage: generate_task_bags <out_dir> [urdf scene]\n"
                 "  writes <out_dir>/task1.bag, task2.bag, task3.bag (default workcell: the "
                 "package's urdf/workcell.urdf and config/scene.yaml)\n");
    return 2;
  }
  const std::string out_dir = argv[1];
  try {
    const std::string package = argc == 4 ? "" : ros::package::getPath("arm_collision_monitor");
    const std::string urdf = argc == 4 ? argv[2] : package + "/urdf/workcell.urdf";
    const std::string scene = argc == 4 ? argv[3] : package + "/config/scene.yaml";
    const Workcell workcell = LoadWorkcell(urdf, scene);
    for (int task = 1; task <= kTaskCount; ++task) {
      WriteTaskBag(task, workcell, out_dir + "/" + GetTaskSpec(task).name + ".bag");
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "generate_task_bags: %s\n", e.what());
    return 1;
  }
  return 0;
}
