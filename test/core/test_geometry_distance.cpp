// The degenerate families of the distance routines, one by one, against distances derived by
// hand (each expected value is in the comment or the expression next to it). The seeded random
// and extended-precision checks are in test_geometry_stress.cpp.
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "arm_collision_monitor/geometry/distance.h"
#include "test_geometry_shapes.h"

namespace arm_collision_monitor {
namespace {

using Eigen::Vector3d;

// Hand-derived values here are exact or within a few ulps of 1 m.
constexpr double kTol_m = 1e-14;

Box MakeBox(const Vector3d& centre_W, const Vector3d& half_extents_m,
            const Eigen::Quaterniond& q_WB = Eigen::Quaterniond::Identity()) {
  Box b;
  b.X_WB = Eigen::Isometry3d::Identity();
  b.X_WB.linear() = q_WB.toRotationMatrix();
  b.X_WB.translation() = centre_W;
  b.half_extents_m = half_extents_m;
  return b;
}

bool AllFinite(const DistanceResult& r) {
  return std::isfinite(r.distance_m) && r.p_WA.allFinite() && r.p_WB.allFinite();
}

// Distance from a point to a box (clamping in the box frame), for witness checks.
double PointBoxDistance(const Vector3d& p_W, const Box& b) {
  const Vector3d p_B = b.X_WB.inverse(Eigen::Isometry) * p_W;
  return (p_B - p_B.cwiseMax(-b.half_extents_m).cwiseMin(b.half_extents_m)).norm();
}

// Signed distance of a point to a box surface: negative inside (for "on the surface" checks).
double PointBoxSignedDistance(const Vector3d& p_W, const Box& b) {
  const Vector3d p_B = b.X_WB.inverse(Eigen::Isometry) * p_W;
  const Vector3d q = p_B.cwiseAbs() - b.half_extents_m;
  return q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0);
}

// Distance from a point to a capsule's axis.
double PointAxisDistance(const Vector3d& p_W, const Capsule& c) {
  return SegmentSegmentClosestPoints(p_W, p_W, c.p0_W, c.p1_W).distance_m;
}

// ------------------------------------------------------------------------------------------
// Segment-segment

TEST(SegmentSegment, CrossingAxesAtRightAngle) {
  const SegmentClosestPoints c = SegmentSegmentClosestPoints(
      Vector3d(-1, 0, 0), Vector3d(1, 0, 0), Vector3d(0, -1, 0.5), Vector3d(0, 1, 0.5));
  EXPECT_NEAR(c.distance_m, 0.5, kTol_m);
  EXPECT_NEAR(c.s, 0.5, kTol_m);
  EXPECT_NEAR(c.t, 0.5, kTol_m);
  EXPECT_TRUE(c.p_W.isApprox(Vector3d(0, 0, 0), kTol_m) || c.p_W.norm() < kTol_m);
  EXPECT_NEAR((c.q_W - Vector3d(0, 0, 0.5)).norm(), 0.0, kTol_m);
}

TEST(SegmentSegment, CrossingAxesIntersectExactly) {
  const SegmentClosestPoints c = SegmentSegmentClosestPoints(
      Vector3d(-1, -1, 0), Vector3d(1, 1, 0), Vector3d(-1, 1, 0), Vector3d(1, -1, 0));
  EXPECT_NEAR(c.distance_m, 0.0, kTol_m);
  EXPECT_TRUE(c.p_W.allFinite() && c.q_W.allFinite());
  EXPECT_NEAR(c.p_W.norm(), 0.0, kTol_m);
}

TEST(SegmentSegment, ZeroLengthFirstSegmentIsPointToSegment) {
  const SegmentClosestPoints c = SegmentSegmentClosestPoints(
      Vector3d(0.3, 2, 0), Vector3d(0.3, 2, 0), Vector3d(0, 0, 0), Vector3d(1, 0, 0));
  EXPECT_NEAR(c.distance_m, 2.0, kTol_m);
  EXPECT_NEAR(c.t, 0.3, kTol_m);
  EXPECT_EQ(c.p_W, Vector3d(0.3, 2, 0));
}

TEST(SegmentSegment, ZeroLengthSecondSegmentBeyondEnd) {
  // The point (3, 4, 0) projects beyond the end (1, 0, 0) of segment (-1,0,0)-(1,0,0), so the
  // distance is |(3, 4, 0) - (1, 0, 0)| = sqrt(20).
  const SegmentClosestPoints c = SegmentSegmentClosestPoints(
      Vector3d(-1, 0, 0), Vector3d(1, 0, 0), Vector3d(3, 4, 0), Vector3d(3, 4, 0));
  EXPECT_NEAR(c.distance_m, std::sqrt(20.0), kTol_m);
  EXPECT_EQ(c.s, 1.0);
}

TEST(SegmentSegment, BothZeroLengthArePoints) {
  const SegmentClosestPoints c = SegmentSegmentClosestPoints(
      Vector3d(1, 2, 3), Vector3d(1, 2, 3), Vector3d(4, 6, 3), Vector3d(4, 6, 3));
  EXPECT_NEAR(c.distance_m, 5.0, kTol_m);
}

TEST(SegmentSegment, ParallelOverlappingInProjection) {
  const SegmentClosestPoints c = SegmentSegmentClosestPoints(
      Vector3d(0, 0, 0), Vector3d(1, 0, 0), Vector3d(0.5, 1, 0), Vector3d(2, 1, 0));
  EXPECT_NEAR(c.distance_m, 1.0, kTol_m);
  EXPECT_NEAR(c.p_W.y(), 0.0, kTol_m);
  EXPECT_NEAR(c.q_W.y(), 1.0, kTol_m);
  EXPECT_NEAR(c.p_W.x(), c.q_W.x(), kTol_m);
  EXPECT_GE(c.p_W.x(), 0.5 - kTol_m);
  EXPECT_LE(c.p_W.x(), 1.0 + kTol_m);
}

TEST(SegmentSegment, ParallelDisjointEndToEnd) {
  const SegmentClosestPoints c = SegmentSegmentClosestPoints(
      Vector3d(0, 0, 0), Vector3d(1, 0, 0), Vector3d(2, 1, 0), Vector3d(3, 1, 0));
  EXPECT_NEAR(c.distance_m, std::sqrt(2.0), kTol_m);
  EXPECT_EQ(c.s, 1.0);
  EXPECT_EQ(c.t, 0.0);
}

TEST(SegmentSegment, AntiParallelDisjointEndToEnd) {
  const SegmentClosestPoints c = SegmentSegmentClosestPoints(
      Vector3d(0, 0, 0), Vector3d(1, 0, 0), Vector3d(3, 1, 0), Vector3d(2, 1, 0));
  EXPECT_NEAR(c.distance_m, std::sqrt(2.0), kTol_m);
  EXPECT_EQ(c.s, 1.0);
  EXPECT_EQ(c.t, 1.0);
}

TEST(SegmentSegment, AntiParallelOverlapping) {
  const SegmentClosestPoints c = SegmentSegmentClosestPoints(
      Vector3d(0, 0, 0), Vector3d(2, 0, 0), Vector3d(3, 0, 0.75), Vector3d(1, 0, 0.75));
  EXPECT_NEAR(c.distance_m, 0.75, kTol_m);
}

TEST(SegmentSegment, CollinearOverlapping) {
  const SegmentClosestPoints c = SegmentSegmentClosestPoints(
      Vector3d(0, 0, 0), Vector3d(2, 0, 0), Vector3d(1, 0, 0), Vector3d(3, 0, 0));
  EXPECT_NEAR(c.distance_m, 0.0, kTol_m);
  EXPECT_NEAR((c.p_W - c.q_W).norm(), 0.0, kTol_m);
}

TEST(SegmentSegment, CollinearDisjoint) {
  const SegmentClosestPoints c = SegmentSegmentClosestPoints(
      Vector3d(0, 0, 0), Vector3d(1, 1, 1), Vector3d(2, 2, 2), Vector3d(5, 5, 5));
  EXPECT_NEAR(c.distance_m, std::sqrt(3.0), kTol_m);
  EXPECT_EQ(c.s, 1.0);
  EXPECT_EQ(c.t, 0.0);
}

TEST(SegmentSegment, NearlyParallel1em15RadNotCrossing) {
  // Segment 2 rises by 3e-15 over 3 m (angle 1e-15 rad); at x in [0, 1] its height is
  // 0.5 + 1e-15 (x + 1), least at x = 0.
  const SegmentClosestPoints c = SegmentSegmentClosestPoints(
      Vector3d(0, 0, 0), Vector3d(1, 0, 0), Vector3d(-1, 0.5, 0), Vector3d(2, 0.5 + 3e-15, 0));
  EXPECT_NEAR(c.distance_m, 0.5 + 1e-15, kTol_m);
  EXPECT_NEAR(c.p_W.x(), 0.0, kTol_m);
}

TEST(SegmentSegment, NearlyParallel1em15RadCrossingInProjection) {
  // Segment 2 crosses the x axis's vertical plane at x = 0.5 at a 1e-15 rad angle, 0.25 above.
  const SegmentClosestPoints c = SegmentSegmentClosestPoints(
      Vector3d(0, 0, 0), Vector3d(1, 0, 0), Vector3d(-0.5, -1e-15, 0.25),
      Vector3d(1.5, 1e-15, 0.25));
  EXPECT_NEAR(c.distance_m, 0.25, kTol_m);
  const SegmentClosestPoints touching = SegmentSegmentClosestPoints(
      Vector3d(0, 0, 0), Vector3d(1, 0, 0), Vector3d(-0.5, -1e-15, 0), Vector3d(1.5, 1e-15, 0));
  EXPECT_NEAR(touching.distance_m, 0.0, kTol_m);
  EXPECT_TRUE(touching.p_W.allFinite() && touching.q_W.allFinite());
}

TEST(SegmentSegment, FarFromOriginAt1e4) {
  // The right-angle crossing shifted by ~1e4 m: the distance keeps its local accuracy.
  const Vector3d o(1e4 + 0.123, -1e4 + 0.456, 1e4 + 0.789);
  const SegmentClosestPoints c = SegmentSegmentClosestPoints(
      o + Vector3d(-1, 0, 0), o + Vector3d(1, 0, 0), o + Vector3d(0, -1, 0.5),
      o + Vector3d(0, 1, 0.5));
  EXPECT_NEAR(c.distance_m, 0.5, 1e-11);
  EXPECT_NEAR((c.p_W - o).norm(), 0.0, 1e-11);
}

TEST(SegmentSegment, TinySegmentsKeepRelativeAccuracy) {
  // The right-angle crossing scaled down until products of four lengths underflow (1e-140 m:
  // |d1 x d2|^2 ~ 1e-560): the routine rescales, so the distance stays 0.5 * scale.
  for (const double scale : {1e-100, 1e-140}) {
    const SegmentClosestPoints c = SegmentSegmentClosestPoints(
        scale * Vector3d(-1, 0, 0), scale * Vector3d(1, 0, 0), scale * Vector3d(0, -1, 0.5),
        scale * Vector3d(0, 1, 0.5));
    EXPECT_NEAR(c.distance_m / scale, 0.5, kTol_m) << "scale " << scale;
    EXPECT_NEAR(c.s, 0.5, kTol_m);
    EXPECT_NEAR(c.t, 0.5, kTol_m);
  }
}

// ------------------------------------------------------------------------------------------
// Capsule-capsule

TEST(CapsuleCapsule, SeparatedWitnessesOnSurfaces) {
  const Capsule a = MakeCapsule(Vector3d(-1, 0, 0), Vector3d(1, 0, 0), 0.1);
  const Capsule b = MakeCapsule(Vector3d(0, -1, 1), Vector3d(0, 1, 1), 0.2);
  const DistanceResult r = CapsuleCapsuleDistance(a, b);
  EXPECT_NEAR(r.distance_m, 0.7, kTol_m);
  EXPECT_NEAR((r.p_WA - Vector3d(0, 0, 0.1)).norm(), 0.0, kTol_m);
  EXPECT_NEAR((r.p_WB - Vector3d(0, 0, 0.8)).norm(), 0.0, kTol_m);
}

TEST(CapsuleCapsule, ZeroLengthCapsulesAreSpheres) {
  const Capsule a = MakeCapsule(Vector3d(1, 2, 3), Vector3d(1, 2, 3), 0.5);
  const Capsule b = MakeCapsule(Vector3d(4, 6, 3), Vector3d(4, 6, 3), 1.5);
  const DistanceResult r = CapsuleCapsuleDistance(a, b);
  EXPECT_NEAR(r.distance_m, 5.0 - 2.0, kTol_m);
  EXPECT_NEAR((r.p_WA - Vector3d(1.3, 2.4, 3)).norm(), 0.0, kTol_m);
  EXPECT_NEAR((r.p_WB - Vector3d(3.1, 4.8, 3)).norm(), 0.0, kTol_m);
}

TEST(CapsuleCapsule, SphereAgainstCapsuleSide) {
  const Capsule sphere = MakeCapsule(Vector3d(0.5, 3, 0), Vector3d(0.5, 3, 0), 1.0);
  const Capsule c = MakeCapsule(Vector3d(0, 0, 0), Vector3d(2, 0, 0), 0.5);
  EXPECT_NEAR(CapsuleCapsuleDistance(sphere, c).distance_m, 1.5, kTol_m);
}

TEST(CapsuleCapsule, CrossingAxesOverlapGivesCommonPointNoNaN) {
  const Capsule a = MakeCapsule(Vector3d(-1, 0, 0), Vector3d(1, 0, 0), 0.1);
  const Capsule b = MakeCapsule(Vector3d(0, -1, 0), Vector3d(0, 1, 0), 0.1);
  const DistanceResult r = CapsuleCapsuleDistance(a, b);
  EXPECT_EQ(r.distance_m, 0.0);
  ASSERT_TRUE(AllFinite(r));
  EXPECT_EQ(r.p_WA, r.p_WB);
  EXPECT_LE(PointAxisDistance(r.p_WA, a), a.radius_m + kTol_m);
  EXPECT_LE(PointAxisDistance(r.p_WA, b), b.radius_m + kTol_m);
}

TEST(CapsuleCapsule, CrossingAxesZeroRadiusNoNaN) {
  const Capsule a = MakeCapsule(Vector3d(-1, 0, 0), Vector3d(1, 0, 0), 0.0);
  const Capsule b = MakeCapsule(Vector3d(0, -1, 0), Vector3d(0, 1, 0), 0.0);
  const DistanceResult r = CapsuleCapsuleDistance(a, b);
  EXPECT_EQ(r.distance_m, 0.0);
  EXPECT_TRUE(AllFinite(r));
}

TEST(CapsuleCapsule, PartialOverlapCommonPointInBoth) {
  const Capsule a = MakeCapsule(Vector3d(-1, 0, 0), Vector3d(1, 0, 0), 0.3);
  const Capsule b = MakeCapsule(Vector3d(0, -1, 0.5), Vector3d(0, 1, 0.5), 0.3);
  const DistanceResult r = CapsuleCapsuleDistance(a, b);
  EXPECT_EQ(r.distance_m, 0.0);
  EXPECT_LE(PointAxisDistance(r.p_WA, a), a.radius_m + kTol_m);
  EXPECT_LE(PointAxisDistance(r.p_WA, b), b.radius_m + kTol_m);
}

TEST(CapsuleCapsule, Touching) {
  // Axes 0.5 apart, radii 0.25 + 0.25.
  const Capsule a = MakeCapsule(Vector3d(0, 0, 0), Vector3d(1, 0, 0), 0.25);
  const Capsule b = MakeCapsule(Vector3d(0.5, 0.5, -1), Vector3d(0.5, 0.5, 1), 0.25);
  const DistanceResult r = CapsuleCapsuleDistance(a, b);
  EXPECT_NEAR(r.distance_m, 0.0, kTol_m);
  EXPECT_NEAR((r.p_WA - r.p_WB).norm(), 0.0, kTol_m);
  EXPECT_NEAR((r.p_WA - Vector3d(0.5, 0.25, 0)).norm(), 0.0, kTol_m);
}

TEST(CapsuleCapsule, ParallelSideBySide) {
  const Capsule a = MakeCapsule(Vector3d(0, 0, 0), Vector3d(0, 0, 2), 0.1);
  const Capsule b = MakeCapsule(Vector3d(1, 0, 1), Vector3d(1, 0, 3), 0.2);
  const DistanceResult r = CapsuleCapsuleDistance(a, b);
  EXPECT_NEAR(r.distance_m, 0.7, kTol_m);
  EXPECT_NEAR((r.p_WA - r.p_WB).norm(), 0.7, kTol_m);
  EXPECT_NEAR(r.p_WA.x(), 0.1, kTol_m);
}

TEST(CapsuleCapsule, FarFromOriginAt1e4) {
  const Vector3d o(-1e4 - 0.3, 1e4 + 0.7, 1e4 - 0.1);
  const Capsule a = MakeCapsule(o + Vector3d(-1, 0, 0), o + Vector3d(1, 0, 0), 0.1);
  const Capsule b = MakeCapsule(o + Vector3d(0, -1, 1), o + Vector3d(0, 1, 1), 0.2);
  const DistanceResult r = CapsuleCapsuleDistance(a, b);
  EXPECT_NEAR(r.distance_m, 0.7, 1e-11);
  EXPECT_NEAR((r.p_WA - (o + Vector3d(0, 0, 0.1))).norm(), 0.0, 1e-11);
}

// ------------------------------------------------------------------------------------------
// Capsule-box

TEST(CapsuleBox, ParallelAboveFace) {
  const Box b = MakeBox(Vector3d::Zero(), Vector3d(1, 1, 1));
  const Capsule c = MakeCapsule(Vector3d(-2, 0, 1.5), Vector3d(2, 0, 1.5), 0.25);
  const DistanceResult r = CapsuleBoxDistance(c, b);
  EXPECT_NEAR(r.distance_m, 0.25, kTol_m);
  EXPECT_NEAR(r.p_WB.z(), 1.0, kTol_m);
  EXPECT_NEAR(r.p_WA.z(), 1.25, kTol_m);
  EXPECT_LE(std::abs(r.p_WB.x()), 1.0 + kTol_m);
}

TEST(CapsuleBox, ParallelToEdge) {
  // Axis along y at (1.5, y, 1.5): nearest box feature is the edge (1, y, 1).
  const Box b = MakeBox(Vector3d::Zero(), Vector3d(1, 1, 1));
  const Capsule c = MakeCapsule(Vector3d(1.5, -3, 1.5), Vector3d(1.5, 3, 1.5), 0.1);
  const DistanceResult r = CapsuleBoxDistance(c, b);
  EXPECT_NEAR(r.distance_m, std::sqrt(0.5) - 0.1, kTol_m);
  EXPECT_NEAR(r.p_WB.x(), 1.0, kTol_m);
  EXPECT_NEAR(r.p_WB.z(), 1.0, kTol_m);
}

TEST(CapsuleBox, SkewAgainstEdge) {
  // The segment (t, 2, 2), t in [-3, 3], runs parallel to the edge (x, 1, 1) beyond its ends:
  // the box point is the edge or its end vertices, distance sqrt(2).
  const Box b = MakeBox(Vector3d::Zero(), Vector3d(1, 1, 1));
  const Capsule c = MakeCapsule(Vector3d(-3, 2, 2), Vector3d(3, 2, 2), 0.0);
  EXPECT_NEAR(CapsuleBoxDistance(c, b).distance_m, std::sqrt(2.0), kTol_m);
}

TEST(CapsuleBox, SphereAtVertex) {
  const Box b = MakeBox(Vector3d::Zero(), Vector3d(1, 1, 1));
  const Capsule sphere = MakeCapsule(Vector3d(2, 2, 2), Vector3d(2, 2, 2), 0.5);
  const DistanceResult r = CapsuleBoxDistance(sphere, b);
  EXPECT_NEAR(r.distance_m, std::sqrt(3.0) - 0.5, kTol_m);
  EXPECT_NEAR((r.p_WB - Vector3d(1, 1, 1)).norm(), 0.0, kTol_m);
}

TEST(CapsuleBox, SegmentPiercesBoxWithEndpointsOutside) {
  const Box b = MakeBox(Vector3d::Zero(), Vector3d(1, 2, 3));
  const Capsule c = MakeCapsule(Vector3d(-5, 0.5, 0.5), Vector3d(5, 0.1, -0.2), 0.01);
  const DistanceResult r = CapsuleBoxDistance(c, b);
  EXPECT_EQ(r.distance_m, 0.0);
  EXPECT_EQ(r.p_WA, r.p_WB);
  EXPECT_LE(PointBoxDistance(r.p_WA, b), kTol_m);
  EXPECT_LE(PointAxisDistance(r.p_WA, c), kTol_m);
}

TEST(CapsuleBox, TouchingFace) {
  const Box b = MakeBox(Vector3d::Zero(), Vector3d(1, 1, 1));
  const Capsule c = MakeCapsule(Vector3d(0.2, 0.3, 1.5), Vector3d(0.2, 0.3, 3.0), 0.5);
  const DistanceResult r = CapsuleBoxDistance(c, b);
  EXPECT_NEAR(r.distance_m, 0.0, kTol_m);
  EXPECT_NEAR((r.p_WA - Vector3d(0.2, 0.3, 1.0)).norm(), 0.0, kTol_m);
}

TEST(CapsuleBox, RadiusOverlapCommonPoint) {
  const Box b = MakeBox(Vector3d::Zero(), Vector3d(1, 1, 1));
  const Capsule c = MakeCapsule(Vector3d(-2, 0, 1.2), Vector3d(2, 0, 1.2), 0.5);
  const DistanceResult r = CapsuleBoxDistance(c, b);
  EXPECT_EQ(r.distance_m, 0.0);
  EXPECT_LE(PointBoxDistance(r.p_WA, b), kTol_m);
  EXPECT_LE(PointAxisDistance(r.p_WA, c), c.radius_m + kTol_m);
}

TEST(CapsuleBox, RotatedBox) {
  // Rotated 45 deg about z: a vertical edge at (sqrt(2), 0, z).
  const Box b = MakeBox(Vector3d::Zero(), Vector3d(1, 1, 1),
                        Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 4, Vector3d::UnitZ())));
  const Capsule sphere = MakeCapsule(Vector3d(3, 0, 0.5), Vector3d(3, 0, 0.5), 0.5);
  const DistanceResult r = CapsuleBoxDistance(sphere, b);
  EXPECT_NEAR(r.distance_m, 3.0 - std::sqrt(2.0) - 0.5, kTol_m);
  EXPECT_NEAR((r.p_WB - Vector3d(std::sqrt(2.0), 0, 0.5)).norm(), 0.0, kTol_m);
  EXPECT_NEAR(PointBoxSignedDistance(r.p_WB, b), 0.0, kTol_m);
}

