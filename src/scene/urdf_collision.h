// Collision geometry of URDF links as the monitor's primitives.
#pragma once

#include <urdf_model/model.h>

#include <string>
#include <utility>
#include <vector>

#include "arm_collision_monitor/geometry/primitives.h"

namespace arm_collision_monitor {

/// The primitives of one link, in the link frame L, and any geometry that has none.
struct UrdfLinkGeometry {
  /// (name, shape): the name is the <collision name=...> or its index in the link.
  std::vector<std::pair<std::string, Shape>> shapes_L;
  /// Filename of the first <mesh> collision geometry, "" if none: a mesh has no primitive, the
  /// scene file must replace or ignore the link.
  std::string mesh_filename;

  int capsule_count() const;
};

/// Converts every <collision> of `link`:
///  - cylinder (radius r, length L) -> the capsule whose segment is the cylinder's axis (length
///    L) with radius r: it encloses the cylinder (it adds two hemispherical caps of radius r);
///  - sphere -> a zero-length capsule;  box -> a Box;
///  - a cylinder plus two spheres of its radius centred on its end faces (the usual way of
///    writing a capsule in URDF) -> that one capsule.
/// Throws LoadError naming `urdf_path` and the link for a negative, zero-size or non-finite
/// dimension.
UrdfLinkGeometry ReadUrdfLinkGeometry(const urdf::Link& link, const std::string& urdf_path);

}  // namespace arm_collision_monitor
