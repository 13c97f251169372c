#include "moveit_sections.h"

#include <algorithm>
#include <filesystem>
#include <sstream>

#include "arm_collision_monitor/core/load_error.h"
#include "arm_collision_monitor/scene/srdf_reader.h"

namespace arm_collision_monitor {
namespace scene_sections {
namespace {

std::string Quoted(const std::string& name) { return " '" + name + "'"; }

// Runs `read`, prefixing any LoadError with the scene file's key that named the file.
template <typename Read>
auto ReadNamedFile(const Where& where, Read read) {
  try {
    return read();
  } catch (const LoadError& e) {
    throw LoadError(where.file + ": " + where.element + ": " + e.what());
  }
}

// The frames beside the URDF's links that planning-scene objects may name: the fixed virtual
// joints' parent frames (the fixed frame), and the moving ones' with the root link's pose in
// them from the scene's robot state, or MoveIt's default, the identity.
struct HeaderFrames {
  struct Placed {
    SrdfVirtualJoint joint;
    const SceneJointPose* pose = nullptr;  // the scene's value of the joint, if it gives one
    bool is_used = false;                  // some object is in its parent frame
  };
  std::vector<std::string> root_aliases;
  std::vector<Placed> placed;
  std::vector<Eigen::Isometry3d> X_WL;  // the links' poses (those fixed to the root are used)
};

// The pose in W of a planning-scene object's header frame: the fixed frame (a root alias means
// it), a URDF link fixed to it (its pose does not depend on q), or a placed frame. No frame is
// MoveIt's planning frame: a moving virtual joint's parent frame, else the fixed frame.
Eigen::Isometry3d HeaderFramePose(const SceneCollisionObject& object, const Workcell& workcell,
                                  const std::string& path, HeaderFrames* frames) {
  std::string frame = object.frame_id;
  if (frame.empty() && !frames->placed.empty()) frame = frames->placed.front().joint.parent_frame;
  const std::vector<std::string>& aliases = frames->root_aliases;
  if (frame.empty() || std::find(aliases.begin(), aliases.end(), frame) != aliases.end()) {
    frame = workcell.fixed_frame;
  }
  const std::vector<Eigen::Isometry3d>& X_WL = frames->X_WL;
  for (HeaderFrames::Placed& placed : frames->placed) {
    if (frame != placed.joint.parent_frame) continue;
    placed.is_used = true;
    if (placed.pose == nullptr) return X_WL[0];
    return X_WL[0] * placed.pose->X_PC.inverse();  // the root link is the joint's child
  }
  const int link = workcell.kinematics.FindLink(frame);
  const std::string where = path + ":" + std::to_string(object.line) + ": " + object.element +
                            ": header.frame_id" + Quoted(frame);
  if (link < 0) {
    throw LoadError(where + " is not a URDF link (expected the fixed frame" +
                    Quoted(workcell.fixed_frame) + " or a link fixed to it)");
  }
  if (workcell.kinematics.is_moving(link)) {
    throw LoadError(where + " is a moving link (expected the fixed frame" +
                    Quoted(workcell.fixed_frame) +
                    " or a link fixed to it: planning-scene objects are static)");
  }
  return X_WL[link];
}

// The notice for a placed frame that objects are in: where the root link stands in it.
std::string PlacedFrameNotice(const HeaderFrames::Placed& placed, const std::string& path,
                              const std::string& srdf_path, const std::string& root) {
  const std::string& frame = placed.joint.parent_frame;
  std::ostringstream text;
  text << path << ": the objects in" << Quoted(frame)
       << " (MoveIt's planning frame, also for objects without a frame) are placed with the root"
       << " link" << Quoted(root) << " at ";
  if (placed.pose != nullptr) {
    const Eigen::Vector3d p = placed.pose->X_PC.translation();
    const Eigen::Quaterniond r(placed.pose->X_PC.linear());
    text << "translation [" << p.x() << ", " << p.y() << ", " << p.z() << "] m, rotation ["
         << r.x() << ", " << r.y() << ", " << r.z() << ", " << r.w()
         << "] (x, y, z, w), the pose robot_state.multi_dof_joint_state gives (line "
         << placed.pose->line << ")";
  } else {
    text << "its origin, MoveIt's default: robot_state.multi_dof_joint_state gives no pose";
  }
  text << " of the SRDF's " << placed.joint.type << " virtual joint" << Quoted(placed.joint.name)
       << " (" << srdf_path << ":" << placed.joint.line
       << "); the monitor takes the robot to stay there";
  return text.str();
}

// The shapes of one shape_msgs/SolidPrimitive at X_WP.
Shape ScenePrimitiveShape_W(const ScenePrimitive& primitive, const Eigen::Isometry3d& X_WP,
                            CylinderModel cylinder_model) {
  const std::vector<double>& d = primitive.dimensions_m;
  switch (primitive.type) {
    case SolidPrimitiveType::kBox:
      return Box{X_WP, 0.5 * Eigen::Vector3d(d[0], d[1], d[2])};
    case SolidPrimitiveType::kSphere:
      return SphereShape_L(X_WP, d[0]);
    default:  // cylinder, or a cone as its bounding cylinder: [height, radius], centred on P
      return CylinderShape_L(X_WP, d[1], d[0], cylinder_model);
  }
}

// Every shape of `object` in W: its primitives, then each mesh's fitted primitives.
std::vector<Shape> CollisionObjectShapes_W(const SceneCollisionObject& object,
                                           const Eigen::Isometry3d& X_WF,
                                           const ShapeOptions& options, const std::string& path,
                                           MeshFitter* meshes) {
  std::vector<Shape> shapes_W;
  for (const ScenePrimitive& primitive : object.primitives) {
    shapes_W.push_back(
        ScenePrimitiveShape_W(primitive, X_WF * primitive.X_FP, options.cylinder_model));
  }
  for (std::size_t m = 0; m < object.meshes.size(); ++m) {
    const SceneMesh& mesh = object.meshes[m];
    const std::vector<Shape> shapes_M = meshes->FitInline(
        TriangleMesh{mesh.vertices_M, mesh.triangles},
        path + ":" + std::to_string(object.line) + ": " + object.element + ".meshes[" +
            std::to_string(m) + "]");
    for (const Shape& shape_M : shapes_M) {
      shapes_W.push_back(TransformShape(X_WF * mesh.X_FM, shape_M));
    }
  }
  return shapes_W;
}

// One collision object: the object and its primitives, appended to `workcell`.
void AddCollisionObject(const SceneCollisionObject& object, const std::string& path,
                        const ShapeOptions& options, double tolerance_m, HeaderFrames* frames,
                        MeshFitter* meshes, NameRegistry* names, Workcell* workcell) {
  const std::string origin = path + ":" + std::to_string(object.line) + ": " + object.element;
  names->Claim(object.id, origin);
  const std::vector<Shape> shapes_W =
      CollisionObjectShapes_W(object, HeaderFramePose(object, *workcell, path, frames),
                              options, path, meshes);
  ObjectSpec spec;
  spec.name = object.id;
  AppendObject(spec, shapes_W, tolerance_m, origin, names, workcell);
}

// For links without primitives, the fixed child links with primitives (at most three links):
// "; 'link1' has geometry on its fixed child 'link1_sc'" (a URDF that keeps its collision shapes
// on such children, as franka_description's with_sc, while the SRDF names the parents); "".
std::string FixedChildrenHint(const Workcell& workcell, const std::vector<std::string>& links) {
  constexpr int kHintedLinks = 3;
  const KinematicModel& kinematics = workcell.kinematics;
  std::string hint;
  int hinted = 0;
  for (const std::string& name : links) {
    const int link = kinematics.FindLink(name);
    std::vector<std::string> children;
    for (int child = 1; child < kinematics.link_count(); ++child) {
      if (kinematics.parent_link(child) == link &&
          kinematics.joint(child).type == JointType::kFixed &&
          !ResolveNames(workcell, kinematics.link_name(child)).empty()) {
        children.push_back(kinematics.link_name(child));
      }
    }
    if (children.empty()) continue;
    hint += "; '" + name + "' has geometry on its fixed child" +
            (children.size() == 1 ? " " : "ren ") + QuotedNames(children);
    if (++hinted == kHintedLinks) break;
  }
  return hint.empty() ? "" : hint + " (a rule holds for a link's own geometry: name the children)";
}

/// QuotedNames with each name's line where `lines` has one: "'a' (line 6), 'b'".
std::string QuotedNamesWithLines(const std::vector<std::string>& names,
                                 const std::map<std::string, int>& lines) {
  std::string text;
  for (const std::string& name : names) {
    text += (text.empty() ? "'" : ", '") + name + "'";
    const auto at = lines.find(name);
    if (at != lines.end()) text += " (line " + std::to_string(at->second) + ")";
  }
  return text;
}

}  // namespace

NamedFile FetchNamedFile(const YAML::Node& node, const Where& where,
                         const ResourceFetcher& fetch) {
  NamedFile file;
  file.url = ResolveResourceName(yaml_fields::ReadName(node, where),
                                 std::filesystem::path(where.file).parent_path().string());
  file.text = ReadNamedFile(where, [&] { return fetch(file.url); });
  return file;
}

std::vector<std::pair<PrimitiveId, PrimitiveId>> ResolveCollisionRules(
    const NamedCollisionRules& rules, const std::string& source, Workcell* workcell) {
  std::vector<std::string> bare_links;  // URDF links without primitives
  std::vector<std::string> unknown;     // neither a link nor an object or primitive
  auto resolve = [&](const std::string& name) {
    std::vector<PrimitiveId> ids = ResolveNames(*workcell, name);
    std::vector<std::string>& skipped =
        workcell->kinematics.FindLink(name) >= 0 ? bare_links : unknown;
    if (ids.empty() && std::find(skipped.begin(), skipped.end(), name) == skipped.end()) {
      skipped.push_back(name);
    }
    return ids;
  };
  std::vector<std::pair<PrimitiveId, PrimitiveId>> pairs;
  for (const auto& [name1, name2] : rules.allowed_pairs) {
    const std::vector<PrimitiveId> side2 = resolve(name2);
    for (const PrimitiveId a : resolve(name1)) {
      for (const PrimitiveId b : side2) {
        if (a != b) pairs.emplace_back(a, b);
      }
    }
  }
  const auto n = static_cast<PrimitiveId>(workcell->primitives.size());
  for (const std::string& name : rules.default_allowed) {
    std::vector<bool> is_denied(n, false);
    for (const auto& [name1, name2] : rules.denied_pairs) {
      if (name1 != name && name2 != name) continue;
      for (const PrimitiveId id : resolve(name1 == name ? name2 : name1)) is_denied[id] = true;
    }
    for (const PrimitiveId a : resolve(name)) {
      for (PrimitiveId b = 0; b < n; ++b) {
        if (a != b && !is_denied[b]) pairs.emplace_back(a, b);
      }
    }
  }
  // The names of a denied pair without a default among them (which it does not limit) are
  // resolved too, so that a typo there is reported as well.
  for (const auto& [name1, name2] : rules.denied_pairs) {
    resolve(name1);
    resolve(name2);
  }
  if (!bare_links.empty()) {
    workcell->warnings.push_back(source + ": skipped " + std::to_string(bare_links.size()) +
                                 " link(s) without primitives (no collision geometry, or "
                                 "ignored under links:): " + QuotedNames(bare_links) +
                                 FixedChildrenHint(*workcell, bare_links));
  }
  if (!unknown.empty()) {
    workcell->warnings.push_back(source + ": skipped " + std::to_string(unknown.size()) +
                                 " unknown name(s), neither a URDF link nor an object of the "
                                 "scene (a typo, or a file of another robot?): " +
                                 QuotedNamesWithLines(unknown, rules.first_line) +
                                 PrefixedNamesHint(workcell->kinematics.link_names(), unknown,
                                                   "the URDF"));
  }
  return pairs;
}

SrdfInput ReadSrdf(const YAML::Node& scene, const std::string& scene_path,
                   const std::string& urdf_robot_name, const ResourceFetcher& fetch,
                   Workcell* workcell) {
  SrdfInput input;
  const char* const trust_key = "srdf_trust_never_between_arms";
  const Where top{scene_path, ""};
  yaml_fields::ReadIfPresent(scene, trust_key, top, yaml_fields::ReadBool,
                             &input.is_never_between_arms_trusted);
  if (!scene["srdf"]) {
    if (scene[trust_key]) top.Child(trust_key).Fail(scene[trust_key], "given without srdf:");
    return input;
  }
  const Where where{scene_path, "srdf"};
  const NamedFile file = FetchNamedFile(scene["srdf"], where, fetch);
  input.path = file.url;
  input.rules =
      ReadNamedFile(where, [&] { return ReadSrdfCollisionRulesText(file.text, input.path); });
  const std::string& robot_name = input.rules.robot_name;
  if (!robot_name.empty() && robot_name != urdf_robot_name) {
    workcell->warnings.push_back(input.path + ": <robot name='" + robot_name +
                                 "'> differs from the URDF's robot '" + urdf_robot_name +
                                 "' (is it the SRDF of this robot?)");
  }
  const std::string& root = workcell->kinematics.link_name(0);
  for (const SrdfVirtualJoint& joint : input.rules.virtual_joints) {
    if (joint.child_link != root || joint.parent_frame == root) continue;
    if (joint.type == "fixed") {
      input.root_aliases.push_back(joint.parent_frame);
    } else {
      input.moving_root_joints.push_back(joint);
      const std::string where = input.path + ":" + std::to_string(joint.line) +
                                ": <virtual_joint name='" + joint.name + "' type='" + joint.type +
                                "'>";
      workcell->moving_root_frames.emplace_back(joint.parent_frame, where);
      workcell->warnings.push_back(
          where + ": the root link moves in '" + joint.parent_frame +
          "'; the monitor works in the root link's frame '" + root +
          "' (planning-scene objects in '" + joint.parent_frame +
          "' are placed with the root link where the scene's robot state puts the joint, else at "
          "the origin of '" + joint.parent_frame + "')");
    }
  }
  return input;
}

std::vector<std::pair<PrimitiveId, PrimitiveId>> SrdfPairs(const SrdfInput& input,
                                                           Workcell* workcell) {
  if (input.path.empty()) return {};
  NamedCollisionRules rules;
  // The arm of a link's primitives ("" for none or the environment).
  auto arm_of = [&](const std::string& link) {
    const std::vector<PrimitiveId> ids = ResolveNames(*workcell, link);
    return ids.empty() ? std::string() : workcell->primitives[ids.front()].group;
  };
  auto note_line = [&](const std::string& name, int line) {
    const auto [at, is_new] = rules.first_line.emplace(name, line);
    if (!is_new) at->second = std::min(at->second, line);
  };
  std::vector<std::string> kept_checked;
  for (const SrdfLinkPair& pair : input.rules.disabled_pairs) {
    note_line(pair.link1, pair.line);
    note_line(pair.link2, pair.line);
    if (!input.is_never_between_arms_trusted && pair.reason == "Never") {
      const std::string arm1 = arm_of(pair.link1);
      const std::string arm2 = arm_of(pair.link2);
      if (!arm1.empty() && !arm2.empty() && arm1 != arm2) {
        kept_checked.push_back(pair.link1 + "' and '" + pair.link2);
        continue;
      }
    }
    rules.allowed_pairs.emplace_back(pair.link1, pair.link2);
  }
  if (!kept_checked.empty()) {
    workcell->notices.push_back(
        input.path + ": " + std::to_string(kept_checked.size()) +
        " <disable_collisions> pair(s) of reason 'Never' between links of two arms stay checked "
        "(the Setup Assistant's random samples never saw them touch, yet the arms can meet; "
        "srdf_trust_never_between_arms: true excuses them, as MoveIt does): " +
        QuotedNames(kept_checked));
  }
  for (const SrdfLinkPair& pair : input.rules.enabled_pairs) {
    rules.denied_pairs.emplace_back(pair.link1, pair.link2);
    note_line(pair.link1, pair.line);
    note_line(pair.link2, pair.line);
  }
  for (const SrdfLink& link : input.rules.default_disabled_links) {
    rules.default_allowed.push_back(link.link);
    note_line(link.link, link.line);
  }
  return ResolveCollisionRules(rules, input.path + ": collision rules", workcell);
}

PlanningSceneInput ReadPlanningScene(const YAML::Node& scene, const std::string& scene_path,
                                     const ShapeOptions& options, const ResourceFetcher& fetch,
                                     const SrdfInput& srdf, MeshFitter* meshes,
                                     NameRegistry* names, Workcell* workcell) {
  PlanningSceneInput input;
  const Where top{scene_path, ""};
  double tolerance_m = 0.0;
  yaml_fields::ReadIfPresent(scene, "planning_scene_acm", top, yaml_fields::ReadBool,
                             &input.is_acm_imported);
  yaml_fields::ReadIfPresent(scene, "planning_scene_tolerance_m", top,
                             yaml_fields::ReadNonNegativeDouble, &tolerance_m);
  if (!scene["planning_scene"]) {
    for (const char* key : {"planning_scene_acm", "planning_scene_tolerance_m"}) {
      if (scene[key]) top.Child(key).Fail(scene[key], "given without planning_scene:");
    }
    return input;
  }
  const Where where{scene_path, "planning_scene"};
  const NamedFile named = FetchNamedFile(scene["planning_scene"], where, fetch);
  input.path = named.url;
  input.file = ReadNamedFile(where, [&] { return ReadPlanningSceneText(named.text, input.path); });
  for (const std::string& notice : input.file.notices) {
    workcell->warnings.push_back(input.path + ": " + notice);
  }
  HeaderFrames frames{srdf.root_aliases, {},
                      std::vector<Eigen::Isometry3d>(workcell->kinematics.link_count())};
  workcell->kinematics.ComputeLinkPoses(Eigen::VectorXd::Zero(workcell->kinematics.q_size()),
                                        &frames.X_WL);
  for (const SrdfVirtualJoint& joint : srdf.moving_root_joints) {
    const std::vector<SceneJointPose>& poses = input.file.joint_poses;
    const auto pose = std::find_if(poses.begin(), poses.end(), [&](const SceneJointPose& p) {
      return p.joint == joint.name;
    });
    frames.placed.push_back({joint, pose != poses.end() ? &*pose : nullptr, false});
  }
  ReadNamedFile(where, [&] {
    for (const SceneCollisionObject& object : input.file.objects) {
      AddCollisionObject(object, input.path, options, tolerance_m, &frames, meshes, names,
                         workcell);
    }
  });
  for (const HeaderFrames::Placed& placed : frames.placed) {
    if (!placed.is_used) continue;
    workcell->warnings.push_back(
        PlacedFrameNotice(placed, input.path, srdf.path, workcell->kinematics.link_name(0)));
    PlacedRootSpec root{placed.joint.name, Eigen::Isometry3d::Identity(),
                        input.path + " (no robot state: the origin)"};
    if (placed.pose != nullptr) {
      root.X_FR = placed.pose->X_PC;
      root.where = input.path + ":" + std::to_string(placed.pose->line) +
                   " (robot_state.multi_dof_joint_state)";
    }
    workcell->placed_roots.push_back(std::move(root));
  }
  return input;
}

std::vector<std::pair<PrimitiveId, PrimitiveId>> PlanningSceneAcmPairs(
    const PlanningSceneInput& input, Workcell* workcell) {
  if (input.path.empty() || !input.is_acm_imported) return {};
  const SceneAllowedCollisions& acm = input.file.allowed_collisions;
  if (acm.allowed_pairs.empty() && acm.disallowed_pairs.empty() &&
      acm.default_allowed_names.empty()) {
    // Asked for, but nothing there (scene geometry text never has a matrix): say so.
    workcell->warnings.push_back(input.path +
                                 ": planning_scene_acm: true, but the file allows no collisions "
                                 "(no allowed_collision_matrix entries): none imported");
    return {};
  }
  NamedCollisionRules rules{acm.allowed_pairs, acm.disallowed_pairs, acm.default_allowed_names,
                            {}};
  // An object skipped for having no shapes has nothing to excuse: not an unknown name.
  const std::vector<std::string>& shapeless = input.file.shapeless_ids;
  const auto is_shapeless = [&](const std::string& name) {
    return std::find(shapeless.begin(), shapeless.end(), name) != shapeless.end();
  };
  for (auto* pairs : {&rules.allowed_pairs, &rules.denied_pairs}) {
    pairs->erase(std::remove_if(pairs->begin(), pairs->end(),
                                [&](const auto& pair) {
                                  return is_shapeless(pair.first) || is_shapeless(pair.second);
                                }),
                 pairs->end());
  }
  rules.default_allowed.erase(
      std::remove_if(rules.default_allowed.begin(), rules.default_allowed.end(), is_shapeless),
      rules.default_allowed.end());
  return ResolveCollisionRules(rules, input.path + ": allowed_collision_matrix", workcell);
}

}  // namespace scene_sections
}  // namespace arm_collision_monitor