TEST(CapsuleBox, ZeroSizeBoxIsPoint) {
  const Box b = MakeBox(Vector3d(0, 0, 2), Vector3d::Zero());
  const Capsule c = MakeCapsule(Vector3d(-1, 0, 0), Vector3d(1, 0, 0), 0.5);
  EXPECT_NEAR(CapsuleBoxDistance(c, b).distance_m, 1.5, kTol_m);
}

TEST(CapsuleBox, FarFromOriginAt1e4) {
  const Vector3d o(1e4 + 0.25, 1e4 - 0.5, -1e4 + 0.125);
  const Box b = MakeBox(o, Vector3d(1, 1, 1),
                        Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 4, Vector3d::UnitZ())));
  const Capsule sphere = MakeCapsule(o + Vector3d(3, 0, 0.5), o + Vector3d(3, 0, 0.5), 0.5);
  EXPECT_NEAR(CapsuleBoxDistance(sphere, b).distance_m, 3.0 - std::sqrt(2.0) - 0.5, 1e-11);
}

// ------------------------------------------------------------------------------------------
// Box-box

TEST(BoxBox, FaceToFace) {
  const Box a = MakeBox(Vector3d::Zero(), Vector3d(1, 1, 1));
  const Box b = MakeBox(Vector3d(3, 0.5, 0.2), Vector3d(1, 1, 1));
  const DistanceResult r = BoxBoxDistance(a, b);
  EXPECT_NEAR(r.distance_m, 1.0, kTol_m);
  EXPECT_NEAR(r.p_WA.x(), 1.0, kTol_m);
  EXPECT_NEAR(r.p_WB.x(), 2.0, kTol_m);
  EXPECT_NEAR((r.p_WA - r.p_WB).norm(), 1.0, kTol_m);
}

