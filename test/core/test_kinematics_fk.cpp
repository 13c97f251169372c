// Forward kinematics against an independent composition: urdfdom's own urdf::Pose/Rotation
// (quaternions) walked from each link up to the root, on seeded random configurations.
#include <gtest/gtest.h>
#include <urdf_model/model.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <limits>
#include <new>
#include <random>
#include <string>
#include <tuple>
#include <vector>

#include "arm_collision_monitor/core/constants.h"
#include "arm_collision_monitor/kinematics/kinematic_model.h"
#include "arm_collision_monitor/kinematics/sin_cos.h"
#include "arm_collision_monitor/kinematics/urdf_conversions.h"
#include "allocation_counter.h"


namespace arm_collision_monitor {
namespace {

const std::string kWorkcellUrdf = std::string(ACM_SOURCE_DIR) + "/urdf/workcell.urdf";
const std::string kDataDir = std::string(ACM_SOURCE_DIR) + "/test/data/";
constexpr double kFkToleranceM = 1e-12;  // the brief's bound: doubles over ~2 m chains
// Largest |R^T R - I| entry allowed in a computed link rotation (dimensionless, ~1e-15): each
// of the up to ~8 rotation products along a chain adds about one unit of 2^-53 (1.1e-16); the
// AngleAxis reference itself reaches ~1e-15 on these models (the test prints both).
constexpr double kOrthonormalityTolerance = 2e-15;
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

// Joints the bundled files lack: a general (non-coordinate) revolute axis under a rotated
// origin, a negative coordinate axis, a revolute mimic with multiplier and offset about a negative
// axis, a continuous joint about a general axis, a prismatic joint along a general axis.
constexpr char kAwkwardAxesUrdf[] = R"(<?xml version="1.0"?>
<robot name="awkward_axes">
  <link name="base"/> <link name="a"/> <link name="b"/> <link name="c"/> <link name="d"/>
  <link name="e"/>
  <joint name="j_general" type="revolute"><parent link="base"/><child link="a"/>
    <origin xyz="0.1 -0.2 0.3" rpy="0.3 -0.7 1.1"/><axis xyz="1 2 -3"/>
    <limit lower="-2" upper="2.5" effort="1" velocity="1"/></joint>
  <joint name="j_negative_z" type="revolute"><parent link="a"/><child link="b"/>
    <origin xyz="0 0.25 0" rpy="0 0 0"/><axis xyz="0 0 -1"/>
    <limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
  <joint name="j_mimic" type="revolute"><parent link="b"/><child link="c"/>
    <origin xyz="0.2 0 0.05" rpy="1.5707963267948966 0 0"/><axis xyz="0 -1 0"/>
    <limit lower="-10" upper="10" effort="1" velocity="1"/>
    <mimic joint="j_negative_z" multiplier="2" offset="0.1"/></joint>
  <joint name="j_continuous" type="continuous"><parent link="c"/><child link="d"/>
    <origin xyz="0 0 0.3" rpy="0 0.4 0"/><axis xyz="0.6 0 0.8"/></joint>
  <joint name="j_slide" type="prismatic"><parent link="d"/><child link="e"/>
    <origin xyz="0.1 0 0" rpy="0.2 0.1 0"/><axis xyz="-1 1 0"/>
    <limit lower="-0.3" upper="0.3" effort="1" velocity="1"/></joint>
</robot>
)";

std::string WriteAwkwardAxesUrdf() {
  const std::string path = ::testing::TempDir() + "awkward_axes.urdf";
  std::ofstream(path) << kAwkwardAxesUrdf;
  return path;
}

// X_WL by the straightforward composition X_WP * X_PJ * AngleAxis(theta, axis) (or a
// Translation3d for prismatic joints), from the model's parsed JointSpecs: the pre-optimisation
// ComputeLinkPoses, kept here as the reference.
std::vector<Eigen::Isometry3d> ReferenceAngleAxisPoses(const KinematicModel& model,
                                                       const Eigen::VectorXd& q) {
  std::vector<Eigen::Isometry3d> X_WL(model.link_count());
  X_WL[0] = model.X_WRoot;
  for (int link = 1; link < model.link_count(); ++link) {
    const JointSpec& joint = model.joint(link);
    double theta = 0.0;
    if (joint.q_index >= 0) theta = q[joint.q_index];
    if (joint.mimic_q_index >= 0) {
      theta = joint.mimic_multiplier * q[joint.mimic_q_index] + joint.mimic_offset;
    }
    const Eigen::Isometry3d X_WJ = X_WL[model.parent_link(link)] * joint.X_PJ;
    if (joint.type == JointType::kPrismatic) {
      X_WL[link] = X_WJ * Eigen::Translation3d(theta * joint.axis_J);
    } else if (joint.type == JointType::kFixed) {
      X_WL[link] = X_WJ;
    } else {
      X_WL[link] = X_WJ * Eigen::AngleAxisd(theta, joint.axis_J);
    }
  }
  return X_WL;
}

// Random q within the limits (continuous joints in [-2 pi, 2 pi], and every 10th sample far
// outside, where SinCos falls back to std::sin/std::cos); compares every link pose with the
// reference and checks orthonormality and the exact bottom row.
void CompareWithAngleAxisReference(const std::string& urdf_path, int samples) {
  KinematicModel model = KinematicModel::FromUrdfFile(urdf_path);
  model.X_WRoot = Eigen::Translation3d(0.4, -1.2, 0.7) *
                  Eigen::AngleAxisd(0.9, Eigen::Vector3d(1.0, -2.0, 2.0).normalized());
  std::string why;
  ASSERT_TRUE(model.Validate(&why)) << why;
  std::cout << "seed " << kSeed << " for " << urdf_path << "\n";
  std::mt19937_64 rng(kSeed);
  std::vector<Eigen::Isometry3d> X_WL(model.link_count());
  Eigen::VectorXd q(model.q_size());
  double position_err_m = 0.0, rotation_err = 0.0, orthonormality_err = 0.0;
  double reference_orthonormality_err = 0.0;
  for (int sample = 0; sample < samples; ++sample) {
    for (int link = 1; link < model.link_count(); ++link) {
      const JointSpec& joint = model.joint(link);
      if (joint.q_index < 0) continue;
      const double span = sample % 10 == 9 ? 1e7 : 2.0 * M_PI;
      const double lower = std::isfinite(joint.lower) ? joint.lower : -span;
      const double upper = std::isfinite(joint.upper) ? joint.upper : span;
      q[joint.q_index] = std::uniform_real_distribution<double>(lower, upper)(rng);
    }
    model.ComputeLinkPoses(q, &X_WL);
    const std::vector<Eigen::Isometry3d> X_ref = ReferenceAngleAxisPoses(model, q);
    for (int link = 0; link < model.link_count(); ++link) {
      position_err_m =
          std::max(position_err_m, (X_WL[link].translation() - X_ref[link].translation()).norm());
      rotation_err = std::max(
          rotation_err, (X_WL[link].linear() - X_ref[link].linear()).cwiseAbs().maxCoeff());
      auto orthonormality_error = [](const Eigen::Matrix3d& R) {
        return (R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
      };
      orthonormality_err = std::max(orthonormality_err, orthonormality_error(X_WL[link].linear()));
      reference_orthonormality_err =
          std::max(reference_orthonormality_err, orthonormality_error(X_ref[link].linear()));
      ASSERT_EQ(X_WL[link].matrix().row(3), Eigen::RowVector4d(0, 0, 0, 1)) << link;
    }
  }
  std::cout << "vs AngleAxis reference: max position error " << position_err_m
            << " m, max rotation entry error " << rotation_err
            << ", max |R^T R - I| entry " << orthonormality_err << " (reference "
            << reference_orthonormality_err << ")\n";
  EXPECT_LE(position_err_m, kFkToleranceM);
  EXPECT_LE(rotation_err, 1e-12);
  EXPECT_LE(orthonormality_err, kOrthonormalityTolerance);
}

TEST(KinematicsFk, WorkcellMatchesAngleAxisReference) {
  CompareWithAngleAxisReference(kWorkcellUrdf, 2000);
}

TEST(KinematicsFk, ThreeLinkArmMatchesAngleAxisReference) {
  CompareWithAngleAxisReference(kDataDir + "three_link_arm.urdf", 2000);
}

TEST(KinematicsFk, GeneralAndNegativeAxesAndRevoluteMimicMatchAngleAxisReference) {
  const std::string path = WriteAwkwardAxesUrdf();
  const KinematicModel model = KinematicModel::FromUrdfFile(path);
  ASSERT_EQ(model.q_size(), 4);
  EXPECT_EQ(model.joint(model.FindJointChildLink("j_mimic")).mimic_q_index,
            model.joint(model.FindJointChildLink("j_negative_z")).q_index);
  CompareWithAngleAxisReference(path, 2000);
  double position_err_m = 0.0, rotation_err = 0.0;
  CompareWithUrdfdom(path, 1000, &position_err_m, &rotation_err);
  EXPECT_LE(position_err_m, kFkToleranceM);
  EXPECT_LE(rotation_err, 1e-12);
}

// MovingLinksTo gives the moving targets and their moving ancestors, in link order (checked
// against a walk up from each target), for seeded random target sets; ComputeLinkPosesOf then
// writes exactly those links, bit for bit as ComputeLinkPoses does, and leaves every other entry
// (the root, pedestals and arm bases fixed to it, the tool points no target needs) as it was.
TEST(KinematicsFk, LinkPosesOfWriteExactlyTheLinksTheTargetsNeed) {
  KinematicModel model = KinematicModel::FromUrdfFile(kWorkcellUrdf);
  model.X_WRoot =
      Eigen::Translation3d(1.0, 2.0, 3.0) * Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitZ());
  std::cout << "seed " << kSeed << "\n";
  std::mt19937_64 rng(kSeed);
  std::uniform_real_distribution<double> angle(-3.0, 3.0);
  auto random_q = [&] {
    Eigen::VectorXd q(model.q_size());
    for (int i = 0; i < q.size(); ++i) q[i] = angle(rng);
    return q;
  };
  const int n = model.link_count();
  int static_links = 0;
  for (int link = 0; link < n; ++link) static_links += !model.is_moving(link);
  ASSERT_EQ(static_links, 5);  // world, two pedestals, two arm bases
  // Every link a target: every moving link.
  std::vector<int> links;
  std::vector<std::uint8_t> all(n, 1);
  model.MovingLinksTo(&all, &links);
  EXPECT_EQ(links.size(), static_cast<std::size_t>(n - static_links));
  // The tool points (no geometry, the last links of their arms) alone need their whole arms.
  std::vector<std::uint8_t> tools(n, 0);
  tools[model.FindLink("left_tool")] = 1;
  model.MovingLinksTo(&tools, &links);
  EXPECT_EQ(links.size(), 8u);  // left_link1..7 and left_tool
  const Eigen::Isometry3d marker(Eigen::Translation3d(-7.0, -7.0, -7.0));
  std::vector<Eigen::Isometry3d> X_full(n), X_of(n);
  for (int sample = 0; sample < 200; ++sample) {
    std::vector<std::uint8_t> targets(n, 0);
    for (int link = 0; link < n; ++link) targets[link] = rng() % 4 == 0;
    // The targets and every link between one and the root; the moving ones are listed.
    std::vector<std::uint8_t> between(n, 0);
    std::vector<char> expected(n, 0);
    for (int link = 0; link < n; ++link) {
      for (int up = link; targets[link] && up >= 0; up = model.parent_link(up)) {
        between[up] = 1;
        expected[up] = model.is_moving(up);
      }
    }
    std::vector<std::uint8_t> flagged = targets;
    model.MovingLinksTo(&flagged, &links);
    ASSERT_EQ(flagged, between) << "sample " << sample;
    ASSERT_TRUE(std::is_sorted(links.begin(), links.end()));
    std::vector<char> listed(n, 0);
    for (const int link : links) listed[link] = 1;
    ASSERT_EQ(listed, expected) << "sample " << sample;
    // The precondition: every entry a link of `links` may read holds its pose.
    model.ComputeLinkPoses(random_q(), &X_of);
    // No moving link hangs directly off the root, so a marked root entry is never read; it
    // shows whether the entries fixed to the root are written.
    X_of[0] = marker;
    for (int link = 1; link < n; ++link) {
      if (model.is_moving(link) && !listed[link]) X_of[link] = marker;
    }
    const Eigen::VectorXd q = random_q();
    model.ComputeLinkPosesOf(q, links, &X_of);
    model.ComputeLinkPoses(q, &X_full);
    for (int link = 0; link < n; ++link) {
      const bool is_written = listed[link] != 0;
      const bool is_marked = link == 0 || (model.is_moving(link) && !is_written);
      const Eigen::Matrix4d& want = is_marked ? marker.matrix() : X_full[link].matrix();
      ASSERT_EQ(X_of[link].matrix(), want) << model.link_name(link) << ", sample " << sample;
    }
  }
}

// UpdateLinkPosesOf, over a run of seeded q that each change a random subset of the joints
// (none, one, some, all), for every moving link or those up to one target, on a model with a
// mimic joint and on one with a prismatic and a mimic:
// every link of the list bit for bit as ComputeLinkPoses at the new q, flagged changed exactly
// when a joint above it changed (checked by a walk up to the root), with its pose at the q before
// left in X_WL_before; the links that do not move are never flagged.
void ExpectUpdateLinkPosesOfMatches(const std::string& urdf_path, const std::string& target) {
  const KinematicModel model = KinematicModel::FromUrdfFile(urdf_path);
  const int n = model.link_count();
  std::vector<int> links;
  std::vector<std::uint8_t> targets(n, target.empty() ? 1 : 0);
  if (!target.empty()) targets[model.FindLink(target)] = 1;
  model.MovingLinksTo(&targets, &links);
  std::mt19937_64 rng(kSeed);
  std::uniform_real_distribution<double> angle(-1.5, 1.5);
  Eigen::VectorXd q = Eigen::VectorXd::Zero(model.q_size());
  std::vector<Eigen::Isometry3d> X_WL(n), X_WL_before(n), X_full(n), X_was(n);
  model.ComputeLinkPoses(q, &X_WL);
  X_WL_before = X_WL;
  std::vector<std::uint8_t> changed(n, 0);
  std::vector<int> scratch(links.size());
  int partial = 0, whole = 0, none = 0;
  for (int sample = 0; sample < 400; ++sample) {
    const Eigen::VectorXd q_before = q;
    const int pattern = static_cast<int>(rng() % 4);  // none, one joint, some, all
    std::vector<char> is_q_changed(model.q_size(), 0);
    for (int i = 0; i < q.size(); ++i) {
      is_q_changed[i] = pattern == 3 || (pattern == 2 && rng() % 2 == 0);
    }
    if (pattern == 1) is_q_changed[rng() % q.size()] = 1;
    for (int i = 0; i < q.size(); ++i) {
      if (is_q_changed[i]) q[i] = angle(rng);
    }
    X_was = X_WL;
    model.UpdateLinkPosesOf(q, q_before, links, &X_WL, &X_WL_before, &changed, &scratch);
    model.ComputeLinkPoses(q, &X_full);
    int changed_count = 0;
    for (const int link : links) {
      bool is_expected = false;
      for (int up = link; up > 0; up = model.parent_link(up)) {
        const JointSpec& joint = model.joint(up);
        const int i = joint.mimic_q_index >= 0 ? joint.mimic_q_index : joint.q_index;
        is_expected |= i >= 0 && is_q_changed[i] && q[i] != q_before[i];
      }
      ASSERT_EQ(changed[link], is_expected ? 1 : 0) << model.link_name(link) << ", " << sample;
      ASSERT_EQ(X_WL[link].matrix(), X_full[link].matrix()) << model.link_name(link);
      if (is_expected) {
        ASSERT_EQ(X_WL_before[link].matrix(), X_was[link].matrix()) << model.link_name(link);
      }
      changed_count += is_expected;
    }
    for (int link = 0; link < n; ++link) {
      if (!model.is_moving(link)) {
        ASSERT_EQ(changed[link], 0) << model.link_name(link);
      }
    }
    none += changed_count == 0;
    whole += changed_count == static_cast<int>(links.size());
    partial += changed_count > 0 && changed_count < static_cast<int>(links.size());
  }
  // Each case came up often.
  EXPECT_GT(none, 50);
  EXPECT_GT(whole, 50);
  EXPECT_GT(partial, 50);
}

TEST(KinematicsFk, UpdateLinkPosesOfRecomputesExactlyTheLinksBelowAChangedJoint) {
  ExpectUpdateLinkPosesOfMatches(kWorkcellUrdf, "");
  ExpectUpdateLinkPosesOfMatches(kWorkcellUrdf, "right_link4");  // the links up to it
  ExpectUpdateLinkPosesOfMatches(WriteAwkwardAxesUrdf(), "");
  ExpectUpdateLinkPosesOfMatches(kDataDir + "three_link_arm.urdf", "");
}

// SinCos against libm over seeded random angles and named adversarial ones. libm's own error
// (below one unit of 2^-53 for results in [-1, 1]) is added to the stated bound.
TEST(KinematicsFk, SinCosIsWithinItsStatedBoundOfLibm) {
  constexpr double kUnit = 1.1102230246251565e-16;  // 2^-53
  std::vector<double> angles = {0.0, -0.0, 1e-300, -1e-300, 1e-8, M_PI / 4, -M_PI / 4,
                                kFastSinCosMaxAngle_rad, -kFastSinCosMaxAngle_rad,
                                std::nextafter(kFastSinCosMaxAngle_rad, 1e300), 1e300, -3e7};
  for (int k = -8; k <= 8; ++k) {  // near multiples of pi/2 and of pi/4, where quadrants meet
    for (const double base : {k * M_PI / 2, k * M_PI / 4, 63661.0 * k * M_PI / 2}) {
      angles.push_back(base);
      angles.push_back(std::nextafter(base, 1e300));
      angles.push_back(std::nextafter(base, -1e300));
    }
  }
  std::cout << "seed " << kSeed << "\n";
  std::mt19937_64 rng(kSeed);
  for (int i = 0; i < 200000; ++i) {
    const double span = i % 2 ? 2.0 * M_PI : kFastSinCosMaxAngle_rad;
    angles.push_back(std::uniform_real_distribution<double>(-span, span)(rng));
  }
  std::vector<double> sin_out(angles.size()), cos_out(angles.size());
  SinCos(angles.data(), static_cast<int>(angles.size()), sin_out.data(), cos_out.data());
  double worst_units = 0.0;
  for (std::size_t i = 0; i < angles.size(); ++i) {
    const double a = angles[i];
    if (!(std::abs(a) <= kFastSinCosMaxAngle_rad)) {  // the fallback is libm itself
      EXPECT_EQ(sin_out[i], std::sin(a)) << a;
      EXPECT_EQ(cos_out[i], std::cos(a)) << a;
      continue;
    }
    const double units = std::max(std::abs(sin_out[i] - std::sin(a)),
                                  std::abs(cos_out[i] - std::cos(a))) / kUnit;
    ASSERT_LE(units, kFastSinCosErrorUlps + 1.0) << "angle " << a;
    worst_units = std::max(worst_units, units);
  }
  std::cout << "worst SinCos error vs libm: " << worst_units << " units of 2^-53\n";
  double s = 0.0, c = 0.0;
  for (const double bad : {std::numeric_limits<double>::infinity(),
                           std::numeric_limits<double>::quiet_NaN()}) {
    SinCos(&bad, 1, &s, &c);
    EXPECT_TRUE(std::isnan(s) && std::isnan(c)) << bad;
  }
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
  EXPECT_EQ(model.MimicJointNames(), std::vector<std::string>{"finger_mimic"});
  // The largest position at an accepted one: a limit and its margin; the mimic at -1 times the
  // slide's; the continuous wrist at the bound of a joint without limits.
  EXPECT_DOUBLE_EQ(model.PositionBound(slide), 0.2 + kJointLimitMargin);
  EXPECT_DOUBLE_EQ(model.PositionBound(finger), 0.2 + kJointLimitMargin);
  EXPECT_DOUBLE_EQ(model.Travel_m(finger), 0.2 + kJointLimitMargin);
  EXPECT_EQ(model.PositionBound(spin), kMaxUnlimitedPosition_rad);
  EXPECT_EQ(model.Travel_m(spin), 0.0);
  EXPECT_TRUE(model.IsFixedJoint("tool_joint"));
  EXPECT_FALSE(model.IsFixedJoint("slide"));
  EXPECT_FALSE(model.IsFixedJoint("finger_mimic"));
  EXPECT_FALSE(model.IsFixedJoint("no_such_joint"));
  // The continuous wrist without limits is the one joint whose positions a turn apart are one
  // pose; with soft limits it is none.
  EXPECT_EQ(model.TurningLinks(), std::vector<int>{model.FindJointChildLink("spin")});
  KinematicModel limited = model;
  ASSERT_TRUE(limited.SetPositionLimits("spin", -4.0, 4.0));
  EXPECT_TRUE(limited.TurningLinks().empty());
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

// A <mimic> naming no joint (a typo) or one without a position of its own (itself) is refused,
// saying which of the two it is (both read "must name an actuated, non-mimic joint" before).
TEST(KinematicsFk, AMimicOfNoJointOrOfOneWithoutAPositionIsRejectedSayingWhich) {
  const std::string mimic = "<mimic joint=\"j_negative_z\"";
  for (const auto& [target, why] :
       {std::make_pair("j_negative_zz", "names no joint of the URDF (a typo?)"),
        std::make_pair("j_mimic", "names a joint with no position of its own")}) {
    std::string urdf = kAwkwardAxesUrdf;
    urdf.replace(urdf.find(mimic), mimic.size(), "<mimic joint=\"" + std::string(target) + "\"");
    const std::string path = ::testing::TempDir() + "bad_mimic.urdf";
    std::ofstream(path) << urdf;
    try {
      KinematicModel::FromUrdfFile(path);
      ADD_FAILURE() << "expected LoadError for " << target;
    } catch (const LoadError& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find("joint 'j_mimic': <mimic joint='" + std::string(target) + "'> " +
                             why),
                std::string::npos)
          << message;
    }
  }
}

// A mistyped <parent link> that names a link below the joint's own child leaves that part of
// the chain in a loop, not below the root (urdfdom accepts it: one root): refused, naming the
// links and a joint of the loop (a Techman user's URDF lost six links without a word).
TEST(KinematicsFk, LinksInALoopOfJointsAreRejected) {
  const std::string path = ::testing::TempDir() + "joint_loop.urdf";
  std::ofstream(path) << "<robot name='r'>\n"
                         "  <link name='base'/><link name='a'/><link name='b'/><link name='c'/>\n"
                         "  <joint name='j1' type='fixed'><parent link='base'/>"
                         "<child link='c'/></joint>\n"
                         "  <joint name='j2' type='revolute'><parent link='b'/><child link='a'/>"
                         "<axis xyz='0 0 1'/><limit lower='-1' upper='1' velocity='1' "
                         "effort='1'/></joint>\n"
                         "  <joint name='j3' type='revolute'><parent link='a'/><child link='b'/>"
                         "<axis xyz='0 0 1'/><limit lower='-1' upper='1' velocity='1' "
                         "effort='1'/></joint>\n"
                         "</robot>\n";
  try {
    KinematicModel::FromUrdfFile(path);
    FAIL() << "expected LoadError";
  } catch (const LoadError& e) {
    const std::string message = e.what();
    for (const std::string& part : std::vector<std::string>{
             path + ": 2 links are not below the root link 'base' ('a', 'b')", "form a loop",
          "is a <parent link> mistyped?"}) {
      EXPECT_NE(message.find(part), std::string::npos) << part << " not in " << message;
    }
    EXPECT_TRUE(message.find("joint 'j2' has parent 'b' and child 'a'") != std::string::npos ||
                message.find("joint 'j3' has parent 'a' and child 'b'") != std::string::npos)
        << message;
  }
}

// A link the walk from the root reaches twice -- the child of two joints: a copied joint, or a
// loop below the root (urdfdom accepts both) -- is refused naming the link and both joints (the
// walk went round the loop until memory ran out; a copied joint crashed the loop check).
TEST(KinematicsFk, ALinkReachedTwiceIsRejected) {
  const std::string revolute = " type='revolute'><axis xyz='0 0 1'/><limit lower='-1' upper='1' "
                               "velocity='1' effort='1'/>";
  for (const auto& [name, joints, parts] :
       {std::tuple{"copied_joint",
                   "<joint name='j1'" + revolute + "<parent link='base'/><child link='a'/></joint>"
                   "<joint name='j2'" + revolute + "<parent link='base'/><child link='a'/></joint>"
                   "<joint name='j3'" + revolute + "<parent link='a'/><child link='b'/></joint>",
                   std::string("link 'a' is the child of more than one joint: 'j1' (parent "
                               "'base'), 'j2' (parent 'base')")},
        std::tuple{"loop_below_root",
                   "<joint name='j1'" + revolute + "<parent link='base'/><child link='a'/></joint>"
                   "<joint name='j2'" + revolute + "<parent link='a'/><child link='b'/></joint>"
                   "<joint name='j3'" + revolute + "<parent link='b'/><child link='a'/></joint>",
                   std::string("link 'a' is the child of more than one joint: 'j1' (parent "
                               "'base'), 'j3' (parent 'b')")}}) {
    const std::string path = ::testing::TempDir() + name + ".urdf";
    std::ofstream(path) << "<robot name='r'><link name='base'/><link name='a'/><link name='b'/>"
                        << joints << "</robot>\n";
    try {
      KinematicModel::FromUrdfFile(path);
      ADD_FAILURE() << "expected LoadError for " << name;
    } catch (const LoadError& e) {
      EXPECT_NE(std::string(e.what()).find(path + ": " + parts), std::string::npos) << e.what();
    }
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
