// LoadMonitorOptions: config/monitor.yaml, validated once at start-up.
#include "arm_collision_monitor/monitor/monitor_options.h"

#include <cmath>
#include <string>

#include "arm_collision_monitor/scene/yaml_fields.h"

namespace arm_collision_monitor {

namespace {

using yaml_fields::ReadIfPresent;
using yaml_fields::Where;

/// The `techniques` map at `where` into *techniques.
void ReadTechniques(const YAML::Node& t, const Where& where, BroadPhaseTechniques* techniques) {
  yaml_fields::RequireMap(t, where);
  yaml_fields::CheckKeys(t,
                         {"directional_neighbours", "inside_node_exit", "pair_deduplication",
                          "bounding_box_pretests"},
                         where);
  ReadIfPresent(t, "directional_neighbours", where, yaml_fields::ReadBool,
                &techniques->directional_neighbours);
  ReadIfPresent(t, "inside_node_exit", where, yaml_fields::ReadBool,
                &techniques->inside_node_exit);
  ReadIfPresent(t, "pair_deduplication", where, yaml_fields::ReadBool,
                &techniques->pair_deduplication);
  ReadIfPresent(t, "bounding_box_pretests", where, yaml_fields::ReadBool,
                &techniques->bounding_box_pretests);
}

/// The `live_objects` map at `where` into *live.
void ReadLiveObjects(const YAML::Node& node, const Where& where, LiveObjectOptions* live) {
  yaml_fields::RequireMap(node, where);
  yaml_fields::CheckKeys(node, {"capacity", "max_primitives_per_object"}, where);
  if (node["capacity"]) {
    // 0 is allowed (no live objects): read as a non-negative whole number.
    const double capacity =
        yaml_fields::ReadNonNegativeDouble(node["capacity"], where.Child("capacity"));
    if (capacity != std::floor(capacity) || capacity > kLiveObjectMaxCapacity) {
      where.Child("capacity").Fail(node["capacity"],
                                   "expected a whole number in [0, " +
                                       std::to_string(kLiveObjectMaxCapacity) + "]");
    }
    live->capacity = static_cast<std::uint32_t>(capacity);
  }
  if (node["max_primitives_per_object"]) {
    const int k = yaml_fields::ReadPositiveInt(node["max_primitives_per_object"],
                                               where.Child("max_primitives_per_object"));
    if (static_cast<std::uint32_t>(k) > kLiveObjectMaxPrimitives) {
      where.Child("max_primitives_per_object")
          .Fail(node["max_primitives_per_object"],
                "expected at most " + std::to_string(kLiveObjectMaxPrimitives));
    }
    live->max_primitives_per_object = static_cast<std::uint32_t>(k);
  }
}

}  // namespace

MonitorOptions LoadMonitorOptions(const std::string& path) {
  const YAML::Node root = yaml_fields::LoadMapFile(path);
  const Where top{path, ""};
  if (root["auto_broad_phase"]) {
    top.Child("auto_broad_phase")
        .Fail(root["auto_broad_phase"],
              "was replaced by 'broad_phase: auto' (the default; name a method to force it)");
  }
  yaml_fields::CheckKeys(
      root,
      {"broad_phase", "max_objects_per_leaf", "grid_cells_per_axis",
       "techniques", "tolerance_m", "max_speed_mps", "cycle_period_s", "speed_scaled_tolerance",
       "reaction_time_s", "stopping_time_s", "index_slack_m", "swept_check",
       "swept_resolution_m", "max_step_m", "fixed_frame", "live_objects"},
      top);
  MonitorOptions options;
  if (root["broad_phase"]) {
    const std::string name = yaml_fields::ReadName(root["broad_phase"], top.Child("broad_phase"));
    if (!ParseBroadPhaseMethod(name, &options.broad_phase.method)) {
      top.Child("broad_phase")
          .Fail(root["broad_phase"],
                "unknown method '" + name +
                    "' (expected auto, octree, naive, grid, rebuild or reinsert)");
    }
  }
  ReadIfPresent(root, "max_objects_per_leaf", top, yaml_fields::ReadPositiveInt,
                &options.broad_phase.max_objects_per_leaf);
  ReadIfPresent(root, "grid_cells_per_axis", top, yaml_fields::ReadPositiveInt,
                &options.broad_phase.grid_cells_per_axis);
  if (root["techniques"]) {
    ReadTechniques(root["techniques"], top.Child("techniques"), &options.broad_phase.techniques);
  }
  ReadIfPresent(root, "tolerance_m", top, yaml_fields::ReadNonNegativeDouble,
                &options.tolerance_m);
  ReadIfPresent(root, "max_speed_mps", top, yaml_fields::ReadPositiveDouble,
                &options.max_speed_mps);
  ReadIfPresent(root, "cycle_period_s", top, yaml_fields::ReadPositiveDouble,
                &options.cycle_period_s);
  ReadIfPresent(root, "reaction_time_s", top, yaml_fields::ReadNonNegativeDouble,
                &options.reaction_time_s);
  ReadIfPresent(root, "stopping_time_s", top, yaml_fields::ReadNonNegativeDouble,
                &options.stopping_time_s);
  ReadIfPresent(root, "speed_scaled_tolerance", top, yaml_fields::ReadBool,
                &options.speed_scaled_tolerance);
  ReadIfPresent(root, "index_slack_m", top, yaml_fields::ReadNonNegativeDouble,
                &options.index_slack_m);
  ReadIfPresent(root, "swept_check", top, yaml_fields::ReadBool, &options.swept_check);
  ReadIfPresent(root, "swept_resolution_m", top, yaml_fields::ReadPositiveDouble,
                &options.swept_resolution_m);
  ReadIfPresent(root, "max_step_m", top, yaml_fields::ReadPositiveDouble, &options.max_step_m);
  ReadIfPresent(root, "fixed_frame", top, yaml_fields::ReadName, &options.fixed_frame);
  if (root["live_objects"]) {
    ReadLiveObjects(root["live_objects"], top.Child("live_objects"), &options.live_objects);
  }
  return options;
}

}  // namespace arm_collision_monitor
