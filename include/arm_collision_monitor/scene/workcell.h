// The workcell model, loaded once at start-up and immutable afterwards (Model/Data split): the
// arms' kinematics (from a URDF), every primitive with its owner and tolerance, the
// environment (from a scene YAML file) and the compatibility matrix.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "arm_collision_monitor/broadphase/compatibility_matrix.h"
#include "arm_collision_monitor/core/constants.h"
#include "arm_collision_monitor/core/load_error.h"
#include "arm_collision_monitor/geometry/primitives.h"
#include "arm_collision_monitor/kinematics/kinematic_model.h"
#include "arm_collision_monitor/scene/mesh_fit_cache.h"
#include "arm_collision_monitor/scene/resource_fetch.h"
#include "arm_collision_monitor/scene/solid_spec.h"

namespace arm_collision_monitor {

/// One primitive of the model, in the frame of its owner.
struct PrimitiveSpec {
  std::string name;          ///< unique, e.g. "left_link3", "left_gripper/finger1", "front_table"
  std::string owner;         ///< the link or object it belongs to
  int link_index = -1;       ///< KinematicModel link carrying it; -1 for an environment object
  std::string group;         ///< the arm it belongs to ("left", "right"), "" for the environment
  std::string variant;       ///< model variant of its link ("" = default, active at start)
  Shape shape_L;             ///< geometry in the owner's frame (link frame, or world for objects)
  double tolerance_m = 0.0;  ///< tolerance zone beyond the surface
  /// Never moves: a link primitive with only fixed joints to the root, or an object that is
  /// neither attachable nor frame-bound. Attachable and frame-bound objects are not static.
  bool is_static = true;
  int object_index = -1;  ///< index into Workcell::objects, -1 for a link primitive
};

/// An arm: a subtree of the URDF whose capsules get one tolerance.
struct ArmSpec {
  std::string name;       ///< "left", "right"
  std::string root_link;  ///< every link at or below it belongs to the arm
  double tolerance_m = kDefaultArmTolerance_m;
};

/// An environment object: one entry of the scene file's objects: (a box, sphere, cylinder,
/// capsule or mesh; frame O is the solid's frame: centre, axis along O's z; a mesh's own frame;
/// a mesh has one primitive per fitted shape) or one collision object of
/// the planning scene (frame O = the fixed frame; its shapes in order). Its primitives are
/// primitive .. primitive + primitive_count - 1, their shape_L already at X_WO_start in W.
struct ObjectSpec {
  std::string name;
  PrimitiveId primitive = 0;  ///< its first primitive
  int primitive_count = 1;    ///< >= 1; consecutive ids
  Eigen::Isometry3d X_WO_start = Eigen::Isometry3d::Identity();
  bool is_attachable = false;  ///< a link may pick it up at run time (Monitor::Attach)
  std::string frame;           ///< TF frame its pose follows at run time; "" if none
};

/// A (link, object) pair the Monitor may excuse while the link grasps the object.
struct GraspTargetSpec {
  std::string link;
  int link_index = -1;
  std::string object;
  int object_index = -1;
};

/// A non-default model of a link (Monitor::SwitchModel). Its primitives carry
/// PrimitiveSpec::variant == name; the default model ("") is the link's primitives with
/// variant "".
struct ModelVariantSpec {
  std::string link;
  int link_index = -1;
  std::string name;
  std::vector<PrimitiveId> primitives;
};

/// How many mesh fits a load computed and how many it took from the fit cache.
struct MeshFitCounts {
  int computed = 0;
  int from_cache = 0;
};

/// Where a planning scene placed its objects with the robot: an SRDF's floating or planar
/// virtual joint holding the root link, objects in whose parent frame the scene has.
struct PlacedRootSpec {
  std::string joint;
  /// The root's pose in the joint's parent frame: robot_state.multi_dof_joint_state's, else the
  /// origin (MoveIt's default).
  Eigen::Isometry3d X_FR = Eigen::Isometry3d::Identity();
  std::string where;  ///< the scene file, and the line of the pose when it gives one
};

/// Everything loaded at start-up (LoadWorkcell); the Monitor only reads it.
struct Workcell {
  std::string urdf_path;
  std::string scene_path;
  std::string fixed_frame = "world";
  /// The frames an SRDF's floating or planar virtual joint moves the root link in, each with
  /// where it says so ("robot.srdf:87: <virtual_joint name='base' type='floating'>"): never the
  /// root's frame, which the node's fixed_frame only renames.
  std::vector<std::pair<std::string, std::string>> moving_root_frames;
  /// The virtual joints that placed planning-scene objects, where they placed them: a plan
  /// replayed must start there, as the objects are checked where the scene placed them.
  std::vector<PlacedRootSpec> placed_roots;
  Aabb world_W;  ///< the world cube the spatial index covers
  KinematicModel kinematics;
  std::vector<std::string> joint_names;   ///< actuated joints, in the order of Monitor's q
  /// The scene file's joint_defaults: (q index, position) of joints the input may leave out.
  std::vector<std::pair<int, double>> joint_defaults;
  std::vector<PrimitiveSpec> primitives;  ///< PrimitiveId = index
  CompatibilityMatrix compatible;         ///< pairs excused at start-up
  std::vector<ArmSpec> arms;
  std::vector<ObjectSpec> objects;
  std::vector<GraspTargetSpec> grasp_targets;
  std::vector<ModelVariantSpec> variants;
  /// The scene file's cylinder_model and mesh_fit, for the objects added at run time
  /// (Monitor::AddObject).
  SolidShapeOptions solid_options;
  /// Start-up findings that do not stop loading but must be shown to the user, e.g. pairs that
  /// are within their tolerances in every sampled configuration (they would warn every cycle),
  /// SRDF or allowed-collision-matrix names that have no primitive (skipped), planning-scene
  /// content that was dropped.
  std::vector<std::string> warnings;
  /// Start-up report that needs no action (the node logs it at INFO level, replay prints it):
  /// one line per fitted mesh (the fit, its primitive count, fitted/mesh volume or "open mesh"),
  /// a line when the fit cache could not be written, the world cube derived when the scene file
  /// gives none, the SRDF's 'Never' pairs between two arms that stay checked. Kept apart from
  /// warnings because a robot of 20 mesh links would otherwise start with 20 warnings about
  /// nothing wrong.
  std::vector<std::string> notices;
  MeshFitCounts mesh_fits;

