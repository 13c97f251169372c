// Conversions from urdfdom types, shared by the kinematics and the scene loader.
#pragma once

#include <urdf_model/model.h>
#include <urdf_world/types.h>

#include <Eigen/Geometry>
#include <string>

namespace tinyxml2 {
class XMLDocument;
class XMLElement;
}

namespace arm_collision_monitor {

/// The rigid transform an URDF <origin> states (rpy applied as fixed-axis roll, pitch, yaw).
Eigen::Isometry3d UrdfPoseToIsometry(const urdf::Pose& pose);

/// Parses the URDF at `urdf_path`. Throws LoadError naming the file when it cannot be opened, is
/// not well-formed XML (with the line and the element) or urdfdom rejects it (with urdfdom's
/// reasons, which it logs through console_bridge, and the line of the joint or link they name;
/// what it logs for a file it takes goes on to the console). Drake's
/// <capsule radius length> collision geometry, which urdfdom does not know, is read as the
/// capsule idiom (a cylinder and a sphere on each end face, appended to the link's collision
/// elements); a bad size or origin of one throws LoadError naming the link and the element.
urdf::ModelInterfaceSharedPtr ParseUrdfFile(const std::string& urdf_path);

/// The error for the file at `path` that tinyxml2 failed to parse as XML: its line (when
/// known), tinyxml2's error name and, for the common ones, what to look for there (the element
/// the file ends inside, an element closed by another's end tag), then "expected a well-formed
/// <expected>".
std::string MalformedXmlError(const std::string& path, const tinyxml2::XMLDocument& doc,
                              const std::string& expected);

/// Whether `xml` is one of xacro's elements (<xacro:macro>, <xacro:include>, a macro's call).
bool IsXacroElement(const tinyxml2::XMLElement* xml);

}  // namespace arm_collision_monitor
