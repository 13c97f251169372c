// Distances between primitives: the narrow phase. Each routine's comment states its error
// bound and the algorithm it follows; test/core/test_geometry_distance.cpp (degenerate families)
// and test/core/test_geometry_stress.cpp (against an extended-precision reference) pin both.
//
// Error bounds are stated for the distance, in metres, as ulps * eps * S (+ a 1e-150 m floor),
// eps = 2^-53 and S the local length scale of the query: the largest of the distance between
// the shapes' reference points (capsule p0_W, box centre), the segment lengths, box diagonals and
// radii (core/constants.h: kSegmentDistanceErrorUlps, kBoxDistanceErrorUlps). The distance does
// not depend on the distance from the origin: differences are taken between nearby inputs first.
// Witness points are absolute coordinates and add a rounding of a few eps * |coordinate|.
// Preconditions: finite inputs with |coordinates|, lengths and radii <= kMaxSupportedCoordinate_m
// (1e60 m), radii and half extents >= 0, rotations orthonormal. Nothing allocates or throws.
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
/// p0 + s (p1 - p0) and q0 + t (q1 - q0) are a closest pair (Ericson §5.1.9, cross-product form).
/// Zero-length, parallel, collinear and crossing segments are handled; distance error <=
/// kSegmentDistanceErrorUlps * eps * S.
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

/// Capsule-capsule: the axes' closest pair pushed out by the radii. When the capsules overlap
/// (or touch), p_WA = p_WB is a point common to both. Error <= kSegmentDistanceErrorUlps * eps * S.
DistanceResult CapsuleCapsuleDistance(const Capsule& a, const Capsule& b);
/// Capsule-box, exact (axis-box minimisation in the box frame). Overlap: p_WA = p_WB common to
/// both. Error <= kBoxDistanceErrorUlps * eps * S.
DistanceResult CapsuleBoxDistance(const Capsule& a, const Box& b);
/// Box-box, exact (every edge of each box against the other box). Overlap: p_WA = p_WB common to
/// both. Error <= kBoxDistanceErrorUlps * eps * S.
DistanceResult BoxBoxDistance(const Box& a, const Box& b);

/// Distance between any two primitives (dispatches to the routines above; the witnesses keep
/// the argument order: p_WA is on `a`).
DistanceResult ShapeDistance(const Shape& a, const Shape& b);

/// True iff the surfaces of `a` and `b` are closer than `threshold_m` (strictly). Exits early:
/// the AABBs grown by the threshold are tested first, then the cheapest exact test per pair.
/// Agrees with ShapeDistance(a, b).distance_m < threshold_m except within the stated error
/// bound (plus a few eps * |coordinate| for the AABB test) of the threshold. False for
/// threshold_m <= 0. Fail safe: true when the threshold or any coordinate, extent or radius is
/// NaN or infinite (ShapeDistance gives no meaningful answer for such input).
bool IsCloserThan(const Shape& a, const Shape& b, double threshold_m);

}  // namespace arm_collision_monitor
