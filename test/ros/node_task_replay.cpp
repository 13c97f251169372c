// rostest checker of test/ros/task{1,2,3}.test and example_dual_arm_shelf.test: replays a bag
// (a task's, or the example's) into the running monitor node and checks every report against
// the offline brute force computed from the same bag with the core library, then the expected
// outcome (parameters of the .test file).
//
// The bag is replayed in lock step: each message is published (restamped with the current
// time, so the node's staleness checks see live input) only after the report of the previous
// one arrived. rosbag play gives no order between its two topics, and the per-cycle comparison
// needs to know exactly which merged state each report is for; lock step also proves every
// message was processed (one report each) and runs faster than real time.
//
// Parameters (~): bag, urdf, scene, node (the monitor's name), grasp_targets ("link:object"
// list), expected_messages, expects_warning, expects_clean_cycle (some complete cycle has no
// warning), first_warning_arm and first_warning_object (both "" to check no first pair),
// first_warning_before_contact, never_warned_object, report_timeout_s.
#include <algorithm>
#include <condition_variable>
#include <mutex>
#include <set>
#include <string>
#include <unordered_map>
#include <vector>

#include <gtest/gtest.h>
#include <ros/ros.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <sensor_msgs/JointState.h>

#include "arm_collision_monitor/MonitorReport.h"
#include "arm_collision_monitor/SetGraspTarget.h"
#include "arm_collision_monitor/ros/resource_fetch_ros.h"

// test_monitor_util.h's LoadBundledWorkcell() uses ACM_SOURCE_DIR, which CMake defines for the
// core tests only; this checker does not call it (it loads the workcell the .test file names).
#ifndef ACM_SOURCE_DIR
#define ACM_SOURCE_DIR "."
#endif
#include "../core/test_monitor_util.h"

namespace arm_collision_monitor {
namespace {

class ReportCollector {
 public:
  void OnReport(const MonitorReport::ConstPtr& msg) {
    std::lock_guard<std::mutex> lock(mutex_);
    reports_.push_back(msg);
    changed_.notify_all();
  }
  /// Waits (at most timeout_s of wall time) until more than `count` reports arrived; returns
  /// report number `count` or null.
  MonitorReport::ConstPtr WaitFor(std::size_t count, double timeout_s) {
    std::unique_lock<std::mutex> lock(mutex_);
    changed_.wait_for(lock, std::chrono::duration<double>(timeout_s),
                      [&] { return reports_.size() > count; });
    return reports_.size() > count ? reports_[count] : nullptr;
  }
  std::size_t size() {
    std::lock_guard<std::mutex> lock(mutex_);
    return reports_.size();
  }

