// The node's services on the live model (~check, ~attach, ~detach,
// ~set_grasp_target): a joint state checked without a cycle, objects held and released, grasp
// targets excused. The live-object services are in monitor_node_live_objects.cpp.

#include "arm_collision_monitor/ros/conversions.h"
#include "arm_collision_monitor/ros/monitor_node.h"

namespace arm_collision_monitor {

std::string MonitorNode::CheckedNamesText(const std::vector<std::string>& names,
                                          std::uint32_t* unknown, std::size_t* given) const {
  std::string ignored;
  for (const std::string& name : names) {
    if (input_->IsModelJoint(name)) {
      ++*given;
      continue;
    }
    const bool is_mimic = input_->IsMimicJoint(name);
    *unknown += is_mimic ? 0 : 1;
    const bool is_fixed = workcell_->kinematics.IsFixedJoint(name);
    ignored += (ignored.empty() ? "; ignored, no joints of the model: '" : ", '") + name + "'" +
               (is_mimic ? " (a mimic joint)" : "") +
               (is_fixed ? " (a fixed joint of the URDF)" : "");
  }
  return ignored;
}

bool MonitorNode::OnCheck(CheckJointState::Request& req, CheckJointState::Response& res) {
  Eigen::VectorXd q;
  const NamedPositions input = ToNamedPositions(req.joint_state);
  const MergeStatus status = input_->MergeIntoCopy(input, &q);
  res.report.header.frame_id = fixed_frame_;
  res.report.header.stamp = req.joint_state.header.stamp;
  std::size_t given = 0;  // the request's names of model joints
  const std::string ignored =
      CheckedNamesText(req.joint_state.name, &res.report.unknown_joints, &given);
  if (status != MergeStatus::kAccepted) {
    res.success = false;
    res.report.input_status = ToInputStatusMsg(ToSafetyStatus(status));
    res.report.stop = true;
    const std::string why = input_->DescribeRefusal(input, status, ros::Time::now().toSec());
    res.message = std::string("joint state refused: ") + MergeStatusName(status) +
                  (why.empty() ? "" : " (" + why + ")") + ignored;
    res.report.stop_reason = res.message;
    return true;
  }
  const std::vector<std::string> missing = input_->MissingJointsNotIn(req.joint_state.name);
  if (!missing.empty()) {
    res.success = false;
    res.report.input_status = ToInputStatusMsg(SafetyStatus::kIncomplete);
    res.report.stop = true;
    res.message = "no position for " + ModelJointsText(missing) +
                  ": never received, and not in the request" + ignored;
    res.report.stop_reason = res.message;
    return true;
  }
  const CycleReport report = monitor_->Check(q);
  const SafetyStatus input_status = ToSafetyStatus(report.input);
  res.report.input_status = ToInputStatusMsg(input_status);
  res.report.stop = report.stop;
  res.report.moved_primitives = report.moved_primitives;
  res.report.reinsert_fallbacks = static_cast<std::uint32_t>(report.counters.reinsert_fallbacks);
  FillReportWarnings(report, &res.report);
  res.success = report.input == InputStatus::kOk;
  // A request with names of no model joint may have missed the model's: those it left out were
  // checked where the live state has them.
  const std::size_t joints = workcell_->joint_names.size();
  const std::string left_out =
      ignored.empty() || given == joints
          ? std::string()
          : "; " + std::to_string(joints - given) + " of the model's " + std::to_string(joints) +
                " joints not in the request, checked at their live positions (or defaults)";
  res.message = res.success ? std::to_string(report.warnings.size()) + " warning(s)" + ignored +
                                  left_out
                            : std::string("joint state refused: ") +
                                  SafetyStatusName(input_status) + " (" +
                                  monitor_->DescribeRefusal(q) + ")";
  // The reason a cycle of this q would give its stop: a refusal's first (the warnings of a
  // refused q are the live model's), else the warnings' as the live report has it.
  if (report.stop && report.input == InputStatus::kOk && !report.warnings.empty()) {
    char reason[kReasonCapacity];
    FormatWarningsReason(report.warnings, primitives_, reason, sizeof(reason));
    res.report.stop_reason = reason;
  } else if (report.stop) {
    res.report.stop_reason = res.message;
  }
  return true;
}

bool MonitorNode::OnAttach(AttachObject::Request& req, AttachObject::Response& res) {
  // A frame-bound object whose frame is unavailable is not where its last pose says: held, it
  // would no longer stop the cell for it.
  for (const BoundObject& bound : bound_objects_) {
    if (bound.object == req.object && !bound.is_available && !monitor_->IsHeld(req.object)) {
      res.success = false;
      res.message = "object '" + req.object + "': its frame '" + bound.frame +
                    "' is unavailable (see the stop's reason): attach it once the frame is back";
      return true;
    }
  }
  const std::string previous = monitor_->HolderOf(req.object);
  res.success = monitor_->Attach(req.object, req.link, &res.message);
  if (res.success) {
    res.message = "attached '" + req.object + "' to '" + req.link + "'" +
                  (previous.empty() || previous == req.link
                       ? ""
                       : " (taken from '" + previous + "', which held it)");
    const std::string notice = monitor_->DescribeHeldMotionBeyondTolerance(req.object);
    if (!notice.empty()) {
      ROS_WARN_STREAM("attach: " << notice);
      res.message += "; " + notice;
    }
  }
  return true;
}

bool MonitorNode::OnDetach(DetachObject::Request& req, DetachObject::Response& res) {
  res.success = monitor_->Detach(req.object, &res.message);
  if (res.success) {
    res.message = "detached '" + req.object + "'";
  }
  return true;
}

bool MonitorNode::OnSetGraspTarget(SetGraspTarget::Request& req,
                                   SetGraspTarget::Response& res) {
  res.success = monitor_->SetGraspTarget(req.link, req.object, req.is_target, &res.message);
  if (res.success) {
    res.message = std::string(req.is_target ? "set" : "cleared") + " grasp target '" +
                  req.object + "' of '" + req.link + "'";
  }
  return true;
}

}  // namespace arm_collision_monitor
