// Every tolerance and constant of the core, in one place. Each has units, a typical value and
// the reason it exists. Prefer tolerances relative to the lengths involved (the *_rel ones,
// dimensionless, multiplied by a length scale of the inputs) over absolute ones.
#pragma once

#include <cstddef>
#include <cstdint>

namespace arm_collision_monitor {

// ---------------------------------------------------------------------------------------------
// Geometry (distance routines)
// ---------------------------------------------------------------------------------------------

// A segment is treated as a point when its length is below this fraction of the other
// segment's length (dimensionless; typical 1e-15). Below it the direction is noise at double
// precision, and collapsing it costs at most that length in distance.
constexpr double kSegmentDegenerateLengthRel = 1e-15;
// Squared lengths below this (m^2; the smallest normal double, ~2.2e-308) are treated as zero:
// dividing by them would overflow. Lengths below ~1.5e-154 m therefore count as points.
constexpr double kSegmentMinSquaredLength_m2 = 2.2250738585072014e-308;
// Segments whose squared sine of the angle between them is below this are handled as parallel
// (dimensionless; typical 1e-36, i.e. 1e-18 rad): s = 0 is then taken before the clamping steps,
// which costs at most length * sin(angle) <= 1e-18 * length. It keeps s = num/denom finite
// (|s| <= 1e18 |r| / |d1|); above ~1e-32 the computed sine is rounding noise anyway, harmlessly.
constexpr double kSegmentParallelSinSquared = 1e-36;
// Below this product of squared segment lengths (m^4; typical 1e-200, i.e. lengths ~1e-50 m)
// the segment routine rescales its input by a power of two first: |d1 x d2|^2 (a product of four
// lengths) underflows near 1e-308 and would silently lose the interior closest point.
constexpr double kSegmentRescaleBelow_m4 = 1e-200;
// When rescaling, segments shorter than 1 / this times their separation (dimensionless; typical
// 1e150) are collapsed to their start points instead: the scaled separation could overflow, and
// the error, at most the segments' lengths, is far below the bound.
constexpr double kSegmentRescaleMaxRatio = 1e150;
// Error bounds stated by the distance routines, as a multiple of the unit roundoff times the
// local length scale S of a query (dimensionless). S = the largest of: the distance between the
// shapes' reference points (segment start, box centre), the segment lengths, the box diagonals
// and the radii. The test suites pin the observed worst error against these bounds.
constexpr double kSegmentDistanceErrorUlps = 16.0;
constexpr double kBoxDistanceErrorUlps = 64.0;
// Absolute floor added to every distance error bound (m; typical 1e-150): squared lengths below
// ~2e-308 m^2 underflow, so features smaller than ~1e-154 m are resolved only to about that.
constexpr double kDistanceErrorFloor_m = 1e-150;
// Inputs are supported up to this magnitude (m; typical 1e60): products of four lengths (the
// squared cross product of two directions) must stay below the double overflow at ~1.8e308.
constexpr double kMaxSupportedCoordinate_m = 1e60;

// The batched single-precision clearance bounds (geometry/clearance_batch.h): the margin taken
// off each bound, in units of the float unit roundoff u = 2^-24 (~6e-8) times the pair's length
// scale S = |c_A|_1 + |c_B|_1 + sum h_A + sum h_B + r_A + r_B (centres, half lengths, radii; m).
// Worst cases, each a multiple of u S: rounding the double shape to float moves it by at most
// u (|c| + 2 sum h + r) per primitive, 2; the sphere bound's difference, norm and sums, 12; the
// direction bound's centre difference, its three-term dot products (each within 3u of the sum
// of the terms' magnitudes), the nine-term reach sums and the direction's norm 1 +- 3u, 20;
// taking the margin off and the larger bound, 2. 64 is over twice their sum, 24; in metres
// 64 u S ~ 4e-6 S (23 um for S = 6 m, the bundled workcell). test_geometry_clearance_batch pins
// that no bound exceeds the exact distance (random, touching, far and degenerate pairs).
constexpr float kClearanceBatchMarginUlps = 64.0f;
// Largest sum of a primitive's |coordinates|, half lengths and radius (m) the batch accepts
// (typical 1e15): squares of lengths must stay far below the float overflow (~3.4e38). A
// primitive beyond it (or with NaN) gets a NaN radius: its bounds are -inf, the exact distance
// decides.
constexpr double kClearanceBatchMaxLength_m = 1e15;
// PairCache::TestPairs bounds a batch of pairs in float only from this many pairs up
// (dimensionless); fewer take the exact double distance directly. Each batched pair pays for
// float copies of its two shapes (~10 ns each) and a share of a 4-lane block (~20 ns per pair),
// about what an exact capsule distance costs (~50 ns): on the bundled workcell, every joint
// moving, batches of 3-14 pairs made the narrow phase slower (perf, every-cycle run: 11.3 % of
// the cycle before, 13.9 % batched), while on 168 pairs of a sphere-robot-like scene the batch
// was 1.3x faster (bench_monitor_cycle BM_NarrowPhase*). 16 lies between; not tuned further.
constexpr std::size_t kClearanceBatchMinPairs = 16;

// ---------------------------------------------------------------------------------------------
// Broad phase (octree, grid)
// ---------------------------------------------------------------------------------------------

/// Deepest octree level (the root is level 0). Bounds the integer cell coordinates (2^16 units
/// per axis) and the recursion depth; a 6.35 m world at this depth has 0.1 mm cells, far below
/// any useful minimum cell size, so in practice min_cell_size_m decides the depth.
constexpr int kOctreeMaxDepth = 16;

/// Cell boundaries are computed in floating point as origin + i * spacing, so adjacent
/// boundaries are spaced by the nominal spacing within a few ulps of the coordinates. The
/// incremental update is exact only for moves strictly shorter than the spacing, so moves of
/// at least spacing * (1 - this) (dimensionless; typical 1e-6, far above the 1e-13 relative
/// rounding of metre-scale coordinates) take the full re-insert path instead.
constexpr double kCellSpacingMarginRel = 1e-6;

/// Location links reserved per primitive at start-up (dimensionless). A primitive smaller than
/// a leaf lies in at most 8 leaves; larger ones in more. Only a reserve: exceeding it grows the
/// pool once, during warm-up.
constexpr int kReservedLinksPerPrimitive = 8;

/// Lattice cells (dimensionless) a box may span, counted as the product over the axes of
/// edge / spacing + 1, before a cell broad phase keeps it in its unlinked list instead of its
/// cells (3 x 3 x 3 for a cube of two spacings). Such a box would be linked to many cells
/// and met in many of them, and boxes that large overlap most others anyway: one
/// structure-of-arrays test each, as the all-pairs broad phase, costs less.
constexpr double kOversizeCells = 27.0;

/// The step, as a fraction of the spacing IsOversize counts cells in (dimensionless), from
/// which a cell broad phase unlinks a moved box until a shorter step: a face moved that far
/// leaves and enters so many cells that one structure-of-arrays test of every box costs less.
/// Measured with bench_broadphase_workloads 'large steps' (14 movers, 200 statics, faces moving
/// up to 0.6 m per cycle; medians over naive's in one run): the grid 3.5x at 1, 2.5x at 0.5,
/// 1.6x at 0.25, 1.3x at 0.1, the octree alike; the other workloads move less and are unchanged.
/// 0.25 keeps arm links stepping a few centimetres per cycle in their cells.
constexpr double kJumpSpacingFraction = 0.25;

// ---------------------------------------------------------------------------------------------
// Kinematics and scene loading
// ---------------------------------------------------------------------------------------------

/// A URDF joint axis shorter than this (dimensionless, the axis is a direction) cannot be
/// normalised reliably: rejected at load. Typical axes have norm 1.
constexpr double kMinJointAxisNorm = 1e-9;
/// KinematicModel::Validate: a stored joint axis counts as a unit vector when its norm is within
/// this of 1 (dimensionless; typical 1e-12). The loader normalises every axis, which leaves the
/// norm within a few ulps (~1e-16) of 1; a larger error means the model was corrupted.
constexpr double kUnitAxisNormTolerance = 1e-12;
/// SinCos (kinematics/sin_cos.h) reduces angles up to this magnitude itself (rad; typical joint
/// angles are within 2 pi). Its three-part pi/2 keeps the reduction exact to ~1e-32 rad for
/// quadrant counts below 2^20 (|angle| < 1.6e6 rad); 1e5 leaves margin. Larger angles, inf and
/// NaN fall back to std::sin/std::cos.
constexpr double kFastSinCosMaxAngle_rad = 1e5;
/// SinCos's stated error bound: each of sin and cos within this many units of 2^-53
/// (absolute, dimensionless; about 1.1e-16 each) of the exact value. Taylor truncation is below
/// 1e-19 and reduction plus Horner rounding stay below ~2.5 units; the test pins the observed
/// worst against this.
constexpr double kFastSinCosErrorUlps = 4.0;
/// ComputeLinkPoses computes the joint sines and cosines for this many links at a time, on the
/// stack (no allocation) before composing their poses; 64 covers two 7-DOF arms and their
/// fixed links in one block and costs 1.5 KiB of stack (angle, sine and cosine arrays).
constexpr int kFkBlockLinks = 64;

/// The "cylinder plus two end spheres" capsule idiom is recognised when the spheres' radii
/// and centres match the cylinder's radius and end centres within this fraction of the
/// cylinder's length plus radius (dimensionless). URDF numbers are printed with ~6 digits, so
/// 1e-6 tolerates their rounding and still rejects deliberately different spheres.
constexpr double kCapsuleIdiomMatchRel = 1e-6;

/// A quaternion read from a MoveIt planning-scene file is normalised when its norm is within
/// this of 1 (dimensionless; typical 1e-2): quaternions printed with two decimals (0.71, 0.71)
/// miss unit norm by ~4e-3. Farther from 1 it is rejected: not a rotation written as a unit
/// quaternion (Euler angles in quaternion fields, a typo), which normalising would hide.
constexpr double kQuaternionUnitNormTolerance = 1e-2;

/// Default tolerance zone around each arm capsule, metres: 1.2 in, the seed's buffer beyond
/// the approximated surface of each arm (TR 90-28, section 3).
constexpr double kDefaultArmTolerance_m = 0.0305;

/// Start-up check for pairs that overlap in every configuration: this many seeded random
/// configurations (plus the home pose) are sampled. 256 makes a pair that is clear in 5% of
/// the joint space escape with probability 0.95^256 < 1e-5.
constexpr int kAlwaysOverlappingSamples = 256;
/// The seed of that sampling (printed in each warning it produces, so it can be reproduced).
constexpr std::uint64_t kAlwaysOverlappingSeed = 20260521;
/// A pair within its tolerances in the home pose and in at least this many of those samples
/// (half), if not in all, gets its own finding: it would warn in most cycles (two links whose
/// fits, with the tolerances, reach each other across a short link between them; a link and an
/// object placed within its reach).
constexpr int kMostlyOverlappingSamples = kAlwaysOverlappingSamples / 2;

// ---------------------------------------------------------------------------------------------
// Monitor
// ---------------------------------------------------------------------------------------------

/// pi (Eigen and <cmath> give it only as macros).
inline constexpr double kPi = 3.14159265358979323846;
/// One whole turn of a revolute joint, rad.
inline constexpr double kTurn = 2.0 * kPi;

/// How far (rad for revolute, m for prismatic joints) a joint position may lie outside its URDF
/// limits before the cycle's input is refused. Typical 0.01: encoders and controllers overshoot
/// limits by a few milliradians; a larger excursion means a corrupt or mis-ordered message.
inline constexpr double kJointLimitMargin = 0.01;

/// The largest magnitude a position of a joint without limits (a continuous joint) may take,
/// rad: beyond it the input is refused as corrupt (a bit flip can make 1e308 of a reading). 1e9
/// rad keeps a pose's rounding under 0.2 um a metre of lever, and takes a joint unwound at one
/// turn a second five years to reach.
inline constexpr double kMaxUnlimitedPosition_rad = 1e9;

/// The most points replay puts between the points of a bag's plans to follow continuous joints'
/// turns (a quarter turn apart, within the joints' velocity limits): 100,000, 40,000 rad of
/// turns, some 15 MB of points for two 7-joint arms. More is refused as a corrupt plan.
inline constexpr std::int64_t kMostPointsBetween = 100000;

/// The largest magnitude a revolute or continuous mimic joint's position may reach over the
/// positions the monitor accepts of the joint it mimics, rad (a prismatic mimic's travel is held
/// to kMaxWorldEdge_m): 16 times kMaxUnlimitedPosition_rad, so that a x10 mimic of a continuous
/// joint loads with its offset (at exactly ten times, an offset of 0.5 rad was refused). A larger
/// one (an absurd multiplier or offset: 1e308 overflowed to NaN poses) is refused at start-up.
/// The rounding of the mimic's computed angle, one unit in its last place, is what the motion
/// bounds may miss: 2e-6 rad from 8.6e9 rad up to the bound (2 um a metre of lever), 1e-9 rad
/// below 4e6 rad.
inline constexpr double kMaxMimicPosition = 16.0 * kMaxUnlimitedPosition_rad;

/// The node's default ~input_timeout_s, s: 5 cycles at 20 Hz. replay tells of a bag whose
/// stamps are further off the times it recorded them (a robot's clock off the recorder's),
/// which such a node would refuse.
inline constexpr double kDefaultInputTimeout_s = 0.25;

/// A step beyond max_step_m is no jump when the time since the last accepted sample shows every
/// joint moved at most this many times its velocity limit allows (a planned path sampled
/// sparsely, a slow publisher): twice, so that stamps jittering by up to half the step's time
/// do not make a path at its velocity limits jump. Dimensionless.
inline constexpr double kJumpVelocityFactor = 2.0;

/// A frame-bound object's speed from its timed poses (Monitor::SetObjectPoseAt, speed-scaled
/// tolerance): a move after more than this many cycle periods without a timed pose takes
/// max_speed_mps, as its speed over so long a gap would average a burst down (a tracker that
/// went silent, then a pose 0.5 m on: 0.1 m/s over 5 s, though it may have moved in the last
/// 0.1 s). 10: a tracker at 2 Hz beside a 20 Hz monitor keeps its measured speed. Cycles,
/// dimensionless.
inline constexpr double kObjectSpeedMaxGapCycles = 10.0;

/// auto's rule (ChooseBroadPhaseMethod), from the sweep of bench_broadphase_workloads (moving
/// 7..1,200 x static 0..3,000 primitives; counts, dimensionless): the uniform grid from
/// kAutoGridMinStatics + kAutoGridStaticsPerMover x moving statics up, or from
/// kAutoGridMinMoving moving up; otherwise all pairs (naive), whose branch-free scan of every
/// box (BoxArray, float, masked by the compatibility words) beats any index's upkeep below that.
/// The octree was best nowhere in the sweep, so auto does not pick it. Measured 2026-12-02 on
/// this 2-core machine (medians per cycle, bench_broadphase_workloads --sweep-only, two runs):
/// up to 150 movers the grid draws level at about 700 statics (0.99 against naive's 0.99 us at
/// 7+700, 28.9 against 28.2 at 150+700) and leads from 1,000; with more movers naive's lead
/// lasts longer, the crossover (interpolated between 1,000 and 3,000 statics) at about 1,250
/// statics for 300 movers, 1,400 for 450, 1,750 for 600 and 2,000 for 1,200 (naive 85 against
/// the grid's 91 us at 300+1,000, 177 against 194 at 450+1,000, 668 against 744 at
/// 1,200+1,000; the grid 160 against 216 at 300+3,000, 1,167 against 1,268 at 1,200+3,000).
/// A single crossover of 700 statics had the grid up to 1.35x naive's time (450+700). The line
/// 700 + 1.9 per mover lies within 10 % of the faster side at every point of the sweep. Naive
/// leads at 0 statics up to the sweep's 1,200 movers (340 against 469 us), the grid's ratio to
/// it falling about 9 % per doubling (1.52 at 600, 1.38 at 1,200): kAutoGridMinMoving
/// extrapolates that to where it reaches 1.
inline constexpr std::uint32_t kAutoGridMinStatics = 700;
inline constexpr double kAutoGridStaticsPerMover = 1.9;
inline constexpr std::uint32_t kAutoGridMinMoving = 12000;
/// Bounds on auto's grid resolution (GridCellsFor; cells per axis). 4: coarser and the grid is
/// all pairs in a few cells; 64: 262,144 cells, 3 MB of per-cell arrays.
/// bench_broadphase_workloads, 14 movers among 200 statics with boxes inflated by up to 0.6 m:
/// 6 cells per axis (about the movers' mean box edge) 6.5 us per cycle against 14.7 us with 16,
/// and 16 against 32 cells 4.7 against 7.1 us with 2,000 statics.
inline constexpr int kAutoGridMinCellsPerAxis = 4;
inline constexpr int kAutoGridMaxCellsPerAxis = 64;

/// Largest gap (m) between a held object and its holding link's geometry that Attach accepts.
/// Bounds how far an attached object can reach beyond its arm, which the start-up reach
/// analysis (statics no moving primitive can reach are left out) relies on. Typical 0.10: a
/// grasped object touches the gripper; 10 cm absorbs perception error.
inline constexpr double kAttachMaxGap_m = 0.10;

/// Live objects (MonitorOptions::live_objects): the largest capacity and primitives per object
/// the options accept (their product of slots is preallocated: 4096 x 64 would already be 2^18
/// primitives, far beyond what the per-pair storage can hold).
inline constexpr std::uint32_t kLiveObjectMaxCapacity = 4096;
inline constexpr std::uint32_t kLiveObjectMaxPrimitives = 64;
/// Monitor::AddObject / MoveObject: a pose's rotation is accepted when |R^T R - I| (max entry)
/// is below this (dimensionless). Typical 1e-6: a unit quaternion turned into a matrix is
/// orthonormal to ~1e-15; a float32 round trip to ~1e-7.
inline constexpr double kLiveObjectRotationTolerance = 1e-6;
/// The node's fixed frame only renames the URDF root's: where TF relates the two, it takes them
/// as one within this offset (m) and rotation angle (rad), else it refuses poses looked up in
/// it (MonitorNode::LookupInFixedFrame). A static identity transform is exact to ~1e-9.
inline constexpr double kFixedFrameMaxOffset_m = 1e-6;
inline constexpr double kFixedFrameMaxAngle_rad = 1e-6;
/// Margin (m) on every side of the world cube derived when the scene file omits world:
/// (DeriveWorldCube). The reach envelopes already bound every primitive for every q; this leaves
/// room for what the broad phase grows boxes by (index slack, speed-scaled tolerance: a box
/// beyond the cube is still checked, only in the border cells). Typical 0.10.
inline constexpr double kDerivedWorldMargin_m = 0.10;
/// The longest edge (m) of a world cube, given or derived: the Monitor's distance bounds keep
/// kLowerBoundMarginPerMetre of it in hand against rounding, 10 um at this edge, well below any
/// swept_resolution_m; a much larger cube (a prismatic joint whose URDF limits are +/-1e9 m)
/// would make that margin metres long, and every pair within it a warning.
inline constexpr double kMaxWorldEdge_m = 1e4;
/// A derived world cube with a longer edge (m) than this names its farthest primitive in its
/// start-up notice: a workcell of arms spans a few metres (the seed's 6.35 m), so such a cube
/// most likely comes from a unit or origin error in one link or object (a YuMi URDF's stand
/// has a collision origin 165 m away).
inline constexpr double kLargeDerivedWorldEdge_m = 20.0;

/// Default index slack, m (MonitorOptions::index_slack_m): a moving primitive is re-indexed
/// once a point of it has moved this far since it was last indexed. Larger means fewer index
/// updates but more candidate pairs; 0.10 m is about three cycles at the 0.61 m/s speed bound
/// and 10 to 20 cycles at the tasks' typical link speeds (scripts/bench sweeps it).
inline constexpr double kDefaultIndexSlack_m = 0.10;

/// Safety margin of the Monitor's distance lower bounds, per metre of the world cube's edge
/// (dimensionless): a pair skips the narrow phase only when its bound exceeds its threshold by
/// this times the edge. The bound adds three rounded quantities (a distance and two
/// displacements), each within ~64 eps of the local length scale (geometry/distance.h), so
/// 1e-9 per metre is over 10^4 times their error for any shape within the world cube.
inline constexpr double kLowerBoundMarginPerMetre = 1e-9;

/// Swept check: the deepest bisection of one step (dimensionless levels; typical depth 5-12 for
/// steps of cm to m at a 1 mm resolution). Reached only when a pair's motion bound is huge (an
/// unlimited prismatic joint): the sub-interval, 2^-40 of the step, is then warned as unresolved
/// rather than bisected forever.
inline constexpr int kMaxSweptBisections = 40;

/// Swept check: the distance tests one step may take over all its pairs (dimensionless; one
/// kinematics and one distance each, about 1 us), kMaxSweptTests and kSweptTestsPerPair more
/// for each pair it sweeps. Past them, each pair left to bisect warns once as not certified
/// clear, at the nearer end of its current interval. The bisection's samples grow with the
/// step's motion over the distance to certify: a continuous joint's reading of 1e6 rad after 0
/// (a corrupt driver) took 27 s to sweep, 1e9 rad hours, while the cycle held the node's thread;
/// the tests of a real step grow with its pairs too (a review's 5,417-primitive scene at 1 Hz:
/// 107,494 tests over some 7,000 pairs). The most otherwise measured: 2,752 (test_monitor_swept's
/// random fast trajectories), 1,340 (a red team's whole-range steps of 784 random robots).
inline constexpr std::uint32_t kMaxSweptTests = 1u << 16;
inline constexpr std::uint32_t kSweptTestsPerPair = 64;

/// Swept check: once a pair's bisection has resolved an interval (a sample within threshold +
/// resolution: the pair warns), the further samples (dimensionless; one kinematics and one
/// distance each) it may take looking for a sample within the threshold, which it then reports
/// instead: a contact 5 mm deep just past a sample 0.2 mm above the threshold was reported as
/// that sample (a dual Kinova Gen3 plan). Bounds the cost of a pair skimming its threshold along
/// a long step.
inline constexpr int kSweptSamplesPastResolved = 32;

/// Swept check: how many levels past the resolution (dimensionless) a pair's bisection may go to
/// certify an interval it could not (the pair near its threshold, a sample within the
/// resolution above it), at most 2^levels - 1 samples a pair and step. Without it, a pair that
/// a 1 kHz step moves 1 mm warned 'not certified clear' for as long as it stayed within about
/// half its motion bound of its threshold (three new users, on an SDA10F, two Jaco2 and two FR3
/// arms, saw such warnings at fraction 0 or 1 for some 10 ms as an arm moved away).
inline constexpr int kSweptRefineLevels = 3;

/// Swept check: the leaver-by-near box tests of one step (dimensionless) from which the pairs of
/// the primitives that may leave their slack are found by one structure-of-arrays scan of every
/// grown box per leaver (BoxArray by id, hits masked by compatibility row) instead of one test
/// per near box: the scan costs a set-up per leaver and a copy of every box, which the one-by-one
/// test's early exit beats on small sets. Callgrind on Monitor::Update* (bench_tasks_experiments
/// workloads): tasks_every_cycle (at most 41 x 41 tests) 15.53M instructions one by one, 17.55M
/// always scanned; sphere_robot at index slack 0 (about 75 x 91) 553.3M one by one, 379.8M
/// scanned.
inline constexpr std::size_t kSweptScanMinTests = 4096;

/// Monitor::Validate: a primitive follows its carrier link when its AABB matches the recomputed
/// one to this relative precision (dimensionless, of the coordinates' magnitude). Typical 1e-9:
/// re-expressing an attached object in its link frame and back costs a few ulps per transform.
inline constexpr double kValidateShapeTolerance_rel = 1e-9;

// ---------------------------------------------------------------------------------------------
// Tasks (the seed's three test trajectories, their bags and the replay tool)
// ---------------------------------------------------------------------------------------------

/// Period of one task cycle, s: the seed's 20 Hz joint-angle rate (TR 90-28, section 3).
inline constexpr double kTaskCyclePeriod_s = 0.05;
/// Speed bound every point of the arms keeps in the task trajectories, m/s: the seed's 24 in/s
/// end-effector limit, which sizes the tolerance and the octree's smallest cell.
inline constexpr double kTaskMaxPointSpeed_mps = 0.61;
/// Header stamp of the first message of every task bag, s since the epoch (fixed, so that a
/// regenerated bag is byte-identical; 2020-09-13 12:26:40 UTC, an arbitrary round number).
inline constexpr double kTaskBagStartStamp_s = 1600000000.0;

// ---------------------------------------------------------------------------------------------
// Mesh fitting (geometry/mesh_fit.h: URDF mesh collision geometry to enclosing primitives)
// ---------------------------------------------------------------------------------------------

/// Growth of every fitted radius and half extent, as a fraction of the mesh's scale S (its
/// bounding-box diagonal plus its largest |coordinate|; dimensionless; typical 1e-9). The fit's
/// own rounding is a few hundred eps * S (~1e-13 S), so 1e-9 keeps every vertex inside in
/// floating point with 10^4 to spare, and costs 1 nm per metre of mesh.
inline constexpr double kMeshFitMarginRel = 1e-9;
/// A mesh whose vertices all lie within this fraction of its extent (bounding-box diagonal) of
/// one plane has no volume (dimensionless; typical 1e-6): a flat, collinear or one-point mesh
/// cannot be a link's solid. Meshes exported flat have thickness ~1e-7 of their size or less;
/// real parts are thicker than 1e-3 of their size.
inline constexpr double kMeshMinThicknessRel = 1e-6;
/// Largest accepted mesh extent, m (the bounding-box diagonal; typical 1000): a robot link is
/// metres long, so a kilometre means the URDF scale or the file's units are wrong.
inline constexpr double kMeshMaxExtent_m = 1000.0;
/// Smallest accepted mesh extent, m (typical 1e-6): below a micrometre the mesh is a unit
/// error (e.g. a scale applied twice), not a part.
inline constexpr double kMeshMinExtent_m = 1e-6;
/// Largest accepted |vertex coordinate| in the link frame, m (typical 1e4): farther than
/// 10 km from its link a mesh is a unit or offset error, and the margin (relative to it) would
/// grow past a micrometre.
inline constexpr double kMeshMaxCoordinate_m = 1e4;
/// Most capsules a chain fit may ask for (dimensionless; typical 64): each costs a primitive in
/// every cycle, and a link needing more is better modelled by hand.
inline constexpr int kMeshFitMaxCapsules = 64;
/// Deepest chain of xacro macro calls the URDF check follows (dimensionless; typical 16): a file
/// left unexpanded rarely nests two, and a longer chain (or a macro calling itself) is refused.
inline constexpr int kXacroMaxMacroDepth = 16;
/// A mesh's default one-capsule fit at least this many times the mesh's volume is reported with
/// a pointer to mesh_fit: tighter: a boxy part (a torso, a base, a camera) gets 2 to 4.5, where
/// its box would be near 1; a round link's capsule stays well below.
inline constexpr double kLooseMeshFitRatio = 2.0;
/// A plan's multi-DOF joint (a mobile base's virtual joint) within this distance (m) and angle
/// (rad) of where it was stands still (DescribeMultiDofMotion): far below any base's motion, far
/// above the rounding of poses written out and read back.
inline constexpr double kMultiDofStill_m = 1e-9;
inline constexpr double kMultiDofStill_rad = 1e-9;
/// A plan's start state has the base where the planning scene placed it (replay) within this
/// distance (m) and angle (rad): 1 mm and 1 mrad, a localised base's jitter between plans and a
/// scene saved at another moment (or written by hand to three places) still agree; the
/// objects are then checked up to 1 mm + 1 mm a metre from the arms off where the plan had
/// them, a tenth of a typical tolerance zone.
inline constexpr double kSceneBaseAgreement_m = 1e-3;
inline constexpr double kSceneBaseAgreement_rad = 1e-3;
/// A mesh (after scale) smaller than this across every axis, m, is reported as a likely unit
/// error (typical robot parts are centimetres; a mesh in metres scaled by 0.001 is a speck): the
/// fit is taken as it is, but the real part's contacts would be missed.
inline constexpr double kSmallMeshEdge_m = 1e-3;
/// Compass search of the fit's axis (and box frame): first step and smallest step, rad. 0.1 rad
/// reaches past the principal axes' typical error on near-symmetric meshes; below 1e-3 rad the
/// volume changes by less than ~1e-3 relative, too little to matter.
inline constexpr double kMeshFitSearchStartStep_rad = 0.1;
inline constexpr double kMeshFitSearchMinStep_rad = 1e-3;
/// Most volume evaluations one compass search makes (dimensionless; typical 64), bounding the
/// fit's time: each costs one pass over the vertices.
inline constexpr int kMeshFitMaxSearchEvaluations = 64;
/// Grid points per axis over which a capsule chain's three candidates (each slab's capsule along
/// the chain's axis, each slab's own smallest one, the whole mesh's one capsule) compare their
/// unions (dimensionless; typical 32): the points a union holds estimate its volume to a few
/// per cent of the box, enough to tell a chain sticking out of a round link's sides from one
/// along it; 32^3 point tests per capsule bound the fit's time.
inline constexpr int kMeshFitChainGridPoints = 32;
/// Seed of the fixed shuffle in the smallest-enclosing-circle step (Welzl's algorithm expects
/// random order; a fixed seed keeps fits deterministic).
inline constexpr std::uint64_t kMeshFitShuffleSeed = 20261123;
/// Version of the fitting algorithm, hashed into MeshFitHash: bump it when a fit's result
/// changes, so that cached fits of the old algorithm are not reused.
inline constexpr std::uint64_t kMeshFitAlgorithmVersion = 3;

}  // namespace arm_collision_monitor