 private:
  std::mutex mutex_;
  std::condition_variable changed_;
  std::vector<MonitorReport::ConstPtr> reports_;
};

// Waits (wall time) until `ready()` holds; false on timeout.
template <typename Ready>
bool WaitUntil(Ready ready, double timeout_s) {
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(timeout_s);
  while (ros::ok() && ros::WallTime::now() < deadline) {
    if (ready()) return true;
    ros::WallDuration(0.01).sleep();  // polling period, not a stand-in for a condition
  }
  return ready();
}

TEST(TaskReplay, EveryReportMatchesTheBruteForceAndTheTaskOutcome) {
  ros::NodeHandle nh, pnh("~");
  std::string bag_path, urdf, scene, node;
  ASSERT_TRUE(pnh.getParam("bag", bag_path));
  ASSERT_TRUE(pnh.getParam("urdf", urdf));
  ASSERT_TRUE(pnh.getParam("scene", scene));
  pnh.param<std::string>("node", node, "/arm_collision_monitor");
  std::vector<std::string> grasp_targets;
  pnh.getParam("grasp_targets", grasp_targets);
  int expected_messages = 0;
  ASSERT_TRUE(pnh.getParam("expected_messages", expected_messages));
  bool expects_warning = false, first_warning_before_contact = false, expects_clean_cycle = false;
  ASSERT_TRUE(pnh.getParam("expects_warning", expects_warning));
  pnh.param("expects_clean_cycle", expects_clean_cycle, false);
  pnh.param("first_warning_before_contact", first_warning_before_contact, false);
  std::string first_warning_arm, first_warning_object, never_warned_object;
  pnh.param<std::string>("first_warning_arm", first_warning_arm, "");
  pnh.param<std::string>("first_warning_object", first_warning_object, "");
  pnh.param<std::string>("never_warned_object", never_warned_object, "");
  double report_timeout_s = 10.0;
  pnh.param("report_timeout_s", report_timeout_s, 10.0);

  // The node resolves package:// mesh URLs (the example's URDF) through resource_retriever:
  // so does the checker.
  WorkcellLoadOptions load_options;
  load_options.fetch = FetchRosResource;
  const auto workcell = std::make_shared<const Workcell>(LoadWorkcell(urdf, scene, load_options));
  const Workcell& wc = *workcell;
  test::ReferenceScene reference_scene;

  // Connect: the node's inputs, its report, and its grasp-target service.
  ReportCollector collector;
  ros::Subscriber report_sub = nh.subscribe(node + "/report", 10000,
                                            &ReportCollector::OnReport, &collector);
  std::unordered_map<std::string, ros::Publisher> publishers;
  rosbag::Bag bag(bag_path, rosbag::bagmode::Read);
  rosbag::View view(bag, rosbag::TypeQuery("sensor_msgs/JointState"));
  for (const rosbag::ConnectionInfo* c : view.getConnections()) {
    if (!publishers.count(c->topic)) {
      publishers[c->topic] = nh.advertise<sensor_msgs::JointState>(c->topic, 10);
    }
  }
  ASSERT_EQ(publishers.size(), 2u) << "a task bag has one topic per arm";
  ASSERT_TRUE(WaitUntil(
      [&] {
        for (auto& [topic, pub] : publishers) {
          if (pub.getNumSubscribers() == 0) return false;
        }
        return report_sub.getNumPublishers() > 0;
      },
      30.0))
      << "the monitor never connected to the input topics and ~report";
  for (const std::string& target : grasp_targets) {
    const std::size_t colon = target.find(':');
    ASSERT_NE(colon, std::string::npos) << target;
    SetGraspTarget srv;
    srv.request.link = target.substr(0, colon);
    srv.request.object = target.substr(colon + 1);
    srv.request.is_target = true;
    ASSERT_TRUE(ros::service::waitForService(node + "/set_grasp_target", ros::Duration(30.0)));
    ASSERT_TRUE(ros::service::call(node + "/set_grasp_target", srv));
    ASSERT_TRUE(srv.response.success) << srv.response.message;
    reference_scene.grasp.insert({wc.kinematics.FindLink(srv.request.link),
                                  wc.FindObject(srv.request.object)});
  }

  // Lock-step replay. The checker merges by name independently of the node: q in model order.
  std::unordered_map<std::string, int> index_of;
  for (std::size_t j = 0; j < wc.joint_names.size(); ++j) index_of[wc.joint_names[j]] = j;
  Eigen::VectorXd q = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(wc.joint_names.size()));
  std::vector<bool> received(wc.joint_names.size(), false);
  const std::size_t reports_before = collector.size();
  std::size_t published = 0, incomplete = 0, warning_reports = 0, clean_reports = 0;
  int first_warning = -1;
  std::vector<test::ReferenceWarning> first_warnings;
  std::set<std::string> never_object_hits;
  bool has_contact = false;
  for (const rosbag::MessageInstance& m : view) {
    sensor_msgs::JointState msg = *m.instantiate<sensor_msgs::JointState>();
    for (std::size_t k = 0; k < msg.name.size(); ++k) {
      const auto it = index_of.find(msg.name[k]);
      ASSERT_NE(it, index_of.end()) << msg.name[k];
      q[it->second] = msg.position[k];
      received[it->second] = true;
    }
    msg.header.stamp = ros::Time::now();
    publishers[m.getTopic()].publish(msg);
    const MonitorReport::ConstPtr report =
        collector.WaitFor(reports_before + published, report_timeout_s);
    ASSERT_TRUE(report) << "no report for message " << published << " within "
                        << report_timeout_s << " s";
    const std::string context = "message " + std::to_string(published);
    ++published;
    if (std::find(received.begin(), received.end(), false) != received.end()) {
      ++incomplete;
      EXPECT_EQ(report->input_status, MonitorReport::INPUT_INCOMPLETE) << context;
      EXPECT_TRUE(report->stop) << context;
      continue;
    }
    ASSERT_EQ(report->input_status, MonitorReport::INPUT_OK) << context;
    const std::vector<test::ReferenceWarning> expected =
        test::ReferenceWarnings(wc, q, reference_scene);
    std::vector<Warning> actual;
    for (const CollisionWarning& w : report->warnings) {
      Warning warning;
      warning.a = w.primitive_a;
      warning.b = w.primitive_b;
      warning.distance_m = w.distance_m;
      warning.threshold_m = w.threshold_m;
      warning.between_samples = w.between_samples;  // compared with the samples' apart
      warning.step_fraction = w.step_fraction;
      actual.push_back(warning);
      EXPECT_EQ(w.primitive_a_name, wc.primitives[w.primitive_a].name) << context;
      EXPECT_EQ(w.primitive_b_name, wc.primitives[w.primitive_b].name) << context;
    }
    test::ExpectSameWarnings(wc, expected, actual, context);
    if (!actual.empty()) {
      EXPECT_TRUE(report->stop) << context;
    }
    if (::testing::Test::HasFailure()) return;
    if (expected.empty()) {
      ++clean_reports;
      continue;
    }
    ++warning_reports;
    if (first_warning < 0) {
      first_warning = static_cast<int>(published - 1);
      first_warnings = expected;
    }
    for (const test::ReferenceWarning& w : expected) {
      has_contact |= w.distance_m == 0.0;
      if (wc.primitives[w.a].owner == never_warned_object ||
          wc.primitives[w.b].owner == never_warned_object) {
        never_object_hits.insert(test::Describe(wc, w.a, w.b));
      }
    }
  }
  EXPECT_EQ(static_cast<int>(published), expected_messages);
  EXPECT_EQ(incomplete, 1u) << "only the first message leaves a joint unknown";
  std::printf("%s: %zu messages, %zu reports, %zu with warnings\n", bag_path.c_str(), published,
              collector.size() - reports_before, warning_reports);

