// LoadWorkcell: the URDF's kinematics and collision geometry plus the scene file, validated
// once at start-up (the scene format is described at the top of config/scene.yaml). The
// sections are read by scene_sections.cpp; the values derived from them (automatic compatible
// pairs, start-up warnings) are computed here, once.
#include <urdf_model/model.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <random>

#include "arm_collision_monitor/core/constants.h"
#include "arm_collision_monitor/geometry/distance.h"
#include "arm_collision_monitor/kinematics/urdf_conversions.h"
#include "arm_collision_monitor/scene/workcell.h"
#include "arm_collision_monitor/scene/workcell_reach.h"
#include "arm_collision_monitor/scene/workcell_shapes.h"
#include "moveit_sections.h"
#include "scene_sections.h"
#include "urdf_collision.h"

namespace arm_collision_monitor {
namespace {

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

// The compatibility matrix: the automatic pairs (primitives of one rigid body: of links joined
// by fixed joints, or of one object; or of a body and its parent body), then the scene's
// `listed` pairs.
CompatibilityMatrix ComputeCompatibility(
    const Workcell& w, const std::vector<std::pair<PrimitiveId, PrimitiveId>>& listed) {
  CompatibilityMatrix compatible(static_cast<std::uint32_t>(w.primitives.size()));
  bool root_has_geometry = false;
  for (const PrimitiveSpec& p : w.primitives) root_has_geometry |= p.link_index == 0;
  std::vector<int> body_of_link, parent_body;
  ComputeRigidBodies(w.kinematics, !root_has_geometry, &body_of_link, &parent_body);
  for (PrimitiveId a = 0; a < w.primitives.size(); ++a) {
    for (PrimitiveId b = a + 1; b < w.primitives.size(); ++b) {
      // An object is one rigid body: its primitives (a mesh's fit, a planning-scene object's
      // shapes) never meet but as they were made.
      const int oa = w.primitives[a].object_index;
      if (oa >= 0 && oa == w.primitives[b].object_index) compatible.Set(a, b, true);
      const int la = w.primitives[a].link_index;
      const int lb = w.primitives[b].link_index;
      if (la < 0 || lb < 0) continue;
      const int ba = body_of_link[la];
      const int bb = body_of_link[lb];
      if (ba == bb || parent_body[ba] == bb || parent_body[bb] == ba) compatible.Set(a, b, true);
    }
  }
  for (const auto& [a, b] : listed) compatible.Set(a, b, true);
  return compatible;
}

// A random configuration within each actuated joint's limits (continuous joints: one turn
// about 0).
void SampleConfiguration(const KinematicModel& model, std::mt19937_64* rng, Eigen::VectorXd* q) {
  for (int link = 1; link < model.link_count(); ++link) {
    const JointSpec& joint = model.joint(link);
    if (joint.q_index < 0) continue;
    const double lower = std::isfinite(joint.lower) ? joint.lower : -M_PI;
    const double upper = std::isfinite(joint.upper) ? joint.upper : M_PI;
    (*q)[joint.q_index] = std::uniform_real_distribution<double>(lower, upper)(*rng);
  }
}

// A name as a YAML flow sequence takes it: plain where that reads back the same, else quoted
// (a planning scene's object ids are free text).
std::string YamlName(const std::string& name) {
  const bool is_plain = !name.empty() && std::all_of(name.begin(), name.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '/' || c == '.' ||
           c == '-';
  });
  // yaml-cpp reads these plain scalars as null.
  const bool is_null = name == "null" || name == "Null" || name == "NULL";
  if (is_plain && !is_null && name != "-") return name;
  std::string quoted = "\"";
  for (const char c : name) {
    if (c == '\n') {
      quoted += "\\n";
    } else if (c == '\t') {
      quoted += "\\t";
    } else if (c == '\r') {
      quoted += "\\r";
    } else {
      if (c == '"' || c == '\\') quoted += '\\';
      quoted += c;
    }
  }
  return quoted + "\"";
}

// The start-up findings of pairs of primitives that touch in the sampled configurations, and the
// compatible: entries that would excuse them: an entry's name stands for what the loader reads
// it as (a link's or object's name for all of its primitives, model variants' too; a
// primitive's own name for it alone), so an entry is shown only where it excuses no pair
// beyond those found in every configuration.
class OverlapReport {
 public:
  OverlapReport(const Workcell& w, const std::string& files) : w_(w), files_(files) {
    for (PrimitiveId id = 0; id < w.primitives.size(); ++id) {
      of_owner_[w.primitives[id].owner].push_back(id);
    }
  }

