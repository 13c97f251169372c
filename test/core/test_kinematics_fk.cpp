// Forward kinematics against an independent composition: urdfdom's own urdf::Pose/Rotation
// (quaternions) walked from each link up to the root, on seeded random configurations.
#include <gtest/gtest.h>
#include <urdf_model/model.h>

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <new>
#include <random>
#include <string>

#include "arm_collision_monitor/kinematics/kinematic_model.h"
#include "arm_collision_monitor/kinematics/urdf_conversions.h"
#include "allocation_counter.h"


namespace arm_collision_monitor {
namespace {

const std::string kWorkcellUrdf = std::string(ACM_SOURCE_DIR) + "/urdf/workcell.urdf";
const std::string kDataDir = std::string(ACM_SOURCE_DIR) + "/test/data/";
constexpr double kFkToleranceM = 1e-12;  // the brief's bound: doubles over ~2 m chains
constexpr std::uint64_t kSeed = 1234567;

// Pose composition with urdfdom's types: (p1, R1) * (p2, R2) = (p1 + R1 p2, R1 R2).
urdf::Pose Compose(const urdf::Pose& a, const urdf::Pose& b) {
  urdf::Pose c;
  c.rotation = a.rotation * b.rotation;
  const urdf::Vector3 rotated = a.rotation * b.position;
  c.position =
      urdf::Vector3(a.position.x + rotated.x, a.position.y + rotated.y, a.position.z + rotated.z);
  return c;
}

// The joint motion as a urdf::Pose: a unit quaternion (axis sin(q/2), cos(q/2)) for revolute
// joints, a translation along the axis for prismatic ones.
urdf::Pose JointMotion(const urdf::Joint& joint, double position) {
  urdf::Pose motion;
  const urdf::Vector3& a = joint.axis;
  const double norm = std::sqrt(a.x * a.x + a.y * a.y + a.z * a.z);
  if (joint.type == urdf::Joint::REVOLUTE || joint.type == urdf::Joint::CONTINUOUS) {
    const double s = std::sin(0.5 * position) / norm;
    motion.rotation.setFromQuaternion(a.x * s, a.y * s, a.z * s, std::cos(0.5 * position));
  } else if (joint.type == urdf::Joint::PRISMATIC) {
    motion.position =
        urdf::Vector3(a.x * position / norm, a.y * position / norm, a.z * position / norm);
  }
  return motion;
}

// X_W(link) by walking from the link to the root of the urdf::Model.
urdf::Pose ReferencePose(const urdf::ModelInterface& urdf_model, const std::string& link_name,
                         const std::map<std::string, double>& joint_positions) {
  urdf::Pose X;  // identity
  urdf::LinkConstSharedPtr link = urdf_model.getLink(link_name);
  while (link->parent_joint) {
    const urdf::Joint& joint = *link->parent_joint;
    double position = 0.0;
    if (joint.mimic) {
      position = joint.mimic->multiplier * joint_positions.at(joint.mimic->joint_name) +
                 joint.mimic->offset;
    } else if (joint_positions.count(joint.name)) {
      position = joint_positions.at(joint.name);
    }
    X = Compose(Compose(joint.parent_to_joint_origin_transform, JointMotion(joint, position)), X);
    link = urdf_model.getLink(joint.parent_link_name);
  }
  return X;
}

// Largest position error and largest rotation-matrix entry error over `samples` random q.
void CompareWithUrdfdom(const std::string& urdf_path, int samples, double* max_position_err_m,
                        double* max_rotation_err) {
  const KinematicModel model = KinematicModel::FromUrdfFile(urdf_path);
  std::string why;
  EXPECT_TRUE(model.Validate(&why)) << why;
  const urdf::ModelInterfaceSharedPtr urdf_model = ParseUrdfFile(urdf_path);
  std::cout << "seed " << kSeed << " for " << urdf_path << "\n";
  std::mt19937_64 rng(kSeed);
  std::vector<Eigen::Isometry3d> X_WL(model.link_count());
  Eigen::VectorXd q(model.q_size());
  *max_position_err_m = 0.0;
  *max_rotation_err = 0.0;
  for (int sample = 0; sample < samples; ++sample) {
    std::map<std::string, double> positions;
    for (int link = 1; link < model.link_count(); ++link) {
      const JointSpec& joint = model.joint(link);
      if (joint.q_index < 0) continue;
      const double lower = std::isfinite(joint.lower) ? joint.lower : -2.0 * M_PI;
      const double upper = std::isfinite(joint.upper) ? joint.upper : 2.0 * M_PI;
      q[joint.q_index] = std::uniform_real_distribution<double>(lower, upper)(rng);
      positions[joint.name] = q[joint.q_index];
    }
    model.ComputeLinkPoses(q, &X_WL);
    for (int link = 0; link < model.link_count(); ++link) {
      const urdf::Pose ref = ReferencePose(*urdf_model, model.link_name(link), positions);
      const Eigen::Vector3d p_ref(ref.position.x, ref.position.y, ref.position.z);
      double qx, qy, qz, qw;
      ref.rotation.getQuaternion(qx, qy, qz, qw);
      const Eigen::Matrix3d R_ref = Eigen::Quaterniond(qw, qx, qy, qz).toRotationMatrix();
      *max_position_err_m =
          std::max(*max_position_err_m, (X_WL[link].translation() - p_ref).norm());
      *max_rotation_err =
          std::max(*max_rotation_err, (X_WL[link].linear() - R_ref).cwiseAbs().maxCoeff());
    }
  }
  std::cout << "max position error " << *max_position_err_m << " m, max rotation entry error "
            << *max_rotation_err << "\n";
}

TEST(KinematicsFk, WorkcellMatchesUrdfdomComposition) {
  double position_err_m = 0.0, rotation_err = 0.0;
  CompareWithUrdfdom(kWorkcellUrdf, 1000, &position_err_m, &rotation_err);
  EXPECT_LE(position_err_m, kFkToleranceM);
  EXPECT_LE(rotation_err, 1e-12);
}

TEST(KinematicsFk, ThirdPartyArmWithOffsetsAndPrismaticAndMimicMatches) {
  double position_err_m = 0.0, rotation_err = 0.0;
  CompareWithUrdfdom(kDataDir + "three_link_arm.urdf", 1000, &position_err_m, &rotation_err);
  EXPECT_LE(position_err_m, kFkToleranceM);
  EXPECT_LE(rotation_err, 1e-12);
}

TEST(KinematicsFk, WorkcellHomePoseIsStraightUpWithReach1905mm) {
  const KinematicModel model = KinematicModel::FromUrdfFile(kWorkcellUrdf);
  ASSERT_EQ(model.q_size(), 14);
  std::vector<Eigen::Isometry3d> X_WL(model.link_count());
  model.ComputeLinkPoses(Eigen::VectorXd::Zero(14), &X_WL);
  for (const std::string side : {"left", "right"}) {
    const Eigen::Vector3d p_WBase = X_WL[model.FindLink(side + "_base_link")].translation();
    const Eigen::Vector3d p_WTool = X_WL[model.FindLink(side + "_tool")].translation();
    EXPECT_NEAR((p_WTool - p_WBase).norm(), 1.905, 1e-12) << side;
    EXPECT_NEAR(p_WTool.x(), p_WBase.x(), 1e-12) << side;  // straight up
    EXPECT_NEAR(p_WTool.y(), p_WBase.y(), 1e-12) << side;
    for (int i = 1; i <= 7; ++i) {  // every link frame parallel to W
      const int link = model.FindLink(side + "_link" + std::to_string(i));
      EXPECT_TRUE(X_WL[link].linear().isIdentity(1e-15)) << side << i;
    }
  }
  EXPECT_EQ(model.ActuatedJointNames().front(), "left_joint1");
  EXPECT_EQ(model.ActuatedJointNames().back(), "right_joint7");
}

TEST(KinematicsFk, ComputeLinkPosesDoesNotAllocate) {
  const KinematicModel model = KinematicModel::FromUrdfFile(kDataDir + "three_link_arm.urdf");
  std::vector<Eigen::Isometry3d> X_WL(model.link_count());
  const Eigen::VectorXd q = Eigen::VectorXd::Constant(model.q_size(), 0.3);
  const std::uint64_t before = test::AllocationCount();
  for (int i = 0; i < 100; ++i) model.ComputeLinkPoses(q, &X_WL);
  EXPECT_EQ(test::AllocationCount(), before);
  // The counter works: a vector of link poses does allocate.
  std::vector<Eigen::Isometry3d> copy = X_WL;
  EXPECT_GT(test::AllocationCount(), before);
}

TEST(KinematicsFk, JointTypesLimitsAndMimicAreRead) {
  const KinematicModel model = KinematicModel::FromUrdfFile(kDataDir + "three_link_arm.urdf");
  const JointSpec& slide = model.joint(model.FindJointChildLink("slide"));
  EXPECT_EQ(slide.type, JointType::kPrismatic);
  EXPECT_EQ(slide.lower, 0.0);
  EXPECT_EQ(slide.upper, 0.2);
  const JointSpec& spin = model.joint(model.FindJointChildLink("spin"));
  EXPECT_EQ(spin.type, JointType::kContinuous);
  EXPECT_TRUE(std::isinf(spin.upper));
  const JointSpec& finger = model.joint(model.FindJointChildLink("finger_mimic"));
  EXPECT_EQ(finger.q_index, -1);
  EXPECT_EQ(finger.mimic_q_index, slide.q_index);
  EXPECT_EQ(finger.mimic_multiplier, -1.0);
  EXPECT_NEAR(model.joint(model.FindJointChildLink("shoulder")).axis_J.norm(), 1.0, 1e-15);
  // Every parent precedes its children.
  for (int link = 1; link < model.link_count(); ++link) EXPECT_LT(model.parent_link(link), link);
}

TEST(KinematicsFk, FloatingJointIsRejectedNamingTheJoint) {
  try {
    KinematicModel::FromUrdfFile(kDataDir + "floating_joint.urdf");
    FAIL() << "expected LoadError";
  } catch (const LoadError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("floating_joint.urdf"), std::string::npos) << message;
    EXPECT_NE(message.find("'free'"), std::string::npos) << message;
    EXPECT_NE(message.find("floating"), std::string::npos) << message;
  }
}

TEST(KinematicsFk, MissingAndMalformedUrdfAreRejectedNamingTheFile) {
  for (const std::string& path : {kDataDir + "does_not_exist.urdf", kDataDir + "malformed.urdf"}) {
    try {
      KinematicModel::FromUrdfFile(path);
      FAIL() << "expected LoadError for " << path;
    } catch (const LoadError& e) {
      EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace arm_collision_monitor
