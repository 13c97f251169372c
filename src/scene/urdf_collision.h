// Collision geometry of URDF links as the monitor's primitives.
#pragma once

#include <urdf_model/model.h>

#include <string>
#include <utility>
#include <vector>

#include "arm_collision_monitor/geometry/primitives.h"
#include "mesh_shapes.h"

namespace arm_collision_monitor {

/// The primitives of one link, in the link frame L.
struct UrdfLinkGeometry {
  /// (name, shape): the name is the <collision name=...> or its index in the link; a mesh
  /// fitted with several primitives gives "name/k" (k = 0, 1, ...), or just "k" when it is the
  /// link's only collision element.
  std::vector<std::pair<std::string, Shape>> shapes_L;

  int capsule_count() const;
};

/// Converts every <collision> of `link`:
///  - cylinder (radius r, length L) -> per `cylinder_model` (CylinderShape_L): by default the
///    capsule whose segment is the cylinder's axis (length L) with radius r, which encloses the
///    cylinder (it adds two hemispherical caps of radius r), or its bounding box, or the
///    smaller of the two;
///  - sphere -> a zero-length capsule;  box -> a Box, of size 0 0 0 a point (a sphere of
///    radius 0);
///  - a cylinder plus two spheres of its radius centred on its end faces (the usual way of
///    writing a capsule in URDF) -> that one capsule;
///  - mesh (filename relative to the URDF's folder unless absolute or a URL, scale) -> the
///    primitives `meshes` fits to it, posed by the element's <origin>.
/// Throws LoadError naming `urdf_path` and the link for a negative, zero-size or non-finite
/// dimension, and (MeshFitter::FitFile) for a mesh that cannot be read or fitted.
UrdfLinkGeometry ReadUrdfLinkGeometry(const urdf::Link& link, const std::string& urdf_path,
                                      CylinderModel cylinder_model, MeshFitter* meshes);

/// The xacro the URDF text `urdf_xml` still holds, which urdfdom ignores. Throws LoadError naming
/// `urdf_path` and the element for xacro that changes the model: any in a <link> or <joint> (an
/// element xacro:..., a value with ${...} or $(...)), or in <robot>'s attributes; a condition
/// or block at the top level; a call of a macro the file does not define, or whose macro writes
/// a link or joint (itself or through its calls). Returns "" without xacro, else a start-up
/// warning counting the rest (definitions, harmless calls) and naming the included files, whose
/// links would be missing. An expanded file's xmlns:xacro attribute on <robot> is fine.
std::string CheckXacroLeft(const std::string& urdf_xml, const std::string& urdf_path);

/// Fails unless urdfdom kept every <collision> of every link of the URDF text `urdf_xml` (a
/// Drake <capsule> as the three of its idiom, ParseUrdfFile):
/// urdfdom drops an element it cannot parse (a mesh scale that is not 3 numbers, say) with
/// only a console message, which would leave a link silently unchecked. Throws LoadError naming
/// `urdf_path`, the link and the counts.
void CheckEveryCollisionRead(const std::string& urdf_xml, const urdf::ModelInterface& model,
                             const std::string& urdf_path);

/// A start-up notice for the <visual> and <collision> meshes of `model` named by a path relative
/// to the URDF's folder (neither absolute nor a URL): the monitor reads such collision meshes
/// (it never reads visual ones), rviz's RobotModel and MoveIt, which read robot_description,
/// find neither. Counts them and names the first; "" when there is none.
std::string RelativeMeshNotice(const urdf::ModelInterface& model, const std::string& urdf_path);

}  // namespace arm_collision_monitor
