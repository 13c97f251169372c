#include "arm_collision_monitor/ros/resource_fetch_ros.h"

#include <resource_retriever/retriever.h>

#include "arm_collision_monitor/core/load_error.h"
#include "arm_collision_monitor/scene/resource_fetch.h"

namespace arm_collision_monitor {

std::string FetchRosResource(const std::string& url) {
  // resource_retriever hands a name without a scheme to curl, which cannot read a plain path.
  if (url.find("://") == std::string::npos) return FetchLocalResource(url);
  resource_retriever::Retriever retriever;
  resource_retriever::MemoryResource resource;
  try {
    resource = retriever.get(url);
  } catch (const resource_retriever::Exception& e) {
    std::string hint;
    // resource_retriever's words for a package ROS does not know (the URL's host part).
    const std::string prefix = "package://";
    if (url.compare(0, prefix.size(), prefix) == 0) {
      const std::string package =
          url.substr(prefix.size(), url.find('/', prefix.size()) - prefix.size());
      if (!package.empty() && std::string(e.what()).find("Package [" + package +
                                                         "] does not exist") != std::string::npos) {
        hint = " (ROS knows no package '" + package + "': source the setup.bash of the " +
               "workspace that holds it, or add the directory above it to ROS_PACKAGE_PATH)";
      }
    }
    throw LoadError(std::string("cannot read it: ") + e.what() + hint);
  }
  if (resource.size == 0) return "";
  return std::string(reinterpret_cast<const char*>(resource.data.get()), resource.size);
}

}  // namespace arm_collision_monitor
