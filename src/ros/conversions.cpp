#include "arm_collision_monitor/ros/conversions.h"

#include "arm_collision_monitor/MonitorReport.h"

namespace arm_collision_monitor {

std::uint8_t WarningSeverity(double distance_m, double threshold_m) {
  if (distance_m <= 0.0) {
    return CollisionWarning::SEVERITY_CONTACT;
  }
  if (distance_m < 0.5 * threshold_m) {
    return CollisionWarning::SEVERITY_CRITICAL;
  }
  return CollisionWarning::SEVERITY_WARNING;
}

void ToWarningMsg(const Workcell& workcell, const Warning& in, CollisionWarning* out) {
  const PrimitiveSpec& a = workcell.primitives[in.a];
  const PrimitiveSpec& b = workcell.primitives[in.b];
  out->primitive_a = in.a;
  out->primitive_a_name = a.name;
  out->owner_a = a.owner;
  out->primitive_b = in.b;
  out->primitive_b_name = b.name;
  out->owner_b = b.owner;
  out->distance_m = in.distance_m;
  out->threshold_m = in.threshold_m;
  out->point_a.x = in.p_WA.x();
  out->point_a.y = in.p_WA.y();
  out->point_a.z = in.p_WA.z();
  out->point_b.x = in.p_WB.x();
  out->point_b.y = in.p_WB.y();
  out->point_b.z = in.p_WB.z();
  out->severity = WarningSeverity(in.distance_m, in.threshold_m);
}

std::uint8_t ToInputStatusMsg(InputStatus status) {
  switch (status) {
    case InputStatus::kOk:
      return MonitorReport::INPUT_OK;
    case InputStatus::kWrongSize:
      return MonitorReport::INPUT_WRONG_SIZE;
    case InputStatus::kNonFinite:
      return MonitorReport::INPUT_NON_FINITE;
    case InputStatus::kOutOfLimits:
      return MonitorReport::INPUT_OUT_OF_LIMITS;
  }
  return MonitorReport::INPUT_WRONG_SIZE;
}

std::uint8_t ToInputStatusMsg(MergeStatus status) {
  // MergeStatus values are defined equal to the message's constants.
  return static_cast<std::uint8_t>(status);
}

const char* InputStatusMsgName(std::uint8_t input_status) {
  switch (input_status) {
    case MonitorReport::INPUT_OK:
      return "ok";
    case MonitorReport::INPUT_WRONG_SIZE:
      return "wrong_size";
    case MonitorReport::INPUT_NON_FINITE:
      return "non_finite";
    case MonitorReport::INPUT_OUT_OF_LIMITS:
      return "out_of_limits";
    case MonitorReport::INPUT_INCOMPLETE:
      return "incomplete";
    case MonitorReport::INPUT_STALE:
      return "stale";
    case MonitorReport::INPUT_STAMP_BACKWARDS:
      return "stamp_backwards";
    case MonitorReport::INPUT_NO_KNOWN_JOINTS:
      return "no_known_joints";
    case MonitorReport::INPUT_FUTURE_STAMP:
      return "future_stamp";
    default:
      return "unknown";
  }
}

}  // namespace arm_collision_monitor
