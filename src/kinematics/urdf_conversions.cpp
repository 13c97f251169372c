#include "arm_collision_monitor/kinematics/urdf_conversions.h"

#include <tinyxml2.h>
#include <urdf_parser/urdf_parser.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <vector>

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

namespace {

// Attribute `name` of `xml` as a finite number >= 0, else a LoadError naming `where`.
double NonNegativeAttribute(const tinyxml2::XMLElement& xml, const char* name,
                            const std::string& where) {
  double value = 0.0;
  if (xml.QueryDoubleAttribute(name, &value) != tinyxml2::XML_SUCCESS || !std::isfinite(value) ||
      value < 0.0) {
    throw LoadError(where + ": <capsule radius, length> must be finite numbers >= 0");
  }
  return value;
}

// "x y z" to round-trip.
std::string XyzText(const urdf::Vector3& v) {
  char text[96];
  std::snprintf(text, sizeof(text), "%.17g %.17g %.17g", v.x, v.y, v.z);
  return text;
}

// Rewrites each <collision> of `link` whose geometry is Drake's <capsule radius length> (along z
// of its <origin>, `length` between the centres of its end spheres), which urdfdom cannot parse
// (it drops the link's collision elements from there on), as the capsule idiom: a <cylinder> of
// that radius and length, and a <sphere> of the radius on each end face, appended to the link
// (the other elements keep their indices). The scene loader reads the idiom as that capsule.
void RewriteDrakeCapsules(const std::string& urdf_path, tinyxml2::XMLElement* link) {
  const char* link_name = link->Attribute("name");
  int index = 0;
  std::vector<tinyxml2::XMLElement*> caps;
  for (tinyxml2::XMLElement* c = link->FirstChildElement("collision"); c != nullptr;
       c = c->NextSiblingElement("collision"), ++index) {
    tinyxml2::XMLElement* geometry = c->FirstChildElement("geometry");
    tinyxml2::XMLElement* capsule =
        geometry == nullptr ? nullptr : geometry->FirstChildElement("capsule");
    if (capsule == nullptr) continue;
    const std::string where = urdf_path + ": link '" + (link_name ? link_name : "") +
                              "' <collision> " + std::to_string(index) + " <capsule>";
    const double radius_m = NonNegativeAttribute(*capsule, "radius", where);
    const double length_m = NonNegativeAttribute(*capsule, "length", where);
    urdf::Pose origin;
    const tinyxml2::XMLElement* origin_xml = c->FirstChildElement("origin");
    try {
      if (origin_xml != nullptr && origin_xml->Attribute("xyz") != nullptr) {
        origin.position.init(origin_xml->Attribute("xyz"));
      }
      if (origin_xml != nullptr && origin_xml->Attribute("rpy") != nullptr) {
        urdf::Vector3 rpy;
        rpy.init(origin_xml->Attribute("rpy"));
        origin.rotation.setFromRPY(rpy.x, rpy.y, rpy.z);
      }
    } catch (const std::exception& e) {
      throw LoadError(where + ": <origin>: " + e.what());
    }
    capsule->SetName("cylinder");
    for (const double side : {-0.5, 0.5}) {
      const urdf::Vector3 offset =
          origin.rotation * urdf::Vector3(0.0, 0.0, side * length_m);
      tinyxml2::XMLElement* cap = link->GetDocument()->NewElement("collision");
      cap->InsertNewChildElement("origin")->SetAttribute(
          "xyz", XyzText(urdf::Vector3(origin.position.x + offset.x,
                                       origin.position.y + offset.y,
                                       origin.position.z + offset.z))
                     .c_str());
      cap->InsertNewChildElement("geometry")->InsertNewChildElement("sphere")->SetAttribute(
          "radius", radius_m);
      caps.push_back(cap);
    }
  }
  for (tinyxml2::XMLElement* cap : caps) link->InsertEndChild(cap);
}

}  // namespace

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
  tinyxml2::XMLElement* robot = doc.RootElement();
  for (tinyxml2::XMLElement* link = robot ? robot->FirstChildElement("link") : nullptr;
       link != nullptr; link = link->NextSiblingElement("link")) {
    RewriteDrakeCapsules(urdf_path, link);
  }
  tinyxml2::XMLPrinter printer;
  doc.Print(&printer);
  const urdf::ModelInterfaceSharedPtr model = urdf::parseURDF(printer.CStr());
  if (!model) {
    throw LoadError(urdf_path +
                    ": not a valid URDF (urdfdom rejected it; its error line above, the one not "
                    "naming urdfdom's own source, names the element); expected a <robot> whose "
                    "links and joints form one tree");
  }
  return model;
}

}  // namespace arm_collision_monitor
