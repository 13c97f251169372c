#include "arm_collision_monitor/kinematics/urdf_conversions.h"

#include <tinyxml2.h>
#include <urdf_parser/urdf_parser.h>

#include <fstream>
#include <sstream>

#include "arm_collision_monitor/core/load_error.h"

namespace arm_collision_monitor {

Eigen::Isometry3d UrdfPoseToIsometry(const urdf::Pose& pose) {
  double qx = 0.0, qy = 0.0, qz = 0.0, qw = 1.0;
  pose.rotation.getQuaternion(qx, qy, qz, qw);
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = Eigen::Quaterniond(qw, qx, qy, qz).normalized().toRotationMatrix();
  X.translation() = Eigen::Vector3d(pose.position.x, pose.position.y, pose.position.z);
  return X;
}

urdf::ModelInterfaceSharedPtr ParseUrdfFile(const std::string& urdf_path) {
  std::ifstream in(urdf_path);
  if (!in) {
    throw LoadError(urdf_path + ": cannot open the URDF file (expected a readable URDF/XML file" +
                    RelativePathNote(urdf_path) + ")");
  }
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string xml = buffer.str();
  // urdfdom reports malformed XML without a line ("Error reading end tag"): tinyxml2 names it.
  tinyxml2::XMLDocument doc;
  if (doc.Parse(xml.c_str(), xml.size()) != tinyxml2::XML_SUCCESS) {
    throw LoadError(urdf_path + ":" + std::to_string(doc.ErrorLineNum()) +
                    ": malformed XML: " + doc.ErrorStr() + " (expected a well-formed URDF)");
  }
  const urdf::ModelInterfaceSharedPtr model = urdf::parseURDF(xml);
  if (!model) {
    throw LoadError(urdf_path +
                    ": not a valid URDF (urdfdom rejected it; its error line above, the one not "
                    "naming urdfdom's own source, names the element); expected a <robot> whose "
                    "links and joints form one tree");
  }
  return model;
}

}  // namespace arm_collision_monitor