  /// Checks the invariants: the kinematics' own, joint defaults of valid q indices and finite,
  /// one compatibility row per primitive, unique primitive names, owners and indices that point
  /// at each other, finite non-negative sizes and tolerances, joint_names matching the
  /// kinematics. False with a reason otherwise.
  bool Validate(std::string* why) const;

  /// Index of the primitive, object or variant with that name; -1 if none.
  int FindPrimitive(const std::string& name) const;
  int FindObject(const std::string& name) const;
  int FindVariant(const std::string& link, const std::string& variant) const;
};

/// What LoadWorkcell needs besides the two files.
struct WorkcellLoadOptions {
  /// Applies to arms whose scene entry gives no tolerance_m (MonitorOptions::tolerance_m).
  double default_arm_tolerance_m = kDefaultArmTolerance_m;
  /// Reads the files the inputs name: URDF meshes, srdf:, planning_scene:, mesh objects. The
  /// default reads local paths and file:// URLs; the ROS programs pass FetchRosResource
  /// (package:// too).
  ResourceFetcher fetch = FetchLocalResource;
  /// Folder of the mesh-fit cache; "" disables it.
  std::string mesh_fit_cache_dir = DefaultMeshFitCacheDir();
};

/// Loads a URDF and a scene YAML file into a workcell (format: comment block at the top of
/// config/scene.yaml), parsing the URDF once for its kinematics and its collision geometry.
/// The files they name are read through `options.fetch`: URDF <mesh> filenames relative to the
/// URDF's folder, the scene's srdf:, planning_scene: and mesh objects relative to the scene
/// file's folder (unless absolute or URLs). Meshes are fitted per the scene's mesh_fit, through
/// the fit cache. Throws LoadError naming the file, the element and what was expected.
Workcell LoadWorkcell(const std::string& urdf_path, const std::string& scene_path,
                      const WorkcellLoadOptions& options);

/// LoadWorkcell with the default options but the arms' default tolerance.
Workcell LoadWorkcell(const std::string& urdf_path, const std::string& scene_path,
                      double default_arm_tolerance_m = kDefaultArmTolerance_m);

}  // namespace arm_collision_monitor
