// Experiment "temporal" (3b): check rate and sub-stepping against missed warnings; and the
// Monitor's swept check at each rate: what it leaves unwarned, and its cost per cycle beside the
// same Monitor checking the samples only.

#include "experiments.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <map>

#include "arm_collision_monitor/geometry/distance.h"
#include "arm_collision_monitor/scene/workcell_shapes.h"

namespace arm_collision_monitor {
namespace bench {
namespace {

using PairKey = std::pair<PrimitiveId, PrimitiveId>;

// One Monitor run over a task's states at every m-th truth sample: the pairs it warned per
// check (at the sample or between samples, sorted) and its mean Update time.
struct SweptRun {
  std::vector<std::vector<PairKey>> warned;
  double mean_us = 0.0;
  std::uint64_t path_cycles = 0;  // cycles whose swept check needed the path
};

SweptRun RunAtRate(const Scenario& s, const TaskRun& task, const MonitorOptions& options,
                   const std::vector<Eigen::VectorXd>& states, std::int64_t m) {
  Monitor monitor(s.workcell, options);
  for (const TaskGraspTarget& g : task.grasp_targets) {
    std::string error;
    if (!monitor.SetGraspTarget(g.link, g.object, true, &error)) {
      std::fprintf(stderr, "SetGraspTarget: %s\n", error.c_str());
    }
  }
  SweptRun run;
  double total_us = 0.0;
  for (std::size_t i = 0; i < states.size(); i += static_cast<std::size_t>(m)) {
    const auto t0 = Clock::now();
    const CycleReport& report = monitor.Update(states[i]);
    total_us += MicrosSince(t0);
    run.path_cycles += report.swept_pairs > 0 ? 1 : 0;
    std::vector<PairKey> pairs;
    for (const Warning& w : report.warnings) pairs.emplace_back(w.a, w.b);
    run.warned.push_back(std::move(pairs));
  }
  run.mean_us = total_us / static_cast<double>(run.warned.size());
  return run;
}

// Whether `run` warned `pair` in a check whose step reaches into [first, last] (truth
// samples): check c covers the samples ((c - 1) m, c m].
bool IsWarnedWithin(const SweptRun& run, std::int64_t m, const PairKey& pair, std::int64_t first,
                    std::int64_t last) {
  const std::int64_t c_end = std::min<std::int64_t>(last / m + 1, run.warned.size() - 1);
  for (std::int64_t c = (first + m - 1) / m; c <= c_end; ++c) {
    const auto& w = run.warned[c];
    if (std::binary_search(w.begin(), w.end(), pair)) return true;
  }
  return false;
}

}  // namespace

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
  Eigen::VectorXd qdot;
  std::printf("== check rate, scene %s: recorded tasks peak at %.3f m/s\n", s.label.c_str(),
              recorded_speed_mps);
  for (const double speed_mps : {0.61, 1.22}) {
    // Seconds of scaled time per recorded 50 ms cycle.
    const double cycle_s = 0.05 * recorded_speed_mps / speed_mps;
    std::vector<std::uint64_t> events(std::size(schedules), 0), missed(std::size(schedules), 0),
        contacts(std::size(schedules), 0), missed_contacts(std::size(schedules), 0),
        swept_missed(std::size(schedules), 0), swept_unwarned(std::size(schedules), 0),
        path_cycles(std::size(schedules), 0), checks(std::size(schedules), 0);
    std::vector<double> swept_us(std::size(schedules), 0.0), samples_us(std::size(schedules), 0.0);
    // The Monitor at each rate: as configured (swept check on), and checking the samples only
    // (swept_check off needs a tolerance above the per-cycle motion: a 2 ms cycle_period_s,
    // which also shrinks the smallest octree cell from 13 to 10 cm).
    const MonitorOptions swept_options = DefaultOptions();
    MonitorOptions samples_options = swept_options;
    samples_options.swept_check = false;
    samples_options.cycle_period_s = 0.002;
    for (const TaskRun& task : s.tasks) {
      const CompatibilityMatrix compatible = TaskCompatibility(wc, task);
      const double duration_s = cycle_s * (task.q.size() - 1);
      const auto samples = static_cast<std::int64_t>(duration_s / kTruthStep_s) + 1;
      // Per pair: start of the current warning run (-1: none) and whether a contact began in it.
      std::map<std::pair<PrimitiveId, PrimitiveId>, std::pair<std::int64_t, std::int64_t>> open;
      std::vector<Eigen::VectorXd> states(samples);
      for (std::int64_t i = 0; i < samples; ++i) {
        TaskStateAt(task.number, wc, i * kTruthStep_s * 0.05 / cycle_s, &states[i], &qdot);
      }
      std::vector<SweptRun> runs;
      for (std::size_t k = 0; k < std::size(schedules); ++k) {
        const std::int64_t m = std::llround(1.0 / (schedules[k].checks_per_s * kTruthStep_s));
        runs.push_back(RunAtRate(s, task, swept_options, states, m));
        const SweptRun samples_only = RunAtRate(s, task, samples_options, states, m);
        const double n_checks = static_cast<double>(runs.back().warned.size());
        swept_us[k] += runs.back().mean_us * n_checks;
        samples_us[k] += samples_only.mean_us * n_checks;
        checks[k] += runs.back().warned.size();
        path_cycles[k] += runs.back().path_cycles;
      }
      auto close = [&](const PairKey& pair, std::int64_t start, std::int64_t end,
                       std::int64_t contact) {
        for (std::size_t k = 0; k < std::size(schedules); ++k) {
          const std::int64_t m = std::llround(1.0 / (schedules[k].checks_per_s * kTruthStep_s));
          ++events[k];
          if ((end / m) * m < start) ++missed[k];
          if (contact >= 0) {
            ++contacts[k];
            if ((contact / m) * m < start) ++missed_contacts[k];
          }
          // The swept check: intervals after the last check are no check's to find; a contact
          // counts as warned when the check that ends the step holding it, or one before, warns.
          if (start > static_cast<std::int64_t>(runs[k].warned.size() - 1) * m) continue;
          if (!IsWarnedWithin(runs[k], m, pair, start, end)) ++swept_missed[k];
          if (contact >= 0 && !IsWarnedWithin(runs[k], m, pair, start, contact)) {
            ++swept_unwarned[k];
          }
        }
      };
      for (std::int64_t i = 0; i < samples; ++i) {
        // The task's own smooth motion, time-scaled: recorded time = scaled time * 0.05 / cycle_s.
        eval.Evaluate(states[i]);
        std::map<std::pair<PrimitiveId, PrimitiveId>, bool> now;  // warning pairs -> touching
        for (std::size_t ia = 0; ia < eval.moving().size(); ++ia) {
          const PrimitiveId a = eval.moving()[ia];
          for (PrimitiveId b = 0; b < n; ++b) {
            if (b == a || !eval.is_default_model(b) || compatible.AreCompatible(a, b)) continue;
            const bool b_moving = !wc.primitives[b].is_static;
            if (b_moving && b < a) continue;  // each moving pair once
            const double t = wc.primitives[a].tolerance_m + wc.primitives[b].tolerance_m;
            if (!IsCloserThan(eval.shape_W(a), eval.shape_W(b), t)) continue;
            const bool touching =
                !IsCloserThan(eval.shape_W(a), eval.shape_W(b), 0.0)
                    ? ShapeDistance(eval.shape_W(a), eval.shape_W(b)).distance_m <= 0.0
                    : true;
            now[{std::min(a, b), std::max(a, b)}] = touching;
          }
        }
        for (auto it = open.begin(); it != open.end();) {
          if (now.count(it->first) == 0) {
            close(it->first, it->second.first, i - 1, it->second.second);
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
      for (const auto& [pair, run] : open) close(pair, run.first, samples - 1, run.second);
    }
    for (std::size_t k = 0; k < std::size(schedules); ++k) {
      csv->Row(s.label, speed_mps, schedules[k].checks_per_s, schedules[k].label,
              schedules[k].checks_per_s * check_us, events[k], missed[k], contacts[k],
              missed_contacts[k], recorded_speed_mps, swept_missed[k], swept_unwarned[k],
              swept_us[k] / checks[k], samples_us[k] / checks[k],
              static_cast<double>(path_cycles[k]) / checks[k]);
      std::printf("  %.2f m/s %-10s %6.0f us/s: %llu of %llu warning events missed, %llu of "
                  "%llu contacts unwarned; swept: %llu missed, %llu unwarned, %.2f us/cycle "
                  "(samples only %.2f), path needed in %.1f %%\n",
                  speed_mps, schedules[k].label, schedules[k].checks_per_s * check_us,
                  static_cast<unsigned long long>(missed[k]),
                  static_cast<unsigned long long>(events[k]),
                  static_cast<unsigned long long>(missed_contacts[k]),
                  static_cast<unsigned long long>(contacts[k]),
                  static_cast<unsigned long long>(swept_missed[k]),
                  static_cast<unsigned long long>(swept_unwarned[k]), swept_us[k] / checks[k],
                  samples_us[k] / checks[k], 100.0 * path_cycles[k] / checks[k]);
    }
  }
}

}  // namespace bench
}  // namespace arm_collision_monitor
