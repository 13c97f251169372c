#include "arm_collision_monitor/ros/resource_fetch_ros.h"

#include <resource_retriever/retriever.h>
#include <rospack/rospack.h>

#include <algorithm>
#include <vector>

#include "arm_collision_monitor/core/load_error.h"
#include "arm_collision_monitor/scene/resource_fetch.h"

namespace arm_collision_monitor {
namespace {

/// The folder of `package` as ROS knows it, "" if it knows none, asked of rospack quietly
/// (resource_retriever asks it aloud: an unknown package printed rospack's own error lines on
/// stderr before the load error).
std::string FindPackage(const std::string& package) {
  rospack::Rospack rospack;
  rospack.setQuiet(true);
  std::vector<std::string> search_path;
  if (!rospack.getSearchPathFromEnv(search_path)) return "";
  rospack.crawl(search_path, /*force=*/false);
  std::string path;
  return rospack.find(package, path) ? path : "";
}

}  // namespace

std::string FetchRosResource(const std::string& url) {
  // A package:// URL is the package's folder and a path in it (what resource_retriever reads,
  // after a lookup of its own).
  const std::string prefix = "package://";
  if (url.compare(0, prefix.size(), prefix) == 0) {
    const std::size_t path_at = std::min(url.find('/', prefix.size()), url.size());
    const std::string package = url.substr(prefix.size(), path_at - prefix.size());
    const std::string folder = FindPackage(package);
    if (folder.empty()) {
      throw LoadError("cannot read it: ROS knows no package '" + package +
                      "' (source the setup.bash of the workspace that holds it, or add the "
                      "directory above it to ROS_PACKAGE_PATH)");
    }
    return ReadWholeFile(folder + url.substr(path_at), "a readable file");
  }
  // resource_retriever hands a name without a scheme to curl, which cannot read a plain path.
  if (url.find("://") == std::string::npos) return FetchLocalResource(url);
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