TEST(BoxBox, TouchingFaces) {
  const Box a = MakeBox(Vector3d::Zero(), Vector3d(1, 1, 1));
  const Box b = MakeBox(Vector3d(2, 0.3, 0.2), Vector3d(1, 1, 1));
  EXPECT_NEAR(BoxBoxDistance(a, b).distance_m, 0.0, kTol_m);
}

TEST(BoxBox, EdgeToEdgeCrossed) {
  // A rotated 45 deg about y has a top edge along y at height sqrt(2); B rotated 45 deg about x
  // has a bottom edge along x at its centre height minus sqrt(2). Gap 0.3 between them.
  const double g = 0.3;
  const Box a = MakeBox(Vector3d::Zero(), Vector3d(1, 1, 1),
                        Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 4, Vector3d::UnitY())));
  const Box b = MakeBox(Vector3d(0, 0, 2 * std::sqrt(2.0) + g), Vector3d(1, 1, 1),
                        Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 4, Vector3d::UnitX())));
  const DistanceResult r = BoxBoxDistance(a, b);
  EXPECT_NEAR(r.distance_m, g, kTol_m);
  EXPECT_NEAR((r.p_WA - Vector3d(0, 0, std::sqrt(2.0))).norm(), 0.0, kTol_m);
  EXPECT_NEAR((r.p_WB - Vector3d(0, 0, std::sqrt(2.0) + g)).norm(), 0.0, kTol_m);
}

