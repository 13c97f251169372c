// Experiment "cylinders" (3a, scene objects): the cylinder_model options (capsule, box) of
// scene cylinders against the exact cylinder, for the arms' capsules.

#ifdef ACM_HAVE_PEERS
#include <fcl/narrowphase/distance.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "arm_collision_monitor/geometry/distance.h"
#include "arm_collision_monitor/scene/workcell_shapes.h"
#include "experiments.h"

namespace arm_collision_monitor {
namespace bench {
namespace {

// Cans of a soft-drink size, m.
constexpr double kCanRadius_m = 0.033;
constexpr double kCanLength_m = 0.12;
constexpr int kUprightCans = 16;  // standing on the front table under the tools' paths
constexpr int kTiltedCans = 8;    // in the air beside the paths, any orientation
// The reference's error bound (m): the golden-section bracket of the segment parameter ends
// below 1e-12, and the point distance is Lipschitz in it with the segment's length (< 1 m),
// so the minimum is found within 1e-12 m; 1e-9 m leaves room for rounding.
constexpr double kReferenceAccuracy_m = 1e-9;

// A can: its frame C (centre, axis along z) in W.
struct Can {
  Eigen::Isometry3d X_WC = Eigen::Isometry3d::Identity();
  Eigen::Vector3d rpy = Eigen::Vector3d::Zero();
};

// Distance (m) from point p_C to the solid cylinder of radius r_m and half length hl_m about
// C's z axis.
double PointCylinderDistance_m(const Eigen::Vector3d& p_C, double r_m, double hl_m) {
  const double radial_m = std::max(std::hypot(p_C.x(), p_C.y()) - r_m, 0.0);
  const double axial_m = std::max(std::abs(p_C.z()) - hl_m, 0.0);
  return std::hypot(radial_m, axial_m);
}

// The exact distance (m, 0 when they meet) between a capsule and the can: the distance from a
// point to a convex solid is convex in the point, hence along the capsule's segment, so golden-
// section search finds its minimum (error: kReferenceAccuracy_m).
double CapsuleCanDistance_m(const Capsule& c_W, const Can& can) {
  const Eigen::Isometry3d X_CW = can.X_WC.inverse(Eigen::Isometry);
  const Eigen::Vector3d a_C = X_CW * c_W.p0_W, ab_C = X_CW * c_W.p1_W - a_C;
  const auto f = [&](double t) {
    return PointCylinderDistance_m(a_C + t * ab_C, kCanRadius_m, 0.5 * kCanLength_m);
  };
  return std::max(0.0, f(GoldenSectionMinimum(f, 0.0, 1.0)) - c_W.radius_m);
}

// FCL's capsule-cylinder distance, the independent check of the reference: GJK with FCL's own
// solver (GST_INDEP). Its default, libccd, over-estimated some of these pairs by up to 8 mm
// (seed 20261121; dense sampling of the cylinder's surface agreed with the reference).
double FclCapsuleCanDistance_m(const Capsule& c_W, const Can& can) {
  const Eigen::Vector3d axis_W = c_W.p1_W - c_W.p0_W;
  Eigen::Isometry3d X_WK = Eigen::Isometry3d::Identity();
  X_WK.translation() = 0.5 * (c_W.p0_W + c_W.p1_W);
  X_WK.linear() =
      Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), axis_W).toRotationMatrix();
  const fcl::Capsuled capsule(c_W.radius_m, axis_W.norm());
  const fcl::Cylinderd cylinder(kCanRadius_m, kCanLength_m);
  fcl::DistanceRequestd request;
  request.gjk_solver_type = fcl::GST_INDEP;
  fcl::DistanceResultd result;
  return fcl::distance(&capsule, X_WK, &cylinder, can.X_WC, request, result);
}

// The cans: upright ones on the front table top (z 0.75 m) near points of the tools' paths
// over it, tilted ones beside points of the paths anywhere; seeded.
std::vector<Can> MakeCans(const Scenario& s, std::mt19937_64* rng) {
  WorkcellShapes eval(*s.workcell);
  std::vector<Eigen::Vector3d> over_table_W, anywhere_W;
  for (const TaskRun& task : s.tasks) {
    for (const Eigen::VectorXd& q : task.q) {
      eval.Evaluate(q);
      for (const char* tool : {"left_link7", "right_link7"}) {
        const int link = s.workcell->kinematics.FindLink(tool);
        const Eigen::Vector3d p_W = eval.X_WL()[link].translation();
        anywhere_W.push_back(p_W);
        if (std::abs(p_W.x() - 0.95) < 0.35 && std::abs(p_W.y()) < 0.85 && p_W.z() < 1.2) {
          over_table_W.push_back(p_W);
        }
      }
    }
  }
  std::uniform_real_distribution<double> offset(-0.12, 0.12), angle(-M_PI, M_PI);
  auto pick = [&](const std::vector<Eigen::Vector3d>& points) {
    return points[std::uniform_int_distribution<std::size_t>(0, points.size() - 1)(*rng)];
  };
  std::vector<Can> cans;
  for (int i = 0; i < kUprightCans + kTiltedCans; ++i) {
    const bool upright = i < kUprightCans && !over_table_W.empty();
    const Eigen::Vector3d p_W = pick(upright ? over_table_W : anywhere_W);
    Can can;
    Eigen::Vector3d c_W = p_W + Eigen::Vector3d(offset(*rng), offset(*rng), offset(*rng));
    if (upright) {
      c_W.x() = std::clamp(c_W.x(), 0.6, 1.3);
      c_W.y() = std::clamp(c_W.y(), -0.85, 0.85);
      c_W.z() = 0.75 + 0.5 * kCanLength_m;
    } else {
      can.rpy = Eigen::Vector3d(angle(*rng), angle(*rng), angle(*rng));
    }
    can.X_WC = PoseFromXyzRpy(c_W, can.rpy);
    cans.push_back(can);
  }
  return cans;
}

std::string CansYaml(const std::vector<Can>& cans) {
  std::ostringstream out;
  out.precision(17);
  for (std::size_t i = 0; i < cans.size(); ++i) {
    const Eigen::Vector3d& p = cans[i].X_WC.translation();
    const Eigen::Vector3d& r = cans[i].rpy;
    out << "  - {name: can" << i << ", type: cylinder, radius_m: " << kCanRadius_m
        << ", length_m: " << kCanLength_m << ", pose: {xyz_m: [" << p.x() << ", " << p.y() << ", "
        << p.z() << "], rpy: [" << r.x() << ", " << r.y() << ", " << r.z() << "]}}\n";
  }
  return out.str();
}

// A random q within the joint limits (continuous joints: a full turn).
Eigen::VectorXd RandomConfiguration(const KinematicModel& model, std::mt19937_64* rng) {
  Eigen::VectorXd q = Eigen::VectorXd::Zero(model.q_size());
  for (int link = 1; link < model.link_count(); ++link) {
    const JointSpec& joint = model.joint(link);
    if (joint.q_index < 0) continue;
    const bool turn = joint.type == JointType::kContinuous;
    q[joint.q_index] = std::uniform_real_distribution<double>(
        turn ? -M_PI : joint.lower, turn ? M_PI : joint.upper)(*rng);
  }
  return q;
}

// Counts of one model on one workload, pairs (arm capsule, can) over every configuration.
struct Counts {
  std::uint64_t pairs = 0, model_warnings = 0, exact_warnings = 0, false_warnings = 0,
                missed = 0, borderline = 0;
};

// The cans' workcells (one per cylinder model), the cans, and the pairs compared.
struct CanWorkload {
  std::vector<Scenario> models;
  std::vector<Can> cans;
  std::vector<PrimitiveId> can_ids;  // per can, in every model's workcell
  std::vector<PrimitiveId> arm;      // the arms' moving capsules of the default model
};

// The reference check against FCL of one workload.
struct FclCheck {
  std::uint64_t pairs = 0;
  double max_difference_m = 0.0;
};

// Counts per model over `configurations`; the reference checked against FCL on the pairs that
// are separated and within 0.5 m of their threshold.
std::vector<Counts> CountWarnings(const CanWorkload& w,
                                  const std::vector<Eigen::VectorXd>& configurations,
                                  FclCheck* fcl) {
  const Workcell& wc = *w.models.front().workcell;
  std::vector<Counts> counts(w.models.size());
  std::vector<WorkcellShapes> evals;
  evals.reserve(w.models.size());
  for (const Scenario& m : w.models) evals.emplace_back(*m.workcell);
  const double bound_m = std::hypot(kCanRadius_m, 0.5 * kCanLength_m);
  for (const Eigen::VectorXd& q : configurations) {
    for (WorkcellShapes& e : evals) e.Evaluate(q);
    for (const PrimitiveId a : w.arm) {
      const Capsule& arm_W = std::get<Capsule>(evals.front().shape_W(a));
      for (std::size_t i = 0; i < w.cans.size(); ++i) {
        const Can& can = w.cans[i];
        const double threshold_m =
            wc.primitives[a].tolerance_m + wc.primitives[w.can_ids[i]].tolerance_m;
        // A lower bound, from the can's bounding sphere; far beyond the threshold it stands in
        // for the exact distance (no warning either way).
        const Capsule centre{can.X_WC.translation(), can.X_WC.translation(), 0.0};
        const double lower_m = CapsuleCapsuleDistance(arm_W, centre).distance_m - bound_m;
        const double exact_m =
            lower_m > threshold_m + 1.0 ? lower_m : CapsuleCanDistance_m(arm_W, can);
        if (exact_m > 0.0 && exact_m < threshold_m + 0.5) {
          const double difference_m = std::abs(FclCapsuleCanDistance_m(arm_W, can) - exact_m);
          fcl->max_difference_m = std::max(fcl->max_difference_m, difference_m);
          ++fcl->pairs;
        }
        const bool is_border = std::abs(exact_m - threshold_m) <= kReferenceAccuracy_m;
        const bool exact_warns = exact_m < threshold_m;
        for (std::size_t m = 0; m < w.models.size(); ++m) {
          // The Monitor's narrow-phase decision on the model.
          const bool model_warns = IsCloserThan(arm_W, evals[m].shape_W(w.can_ids[i]), threshold_m);
          Counts& c = counts[m];
          ++c.pairs;
          c.model_warnings += model_warns;
          c.exact_warnings += exact_warns;
          c.borderline += is_border;
          c.false_warnings += model_warns && !exact_warns && !is_border;
          c.missed += !model_warns && exact_warns && !is_border;
        }
      }
    }
  }
  return counts;
}

}  // namespace

