// libFuzzer harness for the run-time tier: a stream of sensor_msgs/JointState messages, as any
// publisher could send them (random name sets, duplicate and unknown names, mismatched array
// lengths, NaN/inf/huge positions, stamps in any order, clock jumps), through the node's path:
// ToNamedPositions, JointMerger, Monitor::Update and the StopPolicy, on the bundled workcell;
// plus raw joint vectors of any size straight into Monitor::Update. Nothing may crash, throw or
// invoke undefined behaviour, every report must keep the CycleReport contract, and the policy
// must request a stop whenever the input or the report calls for one (checked below; a
// violation aborts).
//
// Seeds: test/fuzz/corpus/ros_joint_state/ (any bytes are a valid input).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include <fuzzer/FuzzedDataProvider.h>

#include "arm_collision_monitor/monitor/monitor.h"
#include "arm_collision_monitor/ros/conversions.h"
#include "arm_collision_monitor/safety/stop_policy.h"
#include "arm_collision_monitor/scene/workcell.h"

namespace arm_collision_monitor {
namespace {

// Bounds that keep one input fast: messages per input, entries per message.
constexpr int kMaxMessages = 64;
constexpr int kMaxEntries = 24;
// The node's default input timeout and stop hold (only the order of magnitude matters).
constexpr double kInputTimeout_s = 0.5;
constexpr double kStopHold_s = 0.25;

struct Fixture {
  std::shared_ptr<const Workcell> workcell;
  MonitorOptions options;
};

const Fixture& BundledWorkcell() {
  static const Fixture fixture = [] {
    const std::string root = ACM_SOURCE_DIR;
    Fixture f;
    f.options = LoadMonitorOptions(root + "/config/monitor.yaml");
    f.workcell = std::make_shared<const Workcell>(LoadWorkcell(
        root + "/urdf/workcell.urdf", root + "/config/scene.yaml", f.options.tolerance_m));
    return f;
  }();
  return fixture;
}

void Require(bool condition) {
  if (!condition) std::abort();  // a broken contract: libFuzzer keeps the input
}

double ConsumePosition(FuzzedDataProvider* in, const JointSpec* joint) {
  switch (in->ConsumeIntegralInRange<int>(0, 7)) {
    case 0:
      return std::numeric_limits<double>::quiet_NaN();
    case 1:
      return in->ConsumeBool() ? std::numeric_limits<double>::infinity()
                               : -std::numeric_limits<double>::infinity();
    case 2:
      return in->ConsumeBool() ? std::numeric_limits<double>::max()
                               : std::numeric_limits<double>::denorm_min();
    case 3:
      return in->ConsumeFloatingPoint<double>();  // any finite double
    default:
      // Mostly in or near the joint's range, so that the geometry gets exercised too.
      if (joint != nullptr && std::isfinite(joint->lower) && std::isfinite(joint->upper)) {
        const double margin = 0.1 * (joint->upper - joint->lower);
        return in->ConsumeFloatingPointInRange<double>(joint->lower - margin,
                                                       joint->upper + margin);
      }
      return in->ConsumeFloatingPointInRange<double>(-4.0, 4.0);
  }
}

// CycleReport's contract (monitor/monitor.h).
void CheckReport(const CycleReport& report, std::uint64_t expected_cycle) {
  Require(report.cycle == expected_cycle);
  if (report.input != InputStatus::kOk || !report.warnings.empty()) Require(report.stop);
  for (std::size_t k = 0; k < report.warnings.size(); ++k) {
    const Warning& w = report.warnings[k];
    Require(w.a < w.b);
    Require(std::isfinite(w.distance_m) && w.distance_m >= 0.0 &&
            (w.distance_m < w.threshold_m || w.distance_m == 0.0));
    Require(w.p_WA.allFinite() && w.p_WB.allFinite());
    if (k > 0) {
      const Warning& v = report.warnings[k - 1];
      Require(v.a < w.a || (v.a == w.a && v.b < w.b));
    }
  }
}

// Check() answers on a copy of the live model: for the q just applied it must agree exactly
// (unless tolerances depend on the speed, which the copy does not share). A check has no step:
// an accepted q gives the live warnings at the sample (not the step's between-samples ones,
// nor an input_jumped stop), a refused one the live warnings kept.
void CheckAgainstCheck(const Monitor& monitor, const Eigen::VectorXd& q) {
  const CycleReport& live = monitor.report();
  const CycleReport copy = monitor.Check(q);
  std::vector<const Warning*> expected;
  for (const Warning& w : live.warnings) {
    if (live.input != InputStatus::kOk || !w.between_samples) expected.push_back(&w);
  }
  Require(copy.input == live.input);
  Require(copy.stop == (live.input != InputStatus::kOk || !expected.empty()));
  Require(copy.warnings.size() == expected.size());
  for (std::size_t k = 0; k < expected.size(); ++k) {
    Require(copy.warnings[k].a == expected[k]->a && copy.warnings[k].b == expected[k]->b);
  }
}

}  // namespace
}  // namespace arm_collision_monitor

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace arm_collision_monitor;
  const Fixture& fixture = BundledWorkcell();
  const std::vector<std::string>& names = fixture.workcell->joint_names;
  const KinematicModel& model = fixture.workcell->kinematics;
  std::vector<const JointSpec*> joint_of(names.size(), nullptr);
  for (int link = 1; link < model.link_count(); ++link) {
    const int i = model.joint(link).q_index;
    if (i >= 0 && i < static_cast<int>(names.size())) joint_of[i] = &model.joint(link);
  }

  FuzzedDataProvider in(data, size);
  Monitor monitor(fixture.workcell, fixture.options);
  JointMerger input(names, kInputTimeout_s);
  StopPolicy policy(kStopHold_s);
  std::uint64_t cycles = 0;
  ros::Time now(1000, 0);
  sensor_msgs::JointState msg;
  for (int m = 0; m < kMaxMessages && in.remaining_bytes() > 0; ++m) {
    // Receive time: mostly forward by about one cycle, sometimes a jump either way.
    const int clock = in.ConsumeIntegralInRange<int>(0, 15);
    double now_s = now.toSec() + (clock == 0 ? -in.ConsumeFloatingPointInRange(0.0, 100.0)
                                 : clock == 1 ? in.ConsumeFloatingPointInRange(0.0, 100.0)
                                              : 0.05);
    now_s = std::max(now_s, 1.0);
    now = ros::Time(now_s);
    if (policy.ObserveClock(now.toSec()) > 0.0) {  // as the node's ClockNow()
      input.OnTimeWentBackwards(now.toSec());
      // Every joint received before the jump awaits input of the new timeline: stale.
      if (input.OldestJoint() >= 0) Require(input.IsStale(now.toSec()));
    }

    if (in.ConsumeIntegralInRange<int>(0, 9) == 0) {
      // A raw joint vector of any size straight into the Monitor (its own validation).
      const int n = in.ConsumeIntegralInRange<int>(0, static_cast<int>(names.size()) + 2);
      Eigen::VectorXd q(n);
      for (int i = 0; i < n; ++i) {
        q[i] = ConsumePosition(&in, i < static_cast<int>(names.size()) ? joint_of[i] : nullptr);
      }
      const CycleReport& report = monitor.Update(q);
      CheckReport(report, ++cycles);
      if (n != static_cast<int>(names.size())) Require(report.input == InputStatus::kWrongSize);
      continue;
    }

    // A JointState message. The stamp is set field by field as deserialisation does, so it may
    // be anything, including an nsec >= 10^9.
    msg.header.stamp.sec = 0;
    msg.header.stamp.nsec = 0;
    switch (in.ConsumeIntegralInRange<int>(0, 3)) {
      case 0:
        break;  // zero: "unknown", replaced by the receive time
      case 1:
        msg.header.stamp.sec = in.ConsumeIntegral<std::uint32_t>();
        msg.header.stamp.nsec = in.ConsumeIntegral<std::uint32_t>();
        break;
      default:
        msg.header.stamp =
            ros::Time(std::max(0.0, now.toSec() - in.ConsumeFloatingPointInRange(-0.2, 1.0)));
    }
    const int entries = in.ConsumeIntegralInRange<int>(0, kMaxEntries);
    msg.name.clear();
    std::vector<int> index_of_entry;
    for (int k = 0; k < entries; ++k) {
      if (!names.empty() && in.ConsumeIntegralInRange<int>(0, 7) != 0) {
        const int i = in.ConsumeIntegralInRange<int>(0, static_cast<int>(names.size()) - 1);
        msg.name.push_back(names[i]);
        index_of_entry.push_back(i);
      } else {
        msg.name.push_back(in.ConsumeRandomLengthString(16));
        index_of_entry.push_back(-1);
      }
    }
    // Usually one position per name; sometimes a different count.
    const int positions = in.ConsumeIntegralInRange<int>(0, 9) == 0
                              ? in.ConsumeIntegralInRange<int>(0, kMaxEntries)
                              : entries;
    msg.position.resize(positions);
    for (int k = 0; k < positions; ++k) {
      const int i = k < entries ? index_of_entry[k] : -1;
      msg.position[k] = ConsumePosition(&in, i >= 0 ? joint_of[i] : nullptr);
    }

    if (in.ConsumeIntegralInRange<int>(0, 15) == 0) {
      Eigen::VectorXd q_copy;
      const Eigen::VectorXd q_before = input.q();
      input.MergeIntoCopy(ToNamedPositions(msg), &q_copy);
      Require(input.q() == q_before);  // the live state is not touched
      continue;
    }
    const NamedPositions named = ToNamedPositions(msg);
    const MergeStatus status = input.Merge(named, now.toSec());
    // Names without positions: ignored, no cycle (MonitorNode::OnJointState).
    if (status == MergeStatus::kNoPositions) {
      Require(msg.position.empty() && !msg.name.empty());
      continue;
    }
    const std::string why =
        status == MergeStatus::kAccepted ? std::string()
                                         : input.DescribeRefusal(named, status, now.toSec());
    Require(status != MergeStatus::kNonFinite || why.rfind("joint '", 0) == 0);
    if (!policy.BeginCycle(status, why, input)) {
      // Refused or incomplete: the node requests a stop without running the Monitor.
      policy.EndCycle(now.toSec());
      Require(policy.stop() && policy.status() != SafetyStatus::kOk && !policy.reason().empty());
      continue;
    }
    // Accepted input is finite: the merge refuses non-finite positions of model joints.
    Require(input.q().allFinite());
    // Each joint dated by the message that gave it, as the node does.
    const std::vector<double>& stamps = input.joint_stamps();
    const CycleReport& report = monitor.Update(
        input.q(), Eigen::Map<const Eigen::VectorXd>(stamps.data(),
                                                     static_cast<Eigen::Index>(stamps.size())));
    CheckReport(report, ++cycles);
    Require(report.input != InputStatus::kNonFinite && report.input != InputStatus::kWrongSize);
    const std::string refusal =
        report.input == InputStatus::kOk ? std::string() : monitor.DescribeRefusal(input.q());
    policy.OnCycleReport(report, refusal, fixture.workcell->primitives, input, now.toSec());
    policy.EndCycle(now.toSec());
    if (report.stop || input.IsStale(now.toSec())) Require(policy.stop());
    if (!fixture.options.speed_scaled_tolerance && in.ConsumeIntegralInRange<int>(0, 7) == 0) {
      CheckAgainstCheck(monitor, input.q());
    }
  }
  Require(monitor.refused_inputs() <= cycles);
  return 0;
}
