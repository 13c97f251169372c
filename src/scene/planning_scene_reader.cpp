// ReadPlanningSceneFile: a moveit_msgs/PlanningScene in YAML, read with the checked readers of
// yaml_fields (a `.scene` file: scene_geometry_text.cpp).
#include "arm_collision_monitor/scene/planning_scene_reader.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <string>
#include <tuple>

#include "arm_collision_monitor/scene/resource_fetch.h"
#include "arm_collision_monitor/scene/yaml_fields.h"
#include "arm_collision_monitor/scene/unit_quaternion.h"

namespace arm_collision_monitor {
namespace {

using yaml_fields::Where;

std::string Lowercase(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

/// A scalar string that may be empty (`name: ''`) or null; "" when absent.
std::string ReadOptionalString(const YAML::Node& node, const Where& where) {
  if (!node.IsDefined() || node.IsNull()) return "";
  if (!node.IsScalar()) where.Fail(node, "expected a string");
  return node.Scalar();
}

/// A message constant written as its number or its name (any case): its value, `first_value`
/// for names[0], `first_value` + 1 for names[1], ...
int ReadEnum(const YAML::Node& node, const Where& where, const std::vector<std::string>& names,
             int first_value, const std::string& expected) {
  if (!node.IsDefined() || !node.IsScalar()) where.Fail(node, "expected " + expected);
  int value = 0;
  if (YAML::convert<int>::decode(node, value)) {
    if (value >= first_value && value < first_value + static_cast<int>(names.size())) {
      return value;
    }
  } else {
    const auto it = std::find(names.begin(), names.end(), Lowercase(node.Scalar()));
    if (it != names.end()) return first_value + static_cast<int>(it - names.begin());
  }
  where.Fail(node, "unknown value '" + node.Scalar() + "' (expected " + expected + ")");
}

/// geometry_msgs/Point or Vector3: {x: , y: , z: } (absent components 0, as in the message)
/// or [x, y, z].
Eigen::Vector3d ReadPoint(const YAML::Node& node, const Where& where) {
  if (node.IsSequence()) return yaml_fields::ReadVector3(node, where);
  if (!node.IsMap()) where.Fail(node, "expected {x: X, y: Y, z: Z} or [x, y, z]");
  yaml_fields::CheckKeys(node, {"x", "y", "z"}, where);
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  yaml_fields::ReadIfPresent(node, "x", where, yaml_fields::ReadFiniteDouble, &p.x());
  yaml_fields::ReadIfPresent(node, "y", where, yaml_fields::ReadFiniteDouble, &p.y());
  yaml_fields::ReadIfPresent(node, "z", where, yaml_fields::ReadFiniteDouble, &p.z());
  return p;
}

/// geometry_msgs/Quaternion: {x: , y: , z: , w: } or [x, y, z, w]; normalised (policy in the
/// header: zero or far from unit norm is an error).
Eigen::Quaterniond ReadOrientation(const YAML::Node& node, const Where& where) {
  const char* const kNames[] = {"x", "y", "z", "w"};
  Eigen::Vector4d xyzw = Eigen::Vector4d::Zero();
  if (node.IsSequence() && node.size() == 4) {
    for (int i = 0; i < 4; ++i) xyzw[i] = yaml_fields::ReadFiniteDouble(node[i], where.Entry(i));
  } else if (node.IsMap()) {
    yaml_fields::CheckKeys(node, {"x", "y", "z", "w"}, where);
    for (int i = 0; i < 4; ++i) {
      yaml_fields::ReadIfPresent(node, kNames[i], where, yaml_fields::ReadFiniteDouble, &xyzw[i]);
    }
  } else {
    where.Fail(node, "expected {x: X, y: Y, z: Z, w: W} or [x, y, z, w]");
  }
  Eigen::Quaterniond q;
  const std::string error = ToUnitQuaternion(xyzw, &q);
  if (!error.empty()) where.Fail(node, error);
  return q;
}

/// geometry_msgs/Pose (keys position, orientation) or Transform (translation, rotation) as X_AB
/// (B's pose in A): its point under `point_key` and its quaternion under `rotation_key`, each
/// optional.
Eigen::Isometry3d ReadRigid(const YAML::Node& node, const Where& where, const char* point_key,
                            const char* rotation_key) {
  yaml_fields::RequireMap(node, where);
  yaml_fields::CheckKeys(node, {point_key, rotation_key}, where);
  Eigen::Isometry3d X_AB = Eigen::Isometry3d::Identity();
  if (node[point_key]) X_AB.translation() = ReadPoint(node[point_key], where.Child(point_key));
  if (node[rotation_key]) {
    X_AB.linear() =
        ReadOrientation(node[rotation_key], where.Child(rotation_key)).toRotationMatrix();
  }
  return X_AB;
}

/// geometry_msgs/Pose as X_AB.
Eigen::Isometry3d ReadPose(const YAML::Node& node, const Where& where) {
  return ReadRigid(node, where, "position", "orientation");
}

/// The poses list `key` of `object`, which must match the `count` shapes of `shapes_key` in
/// length; each pose composed as X_FO * pose.
std::vector<Eigen::Isometry3d> ReadShapePoses(const YAML::Node& object, const char* key,
                                              const char* shapes_key, std::size_t count,
                                              const Eigen::Isometry3d& X_FO, const Where& where) {
  const YAML::Node poses = object[key];
  std::size_t pose_count = 0;
  if (poses) {
    yaml_fields::RequireSequence(poses, where.Child(key));
    pose_count = poses.size();
  }
  if (pose_count != count) {
    where.Child(key).Fail(poses.IsDefined() ? poses : object,
                          std::to_string(pose_count) + " poses for " + std::to_string(count) + " " +
                              shapes_key + " (expected one pose per entry of " + shapes_key + ")");
  }
  std::vector<Eigen::Isometry3d> X_FS;
  for (std::size_t i = 0; i < pose_count; ++i) {
    X_FS.push_back(X_FO * ReadPose(poses[i], where.Child(key).Entry(i)));
  }
  return X_FS;
}

/// shape_msgs/SolidPrimitive: type and dimensions (pose set by the caller).
ScenePrimitive ReadPrimitive(const YAML::Node& node, const Where& where) {
  yaml_fields::RequireMap(node, where);
  yaml_fields::CheckKeys(node, {"type", "dimensions"}, where);
  ScenePrimitive primitive;
  primitive.type = static_cast<SolidPrimitiveType>(
      ReadEnum(node["type"], where.Child("type"), {"box", "sphere", "cylinder", "cone"}, 1,
               "a primitive type: 1 BOX, 2 SPHERE, 3 CYLINDER, 4 CONE, or its name"));
  static const std::map<SolidPrimitiveType, std::pair<std::size_t, const char*>> kForms = {
      {SolidPrimitiveType::kBox, {3, "box: [x, y, z]"}},
      {SolidPrimitiveType::kSphere, {1, "sphere: [radius]"}},
      {SolidPrimitiveType::kCylinder, {2, "cylinder: [height, radius]"}},
      {SolidPrimitiveType::kCone, {2, "cone: [height, radius]"}}};
  const auto& [count, form] = kForms.at(primitive.type);
  const YAML::Node dimensions = node["dimensions"];
  const Where dimensions_where = where.Child("dimensions");
  if (!dimensions.IsDefined() || !dimensions.IsSequence() || dimensions.size() != count) {
    dimensions_where.Fail(dimensions.IsDefined() ? dimensions : node,
                          "expected " + std::to_string(count) + " dimensions in metres, " + form);
  }
  for (std::size_t i = 0; i < count; ++i) {
    primitive.dimensions_m.push_back(
        yaml_fields::ReadPositiveDouble(dimensions[i], dimensions_where.Entry(i)));
  }
  return primitive;
}

std::uint32_t ReadVertexIndex(const YAML::Node& node, std::size_t vertex_count,
                              const Where& where) {
  long long index = -1;
  if (!node.IsDefined() || !node.IsScalar() || !YAML::convert<long long>::decode(node, index) ||
      index < 0 || index >= static_cast<long long>(vertex_count)) {
    where.Fail(node, "bad vertex index '" + (node.IsScalar() ? node.Scalar() : std::string()) +
                         "' (expected an integer from 0 to " + std::to_string(vertex_count - 1) +
                         ": the mesh has " + std::to_string(vertex_count) + " vertices)");
  }
  return static_cast<std::uint32_t>(index);
}

/// shape_msgs/Mesh: inline vertices and triangles (pose set by the caller).
SceneMesh ReadMesh(const YAML::Node& node, const Where& where) {
  yaml_fields::RequireMap(node, where);
  if (node["resource"]) {
    where.Child("resource")
        .Fail(node["resource"],
              "mesh files are not read (expected the mesh inline: vertices and triangles)");
  }
  yaml_fields::CheckKeys(node, {"vertices", "triangles"}, where);
  SceneMesh mesh;
  const Where vertices_where = where.Child("vertices");
  const Where triangles_where = where.Child("triangles");
  const YAML::Node vertices = node["vertices"];
  const YAML::Node triangles = node["triangles"];
  if (!vertices.IsDefined() || !vertices.IsSequence() || vertices.size() == 0 ||
      !triangles.IsDefined() || !triangles.IsSequence() || triangles.size() == 0) {
    where.Fail(node,
               "expected vertices (a list of points) and triangles (a list of "
               "{vertex_indices: [i, j, k]}), both non-empty");
  }
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    mesh.vertices_M.push_back(ReadPoint(vertices[i], vertices_where.Entry(i)));
  }
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    const bool is_message = triangles[t].IsMap();
    if (is_message) {
      yaml_fields::CheckKeys(triangles[t], {"vertex_indices"}, triangles_where.Entry(t));
    }
    const Where triangle_where =
        is_message ? triangles_where.Entry(t).Child("vertex_indices") : triangles_where.Entry(t);
    const YAML::Node indices = is_message ? triangles[t]["vertex_indices"] : triangles[t];
    if (!indices.IsDefined() || !indices.IsSequence() || indices.size() != 3) {
      triangle_where.Fail(indices.IsDefined() ? indices : triangles[t],
                          "expected 3 vertex indices [i, j, k]");
    }
    std::array<std::uint32_t, 3> triangle{};
    for (std::size_t k = 0; k < 3; ++k) {
      triangle[k] = ReadVertexIndex(indices[k], mesh.vertices_M.size(), triangle_where.Entry(k));
    }
    mesh.triangles.push_back(triangle);
  }
  return mesh;
}

/// moveit_msgs/CollisionObject, its shapes posed in its header frame.
SceneCollisionObject ReadCollisionObject(const YAML::Node& node, const Where& entry) {
  yaml_fields::RequireMap(node, entry);
  SceneCollisionObject object;
  object.id = ReadOptionalString(node["id"], entry.Child("id"));
  if (object.id.empty()) {
    entry.Fail(node, "collision object without id (expected id: NAME)");
  }
  const Where where{entry.file, entry.element + " '" + object.id + "'"};
  object.element = where.element;
  object.line = node.Mark().is_null() ? 0 : node.Mark().line + 1;
  yaml_fields::CheckKeys(
      node,
      {"header", "pose", "id", "type", "primitives", "primitive_poses", "meshes", "mesh_poses",
       "planes", "plane_poses", "subframe_names", "subframe_poses", "operation"},
      where);
  if (node["operation"]) {
    const int operation =
        ReadEnum(node["operation"], where.Child("operation"), {"add", "remove", "append", "move"},
                 0, "an operation: 0 ADD, 1 REMOVE, 2 APPEND, 3 MOVE, or its name");
    if (operation != 0) {
      where.Child("operation")
          .Fail(node["operation"],
                "only ADD (0) is read: REMOVE, APPEND and MOVE edit an earlier scene "
                "(expected operation: 0 or none)");
    }
  }
  if (const YAML::Node header = node["header"]) {
    yaml_fields::RequireMap(header, where.Child("header"));
    yaml_fields::CheckKeys(header, {"seq", "stamp", "frame_id"}, where.Child("header"));
    object.frame_id = ReadOptionalString(header["frame_id"], where.Child("header.frame_id"));
  }
  if (const YAML::Node planes = node["planes"]) {
    yaml_fields::RequireSequence(planes, where.Child("planes"));
    if (planes.size() > 0) {
      where.Child("planes").Fail(planes,
                                 "planes are not supported (expected primitives or "
                                 "meshes)");
    }
  }
  Eigen::Isometry3d X_FO = Eigen::Isometry3d::Identity();
  yaml_fields::ReadIfPresent(node, "pose", where, ReadPose, &X_FO);
  const YAML::Node primitives = node["primitives"];
  const YAML::Node meshes = node["meshes"];
  if (primitives) yaml_fields::RequireSequence(primitives, where.Child("primitives"));
  if (meshes) yaml_fields::RequireSequence(meshes, where.Child("meshes"));
  const std::size_t primitive_count = primitives ? primitives.size() : 0;
  const std::size_t mesh_count = meshes ? meshes.size() : 0;
  const auto X_FP =
      ReadShapePoses(node, "primitive_poses", "primitives", primitive_count, X_FO, where);
  for (std::size_t i = 0; i < primitive_count; ++i) {
    object.primitives.push_back(ReadPrimitive(primitives[i], where.Child("primitives").Entry(i)));
    object.primitives.back().X_FP = X_FP[i];
  }
  const auto X_FM = ReadShapePoses(node, "mesh_poses", "meshes", mesh_count, X_FO, where);
  for (std::size_t i = 0; i < mesh_count; ++i) {
    object.meshes.push_back(ReadMesh(meshes[i], where.Child("meshes").Entry(i)));
    object.meshes.back().X_FM = X_FM[i];
  }
  return object;
}

/// A row of the matrix: {enabled: [...]} (the message) or [...] (the compact form), one boolean
/// per entry of the list `names_key`.
std::vector<bool> ReadMatrixRow(const YAML::Node& node, std::size_t size, const char* names_key,
                                const Where& row_where) {
  const bool is_message = node.IsDefined() && node.IsMap();
  if (is_message) yaml_fields::CheckKeys(node, {"enabled"}, row_where);
  const Where where = is_message ? row_where.Child("enabled") : row_where;
  const YAML::Node row = is_message ? node["enabled"] : node;
  if (!row.IsDefined() || !row.IsSequence() || row.size() != size) {
    where.Fail(row.IsDefined() ? row : node,
               "expected " + std::to_string(size) + " booleans, one per " + names_key + " entry");
  }
  std::vector<bool> values;
  for (std::size_t j = 0; j < size; ++j) {
    values.push_back(yaml_fields::ReadBool(row[j], where.Entry(j)));
  }
  return values;
}

std::vector<std::string> ReadUniqueNames(const YAML::Node& node, const Where& where) {
  std::vector<std::string> names;
  if (!node) return names;
  yaml_fields::RequireSequence(node, where);
  std::set<std::string> seen;
  for (std::size_t i = 0; i < node.size(); ++i) {
    names.push_back(yaml_fields::ReadName(node[i], where.Entry(i)));
    if (!seen.insert(names.back()).second) {
      where.Entry(i).Fail(node[i], "name '" + names.back() + "' repeated (expected unique names)");
    }
  }
  return names;
}

/// moveit_msgs/AllowedCollisionMatrix, checked square and symmetric.
SceneAllowedCollisions ReadAllowedCollisions(const YAML::Node& node, const Where& where) {
  yaml_fields::RequireMap(node, where);
  yaml_fields::CheckKeys(
      node, {"entry_names", "entry_values", "default_entry_names", "default_entry_values"}, where);
  const std::vector<std::string> names =
      ReadUniqueNames(node["entry_names"], where.Child("entry_names"));
  const YAML::Node rows = node["entry_values"];
  const Where rows_where = where.Child("entry_values");
  if (!names.empty() || rows) {
    if (!rows.IsDefined() || !rows.IsSequence() || rows.size() != names.size()) {
      rows_where.Fail(rows.IsDefined() ? rows : node, "expected " + std::to_string(names.size()) +
                                                          " rows, one per entry_names entry");
    }
  }
  std::vector<std::vector<bool>> matrix;
  for (std::size_t i = 0; i < names.size(); ++i) {
    matrix.push_back(ReadMatrixRow(rows[i], names.size(), "entry_names", rows_where.Entry(i)));
  }
  SceneAllowedCollisions result;
  for (std::size_t i = 0; i < names.size(); ++i) {
    for (std::size_t j = i + 1; j < names.size(); ++j) {
      if (matrix[i][j] != matrix[j][i]) {
        rows_where.Entry(j).Fail(rows[j], "(" + names[j] + ", " + names[i] + ") differs from (" +
                                              names[i] + ", " + names[j] +
                                              ") (expected a symmetric matrix)");
      }
      (matrix[i][j] ? result.allowed_pairs : result.disallowed_pairs)
          .emplace_back(names[i], names[j]);
    }
  }
  const std::vector<std::string> default_names =
      ReadUniqueNames(node["default_entry_names"], where.Child("default_entry_names"));
  const YAML::Node defaults = node["default_entry_values"];
  const Where defaults_where = where.Child("default_entry_values");
  const std::vector<bool> default_values =
      default_names.empty() && !defaults
          ? std::vector<bool>()
          : ReadMatrixRow(defaults, default_names.size(), "default_entry_names", defaults_where);
  for (std::size_t i = 0; i < default_names.size(); ++i) {
    if (default_values[i]) result.default_allowed_names.push_back(default_names[i]);
  }
  return result;
}

/// The node at `keys` below `node` through maps; an undefined node if there is none. (Recursive:
/// assigning to a YAML::Node would overwrite the node it refers to, not rebind it.)
YAML::Node FindPath(const YAML::Node& node, const std::vector<const char*>& keys,
                    std::size_t first = 0) {
  if (first == keys.size()) return node;
  if (!node.IsDefined() || !node.IsMap() || !node[keys[first]]) {
    return YAML::Node(YAML::NodeType::Undefined);
  }
  return FindPath(node[keys[first]], keys, first + 1);
}

/// robot_state.multi_dof_joint_state: each joint name with its transform (translation and
/// rotation, each optional as in a pose).
std::vector<SceneJointPose> ReadJointPoses(const YAML::Node& root, const Where& top) {
  std::vector<SceneJointPose> poses;
  const YAML::Node state = FindPath(root, {"robot_state", "multi_dof_joint_state"});
  if (!state.IsDefined()) return poses;
  const Where where = top.Child("robot_state").Child("multi_dof_joint_state");
  yaml_fields::RequireMap(state, where);
  const std::vector<std::string> names =
      ReadUniqueNames(state["joint_names"], where.Child("joint_names"));
  const YAML::Node transforms = state["transforms"];
  const Where transforms_where = where.Child("transforms");
  std::size_t count = 0;
  if (transforms) {
    yaml_fields::RequireSequence(transforms, transforms_where);
    count = transforms.size();
  }
  if (count != names.size()) {
    transforms_where.Fail(transforms.IsDefined() ? transforms : state,
                          std::to_string(count) + " transforms for " +
                              std::to_string(names.size()) +
                              " joint_names (expected one per joint name)");
  }
  for (std::size_t i = 0; i < count; ++i) {
    const YAML::Node transform = transforms[i];
    poses.push_back({names[i],
                     ReadRigid(transform, transforms_where.Entry(i), "translation", "rotation"),
                     transform.Mark().is_null() ? 0 : transform.Mark().line + 1});
  }
  return poses;
}

/// How many entries of `node` (link_padding or link_scale: [{link_name, <key>}, ...]) set `key`
/// to other than `neutral` (a value that is no number too: it is ignored all the same).
std::size_t CountChanged(const YAML::Node& node, const char* key, double neutral) {
  std::size_t count = 0;
  if (!node.IsDefined() || !node.IsSequence()) return count;
  for (const YAML::Node& entry : node) {
    const YAML::Node value = entry.IsMap() ? entry[key] : YAML::Node();
    // as<double> with a fallback: a scalar such as "1..0" threw YAML::BadConversion out of the
    // reader (fuzz finding), where every failure is a LoadError.
    count += value.IsDefined() && value.IsScalar() &&
                     !(value.as<double>(std::numeric_limits<double>::quiet_NaN()) == neutral)
                 ? 1
                 : 0;
  }
  return count;
}

/// Notices for robot_state's attached objects, world.octomap's data and MoveIt's link padding
/// and scale (all ignored).
void AddNotices(const YAML::Node& root, PlanningSceneFile* scene) {
  const YAML::Node attached = FindPath(root, {"robot_state", "attached_collision_objects"});
  if (attached.IsDefined() && attached.IsSequence() && attached.size() > 0) {
    scene->notices.push_back(
        "robot_state.attached_collision_objects: " + std::to_string(attached.size()) +
        " objects attached to the robot are ignored");
  }
  const YAML::Node octomap = FindPath(root, {"world", "octomap", "octomap", "data"});
  if (octomap.IsDefined() && octomap.IsSequence() && octomap.size() > 0) {
    scene->notices.push_back("world.octomap: an octomap of " + std::to_string(octomap.size()) +
                             " bytes is ignored (only collision objects are read)");
  }
  for (const auto& [key, field, neutral] : {std::make_tuple("link_padding", "padding", 0.0),
                                            std::make_tuple("link_scale", "scale", 1.0)}) {
    const std::size_t changed = CountChanged(root[key], field, neutral);
    if (changed == 0) continue;
    scene->notices.push_back(std::string(key) + ": MoveIt's " + field + " of " +
                             std::to_string(changed) + " links is ignored (the monitor's margins "
                             "are its tolerances: the scene file's tolerance_m per arm or link)");
  }
}

}  // namespace