TEST(BoxBox, VertexToFace) {
  // B turned so that its (+,+,+) vertex points straight down, sqrt(3) below its centre.
  const double g = 0.2;
  const Eigen::Quaterniond q =
      Eigen::Quaterniond::FromTwoVectors(Vector3d(1, 1, 1).normalized(), Vector3d(0, 0, -1));
  const Box a = MakeBox(Vector3d::Zero(), Vector3d(2, 2, 1));
  const Box b = MakeBox(Vector3d(0.1, -0.2, 1 + g + std::sqrt(3.0)), Vector3d(1, 1, 1), q);
  const DistanceResult r = BoxBoxDistance(a, b);
  EXPECT_NEAR(r.distance_m, g, kTol_m);
  EXPECT_NEAR((r.p_WA - Vector3d(0.1, -0.2, 1)).norm(), 0.0, kTol_m);
  // And the same with the roles swapped.
  const DistanceResult s = BoxBoxDistance(b, a);
  EXPECT_NEAR(s.distance_m, g, kTol_m);
  EXPECT_NEAR((s.p_WB - Vector3d(0.1, -0.2, 1)).norm(), 0.0, kTol_m);
}

TEST(BoxBox, EdgeToFace) {
  // B rotated 45 deg about x: bottom edge along x at centre height - sqrt(2), over A's top.
  const double g = 0.4;
  const Box a = MakeBox(Vector3d::Zero(), Vector3d(3, 3, 1));
  const Box b = MakeBox(Vector3d(0, 0, 1 + g + std::sqrt(2.0)), Vector3d(1, 1, 1),
                        Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 4, Vector3d::UnitX())));
  const DistanceResult r = BoxBoxDistance(a, b);
  EXPECT_NEAR(r.distance_m, g, kTol_m);
  EXPECT_NEAR(r.p_WA.z(), 1.0, kTol_m);
}

