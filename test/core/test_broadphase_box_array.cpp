// BoxArray: the branch-free overlap scan against Aabb::Overlaps, through growth past its
// reserve, swap-removal and NaN bounds.
#include <gtest/gtest.h>

#include <limits>
#include <random>
#include <vector>

#include "arm_collision_monitor/broadphase/box_array.h"

namespace arm_collision_monitor {
namespace {

TEST(BoxArray, ScanFlagsExactlyTheOverlappingBoxesInSlotOrder) {
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
    for (std::uint32_t s = 0; s < expected.size(); ++s) {
      if (query.Overlaps(expected[s])) brute.push_back(s);
      const Aabb got = boxes.Get(s);
      ASSERT_TRUE(got.min_W.cwiseEqual(expected[s].min_W).count() +
                      got.min_W.array().isNaN().count() == 3 &&
                  got.max_W.cwiseEqual(expected[s].max_W).count() +
                      got.max_W.array().isNaN().count() == 3)
          << "slot " << s << " step " << step;
    }
    ASSERT_EQ(hits, brute) << "step " << step;
    hits_seen += hits.size();
  }
  EXPECT_GT(hits_seen, 1000u);  // the scan met boxes, not only empty sets
}

}  // namespace
}  // namespace arm_collision_monitor
