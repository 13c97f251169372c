// ReadSrdfCollisionRules: an SRDF as MoveIt Setup Assistant writes it (groups, group states, end
// effectors, a virtual joint, 21 disable_collisions) read field by field, and every kind of bad
// input rejected with a message naming the file, the element and what was expected.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "arm_collision_monitor/scene/srdf_reader.h"
#include "load_error_expect.h"

namespace arm_collision_monitor {
namespace {

const std::string kSrdf = std::string(ACM_SOURCE_DIR) + "/test/data/moveit/workcell.srdf";

void ExpectPair(const SrdfLinkPair& pair, const std::string& link1, const std::string& link2,
                const std::string& reason, int line) {
  EXPECT_EQ(pair.link1, link1);
  EXPECT_EQ(pair.link2, link2);
  EXPECT_EQ(pair.reason, reason);
  EXPECT_EQ(pair.line, line);
}

TEST(SrdfReader, SetupAssistantFile) {
  const SrdfCollisionRules rules = ReadSrdfCollisionRules(kSrdf);
  EXPECT_EQ(rules.robot_name, "workcell");
  ASSERT_EQ(rules.disabled_pairs.size(), 21u);
  ExpectPair(rules.disabled_pairs.front(), "left_base_link", "left_link1", "Adjacent", 71);
  ExpectPair(rules.disabled_pairs[1], "left_base_link", "right_base_link", "Never", 72);
  ExpectPair(rules.disabled_pairs[3], "left_link1", "left_link3", "Never", 74);
  ExpectPair(rules.disabled_pairs[11], "left_pedestal", "right_pedestal", "Never", 82);
  ExpectPair(rules.disabled_pairs.back(), "right_pedestal", "right_base_link", "Adjacent", 91);
  int adjacent = 0;
  for (const SrdfLinkPair& pair : rules.disabled_pairs) adjacent += pair.reason == "Adjacent";
  EXPECT_EQ(adjacent, 18);  // the 9 joints of each arm's chain, pedestal to tool
  ASSERT_EQ(rules.default_disabled_links.size(), 1u);
  EXPECT_EQ(rules.default_disabled_links[0].link, "world");
  EXPECT_EQ(rules.default_disabled_links[0].line, 92);
  ASSERT_EQ(rules.enabled_pairs.size(), 1u);
  ExpectPair(rules.enabled_pairs[0], "world", "left_tool", "User", 93);
}

TEST(SrdfReader, NamesAreTrimmedAndReasonIsOptional) {
  const SrdfCollisionRules rules = ReadSrdfCollisionRules(
      WriteTempFile("trim.srdf",
                    "<robot name=' r '>\n<disable_collisions link1=' a ' link2='b\n'/>\n"
                    "<disable_default_collisions link=' c'/>\n</robot>\n"));
  EXPECT_EQ(rules.robot_name, "r");
  ASSERT_EQ(rules.disabled_pairs.size(), 1u);
  ExpectPair(rules.disabled_pairs[0], "a", "b", "", 2);
  ASSERT_EQ(rules.default_disabled_links.size(), 1u);
  EXPECT_EQ(rules.default_disabled_links[0].link, "c");
  EXPECT_TRUE(rules.enabled_pairs.empty());
}

TEST(SrdfReader, NotAFile) {
  const std::string missing = ::testing::TempDir() + "acm_test_no_such.srdf";
  ExpectLoadError([&] { ReadSrdfCollisionRules(missing); },
                  {missing, "cannot open", "readable SRDF file"});
  const std::string directory = ::testing::TempDir();
  ExpectLoadError([&] { ReadSrdfCollisionRules(directory); },
                  {directory, "cannot open", "readable SRDF file"});
}

TEST(SrdfReader, BadInputNamesFileElementAndExpectation) {
  ExpectBadInputFilesRejected(
      "bad.srdf",
      {
          {"<robot name='r'>\n<group name='arm'>\n</robot>\n",
           {":2: malformed XML (XML_ERROR_MISMATCHED_ELEMENT): <group>, which begins on line 2, "
            "is closed by an end tag not its own", "well-formed SRDF"}},
          // The file ends before </robot> (a Flexiv Rizon user's): the element left open.
          {"<robot name='r'>\n<group name='arm'>\n</group>\n",
           {":1: malformed XML (XML_ERROR_PARSING): the file ends inside the element that "
            "begins on line 1 (its end tag is missing", "well-formed SRDF"}},
          {"", {"malformed XML (XML_ERROR_EMPTY_DOCUMENT): the file holds no element",
                "well-formed SRDF"}},
          {"<?xml version='1.0'?>\n<model name='r'/>\n",
           {":2:", "<model>", "expected the root element <robot"}},
          {"<robot>\n<disable_collisions link1='a'/>\n</robot>\n",
           {":2:", "robot.disable_collisions[0]", "missing attribute link2", "link1=\"LINK\""}},
          {"<robot>\n<disable_collisions link1='a' link2='b'/>\n"
           "<disable_collisions link2='b'/>\n</robot>\n",
           {":3:", "robot.disable_collisions[1]", "missing attribute link1"}},
          {"<robot>\n<enable_collisions link1='a' link2=' '/>\n</robot>\n",
           {":2:", "robot.enable_collisions[0]", "empty attribute link2", "non-empty link1"}},
          {"<robot>\n\n<disable_default_collisions/>\n</robot>\n",
           {":3:", "robot.disable_default_collisions[0]", "missing attribute link",
            "<disable_default_collisions link=\"LINK\"/>"}},
          {"<robot>\n<enable_colisions link1='a' link2='b'/>\n</robot>\n",
           {":2:", "robot.enable_colisions[0]", "unknown element <enable_colisions>",
            "expected disable_collisions, enable_collisions"}},
      },
      [](const std::string& path) { ReadSrdfCollisionRules(path); });
}

}  // namespace
}  // namespace arm_collision_monitor
