#include "test_monitor_util.h"
using namespace arm_collision_monitor;
TEST(P, P) {
  auto wc = test::LoadBundledWorkcell();
  const KinematicModel& m = wc->kinematics;
  std::vector<double> v4 = {0, 1.0, 1.6, 2.09}, v6 = {0, 1.0, 1.6, 2.09, -2.09}, v5 = {0, M_PI/2, M_PI}, v2={0,1.0,-1.0,2.0};
  int found = 0;
  for (double q2 : v2) for (double q4 : v4) for (double q5 : v5) for (double q6 : v6) {
    auto q = test::MakeQ(*wc, {{"left_joint2", q2}, {"left_joint4", q4}, {"left_joint5", q5}, {"left_joint6", q6}});
    for (auto& w : test::ReferenceWarnings(*wc, q)) {
      auto& pa = wc->primitives[w.a]; auto& pb = wc->primitives[w.b];
      if (pa.group == "left" && pb.group == "left" && m.parent_link(pa.link_index) != pb.link_index && m.parent_link(pb.link_index) != pa.link_index && found < 15) {
        printf("q2=%g q4=%g q5=%g q6=%g: %s d=%.3f thr=%.3f\n", q2, q4, q5, q6, test::Describe(*wc, w.a, w.b).c_str(), w.distance_m, w.threshold_m); ++found; }
    }
  }
}