TEST(BoxBox, OverlapCommonPoint) {
  const Box a = MakeBox(Vector3d::Zero(), Vector3d(1, 1, 1));
  const Box b = MakeBox(Vector3d(1.5, 1.2, 0.3), Vector3d(1, 1, 1),
                        Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Vector3d(1, 2, 3).normalized())));
  const DistanceResult r = BoxBoxDistance(a, b);
  EXPECT_EQ(r.distance_m, 0.0);
  EXPECT_EQ(r.p_WA, r.p_WB);
  EXPECT_LE(PointBoxDistance(r.p_WA, a), kTol_m);
  EXPECT_LE(PointBoxDistance(r.p_WA, b), kTol_m);
}

TEST(BoxBox, CrossShapedOverlapWithNoVertexInside) {
  // Two long thin bars crossing like a plus sign: no vertex of either is inside the other.
  const Box a = MakeBox(Vector3d::Zero(), Vector3d(3, 0.1, 0.1));
  const Box b = MakeBox(Vector3d::Zero(), Vector3d(0.1, 3, 0.1));
  const DistanceResult r = BoxBoxDistance(a, b);
  EXPECT_EQ(r.distance_m, 0.0);
  EXPECT_LE(PointBoxDistance(r.p_WA, a), kTol_m);
  EXPECT_LE(PointBoxDistance(r.p_WA, b), kTol_m);
}

