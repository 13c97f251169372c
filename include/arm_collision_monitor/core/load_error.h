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

/// For names a file gives that `model_names` lack, those the model has with a prefix (ending in
/// '_', '/' or '-': a file written for one arm, or a driver's unprefixed joint names), at most
/// three names and four of the model's each: "; the URDF has 'link7' as 'left_link7',
/// 'right_link7'" (`model`: "the URDF"); "" when none.
inline std::string PrefixedNamesHint(const std::vector<std::string>& model_names,
                                     const std::vector<std::string>& names,
                                     const std::string& model) {
  constexpr int kHintedNames = 3;
  constexpr std::size_t kShownPerName = 4;
  std::string hint;
  int hinted = 0;
  for (const std::string& name : names) {
    std::vector<std::string> prefixed;
    std::size_t more = 0;
    for (const std::string& full : model_names) {
      if (full.size() <= name.size() + 1) continue;
      const std::size_t start = full.size() - name.size();
      const char separator = full[start - 1];
      if (full.compare(start, name.size(), name) != 0 ||
          (separator != '_' && separator != '/' && separator != '-')) {
        continue;
      }
      if (prefixed.size() < kShownPerName) {
        prefixed.push_back(full);
      } else {
        ++more;
      }
    }
    if (prefixed.empty()) continue;
    hint += (hint.empty() ? "; " + model + " has '" : "; '") + name + "' as " +
            QuotedNames(prefixed) + (more > 0 ? " and " + std::to_string(more) + " more" : "");
    if (++hinted == kHintedNames) break;
  }
  return hint;
}

}  // namespace arm_collision_monitor
