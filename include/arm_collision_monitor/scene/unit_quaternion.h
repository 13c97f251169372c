// The quaternion policy of poses read from outside: the planning-scene readers' (the YAML reader
// and the scene geometry text reader, planning_scene_reader.h) and the node's live-object
// services'.
#pragma once

#include <cmath>
#include <string>

#include <Eigen/Geometry>

#include "arm_collision_monitor/core/constants.h"

namespace arm_collision_monitor {

/// Quaternion [x, y, z, w] of norm within kQuaternionUnitNormTolerance of 1, normalised into
/// `q`: returns "". Otherwise (zero, or a norm farther from 1; NaN too) returns what is wrong,
/// for the caller's message, and leaves `q` alone.
inline std::string ToUnitQuaternion(const Eigen::Vector4d& xyzw, Eigen::Quaterniond* q) {
  const double norm = xyzw.norm();
  if (norm == 0.0) {
    return "a zero quaternion is not a rotation (expected a unit quaternion; write w = 1 for "
           "none)";
  }
  if (!(std::abs(norm - 1.0) <= kQuaternionUnitNormTolerance)) {
    return "quaternion norm " + std::to_string(norm) +
           " is not 1 (expected a unit quaternion [x, y, z, w])";
  }
  *q = Eigen::Quaterniond(xyzw[3], xyzw[0], xyzw[1], xyzw[2]).normalized();
  return "";
}

}  // namespace arm_collision_monitor
