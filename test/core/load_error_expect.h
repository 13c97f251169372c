// Test helpers for the start-up loaders: temporary input files and LoadError expectations.
#pragma once

#include <gtest/gtest.h>

#include <fstream>
#include <string>
#include <vector>

#include "arm_collision_monitor/core/load_error.h"

namespace arm_collision_monitor {

/// Writes `text` to a file named after `name` in the test's temporary directory; returns its path.
inline std::string WriteTempFile(const std::string& name, const std::string& text) {
  const std::string path = ::testing::TempDir() + "acm_test_" + name;
  std::ofstream(path) << text;
  return path;
}

/// Expects `load()` to throw LoadError whose message contains every one of `parts`.
template <typename Load>
void ExpectLoadError(Load load, const std::vector<std::string>& parts) {
  try {
    load();
    ADD_FAILURE() << "expected a LoadError mentioning " << parts.front();
  } catch (const LoadError& e) {
    const std::string message = e.what();
    for (const std::string& part : parts) {
      EXPECT_NE(message.find(part), std::string::npos) << "'" << part << "' not in: " << message;
    }
  }
}

}  // namespace arm_collision_monitor
