// Trimming for the scene's text readers (scene geometry text, SRDF attribute values). Private to
// the scene module.
#pragma once

#include <string>
#include <string_view>

namespace arm_collision_monitor {

/// `text` without leading and trailing blanks (spaces, tabs, line ends).
inline std::string Trimmed(std::string_view text) {
  constexpr std::string_view kBlanks = " \t\r\n";
  const std::size_t first = text.find_first_not_of(kBlanks);
  if (first == std::string_view::npos) return "";
  return std::string(text.substr(first, text.find_last_not_of(kBlanks) - first + 1));
}

}  // namespace arm_collision_monitor
