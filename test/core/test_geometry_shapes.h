// Shape builders shared by the geometry tests.
#pragma once

#include <Eigen/Core>

#include "arm_collision_monitor/geometry/primitives.h"

namespace arm_collision_monitor {

/// The capsule of radius `radius_m` around the segment p0_W--p1_W (world frame, metres).
inline Capsule MakeCapsule(const Eigen::Vector3d& p0_W, const Eigen::Vector3d& p1_W,
                           double radius_m) {
  Capsule c;
  c.p0_W = p0_W;
  c.p1_W = p1_W;
  c.radius_m = radius_m;
  return c;
}

}  // namespace arm_collision_monitor
