// The timing summaries of the node's diagnostics, replay and the benchmarks: the nearest-rank
// percentile and the median of passes' medians (SummarizePasses).
#include <gtest/gtest.h>

#include <vector>

#include "arm_collision_monitor/core/timing_summary.h"

namespace arm_collision_monitor {
namespace {

TEST(TimingSummary, NearestRankPercentileIsTheSmallestSampleCoveringTheFraction) {
  const std::vector<double> sorted = {1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0, 10.0};
  EXPECT_EQ(NearestRankPercentile(sorted, 0.5), 5.0);
  EXPECT_EQ(NearestRankPercentile(sorted, 0.51), 6.0);
  EXPECT_EQ(NearestRankPercentile(sorted, 0.99), 10.0);
  EXPECT_EQ(NearestRankPercentile(sorted, 0.0), 1.0);
}

TEST(TimingSummary, PassesMedianAndP99AreTheMediansOfThePasses) {
  // Three passes of five, the last in a slow spell: pass medians 3, 4 and 100, pass p99s (their
  // largest samples) 5, 6 and 100.
  const std::vector<double> samples = {5.0, 1.0, 4.0, 2.0, 3.0,  6.0, 2.0, 5.0, 3.0, 4.0,
                                       100.0, 100.0, 100.0, 100.0, 100.0};
  const TimingSummary pooled = SummarizeTimings(samples);
  const TimingSummary passes = SummarizePasses(samples, 3);
  EXPECT_EQ(pooled.median, 5.0);  // the 8th of 15 sorted samples: the slow pass pulls it up
  EXPECT_EQ(passes.median, 4.0);
  EXPECT_EQ(pooled.p99, 100.0);
  EXPECT_EQ(passes.p99, 6.0);
  // The count, mean and max are over all the samples.
  EXPECT_EQ(passes.count, 15u);
  EXPECT_EQ(passes.mean, pooled.mean);
  EXPECT_EQ(passes.max, 100.0);
}

TEST(TimingSummary, PassesKeepACycleSlowInEveryPass) {
  // One slow cycle (50) in each of three passes of 50: it is every pass's p99.
  std::vector<double> samples;
  for (int pass = 0; pass < 3; ++pass) {
    for (int i = 0; i < 49; ++i) samples.push_back(1.0 + 0.01 * i);
    samples.push_back(50.0);
  }
  EXPECT_EQ(SummarizePasses(samples, 3).p99, 50.0);
}

TEST(TimingSummary, PassesLastPassMayBeShorter) {
  // Passes {3, 1, 2} (median 2), {6, 5, 4} (median 5) and {100}: the median of 2, 5 and 100
  // is 5 (of all seven samples, 4).
  const std::vector<double> samples = {3.0, 1.0, 2.0, 6.0, 5.0, 4.0, 100.0};
  EXPECT_EQ(SummarizePasses(samples, 3).median, 5.0);
  // One pass holding everything is the plain median.
  EXPECT_EQ(SummarizePasses(samples, 1).median, SummarizeTimings(samples).median);
}

TEST(TimingSummary, PassesOfNoSamplesAreZero) {
  const TimingSummary s = SummarizePasses({}, 4);
  EXPECT_EQ(s.count, 0u);
  EXPECT_EQ(s.median, 0.0);
  EXPECT_EQ(s.max, 0.0);
}

TEST(SampleWindow, KeepsTheLatestSamplesUpToItsCapacity) {
  SampleWindow window(3);
  EXPECT_TRUE(window.samples().empty());
  window.Add(1.0);
  window.Add(2.0);
  EXPECT_EQ(window.samples(), (std::vector<double>{1.0, 2.0}));
  for (const double v : {3.0, 4.0, 5.0}) window.Add(v);
  // 1 and 2 overwritten, oldest first; the order does not matter to a summary.
  EXPECT_EQ(window.samples(), (std::vector<double>{4.0, 5.0, 3.0}));
  EXPECT_EQ(SummarizeTimings(window.samples()).max, 5.0);
  const double* data = window.samples().data();
  for (int i = 0; i < 10; ++i) window.Add(i);
  EXPECT_EQ(window.samples().data(), data);  // no reallocation after construction
  EXPECT_EQ(window.samples().size(), 3u);
}

}  // namespace
}  // namespace arm_collision_monitor
