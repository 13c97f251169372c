// Solids by type and size as primitives (see solid_spec.h), through the scene readers' rules.
#include "arm_collision_monitor/scene/solid_spec.h"

#include <cmath>
#include <sstream>

#include "solid_shapes.h"

namespace arm_collision_monitor {
namespace {

// The dimensions a type takes, with their names for messages.
std::vector<const char*> DimensionNames(SolidType type) {
  switch (type) {
    case SolidType::kBox:
      return {"x", "y", "z"};
    case SolidType::kSphere:
      return {"radius"};
    case SolidType::kCylinder:
    case SolidType::kCapsule:
      return {"radius", "length"};
    case SolidType::kMesh:
      break;
  }
  return {};
}

}  // namespace

bool ParseSolidType(const std::string& name, SolidType* type) {
  static const std::pair<const char*, SolidType> kTypes[] = {
      {"box", SolidType::kBox},
      {"sphere", SolidType::kSphere},
      {"cylinder", SolidType::kCylinder},
      {"capsule", SolidType::kCapsule},
      {"mesh", SolidType::kMesh}};
  for (const auto& [n, t] : kTypes) {
    if (name == n) {
      *type = t;
      return true;
    }
  }
  return false;
}

bool MakeSolidShapes_O(const SolidSpec& solid, const SolidShapeOptions& options,
                       std::vector<Shape>* shapes_O, std::string* error) {
  shapes_O->clear();
  const std::vector<const char*> names = DimensionNames(solid.type);
  const std::vector<double>& d = solid.dimensions_m;
  if (d.size() != names.size()) {
    std::ostringstream msg;
    msg << d.size() << " dimensions given, expected " << names.size();
    if (!names.empty()) {
      msg << " (";
      for (std::size_t i = 0; i < names.size(); ++i) msg << (i ? ", " : "") << names[i];
      msg << ", metres)";
    }
    *error = msg.str();
    return false;
  }
  for (std::size_t i = 0; i < d.size(); ++i) {
    // A capsule's segment may have length 0 (a sphere); every other size must be > 0.
    const bool may_be_zero = solid.type == SolidType::kCapsule && i == 1;
    if (!std::isfinite(d[i]) || d[i] < 0.0 || (d[i] == 0.0 && !may_be_zero)) {
      std::ostringstream msg;
      msg << "dimension " << names[i] << " = " << d[i] << ", expected a finite number "
          << (may_be_zero ? ">= 0" : "> 0") << " (metres)";
      *error = msg.str();
      return false;
    }
  }
  const Eigen::Isometry3d X_OO = Eigen::Isometry3d::Identity();
  switch (solid.type) {
    case SolidType::kBox:
      shapes_O->push_back(Box{X_OO, 0.5 * Eigen::Vector3d(d[0], d[1], d[2])});
      return true;
    case SolidType::kSphere:
      shapes_O->push_back(SphereShape_L(X_OO, d[0]));
      return true;
    case SolidType::kCylinder:
      shapes_O->push_back(CylinderShape_L(X_OO, d[0], d[1], options.cylinder_model));
      return true;
    case SolidType::kCapsule:
      shapes_O->push_back(CapsuleShape_L(X_OO, d[0], d[1]));
      return true;
    case SolidType::kMesh:
      break;
  }
  const MeshFit fit = FitMesh(solid.mesh, options.mesh_fit);
  if (fit.check.status != MeshStatus::kOk) {
    *error = std::string("mesh: ") + MeshStatusName(fit.check.status) + ": " + fit.check.message;
    return false;
  }
  *shapes_O = fit.shapes_L;
  return true;
}

}  // namespace arm_collision_monitor