  // The pairs of one pair of owners: `every` (within in all samples) and `most` (in half or
  // more, up to `most_within`), each pair's first primitive of the first owner.
  void Add(const std::string& owner_a, const std::string& owner_b,
           const std::vector<std::pair<PrimitiveId, PrimitiveId>>& every,
           const std::vector<std::pair<PrimitiveId, PrimitiveId>>& most, int most_within) {
    std::vector<std::pair<PrimitiveId, PrimitiveId>> found = every;  // sorted, for lookups
    std::sort(found.begin(), found.end());
    if (!every.empty() && IsExcusedOnlyAmong(owner_a, owner_b, found)) {
      findings_.push_back(files_ + Named(owner_a, owner_b, every) + kWithin + Every() +
                          "if that is by design, list them under compatible: ([" +
                          YamlName(owner_a) + ", " + YamlName(owner_b) + "])");
    } else if (!every.empty()) {
      // Each pair's own entry where its names excuse no other (a link's or object's name
      // stands for all its primitives), up to kNamedPairs of them in one finding.
      std::string entries;
      std::size_t unnamed = 0;
      for (std::size_t i = 0; i < every.size(); ++i) {
        const std::string& a = w_.primitives[every[i].first].name;
        const std::string& b = w_.primitives[every[i].second].name;
        if (!IsExcusedOnlyAmong(a, b, found)) {
          ++unnamed;
        } else if (i < kNamedPairs) {
          entries += std::string(entries.empty() ? "" : ", ") + "[" + YamlName(a) + ", " +
                     YamlName(b) + "]";
        }
      }
      findings_.push_back(
          files_ + Named(owner_a, owner_b, every) + kWithin + Every() +
          (entries.empty() ? "" : "if that is by design, list them under compatible: (" +
                                      entries + (every.size() > kNamedPairs ? ", ...)" : ")")) +
          (unnamed == 0 ? ""
                        : std::string(entries.empty() ? "" : "; ") + std::to_string(unnamed) +
                              " of them compatible: cannot excuse alone (their names stand "
                              "for a link or object, all of whose primitives an entry would "
                              "excuse, model variants' too): a lower tolerance or another fit "
                              "of their geometry (mesh_fit:, links:) may clear them"));
    }
    if (most.empty()) return;
    // Excusing a pair of links is the SRDF's way; a link and an object stay checked.
    const bool is_link_pair = w_.primitives[most.front().first].object_index < 0 &&
                              w_.primitives[most.front().second].object_index < 0;
    findings_.push_back(
        files_ + Named(owner_a, owner_b, most) + kWithin + (most.size() > 1 ? "up to " : "") +
        std::to_string(most_within) + " of " + std::to_string(kAlwaysOverlappingSamples) +
        Sampled() + " (half or more): they would warn in most cycles; " +
        (is_link_pair ? "if the links come that close by design, list them under "
                        "compatible: (or the SRDF's disable_collisions), else a lower "
                        "tolerance or another fit of their geometry (mesh_fit:, links:) may "
                        "clear them"
                      : "a lower tolerance, another fit of the link's geometry (mesh_fit:, "
                        "links:) or the object placed farther may clear them"));
  }

  const std::vector<std::string>& findings() const { return findings_; }

 private:
  static constexpr const char* kWithin = " are within their tolerances in the home pose and in ";
  static constexpr std::size_t kNamedPairs = 3;

