// Test helpers for the start-up loaders: temporary input files and LoadError expectations.
#pragma once

#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <string>
#include <utility>
#include <vector>

#include "arm_collision_monitor/core/load_error.h"

namespace arm_collision_monitor {

/// Writes `text` to a file named after `name` in the test's temporary directory; returns its path.
inline std::string WriteTempFile(const std::string& name, const std::string& text) {
  const std::string path = ::testing::TempDir() + "acm_test_" + name;
  std::ofstream(path) << text;
  return path;
}

/// The whole text of the file `path` (a failure if it cannot be opened).
inline std::string ReadTextFile(const std::string& path) {
  std::ifstream in(path);
  EXPECT_TRUE(in.is_open()) << "cannot open " << path;
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

/// `text` with the first occurrence of each edit's first string replaced by its second (a
/// failure if one is missing).
inline std::string EditedText(std::string text,
                              const std::vector<std::pair<std::string, std::string>>& edits) {
  for (const auto& [from, to] : edits) {
    const std::size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << "'" << from << "' not in the text";
    if (at != std::string::npos) text.replace(at, from.size(), to);
  }
  return text;
}

/// The file `from_path` after EditedText, written as WriteTempFile(`name`); returns its path.
inline std::string WriteEditedFile(const std::string& from_path, const std::string& name,
                                   const std::vector<std::pair<std::string, std::string>>& edits) {
  return WriteTempFile(name, EditedText(ReadTextFile(from_path), edits));
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

/// A bad input file: its text and what the LoadError message must contain besides its path.
struct BadInputFile {
  std::string text;
  std::vector<std::string> parts;
};

/// For each case, writes its text to the temporary file `name` and expects `load(path)` to throw
/// a LoadError whose message contains the path and every one of the case's parts.
template <typename Load>
void ExpectBadInputFilesRejected(const std::string& name, const std::vector<BadInputFile>& cases,
                                 Load load) {
  for (const BadInputFile& bad : cases) {
    const std::string path = WriteTempFile(name, bad.text);
    std::vector<std::string> parts = bad.parts;
    parts.push_back(path);
    ExpectLoadError([&] { load(path); }, parts);
  }
}

}  // namespace arm_collision_monitor
