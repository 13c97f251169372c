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

/// Summarizes samples taken in `passes` passes (> 0), in pass order, each of ceil(samples /
/// passes) samples but the last, which may be shorter: the count, mean and max of all the
/// samples, the median and p99 each the median of the passes' own. Benchmarks take their passes
/// in turns with the others they compare; a slow spell of a shared machine then spoils a pass
/// rather than a share of every method's samples, and moves these little, while a cycle slow in
/// every pass (the same input each time) stays in every pass's p99.
inline TimingSummary SummarizePasses(const std::vector<double>& samples, std::size_t passes) {
  TimingSummary s = SummarizeTimings(samples);
  const std::size_t pass_size = (samples.size() + passes - 1) / passes;
  std::vector<double> medians, p99s;
  for (std::size_t first = 0; first < samples.size(); first += pass_size) {
    const auto begin = samples.begin() + static_cast<std::ptrdiff_t>(first);
    const auto end = samples.begin() +
                     static_cast<std::ptrdiff_t>(std::min(first + pass_size, samples.size()));
    const TimingSummary pass = SummarizeTimings(std::vector<double>(begin, end));
    medians.push_back(pass.median);
    p99s.push_back(pass.p99);
  }
  if (!medians.empty()) {
    s.median = SummarizeTimings(medians).median;
    s.p99 = SummarizeTimings(p99s).median;
  }
  return s;
}

/// The latest `capacity` samples (> 0), the oldest overwritten first: allocation-free after
/// construction, for the node's per-message figures.
class SampleWindow {
 public:
  explicit SampleWindow(std::size_t capacity) : capacity_(capacity) { samples_.reserve(capacity); }
  void Add(double sample) {
    if (samples_.size() < capacity_) {
      samples_.push_back(sample);
      return;
    }
    samples_[next_] = sample;
    next_ = (next_ + 1) % capacity_;
  }
  /// In no particular order.
  const std::vector<double>& samples() const { return samples_; }

 private:
  std::size_t capacity_;
  std::size_t next_ = 0;
  std::vector<double> samples_;
};

}  // namespace arm_collision_monitor
