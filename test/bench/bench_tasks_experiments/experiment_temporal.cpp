// Experiment "temporal" (3b): check rate and sub-stepping against missed warnings.

#include "experiments.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <map>

#include "arm_collision_monitor/geometry/distance.h"
#include "arm_collision_monitor/scene/workcell_shapes.h"

namespace arm_collision_monitor {
namespace bench {

void ExperimentTemporal(const Args& args, const Scenario& s, double check_us, Csv* csv) {
  const double kTruthStep_s = args.quick ? 0.0025 : 0.00125;
  const Workcell& wc = *s.workcell;
  WorkcellShapes eval(wc);
  // Fastest end-point speed of the recorded tasks (m per 50 ms cycle).
  double max_step_m = 0.0;
  std::vector<Eigen::Vector3d> previous;
  for (const TaskRun& task : s.tasks) {
    previous.clear();
    for (const Eigen::VectorXd& q : task.q) {
      eval.Evaluate(q);
      std::vector<Eigen::Vector3d> points;
      for (const PrimitiveId id : eval.moving()) {
        if (const auto* c = std::get_if<Capsule>(&eval.shape_W(id))) {
          points.push_back(c->p0_W);
          points.push_back(c->p1_W);
        }
      }
      if (!previous.empty()) {
        for (std::size_t i = 0; i < points.size(); ++i) {
          max_step_m = std::max(max_step_m, (points[i] - previous[i]).norm());
        }
      }
      previous = points;
    }
  }
  const double recorded_speed_mps = max_step_m / 0.05;
  struct Schedule {
    int checks_per_s;
    const char* label;
  };
  const Schedule schedules[] = {{5, "5 Hz"},       {10, "10 Hz"},      {20, "20 Hz"},
                                {40, "20 Hz x 2"}, {80, "20 Hz x 4"},  {160, "20 Hz x 8"}};
  const auto n = static_cast<PrimitiveId>(wc.primitives.size());
  Eigen::VectorXd q, qdot;
  std::printf("== check rate, scene %s: recorded tasks peak at %.3f m/s\n", s.label.c_str(),
              recorded_speed_mps);
  for (const double speed_mps : {0.61, 1.22}) {
    // Seconds of scaled time per recorded 50 ms cycle.
    const double cycle_s = 0.05 * recorded_speed_mps / speed_mps;
    std::vector<std::uint64_t> events(std::size(schedules), 0), missed(std::size(schedules), 0),
        contacts(std::size(schedules), 0), missed_contacts(std::size(schedules), 0);
    for (const TaskRun& task : s.tasks) {
      const CompatibilityMatrix compatible = TaskCompatibility(wc, task);
      const double duration_s = cycle_s * (task.q.size() - 1);
      const auto samples = static_cast<std::int64_t>(duration_s / kTruthStep_s) + 1;
      // Per pair: start of the current warning run (-1: none) and whether a contact began in it.
      std::map<std::pair<PrimitiveId, PrimitiveId>, std::pair<std::int64_t, std::int64_t>> open;
      auto close = [&](std::int64_t start, std::int64_t end, std::int64_t contact) {
        for (std::size_t k = 0; k < std::size(schedules); ++k) {
          const std::int64_t m = std::llround(1.0 / (schedules[k].checks_per_s * kTruthStep_s));
          ++events[k];
          if ((end / m) * m < start) ++missed[k];
          if (contact >= 0) {
            ++contacts[k];
            if ((contact / m) * m < start) ++missed_contacts[k];
          }
        }
      };
      for (std::int64_t i = 0; i < samples; ++i) {
        // The task's own smooth motion, time-scaled: recorded time = scaled time * 0.05 / cycle_s.
        TaskStateAt(task.number, wc, i * kTruthStep_s * 0.05 / cycle_s, &q, &qdot);
        eval.Evaluate(q);
        std::map<std::pair<PrimitiveId, PrimitiveId>, bool> now;  // warning pairs -> touching
        for (std::size_t ia = 0; ia < eval.moving().size(); ++ia) {
          const PrimitiveId a = eval.moving()[ia];
          for (PrimitiveId b = 0; b < n; ++b) {
            if (b == a || !eval.is_default_model(b) || compatible.AreCompatible(a, b)) continue;
            const bool b_moving = !wc.primitives[b].is_static;
            if (b_moving && b < a) continue;  // each moving pair once
            const double t = wc.primitives[a].tolerance_m + wc.primitives[b].tolerance_m;
            if (!IsCloserThan(eval.shape_W(a), eval.shape_W(b), t)) continue;
            const bool touching = !IsCloserThan(eval.shape_W(a), eval.shape_W(b), 0.0)
                                      ? ShapeDistance(eval.shape_W(a), eval.shape_W(b)).distance_m <= 0.0
                                      : true;
            now[{std::min(a, b), std::max(a, b)}] = touching;
          }
        }
        for (auto it = open.begin(); it != open.end();) {
          if (now.count(it->first) == 0) {
            close(it->second.first, i - 1, it->second.second);
            it = open.erase(it);
          } else {
            ++it;
          }
        }
        for (const auto& [pair, touching] : now) {
          auto it = open.find(pair);
          if (it == open.end()) it = open.emplace(pair, std::make_pair(i, std::int64_t{-1})).first;
          if (touching && it->second.second < 0) it->second.second = i;
        }
      }
      for (const auto& [pair, run] : open) close(run.first, samples - 1, run.second);
    }
    for (std::size_t k = 0; k < std::size(schedules); ++k) {
      csv->Row(s.label, speed_mps, schedules[k].checks_per_s, schedules[k].label,
              schedules[k].checks_per_s * check_us, events[k], missed[k], contacts[k],
              missed_contacts[k], recorded_speed_mps);
      std::printf("  %.2f m/s %-10s %6.0f us/s: %llu of %llu warning events missed, %llu of "
                  "%llu contacts unwarned\n",
                  speed_mps, schedules[k].label, schedules[k].checks_per_s * check_us,
                  static_cast<unsigned long long>(missed[k]),
                  static_cast<unsigned long long>(events[k]),
                  static_cast<unsigned long long>(missed_contacts[k]),
                  static_cast<unsigned long long>(contacts[k]));
    }
  }
}

}  // namespace bench
}  // namespace arm_collision_monitor
