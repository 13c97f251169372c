// The scene file's joint sections, joint_limits: and joint_defaults: (scene_sections.h).
#include "scene_sections.h"

#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

namespace arm_collision_monitor {
namespace scene_sections {

namespace {

// A side of a joint's position range (KinematicModel::PositionRange) for a message: its limit,
// or for a side without one (`limit` infinite) the bound the monitor accepts there.
std::string LimitText(double limit, double accepted) {
  char text[48];
  if (std::isfinite(limit)) {
    std::snprintf(text, sizeof(text), "%.10g", accepted);
  } else {
    std::snprintf(text, sizeof(text), "none: %g", accepted);
  }
  return text;
}

// The entries of a map keyed by actuated joint names (joint_limits:, joint_defaults:): `read`
// gets each value, its place and the joint's name and spec; any other key fails.
template <typename Read>
void ReadActuatedJointMap(const YAML::Node& node, const Where& where, const KinematicModel& model,
                          Read read) {
  if (!node.IsDefined()) return;
  yaml_fields::RequireMap(node, where);
  yaml_fields::RequireUniqueKeys(node, where);
  for (const auto& entry : node) {
    const std::string joint_name = entry.first.as<std::string>("");
    const Where item = where.Child(joint_name);
    const int link = model.FindJointChildLink(joint_name);
    if (link < 0) item.Fail(entry.first, "unknown joint (expected an actuated joint of the URDF)");
    const JointSpec& joint = model.joint(link);
    if (joint.mimic_q_index >= 0) {
      item.Fail(entry.first, "a mimic joint of '" +
                                 model.ActuatedJointNames()[joint.mimic_q_index] +
                                 "' (its position follows that joint's: give that joint's)");
    }
    if (joint.q_index < 0) {
      item.Fail(entry.first, "a fixed joint of the URDF (expected an actuated joint)");
    }
    read(entry.second, item, joint_name, joint);
  }
}

}  // namespace

void ReadJointLimits(const YAML::Node& node, const Where& where, KinematicModel* model) {
  ReadActuatedJointMap(node, where, *model, [&](const YAML::Node& value, const Where& item,
                                                const std::string& joint_name,
                                                const JointSpec& joint) {
    yaml_fields::RequireMap(value, item);
    yaml_fields::CheckKeys(value, {"lower", "upper", "velocity"}, item);
    double lower = joint.lower;
    double upper = joint.upper;
    yaml_fields::ReadIfPresent(value, "lower", item, yaml_fields::ReadFiniteDouble, &lower);
    yaml_fields::ReadIfPresent(value, "upper", item, yaml_fields::ReadFiniteDouble, &upper);
    // A side not given keeps the URDF's (none for a continuous joint).
    const std::pair<double, double> urdf = KinematicModel::PositionRange(joint);
    const auto is_within = [&](double x) { return urdf.first <= x && x <= urdf.second; };
    if (!((lower == joint.lower || is_within(lower)) && lower <= upper &&
          (upper == joint.upper || is_within(upper)))) {
      item.Fail(value, "expected URDF lower (" + LimitText(joint.lower, urdf.first) +
                           ") <= lower <= upper <= URDF upper (" +
                           LimitText(joint.upper, urdf.second) + ")");
    }
    model->SetPositionLimits(joint_name, lower, upper);
    // The joint's real top speed, where the URDF's is the motor's (a Unitree G1's 37 rad/s):
    // what the start-up check of the tolerance against the motion in one cycle uses.
    double velocity = joint.max_velocity;
    yaml_fields::ReadIfPresent(value, "velocity", item, yaml_fields::ReadPositiveDouble,
                               &velocity);
    if (joint.max_velocity > 0.0 && velocity > joint.max_velocity) {
      item.Child("velocity").Fail(value["velocity"], "expected 0 < velocity <= URDF velocity (" +
                                                         std::to_string(joint.max_velocity) +
                                                         ")");
    }
    model->SetVelocityLimit(joint_name, velocity);
  });
}

std::vector<std::pair<int, double>> ReadJointDefaults(const YAML::Node& node, const Where& where,
                                                      const KinematicModel& model) {
  std::vector<std::pair<int, double>> defaults;
  ReadActuatedJointMap(node, where, model, [&](const YAML::Node& value, const Where& item,
                                               const std::string&, const JointSpec& joint) {
    const double position = yaml_fields::ReadFiniteDouble(value, item);
    const auto [lower, upper] = KinematicModel::PositionRange(joint);
    if (!(lower <= position && position <= upper)) {
      item.Fail(value, "expected a position within the joint's limits [" +
                           LimitText(joint.lower, lower) + ", " + LimitText(joint.upper, upper) +
                           "]");
    }
    defaults.emplace_back(joint.q_index, position);
  });
  return defaults;
}

}  // namespace scene_sections
}  // namespace arm_collision_monitor
