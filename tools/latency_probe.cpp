// Latency benchmark driver (a command, not a test): publishes sensor_msgs/JointState for both
// arms at ~rate_hz on one combined topic and measures, per message, the time from publishing to
// receiving (a) the echo node's copy and (b) the monitor's report for it, in the same run.
// Prints p50, p99, max and drops for both, and the monitor's in-node cycle time. Run:
//   roslaunch arm_collision_monitor latency_benchmark.launch [rate_hz:=1000] [duration_s:=10]
// Messages are matched by header.stamp (the report carries its input's stamp); the send time is
// the stamp itself (ros::Time::now(), wall clock without sim time), so latency is receive time
// minus stamp.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <mutex>
#include <string>
#include <thread>
#include <unordered_map>
#include <vector>

#include <ros/ros.h>
#include <sensor_msgs/JointState.h>

#include "arm_collision_monitor/MonitorReport.h"
#include "arm_collision_monitor/core/timing_summary.h"

namespace {

// Joint motion while measuring: each joint swings by this amplitude (rad) about home, slowly
// enough (kSwingFrequency_hz) that the arms stay far apart: the monitor moves its capsules and
// updates its index every cycle without warning.
constexpr double kSwingAmplitude_rad = 0.2;
constexpr double kSwingFrequency_hz = 0.5;
// After the last message, replies still in flight get this long to arrive before counting drops.
constexpr double kDrainTime_s = 1.0;

struct Series {
  std::vector<double> latency_s;
  std::vector<double> cycle_time_s;
};

std::uint64_t Key(const ros::Time& stamp) {
  return static_cast<std::uint64_t>(stamp.sec) * 1000000000ull + stamp.nsec;
}

std::string CpuModel() {
  std::ifstream cpuinfo("/proc/cpuinfo");
  std::string line;
  while (std::getline(cpuinfo, line)) {
    if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
  }
  return "unknown CPU";
}

// The measured messages still awaiting their echo and their report, and the samples so far;
// written by the subscriber thread and the publishing loop, hence the mutex.
struct Measurements {
  std::mutex mutex;
  std::unordered_map<std::uint64_t, bool> echo_pending, report_pending;
  Series echo, report;

