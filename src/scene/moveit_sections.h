// The scene file's MoveIt inputs (format: the comment block at the top of config/scene.yaml):
// srdf: (its collision rules as compatible pairs) and planning_scene: (its world collision
// objects as static objects, optionally its allowed collision matrix as compatible pairs).
// The files are read by srdf_reader.h and planning_scene_reader.h; this maps their names and
// frames onto the workcell. Every failure is a LoadError naming the file and the element.
#pragma once

#include <map>
#include <string>
#include <utility>
#include <vector>

#include "arm_collision_monitor/scene/planning_scene_reader.h"
#include "arm_collision_monitor/scene/srdf_reader.h"
#include "scene_sections.h"

namespace arm_collision_monitor {
namespace scene_sections {

/// A file a srdf: or planning_scene: value names: its URL and its text.
struct NamedFile {
  std::string url;  ///< the name, made absolute against the scene file's folder if a relative path
  std::string text;
};

/// Fetches the file `node` names (a path relative to the scene file's folder unless absolute,
/// or a URL: file://, and package:// when `fetch` resolves it). A LoadError names `where`.
NamedFile FetchNamedFile(const YAML::Node& node, const Where& where, const ResourceFetcher& fetch);

/// Collision rules by name, MoveIt's way: a pair is compatible when it is in allowed_pairs, or
/// when either name is in default_allowed and the pair is not in denied_pairs (denied pairs only
/// limit the defaults: they never remove compatibility given by any other rule).
struct NamedCollisionRules {
  std::vector<std::pair<std::string, std::string>> allowed_pairs;
  std::vector<std::pair<std::string, std::string>> denied_pairs;
  std::vector<std::string> default_allowed;
  /// The line where a name first appears in the source (an SRDF's), for the notice of unknown
  /// names; a name without one is listed bare.
  std::map<std::string, int> first_line;
};

/// The primitive pairs of `rules` in `workcell` (a name stands for what ResolveNames gives).
/// Names with no primitive are skipped; if there are any, one notice listing them, prefixed
/// with `source` ("file: element"), is appended to workcell->warnings.
std::vector<std::pair<PrimitiveId, PrimitiveId>> ResolveCollisionRules(
    const NamedCollisionRules& rules, const std::string& source, Workcell* workcell);

/// What srdf: loaded.
struct SrdfInput {
  std::string path;  ///< "" when the scene file has no srdf:
  SrdfCollisionRules rules;
  /// Parent frames of the SRDF's fixed virtual joints whose child is the URDF root link: other
  /// names of the fixed frame (a Setup Assistant SRDF hangs base_link from "world" this way, and
  /// MoveIt's planning-scene dumps then say "world").
  std::vector<std::string> root_aliases;
  /// The SRDF's floating and planar virtual joints whose child is the URDF root link: the root
  /// stands in their parent frames where the planning scene's robot state puts it.
  std::vector<SrdfVirtualJoint> moving_root_joints;
  /// srdf_trust_never_between_arms: its "Never" pairs of links on two arms are compatible too.
  bool is_never_between_arms_trusted = false;
};

/// srdf: (optional) and srdf_trust_never_between_arms: reads the SRDF (a notice when it names
/// another robot than `urdf_robot_name`, or when a non-fixed virtual joint moves the root link).
SrdfInput ReadSrdf(const YAML::Node& scene, const std::string& scene_path,
                   const std::string& urdf_robot_name, const ResourceFetcher& fetch,
                   Workcell* workcell);

/// The SRDF's <disable_collisions> as allowed pairs, <enable_collisions> as denied pairs,
/// <disable_default_collisions> as default-allowed links, resolved in `workcell` (after every
/// primitive is known). None when there is no srdf:. A <disable_collisions> pair of reason
/// "Never" whose links are on two arms stays checked (the Setup Assistant's random samples never
/// saw it touch, yet the arms can meet; a notice lists them) unless input.is_never_between_arms_
/// trusted.
std::vector<std::pair<PrimitiveId, PrimitiveId>> SrdfPairs(const SrdfInput& input,
                                                           Workcell* workcell);

/// What planning_scene: loaded, kept for its allowed collision matrix.
struct PlanningSceneInput {
  std::string path;  ///< "" when the scene file has no planning_scene:
  bool is_acm_imported = false;
  PlanningSceneFile file;
};

/// planning_scene: (optional), planning_scene_acm and planning_scene_tolerance_m: appends each
/// world collision object of the file as a static object of `workcell` (whose world_W and
/// kinematics must be read). Its frame must be the fixed frame (one of srdf.root_aliases means
/// it), a URDF link fixed to it, or the parent frame of one of srdf.moving_root_joints (the
/// root link where the file's robot_state.multi_dof_joint_state puts it, else at its origin,
/// taken to stay there; a notice says where); "" is MoveIt's planning frame: that parent frame,
/// else the fixed frame. Box -> Box; sphere -> zero-length capsule; cylinder,
/// and a cone's bounding cylinder -> per options.cylinder_model; inline mesh -> the primitives
/// `meshes` fits to it.
/// The file is read through `fetch`; its notices are added to workcell->warnings.
PlanningSceneInput ReadPlanningScene(const YAML::Node& scene, const std::string& scene_path,
                                     const ShapeOptions& options, const ResourceFetcher& fetch,
                                     const SrdfInput& srdf, MeshFitter* meshes,
                                     NameRegistry* names,
                                     Workcell* workcell);

/// The allowed collision matrix of `input` as compatible pairs when planning_scene_acm: true
/// (none otherwise), resolved in `workcell` after every primitive is known.
std::vector<std::pair<PrimitiveId, PrimitiveId>> PlanningSceneAcmPairs(
    const PlanningSceneInput& input, Workcell* workcell);

}  // namespace scene_sections
}  // namespace arm_collision_monitor