  static std::string Sampled() {
    return " sampled configurations (seed " + std::to_string(kAlwaysOverlappingSeed) + ")";
  }
  static std::string Every() {
    return "all " + std::to_string(kAlwaysOverlappingSamples) + Sampled() +
           ": they would warn in every cycle; ";
  }

  // What the loader reads `name` as: an owner's name, all its primitives; else the primitive.
  std::vector<PrimitiveId> Resolved(const std::string& name) const {
    const auto owner = of_owner_.find(name);
    if (owner != of_owner_.end()) return owner->second;
    const int id = w_.FindPrimitive(name);
    if (id < 0) return {};
    return {static_cast<PrimitiveId>(id)};
  }

  // Whether the entry [a, b] excuses no pair still checked but those of `found` (sorted).
  bool IsExcusedOnlyAmong(const std::string& a, const std::string& b,
                          const std::vector<std::pair<PrimitiveId, PrimitiveId>>& found) const {
    for (const PrimitiveId x : Resolved(a)) {
      for (const PrimitiveId y : Resolved(b)) {
        const bool is_checked = !w_.compatible.AreCompatible(x, y) &&
                                !(w_.primitives[x].is_static && w_.primitives[y].is_static);
        if (is_checked && !std::binary_search(found.begin(), found.end(), std::make_pair(x, y))) {
          return false;
        }
      }
    }
    return true;
  }

  // "'a' and 'b'", or the owners with (some of) their pairs of primitives.
  std::string Named(const std::string& a, const std::string& b,
                    const std::vector<std::pair<PrimitiveId, PrimitiveId>>& members) const {
    std::string text = "'" + a + "' and '" + b + "'";
    const auto& [x, y] = members.front();
    if (members.size() == 1 && w_.primitives[x].name == a && w_.primitives[y].name == b) {
      return text;
    }
    text += " (" + std::to_string(members.size()) + " pair" + (members.size() == 1 ? "" : "s") +
            " of their primitives:";
    for (std::size_t i = 0; i < std::min(members.size(), kNamedPairs); ++i) {
      text += std::string(i > 0 ? "," : "") + " '" + w_.primitives[members[i].first].name +
              "' and '" + w_.primitives[members[i].second].name + "'";
    }
    return text + (members.size() > kNamedPairs ? ", ...)" : ")");
  }

  const Workcell& w_;
  const std::string files_;
  std::map<std::string, std::vector<PrimitiveId>> of_owner_;
  std::vector<std::string> findings_;
};

// The findings of the pairs within their tolerances in the home pose and in within[k] of the
// sampled configurations after it, one group per pair of owners (links, objects): in all of
// them, every cycle would warn; in half or more, most would (OverlapReport).
std::vector<std::string> OverlapFindings(
    const Workcell& w, const std::vector<std::pair<PrimitiveId, PrimitiveId>>& pairs,
    const std::vector<int>& within, const std::string& files) {
  struct Group {
    std::string owner_a, owner_b;  // as its first pair has them; each pair in that order
    std::vector<std::pair<PrimitiveId, PrimitiveId>> every, most;
    int most_within = 0;
  };
  std::vector<Group> groups;
  std::map<std::pair<std::string, std::string>, std::size_t> group_of;
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    if (within[k] < kMostlyOverlappingSamples) continue;
    auto [x, y] = pairs[k];
    const std::string& owner_x = w.primitives[x].owner;
    const std::string& owner_y = w.primitives[y].owner;
    // One group whichever comes first (a model variant's primitives come after the objects).
    const auto [it, is_new] = group_of.emplace(std::minmax(owner_x, owner_y), groups.size());
    if (is_new) groups.push_back({owner_x, owner_y, {}, {}, 0});
    Group& group = groups[it->second];
    if (w.primitives[x].owner != group.owner_a) std::swap(x, y);
    if (within[k] == kAlwaysOverlappingSamples) {
      group.every.emplace_back(x, y);
    } else {
      group.most.emplace_back(x, y);
      group.most_within = std::max(group.most_within, within[k]);
    }
  }
  OverlapReport report(w, files);
  for (const Group& g : groups) report.Add(g.owner_a, g.owner_b, g.every, g.most, g.most_within);
  return report.findings();
}

