// Scratch files for the libFuzzer harnesses: the loaders take paths, so the inputs go to files
// in one scratch directory per fuzzing process.
#pragma once

#include <stdlib.h>

#include <cstdlib>
#include <fstream>
#include <string>
#include <string_view>

namespace arm_collision_monitor {
namespace fuzz {

/// The process's scratch directory ("/tmp/acm_fuzz_<what>_XXXXXX"), made on the first call.
inline const std::string& ScratchDirectory(const char* what) {
  static const std::string directory = [what] {
    std::string pattern = std::string("/tmp/acm_fuzz_") + what + "_XXXXXX";
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

}  // namespace fuzz
}  // namespace arm_collision_monitor
