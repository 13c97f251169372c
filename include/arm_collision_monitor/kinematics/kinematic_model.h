// Forward kinematics of a URDF joint tree with Eigen (Model/Data split: the model is built once
// from the URDF; link poses are written into caller-owned storage, no allocation per call).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "arm_collision_monitor/core/constants.h"
#include "arm_collision_monitor/core/load_error.h"

namespace urdf {
class ModelInterface;  // urdfdom's parsed URDF (urdf_model/model.h)
class JointMimic;      // a joint's <mimic> element (urdf_model/joint.h)
}  // namespace urdf

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
  const std::vector<std::string>& link_names() const { return link_names_; }
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
  /// Names of the mimic joints (their positions follow from the joints they mimic), in link
  /// order.
  std::vector<std::string> MimicJointNames() const;
  /// True iff the URDF has a fixed joint named `joint_name` (a driver may publish one: a
  /// Sawyer's torso_t0).
  bool IsFixedJoint(const std::string& joint_name) const;
  /// The links below continuous joints without limits (none set by SetPositionLimits either)
  /// whose positions a whole turn apart are one pose of the model: none of the mimic joints
  /// that follow the joint slides (a prismatic one) or turns by other than whole turns (a
  /// multiplier not a whole number). A driver may report such a joint wrapped, and MoveIt
  /// unwinds a plan's before executing it.
  std::vector<int> TurningLinks() const;
  /// The largest magnitude of the position of `joint` (one of this model's, actuated or mimic;
  /// rad or m) at any position the monitor accepts (AcceptedRange): for an actuated joint an
  /// end of its own range, for a mimic one where the joint it mimics puts it at an end of that
  /// joint's range (multiplier times its position, plus the offset; the mimic's own limits do
  /// not clamp it); inf for a mimic whose leader is not in the model.
  double PositionBound(const JointSpec& joint) const;
  /// How far the child of `joint` can slide from the joint's origin, m: PositionBound for a
  /// prismatic joint, 0 for other joints.
  double Travel_m(const JointSpec& joint) const;
  /// The limits of actuated joint `joint`, a side without one at kMaxUnlimitedPosition_rad (the
  /// monitor refuses a position beyond it).
  static std::pair<double, double> PositionRange(const JointSpec& joint);
  /// The positions the monitor accepts of actuated joint `joint`: PositionRange, its limits
  /// widened by kJointLimitMargin.
  static std::pair<double, double> AcceptedRange(const JointSpec& joint);
  /// The joint `joint` (one of this model's) mimics, nullptr if it mimics none.
  const JointSpec* MimickedJoint(const JointSpec& joint) const;
  /// The link whose parent joint is named `joint_name`, -1 if unknown.
  int FindJointChildLink(const std::string& joint_name) const;
  /// True iff link `link` can move relative to the root (an actuated or mimic joint lies
  /// between them).
  bool is_moving(int link) const { return is_moving_[link]; }

  /// X_WL for every link, given actuated positions q (size q_size()). `X_WL` must already have
  /// link_count() entries. Every entry is written (all 16 matrix coefficients); no allocation.
  void ComputeLinkPoses(const Eigen::Ref<const Eigen::VectorXd>& q,
                        std::vector<Eigen::Isometry3d>* X_WL) const;
  /// The moving links (is_moving) whose poses those of the links flagged in `targets` (one
  /// flag a link, link_count() of them) need, into `links` (cleared first; no allocation
  /// within its capacity): the moving targets and every moving link between them and the root,
  /// in link order. `targets` comes back with those links between flagged too. A per-cycle
  /// loop computes only these (ComputeLinkPosesOf): the links fixed to the root never change,
  /// and a frame without geometry below the last link that carries any (a camera, a tool
  /// point) is not needed.
  void MovingLinksTo(std::vector<std::uint8_t>* targets, std::vector<int>* links) const;
  /// ComputeLinkPoses for `links` only (as MovingLinksTo gives them: in link order, each link's
  /// parent either in `links` or not moving): the other entries are left untouched.
  /// Precondition: the entries of the parents not in `links` already hold their poses, i.e.
  /// `X_WL` was filled by ComputeLinkPoses since X_WRoot last changed. Same results, bit for
  /// bit, as ComputeLinkPoses for the links it writes.
  void ComputeLinkPosesOf(const Eigen::Ref<const Eigen::VectorXd>& q, const std::vector<int>& links,
                          std::vector<Eigen::Isometry3d>* X_WL) const;
  /// ComputeLinkPosesOf for those of `links` that the move from q_before to q moves: the links
  /// below a joint whose position differs bit for bit between them (an actuated joint's q, or a
  /// mimic joint's target's). Preconditions: X_WL holds the poses at q_before (of `links` and of
  /// what ComputeLinkPosesOf reads); X_WL_before agrees with X_WL on the links that do not move.
  /// For each of `links`, (*changed)[link] is set to 1 if it was recomputed, else 0, and a
  /// recomputed link's pose at q_before is left in (*X_WL_before)[link]. When all of `links`
  /// move, the two vectors trade places (no copies), so the entries of the moving links not in
  /// `links` come back exchanged. `changed` holds one flag a link (link_count()), 0 for the
  /// links that do not move; `scratch` has links.size() entries; no allocation. The same poses,
  /// bit for bit, as ComputeLinkPosesOf.
  void UpdateLinkPosesOf(const Eigen::Ref<const Eigen::VectorXd>& q,
                         const Eigen::Ref<const Eigen::VectorXd>& q_before,
                         const std::vector<int>& links, std::vector<Eigen::Isometry3d>* X_WL,
                         std::vector<Eigen::Isometry3d>* X_WL_before,
                         std::vector<std::uint8_t>* changed, std::vector<int>* scratch) const;

  /// Checks the invariants (parents precede children, q indices are 0..q_size()-1 once each,
  /// unit axes, lower <= upper, mimic targets actuated, the forward kinematics' precomputed
  /// per-joint data matches the joints). False with a reason otherwise.
  bool Validate(std::string* why) const;

  /// Start-up only: replaces the position limits of actuated joint `joint_name` (e.g. soft
  /// limits from the scene file). False if no actuated joint has that name.
  bool SetPositionLimits(const std::string& joint_name, double lower, double upper);
  /// Start-up only: replaces the velocity limit of actuated joint `joint_name` (rad/s or m/s,
  /// from the scene file). False if no actuated joint has that name.
  bool SetVelocityLimit(const std::string& joint_name, double max_velocity);

  /// Builds the model from a URDF file. Throws LoadError naming the file and element.
  static KinematicModel FromUrdfFile(const std::string& urdf_path);
  /// Builds the model from a URDF already parsed from `urdf_path` (ParseUrdfFile), for a caller
  /// that also reads the URDF's collision geometry and must not parse the file twice.
  /// `urdf_path` only names the file in LoadError messages.
  static KinematicModel FromUrdf(const urdf::ModelInterface& urdf_model,
                                 const std::string& urdf_path);

  /// Pose of the root link in W (identity unless the caller places the robot).
  Eigen::Isometry3d X_WRoot = Eigen::Isometry3d::Identity();

 private:
  // What ComputeLinkPoses does for the joint into one link (parent P, joint frame J, link L):
  // X_WL = X_WP * X_PJ * (joint motion), with everything that does not depend on q precomputed
  // from the JointSpec by MakeFkStep.
  enum class FkMotion : char {
    kNone,                       // fixed joint
    kTranslate,                  // prismatic: p_JL = position * axis_J
    kRotateAboutCoordinateAxis,  // revolute/continuous about +e_axis (a -e_axis flips the sign)
    kRotateAboutAxis,            // revolute/continuous about any other unit axis_J
  };
  struct FkStep {
    FkMotion motion = FkMotion::kNone;
    int parent = -1;
    // The joint position is multiplier * q[position_q_index] + offset (1 and 0 for actuated
    // joints, the mimic's multiplier and offset for mimic joints, both negated when the axis
    // is -e_axis; index -1 for fixed joints).
    int position_q_index = -1;
    double multiplier = 1.0;
    double offset = 0.0;
    bool is_R_PJ_identity = false;  // exactly the identity: X_WJ then needs no rotation product
    Eigen::Matrix3d R_PJ = Eigen::Matrix3d::Identity();
    Eigen::Vector3d p_PJ = Eigen::Vector3d::Zero();  // m
    int coordinate_axis = 2;  // kRotateAboutCoordinateAxis: 0, 1, 2 for x, y, z
    Eigen::Vector3d axis_J = Eigen::Vector3d::UnitZ();
    // kRotateAboutAxis: K = [axis_J]x and K^2, for R_JL = I + sin K + (1 - cos) K^2.
    Eigen::Matrix3d K = Eigen::Matrix3d::Zero();
    Eigen::Matrix3d K2 = Eigen::Matrix3d::Zero();
  };
  static FkStep MakeFkStep(const JointSpec& joint, int parent);
  // The joint position (rad or m) that q gives the joint of `step`.
  static double JointPosition(const FkStep& step, const Eigen::Ref<const Eigen::VectorXd>& q) {
    return step.multiplier * q[step.position_q_index] + step.offset;
  }
  // Sine and cosine of the rotating joints of a block of at most kFkBlockLinks links, in link
  // order; `next` is the next rotating joint's index into them.
  struct FkBlockAngles {
    double sin_theta[kFkBlockLinks];
    double cos_theta[kFkBlockLinks];
    int next = 0;
  };
  // Pass 1 of ComputePoses: the angles of the rotating joints of links link_at(first) to
  // link_at(end - 1).
  template <typename LinkAt>
  void ComputeBlockAngles(const Eigen::Ref<const Eigen::VectorXd>& q, LinkAt link_at, int first,
                          int end, FkBlockAngles* angles) const;
  // Pass 2 of ComputePoses for one link: T_WL = T_WP * X_PJ * (joint motion), on whole 4-row
  // columns of the 4x4 matrices (aligned vector lanes; the bottom rows 0 0 0 1 come out right
  // by themselves). A rotating joint takes the next angle of `angles`.
  static void ComputeLinkPose(const FkStep& step, const Eigen::Ref<const Eigen::VectorXd>& q,
                              FkBlockAngles* angles, const Eigen::Matrix4d& T_WP,
                              Eigen::Matrix4d* T_WL);
  // The one forward-kinematics loop behind ComputeLinkPoses and ComputeLinkPosesOf: the poses
  // of links link_at(0) to link_at(count - 1), in link order.
  template <typename LinkAt>
  void ComputePoses(const Eigen::Ref<const Eigen::VectorXd>& q, LinkAt link_at, int count,
                    std::vector<Eigen::Isometry3d>* X_WL) const;
  // Exact (bitwise) equality, for Validate.
  static bool FkStepsEqual(const FkStep& a, const FkStep& b);
  // FromUrdf's last step for a <mimic> joint (child link `link`): its target's q index, its
  // multiplier and offset, validated.
  void ResolveMimic(int link, const urdf::JointMimic& mimic, const std::string& urdf_path);

  std::vector<std::string> link_names_;
  std::vector<int> parent_link_;
  std::vector<JointSpec> joints_;
  std::vector<char> is_moving_;  // char, not bool: plain storage, indexed per link
  std::vector<FkStep> fk_steps_;  // per link, entry 0 (the root) unused; see MakeFkStep
  int q_size_ = 0;
};

}  // namespace arm_collision_monitor
