// Small helpers shared by the broad-phase implementations (internal to the module).
#pragma once

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "arm_collision_monitor/broadphase/broad_phase.h"

namespace arm_collision_monitor {

/// The pair {a, b} with the smaller id first.
inline CandidatePair MakeOrderedPair(PrimitiveId a, PrimitiveId b) {
  return a < b ? CandidatePair{a, b} : CandidatePair{b, a};
}

/// True when the matrix marks (a, b) compatible; ids outside the matrix are never compatible.
inline bool IsCompatiblePair(const CompatibilityMatrix& compatible, PrimitiveId a,
                             PrimitiveId b) {
  return a < compatible.size() && b < compatible.size() && compatible.AreCompatible(a, b);
}

/// Removes element `index` of a dense id list in O(1) by moving the last element into its
/// place; `slot` maps each id to its index in the list and is kept in step.
inline void SwapRemove(std::vector<PrimitiveId>* list, std::vector<std::uint32_t>* slot,
                       std::uint32_t index) {
  const PrimitiveId last = list->back();
  (*list)[index] = last;
  (*slot)[last] = index;
  list->pop_back();
}

/// Validate()'s failure: sets *why (when given) to `message` and returns false.
inline bool FailValidation(std::string* why, const std::string& message) {
  if (why != nullptr) *why = message;
  return false;
}

/// Edge (m) of the cube a broad phase spans: the largest edge of `world_W`, or 0 when that is
/// not a positive finite length.
inline double WorldCubeEdge(const Aabb& world_W) {
  const double edge_m = (world_W.max_W - world_W.min_W).maxCoeff();
  return std::isfinite(edge_m) && edge_m > 0.0 ? edge_m : 0.0;
}

/// Coordinate of lattice point `units` on one axis: origin + units * spacing. Every cell
/// boundary is computed by this one expression, so two cells that share a boundary compute
/// bit-identical coordinates for it and closed-box tests agree on which cells a box touches.
inline double LatticeCoordinate(double origin_m, std::uint32_t units, double spacing_m) {
  return origin_m + static_cast<double>(units) * spacing_m;
}

}  // namespace arm_collision_monitor
