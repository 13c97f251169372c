// Welzl's smallest enclosing circle, iterative form (see smallest_circle.h).
#include "arm_collision_monitor/geometry/smallest_circle.h"

namespace arm_collision_monitor {
namespace {

using Eigen::Vector2d;

struct Circle {
  Vector2d centre = Vector2d::Zero();
  double radius2 = 0.0;  // squared radius
  bool Contains(const Vector2d& p) const { return (p - centre).squaredNorm() <= radius2; }
};

Circle DiametralCircle(const Vector2d& a, const Vector2d& b) {
  const Vector2d centre = 0.5 * (a + b);
  return Circle{centre, (a - centre).squaredNorm()};
}

// Circle through three points; for (nearly) collinear points, whose circumcentre is not finite,
// the largest diametral circle of the three pairs.
Circle CircleThrough(const Vector2d& a, const Vector2d& b, const Vector2d& c) {
  const Vector2d ab = b - a;
  const Vector2d ac = c - a;
  const double d = 2.0 * (ab.x() * ac.y() - ab.y() * ac.x());
  const Vector2d offset((ac.y() * ab.squaredNorm() - ab.y() * ac.squaredNorm()) / d,
                        (ab.x() * ac.squaredNorm() - ac.x() * ab.squaredNorm()) / d);
  if (d != 0.0 && offset.allFinite()) return Circle{a + offset, offset.squaredNorm()};
  Circle best = DiametralCircle(a, b);
  for (const Circle& other : {DiametralCircle(a, c), DiametralCircle(b, c)}) {
    if (other.radius2 > best.radius2) best = other;
  }
  return best;
}

}  // namespace

Vector2d SmallestCircleCentre(const std::vector<Vector2d>& p) {
  Circle disc{p.front(), 0.0};
  for (std::size_t i = 1; i < p.size(); ++i) {
    if (disc.Contains(p[i])) continue;
    disc = Circle{p[i], 0.0};
    for (std::size_t j = 0; j < i; ++j) {
      if (disc.Contains(p[j])) continue;
      disc = DiametralCircle(p[i], p[j]);
      for (std::size_t k = 0; k < j; ++k) {
        if (!disc.Contains(p[k])) disc = CircleThrough(p[i], p[j], p[k]);
      }
    }
  }
  return disc.centre;
}

}  // namespace arm_collision_monitor