// What a primitive `width_m` wide (over kLargeDerivedWorldEdge_m) most likely is.
std::string UnitErrorHint(const PrimitiveSpec& p, double width_m) {
  char text[64];
  std::snprintf(text, sizeof(text), "%.6g m", width_m);
  const std::string owner = (p.link_index >= 0 ? "link '" : "object '") + p.owner + "'";
  return std::string("it is ") + text + " wide: a unit error in " + owner +
         " (a mesh in millimetres without scale=\"0.001 0.001 0.001\"?)";
}

// The start-up warning of a primitive whose box (with its tolerance) `box_W` in the home pose is
// not inside the world cube `world_W`; one wider than kLargeDerivedWorldEdge_m (as with a derived
// cube, DerivedWorldNotice) and than the cube itself, so that no shift of its home pose would
// fit it, is most likely a unit error, such as a mesh in millimetres without scale.
std::string OutsideWorldWarning(const PrimitiveSpec& p, const Aabb& box_W, const Aabb& world_W,
                                const std::string& files) {
  std::string warning = files + "'" + p.name +
                        "' with its tolerance is not inside the world cube in the home pose "
                        "(expected world: to enclose the workcell)";
  const double width_m = (box_W.max_W - box_W.min_W).maxCoeff();
  const double world_edge_m = (world_W.max_W - world_W.min_W).maxCoeff();
  if (!(width_m > kLargeDerivedWorldEdge_m && width_m > world_edge_m)) return warning;
  return warning + "; " + UnitErrorHint(p, width_m);
}

// With a derived world cube, which holds every primitive, the start-up warnings of those wider
// than kLargeDerivedWorldEdge_m in the home pose (the widest of each link or object), put first:
// a unit error otherwise shows as pairs that warn in every cycle, its hint far below them.
std::vector<std::string> WideInDerivedWorldWarnings(const Workcell& w) {
  const WorkcellShapes shapes(w, WorkcellShapes::Models::kAll);  // the home pose
  std::map<std::string, std::pair<double, PrimitiveId>> widest;  // per link or object
  for (PrimitiveId id = 0; id < w.primitives.size(); ++id) {
    const PrimitiveSpec& p = w.primitives[id];
    const Aabb box_W = ComputeAabb(shapes.shape_W(id)).Inflated(p.tolerance_m);
    const double width_m = (box_W.max_W - box_W.min_W).maxCoeff();
    if (!(width_m > kLargeDerivedWorldEdge_m)) continue;
    const std::string owner = (p.link_index >= 0 ? "link " : "object ") + p.owner;
    auto [it, is_new] = widest.emplace(owner, std::make_pair(width_m, id));
    if (!is_new && width_m > it->second.first) it->second = {width_m, id};
  }
  std::vector<std::string> warnings;
  for (const auto& [owner, found] : widest) {
    const PrimitiveSpec& p = w.primitives[found.second];
    warnings.push_back(w.urdf_path + ", " + w.scene_path + ": '" + p.name +
                       "' with its tolerance, in the home pose: " +
                       UnitErrorHint(p, found.first) +
                       "; if it is that wide, give world: to enclose the workcell");
  }
  return warnings;
}