  // A reply stamped `stamp` arrived now: its latency (and the monitor's cycle time, when
  // cycle_time_s >= 0) join `series` if the message was measured and not yet answered.
  void Record(std::unordered_map<std::uint64_t, bool>* pending, Series* series,
              const ros::Time& stamp, double cycle_time_s) {
    const double latency_s = (ros::Time::now() - stamp).toSec();
    std::lock_guard<std::mutex> lock(mutex);
    const auto it = pending->find(Key(stamp));
    if (it == pending->end()) return;  // warm-up, or a duplicate
    pending->erase(it);
    series->latency_s.push_back(latency_s);
    if (cycle_time_s >= 0.0) series->cycle_time_s.push_back(cycle_time_s);
  }
};

std::vector<std::string> BothArmsJointNames() {
  std::vector<std::string> joints;
  for (const char* arm : {"left", "right"}) {
    for (int i = 1; i <= 7; ++i) joints.push_back(std::string(arm) + "_joint" + std::to_string(i));
  }
  return joints;
}

// Waits (bounded) for both the echo node and the monitor to be connected both ways.
bool WaitForConnections(const ros::Publisher& pub, const ros::Subscriber& echo_sub,
                        const ros::Subscriber& report_sub) {
  const ros::WallTime connect_deadline = ros::WallTime::now() + ros::WallDuration(30.0);
  while (ros::ok() && (pub.getNumSubscribers() < 2 || echo_sub.getNumPublishers() < 1 ||
                       report_sub.getNumPublishers() < 1)) {
    if (ros::WallTime::now() > connect_deadline) return false;
    ros::WallDuration(0.01).sleep();
  }
  return true;
}

// Publishes `total` messages at rate_hz, the joints swinging about home; those after the first
// `warmup` are measured.
void PublishSwing(const ros::Publisher& pub, const std::vector<std::string>& joints,
                  double rate_hz, long warmup, long total, Measurements* measurements) {
  sensor_msgs::JointState msg;
  msg.name = joints;
  msg.position.assign(joints.size(), 0.0);
  ros::WallRate rate(rate_hz);
  for (long i = 0; i < total && ros::ok(); ++i) {
    const double t_s = i / rate_hz;
    for (std::size_t j = 0; j < joints.size(); ++j) {
      msg.position[j] = kSwingAmplitude_rad * std::sin(2.0 * M_PI * kSwingFrequency_hz * t_s + j);
    }
    msg.header.stamp = ros::Time::now();
    if (i >= warmup) {
      std::lock_guard<std::mutex> lock(measurements->mutex);
      measurements->echo_pending.emplace(Key(msg.header.stamp), true);
      measurements->report_pending.emplace(Key(msg.header.stamp), true);
    }
    pub.publish(msg);
    rate.sleep();
  }
}

// p50, p99 and max in microseconds; NaN for a series that received nothing, so that no aim
// reads as met.
struct MicrosRow {
  double p50, p99, max;
};

MicrosRow SummarizeMicros(const std::vector<double>& samples_s) {
  const arm_collision_monitor::TimingSummary s = arm_collision_monitor::SummarizeTimings(samples_s);
  if (s.count == 0) return MicrosRow{NAN, NAN, NAN};
  return MicrosRow{1e6 * s.median, 1e6 * s.p99, 1e6 * s.max};
}

// The table of both series, the monitor's cycle time and the aims (the caller holds the mutex).
void PrintResults(const Measurements& m, long measured, double rate_hz, long warmup) {
  std::printf("latency_probe: %ld JointState messages (14 joints) at %.0f Hz on loopback, "
              "after %ld warm-up; %s, %u hardware threads\n",
              measured, rate_hz, warmup, CpuModel().c_str(), std::thread::hardware_concurrency());
  std::printf("  %-28s %9s %9s %9s %9s %8s\n", "publish -> receive (us)", "p50", "p99", "max",
              "received", "dropped");
  const MicrosRow echo_us = SummarizeMicros(m.echo.latency_s);
  const MicrosRow report_us = SummarizeMicros(m.report.latency_s);
  const MicrosRow cycle_us = SummarizeMicros(m.report.cycle_time_s);
  const auto row = [](const char* name, const MicrosRow& us, std::size_t received,
                      std::size_t dropped) {
    std::printf("  %-28s %9.1f %9.1f %9.1f %9zu %8zu\n", name, us.p50, us.p99, us.max, received,
                dropped);
  };
  row("echo node (reference)", echo_us, m.echo.latency_s.size(), m.echo_pending.size());
  row("monitor report", report_us, m.report.latency_s.size(), m.report_pending.size());
  std::printf("  monitor cycle time in the node (us): p50 %.1f  p99 %.1f  max %.1f\n", cycle_us.p50,
              cycle_us.p99, cycle_us.max);
  std::printf("  aims: p50 <= echo + 20 us: %s (%+.1f us); p99 <= 1.2 x echo: %s (%.2f x); "
              "no drop: %s\n",
              report_us.p50 <= echo_us.p50 + 20.0 ? "met" : "missed", report_us.p50 - echo_us.p50,
              report_us.p99 <= 1.2 * echo_us.p99 ? "met" : "missed", report_us.p99 / echo_us.p99,
              m.report_pending.empty() ? "met" : "missed");
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "latency_probe");
  ros::NodeHandle nh;
  ros::NodeHandle private_nh("~");
  const double rate_hz = private_nh.param("rate_hz", 1000.0);
  const double duration_s = private_nh.param("duration_s", 10.0);
  const double warmup_s = private_nh.param("warmup_s", 1.0);
  const std::vector<std::string> joints = BothArmsJointNames();

  Measurements m;
  const ros::Publisher pub = nh.advertise<sensor_msgs::JointState>("joint_states", 100);
  const ros::Subscriber echo_sub = nh.subscribe<sensor_msgs::JointState>(
      "echo", 10000,
      [&](const sensor_msgs::JointState::ConstPtr& msg) {
        m.Record(&m.echo_pending, &m.echo, msg->header.stamp, -1.0);
      },
      ros::VoidConstPtr(), ros::TransportHints().tcpNoDelay());
  const ros::Subscriber report_sub = nh.subscribe<arm_collision_monitor::MonitorReport>(
      "report", 10000,
      [&](const arm_collision_monitor::MonitorReport::ConstPtr& msg) {
        m.Record(&m.report_pending, &m.report, msg->header.stamp, msg->cycle_time_s);
      },
      ros::VoidConstPtr(), ros::TransportHints().tcpNoDelay());
  ros::AsyncSpinner spinner(1);
  spinner.start();
  if (!WaitForConnections(pub, echo_sub, report_sub)) {
    ROS_FATAL("latency_probe: echo node or monitor not connected after 30 s");
    return 1;
  }

  const long warmup = std::lround(warmup_s * rate_hz);
  const long total = warmup + std::lround(duration_s * rate_hz);
  PublishSwing(pub, joints, rate_hz, warmup, total, &m);
  ros::WallDuration(kDrainTime_s).sleep();

  std::lock_guard<std::mutex> lock(m.mutex);
  PrintResults(m, total - warmup, rate_hz, warmup);
  return 0;
}
