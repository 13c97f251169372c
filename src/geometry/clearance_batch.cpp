// The batched single-precision clearance bounds (see clearance_batch.h).
#include "arm_collision_monitor/geometry/clearance_batch.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "arm_collision_monitor/core/constants.h"

namespace arm_collision_monitor {
namespace {

/// Pairs per block: one SSE register of floats per field (more lanes only waste work
/// on the short batches of a cycle: a few to a few tens of pairs).
constexpr int kLanes = 4;
/// The unit roundoff of float (2^-24), the unit of kClearanceBatchMarginUlps.
constexpr float kFloatUnitRoundoff = 5.9604644775390625e-8f;

/// Three floats of one lane, written out so that the lane loop has no inner loops.
struct V3 {
  float x, y, z;
};
inline V3 operator-(V3 a, V3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline V3 operator+(V3 a, V3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline V3 operator*(float t, V3 a) { return {t * a.x, t * a.y, t * a.z}; }
inline float Dot(V3 a, V3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline float Clamp(float v, float half) {
  const float above = v > -half ? v : -half;
  return above < half ? above : half;
}

/// One primitive's fields as the lane loop reads them.
struct LanePrimitive {
  V3 c, u0, u1, u2;
  float h0, h1, h2, r;
};
inline LanePrimitive Load(const FloatPrimitive& p) {
  return {{p.c_W[0], p.c_W[1], p.c_W[2]},
          {p.u_W[0][0], p.u_W[0][1], p.u_W[0][2]},
          {p.u_W[1][0], p.u_W[1][1], p.u_W[1][2]},
          {p.u_W[2][0], p.u_W[2][1], p.u_W[2][2]},
          p.half_m[0], p.half_m[1], p.half_m[2], p.radius_m};
}

/// The point of the primitive's core (the box without its radius) nearest to x in the core's
/// own metric (clamped edge coordinates): the step of the alternating projections.
inline V3 ClampIntoCore(const LanePrimitive& s, V3 x) {
  const V3 w = x - s.c;
  return s.c + Clamp(Dot(s.u0, w), s.h0) * s.u0 + Clamp(Dot(s.u1, w), s.h1) * s.u1 +
         Clamp(Dot(s.u2, w), s.h2) * s.u2;
}

/// Half width of the primitive along unit direction n: sum |u_i.n| h_i + r.
inline float Reach(const LanePrimitive& s, V3 n) {
  return std::abs(Dot(s.u0, n)) * s.h0 + std::abs(Dot(s.u1, n)) * s.h1 +
         std::abs(Dot(s.u2, n)) * s.h2 + s.r;
}

inline float SumAbs(V3 a) { return std::abs(a.x) + std::abs(a.y) + std::abs(a.z); }

/// The certified bounds of one block of pairs (primitives[ia[l]], primitives[ib[l]]) (see the
/// header), lane by lane without branches: the compiler vectorises the lane loop, loading each
/// field of the kLanes primitives element by element.
void BoundBlock(const FloatPrimitive* primitives, const PrimitiveId ia[kLanes],
                const PrimitiveId ib[kLanes], float bound_m[kLanes]) {
  for (int l = 0; l < kLanes; ++l) {
    const LanePrimitive A = Load(primitives[ia[l]]);
    const LanePrimitive B = Load(primitives[ib[l]]);
    const V3 d = B.c - A.c;
    const float sum_h_a = A.h0 + A.h1 + A.h2;
    const float sum_h_b = B.h0 + B.h1 + B.h2;
    // Enclosing spheres about the centres: |sum t_i u_i| <= sum h_i for unit u_i.
    const float centres_m = std::sqrt(Dot(d, d));
    const float sphere_bound_m = centres_m - (sum_h_a + A.r) - (sum_h_b + B.r);
    // Alternating projections from A's centre: q on B, p on A, then q on B again.
    V3 q = ClampIntoCore(B, A.c);
    const V3 p = ClampIntoCore(A, q);
    q = ClampIntoCore(B, p);
    V3 n = q - p;
    // Cores that meet give no direction: the centres' then (zero too: the sphere bound decides).
    const float nn_pq = Dot(n, n);
    const bool has_direction = nn_pq > 0.0f;
    n = {has_direction ? n.x : d.x, has_direction ? n.y : d.y, has_direction ? n.z : d.z};
    const float nn = has_direction ? nn_pq : centres_m * centres_m;
    n = (1.0f / std::sqrt(nn)) * n;
    const float axis_bound_m = Dot(n, d) - Reach(A, n) - Reach(B, n);
    // nn = 0 leaves axis_bound_m NaN: the sphere bound then (for NaN input both are NaN).
    const float bound = axis_bound_m > sphere_bound_m ? axis_bound_m : sphere_bound_m;
    const float scale_m = SumAbs(A.c) + SumAbs(B.c) + sum_h_a + sum_h_b + A.r + B.r;
    bound_m[l] = bound - kClearanceBatchMarginUlps * kFloatUnitRoundoff * scale_m;
  }
}


// `shape_W` rounded to float into `f`, each number once (written field by field in place: a
// 64-byte copy read back right after scalar stores would stall on store forwarding).
void RoundToFloat(const Shape& shape_W, FloatPrimitive* f) {
  if (const auto* capsule = std::get_if<Capsule>(&shape_W)) {
    const Eigen::Vector3d axis_W = capsule->p1_W - capsule->p0_W;
    const double length_m = axis_W.norm();
    const Eigen::Vector3d centre_W = capsule->p0_W + 0.5 * axis_W;
    // A zero length (a sphere) has no direction; h_0 = 0 then makes u_0 irrelevant.
    const Eigen::Vector3d u_W =
        length_m > 0.0 ? Eigen::Vector3d(axis_W / length_m) : Eigen::Vector3d::Zero();
    for (int k = 0; k < 3; ++k) {
      f->c_W[k] = static_cast<float>(centre_W[k]);
      f->u_W[0][k] = static_cast<float>(u_W[k]);
      f->u_W[1][k] = 0.0f;
      f->u_W[2][k] = 0.0f;
      f->half_m[k] = 0.0f;
    }
    f->half_m[0] = static_cast<float>(0.5 * length_m);
    f->radius_m = static_cast<float>(capsule->radius_m);
    return;
  }
  const Box& box = std::get<Box>(shape_W);
  for (int k = 0; k < 3; ++k) {
    f->c_W[k] = static_cast<float>(box.X_WB.translation()[k]);
    f->half_m[k] = static_cast<float>(box.half_extents_m[k]);
    for (int i = 0; i < 3; ++i) f->u_W[i][k] = static_cast<float>(box.X_WB.linear()(k, i));
  }
  f->radius_m = 0.0f;
}

}  // namespace

void ToFloatPrimitive(const Shape& shape_W, FloatPrimitive* f) {
  RoundToFloat(shape_W, f);
  // NaN, or beyond the float range the batch supports: a NaN radius makes every bound -inf. The
  // sum of magnitudes bounds each (and is NaN or inf with any of them).
  float sum_m = std::abs(f->radius_m);
  for (int k = 0; k < 3; ++k) {
    sum_m += std::abs(f->c_W[k]) + std::abs(f->half_m[k]) + std::abs(f->u_W[0][k]) +
             std::abs(f->u_W[1][k]) + std::abs(f->u_W[2][k]);
  }
  if (!(sum_m <= static_cast<float>(kClearanceBatchMaxLength_m))) {
    f->radius_m = std::numeric_limits<float>::quiet_NaN();
  }
}

void ComputeClearanceLowerBounds(const FloatPrimitive* primitives, const PrimitiveId* a,
                                 const PrimitiveId* b, std::size_t count,
                                 double* lower_bound_m) {
  float bound_m[kLanes];
  for (std::size_t first = 0; first < count; first += kLanes) {
    const int live = static_cast<int>(std::min<std::size_t>(kLanes, count - first));
    PrimitiveId ia[kLanes], ib[kLanes];
    for (int l = 0; l < kLanes; ++l) {
      ia[l] = a[first + std::min(l, live - 1)];
      ib[l] = b[first + std::min(l, live - 1)];
    }
    BoundBlock(primitives, ia, ib, bound_m);
    for (int l = 0; l < live; ++l) {
      // NaN (bad input) would compare false anyway; -inf says the same plainly.
      lower_bound_m[first + l] = std::isnan(bound_m[l])
                                     ? -std::numeric_limits<double>::infinity()
                                     : static_cast<double>(bound_m[l]);
    }
  }
}

}  // namespace arm_collision_monitor