// Start-up findings from sampled configurations of every model: primitives outside the world
// cube in the home pose, and pairs within their tolerances in the home pose and in every sampled
// configuration (they would warn in every cycle) or in half of them at least (in most cycles).
std::vector<std::string> SampledConfigurationWarnings(const Workcell& w) {
  const std::size_t n = w.primitives.size();
  const std::string files = w.urdf_path + ", " + w.scene_path + ": ";
  std::vector<std::string> warnings;
  std::vector<std::pair<PrimitiveId, PrimitiveId>> candidates;
  for (PrimitiveId a = 0; a < n; ++a) {
    for (PrimitiveId b = a + 1; b < n; ++b) {
      if (w.primitives[a].is_static && w.primitives[b].is_static) continue;  // never checked
      if (!w.compatible.AreCompatible(a, b)) candidates.emplace_back(a, b);
    }
  }
  WorkcellShapes shapes(w, WorkcellShapes::Models::kAll);  // sample 0: the home pose
  for (PrimitiveId id = 0; id < n; ++id) {
    const PrimitiveSpec& p = w.primitives[id];
    const Aabb box_W = ComputeAabb(shapes.shape_W(id)).Inflated(p.tolerance_m);
    if (!w.world_W.Contains(box_W)) {
      warnings.push_back(OutsideWorldWarning(p, box_W, w.world_W, files));
    }
  }
  // The pairs within their tolerances in the home pose, and in how many samples after it.
  auto is_within = [&](const std::pair<PrimitiveId, PrimitiveId>& pair) {
    const double threshold_m =
        w.primitives[pair.first].tolerance_m + w.primitives[pair.second].tolerance_m;
    return IsCloserThan(shapes.shape_W(pair.first), shapes.shape_W(pair.second), threshold_m);
  };
  candidates.erase(std::remove_if(candidates.begin(), candidates.end(),
                                  [&](const auto& pair) { return !is_within(pair); }),
                   candidates.end());
  std::vector<int> within(candidates.size(), 0);
  std::mt19937_64 rng(kAlwaysOverlappingSeed);
  Eigen::VectorXd q = Eigen::VectorXd::Zero(w.kinematics.q_size());
  for (int sample = 1; sample <= kAlwaysOverlappingSamples && !candidates.empty(); ++sample) {
    SampleConfiguration(w.kinematics, &rng, &q);
    shapes.Evaluate(q);
    for (std::size_t k = 0; k < candidates.size(); ++k) within[k] += is_within(candidates[k]);
  }
  const std::vector<std::string> pairs = OverlapFindings(w, candidates, within, files);
  warnings.insert(warnings.end(), pairs.begin(), pairs.end());
  return warnings;
}

// Refuses a prismatic joint that slides further than kMaxWorldEdge_m within its limits (URDF
// limits of +/-1e9 m spelling "none"): the lever arms of the joints above it would take its whole
// travel in (every step checked pair by pair down to its samples: seconds a cycle), and so
// would a derived world cube.
void CheckPrismaticTravel(const KinematicModel& model, const std::string& urdf_path) {
  // The actuated joints first: a mimic joint slides as far as the joint it mimics puts it.
  std::vector<int> links;
  for (int link = 1; link < model.link_count(); ++link) {
    if (model.joint(link).mimic_q_index < 0) links.push_back(link);
  }
  for (int link = 1; link < model.link_count(); ++link) {
    if (model.joint(link).mimic_q_index >= 0) links.push_back(link);
  }
  for (const int link : links) {
    const JointSpec& joint = model.joint(link);
    const double travel_m = model.Travel_m(joint);
    if (travel_m <= kMaxWorldEdge_m) continue;
    // A mimic joint slides as the joint it mimics puts it: that joint's limits are the cure.
    const JointSpec* limited = &joint;
    char text[200];
    std::snprintf(text, sizeof(text), "%.6g m", travel_m);
    std::string how = std::string(" slides up to ") + text;
    if (const JointSpec* target = model.MimickedJoint(joint)) {
      limited = target;
      std::snprintf(text, sizeof(text), " (multiplier %.6g, offset %.6g)",
                    joint.mimic_multiplier, joint.mimic_offset);
      how = " mimics '" + limited->name + "'" + text + how + " with it";
    }
    std::snprintf(text, sizeof(text), "; '%s' is limited to [%.6g, %.6g]",
                  limited->name.c_str(), limited->lower, limited->upper);
    throw LoadError(urdf_path + ": prismatic joint '" + joint.name + "'" + how + ", over the " +
                    std::to_string(static_cast<long long>(kMaxWorldEdge_m)) +
                    " m a workcell may span (the motion bounds of the joints above it would "
                    "take that travel in whole)" + text + ": give it its real limits (the scene "
                    "file's joint_limits: {" + limited->name + ": {lower: l, upper: u}})");
  }
}

