#include "arm_collision_monitor/geometry/primitives.h"

#include <algorithm>
#include <cmath>

namespace arm_collision_monitor {

Shape TransformShape(const Eigen::Isometry3d& X_WL, const Shape& shape_L) {
  if (const auto* capsule = std::get_if<Capsule>(&shape_L)) {
    return Capsule{X_WL * capsule->p0_W, X_WL * capsule->p1_W, capsule->radius_m};
  }
  // X_WL * X_LB written out (Eigen's general transform product is a call; this runs for every
  // moved box each cycle).
  const Box& box = std::get<Box>(shape_L);
  Box out{Eigen::Isometry3d::Identity(), box.half_extents_m};
  out.X_WB.linear().noalias() = X_WL.linear() * box.X_WB.linear();
  out.X_WB.translation().noalias() = X_WL.linear() * box.X_WB.translation();
  out.X_WB.translation() += X_WL.translation();
  return out;
}

double MaxDistanceFromPoint_m(const Shape& shape, const Eigen::Vector3d& p) {
  if (const auto* capsule = std::get_if<Capsule>(&shape)) {
    return std::max((capsule->p0_W - p).norm(), (capsule->p1_W - p).norm()) + capsule->radius_m;
  }
  const Box& box = std::get<Box>(shape);
  // The farthest point of a box from p is the vertex opposite p in every axis.
  const Eigen::Vector3d p_B = box.X_WB.inverse(Eigen::Isometry) * p;
  return (p_B.cwiseAbs() + box.half_extents_m).norm();
}

double MaxDistanceFromAxis_m(const Shape& shape, const Eigen::Vector3d& axis) {
  // The distance from a line is convex: largest at an endpoint of a segment, a vertex of a box.
  if (const auto* capsule = std::get_if<Capsule>(&shape)) {
    return std::max(capsule->p0_W.cross(axis).norm(), capsule->p1_W.cross(axis).norm()) +
           capsule->radius_m;
  }
  const Box& box = std::get<Box>(shape);
  double farthest_m = 0.0;
  for (int vertex = 0; vertex < 8; ++vertex) {
    farthest_m = std::max(farthest_m, (box.X_WB * box.Vertex_B(vertex)).cross(axis).norm());
  }
  return farthest_m;
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
