// The node's live-object services (~add_object, ~move_object, ~remove_object): requests
// translated to Monitor::AddObject, MoveObject and RemoveObject. Solids and meshes become
// primitives here (MakeSolidShapes_O, which may fit a mesh), in the service call, never in the
// cycle.

#include "arm_collision_monitor/ros/conversions.h"
#include "arm_collision_monitor/ros/monitor_node.h"
#include "arm_collision_monitor/scene/unit_quaternion.h"
#include "arm_collision_monitor/scene/solid_spec.h"

namespace arm_collision_monitor {

bool MonitorNode::ResolvePose(const geometry_msgs::Pose& pose, const std::string& frame,
                              Eigen::Isometry3d* X_WO, std::string* error) {
  // tf2::fromMsg would take any quaternion: a zero one, or {w: 2}, as no rotation.
  Eigen::Quaterniond R_FO;
  const std::string why = ToUnitQuaternion(
      Eigen::Vector4d(pose.orientation.x, pose.orientation.y, pose.orientation.z,
                      pose.orientation.w),
      &R_FO);
  if (!why.empty()) {
    *error = "pose.orientation: " + why;
    return false;
  }
  Eigen::Isometry3d X_FO = Eigen::Isometry3d::Identity();
  X_FO.linear() = R_FO.toRotationMatrix();
  X_FO.translation() = Eigen::Vector3d(pose.position.x, pose.position.y, pose.position.z);
  if (frame == workcell_->fixed_frame) {
    *X_WO = X_FO;
    return true;
  }
  // In (or through) a fixed frame that TF puts apart from the root, it would be misplaced.
  const std::string offset = FixedFrameOffset();
  if (!offset.empty()) {
    *error = offset;
    return false;
  }
  if (frame.empty() || frame == fixed_frame_) {
    *X_WO = X_FO;
    return true;
  }
  // tf2's own message would blame the fixed frame when TF has neither.
  if (!tf_buffer_._frameExists(frame)) {
    *error = "frame '" + frame + "' is not known to TF (no transform to '" + fixed_frame_ + "')";
    return false;
  }
  try {
    Eigen::Isometry3d X_WF = Eigen::Isometry3d::Identity();
    const std::string bad = ToRigidTransform(LookupInFixedFrame(frame).transform, &X_WF);
    if (!bad.empty()) {
      *error = "transform from '" + frame + "' to '" + fixed_frame_ + "': " + bad;
      return false;
    }
    *X_WO = X_WF * X_FO;
    return true;
  } catch (const tf2::TransformException& e) {
    *error = "no transform from '" + frame + "' to '" + fixed_frame_ + "': " + e.what();
    return false;
  }
}

void MonitorNode::RefreshPrimitives() {
  for (PrimitiveId id = 0; id < primitives_.size(); ++id) primitives_[id] = monitor_->primitive(id);
}

bool MonitorNode::OnAddObject(AddObject::Request& req, AddObject::Response& res) {
  res.success = false;
  const std::string what = "add_object '" + req.name + "': ";
  SolidSpec solid;
  if (!ParseSolidType(req.type, &solid.type)) {
    res.message = what + "unknown type '" + req.type +
                  "' (expected box, sphere, cylinder, capsule or mesh)";
    return true;
  }
  const bool is_mesh = solid.type == SolidType::kMesh;
  if (!is_mesh && (!req.mesh_vertices.empty() || !req.mesh_triangles.empty())) {
    res.message = what + "mesh_vertices and mesh_triangles are for type mesh only";
    return true;
  }
  if (req.mesh_triangles.size() % 3 != 0) {
    res.message = what + "mesh_triangles holds " + std::to_string(req.mesh_triangles.size()) +
                  " indices, expected triples";
    return true;
  }
  solid.dimensions_m = req.dimensions_m;
  for (const geometry_msgs::Point& p : req.mesh_vertices) {
    solid.mesh.vertices_L.emplace_back(p.x, p.y, p.z);
  }
  for (std::size_t i = 0; i + 2 < req.mesh_triangles.size(); i += 3) {
    solid.mesh.triangles.push_back(
        {req.mesh_triangles[i], req.mesh_triangles[i + 1], req.mesh_triangles[i + 2]});
  }
  std::vector<Shape> shapes_O;
  std::string why;
  if (!MakeSolidShapes_O(solid, monitor_->workcell().solid_options, &shapes_O, &why)) {
    res.message = what + why;
    return true;
  }
  Eigen::Isometry3d X_WO;
  if (!ResolvePose(req.pose, req.frame, &X_WO, &why)) {
    res.message = what + why;
    return true;
  }
  res.success = monitor_->AddObject(req.name, shapes_O, X_WO, req.tolerance_m, req.attachable,
                                    &res.message);
  if (res.success) {
    RefreshPrimitives();
    res.message = "added '" + req.name + "' (" + std::to_string(shapes_O.size()) +
                  " primitive(s))";
  }
  return true;
}

bool MonitorNode::OnMoveObject(MoveObject::Request& req, MoveObject::Response& res) {
  Eigen::Isometry3d X_WO;
  std::string why;
  res.success = ResolvePose(req.pose, req.frame, &X_WO, &why);
  if (!res.success) {
    res.message = "move_object '" + req.name + "': " + why;
    return true;
  }
  res.success = monitor_->MoveObject(req.name, X_WO, &res.message);
  if (res.success) res.message = "moved '" + req.name + "'";
  return true;
}

bool MonitorNode::OnRemoveObject(RemoveObject::Request& req, RemoveObject::Response& res) {
  res.success = monitor_->RemoveObject(req.name, &res.message);
  if (res.success) {
    RefreshPrimitives();
    res.message = "removed '" + req.name + "'";
  }
  return true;
}

}  // namespace arm_collision_monitor
