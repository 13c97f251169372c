// libFuzzer harness for the start-up tier: a URDF, a scene YAML and a Monitor options YAML, as a
// user could supply them, through LoadWorkcell, LoadMonitorOptions and the Monitor constructor,
// then one cycle at the joints' mid-range. LoadError is the expected answer to bad input; any
// other exception, a crash, undefined behaviour or a leak is a finding.
//
// Input: the three texts separated by kSeparator, in the order URDF, scene, options; with only
// two parts the bundled config/monitor.yaml is used. Seeds: test/fuzz/corpus/monitor_startup/.
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "arm_collision_monitor/core/load_error.h"
#include "arm_collision_monitor/monitor/monitor.h"
#include "arm_collision_monitor/scene/workcell.h"
#include "fuzz_files.h"

namespace arm_collision_monitor {
namespace {

constexpr std::string_view kSeparator = "\n=====\n";

// The three texts' files, in the scratch directory.
struct ScratchFiles {
  std::string urdf_path;
  std::string scene_path;
  std::string options_path;
};

const ScratchFiles& Scratch() {
  static const ScratchFiles files = [] {
    const std::string& base = fuzz::ScratchDirectory("startup");
    return ScratchFiles{base + "/workcell.urdf", base + "/scene.yaml", base + "/monitor.yaml"};
  }();
  return files;
}

std::vector<std::string_view> Split(std::string_view text) {
  std::vector<std::string_view> parts;
  while (true) {
    const std::size_t at = text.find(kSeparator);
    parts.push_back(text.substr(0, at));
    if (at == std::string_view::npos) return parts;
    text.remove_prefix(at + kSeparator.size());
  }
}

}  // namespace
}  // namespace arm_collision_monitor

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  arm_collision_monitor::fuzz::SilenceConsoleBridge();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace arm_collision_monitor;
  const std::vector<std::string_view> parts =
      Split(std::string_view(reinterpret_cast<const char*>(data), size));
  if (parts.size() < 2 || parts.size() > 3) return -1;  // not in the input format: not kept
  const ScratchFiles& files = Scratch();
  fuzz::WriteScratchFile(files.urdf_path, parts[0]);
  fuzz::WriteScratchFile(files.scene_path, parts[1]);
  const std::string options_path = parts.size() == 3
                                       ? files.options_path
                                       : std::string(ACM_SOURCE_DIR) + "/config/monitor.yaml";
  if (parts.size() == 3) fuzz::WriteScratchFile(files.options_path, parts[2]);

  std::shared_ptr<const Workcell> workcell;
  MonitorOptions options;
  try {
    // In the node's order: the options give the default arm tolerance of the workcell.
    options = LoadMonitorOptions(options_path);
    workcell = std::make_shared<const Workcell>(
        LoadWorkcell(files.urdf_path, files.scene_path, options.tolerance_m));
  } catch (const LoadError&) {
    return 0;  // refused with a message: the expected answer to bad input
  }

  // Accepted input must give a working Monitor: it may still refuse inconsistent options with
  // LoadError, but not crash, and its first cycle must not throw.
  std::unique_ptr<Monitor> monitor;
  try {
    monitor = std::make_unique<Monitor>(workcell, options);
  } catch (const LoadError&) {
    return 0;
  }
  const KinematicModel& model = workcell->kinematics;
  const int q_size = static_cast<int>(workcell->joint_names.size());
  Eigen::VectorXd q = Eigen::VectorXd::Zero(q_size);
  for (int link = 1; link < model.link_count(); ++link) {
    const JointSpec& joint = model.joint(link);
    if (joint.q_index < 0 || joint.q_index >= q_size || !std::isfinite(joint.lower) ||
        !std::isfinite(joint.upper)) {
      continue;
    }
    q[joint.q_index] = 0.5 * joint.lower + 0.5 * joint.upper;
  }
  const CycleReport& report = monitor->Update(q);
  // Contract of CycleReport: a refused input or any warning requests a stop.
  if ((report.input != InputStatus::kOk || !report.warnings.empty()) && !report.stop) std::abort();
  return 0;
}
