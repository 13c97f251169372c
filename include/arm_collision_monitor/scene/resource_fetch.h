// The files the start-up inputs name (URDF meshes, the scene file's srdf:, planning_scene: and
// mesh objects) are read through a fetcher: a function from a URL to its bytes. The core's
// fetcher reads local files; the ROS layer passes one that also resolves package:// URLs
// (FetchRosResource in ros/resource_fetch_ros.h), so the core needs no ROS.
#pragma once

#include <functional>
#include <string>

namespace arm_collision_monitor {

/// Maps a resource URL to the resource's bytes. Throws LoadError saying why it cannot (the
/// caller prefixes the file and element that named the resource).
using ResourceFetcher = std::function<std::string(const std::string& url)>;

/// `name` as a URL to fetch: a name with a scheme ("package://...", "file://...", ...) as
/// given; an absolute path as given; a relative one joined to `base_dir` and made absolute (a
/// relative `base_dir` taken from the working directory), so that errors name the file looked
/// for, without normalising it (a '..' after a symbolic link is the link target's parent).
std::string ResolveResourceName(const std::string& name, const std::string& base_dir);

/// The core's fetcher: a plain file path or a file:// URL is read from the file system; any
/// other scheme, package:// included (it needs ROS's package index), is refused with a
/// LoadError that says what to give instead.
std::string FetchLocalResource(const std::string& url);

/// Reads a whole regular file; `what` names what it should be ("an SRDF file") for the error.
/// Throws LoadError "path: cannot open the file (expected what)".
std::string ReadWholeFile(const std::string& path, const std::string& what);

}  // namespace arm_collision_monitor
