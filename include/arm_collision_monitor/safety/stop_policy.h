// The stop policy (README "Stop policy"): decides, every cycle and on every staleness check,
// whether the arms must stop and why, from plain values -- the input merger's state, the
// Monitor's cycle report, object pose failures and the clock. ROS-free: the node only feeds it
// and publishes its decision. A stop is requested while any of these holds:
//   - some model joint was never received (start-up: stop until the model is complete);
//   - the last input message was refused (wrong size, non-finite, out of limits, stamp going
//     backwards, stamped further than the input timeout from now, no model joint);
//   - some joint's newest input was received longer ago than the input timeout;
//   - the clock went back (simulated time: a looping bag, a simulator reset) and some joint has
//     not been received since (every time-derived state is re-based on the jump);
//   - a frame-bound scene object's pose could not be looked up;
//   - the last cycle's step was larger than max_step_m ("input jumped");
//   - the last cycle reported a warning (at its q or between it and the last, swept check).
// It is cleared by the first cycle on accepted, complete, fresh input with no warning that comes
// at least the hold time after the condition was last seen (no chattering on a pair hovering at
// its threshold).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "arm_collision_monitor/monitor/monitor.h"
#include "arm_collision_monitor/safety/joint_merger.h"
#include "arm_collision_monitor/safety/safety_status.h"
#include "arm_collision_monitor/scene/workcell.h"

namespace arm_collision_monitor {

SafetyStatus ToSafetyStatus(InputStatus status);

/// The longest stop reason, in bytes with its end (reserved once, so the cycle never allocates;
/// a longer one is cut).
constexpr std::size_t kReasonCapacity = 384;

/// The stop reason of a cycle's `warnings` (not empty), naming the pair deepest in its tolerance
/// zone by `primitives`: "N warning(s), the deepest a - b at d m (threshold t m)", and where
/// between samples; written into `text` (`size` bytes, cut there), without allocating.
void FormatWarningsReason(const std::vector<Warning>& warnings,
                          const std::vector<PrimitiveSpec>& primitives, char* text,
                          std::size_t size);

/// What a staleness check found.
struct StaleCheck {
  bool is_stale = false;
  bool is_new_episode = false;  ///< the first check of this stale episode
};

class StopPolicy {
 public:
  /// `stop_hold_s` >= 0: minimum duration of a requested stop. Starts stopped ("waiting for
  /// joint states") until a clean cycle.
  explicit StopPolicy(double stop_hold_s);

  /// Reads the clock (s): returns how far it went back since the last reading (0: it did not),
  /// and then re-bases the hold on `now_s` (a deadline of the old timeline would lie in the
  /// future). The caller re-bases its other time-derived state (JointMerger::OnTimeWentBackwards).
  double ObserveClock(double now_s);

  /// Starts a cycle's evaluation. `pending` is the first refusal of the merger since the last
  /// cycle (kAccepted: none). True when the Monitor may run on input.q(); false when the input
  /// alone already decides the stop (refused, or the model incomplete).
  /// `pending_why`: what in the message was refused (JointMerger::DescribeRefusal; "" if
  /// nothing more), added to the reason.
  bool BeginCycle(MergeStatus pending, const std::string& pending_why, const JointMerger& input);
  /// A frame-bound object's pose could not be had this cycle.
  void OnObjectPoseUnavailable(const std::string& object, const std::string& frame,
                               const std::string& error);
  /// The Monitor's report of this cycle (with `refusal`, Monitor::DescribeRefusal's text when
  /// it refused q, added to the reason), the primitives it names, and the input's staleness at
  /// `now_s`.
  void OnCycleReport(const CycleReport& report, const std::string& refusal,
                     const std::vector<PrimitiveSpec>& primitives, const JointMerger& input,
                     double now_s);
  /// Ends the cycle at `now_s`: applies the hold; see stop(), reason(), status().
  void EndCycle(double now_s);

  /// Between cycles (a timer): a stale complete input requests a stop at once.
  StaleCheck CheckStaleness(const JointMerger& input, double now_s);

  bool stop() const { return stop_; }
  /// The condition that requested the current stop ("" when stop() is false); once it is no
  /// longer seen and the stop is only held, it says so.
  const std::string& reason() const { return reason_; }
  /// This cycle's input verdict (kStale after a stale CheckStaleness()).
  SafetyStatus status() const { return status_; }
  double hold_until_s() const { return hold_until_s_; }

 private:
  /// Conditions, by rank: a higher one found in the same cycle replaces a lower one.
  enum class Rank : std::uint8_t { kNone, kWarning, kJumped, kObjectPose, kStale, kRefused };
  void Raise(Rank rank, SafetyStatus status, const char* format, ...)
      __attribute__((format(printf, 4, 5)));
  void RaiseRefused(SafetyStatus status, const std::string& why);
  void RaiseStale(const JointMerger& input, double now_s);

  double stop_hold_s_;
  double hold_until_s_ = 0.0;
  double last_now_s_ = 0.0;  ///< the latest ObserveClock() reading
  bool stop_ = true;
  bool is_stale_episode_ = false;
  bool is_held_ = false;  ///< the stop's condition is gone, the hold keeps it
  std::string reason_;
  std::string condition_;  ///< this cycle's condition ("" none)
  Rank rank_ = Rank::kNone;
  SafetyStatus status_ = SafetyStatus::kOk;
};

}  // namespace arm_collision_monitor
