// Sine and cosine for forward kinematics, inline and branch-free: libm's sincos, an opaque call
// per joint, took about half of ComputeLinkPoses; a loop over these vectorizes (two lanes even
// on baseline x86-64 SSE2).
#pragma once

#include <cmath>
#include <cstdint>
#include <cstring>

#include "arm_collision_monitor/core/constants.h"

namespace arm_collision_monitor {

/// sin(angle_rad) and cos(angle_rad) for |angle_rad| <= kFastSinCosMaxAngle_rad (other angles
/// give meaningless results: use SinCos), each within kFastSinCosErrorUlps units of 2^-53
/// (absolute) of the true value. Branch-free, so loops over it vectorize.
// Cody & Waite range reduction by pi/2 (Cody & Waite, "Software Manual for the Elementary
// Functions", 1980, ch. 8) then Taylor polynomials on |r| <= pi/4.
inline void SinCosOfReducibleAngle(double angle_rad, double* sin_out, double* cos_out) {
  // pi/2 = kPiOver2Hi + kPiOver2Mid + kPiOver2Lo: Hi and Mid hold 33 significant bits each, so
  // k * Hi and k * Mid are exact for |k| < 2^20 and angle - k * Hi cancels exactly.
  constexpr double kPiOver2Hi = 1.5707963267341256;
  constexpr double kPiOver2Mid = 6.077100506303966e-11;
  constexpr double kPiOver2Lo = 2.0222662487959506e-21;
  constexpr double kTwoOverPi = 0.6366197723675814;
  // Adding 1.5 * 2^52 rounds to the nearest integer k (|k| < 2^51) and leaves k, two's
  // complement, in the low bits of the sum's mantissa.
  constexpr double kRoundToInteger = 6755399441055744.0;
  const double shifted = angle_rad * kTwoOverPi + kRoundToInteger;
  const double k = shifted - kRoundToInteger;
  std::uint64_t quadrant_bits;  // k mod 4 in bits 0 and 1
  std::memcpy(&quadrant_bits, &shifted, sizeof(double));
  const double r = ((angle_rad - k * kPiOver2Hi) - k * kPiOver2Mid) - k * kPiOver2Lo;
  const double z = r * r;
  // Taylor series; on |r| <= pi/4 the first omitted terms (r^19/19!, r^20/20!) are below 1e-19.
  constexpr double f3 = 6.0, f5 = f3 * 20.0, f7 = f5 * 42.0, f9 = f7 * 72.0, f11 = f9 * 110.0,
                   f13 = f11 * 156.0, f15 = f13 * 210.0, f17 = f15 * 272.0;
  constexpr double f2 = 2.0, f4 = f2 * 12.0, f6 = f4 * 30.0, f8 = f6 * 56.0, f10 = f8 * 90.0,
                   f12 = f10 * 132.0, f14 = f12 * 182.0, f16 = f14 * 240.0, f18 = f16 * 306.0;
  const double sin_r =
      r + r * z *
              (-1.0 / f3 +
               z * (1.0 / f5 +
                    z * (-1.0 / f7 +
                         z * (1.0 / f9 +
                              z * (-1.0 / f11 +
                                   z * (1.0 / f13 + z * (-1.0 / f15 + z * (1.0 / f17))))))));
  const double cos_r =
      1.0 - 0.5 * z +
      z * z *
          (1.0 / f4 +
           z * (-1.0 / f6 +
                z * (1.0 / f8 +
                     z * (-1.0 / f10 +
                          z * (1.0 / f12 +
                               z * (-1.0 / f14 + z * (1.0 / f16 + z * (-1.0 / f18))))))));
  // Quadrant k mod 4: sin = (sin_r, cos_r, -sin_r, -cos_r), cos = (cos_r, -sin_r, -cos_r, sin_r),
  // selected with bit masks rather than branches (random joint angles would mispredict them).
  std::uint64_t sin_r_bits, cos_r_bits;
  std::memcpy(&sin_r_bits, &sin_r, sizeof(double));
  std::memcpy(&cos_r_bits, &cos_r, sizeof(double));
  const std::uint64_t swap = std::uint64_t{0} - (quadrant_bits & 1);  // all ones if k is odd
  std::uint64_t sin_bits = (cos_r_bits & swap) | (sin_r_bits & ~swap);
  std::uint64_t cos_bits = (sin_r_bits & swap) | (cos_r_bits & ~swap);
  sin_bits ^= (quadrant_bits & 2) << 62;        // negative in quadrants 2 and 3
  cos_bits ^= ((quadrant_bits + 1) & 2) << 62;  // negative in quadrants 1 and 2
  std::memcpy(sin_out, &sin_bits, sizeof(double));
  std::memcpy(cos_out, &cos_bits, sizeof(double));
}

/// sin and cos of `count` angles (any doubles; inf and NaN give NaN like std::sin): angles up to
/// kFastSinCosMaxAngle_rad within kFastSinCosErrorUlps units of 2^-53, larger ones through
/// std::sin/std::cos.
inline void SinCos(const double* angle_rad, int count, double* sin_out, double* cos_out) {
  for (int i = 0; i < count; ++i) {
    SinCosOfReducibleAngle(angle_rad[i], &sin_out[i], &cos_out[i]);
  }
  for (int i = 0; i < count; ++i) {
    if (!(std::abs(angle_rad[i]) <= kFastSinCosMaxAngle_rad)) {
      sin_out[i] = std::sin(angle_rad[i]);
      cos_out[i] = std::cos(angle_rad[i]);
    }
  }
}

}  // namespace arm_collision_monitor
