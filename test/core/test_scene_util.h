// Shared by the scene loader tests: the bundled input files and compatibility by name.
#pragma once

#include <gtest/gtest.h>

#include <string>

#include "arm_collision_monitor/scene/workcell.h"

namespace arm_collision_monitor {

inline const std::string kSource = ACM_SOURCE_DIR;
inline const std::string kUrdf = kSource + "/urdf/workcell.urdf";
inline const std::string kScene = kSource + "/config/scene.yaml";
inline const std::string kData = kSource + "/test/data/";

/// Whether the primitives named `a` and `b` are compatible in `w`; a failure if either is unknown.
inline bool Compatible(const Workcell& w, const std::string& a, const std::string& b) {
  const int ia = w.FindPrimitive(a);
  const int ib = w.FindPrimitive(b);
  EXPECT_GE(ia, 0) << a;
  EXPECT_GE(ib, 0) << b;
  return ia >= 0 && ib >= 0 && w.compatible.AreCompatible(ia, ib);
}

}  // namespace arm_collision_monitor
