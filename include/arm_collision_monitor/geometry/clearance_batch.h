// The narrow phase's batched pre-test: certified lower bounds on the distances of many primitive
// pairs at once, in single precision, so that only the pairs it cannot settle pay for the exact
// double distance (geometry/distance.h) and its witness points.
//
// Every primitive is held as a "rounded box" in float: a centre c, three edge vectors u_0..u_2
// with half lengths h_0..h_2 (the points c + sum t_i u_i, |t_i| <= h_i), grown by a radius r.
// A box is its centre, its frame's axes and half extents with r = 0; a capsule is its segment's
// midpoint, the segment's direction and half length (u_1 = u_2 = 0) with its radius; a sphere
// (zero-length capsule) has h = 0. One branch-free kernel then serves every pair type.
//
// A pair's bound is the larger of two lower bounds, both valid whatever the float arithmetic
// picks as directions (only their rounding needs the margin):
// - bounding spheres: |c_B - c_A| less each primitive's enclosing radius (sum of h_i, plus r);
// - a separating direction: the gap between the two primitives' projections on a direction n
//   (support functions: c.n +- (sum |u_i.n| h_i + r)) bounds their distance from below for any
//   n. n is taken from the pair of points that three alternating projections (clamping a point
//   into one core, then into the other; von Neumann's alternating projections onto convex sets)
//   reach; the nearer they come to the closest pair, the nearer the bound comes to the distance.
// The float rounding of the inputs and of the arithmetic is then taken off the bound:
// kClearanceBatchMarginUlps units of 2^-24 times the pair's length scale (core/constants.h, with
// its derivation), so the bound never exceeds the exact distance of the double shapes.
//
// Layout: each primitive's 16 floats fill one 64-byte line (pairs name primitives in any order,
// so a pair reads two lines). The kernel takes 4 pairs at a time and runs its arithmetic lane by
// lane without branches; the compiler turns that lane loop into vector instructions, one lane
// per pair, loading each field of the 4 primitives element by element (SSE has no gather).
#pragma once

#include <cstddef>
#include <cstdint>

#include "arm_collision_monitor/geometry/primitives.h"

namespace arm_collision_monitor {

/// One primitive in single precision (see the file comment), world frame, metres.
struct alignas(64) FloatPrimitive {
  float c_W[3] = {0.0f, 0.0f, 0.0f};     ///< centre
  float u_W[3][3] = {};                  ///< edge directions (unit, or zero for a capsule's)
  float half_m[3] = {0.0f, 0.0f, 0.0f};  ///< half lengths along u_W[i], >= 0
  float radius_m = 0.0f;                 ///< >= 0
};
static_assert(sizeof(FloatPrimitive) == 64, "one cache line per primitive");

/// `shape_W` rounded to single precision into `f` (each number rounded once from its double
/// value); NaN radius beyond the supported lengths (kClearanceBatchMaxLength_m).
void ToFloatPrimitive(const Shape& shape_W, FloatPrimitive* f);

/// For each of the `count` pairs k, (primitives[a[k]], primitives[b[k]]): lower_bound_m[k] <=
/// the exact distance of the double shapes the two were made from (ToFloatPrimitive), the
/// rounding margin already taken off; negative when the bound says nothing (overlapping or
/// close shapes). A primitive with NaN or a length beyond kClearanceBatchMaxLength_m gives -inf
/// (never a false "clear"). Allocates nothing.
void ComputeClearanceLowerBounds(const FloatPrimitive* primitives, const PrimitiveId* a,
                                 const PrimitiveId* b, std::size_t count,
                                 double* lower_bound_m);

}  // namespace arm_collision_monitor
