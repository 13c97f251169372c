// ToRigidTransform: what TF hands the node becomes a rigid pose, or a refusal naming why.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "arm_collision_monitor/ros/conversions.h"

namespace arm_collision_monitor {
namespace {

geometry_msgs::Transform MakeTransform(double x, double y, double z, double w) {
  geometry_msgs::Transform transform;
  transform.translation.x = 1.0;
  transform.translation.y = -2.0;
  transform.translation.z = 0.5;
  transform.rotation.x = x;
  transform.rotation.y = y;
  transform.rotation.z = z;
  transform.rotation.w = w;
  return transform;
}

// tf2 keeps a quaternion whose squared norm is within 0.01 of 1: the half turn about z scaled by
// 1.004 would stretch the shapes it places by 0.8 % (tf2::transformToEigen keeps it as it is).
// Normalised, its matrix is the exact rotation.
TEST(RosConversions, TfQuaternionOffUnitNormIsNormalised) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  const double s = 1.004;
  ASSERT_EQ(ToRigidTransform(MakeTransform(0.0, 0.0, s * std::sqrt(0.5), s * std::sqrt(0.5)), &X),
            "");
  EXPECT_NEAR((X.linear().transpose() * X.linear() - Eigen::Matrix3d::Identity()).norm(), 0.0,
              1e-15);
  EXPECT_NEAR((X.linear() * Eigen::Vector3d::UnitX() - Eigen::Vector3d::UnitY()).norm(), 0.0,
              1e-15);
  EXPECT_EQ(X.translation(), Eigen::Vector3d(1.0, -2.0, 0.5));
}

// A chain of three static frames each of norm 1.0049, which tf2 accepts one by one, composes
// to a quaternion of norm 1.0148 (a review's): normalised as well, not refused (refused, the
// object it places would be unavailable, a stop, until a restart).
TEST(RosConversions, TfChainOfQuaternionsOffUnitNormIsNormalised) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  const double s = std::pow(1.0049, 3);
  ASSERT_EQ(ToRigidTransform(MakeTransform(s * 0.5, s * 0.5, s * 0.5, s * 0.5), &X), "");
  EXPECT_NEAR((X.linear().transpose() * X.linear() - Eigen::Matrix3d::Identity()).norm(), 0.0,
              1e-15);
  EXPECT_NEAR((X.linear() * Eigen::Vector3d::UnitX() - Eigen::Vector3d::UnitY()).norm(), 0.0,
              1e-15);
}

TEST(RosConversions, BadTfTransformIsNamedAndLeavesThePose) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const Eigen::Isometry3d before = Eigen::Isometry3d(Eigen::Translation3d(3.0, 4.0, 5.0));
  for (const geometry_msgs::Transform& transform :
       {MakeTransform(0.0, 0.0, 0.0, 0.0), MakeTransform(nan, 0.0, 0.0, 1.0)}) {
    Eigen::Isometry3d X = before;
    EXPECT_EQ(ToRigidTransform(transform, &X), "rotation: quaternion zero or not finite");
    EXPECT_EQ(X.matrix(), before.matrix());
  }
  geometry_msgs::Transform far = MakeTransform(0.0, 0.0, 0.0, 1.0);
  far.translation.y = std::numeric_limits<double>::infinity();
  Eigen::Isometry3d X = before;
  EXPECT_EQ(ToRigidTransform(far, &X), "translation not finite");
  EXPECT_EQ(X.matrix(), before.matrix());
}

}  // namespace
}  // namespace arm_collision_monitor
