// Checked reading of YAML fields for the start-up loaders: every failure is a LoadError whose
// message names the file (with the line when known), the element and what was expected.
#pragma once

#include <yaml-cpp/yaml.h>

#include <Eigen/Core>
#include <cstddef>
#include <initializer_list>
#include <string>

namespace arm_collision_monitor {
namespace yaml_fields {

/// Where an element is: the file and a readable element path, e.g. "objects[3] 'front_box'".
struct Where {
  std::string file;
  std::string element;

  Where Child(const std::string& name) const;
  /// Entry `index` of the sequence at this element, e.g. "objects[3]".
  Where Entry(std::size_t index) const;
  /// "file:line: element: what" (line omitted when yaml-cpp has no mark for `node`).
  [[noreturn]] void Fail(const YAML::Node& node, const std::string& what) const;
};

/// Loads a YAML file whose top level must be a map (an empty file is an empty map).
YAML::Node LoadMapFile(const std::string& path);
/// The same from the file's text (fetched by the caller); `path` names it in the messages.
YAML::Node LoadMapText(const std::string& text, const std::string& path);

void RequireMap(const YAML::Node& node, const Where& where);
void RequireSequence(const YAML::Node& node, const Where& where);
/// Fails on a key that appears twice in `map` (yaml-cpp would silently keep both).
void RequireUniqueKeys(const YAML::Node& map, const Where& where);
/// Fails on a repeated key and on any key of `map` not in `allowed` (a misspelt key must not be
/// silently ignored).
void CheckKeys(const YAML::Node& map, std::initializer_list<const char*> allowed,
               const Where& where);

double ReadFiniteDouble(const YAML::Node& node, const Where& where);
double ReadNonNegativeDouble(const YAML::Node& node, const Where& where);
double ReadPositiveDouble(const YAML::Node& node, const Where& where);
int ReadPositiveInt(const YAML::Node& node, const Where& where);
bool ReadBool(const YAML::Node& node, const Where& where);
/// A non-empty scalar string.
std::string ReadName(const YAML::Node& node, const Where& where);
Eigen::Vector3d ReadVector3(const YAML::Node& node, const Where& where);

/// For an optional key: when `map` has `key`, *value = read(map[key], where.Child(key)), with
/// `read` one of the readers above; otherwise *value keeps its default.
template <typename T, typename Reader>
void ReadIfPresent(const YAML::Node& map, const char* key, const Where& where, Reader read,
                   T* value) {
  if (map[key]) *value = read(map[key], where.Child(key));
}

}  // namespace yaml_fields
}  // namespace arm_collision_monitor
