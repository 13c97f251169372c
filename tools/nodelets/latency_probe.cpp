// Latency benchmark driver (a command, not a test), a nodelet: publishes sensor_msgs/JointState
// for both arms at ~rate_hz on one combined topic, each message a new shared pointer, and
// measures per message the time from publishing to receiving
//   (a) the monitor nodelet's report: the monitor loaded into the same manager, its input handed
//       over in-process without serialisation (README "In-process input");
//   (b) monitor_node's report: a separate process, input and report over TCP (loopback);
//   (c) the TCP echo's copy (latency_echo, a separate process): the reference.
// All three receive the same messages in the same run. Prints p50, p99, max and drops of each,
// the monitors' cycle times and the aims, then shuts the manager down (ending the launch):
//   roslaunch arm_collision_monitor latency_benchmark.launch [rate_hz:=1000] [duration_s:=10]
// Messages are matched by header.stamp (a report carries its input's stamp); the send time is
// the stamp itself (ros::Time::now(), wall clock without sim time), so latency is receive time
// minus stamp. All three replies are recorded the same way, in the thread that delivers them
// (RecordOnDeliveryQueue): the TCP ones in roscpp's poll thread as it reads them off the socket,
// the nodelet's inside the monitor's publish(); none waits for the manager to wake a thread.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <unordered_map>
#include <vector>

#include <boost/make_shared.hpp>
#include <nodelet/nodelet.h>
#include <pluginlib/class_list_macros.hpp>
#include <ros/callback_queue_interface.h>
#include <ros/ros.h>
#include <ros/subscription_queue.h>
#include <sensor_msgs/JointState.h>

#include "arm_collision_monitor/MonitorReport.h"
#include "arm_collision_monitor/core/timing_summary.h"

namespace arm_collision_monitor {
namespace {

// Joint motion while measuring: each joint swings by this amplitude (rad) about home, slowly
// enough (kSwingFrequency_hz) that the arms stay far apart: the monitors move their capsules and
// update their index every cycle without warning.
constexpr double kSwingAmplitude_rad = 0.2;
constexpr double kSwingFrequency_hz = 0.5;
// After the last message, replies still in flight get this long to arrive before counting drops.
constexpr double kDrainTime_s = 1.0;
// The monitors and the echo must be connected within this time after start-up.
constexpr double kConnectTimeout_s = 30.0;

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

// One receiver's measured messages still awaiting their reply, and its samples so far.
struct Series {
  std::unordered_map<std::uint64_t, bool> pending;
  std::vector<double> latency_s;
  std::vector<double> cycle_time_s;
};

// The three receivers' series; written by the subscriptions (in the delivering threads) and the
// publishing thread, hence the mutex.
struct Measurements {
  std::mutex mutex;
  Series echo, tcp_report, nodelet_report;

