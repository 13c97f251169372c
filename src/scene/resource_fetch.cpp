#include "arm_collision_monitor/scene/resource_fetch.h"

#include <filesystem>
#include <fstream>
#include <sstream>

#include "arm_collision_monitor/core/load_error.h"

namespace arm_collision_monitor {
namespace {

constexpr const char* kFileScheme = "file://";

bool StartsWith(const std::string& text, const std::string& prefix) {
  return text.compare(0, prefix.size(), prefix) == 0;
}

}  // namespace

std::string ResolveResourceName(const std::string& name, const std::string& base_dir) {
  if (name.find("://") != std::string::npos) return name;
  const std::filesystem::path path(name);
  if (path.is_absolute()) return name;
  // Absolute, so that an error names the file looked for, not a path that reads as taken from
  // the working directory (the base is; the name is not). Not normalised: the system resolves
  // a '..' after a symbolic link against the link's target.
  const std::filesystem::path joined = std::filesystem::path(base_dir) / path;
  std::error_code error;
  const std::filesystem::path absolute = std::filesystem::absolute(joined, error);
  return (error ? joined : absolute).string();
}

std::string ReadWholeFile(const std::string& path, const std::string& what) {
  std::error_code error;
  std::ifstream in;
  if (std::filesystem::is_regular_file(path, error)) in.open(path, std::ios::binary);
  if (!in.is_open()) {
    throw LoadError(path + ": cannot open the file (expected " + what + RelativePathNote(path) +
                    ")");
  }
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

std::string FetchLocalResource(const std::string& url) {
  if (StartsWith(url, kFileScheme)) {
    return ReadWholeFile(url.substr(std::string(kFileScheme).size()), "a readable file");
  }
  const std::size_t scheme_end = url.find("://");
  if (scheme_end != std::string::npos) {
    throw LoadError(url.substr(0, scheme_end + 3) +
                    " URLs are not resolved by the plain loader (package:// needs ROS's package "
                    "index: the monitor node and replay resolve it); give a file path (absolute, "
                    "or relative to the file that names it) or a file:// URL");
  }
  return ReadWholeFile(url, "a readable file");
}

}  // namespace arm_collision_monitor
