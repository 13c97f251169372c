// Experiment "fidelity" (3a): cylinder models of the arm links against the exact URDF geometry.

#ifdef ACM_HAVE_PEERS
#include "experiments.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <map>
#include <tuple>

#include "arm_collision_monitor/core/timing_summary.h"
#include "arm_collision_monitor/geometry/distance.h"
#include "arm_collision_monitor/peers/exact_oracle.h"
#include "arm_collision_monitor/scene/workcell_shapes.h"

namespace arm_collision_monitor {
namespace bench {
namespace {

// Model fidelity (3a): models of each link whose URDF geometry is one bare cylinder (radius r,
// length L, axis z of its frame C), run by the Monitor and compared with the exact URDF geometry
// (FCL) per owner pair (link or object) and cycle. Links with other geometry (the grippers: a
// cylinder with a sphere of its radius on each end face, i.e. exactly a capsule) keep their
// default model in every model. Conservative models contain the cylinder; "tight" does not.
enum class CylinderModel {
  kCapsule,            // the default: the capsule of the cylinder's axis and radius
  kTightCapsule,       // caps ending on the end faces: inside the cylinder, not conservative
  kMinVolumeCapsule,   // one capsule: segment shortened by h, radius sqrt(r^2 + h^2)
  kParallel3,          // 3 parallel capsules, radius sqrt(3)/2 r, axes r/2 off-axis at 120 deg
  kParallel7,          // 7 parallel capsules, radius r/2: on the axis + 6 at sqrt(3)/2 r, 60 deg
  kCapsuleEndSpheres,  // capsule of radius r stopping 2h short of each end + a sphere per end
};

struct CylinderModelInfo {
  CylinderModel model;
  const char* label;
  bool is_conservative;
  const char* variant;  // scene-file variant name (switched in); nullptr: a links: override
};

const CylinderModelInfo kCylinderModels[] = {
    {CylinderModel::kCapsule, "capsule", true, nullptr},
    {CylinderModel::kTightCapsule, "tight capsule", false, nullptr},
    {CylinderModel::kMinVolumeCapsule, "min-volume capsule", true, nullptr},
    {CylinderModel::kParallel3, "3 parallel capsules", true, "parallel3"},
    {CylinderModel::kParallel7, "7 parallel capsules", true, "parallel7"},
    {CylinderModel::kCapsuleEndSpheres, "capsule + end spheres", true, "end_spheres"},
};

// Closed-form volumes (m^3) of one cylinder model outside the cylinder (`excess`) and of the
// cylinder outside the model (`uncovered`); NaN where there is none (the parallel covers).
//  - capsule: two hemispheres, 4/3 pi r^3 excess.
//  - tight: the capsule lies inside; the cylinder's corners outside it: 2/3 pi r^3 uncovered.
//  - min-volume capsule: pi R^2 (L - 2h) + 4/3 pi R^3 - pi r^2 L, R^2 = r^2 + h^2 (it reaches the
//    end faces' rim circles, so it contains the cylinder).
//  - capsule + end spheres: per end a sphere of radius R = sqrt(r^2 + h^2) centred on the axis
//    at depth h (it passes through the rim circle); for |z - z_c| <= h its cross-section has
//    radius sqrt(R^2 - (z - z_c)^2) >= r, and the capsule (radius r) covers the rest, its segment
//    ending at depth 2h; the capsule's cap lies inside the sphere (|P - c_s|^2 = r^2 + h^2 -
//    2 h (P - c_m).z <= R^2 on the cap). Outside the cylinder: the sphere's cap beyond the end
//    face, pi c^2 (3R - c) / 3 with c = R - h, and its bulge beyond the side,
//    pi int_{-h}^{h} (h^2 - u^2) du = 4/3 pi h^3. Needs L >= 4h.
struct ModelVolumes {
  double excess_m3 = 0.0, uncovered_m3 = 0.0;
};
double EndSphereExcess_m3(double r, double h) {
  const double R = std::hypot(r, h), c = R - h;
  return 4.0 / 3.0 * M_PI * h * h * h + M_PI * c * c * (3.0 * R - c) / 3.0;
}
double MinVolumeCapsuleVolume_m3(double r, double length, double h) {
  const double R2 = r * r + h * h;
  return M_PI * R2 * (length - 2.0 * h) + 4.0 / 3.0 * M_PI * R2 * std::sqrt(R2);
}
// The depth h of the min-volume capsule and of the end spheres (each minimises its excess).
double MinVolumeCapsuleDepth_m(double r, double length) {
  return GoldenSectionMinimum([&](double h) { return MinVolumeCapsuleVolume_m3(r, length, h); },
                              0.0, 0.5 * length);
}
double EndSphereDepth_m(double r, double length) {
  return GoldenSectionMinimum([&](double h) { return EndSphereExcess_m3(r, h); }, 0.0,
                              std::min(r, 0.25 * length));
}
ModelVolumes ClosedFormVolumes(CylinderModel model, double r, double length) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  switch (model) {
    case CylinderModel::kCapsule:
      return {4.0 / 3.0 * M_PI * r * r * r, 0.0};
    case CylinderModel::kTightCapsule:
      return length >= 2.0 * r ? ModelVolumes{0.0, 2.0 / 3.0 * M_PI * r * r * r}
                               : ModelVolumes{nan, nan};
    case CylinderModel::kMinVolumeCapsule:
      return {MinVolumeCapsuleVolume_m3(r, length, MinVolumeCapsuleDepth_m(r, length)) -
                  M_PI * r * r * length,
              0.0};
    case CylinderModel::kCapsuleEndSpheres:
      return {2.0 * EndSphereExcess_m3(r, EndSphereDepth_m(r, length)), 0.0};
    default:
      return {nan, nan};
  }
}

// The model's capsules of a cylinder, in the cylinder's frame C.
std::vector<Capsule> CylinderModelCapsules_C(CylinderModel model, double r, double length) {
  const double half = 0.5 * length;
  auto axial = [](double x, double y, double z0, double z1, double radius) {
    return Capsule{Eigen::Vector3d(x, y, z0), Eigen::Vector3d(x, y, z1), radius};
  };
  std::vector<Capsule> out;
  switch (model) {
    case CylinderModel::kCapsule:
      out.push_back(axial(0, 0, -half, half, r));
      break;
    case CylinderModel::kTightCapsule: {
      const double h = std::max(0.0, half - r);
      out.push_back(axial(0, 0, -h, h, r));
      break;
    }
    case CylinderModel::kMinVolumeCapsule: {
      const double h = MinVolumeCapsuleDepth_m(r, length);
      out.push_back(axial(0, 0, -(half - h), half - h, std::hypot(r, h)));
      break;
    }
    // Classic minimal coverings of a disc by 3 and 7 equal discs; segments end on the end faces.
    case CylinderModel::kParallel3:
      for (int k = 0; k < 3; ++k) {
        const double a = 2.0 * M_PI * k / 3.0;
        out.push_back(axial(0.5 * r * std::cos(a), 0.5 * r * std::sin(a), -half, half,
                            0.5 * std::sqrt(3.0) * r));
      }
      break;
    case CylinderModel::kParallel7:
      out.push_back(axial(0, 0, -half, half, 0.5 * r));
      for (int k = 0; k < 6; ++k) {
        const double a = M_PI * k / 3.0, d = 0.5 * std::sqrt(3.0) * r;
        out.push_back(axial(d * std::cos(a), d * std::sin(a), -half, half, 0.5 * r));
      }
      break;
    case CylinderModel::kCapsuleEndSpheres: {
      const double h = EndSphereDepth_m(r, length), R = std::hypot(r, h);
      out.push_back(axial(0, 0, -(half - 2.0 * h), half - 2.0 * h, r));
      out.push_back(axial(0, 0, half - h, half - h, R));
      out.push_back(axial(0, 0, -(half - h), -(half - h), R));
      break;
    }
  }
  return out;
}

// The links whose URDF geometry is one bare cylinder: link index -> that cylinder.
std::map<int, LinkElement> BareCylinderLinks(const ExactOracle& oracle) {
  std::map<int, std::vector<LinkElement>> by_link;
  for (const LinkElement& e : oracle.link_elements()) by_link[e.link_index].push_back(e);
  std::map<int, LinkElement> out;
  for (const auto& [link, elements] : by_link) {
    if (elements.size() == 1 && elements[0].kind == LinkElement::Kind::kCylinder) {
      out.emplace(link, elements[0]);
    }
  }
  return out;
}

std::string YamlPoint(const Eigen::Vector3d& p) {
  std::ostringstream out;
  out.precision(12);
  out << "[" << p.x() << ", " << p.y() << ", " << p.z() << "]";
  return out.str();
}

// Scene `s` with cylinder model `info` on every bare-cylinder link: a links: override for
// one-capsule models, a variant (switched in by RunMonitor) for several capsules.
Scenario MakeModelScenario(const Args& args, const Scenario& s, const ExactOracle& oracle,
                           const CylinderModelInfo& info) {
  if (info.model == CylinderModel::kCapsule) return s;
  const Workcell& wc = *s.workcell;
  std::ostringstream text;
  text.precision(12);
  for (const auto& [link, c] : BareCylinderLinks(oracle)) {
    const std::vector<Capsule> capsules = CylinderModelCapsules_C(info.model, c.radius_m,
                                                                  c.length_m);
    const std::string& name = wc.kinematics.link_name(link);
    if (info.variant == nullptr) {
      text << "  " << name << ": {p0_m: " << YamlPoint(c.X_LC * capsules[0].p0_W)
           << ", p1_m: " << YamlPoint(c.X_LC * capsules[0].p1_W)
           << ", radius_m: " << capsules[0].radius_m << "}\n";
      continue;
    }
    text << "  - {link: " << name << ", name: " << info.variant << ", capsules: [";
    for (std::size_t i = 0; i < capsules.size(); ++i) {
      text << (i ? ", " : "") << "{name: " << info.variant << i
           << ", p0_m: " << YamlPoint(c.X_LC * capsules[i].p0_W)
           << ", p1_m: " << YamlPoint(c.X_LC * capsules[i].p1_W)
           << ", radius_m: " << capsules[i].radius_m << "}";
    }
    text << "]}\n";
  }
  const std::string label = s.label + "_" + (info.variant ? info.variant : "override");
  Scenario out = MakeSceneScenario(
      args, s, label,
      InsertAfterKey(s.scene_yaml, info.variant ? "variants" : "links", text.str()));
  out.label = s.label;
  return out;
}

// The primitives of `model_wc` that model `link` under `variant` ("" = default): the variant's
// if the link has one, else the default ones.
std::vector<Capsule> LinkModelCapsules_L(const Workcell& model_wc, int link,
                                         const std::string& variant) {
  const bool has_variant = !variant.empty() && model_wc.FindVariant(
      model_wc.kinematics.link_name(link), variant) >= 0;
  std::vector<Capsule> out;
  for (const PrimitiveSpec& p : model_wc.primitives) {
    if (p.link_index != link || p.variant != (has_variant ? variant : std::string())) continue;
    out.push_back(std::get<Capsule>(p.shape_L));
  }
  return out;
}

// Seeded Monte Carlo volumes, summed over the links that have a URDF cylinder: per link,
// `samples` uniform points in an AABB (link frame) that encloses the exact geometry and the
// model's capsules. `exact_m3`: the exact geometry (with no model: sampled in its own AABB);
// `excess_m3`: the model outside it; `uncovered_m3`: it outside the model. Standard errors:
// binomial, per link, added in quadrature.
struct MonteCarloVolumes {
  double exact_m3 = 0, exact_se_m3 = 0, excess_m3 = 0, excess_se_m3 = 0, uncovered_m3 = 0,
         uncovered_se_m3 = 0;
};
MonteCarloVolumes EstimateVolumes(const ExactOracle& oracle, const Workcell* model_wc,
                                  const std::string& variant, std::uint64_t seed, int samples) {
  std::map<int, std::vector<LinkElement>> exact;
  for (const LinkElement& e : oracle.link_elements()) exact[e.link_index].push_back(e);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  MonteCarloVolumes v;
  double exact_var = 0, excess_var = 0, uncovered_var = 0;
  for (const auto& [link, elements] : exact) {
    if (std::none_of(elements.begin(), elements.end(), [](const LinkElement& e) {
          return e.kind == LinkElement::Kind::kCylinder;
        })) {
      continue;
    }
    std::vector<Capsule> model;
    if (model_wc != nullptr) model = LinkModelCapsules_L(*model_wc, link, variant);
    Aabb box = elements[0].ComputeAabb_L();
    auto grow = [&](const Aabb& b) {
      box.min_W = box.min_W.cwiseMin(b.min_W);
      box.max_W = box.max_W.cwiseMax(b.max_W);
    };
    for (const LinkElement& e : elements) grow(e.ComputeAabb_L());
    for (const Capsule& c : model) grow(c.ComputeAabb());
    const Eigen::Vector3d extent = box.max_W - box.min_W;
    const double box_m3 = extent.prod();
    std::int64_t in_exact = 0, excess = 0, uncovered = 0;
    for (int i = 0; i < samples; ++i) {
      const Eigen::Vector3d p_L =
          box.min_W + Eigen::Vector3d(unit(rng), unit(rng), unit(rng)).cwiseProduct(extent);
      const bool is_exact = std::any_of(elements.begin(), elements.end(),
                                        [&](const LinkElement& e) { return e.Contains(p_L); });
      // Inside a capsule: distance 0 from the zero-radius capsule at p_L.
      const bool is_model = std::any_of(model.begin(), model.end(), [&](const Capsule& c) {
        return CapsuleCapsuleDistance(Capsule{p_L, p_L, 0.0}, c).distance_m <= 0.0;
      });
      in_exact += is_exact;
      excess += is_model && !is_exact;
      uncovered += is_exact && !is_model;
    }
    auto var = [&](std::int64_t k) {
      const double p = static_cast<double>(k) / samples;
      return box_m3 * box_m3 * p * (1.0 - p) / samples;
    };
    v.exact_m3 += box_m3 * in_exact / samples;
    v.excess_m3 += box_m3 * excess / samples;
    v.uncovered_m3 += box_m3 * uncovered / samples;
    exact_var += var(in_exact);
    excess_var += var(excess);
    uncovered_var += var(uncovered);
  }
  v.exact_se_m3 = std::sqrt(exact_var);
  v.excess_se_m3 = std::sqrt(excess_var);
  v.uncovered_se_m3 = std::sqrt(uncovered_var);
  return v;
}

}  // namespace

double GoldenSectionMinimum(const std::function<double(double)>& f, double lo, double hi) {
  const double k = 0.5 * (std::sqrt(5.0) - 1.0);
  double a = lo, b = hi;
  double x1 = b - k * (b - a), x2 = a + k * (b - a), f1 = f(x1), f2 = f(x2);
  while (b - a > 1e-12 * (hi - lo)) {
    if (f1 < f2) {
      b = x2, x2 = x1, f2 = f1, x1 = b - k * (b - a), f1 = f(x1);
    } else {
      a = x1, x1 = x2, f1 = f2, x2 = a + k * (b - a), f2 = f(x2);
    }
  }
  return 0.5 * (a + b);
}

void ExperimentFidelity(const Args& args, const std::vector<const Scenario*>& scenarios,
                        Csv* csv) {
  const int samples = args.quick ? 100000 : 400000;
  // Volumes depend on the arms only: computed once, on the first scenario's models.
  std::vector<MonteCarloVolumes> mc;
  std::vector<double> closed_excess_m3;
  double exact_m3 = 0;
  {
    const Scenario& s = *scenarios.front();
    ExactOracle oracle(*s.workcell);
    double cylinders_m3 = 0;
    for (const auto& [link, c] : BareCylinderLinks(oracle)) {
      cylinders_m3 += M_PI * c.radius_m * c.radius_m * c.length_m;
    }
    // The one denominator of every percentage: the exact volume, sampled in its own AABBs.
    const MonteCarloVolumes exact = EstimateVolumes(oracle, nullptr, "", args.seed, samples);
    exact_m3 = exact.exact_m3;
    std::printf("== model fidelity: volumes by Monte Carlo (seed %llu, %d samples per link and "
                "model; +/- one standard error); exact geometry of the arm links %.6f +/- "
                "%.6f m^3\n",
                static_cast<unsigned long long>(args.seed), samples, exact_m3, exact.exact_se_m3);
    for (const CylinderModelInfo& info : kCylinderModels) {
      const Scenario model = MakeModelScenario(args, s, oracle, info);
      mc.push_back(EstimateVolumes(oracle, model.workcell.get(), info.variant ? info.variant : "",
                                   args.seed, samples));
      double excess = 0, uncovered = 0;
      for (const auto& [link, c] : BareCylinderLinks(oracle)) {
        const ModelVolumes cf = ClosedFormVolumes(info.model, c.radius_m, c.length_m);
        excess += cf.excess_m3;
        uncovered += cf.uncovered_m3;
      }
      closed_excess_m3.push_back(excess);
      const MonteCarloVolumes& v = mc.back();
      std::printf("  %-22s excess %7.3f +/- %.3f %% (closed form %7.3f %%), uncovered %6.3f +/- "
                  "%.3f %% (closed form %6.3f %%)\n",
                  info.label, 100 * v.excess_m3 / exact_m3, 100 * v.excess_se_m3 / exact_m3,
                  100 * excess / exact_m3, 100 * v.uncovered_m3 / exact_m3,
                  100 * v.uncovered_se_m3 / exact_m3, 100 * uncovered / exact_m3);
    }
    const LinkElement& c = BareCylinderLinks(oracle).begin()->second;
    std::printf("  depths: min-volume capsule h = %.4f r, end spheres h = %.4f r (r %.3f m, L "
                "%.3f m); bare cylinders %.6f m^3 of it\n",
                MinVolumeCapsuleDepth_m(c.radius_m, c.length_m) / c.radius_m,
                EndSphereDepth_m(c.radius_m, c.length_m) / c.radius_m, c.radius_m, c.length_m,
                cylinders_m3);
  }
  std::uint64_t conservative_missed = 0;
  for (const Scenario* sp : scenarios) {
    const Scenario& s = *sp;
    const Workcell& wc = *s.workcell;
    ExactOracle oracle(wc);
    // Exact warnings and the oracle's time per cycle (forward kinematics + all owner pairs).
    using OwnerPairs = std::vector<std::pair<int, int>>;
    std::vector<OwnerPairs> exact;
    std::vector<double> exact_us;
    WorkcellShapes eval(wc);
    for (const TaskRun& task : s.tasks) {
      const CompatibilityMatrix compatible = TaskCompatibility(wc, task);
      for (const Eigen::VectorXd& q : task.q) {
        OwnerPairs pairs;
        const auto t0 = Clock::now();
        eval.Evaluate(q);
        oracle.FindWarnings(eval.X_WL(), compatible, &pairs);
        exact_us.push_back(MicrosSince(t0));
        exact.push_back(std::move(pairs));
      }
    }
    std::printf("== model fidelity against the URDF geometry (FCL), scene %s\n", s.label.c_str());
    auto owner_index = [&](const Workcell& model, PrimitiveId id) {
      const PrimitiveSpec& p = model.primitives[id];
      const std::string name =
          p.link_index >= 0 ? model.kinematics.link_name(p.link_index) : p.owner;
      const auto& names = oracle.owner_names();
      return static_cast<int>(std::find(names.begin(), names.end(), name) - names.begin());
    };
    for (std::size_t m = 0; m < std::size(kCylinderModels); ++m) {
      const CylinderModelInfo& info = kCylinderModels[m];
      const Scenario model = MakeModelScenario(args, s, oracle, info);
      const std::string variant = info.variant ? info.variant : "";
      const auto run = [&] {
        return RunMonitor(model, DefaultOptions(), nullptr, info.label, variant);
      };
      const RunResult r = RunInTurns(args.repeats, {run}).front();
      std::uint64_t false_pairs = 0, missed_pairs = 0, total = 0;
      for (std::size_t c = 0; c < r.warnings.size(); ++c) {
        OwnerPairs pairs;
        for (const CandidatePair& p : r.warnings[c]) {
          int a = owner_index(*model.workcell, p.a);
          int b = owner_index(*model.workcell, p.b);
          if (a > b) std::swap(a, b);
          pairs.emplace_back(a, b);
        }
        std::sort(pairs.begin(), pairs.end());
        pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
        for (const auto& p : pairs) {
          false_pairs += !std::binary_search(exact[c].begin(), exact[c].end(), p);
        }
        for (const auto& p : exact[c]) {
          missed_pairs += !std::binary_search(pairs.begin(), pairs.end(), p);
        }
        total += pairs.size();
      }
      if (info.is_conservative) conservative_missed += missed_pairs;
      int arm_primitives = 0;
      for (const LinkElement& e : oracle.link_elements()) {
        if (e.kind == LinkElement::Kind::kCylinder) {
          arm_primitives += LinkModelCapsules_L(*model.workcell, e.link_index, variant).size();
        }
      }
      const TimingSummary sm = SummarizeTimings(r.t_us);
      const MonteCarloVolumes& v = mc[m];
      const double closed = closed_excess_m3[m];
      csv->Row(s.label, info.label, info.is_conservative ? 1 : 0, arm_primitives, sm.median,
               sm.mean, false_pairs, missed_pairs, total, 100 * v.excess_m3 / exact_m3,
               100 * v.excess_se_m3 / exact_m3, 100 * v.uncovered_m3 / exact_m3,
               std::isnan(closed) ? std::string() : std::to_string(100 * closed / exact_m3),
               samples, args.seed);
      std::printf("  %-22s %3d arm capsules  median %7.2f us  false %llu  missed %llu (of %llu "
                  "pair-cycles)  excess volume %.1f %%\n",
                  info.label, arm_primitives, sm.median,
                  static_cast<unsigned long long>(false_pairs),
                  static_cast<unsigned long long>(missed_pairs),
                  static_cast<unsigned long long>(total), 100 * v.excess_m3 / exact_m3);
    }
    std::uint64_t total_exact = 0;
    for (const auto& e : exact) total_exact += e.size();
    const TimingSummary se = SummarizeTimings(exact_us);
    csv->Row(s.label, "exact (FCL on URDF geometry)", 1, "", se.median, se.mean, 0, 0,
             total_exact, 0.0, 0.0, 0.0, 0.0, "", "");
    std::printf("  %-22s median %7.2f us  (%llu pair-cycles)\n", "exact", se.median,
                static_cast<unsigned long long>(total_exact));
  }
  std::printf(
      "conservative models (all but the tight capsule): %llu missed warning pair-cycles "
      "against the exact geometry -- %s\n",
      static_cast<unsigned long long>(conservative_missed),
      conservative_missed == 0 ? "none, as containment guarantees" : "CONTAINMENT VIOLATED");
}

}  // namespace bench
}  // namespace arm_collision_monitor
#endif  // ACM_HAVE_PEERS
