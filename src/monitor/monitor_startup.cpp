#include "arm_collision_monitor/monitor/monitor_startup.h"

namespace arm_collision_monitor {

MonitorStartup LoadMonitorStartup(const std::string& urdf_path, const std::string& scene_path,
                                  const std::string& config_path) {
  MonitorStartup startup;
  startup.options = LoadMonitorOptions(config_path);
  startup.workcell = std::make_shared<const Workcell>(
      LoadWorkcell(urdf_path, scene_path, startup.options.tolerance_m));
  return startup;
}

}  // namespace arm_collision_monitor