PlanningSceneFile ReadPlanningSceneFile(const std::string& path) {
  return ReadPlanningSceneText(ReadWholeFile(path, "a readable planning-scene file"), path);
}

std::string ShapelessObjectNotice(const SceneCollisionObject& object) {
  return object.element + " (line " + std::to_string(object.line) +
         "): no shapes (subframes only, or none): nothing to check; skipped";
}

PlanningSceneFile ReadPlanningSceneText(const std::string& text, const std::string& path) {
  const std::string kTextSuffix = ".scene";
  if (path.size() >= kTextSuffix.size() &&
      path.compare(path.size() - kTextSuffix.size(), kTextSuffix.size(), kTextSuffix) == 0) {
    return ReadSceneGeometryText(text, path);
  }
  const YAML::Node root = yaml_fields::LoadMapText(text, path);
  const Where top{path, ""};
  yaml_fields::CheckKeys(root,
                         {"name", "robot_state", "robot_model_name", "fixed_frame_transforms",
                          "allowed_collision_matrix", "link_padding", "link_scale", "object_colors",
                          "world", "is_diff"},
                         top);
  PlanningSceneFile scene;
  scene.name = ReadOptionalString(root["name"], top.Child("name"));
  if (const YAML::Node world = root["world"]) {
    const Where world_where = top.Child("world");
    yaml_fields::RequireMap(world, world_where);
    yaml_fields::CheckKeys(world, {"collision_objects", "octomap"}, world_where);
    const Where objects_where = world_where.Child("collision_objects");
    if (const YAML::Node objects = world["collision_objects"]) {
      yaml_fields::RequireSequence(objects, objects_where);
      std::set<std::string> ids;
      for (std::size_t i = 0; i < objects.size(); ++i) {
        SceneCollisionObject object = ReadCollisionObject(objects[i], objects_where.Entry(i));
        if (!ids.insert(object.id).second) {
          objects_where.Entry(i).Fail(objects[i],
                                      "id '" + object.id + "' repeated (expected unique ids)");
        }
        if (object.primitives.empty() && object.meshes.empty()) {
          scene.notices.push_back(ShapelessObjectNotice(object));
          scene.shapeless_ids.push_back(object.id);
        } else {
          scene.objects.push_back(std::move(object));
        }
      }
    }
  }
  if (const YAML::Node matrix = root["allowed_collision_matrix"]) {
    scene.allowed_collisions = ReadAllowedCollisions(matrix, top.Child("allowed_collision_matrix"));
  }
  scene.joint_poses = ReadJointPoses(root, top);
  AddNotices(root, &scene);
  return scene;
}

}  // namespace arm_collision_monitor
