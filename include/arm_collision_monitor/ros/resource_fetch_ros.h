// The ROS programs' ResourceFetcher: package:// URLs through the ROS package index (rospack,
// ROS_PACKAGE_PATH), other URLs through resource_retriever, plain paths as files.
#pragma once

#include <string>

namespace arm_collision_monitor {

/// The bytes of `url` (package://pkg/path, file:///path, an absolute path); throws LoadError
/// with the reason when it cannot (a package ROS does not know, with what to do).
std::string FetchRosResource(const std::string& url);

}  // namespace arm_collision_monitor
