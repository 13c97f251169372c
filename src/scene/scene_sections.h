// The scene file's sections (format: the comment block at the top of config/scene.yaml), one
// reader each. Every reader validates its own section and produces its part of the Workcell;
// LoadWorkcell calls them in order. Every failure is a LoadError naming the file and the element.
#pragma once

#include <urdf_model/model.h>
#include <yaml-cpp/yaml.h>

#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "arm_collision_monitor/geometry/mesh_fit.h"
#include "arm_collision_monitor/scene/workcell.h"
#include "arm_collision_monitor/scene/yaml_fields.h"
#include "mesh_shapes.h"
#include "solid_shapes.h"

namespace arm_collision_monitor {
namespace scene_sections {

using yaml_fields::Where;

/// Link, object and primitive names share one namespace (compatible: may name any of them):
/// each is claimed once, with where it was declared.
class NameRegistry {
 public:
  /// Records `name` as declared at `origin` ("file: element"). Throws LoadError naming both
  /// declarations when the name is taken.
  void Claim(const std::string& name, const std::string& origin);

 private:
  std::map<std::string, std::string> origin_of_name_;
};

/// One entry of links: (what replaces or adjusts the URDF collision geometry of a link).
struct LinkOverride {
  bool ignore = false;
  std::optional<double> radius_m;
  std::optional<Eigen::Vector3d> p0_L;  ///< capsule endpoints in the link frame L, given together
  std::optional<Eigen::Vector3d> p1_L;
  std::optional<double> tolerance_m;
};

/// What arms: and links: say about each link: every primitive of a link (from the URDF or a
/// model variant) inherits its arm group and tolerance from here.
struct LinkSettings {
  std::vector<int> arm_of_link;         ///< per link: index into Workcell::arms, -1 if none
  std::vector<LinkOverride> overrides;  ///< per link (KinematicModel link order)
  /// Tolerance of a moving link outside every arm (MonitorOptions::tolerance_m): a moving
  /// primitive without a tolerance zone could pass a static one between two cycles unseen.
  double default_tolerance_m = 0.0;
};

/// How the solids of objects: and of the planning scene become primitives (top-level keys
/// cylinder_model and mesh_fit), and the URDF's cylinders (urdf_cylinder_model).
struct ShapeOptions {
  CylinderModel cylinder_model = CylinderModel::kCapsule;
  MeshFitOptions mesh_fit;  ///< default: one capsule (the URDF's meshes too)
  CylinderModel urdf_cylinder_model = CylinderModel::kCapsule;
};

/// The top level: only the known section names.
void CheckSectionNames(const YAML::Node& scene, const std::string& scene_path);

/// cylinder_model and urdf_cylinder_model: capsule | box | tighter, and mesh_fit: capsule |
/// capsules:K | box | tighter (K in [1, kMeshFitMaxCapsules]); all optional.
ShapeOptions ReadShapeOptions(const YAML::Node& scene, const std::string& scene_path);

/// world: the cube the spatial index covers, in the fixed frame (`node` defined: without it the
/// loader derives the cube, DeriveWorldCube).
Aabb ReadWorld(const YAML::Node& node, const Where& where);

/// joint_limits: soft limits, each within the URDF's limits of an actuated joint; set on `model`.
void ReadJointLimits(const YAML::Node& node, const Where& where, KinematicModel* model);

/// joint_defaults: (q index, position) per actuated joint named, each position within the
/// joint's limits on `model` (after joint_limits).
std::vector<std::pair<int, double>> ReadJointDefaults(const YAML::Node& node, const Where& where,
                                                      const KinematicModel& model);

/// arms: the arms (tolerance `default_tolerance_m` unless given) and, in `arm_of_link`, the arm
/// of every link (-1 outside every arm; the arms' subtrees must be disjoint).
std::vector<ArmSpec> ReadArms(const YAML::Node& node, const Where& where,
                              const KinematicModel& model, double default_tolerance_m,
                              std::vector<int>* arm_of_link);

/// links: the per-link overrides, one entry per link of `model`.
std::vector<LinkOverride> ReadLinkOverrides(const YAML::Node& node, const Where& where,
                                            const KinematicModel& model);

/// The default model of every link, in link order: the URDF's collision geometry
/// (ReadUrdfLinkGeometry: cylinders per `cylinder_model`, meshes fitted by `meshes`) after the
/// links: overrides (a link with a radius_m or p0_m override takes its cylinders as capsules,
/// which the override changes). Claims every link name, then the primitives' names. `workcell`
/// supplies the kinematics and the arms; `warnings` gets one line per radius_m override that
/// narrows a capsule of the link's own geometry (a mesh's fit too).
std::vector<PrimitiveSpec> MakeLinkPrimitives(const urdf::ModelInterface& urdf_model,
                                              const Workcell& workcell, const LinkSettings& links,
                                              CylinderModel cylinder_model, MeshFitter* meshes,
                                              NameRegistry* names,
                                              std::vector<std::string>* warnings);

/// objects: appends each object and its primitives (box, sphere, cylinder per
/// `options.cylinder_model`, capsule, or the primitives `meshes` fits to a mesh file: one
/// primitive named after the object, or several named object/0, object/1, ...) to `workcell`
/// (whose world_W must be read: every primitive must lie inside it).
void ReadObjects(const YAML::Node& node, const Where& where, const ShapeOptions& options,
                 MeshFitter* meshes, NameRegistry* names, Workcell* workcell);

/// Appends `object` and one primitive per shape (in W, at the object's start pose) to
/// `workcell`: named after the object when it has one shape, else object/0, object/1, ...
/// (claimed in `names`), static unless attachable or frame-bound. Throws a LoadError prefixed
/// with `origin` ("file: element") when a shape is not inside workcell->world_W.
void AppendObject(ObjectSpec object, const std::vector<Shape>& shapes_W, double tolerance_m,
                  const std::string& origin, NameRegistry* names, Workcell* workcell);

/// variants: appends each model variant and its capsules (after all primitives so far) to
/// `workcell`.
void ReadVariants(const YAML::Node& node, const Where& where, const LinkSettings& links,
                  NameRegistry* names, Workcell* workcell);

/// The primitives a name stands for in `workcell`: all of a link's (every variant), an
/// object's, or the primitive of that name; empty if none.
std::vector<PrimitiveId> ResolveNames(const Workcell& workcell, const std::string& name);

/// compatible: the listed pairs of primitives, each name resolved to the primitives of that
/// link, object or primitive of `workcell`.
std::vector<std::pair<PrimitiveId, PrimitiveId>> ReadCompatiblePairs(const YAML::Node& node,
                                                                     const Where& where,
                                                                     const Workcell& workcell);

/// grasp_targets: (link, object) pairs of `workcell`'s links and objects, each listed once.
std::vector<GraspTargetSpec> ReadGraspTargets(const YAML::Node& node, const Where& where,
                                              const Workcell& workcell);

}  // namespace scene_sections
}  // namespace arm_collision_monitor
