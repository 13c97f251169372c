#include "arm_collision_monitor/ros/resource_fetch_ros.h"

#include <resource_retriever/retriever.h>
#include <rospack/rospack.h>

#include <vector>

#include "arm_collision_monitor/core/load_error.h"
#include "arm_collision_monitor/scene/resource_fetch.h"

namespace arm_collision_monitor {
namespace {

/// Whether ROS knows `package`, asked of rospack quietly: resource_retriever asks it aloud, and
/// an unknown package then prints rospack's own error lines on stderr before the load error.
bool IsKnownPackage(const std::string& package) {
  rospack::Rospack rospack;
  rospack.setQuiet(true);
  std::vector<std::string> search_path;
  if (!rospack.getSearchPathFromEnv(search_path)) return true;  // the retriever says why
  rospack.crawl(search_path, /*force=*/false);
  std::string path;
  return rospack.find(package, path);
}

}  // namespace

std::string FetchRosResource(const std::string& url) {
  // resource_retriever hands a name without a scheme to curl, which cannot read a plain path.
  if (url.find("://") == std::string::npos) return FetchLocalResource(url);
  const std::string prefix = "package://";
  if (url.compare(0, prefix.size(), prefix) == 0) {
    const std::string package =
        url.substr(prefix.size(), url.find('/', prefix.size()) - prefix.size());
    if (!IsKnownPackage(package)) {
      throw LoadError("cannot read it: ROS knows no package '" + package +
                      "' (source the setup.bash of the workspace that holds it, or add the "
                      "directory above it to ROS_PACKAGE_PATH)");
    }
  }
  resource_retriever::Retriever retriever;
  resource_retriever::MemoryResource resource;
  try {
    resource = retriever.get(url);
  } catch (const resource_retriever::Exception& e) {
    throw LoadError(std::string("cannot read it: ") + e.what());
  }
  if (resource.size == 0) return "";
  return std::string(reinterpret_cast<const char*>(resource.data.get()), resource.size);
}

}  // namespace arm_collision_monitor