// Refuses a revolute or continuous mimic joint whose position, over the positions the monitor
// accepts of the joint it mimics (its limits widened by kJointLimitMargin, or
// +/-kMaxUnlimitedPosition_rad), can pass kMaxMimicPosition: an absurd multiplier or offset
// (1e308) whose poses lose all precision, then overflow to NaN and warn of nothing.
void CheckMimicRange(const KinematicModel& model, const std::string& urdf_path) {
  for (int link = 1; link < model.link_count(); ++link) {
    const JointSpec& joint = model.joint(link);
    const JointSpec* target = model.MimickedJoint(joint);
    if (target == nullptr || joint.type == JointType::kPrismatic) continue;  // Travel_m's
    const double reach = model.PositionBound(joint);
    if (reach <= kMaxMimicPosition) continue;
    const auto [lower, upper] = KinematicModel::AcceptedRange(*target);
    const double m = joint.mimic_multiplier;
    char text[400];
    std::snprintf(text, sizeof(text),
                  " (multiplier %.6g, offset %.6g) reaches %.10g rad over the positions of '%s' "
                  "the monitor accepts ([%.6g, %.6g]), over the %.10g rad a mimic joint may take",
                  m, joint.mimic_offset, reach, target->name.c_str(), lower, upper,
                  kMaxMimicPosition);
    throw LoadError(urdf_path + ": mimic joint '" + joint.name + "'" + text +
                    ": its poses would lose all precision, then overflow; check its <mimic>");
  }
}

// The start-up notice of the actuated joints that can move but have no velocity limit (velocity
// 0, or a continuous joint without <limit>), which the monitor can only take as of unknown
// speed; "" when every such joint has one.
std::string NoVelocityLimitNotice(const Workcell& w) {
  std::vector<std::string> names;
  bool is_any_turning = false;
  const std::vector<int> turning = w.kinematics.TurningLinks();
  for (int link = 1; link < w.kinematics.link_count(); ++link) {
    const JointSpec& joint = w.kinematics.joint(link);
    if (joint.q_index < 0 || joint.max_velocity > 0.0 || joint.lower == joint.upper) continue;
    names.push_back(joint.name);
    is_any_turning |= std::find(turning.begin(), turning.end(), link) != turning.end();
  }
  if (names.empty()) return "";
  return w.urdf_path + ": " + (names.size() == 1 ? "joint " : "joints ") + QuotedNames(names) +
         " without a velocity limit (velocity 0, or no <limit>): the start-up check of the "
         "tolerances does not count " + (names.size() == 1 ? "its" : "their") +
         " motion, a step beyond max_step_m that moves " + (names.size() == 1 ? "it" : "one") +
         " is an 'input jumped' stop whatever its time" +
         (is_any_turning ? ", and a wrapped reading of a continuous joint is not unwound" : "") +
         "; the scene file's joint_limits: {<joint>: {velocity: v}} gives a joint its top speed";
}

// The start-up notice of a derived world cube, in the form world: takes; a large one names the
// primitive that reaches farthest from the origin in the home pose.
std::string DerivedWorldNotice(const Workcell& w) {
  const Eigen::Vector3d center_W = 0.5 * (w.world_W.min_W + w.world_W.max_W);
  const double edge_m = (w.world_W.max_W - w.world_W.min_W).maxCoeff();
  char text[200];
  std::snprintf(text, sizeof(text), "{center_m: [%.3f, %.3f, %.3f], edge_m: %.3f}", center_W.x(),
                center_W.y(), center_W.z(), edge_m);
  std::string notice = w.scene_path +
                       ": world: not given; derived from the arms' reach envelopes and the " +
                       "objects: " + text;
  if (!(edge_m > kLargeDerivedWorldEdge_m)) return notice;
  const WorkcellShapes shapes(w, WorkcellShapes::Models::kAll);  // the home pose
  double farthest_m = 0.0;
  PrimitiveId farthest = 0;
  for (PrimitiveId id = 0; id < w.primitives.size(); ++id) {
    const Aabb box_W = ComputeAabb(shapes.shape_W(id));
    const double reach_m = box_W.min_W.cwiseAbs().cwiseMax(box_W.max_W.cwiseAbs()).norm();
    if (reach_m > farthest_m) {
      farthest_m = reach_m;
      farthest = id;
    }
  }
  std::snprintf(text, sizeof(text), "%.3f", farthest_m);
  return notice + " (over " + std::to_string(static_cast<int>(kLargeDerivedWorldEdge_m)) +
         " m: '" + w.primitives[farthest].name + "' reaches " + text +
         " m from the origin in the home pose; a unit or origin error in its link or object?)";
}

