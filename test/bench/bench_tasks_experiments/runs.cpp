// The timed runs of the seed's experiments (experiments.h): the Monitor and the peers over a
// scenario's tasks, checked against brute force, taken in turns.

#include "experiments.h"

#include <algorithm>
#include <cstring>

#include <benchmark/benchmark.h>

#include "arm_collision_monitor/core/timing_summary.h"
#include "arm_collision_monitor/scene/workcell_shapes.h"

namespace arm_collision_monitor {
namespace bench {
namespace {

void CheckAgainst(const Reference* ref, RunResult* r) {
  if (ref == nullptr) return;
  PairSet extra, missing;
  for (std::size_t c = 0; c < r->warnings.size(); ++c) {
    if (!ref->checked[c]) continue;
    Diff(r->warnings[c], ref->warnings[c], ref->borderline[c], &extra, &missing);
    r->missed += missing.size();
    r->false_warnings += extra.size();
  }
}

#ifdef ACM_HAVE_PEERS
std::vector<PeerPrimitive> PeerPrimitives(const Workcell& wc, const WorkcellShapes& eval) {
  std::vector<PeerPrimitive> out;
  for (PrimitiveId id = 0; id < wc.primitives.size(); ++id) {
    const PrimitiveSpec& p = wc.primitives[id];
    out.push_back(PeerPrimitive{eval.shape_W(id), p.tolerance_m, !p.is_static,
                                eval.is_default_model(id)});
  }
  return out;
}

// A peer's cycle at q: the forward kinematics, the moving shapes handed over, its query.
void RunPeerCycle(const Eigen::VectorXd& q, WorkcellShapes* eval, PeerChecker* peer,
                  PairSet* warnings) {
  eval->Evaluate(q);
  for (const PrimitiveId id : eval->moving()) peer->SetShape(id, eval->shape_W(id));
  peer->FindWarnings(warnings);
}
#endif

// The Monitor of one task: `variant` switched to where a link has it, the grasp targets set.
void SetUpTask(const Scenario& s, const TaskRun& task, const std::string& variant,
               Monitor* monitor) {
  for (const ModelVariantSpec& v : s.workcell->variants) {
    std::string error;
    if (!variant.empty() && v.name == variant && !monitor->SwitchModel(v.link, v.name, &error)) {
      std::fprintf(stderr, "SwitchModel: %s\n", error.c_str());
      std::exit(1);
    }
  }
  for (const TaskGraspTarget& g : task.grasp_targets) {
    std::string error;
    if (!monitor->SetGraspTarget(g.link, g.object, true, &error)) {
      std::fprintf(stderr, "SetGraspTarget: %s\n", error.c_str());
    }
  }
}

}  // namespace

RunResult RunMonitor(const Scenario& s, const MonitorOptions& options, const Reference* ref,
                     const std::string& impl, const std::string& variant) {
  RunResult r;
  r.impl = impl;
  for (std::size_t ti = 0; ti < s.tasks.size(); ++ti) {
    const TaskRun& task = s.tasks[ti];
    {
      Monitor warm_up(s.workcell, options);
      SetUpTask(s, task, variant, &warm_up);
      for (std::size_t c = 0; c < std::min(task.q.size(), kWarmUpCycles); ++c) {
        benchmark::DoNotOptimize(warm_up.Update(task.q[c]).stop);
      }
    }
    Monitor monitor(s.workcell, options);
    SetUpTask(s, task, variant, &monitor);
    r.chosen = monitor.broad_phase_name();
    r.active_primitives = 0;
    for (PrimitiveId id = 0; id < monitor.primitive_count(); ++id) {
      r.active_primitives += monitor.is_active(id);
    }
    for (std::size_t c = 0; c < task.q.size(); ++c) {
      const auto t0 = Clock::now();
      const CycleReport& report = monitor.Update(task.q[c]);
      const double dt = MicrosSince(t0);
      benchmark::DoNotOptimize(report.stop);
      if (c > 0) {
        r.t_us.push_back(dt);
        r.t_task.push_back(static_cast<std::uint8_t>(ti));
      }
      PairSet w;
      for (const Warning& warning : report.warnings) w.push_back({warning.a, warning.b});
      r.warnings.push_back(std::move(w));
      r.counters += report.counters;
      r.reindexed += report.reindexed_primitives;
      r.candidate_pairs += report.candidate_pairs;
      r.narrow_phase_tests += report.narrow_phase_tests;
    }
  }
  CheckAgainst(ref, &r);
  return r;
}

std::vector<double> TaskMeans(const RunResult& r, std::size_t tasks) {
  std::vector<double> sum_us(tasks, 0.0);
  std::vector<std::size_t> samples(tasks, 0);
  for (std::size_t i = 0; i < r.t_us.size(); ++i) {
    sum_us[r.t_task[i]] += r.t_us[i];
    ++samples[r.t_task[i]];
  }
  for (std::size_t ti = 0; ti < tasks; ++ti) sum_us[ti] /= std::max<std::size_t>(1, samples[ti]);
  return sum_us;
}

std::vector<RunResult> RunInTurns(int repeats,
                                  const std::vector<std::function<RunResult()>>& runs) {
  std::vector<RunResult> results(runs.size());
  for (int pass = 0; pass < repeats; ++pass) {
    for (std::size_t turn = 0; turn < runs.size(); ++turn) {
      // Each pass starts one row later: no row is always timed first.
      const std::size_t i = (turn + static_cast<std::size_t>(pass)) % runs.size();
      RunResult next = runs[i]();
      next.t_us.insert(next.t_us.begin(), results[i].t_us.begin(), results[i].t_us.end());
      next.t_task.insert(next.t_task.begin(), results[i].t_task.begin(), results[i].t_task.end());
      results[i] = std::move(next);
    }
  }
  return results;
}

std::vector<RunResult> RunConfigurations(int repeats, const Scenario& s, const Reference& ref,
                                         const std::vector<Configuration>& configs) {
  std::vector<std::function<RunResult()>> runs;
  for (const Configuration& c : configs) {
    runs.push_back([&s, &ref, &c] { return RunMonitor(s, c.options, &ref, c.label); });
  }
  return RunInTurns(repeats, runs);
}

#ifdef ACM_HAVE_PEERS
RunResult RunPeer(const Scenario& s, const PeerFactory& factory, const Reference* ref,
                  bool idle_skip) {
  RunResult r;
  const Workcell& wc = *s.workcell;
  for (std::size_t ti = 0; ti < s.tasks.size(); ++ti) {
    const TaskRun& task = s.tasks[ti];
    {
      WorkcellShapes eval(wc);
      auto warm_up = factory(PeerPrimitives(wc, eval), TaskCompatibility(wc, task));
      PairSet w;
      for (std::size_t c = 0; c < std::min(task.q.size(), kWarmUpCycles); ++c) {
        RunPeerCycle(task.q[c], &eval, warm_up.get(), &w);
      }
    }
    WorkcellShapes eval(wc);
    auto peer = factory(PeerPrimitives(wc, eval), TaskCompatibility(wc, task));
    r.impl = peer->name() + (idle_skip ? " (idle skip)" : "");
    PairSet w;
    for (std::size_t c = 0; c < task.q.size(); ++c) {
      const auto t0 = Clock::now();
      // Bit-identical, the Monitor's idle test.
      const bool idle = idle_skip && c > 0 &&
                        std::memcmp(task.q[c].data(), task.q[c - 1].data(),
                                    sizeof(double) * task.q[c].size()) == 0;
      if (!idle) RunPeerCycle(task.q[c], &eval, peer.get(), &w);
      const double dt = MicrosSince(t0);
      if (c > 0) {
        r.t_us.push_back(dt);
        r.t_task.push_back(static_cast<std::uint8_t>(ti));
      }
      r.warnings.push_back(w);
    }
  }
  CheckAgainst(ref, &r);
  return r;
}

std::vector<std::pair<std::string, PeerFactory>> Peers() {
  return {
      {"fcl_sharp",
       [](const auto& p, const auto& c) { return MakeFclChecker(p, c, PeerTolerance::kSharp); }},
      {"fcl_rounded",
       [](const auto& p, const auto& c) { return MakeFclChecker(p, c, PeerTolerance::kRounded); }},
      {"bullet_rounded",
       [](const auto& p, const auto& c) {
         return MakeBulletChecker(p, c, PeerTolerance::kRounded);
       }},
      {"bullet_sharp",
       [](const auto& p, const auto& c) {
         return MakeBulletChecker(p, c, PeerTolerance::kSharp);
       }},
  };
}
#endif

std::vector<RunResult> RunScalingImplementations(const Scenario& s, const Reference& ref,
                                                 const MonitorOptions& base) {
  std::vector<RunResult> results;
  for (const char* method : {"octree", "naive", "grid"}) {
    MonitorOptions o = base;
    ParseBroadPhaseMethod(method, &o.broad_phase.method);
    results.push_back(RunMonitor(s, o, &ref, method));
  }
#ifdef ACM_HAVE_PEERS
  for (const auto& [name, factory] : Peers()) {
    if (name == "fcl_sharp" || name == "bullet_rounded") {
      results.push_back(RunPeer(s, factory, &ref));
    }
  }
#endif
  return results;
}

void PrintRow(const RunResult& r) {
  const TimingSummary s = SummarizeTimings(r.t_us);
  std::printf(
      "  %-16s mean %8.2f us  median %8.2f  p99 %8.2f  max %9.2f  missed %llu  false %llu\n",
      r.impl.c_str(), s.mean, s.median, s.p99, s.max, static_cast<unsigned long long>(r.missed),
      static_cast<unsigned long long>(r.false_warnings));
  std::fflush(stdout);
}

}  // namespace bench
}  // namespace arm_collision_monitor
