#include "arm_collision_monitor/ros/conversions.h"

#include <cmath>

#include "arm_collision_monitor/MonitorReport.h"

namespace arm_collision_monitor {

std::uint8_t WarningSeverity(double distance_m, double threshold_m) {
  if (distance_m <= 0.0) {
    return CollisionWarning::SEVERITY_CONTACT;
  }
  if (distance_m < 0.5 * threshold_m) {
    return CollisionWarning::SEVERITY_CRITICAL;
  }
  return CollisionWarning::SEVERITY_WARNING;
}

std::string ToRigidTransform(const geometry_msgs::Transform& transform, Eigen::Isometry3d* X) {
  const geometry_msgs::Vector3& t = transform.translation;
  const Eigen::Vector3d p(t.x, t.y, t.z);
  if (!p.allFinite()) return "translation not finite";
  const geometry_msgs::Quaternion& r = transform.rotation;
  const Eigen::Quaterniond R(r.w, r.x, r.y, r.z);
  // tf2 checks each transform it is sent, not the products along a chain, whose norms multiply.
  const double norm = R.norm();
  if (!std::isfinite(norm) || norm == 0.0) return "rotation: quaternion zero or not finite";
  X->linear() = R.normalized().toRotationMatrix();
  X->translation() = p;
  return "";
}

geometry_msgs::Transform ToTransformMsg(const Eigen::Isometry3d& X) {
  geometry_msgs::Transform transform;
  const Eigen::Vector3d p = X.translation();
  const Eigen::Quaterniond r(X.linear());
  transform.translation.x = p.x();
  transform.translation.y = p.y();
  transform.translation.z = p.z();
  transform.rotation.x = r.x();
  transform.rotation.y = r.y();
  transform.rotation.z = r.z();
  transform.rotation.w = r.w();
  return transform;
}

void ToWarningMsg(const std::vector<PrimitiveSpec>& primitives, const Warning& in,
                  CollisionWarning* out) {
  const PrimitiveSpec& a = primitives[in.a];
  const PrimitiveSpec& b = primitives[in.b];
  out->primitive_a = in.a;
  out->primitive_a_name = a.name;
  out->owner_a = a.owner;
  out->primitive_b = in.b;
  out->primitive_b_name = b.name;
  out->owner_b = b.owner;
  out->distance_m = in.distance_m;
  out->threshold_m = in.threshold_m;
  out->point_a.x = in.p_WA.x();
  out->point_a.y = in.p_WA.y();
  out->point_a.z = in.p_WA.z();
  out->point_b.x = in.p_WB.x();
  out->point_b.y = in.p_WB.y();
  out->point_b.z = in.p_WB.z();
  out->severity = WarningSeverity(in.distance_m, in.threshold_m);
  out->between_samples = in.between_samples;
  out->step_fraction = in.step_fraction;
}

std::uint8_t ToInputStatusMsg(SafetyStatus status) {
  using S = SafetyStatus;
  static_assert(static_cast<int>(S::kOutOfLimits) == MonitorReport::INPUT_OUT_OF_LIMITS &&
                    static_cast<int>(S::kIncomplete) == MonitorReport::INPUT_INCOMPLETE &&
                    static_cast<int>(S::kStale) == MonitorReport::INPUT_STALE &&
                    static_cast<int>(S::kFutureStamp) == MonitorReport::INPUT_FUTURE_STAMP,
                "SafetyStatus mirrors MonitorReport::INPUT_*");
  return static_cast<std::uint8_t>(status);
}

}  // namespace arm_collision_monitor
