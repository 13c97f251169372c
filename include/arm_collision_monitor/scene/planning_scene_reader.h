// Reader of a whole moveit_msgs/PlanningScene written as YAML: the world's collision objects and
// the allowed collision matrix, as plain structs. ROS-free; the caller maps frames and names
// onto its workcell.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace arm_collision_monitor {

/// shape_msgs/SolidPrimitive's types, with their message values.
enum class SolidPrimitiveType { kBox = 1, kSphere = 2, kCylinder = 3, kCone = 4 };

/// One entry of a collision object's `primitives`. Dimensions in metres, in shape_msgs' order:
/// box [x, y, z] (full edge lengths along the primitive frame's axes); sphere [radius];
/// cylinder and cone [height, radius] (axis along the primitive frame's z, centred on its origin;
/// the cone's tip towards +z). Every dimension is finite and > 0.
struct ScenePrimitive {
  SolidPrimitiveType type = SolidPrimitiveType::kBox;
  std::vector<double> dimensions_m;
  /// Pose of the primitive frame P in the object's header frame F: object pose * primitive pose.
  Eigen::Isometry3d X_FP = Eigen::Isometry3d::Identity();
};

/// One entry of a collision object's `meshes` (shape_msgs/Mesh).
struct SceneMesh {
  std::vector<Eigen::Vector3d> vertices_M;  ///< in the mesh frame M, metres
  /// Vertex indices of each triangle, each < vertices_M.size().
  std::vector<std::array<std::uint32_t, 3>> triangles;
  /// Pose of the mesh frame M in the object's header frame F: object pose * mesh pose.
  Eigen::Isometry3d X_FM = Eigen::Isometry3d::Identity();
};

/// One collision object of `world.collision_objects` (operation ADD).
struct SceneCollisionObject {
  std::string id;        ///< unique in the file
  std::string frame_id;  ///< header.frame_id; "" (or no header) means the planning (fixed) frame
  /// Where it is, for the caller's messages: "world.collision_objects[2] 'can1'".
  std::string element;
  int line = 0;  ///< its line in the file (1-based; 0 if unknown)
  std::vector<ScenePrimitive> primitives;
  std::vector<SceneMesh> meshes;
};

/// The allowed_collision_matrix (moveit_msgs/AllowedCollisionMatrix), entry by entry. MoveIt's
/// rule: an explicit pair entry wins; otherwise a pair is allowed when a default entry of either
/// name allows it. Only the upper triangle of a symmetric matrix is returned (name1 before name2
/// in entry_names order); the diagonal is ignored.
struct SceneAllowedCollisions {
  std::vector<std::pair<std::string, std::string>> allowed_pairs;     ///< enabled: true
  std::vector<std::pair<std::string, std::string>> disallowed_pairs;  ///< enabled: false
  std::vector<std::string> default_allowed_names;  ///< default_entry_values: true
};

/// One joint of robot_state.multi_dof_joint_state: its value, the pose of the joint's child link
/// C in its parent frame P (for an SRDF virtual joint: where the robot's root link stands).
struct SceneJointPose {
  std::string joint;
  Eigen::Isometry3d X_PC = Eigen::Isometry3d::Identity();
  int line = 0;  ///< its transform's line in the file (1-based; 0 if unknown)
};

/// What a planning-scene file holds for the monitor.
struct PlanningSceneFile {
  std::string name;  ///< the scene's `name`, "" when absent
  std::vector<SceneCollisionObject> objects;
  SceneAllowedCollisions allowed_collisions;
  /// robot_state.multi_dof_joint_state, in file order (none in a `.scene` file).
  std::vector<SceneJointPose> joint_poses;
  /// Content the monitor does not use but the user should know was dropped, one sentence each:
  /// a non-empty octomap, attached collision objects in robot_state, objects of no shapes.
  std::vector<std::string> notices;
  /// The ids of the objects of no shapes (skipped: ShapelessObjectNotice).
  std::vector<std::string> shapeless_ids;
};

