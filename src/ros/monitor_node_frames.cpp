// The node's fixed frame: the name its reports and markers give the URDF root's frame, in which
// the monitor computes (README "Your own robot", fixed_frame), and the TF lookups into it
// (frame-bound objects, live objects given in a TF frame).

#include <sstream>

#include <Eigen/Geometry>

#include "arm_collision_monitor/core/constants.h"
#include "arm_collision_monitor/core/load_error.h"
#include "arm_collision_monitor/ros/conversions.h"
#include "arm_collision_monitor/ros/monitor_node.h"

namespace arm_collision_monitor {
namespace {

// Whether a frame at pose `X_FRoot` relative to the URDF root is the root's own frame under
// another name: within kFixedFrameMaxOffset_m and kFixedFrameMaxAngle_rad (NaN is not).
bool IsAtRoot(const Eigen::Isometry3d& X_FRoot) {
  return X_FRoot.translation().norm() <= kFixedFrameMaxOffset_m &&
         Eigen::AngleAxisd(X_FRoot.linear()).angle() <= kFixedFrameMaxAngle_rad;
}

// Whether `link` is fixed to the URDF root at the root's own pose (a world link's base_link).
bool IsFixedAtRoot(const KinematicModel& kinematics, int link) {
  if (kinematics.is_moving(link)) return false;
  std::vector<Eigen::Isometry3d> X_WL(kinematics.link_count());
  kinematics.ComputeLinkPoses(Eigen::VectorXd::Zero(kinematics.q_size()), &X_WL);
  return IsAtRoot(X_WL[0].inverse(Eigen::Isometry) * X_WL[link]);
}

}  // namespace

void MonitorNode::ResolveFixedFrame(const std::string& config_fixed_frame) {
  // The launch file's, else the config file's, else the URDF root link's own name.
  const std::string& root = workcell_->fixed_frame;
  fixed_frame_ = !options_.fixed_frame.empty()  ? options_.fixed_frame
                 : !config_fixed_frame.empty() ? config_fixed_frame
                                               : root;
  if (fixed_frame_ == root) return;
  const std::string source = !options_.fixed_frame.empty()
                                 ? "parameter " + private_nh_.resolveName("fixed_frame")
                                 : options_.config_path + ": fixed_frame";
  // tf2 refuses such a frame id (and logs each time it is asked about one).
  if (fixed_frame_.front() == '/') {
    throw LoadError(source + ": '" + fixed_frame_ + "': a TF frame id has no leading '/'");
  }
  for (const auto& [frame, where] : workcell_->moving_root_frames) {
    if (frame == fixed_frame_) {
      throw LoadError(source + ": '" + fixed_frame_ + "' is the parent_frame of " + where +
                      ", which moves the URDF root '" + root +
                      "': the monitor computes in the root's frame, which fixed_frame only "
                      "renames (leave it empty)");
    }
  }
  // Another link of the URDF has a pose of its own (but one fixed at the root's): not the
  // root's frame, which fixed_frame only renames (TF poses are looked up in it).
  const int link = workcell_->kinematics.FindLink(fixed_frame_);
  if (link > 0 && !IsFixedAtRoot(workcell_->kinematics, link)) {
    throw LoadError(source + ": '" + fixed_frame_ + "' is a link of the URDF " +
                    options_.urdf_path + " away from its root '" + root +
                    "': the monitor computes in the root's frame, which fixed_frame only "
                    "renames (leave it empty, or name a frame at the root's pose)");
  }
}

std::string MonitorNode::FixedFrameOffset() const {
  const std::string& root = workcell_->fixed_frame;
  if (fixed_frame_ == root) return "";
  const char* const hint = " (fixed_frame only renames the root's frame: leave it empty)";
  // The root's pose in the fixed frame, its quaternion normalised (ToRigidTransform).
  Eigen::Isometry3d X_FRoot = Eigen::Isometry3d::Identity();
  std::string bad;
  try {
    bad = ToRigidTransform(
        tf_buffer_.lookupTransform(fixed_frame_, root, ros::Time(0)).transform, &X_FRoot);
  } catch (const tf2::TransformException&) {
    // A pure rename: TF does not have both. Two frames it has but has not joined (yet: a
    // driver still starting) may be apart once it does.
    if (!tf_buffer_._frameExists(fixed_frame_) || !tf_buffer_._frameExists(root)) return "";
    return "TF has the fixed frame '" + fixed_frame_ + "' and the URDF root '" + root +
           "' but does not relate them" + hint;
  }
  if (!bad.empty()) {
    return "TF's transform from the URDF root '" + root + "' to the fixed frame '" +
           fixed_frame_ + "': " + bad + hint;
  }
  if (IsAtRoot(X_FRoot)) return "";
  std::ostringstream msg;
  msg << "the fixed frame '" << fixed_frame_ << "' is " << X_FRoot.translation().norm()
      << " m and " << Eigen::AngleAxisd(X_FRoot.linear()).angle() << " rad from the URDF root '"
      << root << "' in TF" << hint;
  return msg.str();
}

geometry_msgs::TransformStamped MonitorNode::LookupInFixedFrame(const std::string& frame) const {
  if (frame == workcell_->fixed_frame) {
    // The root's own frame is the one the monitor computes in, whatever TF says of it.
    geometry_msgs::TransformStamped X;
    X.header.frame_id = fixed_frame_;
    X.child_frame_id = frame;
    X.transform.rotation.w = 1.0;
    return X;
  }
  return tf_buffer_.lookupTransform(fixed_frame_, frame, ros::Time(0));
}

}  // namespace arm_collision_monitor