  // A reply stamped `stamp` arrived now: its latency (and the monitor's cycle time, when
  // cycle_time_s >= 0) join `series` if the message was measured and not yet answered.
  void Record(Series* series, const ros::Time& stamp, double cycle_time_s) {
    const double latency_s = (ros::Time::now() - stamp).toSec();
    std::lock_guard<std::mutex> lock(mutex);
    const auto it = series->pending.find(Key(stamp));
    if (it == series->pending.end()) return;  // warm-up, or a duplicate
    series->pending.erase(it);
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

// p50, p99 and max in microseconds; NaN for a series that received nothing, so that no aim
// reads as met.
struct MicrosRow {
  double p50, p99, max;
};

MicrosRow SummarizeMicros(const std::vector<double>& samples_s) {
  const TimingSummary s = SummarizeTimings(samples_s);
  if (s.count == 0) return MicrosRow{NAN, NAN, NAN};
  return MicrosRow{1e6 * s.median, 1e6 * s.p99, 1e6 * s.max};
}

// The table of the three series, the monitors' cycle times and the aims (the caller holds the
// mutex).
void PrintResults(const Measurements& m, long measured, double rate_hz, long warmup) {
  std::printf("latency_probe: %ld JointState messages (14 joints) at %.0f Hz, after %ld warm-up; "
              "%s, %u hardware threads\n",
              measured, rate_hz, warmup, CpuModel().c_str(), std::thread::hardware_concurrency());
  std::printf("  %-34s %9s %9s %9s %9s %8s %9s\n", "publish -> receive (us)", "p50", "p99", "max",
              "received", "dropped", "p50/echo");
  const MicrosRow echo_us = SummarizeMicros(m.echo.latency_s);
  const auto row = [&echo_us](const char* name, const Series& series) {
    const MicrosRow us = SummarizeMicros(series.latency_s);
    std::printf("  %-34s %9.1f %9.1f %9.1f %9zu %8zu %9.3f\n", name, us.p50, us.p99, us.max,
                series.latency_s.size(), series.pending.size(), us.p50 / echo_us.p50);
    return us;
  };
  row("TCP echo node (reference)", m.echo);
  const MicrosRow tcp_us = row("monitor_node report (TCP)", m.tcp_report);
  const MicrosRow nodelet_us = row("monitor nodelet report (in-proc)", m.nodelet_report);
  for (const auto& [name, series] : {std::pair<const char*, const Series*>{"monitor_node",
                                                                           &m.tcp_report},
                                     {"monitor nodelet", &m.nodelet_report}}) {
    const MicrosRow cycle_us = SummarizeMicros(series->cycle_time_s);
    std::printf("  %s cycle time (us): p50 %.1f  p99 %.1f  max %.1f\n", name, cycle_us.p50,
                cycle_us.p99, cycle_us.max);
  }
  std::printf("  aims: TCP p50 <= echo + 20 us: %s (%+.1f us); TCP p99 <= 1.2 x echo: %s "
              "(%.2f x); nodelet p50 <= 0.15 x echo: %s (%.3f x); no drop: %s\n",
              tcp_us.p50 <= echo_us.p50 + 20.0 ? "met" : "missed", tcp_us.p50 - echo_us.p50,
              tcp_us.p99 <= 1.2 * echo_us.p99 ? "met" : "missed", tcp_us.p99 / echo_us.p99,
              nodelet_us.p50 <= 0.15 * echo_us.p50 ? "met" : "missed", nodelet_us.p50 / echo_us.p50,
              m.tcp_report.pending.empty() && m.nodelet_report.pending.empty() ? "met"
                                                                                : "missed");
  std::fflush(stdout);
}

// The probe's callback queue: runs a message callback at once in the thread that delivers the
// message, so that a reply's receive time is taken when roscpp has it, whichever the transport.
// Safe in any thread, unlike the monitor's DirectInputQueue, because the callbacks on it (Record)
// only take Measurements' mutex, which nothing holds while waiting for another lock, and never
// publish. A callback that cannot run now (TryAgain: its subscription's callback is running in
// another thread) and every other kind go to the underlying queue.
class RecordOnDeliveryQueue : public ros::CallbackQueueInterface {
 public:
  explicit RecordOnDeliveryQueue(ros::CallbackQueueInterface* queue) : queue_(queue) {}

  void addCallback(const ros::CallbackInterfacePtr& callback, std::uint64_t owner_id) override {
    if (dynamic_cast<ros::SubscriptionQueue*>(callback.get()) != nullptr && callback->ready() &&
        callback->call() != ros::CallbackInterface::TryAgain) {
      return;
    }
    queue_->addCallback(callback, owner_id);
  }
  void removeByID(std::uint64_t owner_id) override { queue_->removeByID(owner_id); }

 private:
  ros::CallbackQueueInterface* queue_;
};

}  // namespace

/// Topics (remap them): publishes `joint_states`; receives `echo` (the TCP echo's copy),
/// `report` (monitor_node over TCP) and `nodelet_report` (the monitor nodelet in this manager).
/// Private parameters: rate_hz (1000), duration_s (10), warmup_s (1).
class LatencyProbe : public nodelet::Nodelet {
 public:
  ~LatencyProbe() override {
    if (worker_.joinable()) worker_.join();
  }

