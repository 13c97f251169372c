// Frames the peers need for our primitives: FCL and Bullet describe a capsule in its own frame C
// (centre at the origin, axis along z), not by its two end points.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "arm_collision_monitor/geometry/primitives.h"

namespace arm_collision_monitor {

/// Pose X_WC of a capsule's frame C (origin at the segment's midpoint, z along p0 -> p1) and
/// the segment length in metres. A zero-length segment (a sphere) gets R_WC = identity.
struct CapsuleFrame {
  Eigen::Isometry3d X_WC = Eigen::Isometry3d::Identity();
  double length_m = 0.0;
};

inline CapsuleFrame ComputeCapsuleFrame(const Capsule& capsule) {
  CapsuleFrame frame;
  const Eigen::Vector3d axis_W = capsule.p1_W - capsule.p0_W;
  frame.length_m = axis_W.norm();
  frame.X_WC.translation() = 0.5 * (capsule.p0_W + capsule.p1_W);
  if (frame.length_m > 0.0) {
    frame.X_WC.linear() =
        Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), axis_W).toRotationMatrix();
  }
  return frame;
}

}  // namespace arm_collision_monitor
