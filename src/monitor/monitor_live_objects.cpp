// Live objects: added, moved and removed at run time (Monitor::AddObject, MoveObject,
// RemoveObject). Their room is preallocated: MonitorModel::WithLiveSlots appends capacity slots
// of max_primitives_per_object placeholder primitives to the workcell, so every per-primitive
// structure (index entries, compatibility rows, kept pairs, the report) is sized for them at
// start-up, and a slot's primitives only enter the index (is_present) while an object uses it.
#include <algorithm>
#include <cmath>
#include <sstream>

#include "arm_collision_monitor/core/constants.h"
#include "monitor_impl.h"

namespace arm_collision_monitor {

bool IsRigidPose(const Eigen::Isometry3d& X) {
  if (!X.matrix().allFinite()) return false;
  const Eigen::Matrix3d R = X.linear();
  const double error = (R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  return error <= kLiveObjectRotationTolerance && R.determinant() > 0.0;
}

namespace {

// Why `shape` cannot be a primitive, or nullptr: sizes as Workcell::Validate wants them.
const char* ShapeFault(const Shape& shape) {
  if (const auto* capsule = std::get_if<Capsule>(&shape)) {
    if (!capsule->p0_W.allFinite() || !capsule->p1_W.allFinite()) return "end not finite";
    if (!std::isfinite(capsule->radius_m) || capsule->radius_m < 0.0) {
      return "radius not a finite number >= 0";
    }
    return nullptr;
  }
  const Box& box = std::get<Box>(shape);
  if (!IsRigidPose(box.X_WB)) return "box pose not finite or not a rotation";
  if (!box.half_extents_m.allFinite() || (box.half_extents_m.array() <= 0.0).any()) {
    return "box half extents not finite numbers > 0";
  }
  return nullptr;
}

std::string LiveSlotName(std::uint32_t slot) { return "~live" + std::to_string(slot); }

}  // namespace

// --- the model: the slots --------------------------------------------------------------------

std::shared_ptr<const Workcell> MonitorModel::WithLiveSlots(std::shared_ptr<const Workcell> wc,
                                                            const LiveObjectOptions& live) {
  if (live.capacity > kLiveObjectMaxCapacity || live.max_primitives_per_object < 1 ||
      live.max_primitives_per_object > kLiveObjectMaxPrimitives) {
    throw LoadError("monitor options: live_objects needs capacity in [0, " +
                    std::to_string(kLiveObjectMaxCapacity) +
                    "] and max_primitives_per_object in [1, " +
                    std::to_string(kLiveObjectMaxPrimitives) + "]");
  }
  if (!wc || live.capacity == 0) return wc;
  auto out = std::make_shared<Workcell>(*wc);
  const auto n0 = static_cast<std::uint32_t>(wc->primitives.size());
  const std::uint32_t k_max = live.max_primitives_per_object;
  const Eigen::Vector3d p_W_centre = 0.5 * (wc->world_W.min_W + wc->world_W.max_W);
  for (std::uint32_t slot = 0; slot < live.capacity; ++slot) {
    ObjectSpec object;
    object.name = LiveSlotName(slot);
    object.primitive = n0 + slot * k_max;
    object.primitive_count = static_cast<int>(k_max);
    for (std::uint32_t k = 0; k < k_max; ++k) {
      PrimitiveSpec p;
      p.name = object.name + "/" + std::to_string(k);
      p.owner = object.name;
      p.shape_L = Capsule{p_W_centre, p_W_centre, 0.0};
      p.object_index = static_cast<int>(out->objects.size());
      out->primitives.push_back(p);
    }
    out->objects.push_back(object);
  }
  // The start-up pairs carried over; a slot is excused with nothing (AddObject excuses an
  // object's own primitives with each other while it exists).
  CompatibilityMatrix compatible(static_cast<std::uint32_t>(out->primitives.size()));
  for (std::uint32_t a = 0; a < n0; ++a) {
    for (std::uint32_t b = a + 1; b < n0; ++b) {
      if (wc->compatible.AreCompatible(a, b)) compatible.Set(a, b, true);
    }
  }
  out->compatible = std::move(compatible);
  return out;
}

// --- the data --------------------------------------------------------------------------------

void Monitor::Impl::InitLiveObjects() {
  const std::uint32_t n = model.primitive_count;
  const std::uint32_t first = model.first_live_primitive;
  const std::uint32_t slots = model.options.live_objects.capacity;
  is_present.assign(n, 1);
  std::fill(is_present.begin() + first, is_present.end(), 0);
  live.name.assign(slots, std::string());
  live.is_attachable.assign(slots, 0);
  live.shape_count.assign(slots, 0);
  live.spec.assign(model.workcell->primitives.begin() + first, model.workcell->primitives.end());
  live.shape_O.assign(n - first, Shape{});
  live.count = 0;
  live_end = first;
}

int Monitor::Impl::FindObject(const std::string& name) const {
  const int o = model.workcell->FindObject(name);
  if (o >= 0 && o < model.first_live_object) return o;  // not a slot's placeholder name
  if (name.empty()) return -1;
  const auto it = std::find(live.name.begin(), live.name.end(), name);
  return it == live.name.end() ? -1
                               : model.first_live_object + static_cast<int>(it - live.name.begin());
}

void Monitor::Impl::MarkAllStaticsReachable() {
  for (PrimitiveId id = 0; id < model.primitive_count; ++id) {
    if (is_reachable[id]) continue;
    is_reachable[id] = 1;
    if (ShouldBeInBroadPhase(id) && !in_broad_phase[id]) AddToBroadPhase(id);
  }
}

// Whether `name` names a link, an object or a primitive (scene file or live) already.
bool Monitor::Impl::IsNameTaken(const std::string& name) const {
  if (model.kinematics->FindLink(name) >= 0 || FindObject(name) >= 0) return true;
  const int p = model.workcell->FindPrimitive(name);
  if (p >= 0 && !model.is_live(static_cast<PrimitiveId>(p))) return true;
  for (PrimitiveId id = model.first_live_primitive; id < model.primitive_count; ++id) {
    if (is_present[id] && Spec(id).name == name) return true;
  }
  return false;
}

void Monitor::Impl::ValidateLiveObjects(std::ostringstream* msg) const {
  const std::uint32_t k_max = model.options.live_objects.max_primitives_per_object;
  std::uint32_t used = 0;
  for (std::size_t slot = 0; slot < live.name.size(); ++slot) {
    used += live.name[slot].empty() ? 0 : 1;
    const PrimitiveId first = model.first_live_primitive + static_cast<PrimitiveId>(slot) * k_max;
    const int count = live.name[slot].empty() ? 0 : live.shape_count[slot];
    for (std::uint32_t k = 0; k < k_max; ++k) {
      const PrimitiveId a = first + k;
      if (static_cast<bool>(is_present[a]) != (static_cast<int>(k) < count)) {
        *msg << "live slot " << slot << ": primitive " << a << " presence is stale";
        return;
      }
      for (std::uint32_t j = k + 1; j < k_max; ++j) {
        if (compatible.AreCompatible(a, first + j) != (static_cast<int>(j) < count)) {
          *msg << "live slot " << slot << ": its own pair (" << a << "," << first + j
               << ") compatibility is stale";
          return;
        }
      }
    }
  }
  if (used != live.count) *msg << "live objects: " << used << " slots used, count " << live.count;
  for (PrimitiveId id = live_end; id < model.primitive_count && msg->tellp() == 0; ++id) {
    if (is_present[id] || carrier[id] >= 0 || moved[id]) {
      *msg << "live slot primitive " << id << " in use past live_end " << live_end;
    }
  }
}

// --- the calls -------------------------------------------------------------------------------

bool Monitor::AddObject(const std::string& name, const std::vector<Shape>& shapes_O,
                        const Eigen::Isometry3d& X_WO, double tolerance_m, bool is_attachable,
                        std::string* error) {
  Impl& m = *impl_;
  const auto fail = [&](const std::string& why) {
    SetError(error, "AddObject '" + name + "': " + why);
    return false;
  };
  const LiveObjectOptions& options = m.model.options.live_objects;
  if (name.empty()) return fail("empty name");
  if (m.live.count >= options.capacity) {
    return fail("no free slot: all " + std::to_string(options.capacity) +
                " live objects are in use (monitor options live_objects: capacity)");
  }
  if (shapes_O.empty() || shapes_O.size() > options.max_primitives_per_object) {
    return fail(std::to_string(shapes_O.size()) + " primitives, expected 1 to " +
                std::to_string(options.max_primitives_per_object) +
                " (monitor options live_objects: max_primitives_per_object)");
  }
  if (!std::isfinite(tolerance_m) || tolerance_m < 0.0) {
    return fail("tolerance_m must be a finite number >= 0");
  }
  if (!IsRigidPose(X_WO)) return fail("pose not finite or its rotation not orthonormal");
  const std::size_t count = shapes_O.size();
  for (std::size_t k = 0; k <= count; ++k) {
    // The object's name, then its primitives' when it has several.
    if (k > 0 && count == 1) break;
    const std::string taken = k == 0 ? name : name + "/" + std::to_string(k - 1);
    if (m.IsNameTaken(taken)) {
      return fail("the name '" + taken + "' is already used by a link, object or primitive");
    }
  }
  for (std::size_t k = 0; k < count; ++k) {
    if (const char* fault = ShapeFault(shapes_O[k])) {
      return fail("primitive " + std::to_string(k) + ": " + fault);
    }
    if (!m.model.workcell->world_W.Contains(ComputeAabb(TransformShape(X_WO, shapes_O[k])))) {
      return fail("primitive " + std::to_string(k) + " is not inside the world cube");
    }
  }
  // Accepted: the first free slot.
  const auto slot = static_cast<std::uint32_t>(
      std::find(m.live.name.begin(), m.live.name.end(), std::string()) - m.live.name.begin());
  const std::uint32_t k_max = options.max_primitives_per_object;
  const PrimitiveId first = m.model.first_live_primitive + slot * k_max;
  m.live.name[slot] = name;
  m.live.is_attachable[slot] = is_attachable ? 1 : 0;
  m.live.shape_count[slot] = static_cast<int>(count);
  for (std::size_t k = 0; k < count; ++k) {
    const PrimitiveId id = first + static_cast<PrimitiveId>(k);
    const std::uint32_t s = id - m.model.first_live_primitive;
    PrimitiveSpec& spec = m.live.spec[s];
    spec.name = count == 1 ? name : name + "/" + std::to_string(k);
    spec.owner = name;
    spec.tolerance_m = tolerance_m;
    spec.is_static = !is_attachable;
    m.live.shape_O[s] = shapes_O[k];
    m.shape_W[id] = TransformShape(X_WO, shapes_O[k]);
    m.shape_prev_W[id] = m.shape_W[id];
    m.shape_C[id] = m.shape_W[id];
    m.carrier[id] = -1;
    m.tol_base[id] = tolerance_m;
    m.tol_now[id] = tolerance_m;
    m.is_moving[id] = 0;  // resting, like a scene object: never tested against other statics
    m.is_reachable[id] = 1;
    m.is_present[id] = 1;
    m.moved[id] = 0;
    m.SetCarrierBounds(id);
    m.AddToBroadPhase(id);
    // Its own primitives (a mesh's capsules overlap) never warn against each other when held.
    for (PrimitiveId other = first; other < id; ++other) m.compatible.Set(other, id, true);
  }
  m.PrepareBounds();
  ++m.live.count;
  m.live_end = std::max(m.live_end, first + k_max);
  m.scene_changed = true;
  return true;
}

bool Monitor::MoveObject(const std::string& name, const Eigen::Isometry3d& X_WO,
                         std::string* error) {
  Impl& m = *impl_;
  const auto fail = [&](const std::string& why) {
    SetError(error, "MoveObject '" + name + "': " + why);
    return false;
  };
  const int o = m.FindObject(name);
  if (o < 0) return fail("unknown object");
  const int slot = m.model.LiveSlot(o);
  if (slot < 0) {
    return fail("an object of the scene file, not a live one (frame-bound ones follow TF)");
  }
  if (m.holder[o] >= 0) {
    return fail("held by link '" + m.model.kinematics->link_name(m.holder[o]) + "'");
  }
  if (!IsRigidPose(X_WO)) return fail("pose not finite or its rotation not orthonormal");
  const std::uint32_t k_max = m.model.options.live_objects.max_primitives_per_object;
  const std::uint32_t first_s = static_cast<std::uint32_t>(slot) * k_max;
  const int count = m.live.shape_count[slot];
  for (int k = 0; k < count; ++k) {
    const Shape& shape_O = m.live.shape_O[first_s + k];
    if (!m.model.workcell->world_W.Contains(ComputeAabb(TransformShape(X_WO, shape_O)))) {
      return fail("primitive " + std::to_string(k) + " would leave the world cube");
    }
  }
  for (int k = 0; k < count; ++k) {
    const PrimitiveId id = m.model.first_live_primitive + first_s + k;
    m.shape_W[id] = TransformShape(X_WO, m.live.shape_O[first_s + k]);
    m.shape_prev_W[id] = m.shape_W[id];
    m.shape_C[id] = m.shape_W[id];
    m.Reindex(id, false);
  }
  m.scene_changed = true;
  return true;
}

bool Monitor::RemoveObject(const std::string& name, std::string* error) {
  Impl& m = *impl_;
  const int o = m.FindObject(name);
  if (o < 0) {
    SetError(error, "RemoveObject '" + name + "': unknown object");
    return false;
  }
  const int slot = m.model.LiveSlot(o);
  if (slot < 0) {
    SetError(error, "RemoveObject '" + name + "': an object of the scene file, not a live one");
    return false;
  }
  if (m.holder[o] >= 0 && !Detach(name, error)) return false;
  // Its grasp targets go with it: the slot's next object is excused with no link.
  const std::size_t object_count = m.model.objects.size();
  for (int link = 0; link < m.model.kinematics->link_count(); ++link) {
    std::uint8_t& is_target = m.grasp[static_cast<std::size_t>(link) * object_count + o];
    if (!is_target) continue;
    is_target = 0;
    m.RefreshCompatibility(link, o);
  }
  const std::uint32_t k_max = m.model.options.live_objects.max_primitives_per_object;
  const std::uint32_t first_s = static_cast<std::uint32_t>(slot) * k_max;
  const int count = m.live.shape_count[slot];
  for (int k = 0; k < count; ++k) {
    const std::uint32_t s = first_s + k;
    const PrimitiveId id = m.model.first_live_primitive + s;
    if (m.in_broad_phase[id]) m.RemoveFromBroadPhase(id);
    m.is_present[id] = 0;
    m.moved[id] = 0;
    for (int j = 0; j < k; ++j) m.compatible.Set(id - k + j, id, false);
    m.live.spec[s] = m.model.workcell->primitives[id];  // the placeholder again
  }
  m.live.name[slot].clear();
  m.live.shape_count[slot] = 0;
  m.live.is_attachable[slot] = 0;
  --m.live.count;
  while (m.live_end > m.model.first_live_primitive &&
         m.live.name[(m.live_end - 1 - m.model.first_live_primitive) / k_max].empty()) {
    m.live_end -= k_max;
  }
  m.cache.MarkStale();
  m.scene_changed = true;
  return true;
}

std::uint32_t Monitor::live_object_count() const { return impl_->live.count; }

}  // namespace arm_collision_monitor
