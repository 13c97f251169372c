// Shape builders and an independent containment test shared by the geometry, scene and fuzz tests.
#pragma once

#include <algorithm>
#include <variant>

#include <Eigen/Core>
#include <Eigen/Geometry>

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

/// Whether p lies in the closed capsule or box: plain double arithmetic, independent of the
/// distance routines and of the loader's own check (callers test fits whose margin,
/// kMeshFitMarginRel times the mesh's scale, is far above this test's rounding).
inline bool InShape(const Shape& shape, const Eigen::Vector3d& p) {
  if (const auto* c = std::get_if<Capsule>(&shape)) {
    const Eigen::Vector3d d = c->p1_W - c->p0_W;
    double s = d.squaredNorm() > 0.0 ? (p - c->p0_W).dot(d) / d.squaredNorm() : 0.0;
    s = std::min(1.0, std::max(0.0, s));
    return (p - c->p0_W - s * d).norm() <= c->radius_m;
  }
  const Box& b = std::get<Box>(shape);
  const Eigen::Vector3d q = b.X_WB.inverse() * p;
  return (q.cwiseAbs().array() <= b.half_extents_m.array()).all();
}

}  // namespace arm_collision_monitor
