// The scenarios of the seed's experiments (experiments.h): files, the tasks mapped onto edited
// scenes, the default and seed-loop options, and the brute-force reference.

#include "experiments.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <regex>

#include "arm_collision_monitor/geometry/distance.h"
#include "arm_collision_monitor/scene/workcell_shapes.h"

namespace arm_collision_monitor {
namespace bench {

double MicrosSince(Clock::time_point t0) {
  return std::chrono::duration<double, std::micro>(Clock::now() - t0).count();
}

std::string SourcePath(const std::string& rel) { return std::string(ACM_SOURCE_DIR) + "/" + rel; }

std::string ReadFile(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

void WriteFile(const std::string& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
}

std::vector<TaskRun> MakeTasks(const Workcell& workcell) {
  std::vector<TaskRun> tasks;
  for (int task = 1; task <= kTaskCount; ++task) {
    const TaskSpec& spec = GetTaskSpec(task);
    tasks.push_back(TaskRun{task, spec.name, MakeTaskTrajectory(task, workcell),
                            spec.grasp_targets});
  }
  return tasks;
}

CompatibilityMatrix TaskCompatibility(const Workcell& wc, const TaskRun& task) {
  CompatibilityMatrix m = wc.compatible;
  for (const TaskGraspTarget& g : task.grasp_targets) {
    const int object = wc.FindObject(g.object);
    if (object < 0) continue;
    const PrimitiveId object_primitive = wc.objects[object].primitive;
    for (std::size_t id = 0; id < wc.primitives.size(); ++id) {
      if (wc.primitives[id].owner == g.link)
        m.Set(static_cast<PrimitiveId>(id), object_primitive, true);
    }
  }
  return m;
}

std::string InsertAfterKey(const std::string& yaml, const std::string& key,
                           const std::string& extra_yaml) {
  const std::string needle = "\n" + key + ":\n";
  const std::size_t at = yaml.find(needle);
  if (at == std::string::npos) {
    std::fprintf(stderr, "scene file has no top-level '%s:' list\n", key.c_str());
    std::exit(1);
  }
  std::string out = yaml;
  out.insert(at + needle.size(), extra_yaml);
  return out;
}

std::string ExtraBoxesYaml(std::mt19937_64* rng, int count, bool near) {
  std::uniform_real_distribution<double> edge(0.02, 0.08);
  std::uniform_real_distribution<double> nx(-0.6, 1.6), ny(-2.0, 2.0), nz(0.05, 2.6);
  std::uniform_real_distribution<double> fxy(-3.0, 3.0), fz(3.2, 6.0);
  std::ostringstream out;
  out.precision(6);
  for (int i = 0; i < count; ++i) {
    const double x = near ? nx(*rng) : fxy(*rng);
    const double y = near ? ny(*rng) : fxy(*rng);
    const double z = near ? nz(*rng) : fz(*rng);
    out << "  - {name: extra" << i << ", size_m: [" << edge(*rng) << ", " << edge(*rng) << ", "
        << edge(*rng) << "], pose: {xyz_m: [" << x << ", " << y << ", " << z << "]}}\n";
  }
  return out.str();
}

ArmCopies MakeArmCopies(int pairs) {
  static const double kShift_m[4][2] = {{0.0, 0.0}, {-1.3, 0.0}, {-1.3, 1.6}, {-1.3, -1.6}};
  const std::string urdf = ReadFile(SourcePath("urdf/workcell.urdf"));
  const std::string scene = ReadFile(SourcePath("config/scene.yaml"));
  const std::size_t body_start = urdf.find("<link name=\"world\"/>") + 20;
  const std::size_t body_end = urdf.rfind("</robot>");
  const std::string body = urdf.substr(body_start, body_end - body_start);
  std::string copies, arms, links;
  for (int k = 1; k < pairs; ++k) {
    const std::string p = "c" + std::to_string(k);
    // Links and joints renamed (materials keep their names: they are defined once).
    std::string b = std::regex_replace(
        body, std::regex("(<link name|<joint name|parent link|child link)=\"(left|right)_"),
        "$1=\"" + p + "$2_");
    for (const char* side : {"left", "right"}) {
      const double y0 = std::string(side) == "left" ? 0.55 : -0.55;
      std::ostringstream from, to;
      from << "<origin xyz=\"0 " << (y0 > 0 ? "0.55" : "-0.55") << " 0\"";
      to << "<origin xyz=\"" << kShift_m[k][0] << " " << y0 + kShift_m[k][1] << " 0\"";
      const std::size_t at = b.find(from.str());
      b.replace(at, from.str().size(), to.str());
      arms += "  - {name: " + p + side + ", root_link: " + p + side +
              "_base_link, tolerance_m: 0.0305}\n";
      links += "  " + p + side + "_base_link: {ignore: true}\n";
    }
    copies += b;
  }
  ArmCopies out;
  out.urdf = urdf.substr(0, body_end) + copies + "</robot>\n";
  out.scene = InsertAfterKey(InsertAfterKey(scene, "arms", arms), "links", links);
  return out;
}

std::vector<TaskRun> MapTasks(const std::vector<TaskRun>& base, const Workcell& base_wc,
                              const Workcell& wc) {
  std::vector<int> source(wc.joint_names.size()), shift(wc.joint_names.size(), 0);
  for (std::size_t i = 0; i < wc.joint_names.size(); ++i) {
    std::string name = wc.joint_names[i];
    std::smatch m;
    if (std::regex_match(name, m, std::regex("c([0-9]+)(.*)"))) {
      shift[i] = 37 * std::stoi(m[1]);
      name = m[2];
    }
    const auto it = std::find(base_wc.joint_names.begin(), base_wc.joint_names.end(), name);
    source[i] = static_cast<int>(it - base_wc.joint_names.begin());
  }
  std::vector<TaskRun> out;
  for (const TaskRun& t : base) {
    TaskRun r{t.number, t.name, {}, t.grasp_targets};
    const std::size_t n = t.q.size();
    for (std::size_t c = 0; c < n; ++c) {
      Eigen::VectorXd q(wc.joint_names.size());
      for (std::size_t i = 0; i < source.size(); ++i) q[i] = t.q[(c + shift[i]) % n][source[i]];
      r.q.push_back(q);
    }
    out.push_back(std::move(r));
  }
  return out;
}

Scenario MakeSceneScenario(const Args& args, const Scenario& base, const std::string& label,
                           const std::string& yaml) {
  Scenario s;
  s.label = label;
  s.scene_yaml = yaml;
  const std::string path = args.out_dir + "/scene_" + label + ".yaml";
  WriteFile(path, yaml);
  s.workcell =
      std::make_shared<const Workcell>(LoadWorkcell(SourcePath("urdf/workcell.urdf"), path));
  std::remove(path.c_str());
  s.tasks = MapTasks(base.tasks, *base.workcell, *s.workcell);
  return s;
}

MonitorOptions DefaultOptions() { return LoadMonitorOptions(SourcePath("config/monitor.yaml")); }

MonitorOptions SeedLoopOptions() {
  MonitorOptions o = DefaultOptions();
  o.index_slack_m = 0.0;
  o.broad_phase.method = BroadPhaseMethod::kOctree;
  return o;
}

MonitorOptions SweptOffOptions() {
  MonitorOptions o = DefaultOptions();
  o.swept_check = false;
  o.cycle_period_s /= 25.0;
  o.max_speed_mps *= 25.0;
  return o;
}

Reference BruteForce(const Scenario& s, int stride) {
  const Workcell& wc = *s.workcell;
  WorkcellShapes eval(wc);
  Reference ref;
  const auto n = static_cast<PrimitiveId>(wc.primitives.size());
  for (const TaskRun& task : s.tasks) {
    const CompatibilityMatrix compatible = TaskCompatibility(wc, task);
    for (std::size_t c = 0; c < task.q.size(); ++c) {
      const bool check = c % stride == 0;
      ref.checked.push_back(check);
      if (!check) {
        ref.warnings.emplace_back();
        ref.borderline.emplace_back();
        continue;
      }
      eval.Evaluate(task.q[c]);
      PairSet w, border;
      for (PrimitiveId a = 0; a < n; ++a) {
        if (!eval.is_default_model(a)) continue;
        for (PrimitiveId b = a + 1; b < n; ++b) {
          if (!eval.is_default_model(b)) continue;
          if (wc.primitives[a].is_static && wc.primitives[b].is_static) continue;
          if (compatible.AreCompatible(a, b)) continue;
          const double t = wc.primitives[a].tolerance_m + wc.primitives[b].tolerance_m;
          if (!IsCloserThan(eval.shape_W(a), eval.shape_W(b), t + 1e-9)) continue;
          const double d = ShapeDistance(eval.shape_W(a), eval.shape_W(b)).distance_m;
          if (std::abs(d - t) <= 1e-9) {
            border.push_back({a, b});
          } else if (d < t) {
            w.push_back({a, b});
          }
        }
      }
      ref.warnings.push_back(std::move(w));
      ref.borderline.push_back(std::move(border));
    }
  }
  return ref;
}

void Diff(const PairSet& got, const PairSet& want, const PairSet& border, PairSet* extra,
          PairSet* missing) {
  extra->clear();
  missing->clear();
  auto in = [](const PairSet& v, const CandidatePair& p) {
    return std::binary_search(v.begin(), v.end(), p);
  };
  for (const auto& p : got) {
    if (!in(want, p) && !in(border, p)) extra->push_back(p);
  }
  for (const auto& p : want) {
    if (!in(got, p) && !in(border, p)) missing->push_back(p);
  }
}

}  // namespace bench
}  // namespace arm_collision_monitor