TEST(BoxBox, OneInsideTheOther) {
  const Box a = MakeBox(Vector3d::Zero(), Vector3d(3, 3, 3));
  const Box b = MakeBox(Vector3d(0.5, 0, 0), Vector3d(0.1, 0.2, 0.3),
                        Eigen::Quaterniond(Eigen::AngleAxisd(1.0, Vector3d::UnitZ())));
  EXPECT_EQ(BoxBoxDistance(a, b).distance_m, 0.0);
  EXPECT_EQ(BoxBoxDistance(b, a).distance_m, 0.0);
}

TEST(BoxBox, FarFromOriginAt1e4) {
  const Vector3d o(1e4 + 0.1, 1e4 + 0.2, 1e4 + 0.3);
  const double g = 0.3;
  const Box a = MakeBox(o, Vector3d(1, 1, 1),
                        Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 4, Vector3d::UnitY())));
  const Box b = MakeBox(o + Vector3d(0, 0, 2 * std::sqrt(2.0) + g), Vector3d(1, 1, 1),
                        Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 4, Vector3d::UnitX())));
  EXPECT_NEAR(BoxBoxDistance(a, b).distance_m, g, 1e-11);
}

// ------------------------------------------------------------------------------------------
// Dispatch and IsCloserThan

TEST(ShapeDistance, DispatchKeepsArgumentOrder) {
  const Box b = MakeBox(Vector3d::Zero(), Vector3d(1, 1, 1));
  const Capsule c = MakeCapsule(Vector3d(0, 0, 3), Vector3d(0, 0, 4), 0.5);
  const DistanceResult cb = ShapeDistance(Shape(c), Shape(b));
  const DistanceResult bc = ShapeDistance(Shape(b), Shape(c));
  EXPECT_NEAR(cb.distance_m, 1.5, kTol_m);
  EXPECT_NEAR(bc.distance_m, 1.5, kTol_m);
  EXPECT_NEAR(cb.p_WA.z(), 2.5, kTol_m);
  EXPECT_NEAR(bc.p_WA.z(), 1.0, kTol_m);
  EXPECT_NEAR(bc.p_WB.z(), 2.5, kTol_m);
}

