// Reader of MoveIt's SRDF (Semantic Robot Description Format, srdfdom 0.6+): the collision rules
// only, as plain structs. ROS-free; the caller maps link names onto its model.
#pragma once

#include <string>
#include <vector>

namespace arm_collision_monitor {

/// One <disable_collisions> or <enable_collisions> element. Names are trimmed of surrounding
/// whitespace (as srdfdom does); `reason` is "" when absent (Setup Assistant writes "Adjacent",
/// "Never", "Always", "Default", "User").
struct SrdfLinkPair {
  std::string link1;
  std::string link2;
  std::string reason;
  int line = 0;  ///< line of the element in the file (1-based)
};

/// One <disable_default_collisions link="..."/> element.
struct SrdfLink {
  std::string link;
  int line = 0;
};

/// One <virtual_joint name type parent_frame child_link/>: how the robot's root link hangs from
/// a frame outside the URDF (MoveIt's planning frame is its parent_frame).
struct SrdfVirtualJoint {
  std::string name;
  std::string type;  ///< "fixed", "floating" or "planar"
  std::string parent_frame;
  std::string child_link;
  int line = 0;
};

/// The collision rules of an SRDF, and its virtual joints, in file order. MoveIt applies them
/// as: a link listed in default_disabled_links may touch anything by default; enabled_pairs
/// re-enable checking for their pairs (overriding that default); disabled_pairs excuse their
/// pairs. Link names are not checked against any URDF here (the caller knows the model). Pairs
/// are returned as written: repeats and link1 == link2 are kept, link1/link2 order is the
/// file's.
struct SrdfCollisionRules {
  std::string robot_name;  ///< <robot name=...>, "" when absent
  std::vector<SrdfLinkPair> disabled_pairs;
  std::vector<SrdfLinkPair> enabled_pairs;
  std::vector<SrdfLink> default_disabled_links;
  std::vector<SrdfVirtualJoint> virtual_joints;
};

/// Reads the collision rules of the SRDF file at `path` (a file system path: resolving
/// `package://` URLs or reading robot_description_semantic is the caller's job).
///
/// Read: <disable_collisions link1 link2 [reason]>, <enable_collisions link1 link2 [reason]>,
/// <disable_default_collisions link>, <virtual_joint name type parent_frame child_link>. Ignored
/// (they describe planning, not collision geometry): <group>, <group_state>, <end_effector>,
/// <passive_joint>, <joint_property>,
/// <link_sphere_approximation>. Any other element under <robot> is rejected, so that a misspelt
/// rule (say <enable_colisions>) is not silently dropped; so is an unexpanded .srdf.xacro (its
/// <xacro:...> elements): run xacro first.
///
/// Throws LoadError "path[:line]: element: what was expected" when the path is not a readable
/// regular file, the XML is malformed (with its line), the root element is not <robot>, an
/// element is unknown, or a rule lacks a link attribute (or has an empty one).
SrdfCollisionRules ReadSrdfCollisionRules(const std::string& path);

/// The same from the SRDF's text (fetched by the caller, e.g. through a ResourceFetcher);
/// `path` names it in the messages.
SrdfCollisionRules ReadSrdfCollisionRulesText(const std::string& text, const std::string& path);

}  // namespace arm_collision_monitor
