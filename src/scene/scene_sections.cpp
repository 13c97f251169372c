#include "scene_sections.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <utility>

#include "urdf_collision.h"

namespace arm_collision_monitor {
namespace scene_sections {
namespace {

std::string Quoted(const std::string& name) { return " '" + name + "'"; }

// A primitive of `link` with what it inherits from the link: owner, arm group, tolerance (the
// link's override, else its arm's, else the default for a moving link, else 0) and whether it
// is static. Name and shape are the caller's.
PrimitiveSpec NewLinkPrimitive(int link, const Workcell& workcell, const LinkSettings& links) {
  const KinematicModel& model = workcell.kinematics;
  const int arm = links.arm_of_link[link];
  PrimitiveSpec p;
  p.owner = model.link_name(link);
  p.link_index = link;
  p.group = arm >= 0 ? workcell.arms[arm].name : "";
  if (links.overrides[link].tolerance_m) {
    p.tolerance_m = *links.overrides[link].tolerance_m;
  } else if (arm >= 0) {
    p.tolerance_m = workcell.arms[arm].tolerance_m;
  } else {
    p.tolerance_m = model.is_moving(link) ? links.default_tolerance_m : 0.0;
  }
  p.is_static = !model.is_moving(link);
  return p;
}

// The link's primitives in L after the scene's override (an override with its radius reads no
// URDF geometry: explicit overrides win, even over a mesh that could not be read).
std::vector<std::pair<std::string, Shape>> LinkShapes(const urdf::Link& link, const LinkOverride& o,
                                                      const std::string& urdf_path,
                                                      const std::string& scene_path,
                                                      CylinderModel cylinder_model,
                                                      MeshFitter* meshes,
                                                      std::vector<std::string>* warnings) {
  if (o.ignore) return {};
  if (o.p0_L && o.radius_m) return {{"0", Capsule{*o.p0_L, *o.p1_L, *o.radius_m}}};
  // The overrides change a capsule: the link's cylinders stay capsules for them.
  const bool is_capsule_override = o.p0_L || o.radius_m;
  const UrdfLinkGeometry geometry = ReadUrdfLinkGeometry(
      link, urdf_path, is_capsule_override ? CylinderModel::kCapsule : cylinder_model, meshes);
  if (o.p0_L) {
    if (geometry.capsule_count() != 1 || geometry.shapes_L.size() != 1) {
      throw LoadError(scene_path + ": links." + link.name +
                      ": radius_m is required with p0_m/p1_m (the URDF link has no single "
                      "capsule to take it from)");
    }
    const double radius_m = std::get<Capsule>(geometry.shapes_L[0].second).radius_m;
    return {{"0", Capsule{*o.p0_L, *o.p1_L, radius_m}}};
  }
  auto shapes = geometry.shapes_L;
  if (o.radius_m) {
    if (geometry.capsule_count() == 0) {
      throw LoadError(scene_path + ": links." + link.name +
                      ": radius_m given but the link has no capsule (cylinder or sphere)");
    }
    double widest_m = 0.0;
    for (auto& named : shapes) {
      auto* capsule = std::get_if<Capsule>(&named.second);
      if (capsule == nullptr) continue;
      widest_m = std::max(widest_m, capsule->radius_m);
      capsule->radius_m = *o.radius_m;
    }
    if (widest_m > *o.radius_m) {
      char text[160];
      std::snprintf(text, sizeof(text), ": radius_m %.6g m is below the %.6g m of a capsule of "
                    "the link's own geometry", *o.radius_m, widest_m);
      warnings->push_back(scene_path + ": links." + link.name + text +
                          " (a mesh's fit too): part of the link is left outside its model");
    }
  }
  return shapes;
}

// pose: {xyz_m, rpy} of an objects: entry.
Eigen::Isometry3d ReadObjectPose(const YAML::Node& entry, const Where& item) {
  const YAML::Node pose = entry["pose"];
  const Where pose_where = item.Child("pose");
  if (!pose.IsDefined()) item.Fail(entry, "missing pose: {xyz_m: [x, y, z], rpy: [r, p, y]}");
  yaml_fields::RequireMap(pose, pose_where);
  yaml_fields::CheckKeys(pose, {"xyz_m", "rpy"}, pose_where);
  const Eigen::Vector3d xyz_m = yaml_fields::ReadVector3(pose["xyz_m"], pose_where.Child("xyz_m"));
  Eigen::Vector3d rpy = Eigen::Vector3d::Zero();
  yaml_fields::ReadIfPresent(pose, "rpy", pose_where, yaml_fields::ReadVector3, &rpy);
  return PoseFromXyzRpy(xyz_m, rpy);
}

// The keys each objects: type takes for its size, the first the type's default.
struct ObjectType {
  const char* name;
  std::vector<const char*> size_keys;
};
const std::vector<ObjectType>& ObjectTypes() {
  static const std::vector<ObjectType> types = {{"box", {"size_m"}},
                                                {"sphere", {"radius_m"}},
                                                {"cylinder", {"radius_m", "length_m"}},
                                                {"capsule", {"radius_m", "length_m"}},
                                                {"mesh", {"mesh", "scale"}}};
  return types;
}

// The solid of an objects: entry (type: box unless given), in its frame O at X_WO, in W: one
// primitive, or those fitted to a mesh.
std::vector<Shape> ReadObjectShapes(const YAML::Node& entry, const Where& item,
                                    const Eigen::Isometry3d& X_WO, const ShapeOptions& options,
                                    MeshFitter* meshes) {
  std::string type = "box";
  yaml_fields::ReadIfPresent(entry, "type", item, yaml_fields::ReadName, &type);
  const auto& types = ObjectTypes();
  const auto it = std::find_if(types.begin(), types.end(),
                               [&](const ObjectType& t) { return type == t.name; });
  if (it == types.end()) {
    item.Child("type").Fail(entry["type"], "unknown type" + Quoted(type) +
                                 " (expected box, sphere, cylinder, capsule or mesh)");
  }
  for (const char* key : {"size_m", "radius_m", "length_m", "mesh", "scale"}) {
    const bool is_taken = std::find_if(it->size_keys.begin(), it->size_keys.end(), [&](auto k) {
                            return std::string(k) == key;
                          }) != it->size_keys.end();
    const bool is_optional = std::string(key) == "scale";
    if (is_taken && !is_optional && !entry[key]) item.Fail(entry, "a " + type + " needs " + key);
    if (!is_taken && entry[key]) {
      item.Child(key).Fail(entry[key], std::string(key) + " is not a key of a " + type);
    }
  }
  if (type == "mesh") {
    const std::string name = yaml_fields::ReadName(entry["mesh"], item.Child("mesh"));
    Eigen::Vector3d scale = Eigen::Vector3d::Ones();
    yaml_fields::ReadIfPresent(entry, "scale", item, yaml_fields::ReadVector3, &scale);
    const std::string folder = std::filesystem::path(item.file).parent_path().string();
    std::vector<Shape> shapes_W;
    for (const Shape& shape_O :
         meshes->FitFile(name, folder, scale, item.file + ": " + item.element)) {
      shapes_W.push_back(TransformShape(X_WO, shape_O));
    }
    return shapes_W;
  }
  if (type == "box") {
    const Eigen::Vector3d size_m = yaml_fields::ReadVector3(entry["size_m"], item.Child("size_m"));
    if ((size_m.array() <= 0.0).any()) {
      item.Fail(entry["size_m"], "size_m must be 3 numbers > 0 (full edge lengths, metres)");
    }
    return {Box{X_WO, 0.5 * size_m}};
  }
  const double radius_m =
      yaml_fields::ReadPositiveDouble(entry["radius_m"], item.Child("radius_m"));
  if (type == "sphere") return {SphereShape_L(X_WO, radius_m)};
  if (type == "cylinder") {
    const double length_m =
        yaml_fields::ReadPositiveDouble(entry["length_m"], item.Child("length_m"));
    return {CylinderShape_L(X_WO, radius_m, length_m, options.cylinder_model)};
  }
  return {CapsuleShape_L(X_WO, radius_m,
                         yaml_fields::ReadNonNegativeDouble(entry["length_m"],
                                                            item.Child("length_m")))};
}

// One objects: entry: the object and its primitives, appended to `workcell`.
void ReadObject(const YAML::Node& entry, Where item, const ShapeOptions& options,
                MeshFitter* meshes, NameRegistry* names, Workcell* workcell) {
  yaml_fields::RequireMap(entry, item);
  yaml_fields::CheckKeys(entry,
                         {"name", "type", "size_m", "radius_m", "length_m", "mesh", "scale",
                          "pose", "tolerance_m", "attachable", "frame"},
                         item);
  ObjectSpec object;
  object.name = yaml_fields::ReadName(entry["name"], item.Child("name"));
  item.element += Quoted(object.name);
  const std::string origin = item.file + ": " + item.element;
  names->Claim(object.name, origin);
  object.X_WO_start = ReadObjectPose(entry, item);
  yaml_fields::ReadIfPresent(entry, "attachable", item, yaml_fields::ReadBool,
                             &object.is_attachable);
  yaml_fields::ReadIfPresent(entry, "frame", item, yaml_fields::ReadName, &object.frame);
  double tolerance_m = 0.0;
  yaml_fields::ReadIfPresent(entry, "tolerance_m", item, yaml_fields::ReadNonNegativeDouble,
                             &tolerance_m);
  const std::vector<Shape> shapes_W =
      ReadObjectShapes(entry, item, object.X_WO_start, options, meshes);
  AppendObject(object, shapes_W, tolerance_m, origin, names, workcell);
}

// One capsule of a variants: entry, a primitive of `variant`'s link.
PrimitiveSpec ReadVariantCapsule(const YAML::Node& cap, const Where& cap_where,
                                 const ModelVariantSpec& variant, const Workcell& workcell,
                                 const LinkSettings& links, NameRegistry* names) {
  yaml_fields::RequireMap(cap, cap_where);
  yaml_fields::CheckKeys(cap, {"name", "p0_m", "p1_m", "radius_m"}, cap_where);
  PrimitiveSpec p = NewLinkPrimitive(variant.link_index, workcell, links);
  p.name = variant.link + "/" + yaml_fields::ReadName(cap["name"], cap_where.Child("name"));
  names->Claim(p.name, cap_where.file + ": " + cap_where.element);
  p.variant = variant.name;
  p.shape_L =
      Capsule{yaml_fields::ReadVector3(cap["p0_m"], cap_where.Child("p0_m")),
              yaml_fields::ReadVector3(cap["p1_m"], cap_where.Child("p1_m")),
              yaml_fields::ReadNonNegativeDouble(cap["radius_m"], cap_where.Child("radius_m"))};
  return p;
}

// One variants: entry: the variant and its capsules, appended to `workcell`.
void ReadVariant(const YAML::Node& entry, Where item, const LinkSettings& links,
                 NameRegistry* names, Workcell* workcell) {
  yaml_fields::RequireMap(entry, item);
  yaml_fields::CheckKeys(entry, {"link", "name", "capsules"}, item);
  ModelVariantSpec variant;
  variant.link = yaml_fields::ReadName(entry["link"], item.Child("link"));
  variant.link_index = workcell->kinematics.FindLink(variant.link);
  if (variant.link_index < 0) {
    item.Fail(entry["link"], "unknown link" + Quoted(variant.link) + " (expected a URDF link)");
  }
  variant.name = yaml_fields::ReadName(entry["name"], item.Child("name"));
  item.element += Quoted(variant.link + "/" + variant.name);
  if (workcell->FindVariant(variant.link, variant.name) >= 0) {
    item.Fail(entry["name"], "duplicate variant of this link");
  }
  const YAML::Node capsules = entry["capsules"];
  const Where capsules_where = item.Child("capsules");
  yaml_fields::RequireSequence(capsules, capsules_where);
  if (capsules.size() == 0) capsules_where.Fail(capsules, "expected at least one capsule");
  for (std::size_t c = 0; c < capsules.size(); ++c) {
    const PrimitiveSpec p =
        ReadVariantCapsule(capsules[c], capsules_where.Entry(c), variant, *workcell, links, names);
    variant.primitives.push_back(static_cast<PrimitiveId>(workcell->primitives.size()));
    workcell->primitives.push_back(p);
  }
  workcell->variants.push_back(variant);
}

}  // namespace

void NameRegistry::Claim(const std::string& name, const std::string& origin) {
  const auto [it, inserted] = origin_of_name_.emplace(name, origin);
  if (!inserted) {
    throw LoadError(origin + ": duplicate name" + Quoted(name) + " (already used by " + it->second +
                    "; expected unique link, object and primitive names)");
  }
}

std::vector<PrimitiveId> ResolveNames(const Workcell& w, const std::string& name) {
  std::vector<PrimitiveId> ids;
  const int link = w.kinematics.FindLink(name);
  for (PrimitiveId id = 0; id < w.primitives.size(); ++id) {
    const PrimitiveSpec& p = w.primitives[id];
    if ((link >= 0 && p.link_index == link) || (link < 0 && (p.owner == name || p.name == name))) {
      ids.push_back(id);
    }
  }
  return ids;
}

void CheckSectionNames(const YAML::Node& scene, const std::string& scene_path) {
  yaml_fields::CheckKeys(scene,
                         {"world", "arms", "links", "joint_limits", "joint_defaults", "objects",
                          "compatible", "grasp_targets", "variants", "cylinder_model",
                          "urdf_cylinder_model", "mesh_fit", "srdf",
                          "srdf_trust_never_between_arms", "planning_scene",
                          "planning_scene_acm", "planning_scene_tolerance_m"},
                         Where{scene_path, ""});
}

ShapeOptions ReadShapeOptions(const YAML::Node& scene, const std::string& scene_path) {
  ShapeOptions options;
  auto read_cylinder_model = [&](const char* key, CylinderModel* model) {
    std::string name = "capsule";
    yaml_fields::ReadIfPresent(scene, key, Where{scene_path, ""}, yaml_fields::ReadName, &name);
    if (name == "box") {
      *model = CylinderModel::kBox;
    } else if (name == "tighter") {
      *model = CylinderModel::kTighter;
    } else if (name != "capsule") {
      Where{scene_path, key}.Fail(scene[key],
                                  "expected capsule, box or tighter, got" + Quoted(name));
    }
  };
  read_cylinder_model("cylinder_model", &options.cylinder_model);
  read_cylinder_model("urdf_cylinder_model", &options.urdf_cylinder_model);
  std::string fit = "capsule";
  const Where fit_where{scene_path, "mesh_fit"};
  yaml_fields::ReadIfPresent(scene, "mesh_fit", Where{scene_path, ""}, yaml_fields::ReadName, &fit);
  const std::string chain = "capsules:";
  if (fit == "box") {
    options.mesh_fit.kind = MeshFitKind::kOrientedBox;
  } else if (fit == "tighter") {
    options.mesh_fit.kind = MeshFitKind::kTighter;
  } else if (fit.compare(0, chain.size(), chain) == 0) {
    options.mesh_fit.kind = MeshFitKind::kCapsuleChain;
    const std::string count = fit.substr(chain.size());
    const bool is_digits = !count.empty() && count.size() <= 3 &&
                           std::all_of(count.begin(), count.end(), ::isdigit);
    options.mesh_fit.capsule_count = is_digits ? std::stoi(count) : 0;
    if (options.mesh_fit.capsule_count < 1 ||
        options.mesh_fit.capsule_count > kMeshFitMaxCapsules) {
      fit_where.Fail(scene["mesh_fit"], "capsules:K needs K in [1, " +
                                            std::to_string(kMeshFitMaxCapsules) + "], got" +
                                            Quoted(fit));
    }
  } else if (fit != "capsule") {
    fit_where.Fail(scene["mesh_fit"], "expected capsule, capsules:K, box or tighter, got" +
                                     Quoted(fit));
  }
  return options;
}

Aabb ReadWorld(const YAML::Node& node, const Where& where) {
  yaml_fields::RequireMap(node, where);
  yaml_fields::CheckKeys(node, {"center_m", "edge_m"}, where);
  const Eigen::Vector3d center_W =
      yaml_fields::ReadVector3(node["center_m"], where.Child("center_m"));
  const double edge_m = yaml_fields::ReadPositiveDouble(node["edge_m"], where.Child("edge_m"));
  if (edge_m > kMaxWorldEdge_m) {
    where.Child("edge_m").Fail(
        node["edge_m"], "expected at most " +
                            std::to_string(static_cast<long long>(kMaxWorldEdge_m)) +
                            " m (the monitor's distance bounds keep 1e-9 of the edge in hand "
                            "against rounding), got " + node["edge_m"].Scalar());
  }
  return Aabb::Cube(center_W, edge_m);
}

std::vector<ArmSpec> ReadArms(const YAML::Node& node, const Where& where,
                              const KinematicModel& model, double default_tolerance_m,
                              std::vector<int>* arm_of_link) {
  arm_of_link->assign(model.link_count(), -1);
  std::vector<ArmSpec> arms;
  if (!node.IsDefined()) return arms;
  yaml_fields::RequireSequence(node, where);
  std::vector<int> root_of_arm;
  for (std::size_t i = 0; i < node.size(); ++i) {
    Where item = where.Entry(i);
    const YAML::Node& entry = node[i];
    yaml_fields::RequireMap(entry, item);
    yaml_fields::CheckKeys(entry, {"name", "root_link", "tolerance_m"}, item);
    ArmSpec arm;
    arm.name = yaml_fields::ReadName(entry["name"], item.Child("name"));
    item.element += Quoted(arm.name);
    arm.root_link = yaml_fields::ReadName(entry["root_link"], item.Child("root_link"));
    arm.tolerance_m = default_tolerance_m;
    yaml_fields::ReadIfPresent(entry, "tolerance_m", item, yaml_fields::ReadNonNegativeDouble,
                               &arm.tolerance_m);
    for (const ArmSpec& other : arms) {
      if (other.name == arm.name) item.Fail(entry["name"], "duplicate arm name" + Quoted(arm.name));
    }
    const int root = model.FindLink(arm.root_link);
    if (root < 0) {
      item.Fail(entry["root_link"],
                "unknown link" + Quoted(arm.root_link) + " (expected a link of the URDF)");
    }
    root_of_arm.push_back(root);
    arms.push_back(arm);
  }
  for (int link = 0; link < model.link_count(); ++link) {
    for (int a = 0; a < static_cast<int>(arms.size()); ++a) {
      bool below = false;
      for (int l = link; l >= 0 && !below; l = model.parent_link(l)) below = l == root_of_arm[a];
      if (!below) continue;
      if ((*arm_of_link)[link] >= 0) {
        where.Fail(node, "arms" + Quoted(arms[(*arm_of_link)[link]].name) + " and" +
                             Quoted(arms[a].name) + " both contain link" +
                             Quoted(model.link_name(link)) + " (expected disjoint subtrees)");
      }
      (*arm_of_link)[link] = a;
    }
  }
  return arms;
}

std::vector<LinkOverride> ReadLinkOverrides(const YAML::Node& node, const Where& where,
                                            const KinematicModel& model) {
  std::vector<LinkOverride> overrides(model.link_count());
  if (!node.IsDefined()) return overrides;
  yaml_fields::RequireMap(node, where);
  yaml_fields::RequireUniqueKeys(node, where);
  for (const auto& entry : node) {
    const std::string link_name = entry.first.as<std::string>("");
    const Where item = where.Child(link_name);
    const int link = model.FindLink(link_name);
    if (link < 0) item.Fail(entry.first, "unknown link (expected a link of the URDF)");
    const YAML::Node& value = entry.second;
    yaml_fields::RequireMap(value, item);
    yaml_fields::CheckKeys(value, {"ignore", "radius_m", "p0_m", "p1_m", "tolerance_m"}, item);
    LinkOverride& o = overrides[link];
    yaml_fields::ReadIfPresent(value, "ignore", item, yaml_fields::ReadBool, &o.ignore);
    yaml_fields::ReadIfPresent(value, "radius_m", item, yaml_fields::ReadNonNegativeDouble,
                               &o.radius_m);
    yaml_fields::ReadIfPresent(value, "p0_m", item, yaml_fields::ReadVector3, &o.p0_L);
    yaml_fields::ReadIfPresent(value, "p1_m", item, yaml_fields::ReadVector3, &o.p1_L);
    if (o.p0_L.has_value() != o.p1_L.has_value()) {
      item.Fail(value, "p0_m and p1_m must be given together (the capsule's endpoints)");
    }
    yaml_fields::ReadIfPresent(value, "tolerance_m", item, yaml_fields::ReadNonNegativeDouble,
                               &o.tolerance_m);
  }
  return overrides;
}

std::vector<PrimitiveSpec> MakeLinkPrimitives(const urdf::ModelInterface& urdf_model,
                                              const Workcell& workcell, const LinkSettings& links,
                                              CylinderModel cylinder_model, MeshFitter* meshes,
                                              NameRegistry* names,
                                              std::vector<std::string>* warnings) {
  const KinematicModel& model = workcell.kinematics;
  for (int link = 0; link < model.link_count(); ++link) {
    names->Claim(model.link_name(link),
                 workcell.urdf_path + ": link" + Quoted(model.link_name(link)));
  }
  std::vector<PrimitiveSpec> primitives;
  for (int link = 0; link < model.link_count(); ++link) {
    const std::string& link_name = model.link_name(link);
    const urdf::LinkConstSharedPtr urdf_link = urdf_model.getLink(link_name);
    const auto shapes =
        LinkShapes(*urdf_link, links.overrides[link], workcell.urdf_path, workcell.scene_path,
                   cylinder_model, meshes, warnings);
    for (const auto& [suffix, shape_L] : shapes) {
      PrimitiveSpec p = NewLinkPrimitive(link, workcell, links);
      p.name = shapes.size() == 1 ? link_name : link_name + "/" + suffix;
      p.shape_L = shape_L;
      if (p.name != link_name)
        names->Claim(p.name, workcell.urdf_path + ": link" + Quoted(link_name));
      primitives.push_back(p);
    }
  }
  return primitives;
}

void AppendObject(ObjectSpec object, const std::vector<Shape>& shapes_W, double tolerance_m,
                  const std::string& origin, NameRegistry* names, Workcell* workcell) {
  object.primitive = static_cast<PrimitiveId>(workcell->primitives.size());
  object.primitive_count = static_cast<int>(shapes_W.size());
  for (std::size_t k = 0; k < shapes_W.size(); ++k) {
    PrimitiveSpec p;
    p.name = shapes_W.size() == 1 ? object.name : object.name + "/" + std::to_string(k);
    if (p.name != object.name) names->Claim(p.name, origin);
    p.owner = object.name;
    p.shape_L = shapes_W[k];
    p.tolerance_m = tolerance_m;
    p.is_static = !object.is_attachable && object.frame.empty();
    p.object_index = static_cast<int>(workcell->objects.size());
    if (!workcell->world_W.Contains(ComputeAabb(p.shape_L))) {
      throw LoadError(origin + ": shape " + std::to_string(k) +
                      " is not inside the world cube (expected it within world:)");
    }
    workcell->primitives.push_back(p);
  }
  workcell->objects.push_back(object);
}

void ReadObjects(const YAML::Node& node, const Where& where, const ShapeOptions& options,
                 MeshFitter* meshes, NameRegistry* names, Workcell* workcell) {
  if (!node.IsDefined()) return;
  yaml_fields::RequireSequence(node, where);
  for (std::size_t i = 0; i < node.size(); ++i) {
    ReadObject(node[i], where.Entry(i), options, meshes, names, workcell);
  }
}

void ReadVariants(const YAML::Node& node, const Where& where, const LinkSettings& links,
                  NameRegistry* names, Workcell* workcell) {
  if (!node.IsDefined()) return;
  yaml_fields::RequireSequence(node, where);
  for (std::size_t i = 0; i < node.size(); ++i) {
    ReadVariant(node[i], where.Entry(i), links, names, workcell);
  }
}

std::vector<std::pair<PrimitiveId, PrimitiveId>> ReadCompatiblePairs(const YAML::Node& node,
                                                                     const Where& where,
                                                                     const Workcell& workcell) {
  std::vector<std::pair<PrimitiveId, PrimitiveId>> pairs;
  if (!node.IsDefined()) return pairs;
  yaml_fields::RequireSequence(node, where);
  for (std::size_t i = 0; i < node.size(); ++i) {
    const Where item = where.Entry(i);
    const YAML::Node& pair = node[i];
    if (!pair.IsSequence() || pair.size() != 2) {
      item.Fail(pair, "expected a pair [a, b] of link, object or primitive names");
    }
    std::vector<PrimitiveId> sides[2];
    for (int s = 0; s < 2; ++s) {
      const std::string name = yaml_fields::ReadName(pair[s], item);
      sides[s] = ResolveNames(workcell, name);
      if (sides[s].empty()) {
        item.Fail(pair[s], "unknown name" + Quoted(name) +
                               " (expected a link with primitives, an object or a primitive)");
      }
    }
    for (PrimitiveId a : sides[0]) {
      for (PrimitiveId b : sides[1]) {
        if (a != b) pairs.emplace_back(a, b);
      }
    }
  }
  return pairs;
}

std::vector<GraspTargetSpec> ReadGraspTargets(const YAML::Node& node, const Where& where,
                                              const Workcell& workcell) {
  std::vector<GraspTargetSpec> targets;
  if (!node.IsDefined()) return targets;
  yaml_fields::RequireSequence(node, where);
  for (std::size_t i = 0; i < node.size(); ++i) {
    const YAML::Node& entry = node[i];
    const Where item = where.Entry(i);
    yaml_fields::RequireMap(entry, item);
    yaml_fields::CheckKeys(entry, {"link", "object"}, item);
    GraspTargetSpec target;
    target.link = yaml_fields::ReadName(entry["link"], item.Child("link"));
    target.link_index = workcell.kinematics.FindLink(target.link);
    if (target.link_index < 0) {
      item.Fail(entry["link"], "unknown link" + Quoted(target.link) + " (expected a URDF link)");
    }
    target.object = yaml_fields::ReadName(entry["object"], item.Child("object"));
    target.object_index = workcell.FindObject(target.object);
    if (target.object_index < 0) {
      item.Fail(entry["object"],
                "unknown object" + Quoted(target.object) + " (expected a name from objects:)");
    }
    for (const GraspTargetSpec& other : targets) {
      if (other.link == target.link && other.object == target.object) {
        item.Fail(entry, "duplicate grasp target");
      }
    }
    targets.push_back(target);
  }
  return targets;
}

}  // namespace scene_sections
}  // namespace arm_collision_monitor