// The world cube of a scene file without one: derived from the arms' reach and the objects,
// with its notice, and the warnings of primitives too wide for a workcell put first.
void DeriveWorld(Workcell* w) {
  w->world_W = DeriveWorldCube(*w);
  w->notices.push_back(DerivedWorldNotice(*w));
  const std::vector<std::string> wide = WideInDerivedWorldWarnings(*w);
  w->warnings.insert(w->warnings.begin(), wide.begin(), wide.end());
}

// The start-up warning of a scene file without arms: every link is then the environment's, a
// moving one with the default tolerance, and an SRDF's 'Never' pairs are all excused, between
// what the user takes for two arms too (moveit_sections.cpp).
std::string NoArmsWarning(const Workcell& w, double default_arm_tolerance_m) {
  char text[64];
  std::snprintf(text, sizeof(text), "%.6g m", default_arm_tolerance_m);
  return w.scene_path + ": arms: not given or empty: no link belongs to an arm, so every moving "
         "link takes the default tolerance (" + text + "), its pairs are not arm-to-arm pairs, "
         "and an SRDF's 'Never' pairs are all excused; name each arm by its top link (arms: "
         "[{name: left, root_link: <link>}, {name: right, root_link: <link>}])";
}

}  // namespace

Workcell LoadWorkcell(const std::string& urdf_path, const std::string& scene_path,
                      double default_arm_tolerance_m) {
  WorkcellLoadOptions options;
  options.default_arm_tolerance_m = default_arm_tolerance_m;
  return LoadWorkcell(urdf_path, scene_path, options);
}

