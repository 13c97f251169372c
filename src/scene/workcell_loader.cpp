// LoadWorkcell: the URDF's kinematics and collision geometry plus the scene file, validated
// once at start-up (the scene format is described at the top of config/scene.yaml).
#include <urdf_model/model.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <random>
#include <set>

#include "arm_collision_monitor/core/constants.h"
#include "arm_collision_monitor/geometry/distance.h"
#include "arm_collision_monitor/kinematics/urdf_conversions.h"
#include "arm_collision_monitor/scene/workcell.h"
#include "urdf_collision.h"
#include "arm_collision_monitor/scene/yaml_fields.h"

namespace arm_collision_monitor {
namespace {

using yaml_fields::Where;

struct LinkOverride {
  bool ignore = false;
  std::optional<double> radius_m;
  std::optional<Eigen::Vector3d> p0_L;
  std::optional<Eigen::Vector3d> p1_L;
  std::optional<double> tolerance_m;
};

std::string Quoted(const std::string& name) { return " '" + name + "'"; }

// ----- scene sections -----------------------------------------------------------------------

Aabb ReadWorld(const YAML::Node& node, const Where& where) {
  if (!node.IsDefined()) where.Fail(node, "missing; expected {center_m: [x, y, z], edge_m: e}");
  yaml_fields::RequireMap(node, where);
  yaml_fields::CheckKeys(node, {"center_m", "edge_m"}, where);
  const Eigen::Vector3d center_W =
      yaml_fields::ReadVector3(node["center_m"], where.Child("center_m"));
  const double edge_m = yaml_fields::ReadPositiveDouble(node["edge_m"], where.Child("edge_m"));
  return Aabb{(center_W.array() - 0.5 * edge_m).matrix(),
              (center_W.array() + 0.5 * edge_m).matrix()};
}

// The arm each link belongs to (-1: environment). Links are in topological order.
std::vector<int> ReadArms(const YAML::Node& node, const Where& where, const KinematicModel& model,
                          double default_tolerance_m, std::vector<ArmSpec>* arms) {
  std::vector<int> arm_of_link(model.link_count(), -1);
  if (!node.IsDefined()) return arm_of_link;
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
    for (const ArmSpec& other : *arms) {
      if (other.name == arm.name) item.Fail(entry["name"], "duplicate arm name" + Quoted(arm.name));
    }
    const int root = model.FindLink(arm.root_link);
    if (root < 0) {
      item.Fail(entry["root_link"],
                "unknown link" + Quoted(arm.root_link) + " (expected a link of the URDF)");
    }
    root_of_arm.push_back(root);
    arms->push_back(arm);
  }
  for (int link = 0; link < model.link_count(); ++link) {
    for (int a = 0; a < static_cast<int>(arms->size()); ++a) {
      bool below = false;
      for (int l = link; l >= 0 && !below; l = model.parent_link(l)) below = l == root_of_arm[a];
      if (!below) continue;
      if (arm_of_link[link] >= 0) {
        where.Fail(node, "arms" + Quoted((*arms)[arm_of_link[link]].name) + " and" +
                             Quoted((*arms)[a].name) + " both contain link" +
                             Quoted(model.link_name(link)) + " (expected disjoint subtrees)");
      }
      arm_of_link[link] = a;
    }
  }
  return arm_of_link;
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

// Soft limits: each must lie within the URDF's limits of an actuated joint.
void ReadJointLimits(const YAML::Node& node, const Where& where, KinematicModel* model) {
  if (!node.IsDefined()) return;
  yaml_fields::RequireMap(node, where);
  yaml_fields::RequireUniqueKeys(node, where);
  for (const auto& entry : node) {
    const std::string joint_name = entry.first.as<std::string>("");
    const Where item = where.Child(joint_name);
    const int link = model->FindJointChildLink(joint_name);
    if (link < 0 || model->joint(link).q_index < 0) {
      item.Fail(entry.first, "unknown joint (expected an actuated joint of the URDF)");
    }
    yaml_fields::RequireMap(entry.second, item);
    yaml_fields::CheckKeys(entry.second, {"lower", "upper"}, item);
    const JointSpec& joint = model->joint(link);
    double lower = joint.lower;
    double upper = joint.upper;
    yaml_fields::ReadIfPresent(entry.second, "lower", item, yaml_fields::ReadFiniteDouble, &lower);
    yaml_fields::ReadIfPresent(entry.second, "upper", item, yaml_fields::ReadFiniteDouble, &upper);
    if (!(joint.lower <= lower && lower <= upper && upper <= joint.upper)) {
      item.Fail(entry.second, "expected URDF lower (" + std::to_string(joint.lower) +
                                  ") <= lower <= upper <= URDF upper (" +
                                  std::to_string(joint.upper) + ")");
    }
    model->SetPositionLimits(joint_name, lower, upper);
  }
}

// The link's primitives in L after the scene's override.
std::vector<std::pair<std::string, Shape>> LinkShapes(const urdf::Link& link, const LinkOverride& o,
                                                      const std::string& urdf_path,
                                                      const std::string& scene_path) {
  if (o.ignore) return {};
  const UrdfLinkGeometry geometry = ReadUrdfLinkGeometry(link, urdf_path);
  const std::string override_hint =
      scene_path + " links:" + Quoted(link.name) + " {p0_m, p1_m, radius_m} or {ignore: true}";
  if (o.p0_L) {
    double radius_m = 0.0;
    if (o.radius_m) {
      radius_m = *o.radius_m;
    } else if (geometry.capsule_count() == 1 && geometry.shapes_L.size() == 1 &&
               geometry.mesh_filename.empty()) {
      radius_m = std::get<Capsule>(geometry.shapes_L[0].second).radius_m;
    } else {
      throw LoadError(scene_path + ": links." + link.name +
                      ": radius_m is required with p0_m/p1_m (the URDF link has no single "
                      "capsule to take it from)");
    }
    return {{"0", Capsule{*o.p0_L, *o.p1_L, radius_m}}};
  }
  if (!geometry.mesh_filename.empty()) {
    throw LoadError(urdf_path + ": link" + Quoted(link.name) + ": <collision> <mesh filename='" +
                    geometry.mesh_filename +
                    "'> has no primitive (expected box, cylinder or sphere); model the link in " +
                    override_hint);
  }
  auto shapes = geometry.shapes_L;
  if (o.radius_m) {
    if (geometry.capsule_count() == 0) {
      throw LoadError(scene_path + ": links." + link.name +
                      ": radius_m given but the link has no capsule (cylinder or sphere)");
    }
    for (auto& named : shapes) {
      if (auto* capsule = std::get_if<Capsule>(&named.second)) capsule->radius_m = *o.radius_m;
    }
  }
  return shapes;
}

// ----- compatibility ------------------------------------------------------------------------

// Rigid bodies: links joined by fixed joints, except that a root link without geometry (a
// "world" frame) does not merge what is fixed to it (both pedestals are fixed to the world, yet
// they are separate parts). Returns the body of each link and the parent body of each body.
void ComputeRigidBodies(const KinematicModel& model, bool root_is_frame,
                        std::vector<int>* body_of_link, std::vector<int>* parent_body) {
  body_of_link->assign(model.link_count(), 0);
  parent_body->assign(1, -1);
  for (int link = 1; link < model.link_count(); ++link) {
    const int parent = model.parent_link(link);
    const bool merges = model.joint(link).type == JointType::kFixed &&
                        model.joint(link).mimic_q_index < 0 && !(parent == 0 && root_is_frame);
    if (merges) {
      (*body_of_link)[link] = (*body_of_link)[parent];
    } else {
      (*body_of_link)[link] = static_cast<int>(parent_body->size());
      parent_body->push_back((*body_of_link)[parent]);
    }
  }
}

std::vector<PrimitiveId> ResolveNames(const Workcell& w, const KinematicModel& model,
                                      const std::string& name) {
  std::vector<PrimitiveId> ids;
  const int link = model.FindLink(name);
  for (PrimitiveId id = 0; id < w.primitives.size(); ++id) {
    const PrimitiveSpec& p = w.primitives[id];
    if ((link >= 0 && p.link_index == link) || (link < 0 && (p.owner == name || p.name == name))) {
      ids.push_back(id);
    }
  }
  return ids;
}

// Start-up findings from sampled configurations: primitives outside the world cube in the home
// pose, and pairs within their tolerances in the home pose and in every sampled configuration.
void CheckSampledConfigurations(Workcell* w) {
  const KinematicModel& model = w->kinematics;
  const std::size_t n = w->primitives.size();
  std::vector<std::pair<PrimitiveId, PrimitiveId>> candidates;
  for (PrimitiveId a = 0; a < n; ++a) {
    for (PrimitiveId b = a + 1; b < n; ++b) {
      const PrimitiveSpec& pa = w->primitives[a];
      const PrimitiveSpec& pb = w->primitives[b];
      if (pa.is_static && pb.is_static) continue;  // never checked by the monitor
      if (w->compatible.AreCompatible(a, b)) continue;
      candidates.emplace_back(a, b);
    }
  }
  std::mt19937_64 rng(kAlwaysOverlappingSeed);
  std::vector<Eigen::Isometry3d> X_WL(model.link_count());
  std::vector<Shape> shapes_W(n);
  Eigen::VectorXd q = Eigen::VectorXd::Zero(model.q_size());
  for (int sample = 0; sample <= kAlwaysOverlappingSamples && (sample == 0 || !candidates.empty());
       ++sample) {
    if (sample > 0) {  // sample 0 is the home pose
      for (int link = 1; link < model.link_count(); ++link) {
        const JointSpec& joint = model.joint(link);
        if (joint.q_index < 0) continue;
        const double lower = std::isfinite(joint.lower) ? joint.lower : -M_PI;
        const double upper = std::isfinite(joint.upper) ? joint.upper : M_PI;
        q[joint.q_index] = std::uniform_real_distribution<double>(lower, upper)(rng);
      }
    }
    model.ComputeLinkPoses(q, &X_WL);
    for (std::size_t i = 0; i < n; ++i) {
      const PrimitiveSpec& p = w->primitives[i];
      shapes_W[i] = p.link_index >= 0 ? TransformShape(X_WL[p.link_index], p.shape_L) : p.shape_L;
      if (sample == 0 && !w->world_W.Contains(ComputeAabb(shapes_W[i]).Inflated(p.tolerance_m))) {
        w->warnings.push_back(w->urdf_path + ", " + w->scene_path + ": '" + p.name +
                              "' with its tolerance is not inside the world cube in the home "
                              "pose (expected world: to enclose the workcell)");
      }
    }
    candidates.erase(std::remove_if(candidates.begin(), candidates.end(),
                                    [&](const auto& pair) {
                                      const double threshold_m =
                                          w->primitives[pair.first].tolerance_m +
                                          w->primitives[pair.second].tolerance_m;
                                      return !IsCloserThan(shapes_W[pair.first],
                                                           shapes_W[pair.second], threshold_m);
                                    }),
                     candidates.end());
  }
  for (const auto& [a, b] : candidates) {
    w->warnings.push_back(
        w->urdf_path + ", " + w->scene_path + ": '" + w->primitives[a].name + "' and '" +
        w->primitives[b].name + "' are within their tolerances in the home pose and in all " +
        std::to_string(kAlwaysOverlappingSamples) + " sampled configurations (seed " +
        std::to_string(kAlwaysOverlappingSeed) +
        "): they would warn in every cycle; if that is by design, list them under compatible:");
  }
}

}  // namespace

Shape TransformShape(const Eigen::Isometry3d& X_WL, const Shape& shape_L) {
  if (const auto* capsule = std::get_if<Capsule>(&shape_L)) {
    return Capsule{X_WL * capsule->p0_W, X_WL * capsule->p1_W, capsule->radius_m};
  }
  const Box& box = std::get<Box>(shape_L);
  return Box{X_WL * box.X_WB, box.half_extents_m};
}

bool Workcell::Validate(std::string* why) const {
  if (!kinematics.Validate(why)) return false;
  auto fail = [&](const std::string& what) {
    *why = what;
    return false;
  };
  if (joint_names != kinematics.ActuatedJointNames()) return fail("joint_names != kinematics");
  if (!((world_W.min_W.array() < world_W.max_W.array()).all())) return fail("empty world cube");
  if (compatible.size() != primitives.size()) return fail("compatibility matrix size");
  std::set<std::string> names;
  for (std::size_t i = 0; i < primitives.size(); ++i) {
    const PrimitiveSpec& p = primitives[i];
    const std::string where = "primitive " + std::to_string(i) + " '" + p.name + "': ";
    if (!names.insert(p.name).second) return fail(where + "duplicate name");
    if (!std::isfinite(p.tolerance_m) || p.tolerance_m < 0.0) return fail(where + "tolerance");
    if ((p.link_index >= 0) == (p.object_index >= 0)) {
      return fail(where + "must belong to exactly one link or object");
    }
    if (p.link_index >= kinematics.link_count() ||
        p.object_index >= static_cast<int>(objects.size())) {
      return fail(where + "owner index out of range");
    }
    const std::string& owner_name =
        p.link_index >= 0 ? kinematics.link_name(p.link_index) : objects[p.object_index].name;
    if (p.owner != owner_name) return fail(where + "owner name does not match its index");
    if (p.object_index >= 0 && objects[p.object_index].primitive != i) {
      return fail(where + "its object does not point back at it");
    }
    if (const auto* capsule = std::get_if<Capsule>(&p.shape_L)) {
      if (!capsule->p0_W.allFinite() || !capsule->p1_W.allFinite() ||
          !std::isfinite(capsule->radius_m) || capsule->radius_m < 0.0) {
        return fail(where + "capsule not finite or negative radius");
      }
    } else {
      const Box& box = std::get<Box>(p.shape_L);
      if (!box.X_WB.matrix().allFinite() || !box.half_extents_m.allFinite() ||
          (box.half_extents_m.array() <= 0.0).any()) {
        return fail(where + "box not finite or not positive");
      }
    }
    if (!p.variant.empty() && FindVariant(p.owner, p.variant) < 0) {
      return fail(where + "unknown variant");
    }
  }
  for (const ModelVariantSpec& v : variants) {
    for (const PrimitiveId id : v.primitives) {
      if (id >= primitives.size() || primitives[id].variant != v.name ||
          primitives[id].link_index != v.link_index) {
        return fail("variant '" + v.link + "/" + v.name + "': primitive list inconsistent");
      }
    }
  }
  for (const GraspTargetSpec& g : grasp_targets) {
    if (g.link_index < 0 || g.link_index >= kinematics.link_count() || g.object_index < 0 ||
        g.object_index >= static_cast<int>(objects.size())) {
      return fail("grasp target '" + g.link + "'/'" + g.object + "': index out of range");
    }
  }
  return true;
}

int Workcell::FindPrimitive(const std::string& name) const {
  for (std::size_t i = 0; i < primitives.size(); ++i) {
    if (primitives[i].name == name) return static_cast<int>(i);
  }
  return -1;
}

int Workcell::FindObject(const std::string& name) const {
  for (std::size_t i = 0; i < objects.size(); ++i) {
    if (objects[i].name == name) return static_cast<int>(i);
  }
  return -1;
}

int Workcell::FindVariant(const std::string& link, const std::string& variant) const {
  for (std::size_t i = 0; i < variants.size(); ++i) {
    if (variants[i].link == link && variants[i].name == variant) return static_cast<int>(i);
  }
  return -1;
}

Workcell LoadWorkcell(const std::string& urdf_path, const std::string& scene_path,
                      double default_arm_tolerance_m) {
  Workcell w;
  w.urdf_path = urdf_path;
  w.scene_path = scene_path;
  w.kinematics = KinematicModel::FromUrdfFile(urdf_path);
  const urdf::ModelInterfaceSharedPtr urdf_model = ParseUrdfFile(urdf_path);
  const KinematicModel& model = w.kinematics;
  w.joint_names = model.ActuatedJointNames();
  w.fixed_frame = model.link_name(0);

  const YAML::Node scene = yaml_fields::LoadMapFile(scene_path);
  const Where top{scene_path, ""};
  yaml_fields::CheckKeys(scene,
                         {"world", "arms", "links", "joint_limits", "objects", "compatible",
                          "grasp_targets", "variants"},
                         top);
  ReadJointLimits(scene["joint_limits"], Where{scene_path, "joint_limits"}, &w.kinematics);
  w.world_W = ReadWorld(scene["world"], Where{scene_path, "world"});
  const std::vector<int> arm_of_link =
      ReadArms(scene["arms"], Where{scene_path, "arms"}, model, default_arm_tolerance_m, &w.arms);
  const std::vector<LinkOverride> overrides =
      ReadLinkOverrides(scene["links"], Where{scene_path, "links"}, model);

  std::map<std::string, std::string> name_origin;  // every name -> where it was declared
  auto claim_name = [&](const std::string& name, const std::string& origin) {
    const auto [it, inserted] = name_origin.emplace(name, origin);
    if (!inserted) {
      throw LoadError(origin + ": duplicate name" + Quoted(name) + " (already used by " +
                      it->second + "; expected unique link, object and primitive names)");
    }
  };
  for (int link = 0; link < model.link_count(); ++link) {
    claim_name(model.link_name(link), urdf_path + ": link" + Quoted(model.link_name(link)));
  }

  // Link primitives, in link order.
  // A moving link outside every arm still gets the default tolerance: a moving primitive
  // without a tolerance zone could pass a static one between two cycles unseen.
  auto link_tolerance_m = [&](int link) {
    if (overrides[link].tolerance_m) return *overrides[link].tolerance_m;
    if (arm_of_link[link] >= 0) return w.arms[arm_of_link[link]].tolerance_m;
    return model.is_moving(link) ? default_arm_tolerance_m : 0.0;
  };
  for (int link = 0; link < model.link_count(); ++link) {
    const std::string& link_name = model.link_name(link);
    const urdf::LinkConstSharedPtr urdf_link = urdf_model->getLink(link_name);
    const auto shapes = LinkShapes(*urdf_link, overrides[link], urdf_path, scene_path);
    for (const auto& [suffix, shape_L] : shapes) {
      PrimitiveSpec p;
      p.name = shapes.size() == 1 ? link_name : link_name + "/" + suffix;
      p.owner = link_name;
      p.link_index = link;
      p.group = arm_of_link[link] >= 0 ? w.arms[arm_of_link[link]].name : "";
      p.shape_L = shape_L;
      p.tolerance_m = link_tolerance_m(link);
      p.is_static = !model.is_moving(link);
      if (p.name != link_name) claim_name(p.name, urdf_path + ": link" + Quoted(link_name));
      w.primitives.push_back(p);
    }
  }

  // Environment objects.
  const YAML::Node objects = scene["objects"];
  if (objects.IsDefined()) {
    const Where where{scene_path, "objects"};
    yaml_fields::RequireSequence(objects, where);
    for (std::size_t i = 0; i < objects.size(); ++i) {
      const YAML::Node& entry = objects[i];
      Where item = where.Entry(i);
      yaml_fields::RequireMap(entry, item);
      yaml_fields::CheckKeys(
          entry, {"name", "size_m", "pose", "tolerance_m", "attachable", "frame"}, item);
      ObjectSpec object;
      object.name = yaml_fields::ReadName(entry["name"], item.Child("name"));
      item.element += Quoted(object.name);
      claim_name(object.name, scene_path + ": " + item.element);
      const Eigen::Vector3d size_m =
          yaml_fields::ReadVector3(entry["size_m"], item.Child("size_m"));
      if ((size_m.array() <= 0.0).any()) {
        item.Fail(entry["size_m"], "size_m must be 3 numbers > 0 (full edge lengths, metres)");
      }
      const YAML::Node pose = entry["pose"];
      const Where pose_where = item.Child("pose");
      if (!pose.IsDefined()) item.Fail(entry, "missing pose: {xyz_m: [x, y, z], rpy: [r, p, y]}");
      yaml_fields::RequireMap(pose, pose_where);
      yaml_fields::CheckKeys(pose, {"xyz_m", "rpy"}, pose_where);
      const Eigen::Vector3d xyz_m =
          yaml_fields::ReadVector3(pose["xyz_m"], pose_where.Child("xyz_m"));
      Eigen::Vector3d rpy = Eigen::Vector3d::Zero();
      yaml_fields::ReadIfPresent(pose, "rpy", pose_where, yaml_fields::ReadVector3, &rpy);
      // URDF convention: fixed-axis roll about x, then pitch about y, then yaw about z.
      object.X_WO_start.linear() = (Eigen::AngleAxisd(rpy.z(), Eigen::Vector3d::UnitZ()) *
                                    Eigen::AngleAxisd(rpy.y(), Eigen::Vector3d::UnitY()) *
                                    Eigen::AngleAxisd(rpy.x(), Eigen::Vector3d::UnitX()))
                                       .toRotationMatrix();
      object.X_WO_start.translation() = xyz_m;
      yaml_fields::ReadIfPresent(entry, "attachable", item, yaml_fields::ReadBool,
                                 &object.is_attachable);
      yaml_fields::ReadIfPresent(entry, "frame", item, yaml_fields::ReadName, &object.frame);
      PrimitiveSpec p;
      p.name = object.name;
      p.owner = object.name;
      p.shape_L = Box{object.X_WO_start, 0.5 * size_m};
      yaml_fields::ReadIfPresent(entry, "tolerance_m", item, yaml_fields::ReadNonNegativeDouble,
                                 &p.tolerance_m);
      p.is_static = !object.is_attachable && object.frame.empty();
      p.object_index = static_cast<int>(w.objects.size());
      if (!w.world_W.Contains(ComputeAabb(p.shape_L))) {
        item.Fail(entry, "the box is not inside the world cube (expected it within world:)");
      }
      object.primitive = static_cast<PrimitiveId>(w.primitives.size());
      w.primitives.push_back(p);
      w.objects.push_back(object);
    }
  }

  // Model variants (their primitives follow all default ones).
  const YAML::Node variants = scene["variants"];
  if (variants.IsDefined()) {
    const Where where{scene_path, "variants"};
    yaml_fields::RequireSequence(variants, where);
    for (std::size_t i = 0; i < variants.size(); ++i) {
      const YAML::Node& entry = variants[i];
      Where item = where.Entry(i);
      yaml_fields::RequireMap(entry, item);
      yaml_fields::CheckKeys(entry, {"link", "name", "capsules"}, item);
      ModelVariantSpec variant;
      variant.link = yaml_fields::ReadName(entry["link"], item.Child("link"));
      variant.link_index = model.FindLink(variant.link);
      if (variant.link_index < 0) {
        item.Fail(entry["link"], "unknown link" + Quoted(variant.link) + " (expected a URDF link)");
      }
      variant.name = yaml_fields::ReadName(entry["name"], item.Child("name"));
      item.element += Quoted(variant.link + "/" + variant.name);
      if (w.FindVariant(variant.link, variant.name) >= 0) {
        item.Fail(entry["name"], "duplicate variant of this link");
      }
      const YAML::Node capsules = entry["capsules"];
      const Where capsules_where = item.Child("capsules");
      yaml_fields::RequireSequence(capsules, capsules_where);
      if (capsules.size() == 0) capsules_where.Fail(capsules, "expected at least one capsule");
      for (std::size_t c = 0; c < capsules.size(); ++c) {
        const YAML::Node& cap = capsules[c];
        const Where cap_where = capsules_where.Entry(c);
        yaml_fields::RequireMap(cap, cap_where);
        yaml_fields::CheckKeys(cap, {"name", "p0_m", "p1_m", "radius_m"}, cap_where);
        PrimitiveSpec p;
        p.name = variant.link + "/" + yaml_fields::ReadName(cap["name"], cap_where.Child("name"));
        claim_name(p.name, scene_path + ": " + cap_where.element);
        p.owner = variant.link;
        p.link_index = variant.link_index;
        p.group = arm_of_link[variant.link_index] >= 0
                      ? w.arms[arm_of_link[variant.link_index]].name
                      : "";
        p.variant = variant.name;
        p.shape_L = Capsule{
            yaml_fields::ReadVector3(cap["p0_m"], cap_where.Child("p0_m")),
            yaml_fields::ReadVector3(cap["p1_m"], cap_where.Child("p1_m")),
            yaml_fields::ReadNonNegativeDouble(cap["radius_m"], cap_where.Child("radius_m"))};
        p.tolerance_m = link_tolerance_m(variant.link_index);
        p.is_static = !model.is_moving(variant.link_index);
        variant.primitives.push_back(static_cast<PrimitiveId>(w.primitives.size()));
        w.primitives.push_back(p);
      }
      w.variants.push_back(variant);
    }
  }

  // Compatibility: automatic pairs, then the scene's.
  w.compatible = CompatibilityMatrix(static_cast<std::uint32_t>(w.primitives.size()));
  bool root_has_geometry = false;
  for (const PrimitiveSpec& p : w.primitives) root_has_geometry |= p.link_index == 0;
  std::vector<int> body_of_link, parent_body;
  ComputeRigidBodies(model, !root_has_geometry, &body_of_link, &parent_body);
  for (PrimitiveId a = 0; a < w.primitives.size(); ++a) {
    for (PrimitiveId b = a + 1; b < w.primitives.size(); ++b) {
      const int la = w.primitives[a].link_index;
      const int lb = w.primitives[b].link_index;
      if (la < 0 || lb < 0) continue;
      const int ba = body_of_link[la];
      const int bb = body_of_link[lb];
      if (ba == bb || parent_body[ba] == bb || parent_body[bb] == ba) w.compatible.Set(a, b, true);
    }
  }
  const YAML::Node compatible = scene["compatible"];
  if (compatible.IsDefined()) {
    const Where where{scene_path, "compatible"};
    yaml_fields::RequireSequence(compatible, where);
    for (std::size_t i = 0; i < compatible.size(); ++i) {
      const Where item = where.Entry(i);
      const YAML::Node& pair = compatible[i];
      if (!pair.IsSequence() || pair.size() != 2) {
        item.Fail(pair, "expected a pair [a, b] of link, object or primitive names");
      }
      std::vector<PrimitiveId> sides[2];
      for (int s = 0; s < 2; ++s) {
        const std::string name = yaml_fields::ReadName(pair[s], item);
        sides[s] = ResolveNames(w, model, name);
        if (sides[s].empty()) {
          item.Fail(pair[s], "unknown name" + Quoted(name) +
                                 " (expected a link with primitives, an object or a primitive)");
        }
      }
      for (PrimitiveId a : sides[0]) {
        for (PrimitiveId b : sides[1]) {
          if (a != b) w.compatible.Set(a, b, true);
        }
      }
    }
  }

  // Grasp targets.
  const YAML::Node grasp_targets = scene["grasp_targets"];
  if (grasp_targets.IsDefined()) {
    const Where where{scene_path, "grasp_targets"};
    yaml_fields::RequireSequence(grasp_targets, where);
    for (std::size_t i = 0; i < grasp_targets.size(); ++i) {
      const YAML::Node& entry = grasp_targets[i];
      const Where item = where.Entry(i);
      yaml_fields::RequireMap(entry, item);
      yaml_fields::CheckKeys(entry, {"link", "object"}, item);
      GraspTargetSpec target;
      target.link = yaml_fields::ReadName(entry["link"], item.Child("link"));
      target.link_index = model.FindLink(target.link);
      if (target.link_index < 0) {
        item.Fail(entry["link"], "unknown link" + Quoted(target.link) + " (expected a URDF link)");
      }
      target.object = yaml_fields::ReadName(entry["object"], item.Child("object"));
      target.object_index = w.FindObject(target.object);
      if (target.object_index < 0) {
        item.Fail(entry["object"],
                  "unknown object" + Quoted(target.object) + " (expected a name from objects:)");
      }
      for (const GraspTargetSpec& other : w.grasp_targets) {
        if (other.link == target.link && other.object == target.object) {
          item.Fail(entry, "duplicate grasp target");
        }
      }
      w.grasp_targets.push_back(target);
    }
  }

  CheckSampledConfigurations(&w);
  return w;
}

}  // namespace arm_collision_monitor
