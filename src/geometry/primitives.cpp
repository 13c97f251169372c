#include "arm_collision_monitor/geometry/primitives.h"

namespace arm_collision_monitor {

Shape TransformShape(const Eigen::Isometry3d& X_WL, const Shape& shape_L) {
  if (const auto* capsule = std::get_if<Capsule>(&shape_L)) {
    return Capsule{X_WL * capsule->p0_W, X_WL * capsule->p1_W, capsule->radius_m};
  }
  const Box& box = std::get<Box>(shape_L);
  return Box{X_WL * box.X_WB, box.half_extents_m};
}

Eigen::Isometry3d PoseFromXyzRpy(const Eigen::Vector3d& p_WF_m, const Eigen::Vector3d& rpy_rad) {
  Eigen::Isometry3d X_WF = Eigen::Isometry3d::Identity();
  X_WF.linear() = (Eigen::AngleAxisd(rpy_rad.z(), Eigen::Vector3d::UnitZ()) *
                   Eigen::AngleAxisd(rpy_rad.y(), Eigen::Vector3d::UnitY()) *
                   Eigen::AngleAxisd(rpy_rad.x(), Eigen::Vector3d::UnitX()))
                      .toRotationMatrix();
  X_WF.translation() = p_WF_m;
  return X_WF;
}

}  // namespace arm_collision_monitor
