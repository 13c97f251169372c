// libFuzzer harness for the SRDF reader: an SRDF file as a user (or MoveIt Setup Assistant)
// could supply it, through ReadSrdfCollisionRules, then, when it is read, through LoadWorkcell
// as the srdf: of a small arm's scene (test/data/three_link_arm.urdf), which maps its names onto
// the primitives. LoadError is the expected answer to bad input; any other exception, a crash,
// undefined behaviour, a leak or a broken invariant of the result is a finding.
//
// Input: the SRDF text. Seeds: test/fuzz/corpus/scene_srdf/.
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>

#include "arm_collision_monitor/core/load_error.h"
#include "arm_collision_monitor/scene/srdf_reader.h"
#include "arm_collision_monitor/scene/workcell.h"
#include "fuzz_files.h"

namespace arm_collision_monitor {
namespace {

const std::string& SrdfPath() {
  static const std::string path = fuzz::ScratchDirectory("srdf") + "/robot.srdf";
  return path;
}

// The three-link arm's scene with the fuzzed SRDF.
const std::string& ScenePath() {
  static const std::string path = [] {
    const std::string scene = fuzz::ScratchDirectory("srdf") + "/scene.yaml";
    fuzz::WriteScratchFile(scene,
                           "world: {center_m: [0.0, 0.0, 1.0], edge_m: 4.0}\n"
                           "arms:\n  - {name: arm, root_link: upper_arm}\n"
                           "srdf: " + SrdfPath() + "\n");
    return scene;
  }();
  return path;
}

bool IsWellFormed(const SrdfLinkPair& pair) {
  return !pair.link1.empty() && !pair.link2.empty() && pair.line >= 1;
}

}  // namespace
}  // namespace arm_collision_monitor

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  arm_collision_monitor::fuzz::SilenceConsoleBridge();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace arm_collision_monitor;
  fuzz::WriteScratchFile(SrdfPath(),
                         std::string_view(reinterpret_cast<const char*>(data), size));
  SrdfCollisionRules rules;
  try {
    rules = ReadSrdfCollisionRules(SrdfPath());
  } catch (const LoadError&) {
    return 0;  // refused with a message: the expected answer to bad input
  }
  // The reader's contract (srdf_reader.h): every rule names non-empty links and its line.
  for (const auto* pairs : {&rules.disabled_pairs, &rules.enabled_pairs}) {
    for (const SrdfLinkPair& pair : *pairs) {
      if (!IsWellFormed(pair)) std::abort();
    }
  }
  for (const SrdfLink& link : rules.default_disabled_links) {
    if (link.link.empty() || link.line < 1) std::abort();
  }
  fuzz::LoadThreeLinkArmAndValidate(ScenePath());
  return 0;
}