/// Reads a planning-scene YAML file: the fields of moveit_msgs/PlanningScene as `rostopic echo`
/// (or a YAML dump of the message) writes them, and the compact form of benchmark suites
/// (robowflex, MotionBenchMaker): positions as [x, y, z], orientations as [x, y, z, w],
/// primitive types as names (box, sphere, cylinder, cone; any case), triangles as [i, j, k],
/// matrix rows as lists of booleans. Every key is optional.
///
/// Read: world.collision_objects (id, header.frame_id, pose, primitives + primitive_poses,
/// meshes + mesh_poses, operation), allowed_collision_matrix, name and robot_state's
/// multi_dof_joint_state (joint_names with their transforms: geometry_msgs/Transform, the
/// compact form as for poses). Ignored: the rest of robot_state (a notice if it has attached
/// objects), robot_model_name, fixed_frame_transforms,
/// link_padding, link_scale, object_colors, world.octomap (a notice if it has data), is_diff,
/// and each object's type (object_recognition_msgs/ObjectType), subframe_names, subframe_poses.
///
/// Policies: only operation ADD (0, "add") or none is accepted: REMOVE, APPEND and MOVE are edits
/// of an earlier scene, which a file alone cannot replay. Poses compose object pose * shape pose
/// (an absent pose or orientation is the identity). A quaternion of norm within
/// kQuaternionUnitNormTolerance of 1 is normalised; zero or farther from 1 is an error (MoveIt
/// reads an all-zero quaternion as the identity; here it must be written). Planes are rejected
/// (no half-spaces in the monitor), as are mesh `resource` files (expected inline vertices).
///
/// An object of no shapes (MoveIt keeps one for its subframes) has nothing to check: skipped with
/// a notice (ShapelessObjectNotice).
///
/// Throws LoadError "path[:line]: element: what was expected" for a missing file, malformed
/// YAML, an unknown key, a collision object without id, a repeated id, an
/// unknown primitive type, a wrong number of dimensions, a dimension that is not a finite
/// number > 0, shape and pose lists of different lengths, a bad quaternion, a mesh without
/// triangles or with a vertex index out of range, and a matrix that is not square, symmetric and
/// named by unique names, and multi-DOF joint names that are repeated or not one per transform.
PlanningSceneFile ReadPlanningSceneFile(const std::string& path);

/// The same from the file's text (fetched by the caller, e.g. through a ResourceFetcher);
/// `path` names it in the messages. A `path` ending in `.scene` is read as scene geometry text
/// (ReadSceneGeometryText).
PlanningSceneFile ReadPlanningSceneText(const std::string& text, const std::string& path);

/// The notice of an object of no shapes, which the readers skip: "object 'ID' (line N): no
/// shapes (subframes only, or none): nothing to check; skipped".
std::string ShapelessObjectNotice(const SceneCollisionObject& object);

/// Reads MoveIt's scene geometry text: a `.scene` file as RViz's Motion Planning panel exports
/// it (PlanningScene::saveGeometryToStream), in the format of MoveIt 1.1 on (each object's pose
/// and subframes) or the older one (shape poses in the planning frame), told apart as MoveIt
/// does. Its objects become `objects` (frame_id "": the planning frame; `line`: the line of the
/// object's `*`); it has no matrix. Shapes: box, sphere, cylinder and cone (dimensions into
/// shape_msgs' order: the text's "radius length" becomes [height, radius]) and inline meshes;
/// colours and subframes are read and dropped. Policies as above: planes, a repeated id and a
/// bad quaternion are errors, an object without shapes is skipped with a notice.
///
/// Throws LoadError "path:line: element: what was expected" (element: "scene", "object 'ID'",
/// "object 'ID' shape K") for a missing '.' at the end, an unknown marker or shape type, a
/// token that is not a finite number (or a count) where one is expected, a dimension <= 0, a
/// mesh of fewer than 3 vertices or no triangle, and a vertex index out of range.
PlanningSceneFile ReadSceneGeometryText(const std::string& text, const std::string& path);

}  // namespace arm_collision_monitor
