#include "arm_collision_monitor/safety/safety_status.h"

namespace arm_collision_monitor {

const char* SafetyStatusName(SafetyStatus status) {
  switch (status) {
    case SafetyStatus::kOk:
      return "ok";
    case SafetyStatus::kWrongSize:
      return "wrong_size";
    case SafetyStatus::kNonFinite:
      return "non_finite";
    case SafetyStatus::kOutOfLimits:
      return "out_of_limits";
    case SafetyStatus::kIncomplete:
      return "incomplete";
    case SafetyStatus::kStale:
      return "stale";
    case SafetyStatus::kStampBackwards:
      return "stamp_backwards";
    case SafetyStatus::kNoKnownJoints:
      return "no_known_joints";
    case SafetyStatus::kFutureStamp:
      return "future_stamp";
  }
  return "unknown";
}

}  // namespace arm_collision_monitor
