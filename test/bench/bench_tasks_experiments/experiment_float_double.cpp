// Experiment "float": capsule distances in float against double.

#include "experiments.h"

#include <algorithm>
#include <cmath>

#include <benchmark/benchmark.h>

#include "arm_collision_monitor/core/constants.h"
#include "arm_collision_monitor/core/timing_summary.h"
#include "arm_collision_monitor/geometry/distance.h"

namespace arm_collision_monitor {
namespace bench {
namespace {

// Closest distance between segments p0-p1 and q0-q1 in scalar type T, for the float/double
// study only (Ericson, Real-Time Collision Detection, 5.1.9: clamp s, solve t, re-clamp s).
template <typename T>
T SegmentDistance(const Eigen::Matrix<T, 3, 1>& p0, const Eigen::Matrix<T, 3, 1>& p1,
                  const Eigen::Matrix<T, 3, 1>& q0, const Eigen::Matrix<T, 3, 1>& q1) {
  const Eigen::Matrix<T, 3, 1> d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
  const T a = d1.dot(d1), e = d2.dot(d2), f = d2.dot(r);
  T s = 0, t = 0;
  if (a <= T(0) && e <= T(0)) return r.norm();
  if (a <= T(0)) {
    t = std::clamp(f / e, T(0), T(1));
  } else {
    const T c = d1.dot(r);
    if (e <= T(0)) {
      s = std::clamp(-c / a, T(0), T(1));
    } else {
      const T b = d1.dot(d2), denom = a * e - b * b;
      s = denom != T(0) ? std::clamp((b * f - c * e) / denom, T(0), T(1)) : T(0);
      t = (b * s + f) / e;
      if (t < T(0)) {
        t = 0;
        s = std::clamp(-c / a, T(0), T(1));
      } else if (t > T(1)) {
        t = 1;
        s = std::clamp((b - c) / a, T(0), T(1));
      }
    }
  }
  return (p0 + s * d1 - (q0 + t * d2)).norm();
}

}  // namespace

void ExperimentFloatDouble(const Args& args) {
  const int pairs = args.quick ? 50000 : 200000;
  std::mt19937_64 rng(args.seed);
  std::uniform_real_distribution<double> pos(-1.0, 1.0), len(0.0, 0.4), tilt_exp(-8.0, -2.0);
  constexpr double kRadius_m = 0.05, kThreshold_m = 2 * kDefaultArmTolerance_m;
  struct Case {
    Eigen::Vector3d p0, p1, q0, q1;
  };
  std::vector<Case> cases(pairs);
  for (int i = 0; i < pairs; ++i) {
    Case& c = cases[i];
    c.p0 = Eigen::Vector3d(pos(rng), pos(rng), pos(rng)) + Eigen::Vector3d(0.5, 0.0, 1.2);
    const Eigen::Vector3d dir = Eigen::Vector3d(pos(rng), pos(rng), pos(rng)).normalized();
    c.p1 = c.p0 + len(rng) * dir;
    // A fifth of the pairs nearly parallel (angle 1e-8 .. 1e-2 rad) and close: the hard case.
    if (i % 5 == 0) {
      const Eigen::Vector3d off = 0.12 * Eigen::Vector3d(pos(rng), pos(rng), pos(rng));
      const Eigen::Vector3d tilt =
          std::pow(10.0, tilt_exp(rng)) * Eigen::Vector3d(pos(rng), pos(rng), pos(rng));
      c.q0 = c.p0 + off;
      c.q1 = c.q0 + len(rng) * (dir + tilt).normalized();
    } else {
      c.q0 = c.p0 + 0.3 * Eigen::Vector3d(pos(rng), pos(rng), pos(rng));
      c.q1 = c.q0 + len(rng) * Eigen::Vector3d(pos(rng), pos(rng), pos(rng)).normalized();
    }
  }
  std::vector<long double> truth(pairs);
  for (int i = 0; i < pairs; ++i) {
    const Case& c = cases[i];
    truth[i] = std::max<long double>(
        0, SegmentDistance<long double>(c.p0.cast<long double>(), c.p1.cast<long double>(),
                                        c.q0.cast<long double>(), c.q1.cast<long double>()) -
               2 * static_cast<long double>(kRadius_m));
  }
  Csv csv(args.out_dir + "/float_double.csv",
          "routine,ns_per_call,max_error_m,p99_error_m,wrong_decisions,pairs,seed");
  auto study = [&](const char* name, const std::function<double(const Case&)>& f) {
    std::vector<double> out(pairs);
    // Fastest of five passes: the least disturbed by other processes.
    double ns = 1e300;
    for (int pass = 0; pass < 5; ++pass) {
      const auto t0 = Clock::now();
      for (int i = 0; i < pairs; ++i) out[i] = f(cases[i]);
      benchmark::DoNotOptimize(out.data());
      ns = std::min(ns, MicrosSince(t0) * 1e3 / pairs);
    }
    std::vector<double> err(pairs);
    int wrong = 0;
    for (int i = 0; i < pairs; ++i) {
      err[i] = static_cast<double>(std::abs(static_cast<long double>(out[i]) - truth[i]));
      wrong += (out[i] < kThreshold_m) != (truth[i] < kThreshold_m);
    }
    std::sort(err.begin(), err.end());
    csv.Row(name, ns, err.back(), NearestRankPercentile(err, 0.99), wrong, pairs,
            args.seed);
    std::printf("  %-16s %7.1f ns/call  max error %.3g m  wrong decisions %d\n", name, ns,
                err.back(), wrong);
  };
  std::printf("== float against double (%d capsule pairs, seed %llu)\n", pairs,
              static_cast<unsigned long long>(args.seed));
  study("float", [&](const Case& c) {
    return static_cast<double>(std::max(
        0.0f, SegmentDistance<float>(c.p0.cast<float>(), c.p1.cast<float>(), c.q0.cast<float>(),
                                     c.q1.cast<float>()) - 2.0f * static_cast<float>(kRadius_m)));
  });
  study("double", [&](const Case& c) {
    return std::max(0.0, SegmentDistance<double>(c.p0, c.p1, c.q0, c.q1) - 2 * kRadius_m);
  });
  study("library double", [&](const Case& c) {
    return CapsuleCapsuleDistance(Capsule{c.p0, c.p1, kRadius_m}, Capsule{c.q0, c.q1, kRadius_m})
        .distance_m;
  });
}

}  // namespace bench
}  // namespace arm_collision_monitor