TEST(IsCloserThan, EachPairAroundItsDistance) {
  const Shape box_a = MakeBox(Vector3d::Zero(), Vector3d(1, 1, 1));
  const Shape box_b = MakeBox(Vector3d(3, 0, 0), Vector3d(1, 1, 1));  // 1.0 from box_a
  const Shape cap_a = MakeCapsule(Vector3d(0, 0, 3), Vector3d(0, 0, 4), 0.5);  // 1.5 from box_a
  const Shape cap_b = MakeCapsule(Vector3d(0, 2, 3), Vector3d(0, 2, 4), 0.5);  // 1.0 from cap_a
  struct Case {
    const Shape* a;
    const Shape* b;
    double distance_m;
  };
  for (const Case& c : {Case{&box_a, &box_b, 1.0}, Case{&cap_a, &box_a, 1.5},
                        Case{&box_a, &cap_a, 1.5}, Case{&cap_a, &cap_b, 1.0}}) {
    EXPECT_TRUE(IsCloserThan(*c.a, *c.b, c.distance_m + 1e-9));
    EXPECT_FALSE(IsCloserThan(*c.a, *c.b, c.distance_m - 1e-9));
    EXPECT_FALSE(IsCloserThan(*c.a, *c.b, 0.0));
  }
  // Overlapping shapes are closer than any positive threshold, never closer than 0.
  EXPECT_TRUE(IsCloserThan(box_a, box_a, 1e-12));
  EXPECT_FALSE(IsCloserThan(box_a, box_a, 0.0));
}