  if (expects_clean_cycle) {
    EXPECT_GT(clean_reports, 0u) << "no complete cycle without a warning";
  }
  if (!expects_warning) {
    EXPECT_EQ(warning_reports, 0u);
    return;
  }
  ASSERT_GE(first_warning, 0) << "no warning at all";
  if (first_warning_arm.empty() && first_warning_object.empty()) return;
  for (const test::ReferenceWarning& w : first_warnings) {
    const bool a_is_arm = wc.primitives[w.a].group == first_warning_arm;
    const PrimitiveSpec& arm = wc.primitives[a_is_arm ? w.a : w.b];
    const PrimitiveSpec& object = wc.primitives[a_is_arm ? w.b : w.a];
    std::printf("first warning at message %d: %s at %.4f m (threshold %.4f m)\n", first_warning,
                test::Describe(wc, w.a, w.b).c_str(), w.distance_m, w.threshold_m);
    EXPECT_EQ(arm.group, first_warning_arm) << test::Describe(wc, w.a, w.b);
    EXPECT_EQ(object.owner, first_warning_object) << test::Describe(wc, w.a, w.b);
    if (first_warning_before_contact) {
      EXPECT_GT(w.distance_m, 0.0);
    }
  }
  EXPECT_TRUE(has_contact) << "the arm never reaches " << first_warning_object;
  if (!never_warned_object.empty()) {
    EXPECT_TRUE(never_object_hits.empty())
        << "warned against " << never_warned_object << ": " << *never_object_hits.begin();
  }
}

}  // namespace
}  // namespace arm_collision_monitor

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "task_replay_checker");
  ros::AsyncSpinner spinner(1);
  spinner.start();
  const int result = RUN_ALL_TESTS();
  spinner.stop();
  ros::shutdown();
  return result;
}
