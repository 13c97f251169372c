// What every program that runs a Monitor loads at start-up, in one sequence, so that the same
// files give the same model and thresholds in the node and in replay.
#pragma once

#include <memory>
#include <string>

#include "arm_collision_monitor/monitor/monitor_options.h"
#include "arm_collision_monitor/scene/workcell.h"

namespace arm_collision_monitor {

/// The loaded inputs of a Monitor: its options and the workcell.
struct MonitorStartup {
  MonitorOptions options;
  std::shared_ptr<const Workcell> workcell;
};

/// Loads the Monitor options (`config_path`), then the workcell from `urdf_path` and
/// `scene_path` with the options' tolerance_m as the default arm tolerance, the files they name
/// read through `fetch` (the ROS programs pass FetchRosResource, for package:// URLs). The
/// workcell's start-up findings (Workcell::warnings, Workcell::notices) are the caller's to
/// show. Throws LoadError naming the file and the element.
MonitorStartup LoadMonitorStartup(const std::string& urdf_path, const std::string& scene_path,
                                  const std::string& config_path, const ResourceFetcher& fetch);

}  // namespace arm_collision_monitor
