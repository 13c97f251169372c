// ReadSrdfCollisionRules: the collision rules of a MoveIt SRDF, parsed with tinyxml2.
#include "arm_collision_monitor/scene/srdf_reader.h"

#include <tinyxml2.h>

#include <cstring>
#include <map>

#include "arm_collision_monitor/core/load_error.h"
#include "arm_collision_monitor/kinematics/urdf_conversions.h"
#include "arm_collision_monitor/scene/resource_fetch.h"
#include "text_trim.h"

namespace arm_collision_monitor {
namespace {

// The SRDF elements MoveIt reads that carry no collision rule (srdfdom's srdf::Model).
constexpr const char* kIgnoredElements[] = {"group",
                                            "group_state",
                                            "end_effector",
                                            "passive_joint",
                                            "joint_property",
                                            "link_sphere_approximation"};

[[noreturn]] void Fail(const std::string& path, int line, const std::string& element,
                       const std::string& what) {
  std::string location = path;
  if (line > 0) location += ":" + std::to_string(line);
  throw LoadError(location + ": " + element + ": " + what);
}

bool IsIgnored(const char* name) {
  for (const char* ignored : kIgnoredElements) {
    if (std::strcmp(name, ignored) == 0) return true;
  }
  return false;
}

/// The trimmed value of the required attribute `name` of `xml`; fails when absent or empty.
std::string RequiredName(const tinyxml2::XMLElement& xml, const char* name, const std::string& path,
                         const std::string& element, const std::string& form) {
  const char* value = xml.Attribute(name);
  const std::string trimmed = value == nullptr ? "" : Trimmed(value);
  if (trimmed.empty()) {
    Fail(path, xml.GetLineNum(), element,
         std::string(value == nullptr ? "missing" : "empty") + " attribute " + name +
             " (expected " + form + ")");
  }
  return trimmed;
}

SrdfLinkPair ReadLinkPair(const tinyxml2::XMLElement& xml, const std::string& path,
                          const std::string& element) {
  const std::string form = std::string("<") + xml.Name() +
                           " link1=\"LINK\" link2=\"LINK\" reason=\"...\"/>, a non-empty link1 "
                           "and link2";
  SrdfLinkPair pair;
  pair.link1 = RequiredName(xml, "link1", path, element, form);
  pair.link2 = RequiredName(xml, "link2", path, element, form);
  const char* reason = xml.Attribute("reason");
  pair.reason = reason == nullptr ? "" : reason;
  pair.line = xml.GetLineNum();
  return pair;
}

}  // namespace

SrdfCollisionRules ReadSrdfCollisionRules(const std::string& path) {
  return ReadSrdfCollisionRulesText(ReadWholeFile(path, "a readable SRDF file"), path);
}

SrdfCollisionRules ReadSrdfCollisionRulesText(const std::string& text, const std::string& path) {
  tinyxml2::XMLDocument doc;
  if (doc.Parse(text.c_str(), text.size()) != tinyxml2::XML_SUCCESS) {
    throw LoadError(MalformedXmlError(path, doc, "SRDF"));
  }
  const tinyxml2::XMLElement* robot = doc.RootElement();
  if (robot == nullptr || std::strcmp(robot->Name(), "robot") != 0) {
    Fail(path, robot == nullptr ? 0 : robot->GetLineNum(),
         robot == nullptr ? "(document)" : std::string("<") + robot->Name() + ">",
         "expected the root element <robot name=\"...\">");
  }
  SrdfCollisionRules rules;
  if (const char* name = robot->Attribute("name")) rules.robot_name = Trimmed(name);
  std::map<std::string, int> counts;  // entries per element name, for "name[index]"
  for (const tinyxml2::XMLElement* xml = robot->FirstChildElement(); xml != nullptr;
       xml = xml->NextSiblingElement()) {
    const std::string name = xml->Name();
    const std::string element = "robot." + name + "[" + std::to_string(counts[name]++) + "]";
    if (name == "disable_collisions") {
      rules.disabled_pairs.push_back(ReadLinkPair(*xml, path, element));
    } else if (name == "enable_collisions") {
      rules.enabled_pairs.push_back(ReadLinkPair(*xml, path, element));
    } else if (name == "disable_default_collisions") {
      const std::string link =
          RequiredName(*xml, "link", path, element, "<disable_default_collisions link=\"LINK\"/>");
      rules.default_disabled_links.push_back(SrdfLink{link, xml->GetLineNum()});
    } else if (name == "virtual_joint") {
      const std::string form =
          "<virtual_joint name=\"NAME\" type=\"fixed|floating|planar\" parent_frame=\"FRAME\" "
          "child_link=\"LINK\"/>";
      SrdfVirtualJoint joint;
      joint.name = RequiredName(*xml, "name", path, element, form);
      joint.type = RequiredName(*xml, "type", path, element, form);
      joint.parent_frame = RequiredName(*xml, "parent_frame", path, element, form);
      joint.child_link = RequiredName(*xml, "child_link", path, element, form);
      joint.line = xml->GetLineNum();
      rules.virtual_joints.push_back(joint);
    } else if (!IsIgnored(name.c_str())) {
      Fail(path, xml->GetLineNum(), element,
           "unknown element <" + name +
               "> (expected disable_collisions, enable_collisions, disable_default_collisions, "
               "group, group_state, end_effector, virtual_joint, passive_joint, joint_property "
               "or link_sphere_approximation)");
    }
  }
  return rules;
}

}  // namespace arm_collision_monitor
