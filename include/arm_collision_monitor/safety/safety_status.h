// A cycle's input verdict, shared by the joint merger and the stop policy.
#pragma once

#include <cstdint>

namespace arm_collision_monitor {

/// A cycle's input verdict; the values equal MonitorReport's INPUT_* constants (the node passes
/// them through), and MergeStatus's where they overlap.
enum class SafetyStatus : std::uint8_t {
  kOk = 0,
  kWrongSize = 1,       ///< lengths differ, a name twice, or q not one per model joint
  kNonFinite = 2,       ///< a NaN or inf position of a model joint
  kOutOfLimits = 3,     ///< the Monitor refused q: outside a joint's limits (beyond the margin)
  kIncomplete = 4,      ///< some model joint was never received
  kStale = 5,           ///< a joint's newest input, or the message stamp, older than the timeout
  kStampBackwards = 6,  ///< older than the last accepted stamp of one of its joints
  kNoKnownJoints = 7,   ///< the message named no joint of the model
  kFutureStamp = 8,     ///< stamped further ahead of now than the input timeout
};
constexpr int kSafetyStatusCount = static_cast<int>(SafetyStatus::kFutureStamp) + 1;

/// Short lower-case name ("ok", "wrong_size", ...), for logs, reasons and diagnostics.
const char* SafetyStatusName(SafetyStatus status);

}  // namespace arm_collision_monitor
