// LoadMonitorOptions: config/monitor.yaml, validated once at start-up.
#include "arm_collision_monitor/scene/workcell.h"
#include "yaml_fields.h"

namespace arm_collision_monitor {

MonitorOptions LoadMonitorOptions(const std::string& path) {
  using yaml_fields::Where;
  const YAML::Node root = yaml_fields::LoadMapFile(path);
  const Where top{path, ""};
  yaml_fields::CheckKeys(
      root,
      {"broad_phase", "auto_broad_phase", "max_objects_per_leaf", "grid_cells_per_axis",
       "techniques", "tolerance_m", "max_speed_mps", "cycle_period_s", "speed_scaled_tolerance",
       "reaction_time_s", "stopping_time_s", "fixed_frame"},
      top);
  MonitorOptions options;
  if (root["broad_phase"]) {
    const std::string name = yaml_fields::ReadName(root["broad_phase"], top.Child("broad_phase"));
    if (!ParseBroadPhaseMethod(name, &options.broad_phase.method)) {
      top.Child("broad_phase")
          .Fail(root["broad_phase"], "unknown method '" + name +
                                         "' (expected octree, naive, grid, rebuild or reinsert)");
    }
  }
  if (root["auto_broad_phase"]) {
    options.auto_broad_phase =
        yaml_fields::ReadBool(root["auto_broad_phase"], top.Child("auto_broad_phase"));
  }
  if (root["max_objects_per_leaf"]) {
    options.broad_phase.max_objects_per_leaf = yaml_fields::ReadPositiveInt(
        root["max_objects_per_leaf"], top.Child("max_objects_per_leaf"));
  }
  if (root["grid_cells_per_axis"]) {
    options.broad_phase.grid_cells_per_axis =
        yaml_fields::ReadPositiveInt(root["grid_cells_per_axis"], top.Child("grid_cells_per_axis"));
  }
  if (root["techniques"]) {
    const YAML::Node t = root["techniques"];
    const Where where = top.Child("techniques");
    yaml_fields::RequireMap(t, where);
    yaml_fields::CheckKeys(t,
                           {"directional_neighbours", "inside_node_exit", "pair_deduplication",
                            "bounding_box_pretests"},
                           where);
    BroadPhaseTechniques& techniques = options.broad_phase.techniques;
    auto read = [&](const char* key, bool* value) {
      if (t[key]) *value = yaml_fields::ReadBool(t[key], where.Child(key));
    };
    read("directional_neighbours", &techniques.directional_neighbours);
    read("inside_node_exit", &techniques.inside_node_exit);
    read("pair_deduplication", &techniques.pair_deduplication);
    read("bounding_box_pretests", &techniques.bounding_box_pretests);
  }
  auto read_double = [&](const char* key, bool positive, double* value) {
    if (!root[key]) return;
    *value = positive ? yaml_fields::ReadPositiveDouble(root[key], top.Child(key))
                      : yaml_fields::ReadNonNegativeDouble(root[key], top.Child(key));
  };
  read_double("tolerance_m", false, &options.tolerance_m);
  read_double("max_speed_mps", true, &options.max_speed_mps);
  read_double("cycle_period_s", true, &options.cycle_period_s);
  read_double("reaction_time_s", false, &options.reaction_time_s);
  read_double("stopping_time_s", false, &options.stopping_time_s);
  if (root["speed_scaled_tolerance"]) {
    options.speed_scaled_tolerance =
        yaml_fields::ReadBool(root["speed_scaled_tolerance"], top.Child("speed_scaled_tolerance"));
  }
  if (root["fixed_frame"]) {
    options.fixed_frame = yaml_fields::ReadName(root["fixed_frame"], top.Child("fixed_frame"));
  }
  // The farthest a primitive moves in one cycle: the octree's smallest cell (seed, section 3).
  options.broad_phase.min_cell_size_m = options.max_speed_mps * options.cycle_period_s;
  return options;
}

}  // namespace arm_collision_monitor
