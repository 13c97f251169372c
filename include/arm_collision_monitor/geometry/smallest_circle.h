// The smallest circle enclosing a set of points in the plane (Welzl's algorithm; de Berg et al.,
// Computational Geometry, section 4.7, in its iterative form).
#pragma once

#include <vector>

#include <Eigen/Core>

namespace arm_collision_monitor {

/// Centre of the smallest circle enclosing `points` (not empty). Expected linear time when the
/// points come in random order; any order gives a correct circle. Rounding can cost tightness:
/// callers that need containment recompute the radius as the exact largest distance.
Eigen::Vector2d SmallestCircleCentre(const std::vector<Eigen::Vector2d>& points);

}  // namespace arm_collision_monitor
