// Triangle meshes from mesh files (STL, COLLADA, OBJ and the other formats assimp reads).
#pragma once

#include <Eigen/Core>
#include <string>

#include "arm_collision_monitor/geometry/mesh_fit.h"

namespace arm_collision_monitor {

/// The triangles of the mesh file whose bytes are `bytes`, in the file's frame M scaled by
/// `scale` (per axis, as URDF's <mesh scale>), in metres. `name` (a path or URL) gives the
/// format by its extension (assimp falls back to sniffing the content).
///
/// Every node's transformation is applied (assimp's scene graph), but the root node's rotation
/// is dropped while its scale and translation are kept, as rviz does since 1.14.x (PRs #1685
/// and #1689): assimp turns a COLLADA file's <up_axis> into a rotation of the root node (to
/// its Y-up convention) and its <unit meter="..."> into the root's scale; ROS meshes are Z-up,
/// so the up-axis rotation is undone and the unit kept. (MoveIt's geometric_shapes clears the
/// whole root transformation, ignoring <unit> as well; rviz shows what the user sees, and a
/// unit other than metres is what the file says its numbers mean.)
///
/// Points and lines are skipped; polygons are triangulated. Vertices at identical positions
/// are merged (STL stores a corner once per facet). Throws LoadError (its message without the
/// caller's context) when assimp cannot read the bytes or they hold no triangle, and, before
/// assimp reads them, when a COLLADA file's <p> holds anything but integers and spaces (assimp
/// 5.2 would append indices until memory runs out).
TriangleMesh ReadMeshFileBytes(const std::string& bytes, const std::string& name,
                               const Eigen::Vector3d& scale);

}  // namespace arm_collision_monitor
