#include "solid_shapes.h"

#include <cmath>

namespace arm_collision_monitor {

std::pair<Eigen::Vector3d, Eigen::Vector3d> CylinderAxisEnds_L(const Eigen::Isometry3d& X_LC,
                                                              double length_m) {
  const Eigen::Vector3d half_axis_C(0.0, 0.0, 0.5 * length_m);
  return {X_LC * (-half_axis_C), X_LC * half_axis_C};
}

Shape SphereShape_L(const Eigen::Isometry3d& X_LS, double radius_m) {
  return Capsule{X_LS.translation(), X_LS.translation(), radius_m};
}

Shape CapsuleShape_L(const Eigen::Isometry3d& X_LC, double radius_m, double length_m) {
  const auto [end0_L, end1_L] = CylinderAxisEnds_L(X_LC, length_m);
  return Capsule{end0_L, end1_L, radius_m};
}

Shape CylinderShape_L(const Eigen::Isometry3d& X_LC, double radius_m, double length_m,
                      CylinderModel model) {
  // Volumes: the box 4 r^2 L, the capsule pi r^2 L + 4/3 pi r^3; the box is the smaller when
  // (4 - pi) L < 4/3 pi r.
  const bool is_box_smaller = (4.0 - M_PI) * length_m < 4.0 / 3.0 * M_PI * radius_m;
  if (model == CylinderModel::kBox || (model == CylinderModel::kTighter && is_box_smaller)) {
    return Box{X_LC, Eigen::Vector3d(radius_m, radius_m, 0.5 * length_m)};
  }
  return CapsuleShape_L(X_LC, radius_m, length_m);
}

}  // namespace arm_collision_monitor
