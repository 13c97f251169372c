#include "arm_collision_monitor/monitor/monitor_startup.h"

namespace arm_collision_monitor {

MonitorStartup LoadMonitorStartup(const std::string& urdf_path, const std::string& scene_path,
                                  const std::string& config_path, const ResourceFetcher& fetch) {
  MonitorStartup startup;
  startup.options = LoadMonitorOptions(config_path);
  WorkcellLoadOptions load;
  load.default_arm_tolerance_m = startup.options.tolerance_m;
  load.fetch = fetch;
  startup.workcell = std::make_shared<const Workcell>(LoadWorkcell(urdf_path, scene_path, load));
  return startup;
}

}  // namespace arm_collision_monitor