 private:
  void onInit() override {
    // Over the multi-threaded queue: replies may be recorded concurrently (Record locks).
    ros::NodeHandle nh = getMTNodeHandle();
    const ros::NodeHandle& private_nh = getMTPrivateNodeHandle();
    record_queue_ = std::make_unique<RecordOnDeliveryQueue>(nh.getCallbackQueue());
    nh.setCallbackQueue(record_queue_.get());
    rate_hz_ = private_nh.param("rate_hz", 1000.0);
    duration_s_ = private_nh.param("duration_s", 10.0);
    warmup_s_ = private_nh.param("warmup_s", 1.0);
    pub_ = nh.advertise<sensor_msgs::JointState>("joint_states", 100);
    const auto tcp = ros::TransportHints().tcpNoDelay();
    echo_sub_ = nh.subscribe<sensor_msgs::JointState>(
        "echo", 10000,
        [this](const sensor_msgs::JointState::ConstPtr& msg) {
          m_.Record(&m_.echo, msg->header.stamp, -1.0);
        },
        ros::VoidConstPtr(), tcp);
    report_subs_.push_back(Subscribe(nh, "report", &m_.tcp_report));
    report_subs_.push_back(Subscribe(nh, "nodelet_report", &m_.nodelet_report));
    worker_ = std::thread([this] { Run(); });
  }

  ros::Subscriber Subscribe(ros::NodeHandle& nh, const std::string& topic, Series* series) {
    return nh.subscribe<MonitorReport>(
        topic, 10000,
        [this, series](const MonitorReport::ConstPtr& msg) {
          m_.Record(series, msg->header.stamp, msg->cycle_time_s);
        },
        ros::VoidConstPtr(), ros::TransportHints().tcpNoDelay());
  }

  // Waits (bounded) for the echo and both monitors to be connected both ways.
  bool WaitForConnections() const {
    const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(kConnectTimeout_s);
    while (ros::ok() && (pub_.getNumSubscribers() < 3 || echo_sub_.getNumPublishers() < 1 ||
                         report_subs_[0].getNumPublishers() < 1 ||
                         report_subs_[1].getNumPublishers() < 1)) {
      if (ros::WallTime::now() > deadline) return false;
      ros::WallDuration(0.01).sleep();
    }
    return true;
  }

  // Publishes `total` messages at rate_hz, the joints swinging about home, each a new shared
  // pointer (never changed once published: in-process subscribers hold it); those after the
  // first `warmup` are measured.
  void PublishSwing(long warmup, long total) {
    const std::vector<std::string> joints = BothArmsJointNames();
    ros::WallRate rate(rate_hz_);
    for (long i = 0; i < total && ros::ok(); ++i) {
      const auto msg = boost::make_shared<sensor_msgs::JointState>();
      msg->name = joints;
      msg->position.resize(joints.size());
      const double t_s = i / rate_hz_;
      for (std::size_t j = 0; j < joints.size(); ++j) {
        msg->position[j] =
            kSwingAmplitude_rad * std::sin(2.0 * M_PI * kSwingFrequency_hz * t_s + j);
      }
      msg->header.stamp = ros::Time::now();
      if (i >= warmup) {
        std::lock_guard<std::mutex> lock(m_.mutex);
        for (Series* series : {&m_.echo, &m_.tcp_report, &m_.nodelet_report}) {
          series->pending.emplace(Key(msg->header.stamp), true);
        }
      }
      pub_.publish(sensor_msgs::JointState::ConstPtr(msg));
      rate.sleep();
    }
  }

  void Run() {
    if (!WaitForConnections()) {
      NODELET_FATAL("latency_probe: echo node or monitors not connected after %.0f s",
                    kConnectTimeout_s);
    } else {
      const long warmup = std::lround(warmup_s_ * rate_hz_);
      const long total = warmup + std::lround(duration_s_ * rate_hz_);
      PublishSwing(warmup, total);
      ros::WallDuration(kDrainTime_s).sleep();
      std::lock_guard<std::mutex> lock(m_.mutex);
      PrintResults(m_, total - warmup, rate_hz_, warmup);
    }
    ros::requestShutdown();  // the manager exits, which ends the launch
  }

  double rate_hz_ = 0.0, duration_s_ = 0.0, warmup_s_ = 0.0;
  Measurements m_;
  std::unique_ptr<RecordOnDeliveryQueue> record_queue_;  // outlives the subscriptions below
  ros::Publisher pub_;
  ros::Subscriber echo_sub_;
  std::vector<ros::Subscriber> report_subs_;  ///< TCP monitor, nodelet monitor
  std::thread worker_;
};

}  // namespace arm_collision_monitor

PLUGINLIB_EXPORT_CLASS(arm_collision_monitor::LatencyProbe, nodelet::Nodelet)
