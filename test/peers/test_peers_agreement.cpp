// The peers (FCL, Bullet) against brute force with our distance routines, on seeded random
// scenes of moving capsules among static boxes, some boxes with a tolerance zone of their own.
// kRounded must give exactly our warnings (up to the peers' stated accuracy at the threshold);
// kSharp must give a superset, every extra pair explained by a sharp edge or corner.
#include <algorithm>
#include <cstdio>
#include <iterator>
#include <string>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "arm_collision_monitor/geometry/distance.h"
#include "arm_collision_monitor/peers/peer_checker.h"

namespace arm_collision_monitor {
namespace {

// Pairs whose distance lies within this of the threshold (m) may legitimately be decided
// either way by a peer: FCL's distance query and Bullet's GJK stop at ~1e-6 m.
constexpr double kPeerThresholdBand_m = 1e-5;

struct RandomScene {
  std::vector<PeerPrimitive> primitives;
  CompatibilityMatrix compatible;
};

Eigen::Vector3d RandomPoint(std::mt19937_64* rng, double half_edge_m) {
  std::uniform_real_distribution<double> u(-half_edge_m, half_edge_m);
  return Eigen::Vector3d(u(*rng), u(*rng), u(*rng));
}

Capsule RandomCapsule(std::mt19937_64* rng) {
  std::uniform_real_distribution<double> length(0.0, 0.4), radius(0.02, 0.1);
  Capsule c;
  c.p0_W = RandomPoint(rng, 1.0);
  c.p1_W = c.p0_W + length(*rng) * Eigen::Vector3d::Random(3).normalized();
  c.radius_m = radius(*rng);
  return c;
}

RandomScene MakeScene(std::mt19937_64* rng, int capsules, int boxes) {
  RandomScene scene;
  std::uniform_real_distribution<double> half(0.02, 0.3), tolerance(0.0, 0.05), unit(0.0, 1.0);
  for (int i = 0; i < capsules; ++i) {
    scene.primitives.push_back(PeerPrimitive{RandomCapsule(rng), tolerance(*rng), true, true});
  }
  for (int i = 0; i < boxes; ++i) {
    Box b;
    b.X_WB.linear() = Eigen::Quaterniond::UnitRandom().toRotationMatrix();
    b.X_WB.translation() = RandomPoint(rng, 1.0);
    b.half_extents_m = Eigen::Vector3d(half(*rng), half(*rng), half(*rng));
    // Half of the boxes have a zone of their own, where rounded and sharp growth differ.
    const double tol_m = unit(*rng) < 0.5 ? 0.0 : tolerance(*rng);
    scene.primitives.push_back(PeerPrimitive{b, tol_m, false, true});
  }
  scene.compatible = CompatibilityMatrix(static_cast<std::uint32_t>(scene.primitives.size()));
  for (int i = 0; i + 1 < capsules; i += 3) scene.compatible.Set(i, i + 1, true);
  return scene;
}

double Threshold(const RandomScene& s, PrimitiveId a, PrimitiveId b) {
  return s.primitives[a].tolerance_m + s.primitives[b].tolerance_m;
}

// Our answer by brute force, plus the pairs too close to the threshold to call.
void BruteForce(const RandomScene& s, std::vector<CandidatePair>* sure,
                std::vector<CandidatePair>* borderline) {
  sure->clear();
  borderline->clear();
  const auto n = static_cast<PrimitiveId>(s.primitives.size());
  for (PrimitiveId a = 0; a < n; ++a) {
    for (PrimitiveId b = a + 1; b < n; ++b) {
      if (!s.primitives[a].is_moving && !s.primitives[b].is_moving) continue;
      if (s.compatible.AreCompatible(a, b)) continue;
      const double d = ShapeDistance(s.primitives[a].shape_W, s.primitives[b].shape_W).distance_m;
      const double t = Threshold(s, a, b);
      if (std::abs(d - t) <= kPeerThresholdBand_m) {
        borderline->push_back({a, b});
      } else if (d < t) {
        sure->push_back({a, b});
      }
    }
  }
}

Shape GrownSharp(const PeerPrimitive& p) {
  if (const auto* c = std::get_if<Capsule>(&p.shape_W)) {
    Capsule g = *c;
    g.radius_m += p.tolerance_m;
    return g;
  }
  Box g = std::get<Box>(p.shape_W);
  g.half_extents_m.array() += p.tolerance_m;
  return g;
}

bool Contains(const std::vector<CandidatePair>& v, const CandidatePair& p) {
  return std::binary_search(v.begin(), v.end(), p);
}

void MoveCapsules(std::mt19937_64* rng, RandomScene* s, PeerChecker* peer) {
  for (PrimitiveId id = 0; id < s->primitives.size(); ++id) {
    if (!s->primitives[id].is_moving) continue;
    Capsule c = std::get<Capsule>(s->primitives[id].shape_W);
    // Same length and radius (the peer keeps its shape), new pose.
    const double length_m = (c.p1_W - c.p0_W).norm();
    c.p0_W = RandomPoint(rng, 1.0);
    c.p1_W = c.p0_W + length_m * Eigen::Vector3d::Random(3).normalized();
    s->primitives[id].shape_W = c;
    peer->SetShape(id, c);
  }
}

class PeersAgreement : public ::testing::TestWithParam<int> {};

TEST_P(PeersAgreement, RandomScenesMatchBruteForce) {
  const std::uint64_t seed = 20261121u + static_cast<std::uint64_t>(GetParam());
  std::printf("seed %llu\n", static_cast<unsigned long long>(seed));
  for (const PeerTolerance mode : {PeerTolerance::kRounded, PeerTolerance::kSharp}) {
    for (const bool use_fcl : {true, false}) {
      std::mt19937_64 rng(seed);
      std::srand(static_cast<unsigned>(seed));  // Eigen's Random() draws from rand()
      RandomScene scene = MakeScene(&rng, 12, 20);
      auto peer = use_fcl ? MakeFclChecker(scene.primitives, scene.compatible, mode)
                          : MakeBulletChecker(scene.primitives, scene.compatible, mode);
      std::vector<CandidatePair> got, sure, borderline;
      int warnings_seen = 0, extra_sharp = 0;
      for (int cycle = 0; cycle < 60; ++cycle) {
        if (cycle > 0) MoveCapsules(&rng, &scene, peer.get());
        peer->FindWarnings(&got);
        BruteForce(scene, &sure, &borderline);
        warnings_seen += static_cast<int>(sure.size());
        for (const CandidatePair& p : sure) {
          EXPECT_TRUE(Contains(got, p)) << peer->name() << " missed (" << p.a << ", " << p.b
                                        << ") at cycle " << cycle;
        }
        for (const CandidatePair& p : got) {
          if (Contains(sure, p) || Contains(borderline, p)) continue;
          if (mode == PeerTolerance::kSharp) {
            // Allowed only where the sharp grown shapes overlap.
            const double d = ShapeDistance(GrownSharp(scene.primitives[p.a]),
                                           GrownSharp(scene.primitives[p.b])).distance_m;
            EXPECT_LE(d, kPeerThresholdBand_m) << peer->name() << " extra (" << p.a << ", "
                                               << p.b << ") not explained by a sharp edge";
            ++extra_sharp;
          } else {
            ADD_FAILURE() << peer->name() << " false warning (" << p.a << ", " << p.b
                          << ") at cycle " << cycle;
          }
        }
      }
      std::printf("%s: %d warnings checked, %d sharp-edge extras\n", peer->name().c_str(),
                  warnings_seen, extra_sharp);
      EXPECT_GT(warnings_seen, 20) << "the scenes must exercise warnings";
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Seeds, PeersAgreement, ::testing::Range(0, 4));

// One moving shape (primitive 0) and one static box (primitive 1) apart, seeded: `kind` 0 two
// capsules (the second moving too), 1 a capsule and a box, 2 a sphere and a box, 3 two boxes.
std::vector<PeerPrimitive> SeparatedPair(std::mt19937_64* rng, int kind, double* distance_m) {
  std::uniform_real_distribution<double> half(0.02, 0.3);
  for (;;) {
    auto random_box = [&] {
      Box b;
      b.X_WB.linear() = Eigen::Quaterniond::UnitRandom().toRotationMatrix();
      b.X_WB.translation() = RandomPoint(rng, 1.0);
      b.half_extents_m = Eigen::Vector3d(half(*rng), half(*rng), half(*rng));
      return b;
    };
    Shape a = RandomCapsule(rng);
    if (kind == 2) std::get<Capsule>(a).p1_W = std::get<Capsule>(a).p0_W;
    if (kind == 3) a = random_box();
    const Shape b = kind == 0 ? Shape(RandomCapsule(rng)) : Shape(random_box());
    *distance_m = ShapeDistance(a, b).distance_m;
    if (*distance_m > 0.005 && *distance_m < 0.5) {
      return {PeerPrimitive{a, 0.0, true, true}, PeerPrimitive{b, 0.0, kind == 0, true}};
    }
  }
}

// The agreement table at the threshold: the rounded peers on pairs whose distance lies a
// margin inside or outside their threshold (the tolerance sum), against our distance. Printed
// per peer, pair kind and margin; a peer must decide every pair right at margins of
// kPeerThresholdBand_m and above (what RandomScenesMatchBruteForce lets it decide either way).
TEST(PeersAgreement, NearThresholdPairsDecidedAtTheStatedAccuracy) {
  constexpr int kPairs = 100;
  const double margins_m[] = {1e-3, 1e-4, 3e-5, 1e-5, 1e-6, 1e-7};
  const char* kinds[] = {"capsule-capsule", "capsule-box", "sphere-box", "box-box"};
  std::printf("%-12s %-16s wrong decisions of %d pairs x 2 at margin (m):", "peer", "pairs",
              kPairs);
  for (const double m : margins_m) std::printf(" %8.0e", m);
  std::printf("\n");
  for (const bool use_fcl : {true, false}) {
    for (int kind = 0; kind < 4; ++kind) {
      std::mt19937_64 rng(20261124u + static_cast<std::uint64_t>(kind));
      std::srand(20261124u);  // Eigen's Random() draws from rand()
      std::vector<int> wrong(std::size(margins_m), 0);
      std::string name;
      for (int i = 0; i < kPairs; ++i) {
        double d_m = 0.0;
        std::vector<PeerPrimitive> pair = SeparatedPair(&rng, kind, &d_m);
        for (std::size_t k = 0; k < std::size(margins_m); ++k) {
          for (const double sign : {1.0, -1.0}) {
            // The threshold a margin beyond (warn) or short of (no warning) the distance.
            pair[0].tolerance_m = d_m + sign * margins_m[k];
            const CompatibilityMatrix none(2);
            auto peer = use_fcl ? MakeFclChecker(pair, none, PeerTolerance::kRounded)
                                : MakeBulletChecker(pair, none, PeerTolerance::kRounded);
            name = peer->name();
            std::vector<CandidatePair> got;
            peer->FindWarnings(&got);
            wrong[k] += (!got.empty()) != (sign > 0.0);
          }
        }
      }
      std::printf("%-12s %-16s %39s", name.c_str(), kinds[kind], "");
      for (std::size_t k = 0; k < std::size(margins_m); ++k) {
        std::printf(" %8d", wrong[k]);
        if (margins_m[k] >= kPeerThresholdBand_m) {
          EXPECT_EQ(wrong[k], 0) << name << " " << kinds[kind] << " at margin " << margins_m[k];
        }
      }
      std::printf("\n");
    }
  }
}

}  // namespace
}  // namespace arm_collision_monitor
