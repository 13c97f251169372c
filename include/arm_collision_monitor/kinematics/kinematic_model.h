// Forward kinematics of a URDF joint tree with Eigen (Model/Data split: the model is built once
// from the URDF; link poses are written into caller-owned storage, no allocation per call).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "arm_collision_monitor/core/load_error.h"

namespace arm_collision_monitor {

/// The URDF joint types the model supports (floating and planar are rejected at load).
enum class JointType { kFixed, kRevolute, kContinuous, kPrismatic };

/// The joint that connects a link to its parent link.
struct JointSpec {
  std::string name;
  JointType type = JointType::kFixed;
  Eigen::Isometry3d X_PJ = Eigen::Isometry3d::Identity();  ///< joint origin in parent link P
  Eigen::Vector3d axis_J = Eigen::Vector3d::UnitZ();       ///< unit axis in the joint frame
  int q_index = -1;    ///< index into q for actuated joints, -1 for fixed
  double lower = 0.0;  ///< position limits (rad or m); +/-inf for continuous
  double upper = 0.0;
  double max_velocity = 0.0;  ///< rad/s or m/s
  /// A URDF <mimic> joint is not actuated (q_index = -1): its position is
  /// mimic_multiplier * q[mimic_q_index] + mimic_offset. -1 when the joint mimics nothing.
  int mimic_q_index = -1;
  double mimic_multiplier = 1.0;
  double mimic_offset = 0.0;
};

/// A URDF joint tree, immutable after FromUrdfFile (apart from start-up soft limits).
class KinematicModel {
 public:
  /// Links in topological order: a link's parent always has a smaller index; link 0 is the
  /// root (its pose is X_WRoot).
  int link_count() const { return static_cast<int>(link_names_.size()); }
  const std::string& link_name(int link) const { return link_names_[link]; }
  /// -1 if unknown.
  int FindLink(const std::string& name) const;
  /// Parent link index, -1 for the root.
  int parent_link(int link) const { return parent_link_[link]; }
  /// The joint from parent_link(link) to `link` (unused for the root).
  const JointSpec& joint(int link) const { return joints_[link]; }
  /// Number of actuated joints (the size of q).
  int q_size() const { return q_size_; }
  /// Names of the actuated joints in q order (depth-first over the tree, siblings by joint
  /// name, so the order does not depend on the order of elements in the file).
  std::vector<std::string> ActuatedJointNames() const;
  /// The link whose parent joint is named `joint_name`, -1 if unknown.
  int FindJointChildLink(const std::string& joint_name) const;
  /// True iff link `link` can move relative to the root (an actuated or mimic joint lies
  /// between them).
  bool is_moving(int link) const { return is_moving_[link]; }

  /// X_WL for every link, given actuated positions q (size q_size()). `X_WL` must already have
  /// link_count() entries.
  void ComputeLinkPoses(const Eigen::Ref<const Eigen::VectorXd>& q,
                        std::vector<Eigen::Isometry3d>* X_WL) const;

  /// Checks the invariants (parents precede children, q indices are 0..q_size()-1 once each,
  /// unit axes, lower <= upper, mimic targets actuated). False with a reason otherwise.
  bool Validate(std::string* why) const;

  /// Start-up only: replaces the position limits of actuated joint `joint_name` (e.g. soft
  /// limits from the scene file). False if no actuated joint has that name.
  bool SetPositionLimits(const std::string& joint_name, double lower, double upper);

  /// Builds the model from a URDF file. Throws LoadError naming the file and element.
  static KinematicModel FromUrdfFile(const std::string& urdf_path);

  /// Pose of the root link in W (identity unless the caller places the robot).
  Eigen::Isometry3d X_WRoot = Eigen::Isometry3d::Identity();

 private:
  std::vector<std::string> link_names_;
  std::vector<int> parent_link_;
  std::vector<JointSpec> joints_;
  std::vector<char> is_moving_;  // char, not bool: plain storage, indexed per link
  int q_size_ = 0;
};

}  // namespace arm_collision_monitor
