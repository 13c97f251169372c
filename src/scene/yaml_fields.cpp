#include "arm_collision_monitor/scene/yaml_fields.h"

#include <cmath>
#include <set>

#include "arm_collision_monitor/core/load_error.h"
#include "arm_collision_monitor/scene/resource_fetch.h"

namespace arm_collision_monitor {
namespace yaml_fields {

Where Where::Child(const std::string& name) const {
  return Where{file, element.empty() ? name : element + "." + name};
}

Where Where::Entry(std::size_t index) const {
  return Where{file, element + "[" + std::to_string(index) + "]"};
}

void Where::Fail(const YAML::Node& node, const std::string& what) const {
  std::string location = file;
  if (node.IsDefined() && !node.Mark().is_null()) {
    location += ":" + std::to_string(node.Mark().line + 1);
  }
  throw LoadError(location + ": " + (element.empty() ? std::string("(top level)") : element) +
                  ": " + what);
}

YAML::Node LoadMapFile(const std::string& path) {
  return LoadMapText(ReadWholeFile(path, "a readable YAML file"), path);
}

YAML::Node LoadMapText(const std::string& text, const std::string& path) {
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::ParserException& e) {
    throw LoadError(path + ":" + std::to_string(e.mark.line + 1) + ": malformed YAML: " + e.msg);
  } catch (const YAML::Exception& e) {
    throw LoadError(path + ": cannot read YAML: " + e.what());
  }
  if (root.IsNull()) return YAML::Node(YAML::NodeType::Map);
  if (!root.IsMap()) {
    Where{path, ""}.Fail(root, "expected a map of keys at the top level");
  }
  return root;
}

// A key a map does not have is an invalid node, whose kind yaml-cpp throws for (InvalidNode, which
// escaped as a crash): IsDefined first.
void RequireMap(const YAML::Node& node, const Where& where) {
  if (!node.IsDefined() || !node.IsMap()) where.Fail(node, "expected a map ({key: value, ...})");
}

void RequireSequence(const YAML::Node& node, const Where& where) {
  if (!node.IsDefined() || !node.IsSequence()) {
    where.Fail(node, "expected a list ([...] or '- ' items)");
  }
}

void RequireUniqueKeys(const YAML::Node& map, const Where& where) {
  std::set<std::string> seen;
  for (const auto& entry : map) {
    const std::string key = entry.first.as<std::string>("");
    if (!seen.insert(key).second) where.Fail(entry.first, "duplicate key '" + key + "'");
  }
}

void CheckKeys(const YAML::Node& map, std::initializer_list<const char*> allowed,
               const Where& where) {
  RequireUniqueKeys(map, where);
  const std::set<std::string> names(allowed.begin(), allowed.end());
  for (const auto& entry : map) {
    const std::string key = entry.first.as<std::string>("");
    if (names.count(key) == 0) {
      std::string expected;
      for (const auto& name : names) expected += (expected.empty() ? "" : ", ") + name;
      where.Fail(entry.first, "unknown key '" + key + "' (expected one of: " + expected + ")");
    }
  }
}

double ReadFiniteDouble(const YAML::Node& node, const Where& where) {
  if (!node.IsDefined() || !node.IsScalar()) where.Fail(node, "expected a number");
  double value = 0.0;
  // yaml-cpp reads ".nan" and ".inf" as numbers: rejected below with a clear reason.
  if (!YAML::convert<double>::decode(node, value)) {
    where.Fail(node, "expected a number, got '" + node.Scalar() + "'");
  }
  if (!std::isfinite(value)) where.Fail(node, "expected a finite number, got " + node.Scalar());
  return value;
}

double ReadNonNegativeDouble(const YAML::Node& node, const Where& where) {
  const double value = ReadFiniteDouble(node, where);
  if (value < 0.0) where.Fail(node, "expected a number >= 0, got " + node.Scalar());
  return value;
}

double ReadPositiveDouble(const YAML::Node& node, const Where& where) {
  const double value = ReadFiniteDouble(node, where);
  if (value <= 0.0) where.Fail(node, "expected a number > 0, got " + node.Scalar());
  return value;
}

int ReadPositiveInt(const YAML::Node& node, const Where& where) {
  if (!node.IsDefined() || !node.IsScalar()) where.Fail(node, "expected a positive integer");
  int value = 0;
  if (!YAML::convert<int>::decode(node, value) || value <= 0) {
    where.Fail(node, "expected a positive integer, got '" + node.Scalar() + "'");
  }
  return value;
}

bool ReadBool(const YAML::Node& node, const Where& where) {
  bool value = false;
  if (!node.IsDefined() || !node.IsScalar() || !YAML::convert<bool>::decode(node, value)) {
    where.Fail(node, "expected true or false");
  }
  return value;
}

std::string ReadName(const YAML::Node& node, const Where& where) {
  if (!node.IsDefined() || !node.IsScalar() || node.Scalar().empty()) {
    where.Fail(node, "expected a non-empty name");
  }
  return node.Scalar();
}

Eigen::Vector3d ReadVector3(const YAML::Node& node, const Where& where) {
  if (!node.IsDefined() || !node.IsSequence() || node.size() != 3) {
    where.Fail(node, "expected a list of 3 numbers [x, y, z]");
  }
  Eigen::Vector3d v;
  for (int i = 0; i < 3; ++i) {
    v[i] = ReadFiniteDouble(node[i], where.Entry(i));
  }
  return v;
}

}  // namespace yaml_fields
}  // namespace arm_collision_monitor
