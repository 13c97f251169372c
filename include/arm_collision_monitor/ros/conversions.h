// Translation between the package's messages and the core's plain types.
#pragma once

#include <cstdint>
#include <string>

#include <Eigen/Geometry>
#include <geometry_msgs/Transform.h>
#include <sensor_msgs/JointState.h>

#include "arm_collision_monitor/CollisionWarning.h"
#include "arm_collision_monitor/monitor/monitor.h"
#include "arm_collision_monitor/safety/joint_merger.h"
#include "arm_collision_monitor/safety/stop_policy.h"

namespace arm_collision_monitor {

/// Fills `out` from core warning `in`; names come from `primitives` (indexed by primitive id:
/// the Monitor's, live objects included, see Monitor::primitive). Reuses `out`'s string
/// capacity.
void ToWarningMsg(const std::vector<PrimitiveSpec>& primitives, const Warning& in,
                  CollisionWarning* out);

/// Severity per CollisionWarning's SEVERITY_* constants.
std::uint8_t WarningSeverity(double distance_m, double threshold_m);

/// MonitorReport::INPUT_* for a safety status (equal values).
std::uint8_t ToInputStatusMsg(SafetyStatus status);

/// A TF transform as a rigid pose into `X`: its quaternion normalised (tf2 keeps one whose
/// squared norm is within 0.01 of 1, and multiplies them along a chain of frames; as it is, its
/// matrix would stretch or shrink the shapes it places). Returns "", else what is wrong (a zero
/// or non-finite quaternion, a non-finite translation), leaving `X` alone.
std::string ToRigidTransform(const geometry_msgs::Transform& transform, Eigen::Isometry3d* X);

/// A rigid pose as a geometry_msgs/Transform (ToRigidTransform's inverse).
geometry_msgs::Transform ToTransformMsg(const Eigen::Isometry3d& X);

/// The merger's view of `msg` (borrows its arrays: valid while `msg` lives); the stamp in
/// seconds, 0 when unset.
inline NamedPositions ToNamedPositions(const sensor_msgs::JointState& msg) {
  return NamedPositions{msg.name, msg.position, msg.header.stamp.toSec()};
}

}  // namespace arm_collision_monitor