void ExperimentFidelityCylinders(const Args& args, const Scenario& base, Csv* csv) {
  std::mt19937_64 rng(args.seed);
  CanWorkload w;
  w.cans = MakeCans(base, &rng);
  const char* const kModels[] = {"capsule", "box"};
  for (const char* model : kModels) {
    const std::string scene = InsertAfterKey(base.scene_yaml, "objects", CansYaml(w.cans)) +
                              "\ncylinder_model: " + model + "\n";
    w.models.push_back(MakeSceneScenario(args, base, std::string("cans_") + model, scene));
  }
  const Workcell& wc = *w.models.front().workcell;
  for (PrimitiveId id = 0; id < wc.primitives.size(); ++id) {
    const PrimitiveSpec& p = wc.primitives[id];
    if (p.link_index >= 0 && !p.is_static && p.variant.empty() &&
        std::holds_alternative<Capsule>(p.shape_L)) {
      w.arm.push_back(id);
    }
  }
  for (std::size_t i = 0; i < w.cans.size(); ++i) {
    w.can_ids.push_back(wc.FindPrimitive("can" + std::to_string(i)));
  }
  std::vector<Eigen::VectorXd> task_q, random_q;
  for (const TaskRun& task : w.models.front().tasks) {
    task_q.insert(task_q.end(), task.q.begin(), task.q.end());
  }
  for (int i = 0; i < (args.quick ? 500 : 2000); ++i) {
    random_q.push_back(RandomConfiguration(wc.kinematics, &rng));
  }
  std::printf("== cylinder objects: %zu cans (r %.3f m, L %.3f m; %d upright on the front "
              "table under the tools' paths, %d tilted beside them; seed %llu) x %zu arm "
              "capsules; exact capsule-cylinder distance by golden section (error < %.0e m), "
              "checked against FCL\n",
              w.cans.size(), kCanRadius_m, kCanLength_m, kUprightCans, kTiltedCans,
              static_cast<unsigned long long>(args.seed), w.arm.size(), kReferenceAccuracy_m);
  for (const auto& [workload, configurations] :
       {std::make_pair("tasks", &task_q), std::make_pair("random", &random_q)}) {
    FclCheck fcl;
    const std::vector<Counts> counts = CountWarnings(w, *configurations, &fcl);
    for (std::size_t m = 0; m < counts.size(); ++m) {
      const Counts& c = counts[m];
      csv->Row(workload, kModels[m], configurations->size(), w.cans.size(), w.arm.size(),
               c.pairs, c.model_warnings, c.exact_warnings, c.false_warnings, c.missed,
               c.borderline, kReferenceAccuracy_m, fcl.pairs, fcl.max_difference_m, args.seed);
      std::printf("  %-7s %-8s %5zu configurations  %9llu pairs  model warns %6llu  exact %6llu"
                  "  false %6llu  missed %llu  (within %.0e m of the threshold: %llu)\n",
                  workload, kModels[m], configurations->size(),
                  static_cast<unsigned long long>(c.pairs),
                  static_cast<unsigned long long>(c.model_warnings),
                  static_cast<unsigned long long>(c.exact_warnings),
                  static_cast<unsigned long long>(c.false_warnings),
                  static_cast<unsigned long long>(c.missed), kReferenceAccuracy_m,
                  static_cast<unsigned long long>(c.borderline));
    }
    std::printf("  %-7s reference against FCL's capsule-cylinder distance: max |difference| "
                "%.2e m over %llu separated pairs within 0.5 m of their threshold\n",
                workload, fcl.max_difference_m, static_cast<unsigned long long>(fcl.pairs));
  }
}

}  // namespace bench
}  // namespace arm_collision_monitor
#endif  // ACM_HAVE_PEERS
