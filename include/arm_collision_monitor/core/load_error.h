// The start-up error tier: user input (URDF, scene file, options) that cannot be used.
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

namespace arm_collision_monitor {

/// Start-up input error. what() names the file, the element and what was expected, e.g.
/// "config/scene.yaml: objects[3] 'front_table': size must be 3 positive numbers".
class LoadError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// For a file that cannot be opened: where a relative `path` was looked for (roslaunch starts a
/// node in ROS_HOME, not in the user's directory), "" for an absolute path or a URL.
inline std::string RelativePathNote(const std::string& path) {
  if (path.empty() || path.find("://") != std::string::npos ||
      std::filesystem::path(path).is_absolute()) {
    return "";
  }
  std::error_code error;
  const std::filesystem::path cwd = std::filesystem::current_path(error);
  return "; the path is relative, taken from the working directory '" +
         (error ? std::string("?") : cwd.string()) +
         "' (roslaunch starts nodes in ROS_HOME: give launch arguments absolute paths or "
         "$(find package)/...)";
}

/// Names for a message, each quoted and comma-separated: "'a', 'b'".
inline std::string QuotedNames(const std::vector<std::string>& names) {
  std::string text;
  for (const std::string& name : names) text += (text.empty() ? "'" : ", '") + name + "'";
  return text;
}

}  // namespace arm_collision_monitor
