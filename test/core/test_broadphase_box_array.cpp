// BoxArray: the branch-free overlap scan against Aabb::Overlaps, through growth past its
// reserve, swap-removal and NaN bounds.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "arm_collision_monitor/broadphase/box_array.h"

namespace arm_collision_monitor {
namespace {

// Every scan path (the portable one, SSE2, AVX2 where the CPU has it) gives the same answers.
class BoxArrayScan : public ::testing::TestWithParam<BoxArray::ScanPath> {
 protected:
  void SetUp() override { BoxArray::ForceScanPath(GetParam()); }
  void TearDown() override { BoxArray::ForceScanPath(BoxArray::ScanPath::kBest); }
};

TEST_P(BoxArrayScan, ScanFlagsExactlyTheOverlappingBoxesInSlotOrder) {
  std::mt19937_64 rng(20261124);
  std::uniform_real_distribution<double> coord(-1.0, 1.0), half(0.0, 0.5), unit(0.0, 1.0);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  auto random_box = [&] {
    const Eigen::Vector3d c(coord(rng), coord(rng), coord(rng));
    const Eigen::Vector3d h(half(rng), half(rng), half(rng));
    Aabb box{c - h, c + h};
    const double u = unit(rng);
    if (u < 0.05) box.min_W[static_cast<int>(u * 60) % 3] = nan;  // NaN: overlaps nothing
    if (u > 0.95) box.max_W = box.min_W;  // a point, touching only closed boxes
    return box;
  };
  BoxArray boxes;
  boxes.Reserve(3);  // the rest grows on PushBack
  std::vector<Aabb> expected;  // the same boxes, slot by slot
  std::size_t hits_seen = 0;
  for (int step = 0; step < 4000; ++step) {
    const double u = unit(rng);
    if (u < 0.45 || expected.empty()) {
      expected.push_back(random_box());
      boxes.PushBack(expected.back());
    } else if (u < 0.7) {
      const auto slot = static_cast<std::uint32_t>(unit(rng) * expected.size());
      expected[slot] = expected.back();
      expected.pop_back();
      boxes.SwapRemove(slot);
    } else {
      const auto slot = static_cast<std::uint32_t>(unit(rng) * expected.size());
      expected[slot] = random_box();
      boxes.Set(slot, expected[slot]);
    }
    ASSERT_EQ(boxes.size(), expected.size());
    const Aabb query = random_box();
    boxes.MarkOverlaps(query);
    std::vector<std::uint32_t> hits;
    boxes.ForEachHit([&](std::uint32_t slot) { hits.push_back(slot); });
    std::vector<std::uint32_t> brute;
    const std::uint64_t* flags = boxes.hit_words();
    for (std::uint32_t s = 0; s < expected.size(); ++s) {
      // hit_words: every overlapping box flagged; Overlaps(slot, box) the exact test.
      const bool is_flagged = (flags[s / 64] >> (s % 64)) & 1;
      ASSERT_TRUE(is_flagged || !query.Overlaps(expected[s])) << "slot " << s << " step " << step;
      ASSERT_EQ(boxes.Overlaps(s, query), query.Overlaps(expected[s])) << "slot " << s;
      if (query.Overlaps(expected[s])) brute.push_back(s);
      const Aabb got = boxes.Get(s);
      ASSERT_TRUE(got.min_W.cwiseEqual(expected[s].min_W).count() +
                      got.min_W.array().isNaN().count() == 3 &&
                  got.max_W.cwiseEqual(expected[s].max_W).count() +
                      got.max_W.array().isNaN().count() == 3)
          << "slot " << s << " step " << step;
    }
    ASSERT_EQ(hits, brute) << "step " << step;
    // No flag past the last slot.
    if (boxes.size() > 0) {
      const std::uint32_t last = boxes.size() - 1;
      ASSERT_EQ(flags[last / 64] >> 1 >> (last % 64), 0u) << "step " << step;
    }
    hits_seen += hits.size();
  }
  EXPECT_GT(hits_seen, 1000u);  // the scan met boxes, not only empty sets
}

TEST_P(BoxArrayScan, BoundsBetweenFloatsAndBeyondTheirRangeAreDecidedExactly) {
  // The scan runs on float copies (rounded to nearest); the answer must still be the exact
  // double test's. Boxes and queries that touch or miss by one double ulp at coordinates no float
  // represents, at zero and denormals, and beyond the float range.
  const double inf = std::numeric_limits<double>::infinity();
  const double coords[] = {0.1, -0.1, 1.0 / 3.0, 1e-300, -1e-300, 0.0, 1e300, -1e300, 5e-324,
                           3.4028235677973366e38, 16777217.0};
  std::vector<Aabb> expected;
  BoxArray boxes;
  for (const double c : coords) {
    for (const double d : {std::nextafter(c, -inf), c, std::nextafter(c, inf)}) {
      // A box ending at d on every axis, and one starting there.
      expected.push_back(Aabb{Eigen::Vector3d::Constant(d - std::abs(d) - 1.0),
                              Eigen::Vector3d::Constant(d)});
      expected.push_back(Aabb{Eigen::Vector3d::Constant(d),
                              Eigen::Vector3d::Constant(d + std::abs(d) + 1.0)});
    }
  }
  for (const Aabb& b : expected) boxes.PushBack(b);
  std::size_t hits_seen = 0, misses_seen = 0;
  for (const Aabb& query : expected) {
    boxes.MarkOverlaps(query);
    std::vector<std::uint32_t> hits, brute;
    boxes.ForEachHit([&](std::uint32_t slot) { hits.push_back(slot); });
    for (std::uint32_t s = 0; s < expected.size(); ++s) {
      if (query.Overlaps(expected[s])) brute.push_back(s);
    }
    ASSERT_EQ(hits, brute);
    hits_seen += hits.size();
    misses_seen += expected.size() - hits.size();
  }
  // Both answers occur, also between boxes one double ulp apart.
  EXPECT_GT(hits_seen, 0u);
  EXPECT_GT(misses_seen, 0u);
}

INSTANTIATE_TEST_SUITE_P(AllPaths, BoxArrayScan,
                         ::testing::Values(BoxArray::ScanPath::kBest, BoxArray::ScanPath::kPortable,
                                           BoxArray::ScanPath::kSse2, BoxArray::ScanPath::kAvx2));

}  // namespace
}  // namespace arm_collision_monitor
