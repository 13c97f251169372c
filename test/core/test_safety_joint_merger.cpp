// JointMerger with plain names, numbers and seconds: merging by name, every refusal (and that it
// leaves q untouched and is counted), unknown names, staleness, clock jumps, the copy merge.
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "arm_collision_monitor/safety/joint_merger.h"

namespace arm_collision_monitor {
namespace {

constexpr double kTimeout_s = 0.25;
const std::vector<std::string> kJoints = {"a1", "a2", "b1"};

MergeStatus MergeAt(JointMerger* merger, const std::vector<std::string>& names,
                    const std::vector<double>& positions, double stamp_s, double now_s) {
  return merger->Merge(NamedPositions{names, positions, stamp_s}, now_s);
}

// Both sources at now_s, stamped now_s.
void MergeAll(JointMerger* merger, double now_s) {
  ASSERT_EQ(MergeAt(merger, {"a1", "a2"}, {0.1, 0.2}, now_s, now_s), MergeStatus::kAccepted);
  ASSERT_EQ(MergeAt(merger, {"b1"}, {0.3}, now_s, now_s), MergeStatus::kAccepted);
}

TEST(JointMerger, MergesByNameInModelOrderAndCompletes) {
  JointMerger merger(kJoints, kTimeout_s);
  EXPECT_FALSE(merger.is_complete());
  EXPECT_EQ(merger.FirstMissingJoint(), 0);
  EXPECT_EQ(merger.missing_count(), 3);
  EXPECT_EQ(merger.MissingJoints(), kJoints);
  EXPECT_EQ(ModelJointsText(merger.MissingJoints()), "3 model joints: 'a1', 'a2', 'b1'");
  EXPECT_EQ(merger.OldestJoint(), -1);
  EXPECT_TRUE(std::isinf(merger.JointAge(0, 10.0)));
  EXPECT_EQ(MergeAt(&merger, {"b1", "a1"}, {3.0, 1.0}, 10.0, 10.0), MergeStatus::kAccepted);
  EXPECT_FALSE(merger.is_complete());
  EXPECT_EQ(merger.FirstMissingJoint(), 1);
  EXPECT_EQ(merger.missing_count(), 1);
  EXPECT_EQ(ModelJointsText(merger.MissingJoints()), "model joint 'a2'");
  EXPECT_TRUE(merger.MissingJointsNotIn({"a2"}).empty());
  EXPECT_EQ(merger.MissingJointsNotIn({"x"}), std::vector<std::string>({"a2"}));
  EXPECT_EQ(MergeAt(&merger, {"a2"}, {2.0}, 10.0625, 10.0625), MergeStatus::kAccepted);
  EXPECT_TRUE(merger.is_complete());
  EXPECT_EQ(merger.FirstMissingJoint(), -1);
  EXPECT_TRUE(merger.MissingJoints().empty());
  EXPECT_EQ(merger.q()[0], 1.0);
  EXPECT_EQ(merger.q()[1], 2.0);
  EXPECT_EQ(merger.q()[2], 3.0);
  EXPECT_EQ(merger.OldestJoint(), 0);  // a1 and b1 at 10.0, a2 at 10.0625
  EXPECT_EQ(merger.JointAge(1, 10.125), 0.0625);  // times exact in binary
  EXPECT_EQ(merger.refused(), 0u);
}

TEST(JointMerger, RefusalsLeaveQUntouchedAndAreCounted) {
  JointMerger merger(kJoints, kTimeout_s);
  MergeAll(&merger, 10.0);
  const Eigen::VectorXd q_before = merger.q();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  struct Case {
    std::vector<std::string> names;
    std::vector<double> positions;
    double stamp_s;
    MergeStatus expected;
    std::string why;  // DescribeRefusal's
  };
  const std::vector<Case> cases = {
      {{"a1", "a2"}, {1.0}, 10.1, MergeStatus::kWrongSize, "2 names but 1 positions"},
      {{"a1", "a1"}, {1.0, 1.0}, 10.1, MergeStatus::kWrongSize, "joint 'a1' named twice"},
      // An unknown name may repeat: the refusal is for the model joint named twice.
      {{"x", "x", "a2", "a2"}, {1.0, 1.0, 1.0, 1.0}, 10.1, MergeStatus::kWrongSize,
       "joint 'a2' named twice"},
      {{"x", "a1", "a2"}, {nan, 1.0, nan}, 10.1, MergeStatus::kNonFinite, "joint 'a2' at nan"},
      {{"a1"}, {-inf}, 10.1, MergeStatus::kNonFinite, "joint 'a1' at -inf"},
      {{"x", "y"}, {1.0, 2.0}, 10.1, MergeStatus::kNoKnownJoints,
       "none of its 2 names is a model joint, the first 'x'"},
      {{}, {}, 10.1, MergeStatus::kNoKnownJoints, "no name"},
      {{"a1"}, {1.0}, 10.1 - kTimeout_s - 0.01, MergeStatus::kStale,
       "stamped 0.260 s before its arrival, over input_timeout_s (0.250 s); also joint 'a1' "
       "0.160 s before its last accepted stamp"},
      {{"a1"}, {1.0}, 10.1 + kTimeout_s + 0.01, MergeStatus::kFutureStamp,
       "stamped 0.260 s after its arrival, over input_timeout_s (0.250 s)"},
      {{"x", "a2"}, {1.0, 2.0}, 9.99, MergeStatus::kStampBackwards,
       "joint 'a2' 0.010 s before its last accepted stamp"},
      // Under a millisecond (a Doosan user's racing publishers read "0.000 s").
      {{"a2"}, {2.0}, 10.0 - 2.5e-4, MergeStatus::kStampBackwards,
       "joint 'a2' 250 us before its last accepted stamp"},
  };
  std::uint64_t refused = 0;
  for (const Case& c : cases) {
    EXPECT_EQ(MergeAt(&merger, c.names, c.positions, c.stamp_s, 10.1), c.expected)
        << MergeStatusName(c.expected);
    EXPECT_EQ(merger.DescribeRefusal(NamedPositions{c.names, c.positions, c.stamp_s}, c.expected,
                                     10.1),
              c.why);
    EXPECT_EQ(merger.q(), q_before) << MergeStatusName(c.expected);
    EXPECT_EQ(merger.refused(), ++refused);
  }
  EXPECT_EQ(merger.refused_with(MergeStatus::kWrongSize), 3u);
  EXPECT_EQ(merger.refused_with(MergeStatus::kNonFinite), 2u);
  EXPECT_EQ(merger.refused_with(MergeStatus::kNoKnownJoints), 2u);
  EXPECT_EQ(merger.refused_with(MergeStatus::kStale), 1u);
  EXPECT_EQ(merger.refused_with(MergeStatus::kFutureStamp), 1u);
  EXPECT_EQ(merger.refused_with(MergeStatus::kStampBackwards), 2u);
  EXPECT_EQ(merger.refused_with(MergeStatus::kAccepted), 0u);
  // A NaN of an unknown name is ignored, not refused.
  EXPECT_EQ(MergeAt(&merger, {"a1", "x"}, {0.5, nan}, 10.1, 10.1), MergeStatus::kAccepted);
  EXPECT_EQ(merger.q()[0], 0.5);
}

TEST(JointMerger, UnknownNamesAreIgnoredAndCounted) {
  JointMerger merger(kJoints, kTimeout_s);
  EXPECT_EQ(MergeAt(&merger, {"x", "a1", "y"}, {9.0, 1.0, 9.0}, 1.0, 1.0),
            MergeStatus::kAccepted);
  EXPECT_EQ(merger.last_unknown_joints(), 2u);
  EXPECT_EQ(MergeAt(&merger, {"a2", "z"}, {2.0, 9.0}, 1.0, 1.0), MergeStatus::kAccepted);
  EXPECT_EQ(merger.last_unknown_joints(), 1u);
  EXPECT_EQ(MergeAt(&merger, {"b1"}, {3.0}, 1.0, 1.0), MergeStatus::kAccepted);
  EXPECT_EQ(merger.last_unknown_joints(), 0u);
  EXPECT_EQ(merger.total_unknown_joints(), 3u);
  EXPECT_EQ(merger.q(), Eigen::Vector3d(1.0, 2.0, 3.0));
}

// A URDF mimic joint (a Piper's second finger, which joint_state_publisher and some drivers
// publish) is no model joint either, but counted apart, and a refusal says what it is.
TEST(JointMerger, MimicJointNamesAreIgnoredAndCountedApart) {
  JointMerger merger(kJoints, kTimeout_s);
  merger.SetMimicJoints({"a2_mimic"});
  EXPECT_TRUE(merger.IsMimicJoint("a2_mimic"));
  EXPECT_FALSE(merger.IsModelJoint("a2_mimic"));
  EXPECT_EQ(MergeAt(&merger, {"a1", "a2_mimic", "x"}, {1.0, 9.0, 9.0}, 1.0, 1.0),
            MergeStatus::kAccepted);
  EXPECT_EQ(merger.last_unknown_joints(), 1u);
  EXPECT_EQ(merger.last_mimic_joints(), 1u);
  const std::vector<std::string> names = {"a2_mimic"};
  const std::vector<double> positions = {0.5};
  const NamedPositions mimic_only{names, positions, 1.0};
  EXPECT_EQ(merger.Merge(mimic_only, 1.0), MergeStatus::kNoKnownJoints);
  EXPECT_EQ(merger.total_unknown_joints(), 1u);
  EXPECT_EQ(merger.total_mimic_joints(), 2u);
  EXPECT_EQ(merger.DescribeRefusal(mimic_only, MergeStatus::kNoKnownJoints, 1.0),
            "none of its 1 names is a model joint, the first 'a2_mimic' (a mimic joint: its "
            "position follows from the joint it mimics in the URDF; give that one)");
  EXPECT_EQ(merger.q()[0], 1.0);
}

TEST(JointMerger, MessagesWithoutPositionsAreIgnoredNotRefused) {
  // JointState's arrays may be empty: a driver publishing efforts only names its joints with no
  // position. Nothing is merged, nothing refused; a joint only such messages name goes stale.
  JointMerger merger(kJoints, kTimeout_s);
  MergeAll(&merger, 10.0);
  const Eigen::VectorXd q_before = merger.q();
  for (const double now_s : {10.1, 10.2, 10.0 + kTimeout_s + 0.1}) {
    EXPECT_EQ(MergeAt(&merger, {"a1", "a2", "b1"}, {}, now_s, now_s), MergeStatus::kNoPositions);
  }
  EXPECT_EQ(merger.position_less(), 3u);
  EXPECT_EQ(merger.refused(), 0u);
  EXPECT_EQ(merger.refused_with(MergeStatus::kNoPositions), 0u);
  EXPECT_EQ(merger.q(), q_before);
  EXPECT_TRUE(merger.IsStale(10.0 + kTimeout_s + 0.1));
  EXPECT_STREQ(MergeStatusName(MergeStatus::kNoPositions), "no_positions");
  // Positions of a different count than the names are still refused, and so is a message
  // naming nothing.
  EXPECT_EQ(MergeAt(&merger, {"a1"}, {1.0, 2.0}, 10.3, 10.3), MergeStatus::kWrongSize);
  EXPECT_EQ(MergeAt(&merger, {}, {}, 10.3, 10.3), MergeStatus::kNoKnownJoints);
  EXPECT_EQ(merger.refused(), 2u);
}

TEST(JointMerger, ZeroStampMeansReceiptTime) {
  JointMerger merger(kJoints, kTimeout_s);
  // Stamp 0 at receipt time 100 s: neither stale nor backwards.
  EXPECT_EQ(MergeAt(&merger, {"a1"}, {1.0}, 0.0, 100.0), MergeStatus::kAccepted);
  // Taken as stamped 100 s: an explicit earlier stamp is now backwards.
  EXPECT_EQ(MergeAt(&merger, {"a1"}, {1.0}, 99.99, 100.0), MergeStatus::kStampBackwards);
  // After stamped messages, an unstamped one is not checked against their stamps: under
  // simulated time (a clock published at 100 Hz) the receipt time may be behind them. The
  // joint's stamp stays the later one.
  ASSERT_EQ(MergeAt(&merger, {"a1", "a2"}, {1.0, 2.0}, 100.5, 100.5), MergeStatus::kAccepted);
  EXPECT_EQ(MergeAt(&merger, {"a1"}, {1.5}, 0.0, 100.49), MergeStatus::kAccepted);
  EXPECT_EQ(merger.joint_stamps()[0], 100.5);
  EXPECT_EQ(MergeAt(&merger, {"a1"}, {1.6}, 0.0, 100.6), MergeStatus::kAccepted);
  EXPECT_EQ(merger.joint_stamps()[0], 100.6);
  EXPECT_EQ(merger.joint_stamps()[1], 100.5);
}

TEST(JointMerger, SilentJointGoesStale) {
  JointMerger merger(kJoints, kTimeout_s);
  EXPECT_FALSE(merger.IsStale(10.0));  // never received is incomplete, not stale
  MergeAll(&merger, 10.0);
  EXPECT_FALSE(merger.IsStale(10.0 + kTimeout_s));
  // Only the a-source keeps publishing: b1 goes stale after the timeout.
  ASSERT_EQ(MergeAt(&merger, {"a1", "a2"}, {0.1, 0.2}, 10.2, 10.2), MergeStatus::kAccepted);
  EXPECT_FALSE(merger.IsStale(10.2));
  EXPECT_TRUE(merger.IsStale(10.0 + kTimeout_s + 0.001));
  EXPECT_EQ(merger.OldestJoint(), 2);
}

TEST(JointMerger, ClockGoingBackAwaitsEveryJointAgain) {
  JointMerger merger(kJoints, kTimeout_s);
  MergeAll(&merger, 100.0);
  merger.OnTimeWentBackwards(5.0);
  // Stale at once, naming a joint awaiting input; ages count from the jump.
  EXPECT_TRUE(merger.IsStale(5.0));
  EXPECT_TRUE(merger.IsAwaitingInput(0));
  EXPECT_EQ(merger.JointAge(0, 5.125), 0.125);
  // The old stamps are forgotten: stamps of the new timeline are not "backwards".
  ASSERT_EQ(MergeAt(&merger, {"a1", "a2"}, {0.1, 0.2}, 5.1, 5.1), MergeStatus::kAccepted);
  EXPECT_FALSE(merger.IsAwaitingInput(0));
  EXPECT_TRUE(merger.IsStale(5.1));
  EXPECT_EQ(merger.OldestJoint(), 2);  // the one still awaiting input
  ASSERT_EQ(MergeAt(&merger, {"b1"}, {0.3}, 5.1, 5.1), MergeStatus::kAccepted);
  EXPECT_FALSE(merger.IsStale(5.1));
}

// joint_defaults: a joint the input leaves out is at its default, complete and never stale,
// until a message gives it; from then on it is an input joint like the others.
TEST(JointMerger, DefaultedJointCountsAsReceivedUntilAMessageGivesIt) {
  JointMerger merger(kJoints, kTimeout_s);
  merger.SetDefaults({{2, 0.75}});
  EXPECT_FALSE(merger.is_complete());
  EXPECT_EQ(merger.FirstMissingJoint(), 0);
  EXPECT_EQ(merger.MissingJoints(), std::vector<std::string>({"a1", "a2"}));
  EXPECT_TRUE(merger.MissingJointsNotIn({"a1", "a2"}).empty());
  EXPECT_EQ(merger.MissingJointsNotIn({"a2", "b1"}), std::vector<std::string>({"a1"}));
  ASSERT_EQ(MergeAt(&merger, {"a1", "a2"}, {0.1, 0.2}, 10.0, 10.0), MergeStatus::kAccepted);
  EXPECT_TRUE(merger.is_complete());
  EXPECT_EQ(merger.FirstMissingJoint(), -1);
  EXPECT_EQ(merger.q(), Eigen::Vector3d(0.1, 0.2, 0.75));
  // No age: the a-source's own silence makes it stale, never b1's.
  EXPECT_EQ(merger.OldestJoint(), 0);
  EXPECT_FALSE(merger.IsStale(10.0 + kTimeout_s));
  ASSERT_EQ(MergeAt(&merger, {"a1", "a2"}, {0.1, 0.2}, 20.0, 20.0), MergeStatus::kAccepted);
  EXPECT_FALSE(merger.IsStale(20.0));
  EXPECT_TRUE(merger.IsStale(20.0 + kTimeout_s + 0.001));
  // Nor does a clock jump make it await input.
  merger.OnTimeWentBackwards(5.0);
  EXPECT_FALSE(merger.IsAwaitingInput(2));
  ASSERT_EQ(MergeAt(&merger, {"a1", "a2"}, {0.1, 0.2}, 5.0, 5.0), MergeStatus::kAccepted);
  EXPECT_FALSE(merger.IsStale(5.0));
  // A message gives it: its value, and from then on its age.
  ASSERT_EQ(MergeAt(&merger, {"b1"}, {-0.5}, 5.0, 5.0), MergeStatus::kAccepted);
  EXPECT_EQ(merger.q()[2], -0.5);
  EXPECT_TRUE(merger.is_complete());
  ASSERT_EQ(MergeAt(&merger, {"a1", "a2"}, {0.1, 0.2}, 5.2, 5.2), MergeStatus::kAccepted);
  EXPECT_EQ(merger.OldestJoint(), 2);
  EXPECT_TRUE(merger.IsStale(5.0 + kTimeout_s + 0.001));
  // A default set again later leaves the received value alone.
  merger.SetDefaults({{2, 0.75}});
  EXPECT_EQ(merger.q()[2], -0.5);
  EXPECT_TRUE(merger.is_complete());
}

TEST(JointMerger, MergeIntoCopyLeavesTheLiveStateAlone) {
  JointMerger merger(kJoints, kTimeout_s);
  MergeAll(&merger, 1.0);
  const Eigen::VectorXd before = merger.q();
  Eigen::VectorXd q;
  const std::vector<std::string> names = {"a2"};
  const std::vector<double> positions = {7.0};
  EXPECT_EQ(merger.MergeIntoCopy(NamedPositions{names, positions, 0.0}, &q),
            MergeStatus::kAccepted);
  EXPECT_EQ(q, Eigen::Vector3d(0.1, 7.0, 0.3));
  EXPECT_EQ(merger.q(), before);
  const std::vector<double> nan = {std::numeric_limits<double>::quiet_NaN()};
  EXPECT_EQ(merger.MergeIntoCopy(NamedPositions{names, nan, 0.0}, &q), MergeStatus::kNonFinite);
  EXPECT_EQ(merger.refused(), 0u);  // a query is not a refused message
}

TEST(JointMerger, ManyLayoutsStayBounded) {
  JointMerger merger(kJoints, kTimeout_s);
  // More distinct layouts than are kept: each still merges correctly.
  for (int k = 0; k < 40; ++k) {
    const std::vector<std::string> names = {"a1", "extra" + std::to_string(k)};
    ASSERT_EQ(MergeAt(&merger, names, {0.01 * k, 0.0}, 1.0, 1.0), MergeStatus::kAccepted);
    EXPECT_EQ(merger.q()[0], 0.01 * k);
  }
  EXPECT_EQ(merger.total_unknown_joints(), 40u);
}

}  // namespace
}  // namespace arm_collision_monitor