namespace {

Workcell ReadWorkcell(const std::string& urdf_path, const std::string& scene_path,
                      const WorkcellLoadOptions& options) {
  using scene_sections::Where;
  const double default_arm_tolerance_m = options.default_arm_tolerance_m;
  const std::string urdf_xml = ReadWholeFile(urdf_path, "a readable URDF file");
  const std::string xacro_warning = CheckXacroLeft(urdf_xml, urdf_path);
  const urdf::ModelInterfaceSharedPtr urdf_model = ParseUrdfFile(urdf_path);  // parsed once
  Workcell w;
  w.urdf_path = urdf_path;
  if (!xacro_warning.empty()) w.warnings.push_back(xacro_warning);
  w.scene_path = scene_path;
  w.kinematics = KinematicModel::FromUrdf(*urdf_model, urdf_path);
  CheckEveryCollisionRead(urdf_xml, *urdf_model, urdf_path);

  const YAML::Node scene = yaml_fields::LoadMapFile(scene_path);
  scene_sections::CheckSectionNames(scene, scene_path);
  const scene_sections::ShapeOptions shape_options =
      scene_sections::ReadShapeOptions(scene, scene_path);
  w.solid_options = SolidShapeOptions{shape_options.cylinder_model, shape_options.mesh_fit};
  scene_sections::ReadJointLimits(scene["joint_limits"], Where{scene_path, "joint_limits"},
                                  &w.kinematics);
  CheckPrismaticTravel(w.kinematics, urdf_path);
  CheckMimicRange(w.kinematics, urdf_path);
  w.joint_defaults = scene_sections::ReadJointDefaults(
      scene["joint_defaults"], Where{scene_path, "joint_defaults"}, w.kinematics);
  // Without world:, every object fits until the cube is derived from the finished workcell.
  const bool derives_world = !scene["world"].IsDefined();
  constexpr double kInf = std::numeric_limits<double>::infinity();
  w.world_W = derives_world
                  ? Aabb{Eigen::Vector3d::Constant(-kInf), Eigen::Vector3d::Constant(kInf)}
                  : scene_sections::ReadWorld(scene["world"], Where{scene_path, "world"});
  scene_sections::LinkSettings links;
  links.default_tolerance_m = default_arm_tolerance_m;
  w.arms = scene_sections::ReadArms(scene["arms"], Where{scene_path, "arms"}, w.kinematics,
                                    default_arm_tolerance_m, &links.arm_of_link);
  links.overrides =
      scene_sections::ReadLinkOverrides(scene["links"], Where{scene_path, "links"}, w.kinematics);

  w.fixed_frame = w.kinematics.link_name(0);

  // Primitives: the links' default models, the objects, the planning scene's objects, then the
  // model variants.
  scene_sections::NameRegistry names;
  MeshFitter meshes(options.fetch, options.mesh_fit_cache_dir, shape_options.mesh_fit);
  w.primitives = scene_sections::MakeLinkPrimitives(
      *urdf_model, w, links, shape_options.urdf_cylinder_model, &meshes, &names, &w.warnings);
  scene_sections::ReadObjects(scene["objects"], Where{scene_path, "objects"}, shape_options,
                              &meshes, &names, &w);
  const scene_sections::SrdfInput srdf =
      scene_sections::ReadSrdf(scene, scene_path, urdf_model->getName(), options.fetch, &w);
  const scene_sections::PlanningSceneInput planning_scene = scene_sections::ReadPlanningScene(
      scene, scene_path, shape_options, options.fetch, srdf, &meshes, &names, &w);
  meshes.ReportTo(&w);
  scene_sections::ReadVariants(scene["variants"], Where{scene_path, "variants"}, links, &names, &w);
  auto compatible_pairs =
      scene_sections::ReadCompatiblePairs(scene["compatible"], Where{scene_path, "compatible"}, w);
  for (const auto& more : {scene_sections::SrdfPairs(srdf, &w),
                           scene_sections::PlanningSceneAcmPairs(planning_scene, &w)}) {
    compatible_pairs.insert(compatible_pairs.end(), more.begin(), more.end());
  }
  w.grasp_targets = scene_sections::ReadGraspTargets(scene["grasp_targets"],
                                                     Where{scene_path, "grasp_targets"}, w);

  // Derived values.
  if (derives_world) DeriveWorld(&w);
  if (w.arms.empty()) w.warnings.push_back(NoArmsWarning(w, default_arm_tolerance_m));
  w.joint_names = w.kinematics.ActuatedJointNames();
  const std::string no_velocity_limit = NoVelocityLimitNotice(w);
  if (!no_velocity_limit.empty()) w.notices.push_back(no_velocity_limit);
  const std::string relative_meshes = RelativeMeshNotice(*urdf_model, urdf_path);
  if (!relative_meshes.empty()) w.notices.push_back(relative_meshes);
  w.compatible = ComputeCompatibility(w, compatible_pairs);
  const std::vector<std::string> sampled = SampledConfigurationWarnings(w);
  w.warnings.insert(w.warnings.end(), sampled.begin(), sampled.end());
  return w;
}

}  // namespace

Workcell LoadWorkcell(const std::string& urdf_path, const std::string& scene_path,
                      const WorkcellLoadOptions& options) {
  // Every read of a YAML node checks its kind first; yaml-cpp's own exception (a node used as
  // another kind) is a load error all the same, never a crash.
  try {
    return ReadWorkcell(urdf_path, scene_path, options);
  } catch (const YAML::Exception& e) {
    throw LoadError(scene_path + ": cannot read it: " + e.what());
  }
}

}  // namespace arm_collision_monitor
