// SmallestCircleCentre against a brute force over every circle through two or three of the
// points (the smallest enclosing circle is one of them), on seeded random and degenerate sets.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <vector>

#include "arm_collision_monitor/geometry/smallest_circle.h"

namespace arm_collision_monitor {
namespace {

using Eigen::Vector2d;

double MaxDistance(const std::vector<Vector2d>& points, const Vector2d& centre) {
  double max_d = 0.0;
  for (const Vector2d& p : points) max_d = std::max(max_d, (p - centre).norm());
  return max_d;
}

// The radius of the smallest enclosing circle, by trying every diametral circle and every
// circumcircle of the points: O(n^4), for small sets only.
double BruteForceRadius(const std::vector<Vector2d>& p) {
  double best = MaxDistance(p, p.front());
  auto consider = [&](const Vector2d& centre) {
    if (centre.allFinite()) best = std::min(best, MaxDistance(p, centre));
  };
  for (std::size_t i = 0; i < p.size(); ++i) {
    for (std::size_t j = i + 1; j < p.size(); ++j) {
      consider(0.5 * (p[i] + p[j]));
      for (std::size_t k = j + 1; k < p.size(); ++k) {
        const Vector2d ab = p[j] - p[i];
        const Vector2d ac = p[k] - p[i];
        const double d = 2.0 * (ab.x() * ac.y() - ab.y() * ac.x());
        if (d == 0.0) continue;
        consider(p[i] + Vector2d((ac.y() * ab.squaredNorm() - ab.y() * ac.squaredNorm()) / d,
                                 (ab.x() * ac.squaredNorm() - ac.x() * ab.squaredNorm()) / d));
      }
    }
  }
  return best;
}

TEST(SmallestCircle, MatchesBruteForceOnRandomSets) {
  const unsigned seed = 20261123u;
  std::printf("seed %u\n", seed);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> coordinate(-1.0, 1.0);
  std::uniform_int_distribution<int> count(1, 14);
  for (int round = 0; round < 400; ++round) {
    std::vector<Vector2d> points(count(rng));
    const double scale = std::pow(10.0, round % 7 - 3);  // 1 mm .. 1 km
    for (Vector2d& p : points) p = scale * Vector2d(coordinate(rng), coordinate(rng));
    const Vector2d centre = SmallestCircleCentre(points);
    const double radius = MaxDistance(points, centre);
    const double reference = BruteForceRadius(points);
    EXPECT_LE(radius, reference * (1.0 + 1e-12) + 1e-300) << "round " << round;
    EXPECT_GE(radius, reference * (1.0 - 1e-12)) << "round " << round;
  }
}

TEST(SmallestCircle, DegenerateSets) {
  // One point, repeated points, collinear points: the centre is the point, the point, the
  // middle of the extreme two.
  EXPECT_EQ(SmallestCircleCentre({Vector2d(2.0, -1.0)}), Vector2d(2.0, -1.0));
  EXPECT_EQ(SmallestCircleCentre({Vector2d(1.0, 1.0), Vector2d(1.0, 1.0), Vector2d(1.0, 1.0)}),
            Vector2d(1.0, 1.0));
  const std::vector<Vector2d> line = {Vector2d(0.0, 0.0), Vector2d(3.0, 3.0), Vector2d(1.0, 1.0),
                                      Vector2d(-1.0, -1.0), Vector2d(2.0, 2.0)};
  EXPECT_NEAR((SmallestCircleCentre(line) - Vector2d(1.0, 1.0)).norm(), 0.0, 1e-15);
}

}  // namespace
}  // namespace arm_collision_monitor
