// Every tolerance and constant of the core, in one place. Each has units, a typical value and
// the reason it exists. Prefer tolerances relative to the lengths involved (the *_rel ones,
// dimensionless, multiplied by a length scale of the inputs) over absolute ones.
#pragma once

#include <cstdint>

namespace arm_collision_monitor {

// ---------------------------------------------------------------------------------------------
// Geometry (distance routines)
// ---------------------------------------------------------------------------------------------

// ---------------------------------------------------------------------------------------------
// Broad phase (octree, grid)
// ---------------------------------------------------------------------------------------------

// ---------------------------------------------------------------------------------------------
// Kinematics and scene loading
// ---------------------------------------------------------------------------------------------

// ---------------------------------------------------------------------------------------------
// Monitor
// ---------------------------------------------------------------------------------------------

}  // namespace arm_collision_monitor
