// Distances between primitives: the narrow phase. Each routine's comment states its error
// bound and the algorithm it follows; test/core/test_distance*.cpp pins both.
#pragma once

#include "arm_collision_monitor/geometry/primitives.h"

namespace arm_collision_monitor {

/// Result of a distance query between shapes A and B.
struct DistanceResult {
  /// Distance between the surfaces in metres; 0 when the shapes touch or overlap.
  double distance_m = 0.0;
  /// Closest points (witnesses) on A and on B, in W. When the shapes overlap, both are a point
  /// inside the overlap or on the deepest features (see each routine).
  Eigen::Vector3d p_WA = Eigen::Vector3d::Zero();
  Eigen::Vector3d p_WB = Eigen::Vector3d::Zero();
};

/// Closest points between segments p0--p1 and q0--q1: parameters s, t in [0, 1] such that
/// p0 + s (p1 - p0) and q0 + t (q1 - q0) are a closest pair. See distance.cpp for the bound.
struct SegmentClosestPoints {
  double s = 0.0;
  double t = 0.0;
  Eigen::Vector3d p_W = Eigen::Vector3d::Zero();
  Eigen::Vector3d q_W = Eigen::Vector3d::Zero();
  double distance_m = 0.0;
};
SegmentClosestPoints SegmentSegmentClosestPoints(const Eigen::Vector3d& p0_W,
                                                 const Eigen::Vector3d& p1_W,
                                                 const Eigen::Vector3d& q0_W,
                                                 const Eigen::Vector3d& q1_W);

DistanceResult CapsuleCapsuleDistance(const Capsule& a, const Capsule& b);
DistanceResult CapsuleBoxDistance(const Capsule& a, const Box& b);
DistanceResult BoxBoxDistance(const Box& a, const Box& b);

/// Distance between any two primitives (dispatches to the routines above; the witnesses keep
/// the argument order: p_WA is on `a`).
DistanceResult ShapeDistance(const Shape& a, const Shape& b);

/// True iff the surfaces of `a` and `b` are closer than `threshold_m` (strictly). Exits early:
/// the AABBs grown by the threshold are tested first, then the cheapest exact test per pair.
/// Must agree with ShapeDistance(a, b).distance_m < threshold_m up to the stated error bound.
bool IsCloserThan(const Shape& a, const Shape& b, double threshold_m);

}  // namespace arm_collision_monitor
