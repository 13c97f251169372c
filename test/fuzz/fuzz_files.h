// Scratch files for the libFuzzer harnesses: the loaders take paths, so the inputs go to files
// in one scratch directory per fuzzing process.
#pragma once

#include <stdlib.h>

#include <console_bridge/console.h>

#include <cstdlib>
#include <fstream>
#include <string>
#include <string_view>

#include "arm_collision_monitor/core/load_error.h"
#include "arm_collision_monitor/scene/workcell.h"

namespace arm_collision_monitor {
namespace fuzz {

/// The process's scratch directory ("$TMPDIR/acm_fuzz_<what>_XXXXXX", /tmp without TMPDIR),
/// made on the first call.
inline const std::string& ScratchDirectory(const char* what) {
  static const std::string directory = [what] {
    const char* tmp = std::getenv("TMPDIR");
    std::string pattern = std::string(tmp != nullptr && tmp[0] != '\0' ? tmp : "/tmp") +
                          "/acm_fuzz_" + what + "_XXXXXX";
    if (mkdtemp(pattern.data()) == nullptr) std::abort();
    return pattern;
  }();
  return directory;
}

/// Writes `text` to `path`, replacing it. The scratch directory is the harness's own: failing
/// to write is a harness bug, hence abort.
inline void WriteScratchFile(const std::string& path, std::string_view text) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(text.data(), static_cast<std::streamsize>(text.size()));
  if (!out) std::abort();
}

/// For LLVMFuzzerInitialize: urdfdom reports parse errors through console_bridge on stderr,
/// noise at 10^4 inputs/s.
inline void SilenceConsoleBridge() {
  console_bridge::setLogLevel(console_bridge::CONSOLE_BRIDGE_LOG_NONE);
}

/// Loads the three-link test arm (test/data/three_link_arm.urdf) with the scene file
/// `scene_path`: a LoadError is the expected answer to bad input; a workcell that loads but
/// breaks its invariants (Workcell::Validate) is a finding, hence abort.
inline void LoadThreeLinkArmAndValidate(const std::string& scene_path) {
  try {
    const Workcell w =
        LoadWorkcell(std::string(ACM_SOURCE_DIR) + "/test/data/three_link_arm.urdf", scene_path);
    std::string why;
    if (!w.Validate(&why)) std::abort();
  } catch (const LoadError&) {
  }
}

}  // namespace fuzz
}  // namespace arm_collision_monitor
