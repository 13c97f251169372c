// The workcell's own checks and look-ups (LoadWorkcell, in workcell_loader.cpp, builds it).
#include "arm_collision_monitor/scene/workcell.h"

#include <cmath>
#include <set>

namespace arm_collision_monitor {

bool Workcell::Validate(std::string* why) const {
  if (!kinematics.Validate(why)) return false;
  auto fail = [&](const std::string& what) {
    *why = what;
    return false;
  };
  if (joint_names != kinematics.ActuatedJointNames()) return fail("joint_names != kinematics");
  for (const auto& [q_index, position] : joint_defaults) {
    if (q_index < 0 || q_index >= kinematics.q_size() || !std::isfinite(position)) {
      return fail("joint default (" + std::to_string(q_index) + ", " + std::to_string(position) +
                  ") out of range");
    }
  }
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
    const ObjectSpec* object = p.object_index >= 0 ? &objects[p.object_index] : nullptr;
    if (object && (i < object->primitive || object->primitive_count < 1 ||
                   i - object->primitive >= static_cast<std::size_t>(object->primitive_count))) {
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

}  // namespace arm_collision_monitor
