// Forward kinematics over a URDF joint tree (Craig, "Introduction to Robotics", ch. 3: a link's
// pose is its parent's pose composed with the joint origin and the joint motion).
#include "arm_collision_monitor/kinematics/kinematic_model.h"

#include <urdf_model/model.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "arm_collision_monitor/core/constants.h"
#include "arm_collision_monitor/kinematics/urdf_conversions.h"

namespace arm_collision_monitor {
namespace {

bool IsFinitePose(const Eigen::Isometry3d& X) { return X.matrix().allFinite(); }

}  // namespace

int KinematicModel::FindLink(const std::string& name) const {
  const auto it = std::find(link_names_.begin(), link_names_.end(), name);
  return it == link_names_.end() ? -1 : static_cast<int>(it - link_names_.begin());
}

int KinematicModel::FindJointChildLink(const std::string& joint_name) const {
  for (int link = 1; link < link_count(); ++link) {
    if (joints_[link].name == joint_name) return link;
  }
  return -1;
}

bool KinematicModel::Validate(std::string* why) const {
  auto fail = [&](int link, const std::string& what) {
    *why = "link " + std::to_string(link) + " '" + link_names_[link] + "': " + what;
    return false;
  };
  const std::size_t n = link_names_.size();
  if (n == 0 || parent_link_.size() != n || joints_.size() != n || is_moving_.size() != n) {
    *why = "per-link arrays are empty or of different sizes";
    return false;
  }
  if (parent_link_[0] != -1) return fail(0, "the root must have no parent");
  std::vector<int> q_owner(q_size_, -1);
  for (int link = 1; link < link_count(); ++link) {
    const JointSpec& joint = joints_[link];
    if (parent_link_[link] < 0 || parent_link_[link] >= link) {
      return fail(link, "its parent does not precede it");
    }
    const bool is_actuated = joint.type != JointType::kFixed;
    if (joint.q_index >= q_size_ ||
        (joint.q_index >= 0) != (is_actuated && joint.mimic_q_index < 0)) {
      return fail(link, "q_index inconsistent with the joint type");
    }
    if (joint.q_index >= 0) {
      if (q_owner[joint.q_index] >= 0) return fail(link, "q_index used twice");
      q_owner[joint.q_index] = link;
    }
    if (is_actuated && std::abs(joint.axis_J.norm() - 1.0) > kUnitAxisNormTolerance) {
      return fail(link, "axis is not a unit vector");
    }
    if (!(joint.lower <= joint.upper)) return fail(link, "lower limit above upper limit");
    if (joint.mimic_q_index >= q_size_) return fail(link, "mimic target out of range");
    const bool moves = is_actuated || is_moving_[parent_link_[link]];
    if (moves != static_cast<bool>(is_moving_[link])) return fail(link, "is_moving is wrong");
  }
  for (int i = 0; i < q_size_; ++i) {
    if (q_owner[i] < 0) {
      *why = "q index " + std::to_string(i) + " has no joint";
      return false;
    }
  }
  return true;
}

bool KinematicModel::SetPositionLimits(const std::string& joint_name, double lower, double upper) {
  const int link = FindJointChildLink(joint_name);
  if (link < 0 || joints_[link].q_index < 0) return false;
  joints_[link].lower = lower;
  joints_[link].upper = upper;
  return true;
}

std::vector<std::string> KinematicModel::ActuatedJointNames() const {
  std::vector<std::string> names(q_size_);
  for (int link = 1; link < link_count(); ++link) {
    if (joints_[link].q_index >= 0) names[joints_[link].q_index] = joints_[link].name;
  }
  return names;
}

void KinematicModel::ComputeLinkPoses(const Eigen::Ref<const Eigen::VectorXd>& q,
                                      std::vector<Eigen::Isometry3d>* X_WL) const {
  auto& poses = *X_WL;
  poses[0] = X_WRoot;
  for (int link = 1; link < link_count(); ++link) {
    const JointSpec& joint = joints_[link];
    const Eigen::Isometry3d X_WJ = poses[parent_link_[link]] * joint.X_PJ;
    double position = 0.0;
    if (joint.q_index >= 0) {
      position = q[joint.q_index];
    } else if (joint.mimic_q_index >= 0) {
      position = joint.mimic_multiplier * q[joint.mimic_q_index] + joint.mimic_offset;
    }
    switch (joint.type) {
      case JointType::kFixed:
        poses[link] = X_WJ;
        break;
      case JointType::kRevolute:
      case JointType::kContinuous:
        poses[link] = X_WJ * Eigen::AngleAxisd(position, joint.axis_J);
        break;
      case JointType::kPrismatic:
        poses[link] = X_WJ * Eigen::Translation3d(position * joint.axis_J);
        break;
    }
  }
}

KinematicModel KinematicModel::FromUrdfFile(const std::string& urdf_path) {
  const urdf::ModelInterfaceSharedPtr urdf_model = ParseUrdfFile(urdf_path);
  const urdf::LinkConstSharedPtr root = urdf_model->getRoot();
  if (!root) throw LoadError(urdf_path + ": <robot>: expected exactly one root link");

  KinematicModel model;
  // Depth-first preorder, children sorted by joint name: parents precede children, each arm's
  // joints are contiguous in q, and the order is reproducible.
  struct Pending {
    urdf::LinkConstSharedPtr link;
    int parent;
  };
  std::vector<Pending> stack{{root, -1}};
  // Actuated joints get q indices in the order we meet them; mimic joints are resolved after.
  std::vector<std::pair<int, urdf::JointMimicSharedPtr>> mimics;
  while (!stack.empty()) {
    const Pending current = stack.back();
    stack.pop_back();
    const int index = model.link_count();
    const std::string& link_name = current.link->name;
    model.link_names_.push_back(link_name);
    model.parent_link_.push_back(current.parent);
    JointSpec spec;
    bool is_moving = false;
    if (current.parent >= 0) {
      const urdf::JointConstSharedPtr joint = current.link->parent_joint;
      const std::string where = urdf_path + ": joint '" + joint->name + "'";
      spec.name = joint->name;
      spec.X_PJ = UrdfPoseToIsometry(joint->parent_to_joint_origin_transform);
      if (!IsFinitePose(spec.X_PJ)) throw LoadError(where + ": <origin> must be finite");
      const Eigen::Vector3d axis(joint->axis.x, joint->axis.y, joint->axis.z);
      switch (joint->type) {
        case urdf::Joint::FIXED:
          spec.type = JointType::kFixed;
          break;
        case urdf::Joint::REVOLUTE:
          spec.type = JointType::kRevolute;
          break;
        case urdf::Joint::CONTINUOUS:
          spec.type = JointType::kContinuous;
          break;
        case urdf::Joint::PRISMATIC:
          spec.type = JointType::kPrismatic;
          break;
        case urdf::Joint::FLOATING:
        case urdf::Joint::PLANAR:
          throw LoadError(where +
                          ": floating and planar joints are not supported (expected revolute, "
                          "continuous, prismatic or fixed)");
        default:
          throw LoadError(where +
                          ": unknown joint type (expected revolute, continuous, "
                          "prismatic or fixed)");
      }
      if (spec.type != JointType::kFixed) {
        if (!axis.allFinite() || axis.norm() < kMinJointAxisNorm) {
          throw LoadError(where + ": <axis> must be a finite non-zero vector");
        }
        spec.axis_J = axis.normalized();
        if (spec.type == JointType::kContinuous) {
          spec.lower = -std::numeric_limits<double>::infinity();
          spec.upper = std::numeric_limits<double>::infinity();
        } else if (joint->limits) {
          spec.lower = joint->limits->lower;
          spec.upper = joint->limits->upper;
          if (!std::isfinite(spec.lower) || !std::isfinite(spec.upper) || spec.lower > spec.upper) {
            throw LoadError(where + ": <limit> must have finite lower <= upper");
          }
        }
        if (joint->limits) {
          spec.max_velocity = joint->limits->velocity;
          if (!std::isfinite(spec.max_velocity) || spec.max_velocity < 0.0) {
            throw LoadError(where + ": <limit velocity> must be finite and >= 0");
          }
        }
        if (joint->mimic) {
          mimics.emplace_back(index, joint->mimic);
        } else {
          spec.q_index = model.q_size_++;
        }
        is_moving = true;
      }
    }
    if (current.parent >= 0 && model.is_moving_[current.parent]) is_moving = true;
    model.joints_.push_back(spec);
    model.is_moving_.push_back(is_moving ? 1 : 0);

    std::vector<urdf::LinkConstSharedPtr> children(current.link->child_links.begin(),
                                                   current.link->child_links.end());
    std::sort(children.begin(), children.end(), [](const auto& a, const auto& b) {
      return a->parent_joint->name < b->parent_joint->name;
    });
    // Reverse so the alphabetically first child is popped (visited) first.
    for (auto it = children.rbegin(); it != children.rend(); ++it) {
      stack.push_back({*it, index});
    }
  }

  for (const auto& [link, mimic] : mimics) {
    JointSpec& spec = model.joints_[link];
    const int target = model.FindJointChildLink(mimic->joint_name);
    if (target < 0 || model.joints_[target].q_index < 0) {
      throw LoadError(urdf_path + ": joint '" + spec.name + "': <mimic joint='" +
                      mimic->joint_name + "'> must name an actuated, non-mimic joint");
    }
    spec.mimic_q_index = model.joints_[target].q_index;
    spec.mimic_multiplier = mimic->multiplier;
    spec.mimic_offset = mimic->offset;
    if (!std::isfinite(spec.mimic_multiplier) || !std::isfinite(spec.mimic_offset)) {
      throw LoadError(urdf_path + ": joint '" + spec.name +
                      "': <mimic> multiplier and offset must be finite");
    }
  }
  return model;
}

}  // namespace arm_collision_monitor
