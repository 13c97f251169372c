// Solids described by type and size (box, sphere, cylinder, capsule, triangle mesh) and how they
// become the monitor's primitives, per the scene file's cylinder_model and mesh_fit options. For
// the objects added at run time (Monitor::AddObject, the node's ~add_object service); the scene
// file's readers apply the same rules (src/scene/solid_shapes.h).
#pragma once

#include <string>
#include <vector>

#include "arm_collision_monitor/geometry/mesh_fit.h"
#include "arm_collision_monitor/geometry/primitives.h"

namespace arm_collision_monitor {

/// How a cylinder (and a cone, through its bounding cylinder) becomes a primitive. Each encloses
/// it: the capsule adds two hemispherical caps of the cylinder's radius on its end faces; the box
/// is the cylinder's tight bounding box (it adds the four edges' corners); kTighter takes, per
/// cylinder, whichever of the two has the smaller volume (the box for a length below about 4.9
/// radii: a disc or a short link; the capsule for a longer one).
enum class CylinderModel { kCapsule, kBox, kTighter };

/// The scene file's cylinder_model and mesh_fit (config/scene.yaml).
struct SolidShapeOptions {
  CylinderModel cylinder_model = CylinderModel::kCapsule;
  MeshFitOptions mesh_fit;  ///< default: one capsule
};

enum class SolidType { kBox, kSphere, kCylinder, kCapsule, kMesh };

/// A solid in its own frame O (centred on O's origin; a cylinder's or capsule's axis along O's
/// z; a mesh's vertices in O, metres).
struct SolidSpec {
  SolidType type = SolidType::kBox;
  /// box: full edge lengths {x, y, z}; sphere: {radius}; cylinder, capsule: {radius, length}
  /// (a capsule's length is its segment's, without the caps); mesh: none.
  std::vector<double> dimensions_m;
  TriangleMesh mesh;  ///< mesh only
};

/// "box", "sphere", "cylinder", "capsule" or "mesh"; false for any other name.
bool ParseSolidType(const std::string& name, SolidType* type);

/// The primitives of `solid` in O: one for a box, sphere, capsule or cylinder (per
/// options.cylinder_model), FitMesh's for a mesh (per options.mesh_fit; allocates, may take
/// milliseconds). False with a message in `error` (naming the dimension or the mesh's fault) for
/// a wrong number of dimensions, a non-finite or non-positive size (a capsule's length may be
/// 0), a mesh with dimensions, or a mesh CheckMesh refuses.
bool MakeSolidShapes_O(const SolidSpec& solid, const SolidShapeOptions& options,
                       std::vector<Shape>* shapes_O, std::string* error);

}  // namespace arm_collision_monitor