TEST(IsCloserThan, NonFiniteInputFailsSafe) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const Shape box = MakeBox(Vector3d::Zero(), Vector3d(1, 1, 1));
  const Shape far_capsule = MakeCapsule(Vector3d(0, 0, 30), Vector3d(0, 0, 40), 0.5);
  ASSERT_FALSE(IsCloserThan(box, far_capsule, 1.0));
  EXPECT_TRUE(IsCloserThan(box, far_capsule, nan));
  EXPECT_TRUE(IsCloserThan(box, far_capsule, inf));
  EXPECT_TRUE(IsCloserThan(box, MakeCapsule(Vector3d(0, 0, 30), Vector3d(nan, 0, 40), 0.5), 1.0));
  EXPECT_TRUE(IsCloserThan(box, MakeCapsule(Vector3d(0, 0, 30), Vector3d(0, 0, 40), nan), 1.0));
  EXPECT_TRUE(IsCloserThan(MakeCapsule(Vector3d(0, 0, 30), Vector3d(0, 0, inf), 0.5), box, 1.0));
  Box bad_box = MakeBox(Vector3d(0, 0, 50), Vector3d(1, 1, 1));
  bad_box.X_WB.linear()(1, 2) = nan;
  EXPECT_TRUE(IsCloserThan(box, bad_box, 1.0));
  bad_box = MakeBox(Vector3d(0, 0, 50), Vector3d(1, nan, 1));
  EXPECT_TRUE(IsCloserThan(bad_box, box, 1.0));
}

}  // namespace
}  // namespace arm_collision_monitor
