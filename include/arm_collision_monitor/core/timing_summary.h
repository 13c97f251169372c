// The one percentile rule of the package and the timing summary built on it, for the node's
// diagnostics, replay, the latency probe, the soak and the benchmarks alike.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace arm_collision_monitor {

/// Nearest-rank percentile (Hyndman & Fan definition 1): the smallest sample such that at least
/// `fraction` of the samples are at most it. `sorted` ascending and not empty; fraction in
/// (0, 1] (values at or below 0 give the minimum).
inline double NearestRankPercentile(const std::vector<double>& sorted, double fraction) {
  const double rank = std::ceil(fraction * static_cast<double>(sorted.size()));
  const std::size_t index = rank <= 1.0 ? 0 : static_cast<std::size_t>(rank) - 1;
  return sorted[std::min(index, sorted.size() - 1)];
}

/// Count, mean, median, p99 and max of a set of samples, in the samples' own unit. All zero for
/// no samples.
struct TimingSummary {
  std::size_t count = 0;
  double mean = 0.0;
  double median = 0.0;
  double p99 = 0.0;
  double max = 0.0;
};

/// Summarizes `samples` (taken by value: sorted in place).
inline TimingSummary SummarizeTimings(std::vector<double> samples) {
  TimingSummary s;
  if (samples.empty()) return s;
  std::sort(samples.begin(), samples.end());
  double sum = 0.0;
  for (const double v : samples) sum += v;
  s.count = samples.size();
  s.mean = sum / static_cast<double>(samples.size());
  s.median = NearestRankPercentile(samples, 0.5);
  s.p99 = NearestRankPercentile(samples, 0.99);
  s.max = samples.back();
  return s;
}

}  // namespace arm_collision_monitor
