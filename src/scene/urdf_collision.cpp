#include "urdf_collision.h"

#include <tinyxml2.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <filesystem>

#include "arm_collision_monitor/core/constants.h"
#include "arm_collision_monitor/core/load_error.h"
#include "arm_collision_monitor/kinematics/urdf_conversions.h"
#include "solid_shapes.h"

namespace arm_collision_monitor {
namespace {

// One <collision> element before the capsule idiom is recognised.
struct CollisionElement {
  std::string name;
  std::string where;  // "urdf: link 'x' <collision> i"
  decltype(urdf::Geometry::type) type = urdf::Geometry::SPHERE;
  Eigen::Isometry3d X_LC = Eigen::Isometry3d::Identity();  // collision origin C in link L
  double radius_m = 0.0;
  double length_m = 0.0;
  Eigen::Vector3d size_m = Eigen::Vector3d::Zero();
  std::string mesh_filename;
  Eigen::Vector3d mesh_scale = Eigen::Vector3d::Ones();
  bool is_absorbed = false;  // a sphere that is an end cap of a capsule-idiom cylinder
  bool is_capsule = false;   // a cylinder whose end caps were absorbed: exactly a capsule
};

// Element i of a link's <collision> list, its sizes checked; `where` names it in errors.
CollisionElement ReadCollisionElement(const urdf::Collision& collision, std::size_t i,
                                      const std::string& where_element) {
  CollisionElement e;
  e.where = where_element;
  const std::string where = e.where + ": ";
  if (!collision.geometry) throw LoadError(where + "expected a <geometry>");
  e.name = collision.name.empty() ? std::to_string(i) : collision.name;
  e.type = collision.geometry->type;
  e.X_LC = UrdfPoseToIsometry(collision.origin);
  if (!e.X_LC.matrix().allFinite()) throw LoadError(where + "<origin> must be finite");
  switch (e.type) {
    case urdf::Geometry::SPHERE: {
      e.radius_m = static_cast<const urdf::Sphere&>(*collision.geometry).radius;
      if (!std::isfinite(e.radius_m) || e.radius_m < 0.0) {
        throw LoadError(where + "<sphere radius> must be a finite number >= 0");
      }
      break;
    }
    case urdf::Geometry::CYLINDER: {
      const auto& cylinder = static_cast<const urdf::Cylinder&>(*collision.geometry);
      e.radius_m = cylinder.radius;
      e.length_m = cylinder.length;
      if (!std::isfinite(e.radius_m) || e.radius_m < 0.0 || !std::isfinite(e.length_m) ||
          e.length_m < 0.0) {
        throw LoadError(where + "<cylinder radius, length> must be finite numbers >= 0");
      }
      break;
    }
    case urdf::Geometry::BOX: {
      const urdf::Vector3& dim = static_cast<const urdf::Box&>(*collision.geometry).dim;
      e.size_m = Eigen::Vector3d(dim.x, dim.y, dim.z);
      if ((e.size_m.array() == 0.0).all()) {
        // A point, as the sphere of radius 0 is (kinova-ros writes its arms' end-effector
        // frames so; FCL and so MoveIt read it as a box of no extent).
        e.type = urdf::Geometry::SPHERE;
        e.radius_m = 0.0;
        break;
      }
      if (!e.size_m.allFinite() || (e.size_m.array() <= 0.0).any()) {
        throw LoadError(where + "<box size> must be 3 finite numbers > 0, or all 0 (a point)");
      }
      break;
    }
    case urdf::Geometry::MESH: {
      const auto& mesh = static_cast<const urdf::Mesh&>(*collision.geometry);
      e.mesh_filename = mesh.filename;
      e.mesh_scale = Eigen::Vector3d(mesh.scale.x, mesh.scale.y, mesh.scale.z);
      break;
    }
    default:
      throw LoadError(where + "unknown geometry (expected box, cylinder, sphere or mesh)");
  }
  return e;
}

// Marks the two spheres (radius r, centred on the cylinder's end faces) of the capsule idiom, and
// the cylinder as their capsule.
void AbsorbEndSpheres(int cylinder_index, std::vector<CollisionElement>* all) {
  const CollisionElement cylinder = (*all)[cylinder_index];
  // The URDF cylinder axis is z of its origin frame.
  const auto [end0_L, end1_L] = CylinderAxisEnds_L(cylinder.X_LC, cylinder.length_m);
  const double tolerance_m = kCapsuleIdiomMatchRel * (cylinder.length_m + cylinder.radius_m);
  auto find_cap = [&](const Eigen::Vector3d& end_L, int skip) {
    for (int i = 0; i < static_cast<int>(all->size()); ++i) {
      const CollisionElement& e = (*all)[i];
      if (i == skip || e.is_absorbed || e.type != urdf::Geometry::SPHERE) continue;
      if (std::abs(e.radius_m - cylinder.radius_m) <= tolerance_m &&
          (e.X_LC.translation() - end_L).norm() <= tolerance_m) {
        return i;
      }
    }
    return -1;
  };
  const int cap0 = find_cap(end0_L, -1);
  if (cap0 < 0) return;
  const int cap1 = find_cap(end1_L, cap0);
  if (cap1 < 0) return;
  (*all)[cap0].is_absorbed = true;
  (*all)[cap1].is_absorbed = true;
  (*all)[cylinder_index].is_capsule = true;
}

}  // namespace

int UrdfLinkGeometry::capsule_count() const {
  int count = 0;
  for (const auto& named : shapes_L) count += std::holds_alternative<Capsule>(named.second);
  return count;
}

UrdfLinkGeometry ReadUrdfLinkGeometry(const urdf::Link& link, const std::string& urdf_path,
                                      CylinderModel cylinder_model, MeshFitter* meshes) {
  std::vector<urdf::CollisionSharedPtr> collisions = link.collision_array;
  if (collisions.empty() && link.collision) collisions.push_back(link.collision);

  std::vector<CollisionElement> elements;
  for (std::size_t i = 0; i < collisions.size(); ++i) {
    const std::string where =
        urdf_path + ": link '" + link.name + "' <collision> " + std::to_string(i) + " (from 0)";
    elements.push_back(ReadCollisionElement(*collisions[i], i, where));
  }

  for (int i = 0; i < static_cast<int>(elements.size()); ++i) {
    if (elements[i].type == urdf::Geometry::CYLINDER) AbsorbEndSpheres(i, &elements);
  }

  const int element_count = static_cast<int>(std::count_if(
      elements.begin(), elements.end(), [](const CollisionElement& e) { return !e.is_absorbed; }));
  const std::string urdf_dir = std::filesystem::path(urdf_path).parent_path().string();
  UrdfLinkGeometry geometry;
  for (const CollisionElement& e : elements) {
    if (e.is_absorbed) continue;
    switch (e.type) {
      case urdf::Geometry::SPHERE:
        geometry.shapes_L.emplace_back(e.name, SphereShape_L(e.X_LC, e.radius_m));
        break;
      case urdf::Geometry::CYLINDER:
        geometry.shapes_L.emplace_back(
            e.name, CylinderShape_L(e.X_LC, e.radius_m, e.length_m,
                                    e.is_capsule ? CylinderModel::kCapsule : cylinder_model));
        break;
      case urdf::Geometry::BOX:
        geometry.shapes_L.emplace_back(e.name, Box{e.X_LC, 0.5 * e.size_m});
        break;
      default: {  // MESH
        const std::vector<Shape> shapes_C =
            meshes->FitFile(e.mesh_filename, urdf_dir, e.mesh_scale, e.where);
        for (std::size_t k = 0; k < shapes_C.size(); ++k) {
          const std::string name = shapes_C.size() == 1 ? e.name
                                   : element_count == 1 ? std::to_string(k)
                                                        : e.name + "/" + std::to_string(k);
          geometry.shapes_L.emplace_back(name, TransformShape(e.X_LC, shapes_C[k]));
        }
        break;
      }
    }
  }
  return geometry;
}

namespace {

// `xml` as "<name attribute='value'>" for its first attribute holding ${...} or $(...), as
// "<name>" when it is an xacro element; "" if neither.
std::string XacroMark(const tinyxml2::XMLElement* xml) {
  const std::string name = xml->Name();
  if (IsXacroElement(xml)) return "<" + name + ">";
  for (const tinyxml2::XMLAttribute* a = xml->FirstAttribute(); a != nullptr; a = a->Next()) {
    const std::string value = a->Value();
    if (value.find("${") != std::string::npos || value.find("$(") != std::string::npos) {
      return "<" + name + " " + a->Name() + "='" + value + "'>";
    }
  }
  return "";
}

// The first element of `xml`'s subtree (itself included) that XacroMark marks; null if none.
const tinyxml2::XMLElement* FirstXacroIn(const tinyxml2::XMLElement* xml) {
  if (!XacroMark(xml).empty()) return xml;
  for (const tinyxml2::XMLElement* child = xml->FirstChildElement(); child != nullptr;
       child = child->NextSiblingElement()) {
    if (const tinyxml2::XMLElement* found = FirstXacroIn(child)) return found;
  }
  return nullptr;
}

using MacroBodies = std::map<std::string, const tinyxml2::XMLElement*>;

// Why a call of the macro `name` could change what urdfdom reads ("" when it cannot): it is not
// defined in the file (an included one may write links), or it writes a link or joint, or
// holds an include, a condition or another such call. Definitions in it are harmless. Each
// macro's verdict is kept in `harms` (a macro met again while its own is pending calls itself).
std::string MacroCallHarm(const std::string& name, const MacroBodies& macros, int depth,
                          std::map<std::string, std::string>* harms) {
  const auto known = harms->find(name);
  if (known != harms->end()) return known->second;
  const auto macro = macros.find(name);
  if (macro == macros.end()) return "a macro this file does not define";
  if (depth > kXacroMaxMacroDepth) return "macros calling each other too deep";
  (*harms)[name] = "its macro '" + name + "' calls itself";  // while pending
  std::string found;
  for (const tinyxml2::XMLElement* child = macro->second->FirstChildElement();
       child != nullptr && found.empty(); child = child->NextSiblingElement()) {
    const std::string child_name = child->Name();
    if (child_name == "link" || child_name == "joint") {
      found = "its macro '" + name + "' writes a <" + child_name + ">";
    } else if (IsXacroElement(child)) {
      const std::string directive = child_name.substr(6);  // after "xacro:" (IsXacroElement)
      if (directive == "macro" || directive == "property" || directive == "arg") continue;
      if (directive == "include" || directive == "if" || directive == "unless" ||
          directive == "insert_block" || directive == "element" || directive == "call") {
        found = "its macro '" + name + "' holds <" + child_name + ">";
      } else {
        found = MacroCallHarm(directive, macros, depth + 1, harms);
      }
    }
  }
  (*harms)[name] = found;
  return found;
}

}  // namespace

std::string CheckXacroLeft(const std::string& urdf_xml, const std::string& urdf_path) {
  tinyxml2::XMLDocument doc;
  if (doc.Parse(urdf_xml.c_str(), urdf_xml.size()) != tinyxml2::XML_SUCCESS) {
    return "";  // urdfdom says why
  }
  const tinyxml2::XMLElement* robot = doc.RootElement();
  if (robot == nullptr) return "";
  // `at` (line `at`'s, in `owner`: "link 'x': " or ""), as `found`, for reason `why`.
  auto refuse = [&](const tinyxml2::XMLElement* at, const std::string& owner,
                    const std::string& found, const std::string& why) {
    throw LoadError(urdf_path + ":" + std::to_string(at->GetLineNum()) + ": " + owner + found +
                    why +
                    ": xacro left in the file that changes the model (expected a plain URDF: "
                    "expand it with xacro first, on a machine with ROS's xacro (Debian's ROS has "
                    "none), e.g. rosrun xacro xacro robot.urdf.xacro > robot.urdf)");
  };
  const std::string robot_mark = XacroMark(robot);
  if (!robot_mark.empty()) refuse(robot, "", robot_mark, "");
  MacroBodies macros;
  for (const tinyxml2::XMLElement* child = robot->FirstChildElement("xacro:macro");
       child != nullptr; child = child->NextSiblingElement("xacro:macro")) {
    const char* name = child->Attribute("name");
    if (name != nullptr) macros[name] = child;
  }
  // What urdfdom reads (links and joints) must hold no xacro; the rest it ignores, and so may
  // the monitor, but for calls of macros that could write links or joints.
  std::map<std::string, std::string> harms;
  int definitions = 0;
  int calls = 0;
  std::vector<std::string> includes;
  for (const tinyxml2::XMLElement* child = robot->FirstChildElement(); child != nullptr;
       child = child->NextSiblingElement()) {
    const std::string name = child->Name();
    if (!IsXacroElement(child)) {
      if (name == "link" || name == "joint") {
        if (const tinyxml2::XMLElement* found = FirstXacroIn(child)) {
          const char* owner = child->Attribute("name");
          refuse(found, name + " '" + (owner != nullptr ? owner : "") + "': ", XacroMark(found),
                 "");
        }
      }
      continue;
    }
    const std::string directive = name.substr(6);  // after "xacro:" (IsXacroElement)
    if (directive == "macro" || directive == "property" || directive == "arg") {
      ++definitions;
    } else if (directive == "include") {
      const char* file = child->Attribute("filename");
      includes.push_back(file != nullptr ? file : "");
    } else if (directive == "if" || directive == "unless" || directive == "insert_block" ||
               directive == "element" || directive == "call") {
      refuse(child, "", "<" + name + ">", "");
    } else {
      const std::string harm = MacroCallHarm(directive, macros, 0, &harms);
      if (!harm.empty()) refuse(child, "", "<" + name + ">", " (" + harm + ")");
      ++calls;
    }
  }
  if (definitions == 0 && calls == 0 && includes.empty()) return "";
  std::string text = urdf_path + ": xacro left in the file, ignored as urdfdom ignores it:";
  if (definitions > 0) {
    text += " " + std::to_string(definitions) + " macro, property or arg definition(s);";
  }
  if (calls > 0) {
    text += " " + std::to_string(calls) + " call(s) of its macros that write no link or joint;";
  }
  if (!includes.empty()) {
    text += " " + std::to_string(includes.size()) + " <xacro:include> not read (" +
            QuotedNames(includes) +
            "): links or collision geometry an included file adds are not in the model "
            "(expand the file with xacro if it adds any);";
  }
  text.pop_back();
  return text;
}

void CheckEveryCollisionRead(const std::string& urdf_xml, const urdf::ModelInterface& model,
                             const std::string& urdf_path) {
  tinyxml2::XMLDocument doc;
  if (doc.Parse(urdf_xml.c_str(), urdf_xml.size()) != tinyxml2::XML_SUCCESS) return;  // urdfdom's
  const tinyxml2::XMLElement* robot = doc.RootElement();
  if (robot == nullptr) return;
  for (const tinyxml2::XMLElement* xml = robot->FirstChildElement("link"); xml != nullptr;
       xml = xml->NextSiblingElement("link")) {
    const char* name = xml->Attribute("name");
    const urdf::LinkConstSharedPtr link = name == nullptr ? nullptr : model.getLink(name);
    if (link == nullptr) continue;
    // A Drake <capsule> is read as three elements (ParseUrdfFile: the capsule idiom).
    std::size_t written = 0;
    int index = 0;
    for (const tinyxml2::XMLElement* c = xml->FirstChildElement("collision"); c != nullptr;
         c = c->NextSiblingElement("collision"), ++index) {
      const tinyxml2::XMLElement* geometry = c->FirstChildElement("geometry");
      written += geometry != nullptr && geometry->FirstChildElement("capsule") != nullptr ? 3 : 1;
      // urdfdom reads the first <geometry> of a <collision> and the first shape in it, and
      // drops any other without a word.
      int geometries = 0, shapes = 0;
      for (const tinyxml2::XMLElement* g = geometry; g != nullptr;
           g = g->NextSiblingElement("geometry")) {
        ++geometries;
      }
      for (const tinyxml2::XMLElement* shape =
               geometry != nullptr ? geometry->FirstChildElement() : nullptr;
           shape != nullptr; shape = shape->NextSiblingElement()) {
        ++shapes;
      }
      if (geometries > 1 || shapes > 1) {
        throw LoadError(urdf_path + ": link '" + link->name + "': its <collision> element " +
                        std::to_string(index) + " (from 0) in the file holds " +
                        (geometries > 1 ? std::to_string(geometries) + " <geometry> elements"
                                        : "a <geometry> of " + std::to_string(shapes) +
                                              " shapes") +
                        "; urdfdom reads only the first: give each shape a <collision> of its "
                        "own");
      }
    }
    const std::size_t read =
        link->collision_array.empty() ? (link->collision ? 1 : 0) : link->collision_array.size();
    if (read != written) {
      throw LoadError(urdf_path + ": link '" + link->name + "' has " + std::to_string(written) +
                      " <collision> elements but urdfdom read " + std::to_string(read) +
                      " (it drops one it cannot parse; its console message says why, e.g. a "
                      "mesh scale that is not 3 numbers); expected every element well formed");
    }
  }
}

std::string RelativeMeshNotice(const urdf::ModelInterface& model, const std::string& urdf_path) {
  int count = 0;
  std::string first;
  const auto note = [&](const urdf::GeometrySharedPtr& geometry, const std::string& link) {
    if (!geometry || geometry->type != urdf::Geometry::MESH) return;
    const std::string& name = static_cast<const urdf::Mesh&>(*geometry).filename;
    if (name.find("://") != std::string::npos || std::filesystem::path(name).is_absolute()) {
      return;
    }
    if (count++ == 0) first = "'" + name + "' of link '" + link + "'";
  };
  for (const auto& [name, link] : model.links_) {
    for (const urdf::VisualSharedPtr& visual : link->visual_array) note(visual->geometry, name);
    if (link->visual_array.empty() && link->visual) note(link->visual->geometry, name);
    for (const urdf::CollisionSharedPtr& c : link->collision_array) note(c->geometry, name);
    if (link->collision_array.empty() && link->collision) note(link->collision->geometry, name);
  }
  if (count == 0) return "";
  return urdf_path + ": " + std::to_string(count) + " mesh" + (count == 1 ? "" : "es") +
         " named by a path relative to the URDF's folder (" + first + (count == 1 ? "" : ", ...") +
         "): the monitor finds collision meshes there, but rviz's RobotModel and MoveIt, which " +
         "read robot_description, do not; write package://<package>/<path> (or " +
         "file:///<absolute path>) to see the robot in rviz";
}

}  // namespace arm_collision_monitor
