// Peer collision checkers (FCL, Bullet) run on the same primitives, poses, tolerances and
// compatibility matrix as the Monitor, so the benchmarks can compare their per-cycle time and
// their warnings with ours cycle by cycle. Not part of the core: built only when FCL and Bullet
// are installed (library arm_collision_monitor_peers).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "arm_collision_monitor/broadphase/broad_phase.h"
#include "arm_collision_monitor/broadphase/compatibility_matrix.h"
#include "arm_collision_monitor/geometry/primitives.h"

namespace arm_collision_monitor {

/// How a peer decides "surfaces closer than tolerance(a) + tolerance(b)".
enum class PeerTolerance : std::uint8_t {
  /// Each shape grown by its tolerance in every direction (Minkowski sum with a ball): a grown
  /// box has rounded edges and corners. The same predicate as ours (Bullet: collision margins,
  /// box pairs through GJK too; FCL: distance query on the ungrown shapes, GJK tolerance 1e-9,
  /// for every pair its broad phase reports).
  kRounded,
  /// Capsule radius + tolerance, box half extents + tolerance along the box axes: the grown box
  /// keeps sharp edges, so near its edges and corners this warns where we do not (a superset).
  /// FCL: boolean collision of the grown shapes; Bullet: grown box with a zero margin.
  kSharp,
};

/// One primitive handed to a peer. Ids are the indices of the vector passed to the factories.
struct PeerPrimitive {
  Shape shape_W;             ///< uninflated, world frame
  double tolerance_m = 0.0;  ///< zone beyond the surface
  bool is_moving = false;    ///< SetShape() may be called for it
  bool is_present = true;    ///< false: left out (e.g. an inactive model variant)
};

class PeerChecker {
 public:
  virtual ~PeerChecker() = default;
  /// "fcl", "bullet", with the tolerance mode ("fcl_sharp", ...).
  virtual std::string name() const = 0;
  /// Primitive `id` (moving, present) now has the world pose of `shape_W`; its kind and
  /// dimensions are those given at construction.
  virtual void SetShape(PrimitiveId id, const Shape& shape_W) = 0;
  /// Every present, non-compatible pair, not both static, whose shapes are closer than the sum
  /// of their tolerances (by this peer's predicate), sorted, a < b. Replaces `pairs`.
  virtual void FindWarnings(std::vector<CandidatePair>* pairs) = 0;
};

/// FCL 0.7: two DynamicAABBTreeCollisionManagers (static, moving), moving-vs-static plus
/// moving self-collision, narrow phase per mode (see PeerTolerance).
std::unique_ptr<PeerChecker> MakeFclChecker(const std::vector<PeerPrimitive>& primitives,
                                            const CompatibilityMatrix& compatible,
                                            PeerTolerance mode);
/// Bullet: btCollisionWorld over btDbvtBroadphase, btCapsuleShapeZ / btBoxShape, an overlap
/// filter for compatible and static-static pairs, discrete collision detection each call.
std::unique_ptr<PeerChecker> MakeBulletChecker(const std::vector<PeerPrimitive>& primitives,
                                               const CompatibilityMatrix& compatible,
                                               PeerTolerance mode);

}  // namespace arm_collision_monitor
