// Translation between the core's cycle results and the package's messages.
#pragma once

#include <cstdint>

#include "arm_collision_monitor/CollisionWarning.h"
#include "arm_collision_monitor/monitor/monitor.h"
#include "arm_collision_monitor/ros/joint_state_input.h"

namespace arm_collision_monitor {

/// Fills `out` from core warning `in`; names come from `workcell` (which primitive ids index).
/// Reuses `out`'s string capacity.
void ToWarningMsg(const Workcell& workcell, const Warning& in, CollisionWarning* out);

/// Severity per CollisionWarning's SEVERITY_* constants.
std::uint8_t WarningSeverity(double distance_m, double threshold_m);

/// MonitorReport::INPUT_* for a status of the core or of the input merger.
std::uint8_t ToInputStatusMsg(InputStatus status);
std::uint8_t ToInputStatusMsg(MergeStatus status);

/// Short lower-case name of a MonitorReport::INPUT_* value, for logs and diagnostics.
const char* InputStatusMsgName(std::uint8_t input_status);

}  // namespace arm_collision_monitor
