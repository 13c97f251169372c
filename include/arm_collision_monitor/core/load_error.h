// The start-up error tier: user input (URDF, scene file, options) that cannot be used.
#pragma once

#include <stdexcept>

namespace arm_collision_monitor {

/// Start-up input error. what() names the file, the element and what was expected, e.g.
/// "config/scene.yaml: objects[3] 'front_table': size must be 3 positive numbers".
class LoadError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace arm_collision_monitor
