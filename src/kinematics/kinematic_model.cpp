// Forward kinematics over a URDF joint tree (Craig, "Introduction to Robotics", ch. 3: a link's
// pose is its parent's pose composed with the joint origin and the joint motion).
#include "arm_collision_monitor/kinematics/kinematic_model.h"

#include <urdf_model/model.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <unordered_set>

#include "arm_collision_monitor/core/constants.h"
#include "arm_collision_monitor/kinematics/sin_cos.h"
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
  if (n == 0 || parent_link_.size() != n || joints_.size() != n || is_moving_.size() != n ||
      fk_steps_.size() != n) {
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
    // The precomputed FK data must be exactly what the joint spec gives (MakeFkStep is
    // deterministic, so equality is bitwise).
    if (!FkStepsEqual(fk_steps_[link], MakeFkStep(joint, parent_link_[link]))) {
      return fail(link, "precomputed forward-kinematics data disagrees with the joint");
    }
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

bool KinematicModel::SetVelocityLimit(const std::string& joint_name, double max_velocity) {
  const int link = FindJointChildLink(joint_name);
  if (link < 0 || joints_[link].q_index < 0) return false;
  joints_[link].max_velocity = max_velocity;
  return true;
}

std::vector<std::string> KinematicModel::ActuatedJointNames() const {
  std::vector<std::string> names(q_size_);
  for (int link = 1; link < link_count(); ++link) {
    if (joints_[link].q_index >= 0) names[joints_[link].q_index] = joints_[link].name;
  }
  return names;
}

std::vector<std::string> KinematicModel::MimicJointNames() const {
  std::vector<std::string> names;
  for (int link = 1; link < link_count(); ++link) {
    if (joints_[link].mimic_q_index >= 0) names.push_back(joints_[link].name);
  }
  return names;
}

std::vector<int> KinematicModel::TurningLinks() const {
  std::vector<int> links;
  for (int link = 1; link < link_count(); ++link) {
    const JointSpec& joint = joints_[link];
    if (joint.q_index < 0 || joint.type != JointType::kContinuous ||
        std::isfinite(joint.lower) || std::isfinite(joint.upper)) {
      continue;
    }
    bool is_one_pose = true;
    for (int other = 1; other < link_count(); ++other) {
      const JointSpec& mimic = joints_[other];
      if (mimic.mimic_q_index != joint.q_index) continue;
      is_one_pose &= mimic.type != JointType::kPrismatic &&
                     mimic.mimic_multiplier == std::round(mimic.mimic_multiplier);
    }
    if (is_one_pose) links.push_back(link);
  }
  return links;
}

double KinematicModel::PositionBound(const JointSpec& joint) const {
  const bool is_mimic = joint.mimic_q_index >= 0;
  const JointSpec* leader = is_mimic ? MimickedJoint(joint) : &joint;
  if (leader == nullptr) return std::numeric_limits<double>::infinity();
  // Linear in the leader's position, which is finite: farthest at an end of its range.
  const auto [lower, upper] = AcceptedRange(*leader);
  const double m = is_mimic ? joint.mimic_multiplier : 1.0;
  const double offset = is_mimic ? joint.mimic_offset : 0.0;
  return std::max(std::abs(m * lower + offset), std::abs(m * upper + offset));
}

double KinematicModel::Travel_m(const JointSpec& joint) const {
  return joint.type == JointType::kPrismatic ? PositionBound(joint) : 0.0;
}

std::pair<double, double> KinematicModel::PositionRange(const JointSpec& joint) {
  return {std::isfinite(joint.lower) ? joint.lower : -kMaxUnlimitedPosition_rad,
          std::isfinite(joint.upper) ? joint.upper : kMaxUnlimitedPosition_rad};
}

std::pair<double, double> KinematicModel::AcceptedRange(const JointSpec& joint) {
  const auto [lower, upper] = PositionRange(joint);
  return {std::isfinite(joint.lower) ? lower - kJointLimitMargin : lower,
          std::isfinite(joint.upper) ? upper + kJointLimitMargin : upper};
}

const JointSpec* KinematicModel::MimickedJoint(const JointSpec& joint) const {
  if (joint.mimic_q_index < 0) return nullptr;
  for (int link = 1; link < link_count(); ++link) {
    if (joints_[link].q_index == joint.mimic_q_index) return &joints_[link];
  }
  return nullptr;
}

bool KinematicModel::IsFixedJoint(const std::string& joint_name) const {
  const int link = FindJointChildLink(joint_name);
  return link > 0 && joints_[link].type == JointType::kFixed;
}

KinematicModel::FkStep KinematicModel::MakeFkStep(const JointSpec& joint, int parent) {
  FkStep step;
  step.parent = parent;
  if (joint.q_index >= 0) {
    step.position_q_index = joint.q_index;
  } else if (joint.mimic_q_index >= 0) {
    step.position_q_index = joint.mimic_q_index;
    step.multiplier = joint.mimic_multiplier;
    step.offset = joint.mimic_offset;
  }
  step.R_PJ = joint.X_PJ.linear();
  step.p_PJ = joint.X_PJ.translation();
  step.is_R_PJ_identity = step.R_PJ == Eigen::Matrix3d::Identity();
  step.axis_J = joint.axis_J;
  switch (joint.type) {
    case JointType::kFixed:
      step.motion = FkMotion::kNone;
      break;
    case JointType::kPrismatic:
      step.motion = FkMotion::kTranslate;
      break;
    case JointType::kRevolute:
    case JointType::kContinuous: {
      int axis = 0;
      const double largest = joint.axis_J.cwiseAbs().maxCoeff(&axis);
      if (largest == 1.0 && (joint.axis_J.array() == 0.0).count() == 2) {  // exactly +-e_axis
        step.motion = FkMotion::kRotateAboutCoordinateAxis;
        step.coordinate_axis = axis;
        if (joint.axis_J[axis] < 0.0) {  // about -e by theta is about +e by -theta (exact)
          step.multiplier = -step.multiplier;
          step.offset = -step.offset;
        }
      } else {
        step.motion = FkMotion::kRotateAboutAxis;
        const Eigen::Vector3d& k = joint.axis_J;
        step.K << 0.0, -k.z(), k.y(),  //
            k.z(), 0.0, -k.x(),        //
            -k.y(), k.x(), 0.0;
        step.K2 = step.K * step.K;
      }
      break;
    }
  }
  return step;
}

bool KinematicModel::FkStepsEqual(const FkStep& a, const FkStep& b) {
  return a.motion == b.motion && a.parent == b.parent &&
         a.position_q_index == b.position_q_index && a.multiplier == b.multiplier &&
         a.offset == b.offset && a.is_R_PJ_identity == b.is_R_PJ_identity && a.R_PJ == b.R_PJ &&
         a.p_PJ == b.p_PJ && a.coordinate_axis == b.coordinate_axis && a.axis_J == b.axis_J &&
         a.K == b.K && a.K2 == b.K2;
}

void KinematicModel::MovingLinksTo(std::vector<std::uint8_t>* targets,
                                   std::vector<int>* links) const {
  // Children follow their parents: one pass from the leaves up flags the links between.
  std::vector<std::uint8_t>& is_needed = *targets;
  for (int link = link_count() - 1; link > 0; --link) {
    if (is_needed[link]) is_needed[parent_link_[link]] = 1;
  }
  links->clear();
  for (int link = 1; link < link_count(); ++link) {
    if (is_needed[link] && is_moving_[link]) links->push_back(link);
  }
}

// ComputeBlockAngles and ComputeLinkPose are steps of ComputePoses, the hot path of every
// cycle: forced inline there (an out-of-line call per link, through the shared library's PLT,
// measured slower).
template <typename LinkAt>
EIGEN_ALWAYS_INLINE void KinematicModel::ComputeBlockAngles(
    const Eigen::Ref<const Eigen::VectorXd>& q, LinkAt link_at, int first, int end,
    FkBlockAngles* angles) const {
  // The rotations' sines and cosines do not depend on each other, so they overlap in the
  // pipeline instead of stalling the chain of pose products.
  double theta[kFkBlockLinks];
  int rotation_count = 0;
  for (int i = first; i < end; ++i) {
    const FkStep& step = fk_steps_[link_at(i)];
    if (step.motion == FkMotion::kRotateAboutCoordinateAxis ||
        step.motion == FkMotion::kRotateAboutAxis) {
      theta[rotation_count++] = JointPosition(step, q);
    }
  }
  SinCos(theta, rotation_count, angles->sin_theta, angles->cos_theta);
  angles->next = 0;
}

EIGEN_ALWAYS_INLINE void KinematicModel::ComputeLinkPose(
    const FkStep& step, const Eigen::Ref<const Eigen::VectorXd>& q, FkBlockAngles* angles,
    const Eigen::Matrix4d& T_WP, Eigen::Matrix4d* T_WL) {
  const Eigen::Vector4d P0 = T_WP.col(0), P1 = T_WP.col(1), P2 = T_WP.col(2);
  // Columns of X_WJ.
  Eigen::Vector4d c0 = P0, c1 = P1, c2 = P2;
  if (!step.is_R_PJ_identity) {
    const Eigen::Matrix3d& R = step.R_PJ;
    c0 = P0 * R(0, 0) + P1 * R(1, 0) + P2 * R(2, 0);
    c1 = P0 * R(0, 1) + P1 * R(1, 1) + P2 * R(2, 1);
    c2 = P0 * R(0, 2) + P1 * R(1, 2) + P2 * R(2, 2);
  }
  const Eigen::Vector3d& p = step.p_PJ;
  Eigen::Vector4d c3 = P0 * p.x() + P1 * p.y() + P2 * p.z() + T_WP.col(3);
  // Rotation by theta about a coordinate axis mixes the other two columns:
  // (ca, cb) <- (c ca + s cb, c cb - s ca), for (a, b) the cyclic successors of the axis.
  const int rotation = angles->next;
  auto rotate = [&](Eigen::Vector4d* ca, Eigen::Vector4d* cb) {
    const double s = angles->sin_theta[rotation], c = angles->cos_theta[rotation];
    const Eigen::Vector4d a = *ca;
    *ca = a * c + *cb * s;
    *cb = *cb * c - a * s;
  };
  switch (step.motion) {
    case FkMotion::kNone:
      break;
    case FkMotion::kTranslate: {
      const Eigen::Vector3d& k = step.axis_J;
      c3 += JointPosition(step, q) * (c0 * k.x() + c1 * k.y() + c2 * k.z());
      break;
    }
    case FkMotion::kRotateAboutCoordinateAxis:
      if (step.coordinate_axis == 0) {
        rotate(&c1, &c2);
      } else if (step.coordinate_axis == 1) {
        rotate(&c2, &c0);
      } else {
        rotate(&c0, &c1);
      }
      ++angles->next;
      break;
    case FkMotion::kRotateAboutAxis: {
      // Rodrigues' formula: R_JL = I + sin(theta) K + (1 - cos(theta)) K^2, K = [k]x.
      const Eigen::Matrix3d R = Eigen::Matrix3d::Identity() +
                                angles->sin_theta[rotation] * step.K +
                                (1.0 - angles->cos_theta[rotation]) * step.K2;
      ++angles->next;
      const Eigen::Vector4d J0 = c0, J1 = c1, J2 = c2;
      c0 = J0 * R(0, 0) + J1 * R(1, 0) + J2 * R(2, 0);
      c1 = J0 * R(0, 1) + J1 * R(1, 1) + J2 * R(2, 1);
      c2 = J0 * R(0, 2) + J1 * R(1, 2) + J2 * R(2, 2);
      break;
    }
  }
  T_WL->col(0) = c0;
  T_WL->col(1) = c1;
  T_WL->col(2) = c2;
  T_WL->col(3) = c3;
}

template <typename LinkAt>
void KinematicModel::ComputePoses(const Eigen::Ref<const Eigen::VectorXd>& q, LinkAt link_at,
                                  int count, std::vector<Eigen::Isometry3d>* X_WL) const {
  auto& poses = *X_WL;
  for (int first = 0; first < count; first += kFkBlockLinks) {
    const int end = std::min(count, first + kFkBlockLinks);
    // Pass 1: sine and cosine of every rotating joint of the block.
    FkBlockAngles angles;
    ComputeBlockAngles(q, link_at, first, end, &angles);
    // Pass 2: X_WL = X_WP * X_PJ * (joint motion), link by link.
    for (int i = first; i < end; ++i) {
      const int link = link_at(i);
      const FkStep& step = fk_steps_[link];
      ComputeLinkPose(step, q, &angles, poses[step.parent].matrix(), &poses[link].matrix());
    }
  }
}

void KinematicModel::ComputeLinkPoses(const Eigen::Ref<const Eigen::VectorXd>& q,
                                      std::vector<Eigen::Isometry3d>* X_WL) const {
  auto& poses = *X_WL;
  poses[0] = X_WRoot;
  poses[0].makeAffine();  // the 4-row column arithmetic below relies on the bottom row 0 0 0 1
  ComputePoses(q, [](int i) { return i + 1; }, link_count() - 1, X_WL);
}

void KinematicModel::ComputeLinkPosesOf(const Eigen::Ref<const Eigen::VectorXd>& q,
                                        const std::vector<int>& links,
                                        std::vector<Eigen::Isometry3d>* X_WL) const {
  const int* const link_of = links.data();
  ComputePoses(q, [link_of](int i) { return link_of[i]; }, static_cast<int>(links.size()), X_WL);
}

void KinematicModel::UpdateLinkPosesOf(const Eigen::Ref<const Eigen::VectorXd>& q,
                                       const Eigen::Ref<const Eigen::VectorXd>& q_before,
                                       const std::vector<int>& links,
                                       std::vector<Eigen::Isometry3d>* X_WL,
                                       std::vector<Eigen::Isometry3d>* X_WL_before,
                                       std::vector<std::uint8_t>* changed,
                                       std::vector<int>* scratch) const {
  std::uint8_t* const is_changed = changed->data();
  int* const recomputed = scratch->data();
  int count = 0;
  // In link order, so a parent's flag is set before its children read it.
  for (const int link : links) {
    const FkStep& step = fk_steps_[link];
    const int i = step.position_q_index;
    const bool is_moved =
        is_changed[step.parent] != 0 ||
        (i >= 0 && std::memcmp(q.data() + i, q_before.data() + i, sizeof(double)) != 0);
    is_changed[link] = is_moved ? 1 : 0;
    if (is_moved) recomputed[count++] = link;
  }
  if (count == 0) return;
  if (count == static_cast<int>(links.size())) {
    // All of them: computed into X_WL_before, which then trades places with X_WL (no copies).
    const int* const link_of = links.data();
    ComputePoses(q, [link_of](int i) { return link_of[i]; }, count, X_WL_before);
    X_WL->swap(*X_WL_before);
    return;
  }
  for (int i = 0; i < count; ++i) (*X_WL_before)[recomputed[i]] = (*X_WL)[recomputed[i]];
  ComputePoses(q, [recomputed](int i) { return recomputed[i]; }, count, X_WL);
}

KinematicModel KinematicModel::FromUrdfFile(const std::string& urdf_path) {
  return FromUrdf(*ParseUrdfFile(urdf_path), urdf_path);
}

namespace {

// The model's joint type for a URDF joint type; floating and planar joints are rejected.
JointType JointTypeFromUrdf(int urdf_type, const std::string& where) {
  switch (urdf_type) {
    case urdf::Joint::FIXED:
      return JointType::kFixed;
    case urdf::Joint::REVOLUTE:
      return JointType::kRevolute;
    case urdf::Joint::CONTINUOUS:
      return JointType::kContinuous;
    case urdf::Joint::PRISMATIC:
      return JointType::kPrismatic;
    case urdf::Joint::FLOATING:
    case urdf::Joint::PLANAR:
      // A simulator's URDF often floats the base on the world: the monitor works in the frame
      // of the root link, so a base that stays put in the workcell is a fixed joint there.
      throw LoadError(where +
                      ": floating and planar joints are not supported (expected revolute, "
                      "continuous, prismatic or fixed): a joint state gives no pose of a free "
                      "body; if it is the base on the world and the base stays put in the "
                      "workcell, make it type='fixed' at the base's place (<origin>), or drop it "
                      "and the world link: the monitor works in the root link's frame");
    default:
      throw LoadError(where +
                      ": unknown joint type (expected revolute, continuous, "
                      "prismatic or fixed)");
  }
}

// The unit axis and the position and velocity limits of a non-fixed joint, validated.
void ReadJointAxisAndLimits(const urdf::Joint& joint, const std::string& where, JointSpec* spec) {
  const Eigen::Vector3d axis(joint.axis.x, joint.axis.y, joint.axis.z);
  if (!axis.allFinite() || axis.norm() < kMinJointAxisNorm) {
    throw LoadError(where + ": <axis> must be a finite non-zero vector");
  }
  spec->axis_J = axis.normalized();
  if (spec->type == JointType::kContinuous) {
    spec->lower = -std::numeric_limits<double>::infinity();
    spec->upper = std::numeric_limits<double>::infinity();
  } else if (joint.limits) {
    spec->lower = joint.limits->lower;
    spec->upper = joint.limits->upper;
    if (!std::isfinite(spec->lower) || !std::isfinite(spec->upper) ||
        spec->lower > spec->upper) {
      throw LoadError(where + ": <limit> must have finite lower <= upper");
    }
  }
  if (joint.limits) {
    spec->max_velocity = joint.limits->velocity;
    if (!std::isfinite(spec->max_velocity) || spec->max_velocity < 0.0) {
      throw LoadError(where + ": <limit velocity> must be finite and >= 0");
    }
  }
}

// The joint spec of a URDF joint without its q or mimic indices (FromUrdf assigns those).
JointSpec JointSpecFromUrdf(const urdf::Joint& joint, const std::string& urdf_path) {
  const std::string where = urdf_path + ": joint '" + joint.name + "'";
  JointSpec spec;
  spec.name = joint.name;
  spec.X_PJ = UrdfPoseToIsometry(joint.parent_to_joint_origin_transform);
  if (!IsFinitePose(spec.X_PJ)) throw LoadError(where + ": <origin> must be finite");
  spec.type = JointTypeFromUrdf(joint.type, where);
  if (spec.type != JointType::kFixed) ReadJointAxisAndLimits(joint, where, &spec);
  return spec;
}

// A link still to visit in FromUrdf's depth-first walk, with its parent's link index.
struct PendingLink {
  urdf::LinkConstSharedPtr link;
  int parent;
};

// Pushes the children of `link` (index `index`) so that the child whose joint name sorts first
// is popped (visited) first.
void PushChildrenByJointName(const urdf::Link& link, int index, std::vector<PendingLink>* stack) {
  std::vector<urdf::LinkConstSharedPtr> children(link.child_links.begin(),
                                                 link.child_links.end());
  std::sort(children.begin(), children.end(), [](const auto& a, const auto& b) {
    return a->parent_joint->name < b->parent_joint->name;
  });
  for (auto it = children.rbegin(); it != children.rend(); ++it) {
    stack->push_back({*it, index});
  }
}

// The refusal of a URDF whose links are not all below its root: with one root, they hang in a
// loop of joints (a mistyped <parent link>), found by walking up from one of them.
LoadError UnreachedLinks(const urdf::ModelInterface& urdf_model, const KinematicModel& model,
                         const std::string& urdf_path) {
  std::vector<std::string> unreached;
  for (const auto& [name, link] : urdf_model.links_) {
    if (model.FindLink(name) < 0) unreached.push_back(name);
  }
  std::vector<std::string> loop;
  urdf::LinkConstSharedPtr link = urdf_model.getLink(unreached.front());
  while (link && std::find(loop.begin(), loop.end(), link->name) == loop.end()) {
    loop.push_back(link->name);
    link = link->getParent();
  }
  std::string why = urdf_path + ": " + std::to_string(unreached.size()) +
                    (unreached.size() == 1 ? " link is" : " links are") +
                    " not below the root link '" + model.link_name(0) + "' (" +
                    QuotedNames(unreached) + ")";
  if (link) {
    const urdf::JointConstSharedPtr joint = link->parent_joint;
    why += joint->parent_link_name == joint->child_link_name
               ? ": joint '" + joint->name + "' names '" + joint->child_link_name +
                     "' as both its parent and its child"
               : ": their joints form a loop, each link's <parent link> below it (joint '" +
                     joint->name + "' has parent '" + joint->parent_link_name + "' and child '" +
                     joint->child_link_name + "')";
    why += "; is a <parent link> mistyped?";
  }
  return LoadError(why);
}

// The refusal of a URDF in which the walk from the root reaches link `name` twice: it is the
// child of two joints (a loop below the root, or a copied joint).
LoadError LinkReachedTwice(const urdf::ModelInterface& urdf_model, const std::string& name,
                           const std::string& urdf_path) {
  std::string joints;
  for (const auto& [joint_name, joint] : urdf_model.joints_) {
    if (joint->child_link_name != name) continue;
    joints += (joints.empty() ? "'" : ", '") + joint_name + "' (parent '" +
              joint->parent_link_name + "')";
  }
  return LoadError(urdf_path + ": link '" + name + "' is the child of more than one joint: " +
                   joints + "; a link has one parent joint (is a <parent link> or a <child "
                   "link> mistyped, or a joint copied?)");
}

}  // namespace

KinematicModel KinematicModel::FromUrdf(const urdf::ModelInterface& urdf_model,
                                        const std::string& urdf_path) {
  const urdf::LinkConstSharedPtr root = urdf_model.getRoot();
  if (!root) throw LoadError(urdf_path + ": <robot>: expected exactly one root link");

  KinematicModel model;
  // Depth-first preorder, children sorted by joint name: parents precede children, each arm's
  // joints are contiguous in q, and the order is reproducible.
  std::vector<PendingLink> stack{{root, -1}};
  // Actuated joints get q indices in the order we meet them; mimic joints are resolved after.
  std::vector<std::pair<int, urdf::JointMimicSharedPtr>> mimics;
  std::unordered_set<std::string> visited;
  while (!stack.empty()) {
    const PendingLink current = stack.back();
    stack.pop_back();
    if (!visited.insert(current.link->name).second) {
      throw LinkReachedTwice(urdf_model, current.link->name, urdf_path);
    }
    const int index = model.link_count();
    model.link_names_.push_back(current.link->name);
    model.parent_link_.push_back(current.parent);
    JointSpec spec;
    bool is_moving = false;
    if (current.parent >= 0) {
      const urdf::JointConstSharedPtr joint = current.link->parent_joint;
      spec = JointSpecFromUrdf(*joint, urdf_path);
      if (spec.type != JointType::kFixed) {
        if (joint->mimic) {
          mimics.emplace_back(index, joint->mimic);
        } else {
          spec.q_index = model.q_size_++;
        }
        is_moving = true;
      }
      if (model.is_moving_[current.parent]) is_moving = true;
    }
    model.joints_.push_back(spec);
    model.is_moving_.push_back(is_moving ? 1 : 0);
    PushChildrenByJointName(*current.link, index, &stack);
  }
  if (static_cast<std::size_t>(model.link_count()) != urdf_model.links_.size()) {
    throw UnreachedLinks(urdf_model, model, urdf_path);
  }
  for (const auto& [link, mimic] : mimics) model.ResolveMimic(link, *mimic, urdf_path);
  model.fk_steps_.resize(model.link_count());
  for (int link = 1; link < model.link_count(); ++link) {
    model.fk_steps_[link] = MakeFkStep(model.joints_[link], model.parent_link_[link]);
  }
  return model;
}

void KinematicModel::ResolveMimic(int link, const urdf::JointMimic& mimic,
                                  const std::string& urdf_path) {
  JointSpec& spec = joints_[link];
  const int target = FindJointChildLink(mimic.joint_name);
  if (target < 0 || joints_[target].q_index < 0) {
    // A typo names no joint; a fixed joint, a mimic one or itself has no position of its own.
    const std::string what = target < 0 ? "names no joint of the URDF (a typo?)"
                                        : "names a joint with no position of its own (fixed, "
                                          "itself a mimic, or this joint)";
    throw LoadError(urdf_path + ": joint '" + spec.name + "': <mimic joint='" +
                    mimic.joint_name + "'> " + what +
                    "; it must name an actuated, non-mimic joint");
  }
  spec.mimic_q_index = joints_[target].q_index;
  spec.mimic_multiplier = mimic.multiplier;
  spec.mimic_offset = mimic.offset;
  if (!std::isfinite(spec.mimic_multiplier) || !std::isfinite(spec.mimic_offset)) {
    throw LoadError(urdf_path + ": joint '" + spec.name +
                    "': <mimic> multiplier and offset must be finite");
  }
}

}  // namespace arm_collision_monitor
