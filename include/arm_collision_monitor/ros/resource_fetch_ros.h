// The ROS programs' ResourceFetcher: resource_retriever resolves package:// (through the ROS
// package index, ROS_PACKAGE_PATH) and file:// URLs and plain paths.
#pragma once

#include <string>

namespace arm_collision_monitor {

/// The bytes of `url` (package://pkg/path, file:///path, an absolute path) read by
/// resource_retriever; throws LoadError with resource_retriever's reason when it cannot.
std::string FetchRosResource(const std::string& url);

}  // namespace arm_collision_monitor
